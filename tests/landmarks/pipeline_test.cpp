// pipeline_test.cpp: corner sources, matching and scoring on a synthetic stereo pair whose
// right image is the left shifted by a known disparity, and the refusals of bad input.
#include <catch2/catch.hpp>

#include <random>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "mapping/landmarks/landmarks.hpp"
#include "model/spec/opencv_reference.hpp"
#include "model/spec/spec_model.hpp"

using namespace hc::landmarks;

namespace {

constexpr int kShift = 8;   // disparity of every scene point

/// Random grey rectangles on a dark background (many Harris corners); the right view is the
/// left moved kShift px to the left, so x_r = x_l - kShift on every row.
StereoImages shifted_pair(int w = 320, int h = 240) {
    cv::Mat scene(h, w + kShift, CV_8UC1, cv::Scalar(20));
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> ux(0, w + kShift - 1), uy(0, h - 1), us(6, 30), uv(60, 250);
    for (int i = 0; i < 120; ++i)
        cv::rectangle(scene, cv::Rect(ux(rng), uy(rng), us(rng), us(rng)), cv::Scalar(uv(rng)), cv::FILLED);
    StereoImages p;
    p.left = scene(cv::Rect(0, 0, w, h)).clone();
    p.right = scene(cv::Rect(kShift, 0, w, h)).clone();
    p.name = "shifted";
    return p;
}

cv::Mat shifted_truth(int w = 320, int h = 240) {
    cv::Mat d(h, w, CV_32F, cv::Scalar(kShift));
    d(cv::Rect(0, 0, kShift, h)).setTo(0);   // no right-image pixel: unknown
    return d;
}

hc::Image to_image(const cv::Mat& m) {
    hc::Image im(m.cols, m.rows);
    for (int r = 0; r < m.rows; ++r) std::copy_n(m.ptr<std::uint8_t>(r), m.cols, &im.at(r, 0));
    return im;
}

}  // namespace

TEST_CASE("the opencv corner source returns the reference mask of docs/metrics.md as keypoints", "[landmarks]") {
    const StereoImages p = shifted_pair();
    const auto kp = detect_pairs(Detector::opencv, {p});
    std::vector<std::uint8_t> mask;
    hc::spec::opencv_corners(to_image(p.left), hc::spec::ReferenceOptions{}, mask);
    long n = 0;
    for (auto v : mask) n += v;
    REQUIRE(static_cast<long>(kp[0].left.points.size()) == n);
    for (const auto& k : kp[0].left.points) {
        INFO("x=" << k.pt.x << " y=" << k.pt.y);
        CHECK(mask[static_cast<size_t>(k.pt.y) * p.left.cols + static_cast<size_t>(k.pt.x)] == 1);
        CHECK(k.class_id == 0);
    }
    CHECK(kp[0].right.frame == 1);
    CHECK(kp[0].left.source == Detector::opencv);
}

TEST_CASE("the spec corner source streams a seed pair first: its corners are the model's on L R L R, frames 2 and 3",
          "[landmarks]") {
    const StereoImages p = shifted_pair();
    const auto kp = detect_pairs(Detector::spec, {p});
    const hc::spec::SpecModel m{};
    const hc::Image l = to_image(p.left), r = to_image(p.right);
    std::int64_t prev = m.reset_max();
    const auto fc = m.run({&l, &r, &l, &r}, prev, 1);
    REQUIRE(static_cast<long>(kp[0].left.points.size()) == fc[2].count);
    REQUIRE(static_cast<long>(kp[0].right.points.size()) == fc[3].count);
    for (const auto& k : kp[0].right.points)
        CHECK(fc[3].mask[static_cast<size_t>(k.pt.y) * p.left.cols + static_cast<size_t>(k.pt.x)] == 1);
}

TEST_CASE("the SIFT 512 source keeps the 512 strongest SIFT points", "[landmarks]") {
    StereoImages p;   // blurred noise: thousands of SIFT blobs
    p.left.create(480, 640, CV_8UC1);
    cv::randu(p.left, 0, 256);
    cv::GaussianBlur(p.left, p.left, cv::Size(9, 9), 2.0);
    p.right = p.left.clone();
    p.name = "noise";
    const auto all = detect_pairs(Detector::sift, {p});
    const auto best = detect_pairs(Detector::sift512, {p});
    REQUIRE(all[0].left.points.size() > 512);
    CHECK(best[0].left.points.size() >= 512);   // retainBest keeps ties at the 512th response
    float weakest = 1e9f;
    for (const auto& k : best[0].left.points) weakest = std::min(weakest, k.response);
    long stronger = 0;
    for (const auto& k : all[0].left.points) stronger += k.response > weakest;
    CHECK(stronger < 512);
}

TEST_CASE("grid on OpenCV corners of a shifted pair: its correct matches agree with the ground truth", "[landmarks]") {
    const StereoImages p = shifted_pair();
    const auto kp = detect_pairs(Detector::opencv, {p});
    const PairResult r = match_pair(p, kp[0], Descriptor::grid, GridParams{16, 2}, MatchParams{}, shifted_truth());
    INFO("all " << r.all() << " correct " << r.correct() << " known " << r.truth_known() << " truth " << r.truth_correct());
    CHECK(r.descriptor_bytes == 35);
    CHECK(r.correct() >= 100);
    CHECK(r.truth_correct() >= 0.95 * r.truth_known());
    CHECK(r.has_truth);
}

TEST_CASE("a ground-truth-correct match has |x_l - x_r - d| <= 1 and |y_r - y_l| <= 1, x-only and wrong ones are told apart",
          "[landmarks]") {
    const StereoImages p = shifted_pair();
    const auto kp = detect_pairs(Detector::opencv, {p});
    for (Descriptor d : {Descriptor::brief, Descriptor::orb, Descriptor::sift}) {
        const PairResult r = match_pair(p, kp[0], d, {}, MatchParams{}, shifted_truth());
        REQUIRE(r.all() > 0);
        for (const auto& m : r.matches) {
            if (m.truth < 0) continue;
            INFO(descriptor_name(d) << " x_l=" << m.left.x << " x_r=" << m.right.x);
            const bool x_ok = std::abs(m.left.x - m.right.x - kShift) <= 1.0f;
            const bool y_ok = std::abs(m.right.y - m.left.y) <= 1.0f;
            CHECK((m.truth == truth_right) == (x_ok && y_ok));
            CHECK((m.truth == truth_x_only) == (x_ok && !y_ok));
            CHECK((m.truth == truth_wrong) == !x_ok);
        }
    }
}

TEST_CASE("acquire puts the landmarks of a shifted pair at fx * b / disparity", "[landmarks]") {
    const double P0[12] = {718.856, 0, 160, 0, 0, 718.856, 120, 0, 0, 0, 1, 0}, P1[12] = {718.856, 0, 160, -386.1448, 0, 718.856, 120, 0, 0, 0, 1, 0};
    const hc::landmarks::RectifiedRig c = hc::landmarks::rig_from_projections(P0, P1);
    const StereoImages p = shifted_pair();
    PipelineOptions o;
    o.descriptor = Descriptor::grid;
    o.grid = {16, 2};
    const auto lm = acquire(p.left, p.right, c, o);
    REQUIRE(lm.size() >= 100);
    long at_depth = 0;
    for (const auto& l : lm) {
        at_depth += std::abs(l.p_cam[2] - 386.1448 / kShift) <= 1e-12 * l.p_cam[2];
        CHECK(l.descriptor.size() == 35u);
        CHECK(l.cov(2, 2) > 0);
    }
    CHECK(at_depth >= 0.95 * static_cast<double>(lm.size()));
}

TEST_CASE("impossible or out-of-range requests are refused with InputError", "[landmarks]") {
    CHECK_THROWS_AS(check_combination(Descriptor::sift, Detector::opencv, Norm::hamming), hc::InputError);
    CHECK_THROWS_AS(check_combination(Descriptor::grid, Detector::opencv, Norm::l2), hc::InputError);
    CHECK_NOTHROW(check_combination(Descriptor::sift, Detector::opencv, Norm::l2));
    CHECK_THROWS_AS(validate(GridParams{1000, 3}), hc::InputError);
    CHECK_THROWS_AS(validate(GridParams{16, -1}), hc::InputError);
    CHECK_THROWS_AS(parse_detector("surf"), hc::InputError);
    CHECK_THROWS_AS(parse_descriptor("surf"), hc::InputError);
    StereoImages bad = shifted_pair();
    bad.right = bad.right(cv::Rect(0, 0, 300, 240)).clone();
    CHECK_THROWS_WITH(detect_pairs(Detector::opencv, {bad}), Catch::Contains("differ in size"));
    StereoImages a = shifted_pair(), b = shifted_pair(160, 120);
    CHECK_THROWS_WITH(detect_pairs(Detector::spec, {a, b}), Catch::Contains("streams one image size"));
}

TEST_CASE("score_formats scores a configuration as the comparison scores grid on the spec source's corners", "[landmarks]") {
    Dataset ds;
    ds.name = "shifted";
    ds.pairs = {shifted_pair()};
    ds.disparity = {shifted_truth()};
    const double P0[12] = {700, 0, 160, 0, 0, 700, 120, 0, 0, 0, 1, 0}, P1[12] = {700, 0, 160, -350, 0, 700, 120, 0, 0, 0, 1, 0};
    const hc::landmarks::RectifiedRig c = hc::landmarks::rig_from_projections(P0, P1);
    ds.calib = {c};
    const Totals t = score_formats(ds, hc::Formats{}, Detector::spec, GridParams{16, 2});
    ComparisonOptions o;
    o.detectors = {Detector::spec};
    o.descriptors = {Descriptor::grid};
    o.grid = {16, 2};
    const auto rows = compare(ds, o);
    REQUIRE(rows.size() == 1);
    CHECK(t.correct == rows[0].totals.correct);
    CHECK(t.truth_correct == rows[0].totals.truth_correct);
    CHECK(t.all == rows[0].totals.all);
    CHECK(t.correct > 50);
    hc::Formats narrow;
    narrow.m_prod_w = 12;   // a configuration that loses most of M's bits scores differently
    narrow.m_drop = 5;
    const Totals tn = score_formats(ds, narrow, Detector::spec, GridParams{16, 2});
    CHECK(tn.keypoints != t.keypoints);
    CHECK_THROWS_AS(score_formats(ds, hc::Formats{}, Detector::opencv), hc::InputError);
}

TEST_CASE("the g x h study of a fixed pair gives the counts of the reference matcher", "[landmarks]") {
    // Counts recorded with the scalar brute-force matcher (one 64-bit popcount per word and
    // pair, offers in index order); any faster matcher must reproduce them exactly.
    Dataset ds;
    ds.name = "shifted";
    ds.pairs = {shifted_pair(), shifted_pair(400, 300)};
    ds.disparity = {shifted_truth(), shifted_truth(400, 300)};
    const double P0[12] = {700, 0, 160, 0, 0, 700, 120, 0, 0, 0, 1, 0}, P1[12] = {700, 0, 160, -350, 0, 700, 120, 0, 0, 0, 1, 0};
    const hc::landmarks::RectifiedRig c = hc::landmarks::rig_from_projections(P0, P1);
    ds.calib = {c, c};
    StudyOptions o;
    o.g_min = 4;
    o.g_max = 33;   // 1 to 18 64-bit words per descriptor
    o.h_min = 0;
    o.h_max = 3;
    o.threads = 1;
    // all,correct,truth_correct_x per cell, g-major (g 4..33, h 0..3); printed ratio test, then drop ties
    const std::string expected[2] = {
        "18,18,18 86,85,85 348,342,342 608,600,599 29,29,29 149,148,148 460,460,460 636,635,635 52,52,52 "
        "224,222,221 535,531,531 648,647,647 61,61,61 290,288,286 569,564,564 651,650,650 90,89,89 "
        "344,340,339 603,600,599 650,650,650 123,122,121 402,399,398 622,619,619 651,651,651 156,155,154 "
        "452,447,446 636,632,632 651,651,651 197,196,195 483,480,479 643,642,642 651,651,651 228,226,225 "
        "513,510,510 649,648,648 651,651,651 266,263,261 535,532,532 650,649,649 651,651,651 299,294,292 "
        "565,562,562 650,650,650 651,651,651 332,327,325 577,574,574 651,651,650 651,651,651 363,359,357 "
        "591,588,588 651,651,651 651,651,651 395,392,390 603,601,601 651,651,651 651,651,651 415,412,410 "
        "611,609,609 651,651,651 651,651,651 442,439,437 618,616,616 651,651,651 651,651,651 460,459,457 "
        "630,630,630 651,651,651 651,651,651 473,472,470 632,632,632 651,651,651 651,651,651 491,489,487 "
        "639,639,639 651,651,651 651,651,651 502,500,498 642,642,642 651,651,651 651,651,651 515,512,511 "
        "645,645,645 651,651,651 651,651,651 525,521,521 647,647,647 651,651,651 651,651,651 541,538,537 "
        "651,650,650 651,651,651 651,651,651 550,548,547 651,650,650 651,651,651 651,651,651 559,557,556 "
        "651,650,650 651,651,651 651,651,651 568,567,565 651,651,650 651,651,651 651,651,651 580,579,577 "
        "651,651,650 651,651,651 651,651,651 587,586,584 651,651,650 651,651,651 651,651,651 591,590,588 "
        "651,651,650 651,651,651 651,651,651 597,595,595 651,651,650 651,651,651 651,651,651 ",
        "3,3,3 46,46,46 281,281,281 578,577,576 9,9,9 101,101,101 416,416,416 628,628,628 24,24,24 "
        "170,170,170 498,498,498 646,646,646 26,26,26 238,238,238 537,537,537 650,650,650 49,49,49 "
        "288,288,288 582,582,581 650,650,650 81,81,81 349,349,349 607,607,607 651,651,651 102,102,102 "
        "408,408,408 626,626,626 650,650,650 143,143,143 448,448,448 638,638,638 650,650,650 168,168,168 "
        "486,486,486 649,648,648 651,651,651 205,205,205 513,513,513 650,649,649 651,651,651 240,240,240 "
        "548,548,548 650,650,650 650,650,650 277,277,277 561,561,561 650,650,650 651,651,651 311,311,311 "
        "577,577,577 651,651,651 651,651,651 353,353,353 589,589,589 651,651,651 651,651,651 375,375,375 "
        "595,595,595 651,651,651 651,651,651 405,405,405 605,605,605 651,651,651 651,651,651 428,428,428 "
        "628,628,628 650,650,650 651,651,651 442,442,442 629,629,629 650,650,650 651,651,651 467,467,467 "
        "637,637,637 651,651,651 650,650,650 478,478,478 641,641,641 651,651,651 650,650,650 493,493,493 "
        "644,644,644 650,650,650 651,651,651 505,505,505 646,646,646 650,650,650 651,651,651 525,525,525 "
        "648,648,648 651,651,651 651,651,651 535,535,535 648,648,648 651,651,651 651,651,651 545,545,545 "
        "649,649,649 651,651,651 651,651,651 554,554,554 649,649,649 651,651,651 651,651,651 572,572,570 "
        "649,649,649 651,651,651 651,651,651 577,577,575 649,649,649 651,651,651 651,651,651 582,582,580 "
        "650,650,650 651,651,651 651,651,651 588,588,588 650,650,650 651,651,651 651,651,651 "};
    for (bool drop_ties : {false, true}) {
        o.match.drop_ties = drop_ties;
        const StudyResult s = study(ds, Detector::opencv, o);
        std::ostringstream got;
        // the recorded third count is the x-only ground-truth check (|x_l - x_r - d| <= 1)
        for (const auto& cell : s.cells) got << cell.all << ',' << cell.correct << ',' << cell.truth_correct_x << ' ';
        INFO("drop_ties " << drop_ties);
        CHECK(got.str() == expected[drop_ties]);
    }
}

TEST_CASE("a match 3 rows off with the right disparity passes the epipolar test but is not ground-truth-correct",
          "[landmarks]") {
    // the right view is the left moved kShift px left and 3 rows up: every true correspondence
    // has x_l - x_r = kShift (the ground truth) and y_r - y_l = -3
    StereoImages p = shifted_pair();
    cv::Mat up(p.right.size(), p.right.type(), cv::Scalar(20));
    p.right(cv::Rect(0, 3, p.right.cols, p.right.rows - 3)).copyTo(up(cv::Rect(0, 0, p.right.cols, p.right.rows - 3)));
    p.right = up;
    const auto kp = detect_pairs(Detector::opencv, {p});
    const PairResult r = match_pair(p, kp[0], Descriptor::brief, {}, MatchParams{}, shifted_truth());
    INFO("correct " << r.correct() << " known " << r.truth_known() << " x only " << r.truth_correct_x() << " x and y "
                    << r.truth_correct());
    REQUIRE(r.truth_known() > 50);
    CHECK(r.truth_correct_x() >= 0.9 * r.truth_known());   // right in x ...
    CHECK(r.truth_correct() <= 0.02 * r.truth_known());    // ... 3 rows off
    Totals t;
    t.add(r);
    CHECK(t.truth_correct == r.truth_correct());
    CHECK(t.truth_correct_x == r.truth_correct_x());
}

TEST_CASE("held_out_choice picks (g, h) on one set of pairs and scores it on the other", "[landmarks]") {
    StudyResult s;
    // three cells, four pairs; ground-truth-correct counts per pair
    auto cell = [](int g, int h, std::vector<long> truth) {
        StudyCell c{g, h, 0, 0, 0, 0, truth, truth};
        for (long v : truth) c.truth_correct += v, c.correct += v;
        return c;
    };
    s.cells = {cell(8, 1, {10, 1, 10, 1}), cell(16, 2, {5, 9, 5, 9}), cell(24, 3, {7, 7, 7, 20})};
    const HeldOutChoice a = held_out_choice(s, {0, 2}, {1, 3}, true);
    CHECK(a.chosen.g == 8);
    CHECK(a.chosen.truth_correct == 20);
    CHECK(a.on_report.g == 8);
    CHECK(a.on_report.truth_correct == 2);
    CHECK(a.report_best.g == 24);
    CHECK(a.report_best.truth_correct == 27);
    const HeldOutChoice b = held_out_choice(s, {1, 3}, {0, 2}, true);
    CHECK(b.chosen.g == 24);
    CHECK(b.on_report.truth_correct == 14);
    CHECK(b.report_best.g == 8);
    CHECK_THROWS(s.on_pairs({4}));
    CHECK(s.best_truth().g == 24);   // on all four pairs: 41 against 28 and 22
}

TEST_CASE("re-observations of a scene moved by whole pixels: tracked without descriptors, grid and BRIEF distances 0",
          "[landmarks]") {
    // frame 1 is frame 0 moved 3 px right and 2 px down: every corner away from the borders is
    // tracked to its moved self, and descriptors that depend only on relative positions or on
    // the patch (grid, BRIEF) are identical there, while random pairs are far apart
    const StereoImages a = shifted_pair(360, 280);
    cv::Mat moved(a.left.size(), a.left.type(), cv::Scalar(20));
    a.left(cv::Rect(0, 0, a.left.cols - 3, a.left.rows - 2)).copyTo(moved(cv::Rect(3, 2, a.left.cols - 3, a.left.rows - 2)));
    Dataset ds;
    ds.name = "moved";
    ds.pairs = {a, StereoImages{moved, moved, "moved"}};
    ReobservationOptions o;
    o.descriptors = {Descriptor::grid, Descriptor::brief};
    const auto kp = detect_dataset(ds, Detector::opencv, o.corners);
    const auto tracks = track_corners(ds.pairs[0].left, ds.pairs[1].left, kp[0].left.points, kp[1].left.points, o);
    REQUIRE(tracks.size() > 100);
    long exact = 0;
    for (const auto& [i, j] : tracks)
        exact += kp[1].left.points[size_t(j)].pt == kp[0].left.points[size_t(i)].pt + cv::Point2f(3, 2);
    // measured 325 of 330: a few tracks end within 1 px of a neighbouring corner instead
    CHECK(exact >= 0.97 * static_cast<double>(tracks.size()));
    const auto rows = reobservation_study(ds, o);
    REQUIRE(rows.size() == 2);
    for (const auto& r : rows) {
        INFO(descriptor_name(r.descriptor) << ": " << r.reobservations << " re-observations, median " << r.same_median
                                           << " against random " << r.random_median);
        CHECK(r.reobservations > 100);
        CHECK(r.random_median > 0.05);
    }
    // BRIEF reads the image: identical where its patch stays off the moved-in border; the grid
    // reads neighbour positions, some of which leave or enter the image: nearly identical
    CHECK(rows[1].same_median == 0.0);
    CHECK(rows[0].same_median < 0.5 * rows[0].random_median);
    CHECK(rows[1].nearest >= 0.9 * rows[1].reobservations);
    CHECK_THROWS_AS(reobservation_study(Dataset{"one", {a}, {}, {}, nullptr}, o), hc::InputError);
    o.descriptors = {Descriptor::sift};
    CHECK_THROWS_AS(reobservation_study(ds, o), hc::InputError);
}
