// BRIEF and FREAK: the Feature2D interface, determinism, the border policies and invariance
// to whole-pixel shifts of the image.
#include <catch2/catch.hpp>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include <set>
#include <vector>

#include "features/features.hpp"

using namespace hc::features;

namespace {

/// A textured test image: uniform noise, lightly smoothed, fixed seed.
cv::Mat texture(int w, int h, int seed) {
    cv::Mat m(h, w, CV_8U);
    cv::RNG rng(static_cast<uint64_t>(seed));
    rng.fill(m, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(m, m, cv::Size(5, 5), 1.2);
    return m;
}

std::vector<cv::KeyPoint> grid_points(int x0, int y0, int x1, int y1, int step) {
    std::vector<cv::KeyPoint> k;
    for (int y = y0; y < y1; y += step)
        for (int x = x0; x < x1; x += step) k.emplace_back(float(x), float(y), 7.f);
    return k;
}

cv::Mat describe(cv::Feature2D& f, const cv::Mat& img, std::vector<cv::KeyPoint>& k) {
    cv::Mat d;
    f.compute(img, k, d);
    return d;
}

}  // namespace

TEST_CASE("BRIEF's pattern has 256 distinct-point tests inside the 48 x 48 patch", "[landmarks][brief]") {
    const auto& p = BriefDescriptor::pattern();
    REQUIRE(p.size() == 256);
    for (const auto& t : p) {
        for (int c = 0; c < 4; ++c) {
            CHECK(t[c] >= -24);
            CHECK(t[c] <= 23);
        }
        CHECK((t[0] != t[2] || t[1] != t[3]));
    }
    // the fixed-seed generator gives the same pattern on every platform: pin two tests
    CHECK(p[0] == cv::Vec4i(-11, -5, -2, 5));
    CHECK(p[255] == cv::Vec4i(2, -17, -8, 11));
}

TEST_CASE("FREAK has 43 fields on 7 rings and 512 distinct pairs", "[landmarks][freak]") {
    const auto& f = FreakDescriptor::fields();
    REQUIRE(f.size() == 43);
    CHECK(f[0].x == Approx(2.0 / 3.0));
    CHECK(f[0].sigma == Approx(1.0 / 3.0));
    CHECK(f[42].x == 0.f);
    CHECK(f[42].y == 0.f);
    const auto& p = FreakDescriptor::pairs();
    REQUIRE(p.size() == 512);
    std::set<std::pair<int, int>> seen;
    for (const auto& q : p) {
        CHECK(q[0] < q[1]);
        CHECK(q[1] < 43);
        seen.insert({q[0], q[1]});
    }
    CHECK(seen.size() == 512);
}

TEST_CASE("BRIEF and FREAK are cv::Feature2D descriptors that cv::BFMatcher matches", "[landmarks][brief][freak]") {
    const cv::Mat img = texture(200, 160, 1);
    std::vector<cv::Ptr<cv::Feature2D>> all{BriefDescriptor::create(), FreakDescriptor::create(),
                                            FreakDescriptor::create(true)};
    const std::vector<int> sizes{32, 64, 64};
    for (size_t n = 0; n < all.size(); ++n) {
        auto& f = *all[n];
        INFO(f.getDefaultName());
        auto k = grid_points(40, 40, 160, 120, 6);
        const size_t before = k.size();
        const cv::Mat d = describe(f, img, k);
        CHECK(k.size() == before);
        CHECK(d.rows == int(k.size()));
        CHECK(d.cols == sizes[n]);
        CHECK(f.descriptorSize() == sizes[n]);
        CHECK(d.type() == CV_8U);
        CHECK(f.descriptorType() == CV_8U);
        CHECK(f.defaultNorm() == cv::NORM_HAMMING);
        std::vector<cv::DMatch> m;
        cv::BFMatcher(f.defaultNorm(), true).match(d, d, m);
        REQUIRE(m.size() == k.size());
        for (const auto& x : m) {
            CHECK(x.queryIdx == x.trainIdx);
            CHECK(x.distance == 0.f);
        }
    }
    CHECK(BriefDescriptor::create()->getDefaultName() == "hc.features.BriefDescriptor");
    CHECK(FreakDescriptor::create()->getDefaultName() == "hc.features.FreakDescriptor");
}

TEST_CASE("BRIEF and FREAK give identical descriptors on a second run", "[landmarks][brief][freak]") {
    const cv::Mat img = texture(200, 160, 2);
    for (auto f : std::vector<cv::Ptr<cv::Feature2D>>{BriefDescriptor::create(), FreakDescriptor::create(true)}) {
        auto k1 = grid_points(30, 30, 170, 130, 5), k2 = k1;
        const cv::Mat a = describe(*f, img, k1), b = describe(*f, img, k2);
        CHECK(cv::norm(a, b, cv::NORM_HAMMING) == 0);
    }
}

TEST_CASE("an image shifted by whole pixels gives identical descriptors at the shifted keypoints", "[landmarks][brief][freak]") {
    const cv::Mat big = texture(260, 220, 3);
    const int dx = 7, dy = 4;
    const cv::Mat a = big(cv::Rect(20, 20, 200, 160)).clone();
    const cv::Mat b = big(cv::Rect(20 - dx, 20 - dy, 200, 160)).clone();  // content moved by (+dx, +dy)
    std::vector<cv::Ptr<cv::Feature2D>> all{BriefDescriptor::create(), FreakDescriptor::create(),
                                            FreakDescriptor::create(true)};
    for (auto& f : all) {
        INFO(f->getDefaultName());
        auto ka = grid_points(40, 40, 150, 120, 7);
        std::vector<cv::KeyPoint> kb;
        for (const auto& k : ka) kb.emplace_back(k.pt.x + dx, k.pt.y + dy, k.size);
        const cv::Mat da = describe(*f, a, ka), db = describe(*f, b, kb);
        REQUIRE(ka.size() == kb.size());
        CHECK(cv::norm(da, db, cv::NORM_HAMMING) == 0);
        for (size_t i = 0; i < ka.size(); ++i) CHECK(ka[i].angle == kb[i].angle);
    }
}

TEST_CASE("a shifted image changes most descriptors at unshifted keypoints", "[landmarks][brief][freak]") {
    const cv::Mat big = texture(260, 220, 4);
    const cv::Mat a = big(cv::Rect(20, 20, 200, 160)).clone();
    const cv::Mat b = big(cv::Rect(15, 17, 200, 160)).clone();
    for (auto f : std::vector<cv::Ptr<cv::Feature2D>>{BriefDescriptor::create(), FreakDescriptor::create()}) {
        auto ka = grid_points(40, 40, 150, 120, 7), kb = ka;
        const cv::Mat da = describe(*f, a, ka), db = describe(*f, b, kb);
        int differ = 0;
        for (int r = 0; r < da.rows; ++r) differ += cv::norm(da.row(r), db.row(r), cv::NORM_HAMMING) > 0;
        CHECK(differ == da.rows);
    }
}

TEST_CASE("the drop policy removes keypoints whose pattern leaves the image, pad keeps them", "[landmarks][brief][freak]") {
    const cv::Mat img = texture(120, 100, 5);
    // BRIEF's margin is 24 + 4 = 28 px; FREAK's ceil(22) + 2 = 24 px
    const std::vector<cv::KeyPoint> kps{{27.f, 50.f, 7.f}, {28.f, 50.f, 7.f}, {91.f, 71.f, 7.f},
                                        {92.f, 71.f, 7.f}, {60.f, 50.f, 7.f}, {0.f, 0.f, 7.f}};
    auto kd = kps, kp = kps;
    cv::Mat dd = describe(*BriefDescriptor::create(BorderPolicy::drop), img, kd);
    cv::Mat dp = describe(*BriefDescriptor::create(BorderPolicy::pad), img, kp);
    REQUIRE(kd.size() == 3);
    CHECK(kd[0].pt == cv::Point2f(28, 50));
    CHECK(kd[1].pt == cv::Point2f(91, 71));
    CHECK(kd[2].pt == cv::Point2f(60, 50));
    REQUIRE(kp.size() == 6);
    CHECK(cv::norm(dd.row(0), dp.row(1), cv::NORM_HAMMING) == 0);
    CHECK(cv::norm(dd.row(2), dp.row(4), cv::NORM_HAMMING) == 0);
    auto kf = kps;
    describe(*FreakDescriptor::create(false, 22.f, BorderPolicy::drop), img, kf);
    CHECK(kf.size() == 5);  // only (0, 0) lies within 24 px of the border
}

TEST_CASE("images that are not 8-bit and bad FREAK scales are input errors", "[landmarks][brief][freak]") {
    cv::Mat f32(50, 50, CV_32F, cv::Scalar(0));
    std::vector<cv::KeyPoint> k{{25.f, 25.f, 7.f}};
    cv::Mat d;
    CHECK_THROWS_AS(BriefDescriptor::create()->compute(f32, k, d), InputError);
    CHECK_THROWS_AS(FreakDescriptor::create(false, 2.f), InputError);
}
