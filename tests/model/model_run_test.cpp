#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "model/driver/model_run.hpp"

using namespace hc;

namespace {

/// A golden reads file without its '#' header lines.
std::string golden_rows(const std::string& name) {
    std::ifstream f(std::string(HC_SOURCE_DIR) + "/golden/" + name);
    REQUIRE(f);
    std::ostringstream out;
    for (std::string line; std::getline(f, line);)
        if (line.empty() || line[0] != '#') out << line << '\n';
    return out.str();
}

std::vector<Image> checkerboard_33x21() {
    std::vector<Image> frames;
    for (int k = 0; k < 3; ++k) frames.push_back(make_pattern(Pattern::checkerboard, 33, 21, k, 1));
    return frames;
}

}  // namespace

TEST_CASE("the cycle model alone reads what the golden file of its stream lists", "[model][model_run]") {
    const std::vector<Image> frames = checkerboard_33x21();
    const ModelRun r = run_cycle_model(frames, Formats{}, true);
    CHECK(r.reads_csv == golden_rows("reads_checkerboard_33x21.csv"));
    const Geometry g{33, 21};
    CHECK(r.writes == 3 * g.frame_writes());
    long rows = -1;   // the header
    for (char c : r.reads_csv) rows += c == '\n';
    CHECK(r.reads == rows);
    REQUIRE(r.corners_per_frame.size() == 3);
    CHECK(r.corners() == r.corners_per_frame[0] + r.corners_per_frame[1] + r.corners_per_frame[2]);
}

TEST_CASE("the cycle model alone lists no reads unless asked and counts the same", "[model][model_run]") {
    const std::vector<Image> frames = checkerboard_33x21();
    const ModelRun with = run_cycle_model(frames, Formats{}, true);
    const ModelRun without = run_cycle_model(frames, Formats{}, false);
    CHECK(without.reads_csv.empty());
    CHECK(without.writes == with.writes);
    CHECK(without.reads == with.reads);
    CHECK(without.corners_per_frame == with.corners_per_frame);
}
