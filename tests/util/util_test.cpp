// util_test.cpp: the shared helpers of model/util/util.hpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "model/util/util.hpp"

using namespace hc;
namespace fs = std::filesystem;

TEST_CASE("FNV-1a of the empty string and of 'a' are the published 64-bit values", "[model][util]") {
    CHECK(util::fnv1a("") == 0xcbf29ce484222325ULL);
    CHECK(util::fnv1a("a") == 0xaf63dc4c8601ec8cULL);
    CHECK(util::hex64(0xaf63dc4c8601ec8cULL) == "af63dc4c8601ec8c");
    // chaining equals hashing the concatenation
    CHECK(util::fnv1a("bc", util::fnv1a("a")) == util::fnv1a("abc"));
}

TEST_CASE("a range a:b reads as first a and last b, an open end as the given end", "[model][util]") {
    CHECK(util::parse_range("0:51", "--pairs").first == 0);
    CHECK(util::parse_range("0:51", "--pairs").last == 51);
    CHECK(util::parse_range("3:", "--pairs", 99).last == 99);
    CHECK(util::parse_range(":4", "--pairs").first == 0);
}

TEST_CASE("a range that is empty, reversed or not numbers is bad input naming the flag", "[model][util]") {
    for (const char* bad : {"5:5", "6:2", "a:b", "3", "-1:4", "1:2x"}) {
        INFO(bad);
        CHECK_THROWS_WITH(util::parse_range(bad, "--pairs"),
                          Catch::Matchers::StartsWith(std::string("--pairs '") + bad + "' is not FIRST:LAST"));
    }
}

TEST_CASE("a size WxH reads as two positive numbers and anything else is bad input", "[model][util]") {
    CHECK(util::parse_size("1241x376") == std::pair<int, int>{1241, 376});
    CHECK_THROWS_AS(util::parse_size("40by30"), InputError);
    CHECK_THROWS_AS(util::parse_size("0x30"), InputError);
    CHECK_THROWS_AS(util::parse_size("40x30x2"), InputError);
}

TEST_CASE("a comma list drops empty items", "[model][util]") {
    CHECK(util::split_csv("a,,b,") == std::vector<std::string>{"a", "b"});
    CHECK(util::split_csv("").empty());
}

namespace {
// The regression set `text`, written to `p` and read back.
std::vector<util::RegressionStream> regression_set(const fs::path& p, const std::string& text) {
    util::write_file_atomic(p, text);
    return util::read_regression_set(p);
}
}  // namespace

TEST_CASE("the regression set reads every stream line and names a bad line", "[model][util]") {
    const util::ScratchDir d;
    const fs::path p = d.path() / "set.txt";
    const auto set = regression_set(p, "# comment\nrandom 40x30 3 0\nflat 33x21 2 5\n");
    REQUIRE(set.size() == 2);
    CHECK(set[0].stem() == "random_40x30");
    CHECK(set[1].frames == 2);
    CHECK(set[1].idle_every == 5);
    CHECK_THROWS_WITH(regression_set(p, "random 40x30 3 0\nflat 33x21\n"), Catch::Matchers::Contains("set.txt:2: expected"));
}

TEST_CASE("an image stream of the regression set names its file and the configuration it breaks", "[model][util]") {
    const util::ScratchDir d;
    const fs::path p = d.path() / "set.txt";
    const auto set = regression_set(p, "w/a_sobel_x.pgm 16x12 2 0 breaks=w/a.json\nw/b.pgm 16x12 1 0\nrandom 40x30 3 0\n");
    REQUIRE(set.size() == 3);
    CHECK(set[0].image == d.path() / "w/a_sobel_x.pgm");
    CHECK(set[0].breaks == d.path() / "w/a.json");
    CHECK(set[0].stem() == "a_sobel_x_16x12");
    CHECK(set[1].breaks.empty());
    CHECK(set[2].image.empty());
    CHECK_THROWS_WITH(regression_set(p, "random 40x30 3 0 breaks=a.json\n"), Catch::Matchers::Contains("set.txt:1: unexpected 'breaks=a.json'"));
    CHECK_THROWS_WITH(regression_set(p, "w/a.pgm 16x12 2 0 breaks=a.json more\n"), Catch::Matchers::Contains("set.txt:1: unexpected 'more'"));
}

TEST_CASE("a file read back is the bytes written, and a missing one is bad input naming it", "[model][util]") {
    const util::ScratchDir d;
    util::write_file_atomic(d.path() / "sub" / "x.bin", std::string("a\0b", 3));
    CHECK(util::read_file(d.path() / "sub" / "x.bin") == std::string("a\0b", 3));
    CHECK_THROWS_WITH(util::read_file(d.path() / "none"), Catch::Matchers::Contains("none'"));
}

TEST_CASE("an output whose folder cannot be made is bad input naming it, and leaves nothing", "[model][util]") {
    const util::ScratchDir d;
    util::write_file_atomic(d.path() / "file", "x");
    const fs::path under_file = d.path() / "file" / "sub" / "out.json";
    CHECK_THROWS_AS(util::write_file_atomic(under_file, "y"), InputError);
    CHECK_THROWS_WITH(util::write_file_atomic(under_file, "y"),
                      Catch::Matchers::Contains("cannot write '" + under_file.string() + "': cannot make its folder"));
    CHECK(util::read_file(d.path() / "file") == "x");
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(d.path())) ++entries;
    CHECK(entries == 1);
    CHECK_THROWS_WITH(util::write_file_atomic(d.path(), "z"), Catch::Matchers::Contains("is a directory"));
}

TEST_CASE("a child process's exit status, working directory and log come back", "[model][util]") {
    const util::ScratchDir d;
    CHECK(util::run_process({"sh", "-c", "exit 3"}) == 3);
    CHECK(util::run_process({"sh", "-c", "pwd; echo oops >&2"}, {.cwd = d.path(), .log = d.path() / "log"}) == 0);
    const std::string log = util::read_file(d.path() / "log");
    CHECK(log.find(fs::canonical(d.path()).string()) != std::string::npos);
    CHECK(log.find("oops") != std::string::npos);
    CHECK(util::run_process({"sh", "-c", "echo $HC_X"}, {.extra_env = {"HC_X=42"}, .stdout_file = d.path() / "out"}) == 0);
    CHECK(util::read_file(d.path() / "out") == "42\n");
    CHECK_THROWS_AS(util::run_process({"no-such-program-hc"}), SimulatorError);
}

TEST_CASE("a plot axis spans its data with a margin, clipped to its bounds", "[model][util]") {
    // recall between 0.9 and 1.0: 5 % of the 0.1 extent either side, the top clipped at 1
    const auto r = util::axis_range({0.9, 0.95, 1.0, std::nan("")}, 0.05, 0.0, 1.0);
    CHECK(r.lo == Approx(0.895));
    CHECK(r.hi == Approx(1.0));
    CHECK(r.gnuplot() == "[0.895:1]");
    // one value: a span of min_span centred on it, then the margin of that span
    const auto one = util::axis_range({2.0}, 0.1, -1e300, 1e300, 1.0);
    CHECK(one.lo == Approx(1.4));
    CHECK(one.hi == Approx(2.6));
    // nothing finite: the bounds when both are given, else [0, 1]
    CHECK(util::axis_range({}, 0.05, 0.0, 1.0).gnuplot() == "[0:1]");
    CHECK(util::axis_range({INFINITY}).hi == 1.0);
}
