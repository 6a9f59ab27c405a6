// eval_kitti_test.cpp: the evaluation on real KITTI frames. Exits 77 (CTest: skipped) with
// a message when the data directory holds no KITTI sequence 01.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>

#include "eval/eval.hpp"
#include "frames/frames.hpp"

using namespace hc;

namespace {
std::filesystem::path g_kitti;

eval::Stream load_pairs(int first, int last) {
    return frames::load_kitti_stream(g_kitti, "01", {first, last}, "pairs", 0);
}
}  // namespace

TEST_CASE("the spec model reaches the thesis's recall and precision on KITTI 01 pairs 0..4", "[eval][kitti]") {
    const auto s = load_pairs(0, 5);
    REQUIRE(s.frames.size() == 10);
    const auto spec_run = eval::run_spec(s, spec::Options{}, 0);
    const auto ref = eval::run_reference(s, {}, 0);
    eval::Confusion c;
    for (size_t k = 2; k < s.frames.size(); ++k) c.add(eval::classify(spec_run.masks[k], ref[k]));
    INFO("TP " << c.tp << " FP " << c.fp << " FN " << c.fn << " recall " << c.recall() << " precision " << c.precision());
    CHECK(c.tp > 1000);
    CHECK(c.recall() > 0.90);     // measured 0.929 on these pairs (0.9595 on all of 01); thesis 0.9648 (seq 00)
    CHECK(c.precision() > 0.95);  // thesis Table 5: 0.9655
}

TEST_CASE("the cycle model equals the spec model at its own thresholds on a KITTI pair", "[eval][kitti][slow]") {
    const auto s = load_pairs(0, 2);
    const auto cyc = eval::run_cycle(s, Formats{}, false);
    const spec::SpecModel m;
    const int W = s.frames[0].width;
    long compared = 0, diff = 0, corners = 0;
    for (int k = 0; k < 3; ++k) {   // the 4th frame's last windows are never read
        spec::Response r;
        m.response(s.frames[k], r);
        const auto& tm = cyc.thr_map[k];
        std::vector<std::uint8_t> mask;
        m.corners(r, [&](int x, int y) { return tm[static_cast<size_t>(y) * W + x]; }, mask);
        for (size_t i = 0; i < mask.size(); ++i)
            if (tm[i] != -1) {
                ++compared;
                corners += cyc.masks[k][i];
                diff += mask[i] != cyc.masks[k][i];
            }
    }
    INFO("compared " << compared << " pixels, " << corners << " hardware corners");
    CHECK(compared > 3L * 1200 * 360);
    CHECK(corners > 500);
    CHECK(diff == 0);
}

int main(int argc, char** argv) {
    const auto d = frames::data_dir("");
    if (!d || !std::filesystem::is_directory(*d / "kitti/sequences/01/image_0")) {
        std::printf("SKIPPED: no KITTI sequence 01 (set HARRIS_COSIM_DATA to a directory holding "
                    "kitti/sequences/01; see the data README.md (../shared/data beside the repository))\n");
        return 77;
    }
    g_kitti = *d / "kitti";
    return Catch::Session().run(argc, argv);
}
