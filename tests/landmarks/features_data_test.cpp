// The grid descriptor's quirks measured on a real stereo pair (KITTI 01 pair 0, else
// opencv-doc's aloe pair) with the 1,000 strongest Harris corners per image; prints the
// figures docs/landmarks.md quotes. Exits 77 (CTest: skipped) without either pair.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <cstdio>
#include <set>

#include "mapping/landmarks/descriptors.hpp"
#include "tests/landmarks/stereo_sample.hpp"

using namespace hc::landmarks;

namespace {
std::optional<hc::features_test::StereoSample> g_sample;

MatchCounts match_grid(const hc::features_test::StereoSample& s, int g, int h, GridVariant v, RatioTest t,
                       std::vector<cv::DMatch>& m) {
    const cv::Mat dl = grid_describe(s.kp_l, g, h, v), dr = grid_describe(s.kp_r, g, h, v);
    MatchCounts c;
    MatchOptions o;
    o.ratio = t;
    m = match_stereo(dl, s.kp_l, dr, s.kp_r, o, &c);
    return c;
}
}  // namespace

TEST_CASE("grid quirks on a real stereo pair: counts per h at g = 16", "[landmarks][grid][data]") {
    const auto& s = *g_sample;
    std::printf("\n%s, %zu + %zu Harris corners, g = 16\n", s.name.c_str(), s.kp_l.size(), s.kp_r.size());
    std::printf("| h | image | keypoints | neighbour hits | in shared cells | shared-bit collisions (descriptors) "
                "| cell 0 by truncation | thesis-only neighbours | corrected-only neighbours | cell offset differs "
                "| descriptors differing | bits set thesis / corrected | centre bit only thesis / corrected "
                "| self bit off centre |\n");
    for (int h = 0; h <= 5; ++h) {
        for (int side = 0; side < 2; ++side) {
            const GridQuirkStats q = grid_quirk_stats(side ? s.kp_r : s.kp_l, 16, h);
            std::printf("| %d | %s | %lld | %lld | %lld | %lld (%lld) | %lld | %lld | %lld | %lld | %lld | %lld / %lld "
                        "| %lld / %lld | %lld |\n",
                        h, side ? "right" : "left", q.keypoints, q.neighbour_hits, q.shared_bit_hits,
                        q.shared_bit_collisions, q.descriptors_with_collision, q.truncation_hits,
                        q.neighbours_thesis_only, q.neighbours_corrected_only, q.relative_cell_differs,
                        q.descriptors_differing, q.bits_set_thesis, q.bits_set_corrected,
                        q.empty_neighbourhood_thesis, q.empty_neighbourhood_corrected, q.self_bit_off_centre);
            CHECK(q.self_bit_off_centre == 0);
            // the corrected reach [-8, 8) lies inside the thesis reach (-10, 8), and where both
            // see a neighbour, truncation and floor agree (integer corner coordinates)
            CHECK(q.neighbours_corrected_only == 0);
            CHECK(q.relative_cell_differs == 0);
            CHECK(q.shared_bit_collisions <= q.shared_bit_hits);
            CHECK(q.descriptors_with_collision <= q.shared_bit_collisions);
            // every bit the thesis grid loses to a collision is a hit it could not record
            CHECK(q.bits_set_thesis <= q.neighbour_hits + q.keypoints);
            CHECK(q.descriptors_differing <= q.keypoints);
        }
    }
}

TEST_CASE("grid matches on a real stereo pair: thesis against corrected variant", "[landmarks][grid][data]") {
    const auto& s = *g_sample;
    std::printf("\n%s: appendix F matching (symmetry, printed ratio test maxRatio 1, |dy| < 5), g = 16\n", s.name.c_str());
    std::printf("| h | thesis, printed | thesis, drop ties | corrected, printed | corrected, drop ties "
                "| same pair in both printed runs | ties left (0/0) thesis | ties right (0/0) thesis "
                "| symmetry removals thesis / corrected | epipolar removals thesis / corrected |\n");
    for (int h = 0; h <= 5; ++h) {
        std::vector<cv::DMatch> mt, mc, unused;
        const MatchCounts ct = match_grid(s, 16, h, GridVariant::thesis, RatioTest::printed, mt);
        const MatchCounts cc = match_grid(s, 16, h, GridVariant::corrected, RatioTest::printed, mc);
        const MatchCounts tt = match_grid(s, 16, h, GridVariant::thesis, RatioTest::drop_ties, unused);
        const MatchCounts tc = match_grid(s, 16, h, GridVariant::corrected, RatioTest::drop_ties, unused);
        std::set<std::pair<int, int>> a;
        for (const auto& m : mt) a.insert({m.queryIdx, m.trainIdx});
        int common = 0;
        for (const auto& m : mc) common += a.count({m.queryIdx, m.trainIdx}) ? 1 : 0;
        std::printf("| %d | %d | %d | %d | %d | %d | %d (%d) | %d (%d) | %d / %d | %d / %d |\n", h, ct.kept, tt.kept,
                    cc.kept, tc.kept, common, ct.ratio_ties_left, ct.ratio_nan_left, ct.ratio_ties_right,
                    ct.ratio_nan_right, ct.symmetry, cc.symmetry, ct.epipolar, cc.epipolar);
        for (const MatchCounts* c : {&ct, &cc, &tt, &tc})
            CHECK(c->left_queries - c->ratio_left - c->symmetry - c->epipolar == c->kept);
        CHECK(ct.ratio_left == 0);  // the printed test with maxRatio 1 never removes a list
        CHECK(ct.ratio_right == 0);
        CHECK(tt.ratio_left == ct.ratio_ties_left);  // dropping ties removes exactly the ties
        CHECK(tt.ratio_right == ct.ratio_ties_right);
        CHECK(tt.kept <= ct.kept);
    }
}

int main(int argc, char** argv) {
    g_sample = hc::features_test::load_stereo_sample(1000);
    if (!g_sample) {
        std::fprintf(stderr, "SKIP: neither KITTI 01 pair 0 (data directory: --data, $HARRIS_COSIM_DATA or "
                             "../shared/data) nor opencv-doc's aloeL.jpg/aloeR.jpg found\n");
        return 77;
    }
    return hc::test::run_catch(argc, argv);
}
