// slam_report_command_test.cpp: the simulation report quotes the command it is given, word for
// word (the command line as the user typed it), in report.md and summary.json, and states the
// first seed, which a typed command without --seed does not show.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "mapping/slam/slam.hpp"

using namespace hc::slam;
namespace fs = std::filesystem;

namespace {
std::string text_of(const fs::path& p) {
    std::ifstream f(p);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}
}  // namespace

TEST_CASE("the simulation report quotes the given command and states the first seed", "[slam]") {
    SimConfig c;
    c.steps = 20;
    const MonteCarlo mc = monte_carlo(c, 2, 7);
    CHECK(mc.first_seed == 7);
    const fs::path dir = fs::temp_directory_path() / ("hc_slam_report_command_" + std::to_string(::getpid()));
    const std::string typed = "harris-cosim slam --simulate --runs 2 --steps 20 --seed 7 --out 'a b'";
    write_simulation_report(dir, c, mc, typed);
    CHECK(text_of(dir / "report.md").find("Command: `" + typed + "`") != std::string::npos);
    CHECK(text_of(dir / "report.md").find("| runs | 2 seeds from 7 |") != std::string::npos);
    const auto j = nlohmann::json::parse(text_of(dir / "summary.json"));
    CHECK(j["command"] == typed);
    CHECK(j["first_seed"] == 7);
    fs::remove_all(dir);
}
