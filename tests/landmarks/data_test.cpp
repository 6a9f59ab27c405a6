// data_test.cpp: the landmark pipeline on the real datasets: the Middlebury 2006 disparity
// encoding pinned on pixels checked by hand against the images, the comparison on
// Middlebury scenes, and KITTI calibration and pairs. Exits 77 (CTest: skipped) with a
// message when the data directory ($HARRIS_COSIM_DATA, else ../shared/data) lacks the sets.
#include <catch2/catch.hpp>

#include "tests/catch_session.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "mapping/landmarks/landmarks.hpp"

namespace fs = std::filesystem;
using namespace hc::landmarks;

namespace {
fs::path g_data;

fs::path half() { return g_data / "middlebury2006" / "half"; }

/// The shift s in [0, 200) whose 9x9 patch of the right view best matches the left view's
/// around (x, y) (sum of squared grey differences).
int best_shift(const StereoImages& im, int x, int y) {
    double best = 1e300;
    int bs = -1;
    for (int s = 0; s < 200 && x - s >= 4; ++s) {
        double e = 0;
        for (int dy = -4; dy <= 4; ++dy)
            for (int dx = -4; dx <= 4; ++dx) {
                const double t = im.left.at<std::uint8_t>(y + dy, x + dx) - im.right.at<std::uint8_t>(y + dy, x - s + dx);
                e += t * t;
            }
        if (e < best) best = e, bs = s;
    }
    return bs;
}
}  // namespace

int main(int argc, char** argv) {
    const char* env = std::getenv("HARRIS_COSIM_DATA");
    g_data = env && *env ? fs::path(env) : fs::path(HC_TEST_DATA_DIR);
    if (!fs::exists(g_data / "middlebury2006" / "half" / "Aloe" / "disp1.png") ||
        !fs::exists(g_data / "kitti" / "sequences" / "01" / "calib.txt")) {
        std::printf("SKIP: no Middlebury 2006 half-size scenes or KITTI 01 under '%s' (set HARRIS_COSIM_DATA)\n",
                    g_data.string().c_str());
        return 77;
    }
    return hc::test::run_catch(argc, argv);
}

TEST_CASE("half-size disp1.png holds twice the half-size disparity: pixels checked by hand", "[landmarks][data]") {
    CHECK(middlebury_disparity(50, 0.5) == 25.0f);
    CHECK(middlebury_disparity(0, 0.5) == 0.0f);
    CHECK(middlebury_scale(555) == 0.5);
    const MiddleburyScene aloe = load_middlebury(half() / "Aloe");
    const MiddleburyScene rocks = load_middlebury(half() / "Rocks1");
    CHECK(aloe.dmin_full == 270);
    // (x, y, PNG value): the tip of the orange leaf shape at (100, 100) and the leaf edge at
    // (450, 300) in Aloe, viewed side by side with the right image shifted by value/2
    struct Pt { const MiddleburyScene* s; int x, y, value; };
    for (const Pt& p : {Pt{&aloe, 100, 100, 50}, Pt{&aloe, 450, 300, 120}, Pt{&rocks, 400, 300, 112}}) {
        INFO(p.s->name << " x=" << p.x << " y=" << p.y);
        const cv::Mat raw = cv::imread((half() / p.s->name / "disp1.png").string(), cv::IMREAD_UNCHANGED);
        CHECK(raw.at<std::uint8_t>(p.y, p.x) == p.value);
        CHECK(p.s->disparity.at<float>(p.y, p.x) == p.value / 2.0f);
        CHECK(best_shift(p.s->images, p.x, p.y) == p.value / 2);   // the images agree at d = value / 2
    }
}

TEST_CASE("a Middlebury folder without disp1.png is refused, naming the file", "[landmarks][data]") {
    const fs::path third = g_data / "middlebury2006" / "third" / "Aloe";
    if (!fs::exists(third / "view1.png")) {
        WARN("no third-size Aloe: skipped");
        return;
    }
    CHECK_THROWS_WITH(load_middlebury(third), Catch::Contains("disp1.png"));
    CHECK_NOTHROW(load_middlebury(third, false));
}

TEST_CASE("the landmarks command's default datasets are the half-size Middlebury scenes and KITTI under the data directory",
          "[landmarks][data]") {
    DatasetChoice c;
    c.data = g_data.string();
    fs::path root;
    const Dataset m = open_dataset(c, root);
    CHECK(root == half());
    CHECK(m.pairs.size() == middlebury_dataset(half()).pairs.size());
    c.dataset = "kitti";
    c.pairs = "3:5";
    const Dataset k = open_dataset(c, root);
    CHECK(root == g_data / "kitti");
    CHECK(k.pairs.size() == 2);
    CHECK(k.name == kitti_dataset(g_data / "kitti", "01", {3, 5}).name);
}

TEST_CASE("grid and SIFT on OpenCV corners of the six half-size scenes: ground truth confirms most correct matches",
          "[landmarks][data]") {
    const Dataset ds = middlebury_dataset(half());
    REQUIRE(ds.pairs.size() == 6);
    ComparisonOptions o;
    o.detectors = {Detector::opencv};
    o.descriptors = {Descriptor::grid, Descriptor::sift};
    const auto rows = compare(ds, o);
    REQUIRE(rows.size() == 2);
    for (const auto& r : rows) {
        INFO(descriptor_name(r.descriptor) << ": all " << r.totals.all << " correct " << r.totals.correct << " known "
                                           << r.totals.truth_known << " truth " << r.totals.truth_correct);
        CHECK(r.totals.pairs == 6);
        CHECK(r.totals.correct > 1000);
        CHECK(r.totals.truth_known > 0.8 * r.totals.correct);
        CHECK(r.totals.truth_correct > 0.8 * r.totals.truth_known);
        const DepthError de = depth_error(r, ds);
        CHECK(de.n <= r.totals.truth_known);   // matches behind the cameras have no depth
        CHECK(de.n >= r.totals.truth_correct);
        CHECK(de.median < 0.01);
    }
    CHECK(rows[0].descriptor_bytes == 35);
    CHECK(rows[1].descriptor_bytes == 512);
}

TEST_CASE("KITTI 01 pairs load with the sequence's P0 and P1", "[landmarks][data]") {
    const Dataset ds = kitti_dataset(g_data / "kitti", "01", {0, 2});
    REQUIRE(ds.pairs.size() == 2);
    CHECK(ds.pairs[0].left.size() == cv::Size(1241, 376));
    CHECK(ds.calib[0].fx == 718.856);
    CHECK(ds.calib[0].baseline() == Approx(386.1448 / 718.856).epsilon(1e-15));
    CHECK(ds.disparity[0].empty());
}
