// eval_memory_test.cpp: peak resident memory of every corner source over long generated
// streams. Each test case forks a child that evaluates FRAMES generated frames of WxH (the
// `blocks` pattern, new content every frame) through a SOURCE with the library
// (eval::evaluate_part) and reads the child's peak resident set (wait4's rusage), so one
// run's memory is measured alone; `eval_memory_tests --run SOURCE W H FRAMES ABLATION` does
// one such run in this process, for measuring by hand.
//
// The bound (512 MB at KITTI's 1241x376) is shown on 2,000 frames at full size for the spec
// source (about a minute). The cycle model and the netlist take about 0.1 s and 1 s of CPU
// per full-size frame, so for them non-growth is shown where it costs little: at full size
// the peak of a run three times longer equals the shorter one's within 16 MB (the retained
// write positions and thresholds once cost about 21 MB a frame), and for the cycle and rtl
// sources a stream of 2,000 small frames stays within 8 MB of a 100-frame one.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <string>

#include <fmt/format.h>

#include "cosim/verilator/netlist.hpp"
#include "eval/sequences.hpp"
#include "io/frames/frames.hpp"

using namespace hc;

namespace {

/// Evaluates a generated stream through one source (the child's work).
int run_child(const std::string& source, int w, int h, int n, bool ablation) {
    std::vector<std::string> names;
    std::vector<int> pairs;
    for (int k = 0; k < n; ++k) {
        names.push_back(fmt::format("gen/{}{:06}", k % 2 ? 'R' : 'L', k / 2));
        pairs.push_back(k / 2);
    }
    frames::FrameFeed feed(names, pairs, "generated", [w, h](int k) { return make_pattern(Pattern::blocks, w, h, k); });
    eval::PartInput in;
    in.source = eval::parse_source(source);
    in.feed = &feed;
    in.first = 0;
    in.last = n;
    in.frames_total = n;
    in.first_pair = 0;
    in.last_pair = (n - 1) / 2;
    in.ablation = ablation;
    in.threads = 0;
    const eval::Part p = eval::evaluate_part(in);
    if (static_cast<int>(p.rows.size()) != n) return 3;
    // every frame was loaded once: none is held for the whole run and reloaded
    if (feed.loads() != n) return 4;
    std::printf("%zu rows, %ld scored\n", p.rows.size(), static_cast<long>(p.rows.size()));
    return 0;
}

/// run_child's status, an exception reported as status 2
int run_child_status(const std::string& source, int w, int h, int n, bool ablation) {
    try {
        return run_child(source, w, h, n, ablation);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "eval_memory_tests: %s\n", e.what());
        return 2;
    }
}

/// Peak resident memory (MB) of a forked child evaluating the stream through the library
/// (this process runs no evaluation itself, so the child starts from the test program's
/// small footprint); REQUIREs a clean exit.
double peak_mb(const std::string& source, int w, int h, int n, bool ablation) {
    std::fflush(nullptr);   // the child's exit flushes nothing the parent still holds
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int rc = run_child_status(source, w, h, n, ablation);
        std::fflush(nullptr);
        std::_Exit(rc);
    }
    int status = 0;
    struct rusage ru {};
    REQUIRE(::wait4(pid, &status, 0, &ru) == pid);
    INFO(source << " over " << n << " frames of " << w << "x" << h << ": exit status " << status);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);
    const double mb = static_cast<double>(ru.ru_maxrss) / 1024.0;   // ru_maxrss is in KB on Linux
    std::printf("peak memory: %s source, %d frames of %dx%d%s: %.1f MB\n", source.c_str(), n, w, h,
                ablation ? " with ablation" : "", mb);
    return mb;
}

constexpr int kW = 1241, kH = 376;   // KITTI's frame size
constexpr double kBoundMb = 512;

}  // namespace

TEST_CASE("the spec source stays under 512 MB over 2,000 full-size frames", "[memory]") {
    const double mb = peak_mb("spec", kW, kH, 2000, false);
    CHECK(mb < kBoundMb);
    // the ablation's eight more spec runs change the work per frame, not what is held
    const double abl = peak_mb("spec", kW, kH, 40, true);
    CHECK(abl < kBoundMb);
}

namespace {

/// A source's peak over a short and a long full-size stream (both under the bound, the long
/// one within 16 MB of the short: retaining each frame's writes and thresholds once cost the
/// cycle source about 21 MB a frame), then over a short and a long stream of small frames
/// (the long one under the bound and within 8 MB of the short).
void check_no_growth(const std::string& source, bool ablation, int full_short, int full_long, int small_w, int small_h,
                     int small_short, int small_long) {
    const double short_run = peak_mb(source, kW, kH, full_short, ablation);
    const double long_run = peak_mb(source, kW, kH, full_long, ablation);
    CHECK(short_run < kBoundMb);
    CHECK(long_run < kBoundMb);
    CHECK(long_run < short_run + 16);
    const double small_short_run = peak_mb(source, small_w, small_h, small_short, ablation);
    const double small_long_run = peak_mb(source, small_w, small_h, small_long, ablation);
    CHECK(small_long_run < kBoundMb);
    CHECK(small_long_run < small_short_run + 8);
}

}  // namespace

TEST_CASE("the cycle source's peak memory does not grow with the stream", "[memory]") {
    check_no_growth("cycle", true, 8, 24, 96, 40, 100, 2000);
}

TEST_CASE("the rtl source's peak memory does not grow with the stream", "[memory][rtl]") {
    std::string why;
    if (!vl::toolchain_available(&why)) {
        WARN("skipped: " << why);
        return;
    }
    // the KITTI-size netlist (the one `eval --source rtl` on KITTI builds and caches), then
    // a small netlist of its own for the long stream
    check_no_growth("rtl", false, 4, 12, 64, 36, 100, 2000);
}

int main(int argc, char** argv) {
    // by hand: one run in this process, e.g. `/usr/bin/time -v eval_memory_tests --run cycle 1241 376 2000 1`
    if (argc == 7 && std::strcmp(argv[1], "--run") == 0)
        return run_child_status(argv[2], std::stoi(argv[3]), std::stoi(argv[4]), std::stoi(argv[5]), argv[6][0] == '1');
    return hc::test::run_catch(argc, argv);
}
