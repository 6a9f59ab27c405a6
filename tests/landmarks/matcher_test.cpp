// The stereo matcher (thesis 6.1, appendix F) on hand-made descriptor sets whose Hamming
// distances are worked out below, each test's removals counted exactly.
#include <catch2/catch.hpp>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <random>
#include <vector>

#include "mapping/landmarks/descriptors.hpp"

using namespace hc::landmarks;

namespace {

cv::Mat bytes(std::initializer_list<int> v) {
    cv::Mat m(static_cast<int>(v.size()), 1, CV_8U);
    int r = 0;
    for (int x : v) m.at<uchar>(r++, 0) = static_cast<uchar>(x);
    return m;
}

std::vector<cv::KeyPoint> at_rows(std::initializer_list<float> ys) {
    std::vector<cv::KeyPoint> k;
    float x = 10;
    for (float y : ys) k.emplace_back(x += 10, y, 7.f);
    return k;
}

// Left  L0 0x00, L1 0xF0, L2 0xFF, L3 0x03 at y 10, 20, 30, 40.
// Right R0 0x01, R1 0xF0, R2 0xF0, R3 0xFE at y 10, 25, 0, 34.9.
// Hamming distances (rows L, columns R):
//        R0 R1 R2 R3
//   L0    1  4  4  7   -> best R0 (1), second R1 (4)
//   L1    5  0  0  3   -> best R1 (0), second R2 (0): a tie, ratio 0/0 = NaN
//   L2    7  4  4  1   -> best R3 (1), second R1 (4)
//   L3    1  6  6  7   -> best R0 (1), second R1 (6)
// Right to left: R0 -> L0 (1), L3 (1): a tie, ratio 1; R1 -> L1 (0), L0 (4);
//   R2 -> L1 (0), L0 (4); R3 -> L2 (1), L1 (3).
// Symmetric: L0-R0, L1-R1, L2-R3; L3 -> R0 but R0 -> L0.
// Epipolar: L0-R0 dy 0, L1-R1 dy 5 (not < 5), L2-R3 dy 4.9, L3-R0 dy 30.
struct Fixture {
    cv::Mat dl = bytes({0x00, 0xF0, 0xFF, 0x03});
    cv::Mat dr = bytes({0x01, 0xF0, 0xF0, 0xFE});
    std::vector<cv::KeyPoint> kl = at_rows({10, 20, 30, 40});
    std::vector<cv::KeyPoint> kr = at_rows({10, 25, 0, 34.9f});
};

std::vector<std::pair<int, int>> pairs(const std::vector<cv::DMatch>& m) {
    std::vector<std::pair<int, int>> p;
    for (const auto& x : m) p.emplace_back(x.queryIdx, x.trainIdx);
    return p;
}

}  // namespace

TEST_CASE("the printed ratio test with maxRatio 1 removes nothing, NaN included", "[landmarks][matcher]") {
    Fixture f;
    MatchCounts c;
    const auto m = match_stereo(f.dl, f.kl, f.dr, f.kr, MatchOptions{}, &c);
    CHECK(pairs(m) == std::vector<std::pair<int, int>>{{0, 0}, {2, 3}});
    CHECK(m[0].distance == 1.f);
    CHECK(m[1].distance == 1.f);
    CHECK(c.left_queries == 4);
    CHECK(c.right_queries == 4);
    CHECK(c.ratio_left == 0);
    CHECK(c.ratio_right == 0);
    CHECK(c.ratio_nan_left == 1);   // L1: 0 / 0
    CHECK(c.ratio_ties_left == 1);
    CHECK(c.ratio_nan_right == 0);
    CHECK(c.ratio_ties_right == 1); // R0: 1 / 1
    CHECK(c.symmetry == 1);         // L3
    CHECK(c.epipolar == 1);         // L1-R1, dy = 5
    CHECK(c.kept == 2);
    MatchOptions none;
    none.ratio = RatioTest::none;
    CHECK(pairs(match_stereo(f.dl, f.kl, f.dr, f.kr, none)) == pairs(m));
}

TEST_CASE("dropping ties removes 0/0 and 1/1 lists, and the symmetry test their partners", "[landmarks][matcher]") {
    Fixture f;
    MatchOptions o;
    o.ratio = RatioTest::drop_ties;
    MatchCounts c;
    const auto m = match_stereo(f.dl, f.kl, f.dr, f.kr, o, &c);
    CHECK(pairs(m) == std::vector<std::pair<int, int>>{{2, 3}});
    CHECK(c.ratio_left == 1);   // L1
    CHECK(c.ratio_right == 1);  // R0
    CHECK(c.symmetry == 2);     // L0 and L3: their match R0 lost its list
    CHECK(c.epipolar == 0);
    CHECK(c.kept == 1);
    CHECK(c.left_queries - c.ratio_left - c.symmetry - c.epipolar == c.kept);
}

TEST_CASE("the printed ratio test with maxRatio 0.5 removes ratio 1 but keeps NaN", "[landmarks][matcher]") {
    Fixture f;
    MatchOptions o;
    o.max_ratio = 0.5;
    MatchCounts c;
    const auto m = match_stereo(f.dl, f.kl, f.dr, f.kr, o, &c);
    CHECK(pairs(m) == std::vector<std::pair<int, int>>{{2, 3}});
    CHECK(c.ratio_left == 0);   // 0.25, NaN, 0.25, 0.1667
    CHECK(c.ratio_right == 1);  // R0: 1 > 0.5
    CHECK(c.symmetry == 2);
    CHECK(c.epipolar == 1);
}

TEST_CASE("without the symmetry test every left best match meets only the epipolar test", "[landmarks][matcher]") {
    Fixture f;
    MatchOptions o;
    o.symmetry = false;
    MatchCounts c;
    const auto m = match_stereo(f.dl, f.kl, f.dr, f.kr, o, &c);
    CHECK(pairs(m) == std::vector<std::pair<int, int>>{{0, 0}, {2, 3}});
    CHECK(c.symmetry == 0);
    CHECK(c.epipolar == 2);  // L1-R1 (dy 5), L3-R0 (dy 30)
    CHECK(c.right_queries == 0);
    o.epipolar = false;
    CHECK(pairs(match_stereo(f.dl, f.kl, f.dr, f.kr, o)) ==
          std::vector<std::pair<int, int>>{{0, 0}, {1, 1}, {2, 3}, {3, 0}});
}

TEST_CASE("the epipolar bound is strict and follows max_dy", "[landmarks][matcher]") {
    Fixture f;
    MatchOptions o;
    o.max_dy = 5.01;
    CHECK(pairs(match_stereo(f.dl, f.kl, f.dr, f.kr, o)) == std::vector<std::pair<int, int>>{{0, 0}, {1, 1}, {2, 3}});
    o.max_dy = 4.9;  // 34.9f - 30 is 4.9000015 in float: removed
    CHECK(pairs(match_stereo(f.dl, f.kl, f.dr, f.kr, o)) == std::vector<std::pair<int, int>>{{0, 0}});
}

TEST_CASE("a query with a single neighbour passes the ratio test", "[landmarks][matcher]") {
    const cv::Mat dl = bytes({0x00, 0x0F}), dr = bytes({0x01});
    MatchOptions o;
    o.ratio = RatioTest::drop_ties;
    MatchCounts c;
    const auto m = match_stereo(dl, at_rows({5, 5}), dr, at_rows({5}), o, &c);
    // L0 -> R0 (1) and L1 -> R0 (3) are single-neighbour lists; R0 -> L0 (1), L1 (3) passes
    CHECK(pairs(m) == std::vector<std::pair<int, int>>{{0, 0}});
    CHECK(c.left_queries == 2);
    CHECK(c.ratio_left == 0);
    CHECK(c.ratio_right == 0);
    CHECK(c.symmetry == 1);  // L1: R0's best is L0
}

TEST_CASE("empty descriptor sets give no matches", "[landmarks][matcher]") {
    MatchCounts c;
    c.kept = 9;
    CHECK(match_stereo(cv::Mat(0, 32, CV_8U), {}, bytes({1}), at_rows({1}), MatchOptions{}, &c).empty());
    CHECK(c.kept == 0);
    CHECK(c.left_queries == 0);
}

TEST_CASE("knn2 agrees with cv::BFMatcher::knnMatch, ties included", "[landmarks][matcher]") {
    std::mt19937 rng(9);
    cv::Mat a(60, 2, CV_8U), b(70, 2, CV_8U);
    for (cv::Mat* m : {&a, &b})
        for (int r = 0; r < m->rows; ++r)
            for (int c = 0; c < 2; ++c) m->at<uchar>(r, c) = uchar(rng() & 0x13);  // few values: many ties
    cv::Mat wa(90, 35, CV_8U), wb(80, 35, CV_8U);  // several 64-bit words and a 3-byte tail
    cv::randu(wa, 0, 256);
    cv::randu(wb, 0, 256);
    cv::Mat fa(40, 8, CV_32F), fb(50, 8, CV_32F);
    cv::randu(fa, 0, 4);
    cv::randu(fb, 0, 4);
    fa.convertTo(fa, CV_32F);
    struct Case {
        cv::Mat q, t;
        int norm;
    };
    for (const auto& k : {Case{a, b, cv::NORM_HAMMING}, Case{b, a, cv::NORM_HAMMING}, Case{wa, wb, cv::NORM_HAMMING},
                          Case{wa, wb, cv::NORM_HAMMING2}, Case{fa, fb, cv::NORM_L2}, Case{fa, fb, cv::NORM_L1}}) {
        std::vector<std::vector<cv::DMatch>> ref;
        cv::BFMatcher(k.norm).knnMatch(k.q, k.t, ref, 2);
        const auto ours = knn2(k.q, k.t, k.norm);
        REQUIRE(ours.size() == ref.size());
        for (size_t i = 0; i < ref.size(); ++i) {
            REQUIRE(ours[i].size() == ref[i].size());
            for (size_t j = 0; j < ref[i].size(); ++j) {
                INFO("query " << i << " rank " << j);
                CHECK(ours[i][j].trainIdx == ref[i][j].trainIdx);
                CHECK(ours[i][j].distance == ref[i][j].distance);
            }
        }
    }
}

TEST_CASE("Hamming matching both ways equals cv::BFMatcher for every width from 1 to 160 bytes", "[landmarks][matcher]") {
    // sparse random descriptors (many equal distances: ties), row counts that are no multiple
    // of the matcher's blocks; the symmetry test reads both directions' best, the drop-ties
    // ratio test both directions' second best
    std::mt19937 rng(11);
    for (int bytes_per_row = 1; bytes_per_row <= 160; bytes_per_row += (bytes_per_row < 24 ? 1 : 17)) {
        INFO("bytes " << bytes_per_row);
        const int nl = 37 + bytes_per_row % 13, nr = 29 + bytes_per_row % 7;
        cv::Mat dl(nl, bytes_per_row, CV_8U), dr(nr, bytes_per_row, CV_8U);
        for (cv::Mat* m : {&dl, &dr})
            for (int r = 0; r < m->rows; ++r)
                for (int c = 0; c < m->cols; ++c) m->at<uchar>(r, c) = uchar(rng() & rng() & rng());
        std::vector<std::vector<cv::DMatch>> lr, rl;
        cv::BFMatcher(cv::NORM_HAMMING).knnMatch(dl, dr, lr, 2);
        cv::BFMatcher(cv::NORM_HAMMING).knnMatch(dr, dl, rl, 2);
        const auto passes = [](const std::vector<cv::DMatch>& v) { return v.size() < 2 || v[0].distance < v[1].distance; };
        std::vector<std::pair<int, int>> expected;
        for (int i = 0; i < nl; ++i) {
            const int j = lr[static_cast<size_t>(i)][0].trainIdx;
            if (passes(lr[static_cast<size_t>(i)]) && passes(rl[static_cast<size_t>(j)]) &&
                rl[static_cast<size_t>(j)][0].trainIdx == i)
                expected.emplace_back(i, j);
        }
        MatchOptions o;
        o.ratio = RatioTest::drop_ties;
        o.epipolar = false;
        std::vector<cv::KeyPoint> kl(static_cast<size_t>(nl)), kr(static_cast<size_t>(nr));
        CHECK(pairs(match_stereo(dl, kl, dr, kr, o)) == expected);
        const auto ours = knn2(dl, dr, cv::NORM_HAMMING);
        for (int i = 0; i < nl; ++i)
            for (size_t k = 0; k < 2; ++k) {
                CHECK(ours[static_cast<size_t>(i)][k].trainIdx == lr[static_cast<size_t>(i)][k].trainIdx);
                CHECK(ours[static_cast<size_t>(i)][k].distance == lr[static_cast<size_t>(i)][k].distance);
            }
    }
}

TEST_CASE("descriptor and norm pairs that cannot work are input errors", "[landmarks][matcher]") {
    CHECK(descriptor_norm_valid(CV_8U, cv::NORM_HAMMING));
    CHECK(descriptor_norm_valid(CV_32F, cv::NORM_L2));
    CHECK_FALSE(descriptor_norm_valid(CV_32F, cv::NORM_HAMMING));  // SIFT on a binary matcher
    CHECK_FALSE(descriptor_norm_valid(CV_8U, cv::NORM_L2));
    CHECK_FALSE(descriptor_norm_valid(CV_8UC2, cv::NORM_HAMMING));
    CHECK_FALSE(descriptor_norm_valid(CV_8U, cv::NORM_INF));
    const cv::Mat sift(3, 128, CV_32F, cv::Scalar(1));
    const auto k3 = at_rows({1, 2, 3});
    MatchOptions o;
    CHECK_THROWS_WITH(match_stereo(sift, k3, sift, k3, o), Catch::Contains("NORM_HAMMING") && Catch::Contains("32F"));
    o.norm = cv::NORM_L2;
    CHECK(match_stereo(sift, k3, sift, k3, o).size() == 1);  // all 0: every best is index 0, symmetric for L0 only
    CHECK_THROWS_AS(require_descriptor_norm(CV_8U, cv::NORM_L2, "ORB"), hc::InputError);
    const cv::Mat b32(3, 32, CV_8U, cv::Scalar(0)), b35(3, 35, CV_8U, cv::Scalar(0));
    CHECK_THROWS_WITH(match_stereo(b32, k3, b35, k3, MatchOptions{}), Catch::Contains("differ"));
    CHECK_THROWS_WITH(match_stereo(b32, at_rows({1, 2}), b32, k3, MatchOptions{}), Catch::Contains("2 left keypoints"));
}

TEST_CASE("SIFT descriptors at shifted keypoints of a shifted image match one to one with NORM_L2", "[landmarks][matcher]") {
    cv::Mat big(220, 260, CV_8U);
    cv::RNG rng(21);
    rng.fill(big, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(big, big, cv::Size(7, 7), 2.0);
    const int dx = 6, dy = 3;
    const cv::Mat left = big(cv::Rect(30, 30, 200, 160)).clone();
    const cv::Mat right = big(cv::Rect(30 - dx, 30 - dy, 200, 160)).clone();  // content moved by (dx, dy)
    std::vector<cv::KeyPoint> kl, kr;
    for (int y = 40; y < 120; y += 16)
        for (int x = 40; x < 160; x += 16) {
            kl.emplace_back(float(x), float(y), 12.f, 0.f);
            kr.emplace_back(float(x + dx), float(y + dy), 12.f, 0.f);
        }
    const auto sift = cv::SIFT::create();
    cv::Mat dl, dr;
    sift->compute(left, kl, dl);
    sift->compute(right, kr, dr);
    REQUIRE(dl.type() == CV_32F);
    REQUIRE(kl.size() == kr.size());
    MatchOptions o;
    o.norm = cv::NORM_L2;
    o.ratio = RatioTest::drop_ties;
    o.max_ratio = 0.8;  // Lowe's ratio, as the thesis's SIFT reference
    MatchCounts c;
    const auto m = match_stereo(dl, kl, dr, kr, o, &c);
    CHECK(int(m.size()) == int(kl.size()));
    for (const auto& x : m) CHECK(x.queryIdx == x.trainIdx);  // (SIFT is not bit-exact under shifts)
    CHECK(c.ratio_left == 0);
    CHECK(c.symmetry == 0);
    CHECK(c.epipolar == 0);
}
