// The grid descriptor (thesis 5.3.2, appendix E) against hand-computed bit vectors, the
// corrected variant, and the bucketed extraction against appendix E transcribed literally.
#include <catch2/catch.hpp>

#include <opencv2/features2d.hpp>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "mapping/landmarks/descriptors.hpp"

using namespace hc::landmarks;

namespace {

cv::KeyPoint kp(float x, float y) { return cv::KeyPoint(x, y, 7.f); }

/// The bit numbers set in row `r` (bit b = byte b >> 3, bit b & 7).
std::vector<int> bits_of(const cv::Mat& d, int r) {
    std::vector<int> b;
    for (int c = 0; c < d.cols; ++c)
        for (int k = 0; k < 8; ++k)
            if (d.at<uchar>(r, c) & (1 << k)) b.push_back(8 * c + k);
    return b;
}

/// Appendix E as printed (reconstructed braces), O(n^2): the reference for grid_describe.
cv::Mat appendix_e(const std::vector<cv::KeyPoint>& kp, int g, int h) {
    int center = g / 2 + 1;
    int needed_bytes = ((g * (g + 1)) >> 3) + 1;
    cv::Mat dp = cv::Mat::zeros(static_cast<int>(kp.size()), needed_bytes, CV_8U);
    std::vector<cv::KeyPoint> ikp;
    for (int i = 0; i < (int)kp.size(); i++) {
        ikp.push_back(kp.at(i));
        ikp.at(i).pt.x = (kp.at(i).pt.x) / (1 << h);
        ikp.at(i).pt.y = (kp.at(i).pt.y) / (1 << h);
    }
    for (int i = 0; i < (int)ikp.size(); i++) {
        cv::KeyPoint selpoint = ikp.at(i);
        int X, Y;
        int tot;
        std::vector<uchar> dsc(static_cast<size_t>(needed_bytes), 0);
        float lx = center - selpoint.pt.x;
        float ly = center - selpoint.pt.y;
        for (int j = 0; j < (int)ikp.size(); j++) {
            X = ikp.at(j).pt.x + lx;
            Y = ikp.at(j).pt.y + ly;
            if (X >= 0 && Y >= 0 && X <= g && Y <= g) {
                tot = g * Y + X;
                dsc[tot >> 3] = dsc[tot >> 3] | (1 << (tot & 0x7));
            }
        }
        for (int j = 0; j < (int)needed_bytes; j++) dp.at<uchar>(i, j) = dsc[j];
    }
    return dp;
}

/// A vector printed as in section 5.3.2 ("00.00. ... .a0"): a hexadecimal number, most
/// significant byte first, cell [0,0] its least significant bit. Returned LSB byte first.
std::vector<uchar> from_printed(const std::string& s) {
    std::vector<uchar> b;
    for (size_t i = 0; i < s.size(); i += 3) b.push_back(static_cast<uchar>(std::stoi(s.substr(i, 2), nullptr, 16)));
    return {b.rbegin(), b.rend()};
}

}  // namespace

TEST_CASE("the thesis grid has (g(g+1) >> 3) + 1 bytes and the corrected grid ceil(g^2/8)", "[landmarks][grid]") {
    CHECK(grid_descriptor_bytes(16, GridVariant::thesis) == 35);  // Table 6 says 32
    CHECK(grid_descriptor_bytes(16, GridVariant::corrected) == 32);
    CHECK(grid_descriptor_bytes(4, GridVariant::thesis) == 3);
    CHECK(grid_descriptor_bytes(4, GridVariant::corrected) == 2);
    CHECK(grid_descriptor_bytes(32, GridVariant::thesis) == 133);
    CHECK(grid_descriptor_bytes(32, GridVariant::corrected) == 128);
    CHECK(grid_descriptor_bytes(5, GridVariant::corrected) == 4);  // 25 bits
    CHECK(GridDescriptor::create(16, 2)->descriptorSize() == 35);
    CHECK(GridDescriptor::create(16, 2, GridVariant::corrected)->descriptorSize() == 32);
}

TEST_CASE("g and h out of range are input errors naming the parameter", "[landmarks][grid]") {
    CHECK_THROWS_AS(GridDescriptor::create(1, 2), hc::InputError);
    CHECK_THROWS_WITH(GridDescriptor::create(257, 2), Catch::Contains("g = 257"));
    CHECK_THROWS_WITH(grid_describe({kp(0, 0)}, 16, -1, GridVariant::thesis), Catch::Contains("h = -1"));
    CHECK_THROWS_WITH(grid_describe({kp(0, 0)}, 16, 17, GridVariant::corrected), Catch::Contains("h = 17"));
    CHECK_NOTHROW(GridDescriptor::create(2, 0));
    CHECK_NOTHROW(GridDescriptor::create(256, 16));
}

TEST_CASE("non-finite or huge keypoint coordinates are input errors", "[landmarks][grid]") {
    CHECK_THROWS_WITH(grid_describe({kp(0, 0), kp(std::nanf(""), 1)}, 16, 2, GridVariant::thesis),
                      Catch::Contains("keypoint 1"));
    CHECK_THROWS_AS(grid_describe({kp(3e7f, 1)}, 16, 2, GridVariant::thesis), hc::InputError);
}

TEST_CASE("a lone keypoint sets only its centre bit g(g/2+1) + g/2+1 = 153 at g = 16", "[landmarks][grid]") {
    const cv::Mat d = grid_describe({kp(100.f, 50.f)}, 16, 2, GridVariant::thesis);
    REQUIRE(d.rows == 1);
    REQUIRE(d.cols == 35);
    CHECK(bits_of(d, 0) == std::vector<int>{153});
    CHECK(d.at<uchar>(0, 19) == 0x02);  // bit 153 = byte 19, bit 1
    const cv::Mat c = grid_describe({kp(100.f, 50.f)}, 16, 2, GridVariant::corrected);
    CHECK(bits_of(c, 0) == std::vector<int>{16 * 8 + 8});  // corrected centre g/2 = 8
}

TEST_CASE("cell (g, Y) and cell (0, Y+1) set the same bit in the thesis grid", "[landmarks][grid]") {
    // g = 16, h = 0, centre 9: dx = +7 -> X = 16, dy = 0 -> Y = 9; dx = -9 -> X = 0, dy = +1 -> Y = 10
    const cv::KeyPoint ref = kp(100, 100), right_edge = kp(107, 100), next_row = kp(91, 101);
    const cv::Mat a = grid_describe({ref, right_edge}, 16, 0, GridVariant::thesis);
    const cv::Mat b = grid_describe({ref, next_row}, 16, 0, GridVariant::thesis);
    CHECK(grid_cell(ref.pt, right_edge.pt, 16, 0, GridVariant::thesis).x == 16);
    CHECK(grid_cell(ref.pt, next_row.pt, 16, 0, GridVariant::thesis).y == 10);
    CHECK(bits_of(a, 0) == std::vector<int>{153, 160});  // 16 * 9 + 16 = 16 * 10 + 0 = 160
    CHECK(bits_of(b, 0) == std::vector<int>{153, 160});
    CHECK(cv::norm(a.row(0), b.row(0), cv::NORM_HAMMING) == 0);
    // the corrected grid keeps them apart: dx = +7 -> X = 15, Y = 8; dx = -9 is outside
    const cv::Mat ca = grid_describe({ref, right_edge}, 16, 0, GridVariant::corrected);
    const cv::Mat cb = grid_describe({ref, next_row}, 16, 0, GridVariant::corrected);
    CHECK(bits_of(ca, 0) == std::vector<int>{136, 143});
    CHECK(bits_of(cb, 0) == std::vector<int>{136});
}

TEST_CASE("negative offsets truncate toward zero, so thesis cell 0 spans two cells", "[landmarks][grid]") {
    // g = 16, h = 2 (cells of 4 px), ref x = 100 -> scaled 25, lx = 9 - 25 = -16.
    const cv::Point2f ref(100, 100);
    const auto X = [&](float x) { return grid_cell(ref, {x, 100}, 16, 2, GridVariant::thesis); };
    CHECK(X(62).x == 0);   // 15.5 - 16 = -0.5 -> 0 (floor would give -1: outside)
    CHECK(X(62).inside);
    CHECK(X(66).x == 0);   // 16.5 - 16 = 0.5 -> 0
    CHECK_FALSE(X(58).inside);  // 14.5 - 16 = -1.5 -> -1
    CHECK(X(130).x == 16); // 32.5 - 16 = 16.5 -> 16
    CHECK_FALSE(X(134).inside); // 17.5 -> 17
    CHECK(X(101).x == 9);  // 25.25 - 16 = 9.25 -> 9: the keypoint's own cell
    CHECK(X(99).x == 8);   // 24.75 - 16 = 8.75 -> 8
    // the reach is (-40, 32) px: 10 cells left, 8 right
    const cv::Mat d = grid_describe({kp(100, 100), kp(62, 100), kp(66, 100)}, 16, 2, GridVariant::thesis);
    CHECK(bits_of(d, 0) == std::vector<int>{144, 153});  // both neighbours in cell (0, 9)
    // the corrected grid floors: -9.5 cells and -8.5 cells are outside its [-8, 8) reach
    CHECK_FALSE(grid_cell(ref, {62, 100}, 16, 2, GridVariant::corrected).inside);
    CHECK_FALSE(grid_cell(ref, {66, 100}, 16, 2, GridVariant::corrected).inside);
    CHECK(grid_cell(ref, {68, 100}, 16, 2, GridVariant::corrected).x == 0);  // -8 cells
    CHECK(grid_cell(ref, {99, 100}, 16, 2, GridVariant::corrected).x == 7);  // floor(-0.25) = -1
}

TEST_CASE("the corrected grid covers cell offsets -g/2 to g - g/2 - 1 with bit g*Y + X", "[landmarks][grid]") {
    const cv::Mat d = grid_describe({kp(100, 100), kp(92, 92), kp(107.9f, 100), kp(108, 100), kp(91.5f, 100)},
                                    16, 0, GridVariant::corrected);
    REQUIRE(d.cols == 32);
    CHECK(bits_of(d, 0) == std::vector<int>{0, 136, 143});  // (0,0), centre (8,8), (15,8)
}

TEST_CASE("a keypoint at non-negative coordinates sets its own centre bit", "[landmarks][grid]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.f, 1300.f), tiny(0.f, 1e-3f);
    std::vector<cv::KeyPoint> kps;
    for (int i = 0; i < 2000; ++i) kps.push_back(kp(u(rng), u(rng)));
    for (int i = 0; i < 200; ++i) kps.push_back(kp(tiny(rng), u(rng)));
    for (int h = 0; h <= 5; ++h) {
        const GridQuirkStats s = grid_quirk_stats(kps, 16, h);
        INFO("h = " << h);
        CHECK(s.self_bit_off_centre == 0);
    }
}

TEST_CASE("at a negative sub-pixel coordinate the float sum can put the keypoint one cell off centre", "[landmarks][grid]") {
    // h = 0: lx = 9 - (-29.5271626) rounds to 38.5271606; -29.5271626 + 38.5271606 = 8.99999809 -> 8
    const cv::Point2f p(-29.5271626f, 5.f);
    const GridCell c = grid_cell(p, p, 16, 0, GridVariant::thesis);
    CHECK(c.x == 8);
    CHECK(c.y == 9);
    CHECK(grid_quirk_stats({kp(p.x, p.y)}, 16, 0).self_bit_off_centre == 1);
    const cv::Mat d = grid_describe({kp(p.x, p.y)}, 16, 0, GridVariant::thesis);
    CHECK(bits_of(d, 0) == std::vector<int>{152});
    CHECK(grid_cell(p, p, 16, 0, GridVariant::corrected).x == 8);  // corrected: exact difference 0
}

TEST_CASE("bucketed extraction equals appendix E transcribed literally", "[landmarks][grid]") {
    std::mt19937 rng(11);
    for (int g : {2, 3, 4, 7, 16, 32}) {
        for (int h : {0, 1, 2, 3, 5}) {
            std::uniform_real_distribution<float> u(-20.f, 40.f * float(1 << h));
            std::uniform_int_distribution<int> pix(-5, 40 << h);
            std::vector<cv::KeyPoint> kps;
            for (int i = 0; i < 200; ++i) kps.push_back(kp(u(rng), u(rng)));          // sub-pixel
            for (int i = 0; i < 200; ++i) kps.push_back(kp(float(pix(rng)), float(pix(rng))));  // pixels
            INFO("g = " << g << ", h = " << h);
            const cv::Mat fast = grid_describe(kps, g, h, GridVariant::thesis);
            const cv::Mat ref = appendix_e(kps, g, h);
            CHECK(cv::norm(fast, ref, cv::NORM_HAMMING) == 0);
        }
    }
}

TEST_CASE("bucketed corrected extraction equals the per-pair rule", "[landmarks][grid]") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.f, 300.f);
    std::vector<cv::KeyPoint> kps;
    for (int i = 0; i < 400; ++i) kps.push_back(kp(u(rng), u(rng)));
    for (int g : {4, 5, 16}) {
        for (int h : {0, 2}) {
            const cv::Mat d = grid_describe(kps, g, h, GridVariant::corrected);
            cv::Mat ref = cv::Mat::zeros(d.size(), CV_8U);
            for (size_t i = 0; i < kps.size(); ++i)
                for (const auto& p : kps) {
                    const GridCell c = grid_cell(kps[i].pt, p.pt, g, h, GridVariant::corrected);
                    if (c.inside) ref.at<uchar>(int(i), c.bit >> 3) |= uchar(1 << (c.bit & 7));
                }
            INFO("g = " << g << ", h = " << h);
            CHECK(cv::norm(d, ref, cv::NORM_HAMMING) == 0);
        }
    }
}

TEST_CASE("whole-pixel shifts of every keypoint leave the grid descriptors unchanged", "[landmarks][grid]") {
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> pix(0, 300);
    std::vector<cv::KeyPoint> a, b;
    for (int i = 0; i < 300; ++i) {
        const float x = float(pix(rng)), y = float(pix(rng));
        a.push_back(kp(x, y));
        b.push_back(kp(x + 3, y + 5));
    }
    for (auto v : {GridVariant::thesis, GridVariant::corrected}) {
        const cv::Mat da = grid_describe(a, 16, 2, v), db = grid_describe(b, 16, 2, v);
        CHECK(cv::norm(da, db, cv::NORM_HAMMING) == 0);
    }
}

TEST_CASE("the example vector of section 5.3.2 decodes to a 12 x 12 pattern the corrected grid reproduces", "[landmarks][grid]") {
    // 18 bytes = 144 bits = g^2 with g = 12; bit k*g + i for cell (i, k), [0,0] the LSB.
    const std::vector<uchar> printed = from_printed("00.00.00.00.00.00.00.00.08.08.00.00.01.01.04.04.00.a0");
    REQUIRE(printed.size() == 18);
    std::vector<cv::Point> cells;
    for (int b = 0; b < 144; ++b)
        if (printed[size_t(b >> 3)] & (1 << (b & 7))) cells.emplace_back(b % 12, b / 12);
    CHECK(cells == std::vector<cv::Point>{{5, 0}, {7, 0}, {6, 1}, {2, 2}, {8, 2}, {4, 3}, {7, 5}, {3, 6}});
    // stars at those cells around a reference at the corrected centre (6, 6), h = 0
    std::vector<cv::KeyPoint> kps{kp(100.5f, 100.5f)};
    for (const auto& c : cells) kps.push_back(kp(100.5f + float(c.x - 6), 100.5f + float(c.y - 6)));
    cv::Mat d = grid_describe(kps, 12, 0, GridVariant::corrected);
    REQUIRE(d.cols == 18);
    d.at<uchar>(0, (12 * 6 + 6) >> 3) &= uchar(~(1 << ((12 * 6 + 6) & 7)));  // Padgett's grid omits the reference star
    CHECK(std::vector<uchar>(d.ptr<uchar>(0), d.ptr<uchar>(0) + 18) == printed);
    // the thesis variant (centre 7, 13 x 13 cells, 20 bytes) shifts the same pattern by one cell
    const cv::Mat t = grid_describe(kps, 12, 0, GridVariant::thesis);
    std::vector<int> expect;
    for (const auto& c : cells) expect.push_back(12 * (c.y + 1) + c.x + 1);
    expect.push_back(12 * 7 + 7);
    std::sort(expect.begin(), expect.end());
    CHECK(t.cols == 20);
    CHECK(bits_of(t, 0) == expect);
}

TEST_CASE("the grid descriptor is a cv::Feature2D that cv::BFMatcher matches", "[landmarks][grid]") {
    const cv::Mat img(120, 160, CV_8U, cv::Scalar(0));
    std::vector<cv::KeyPoint> kps;
    std::mt19937 rng(1);
    std::uniform_int_distribution<int> px(0, 159), py(0, 119);
    for (int i = 0; i < 150; ++i) kps.push_back(kp(float(px(rng)), float(py(rng))));
    const auto grid = GridDescriptor::create(8, 1);
    cv::Ptr<cv::Feature2D> f = grid;
    cv::Mat d;
    std::vector<cv::KeyPoint> k = kps;
    f->compute(img, k, d);
    CHECK(k.size() == kps.size());
    CHECK(d.rows == 150);
    CHECK(d.cols == f->descriptorSize());
    CHECK(d.type() == f->descriptorType());
    CHECK(f->defaultNorm() == cv::NORM_HAMMING);
    CHECK(f->getDefaultName() == "hc.features.GridDescriptor");
    std::vector<cv::DMatch> m;
    cv::BFMatcher(f->defaultNorm()).match(d, d, m);
    REQUIRE(m.size() == 150);
    for (const auto& x : m) CHECK(x.distance == 0.f);
    std::vector<cv::KeyPoint> none;
    CHECK_THROWS_AS(f->detectAndCompute(img, cv::noArray(), none, d, false), hc::InputError);
}
