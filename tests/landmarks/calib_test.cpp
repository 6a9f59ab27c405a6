// calib_test.cpp: the calibration library without data: board specifications, the KITTI
// calib.txt and OpenCV storage formats, undistortion of points checked by hand, and the
// calibration of a synthetic rig from its exact projections.
#include <catch2/catch.hpp>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tests/landmarks/kitti_calib_text.hpp"
#include "mapping/landmarks/calib.hpp"

using namespace hc::landmarks;
namespace fs = std::filesystem;

namespace {

// A KITTI odometry calib.txt in full (P0..P3 and Tr), numbers of sequence 00.
const std::string kKittiFull = std::string(hc::landmarks::test::kKitti00P0P1) +
    "P2: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 4.538225000000e+01 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 -1.130887000000e-01 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 3.779761000000e-03\n"
    "P3: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.372877000000e+02 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 2.369057000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 4.915215000000e-03\n"
    "Tr: 4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 -1.198459927713e-02 "
    "-7.210626507497e-03 8.081198471645e-03 -9.999413164504e-01 -5.403984729748e-02 "
    "9.999738645903e-01 4.859485810390e-04 -7.206933692422e-03 -2.921968648686e-01\n";

bool bit_equal(const cv::Mat& a, const cv::Mat& b) {
    return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

// A rig with distortion, a rotated right camera and a 0.12 baseline (unit of the square).
struct SyntheticRig {
    cv::Mat K1 = (cv::Mat_<double>(3, 3) << 520, 0, 318, 0, 522, 243, 0, 0, 1);
    cv::Mat D1 = (cv::Mat_<double>(1, 5) << -0.21, 0.08, 0.001, -0.0005, 0);
    cv::Mat K2 = (cv::Mat_<double>(3, 3) << 530, 0, 325, 0, 529, 236, 0, 0, 1);
    cv::Mat D2 = (cv::Mat_<double>(1, 5) << -0.18, 0.05, -0.0008, 0.0006, 0);
    cv::Mat rvec = (cv::Mat_<double>(3, 1) << 0.01, -0.02, 0.005);   // right from left
    cv::Mat T = (cv::Mat_<double>(3, 1) << -0.12, 0.002, 0.001);
};

}  // namespace

TEST_CASE("a board is given as inner corners WxH with a positive square", "[calib]") {
    const Board b = parse_board("9x6", 0.025);
    CHECK(b.inner == cv::Size(9, 6));
    CHECK(b.square == 0.025);
    CHECK(parse_board("7X5", 1).inner == cv::Size(7, 5));
    for (const char* bad : {"9", "9x", "x6", "9x6x2", "9*6", "1x6", "9x101", "nine", "-9x6"})
    {
        INFO("board '" << bad << "'");
        CHECK_THROWS_AS(parse_board(bad, 1.0), hc::InputError);
    }
    CHECK_THROWS_WITH(parse_board("9y6", 1.0), Catch::Contains("'9y6'"));
    CHECK_THROWS_AS(parse_board("9x6", 0), hc::InputError);
    CHECK_THROWS_AS(parse_board("9x6", -1), hc::InputError);
}

TEST_CASE("undistortPoints inverts the thesis's radial model at a point checked by hand", "[calib]") {
    // fx = fy = 500, (cx, cy) = (320, 240), k1 = -0.2. The normalised point (0.4, 0.3) has
    // r^2 = 0.25, so eq. 4.2 scales it by 1 - 0.2 * 0.25 = 0.95 to (0.38, 0.285): the camera
    // sees it at (500 * 0.38 + 320, 500 * 0.285 + 240) = (510, 382.5). Undistorted and put
    // back through the same K it is (500 * 0.4 + 320, 500 * 0.3 + 240) = (520, 390).
    Calibration c;
    c.K1 = (cv::Mat_<double>(3, 3) << 500, 0, 320, 0, 500, 240, 0, 0, 1);
    c.D1 = (cv::Mat_<double>(1, 5) << -0.2, 0, 0, 0, 0);
    c.R1 = cv::Mat::eye(3, 3, CV_64F);
    c.rectified.fx = c.rectified.fy = 500;   // the left rectified projection [500 0 320 0; 0 500 240 0; 0 0 1 0]
    c.rectified.cx0 = 320;
    c.rectified.cy = 240;
    auto p = rectify_points(c, Side::left, {{510.f, 382.5f}});
    REQUIRE(p.size() == 1);
    CHECK(p[0].x == Approx(520).margin(1e-3));   // float32 points: 1e-3 px is ~30 ulp at 520
    CHECK(p[0].y == Approx(390).margin(1e-3));
    // With a rectifying rotation of 90 degrees about the optical axis, (x, y, 1) = (0.4, 0.3, 1)
    // becomes (-0.3, 0.4, 1); a rectified projection f = 600, (cx, cy) = (300, 200) puts it at
    // (600 * -0.3 + 300, 600 * 0.4 + 200) = (120, 440).
    c.R1 = (cv::Mat_<double>(3, 3) << 0, -1, 0, 1, 0, 0, 0, 0, 1);
    c.rectified.fx = c.rectified.fy = 600;
    c.rectified.cx0 = 300;
    c.rectified.cy = 200;
    p = rectify_points(c, Side::left, {{510.f, 382.5f}});
    CHECK(p[0].x == Approx(120).margin(1e-3));
    CHECK(p[0].y == Approx(440).margin(1e-3));
    // The right camera uses K2, D2, R2 and the right rectified projection (stereoRectify's P2,
    // here [500 0 320 -50; 0 500 240 0; 0 0 1 0]): no distortion, identity, so no change.
    c.K2 = c.K1.clone();
    c.D2 = cv::Mat::zeros(1, 5, CV_64F);
    c.R2 = cv::Mat::eye(3, 3, CV_64F);
    c.rectified.fx = c.rectified.fy = 500;
    c.rectified.cx1 = 320;
    c.rectified.tx1 = -50;
    c.rectified.cy = 240;
    p = rectify_points(c, Side::right, {{510.f, 382.5f}});
    CHECK(p[0].x == Approx(510).margin(1e-3));
    CHECK(p[0].y == Approx(382.5).margin(1e-3));
}

TEST_CASE("KITTI's calib.txt is read from P0 and P1, ignoring P2, P3 and Tr", "[calib]") {
    const Calibration c = parse_kitti_calib(kKittiFull, "calib.txt");
    CHECK(c.rectified_input);
    CHECK(c.rectified.fx == 718.856);
    CHECK(c.rectified.baseline() == Approx(386.1448 / 718.856).epsilon(1e-15));
    CHECK(c.K1.at<double>(0, 2) == 607.1928);
    CHECK(c.K1.at<double>(1, 2) == 185.2157);
    CHECK(c.T.at<double>(0) == Approx(-386.1448 / 718.856).epsilon(1e-15));
    // Q sends a disparity d to depth f b / d: at d = 10 px, 718.856 * 0.53716... / 10.
    const cv::Mat X = c.Q * (cv::Mat_<double>(4, 1) << 607.1928, 185.2157, 10, 1);
    CHECK(X.at<double>(0) / X.at<double>(3) == Approx(0).margin(1e-12));
    CHECK(X.at<double>(2) / X.at<double>(3) == Approx(386.1448 / 10).epsilon(1e-12));
    // Already rectified images: keypoints are not moved at all.
    const std::vector<cv::Point2f> pts{{12.25f, 300.5f}, {1200.f, 3.f}};
    CHECK(rectify_points(c, Side::left, pts) == pts);
    CHECK(rectify_points(c, Side::right, pts) == pts);
}

TEST_CASE("a malformed KITTI calib.txt is refused naming the file, line and row", "[calib]") {
    CHECK_THROWS_WITH(parse_kitti_calib("P0: 1 0 0 0 0 1 0 0 0 0 1 0\n", "x/calib.txt"),
                      Catch::Contains("x/calib.txt") && Catch::Contains("P1"));
    CHECK_THROWS_WITH(parse_kitti_calib("P0: 1 0 0 0 0 1 0 0 0 0 1\nP1: 1 0 0 -1 0 1 0 0 0 0 1 0\n", "c.txt"),
                      Catch::Contains("c.txt:1") && Catch::Contains("11 numbers"));
    CHECK_THROWS_WITH(parse_kitti_calib("P0: 1 0 0 0 0 1 0 0 0 0 1 0 0\nP1: 1 0 0 -1 0 1 0 0 0 0 1 0\n", "c.txt"),
                      Catch::Contains("c.txt:1"));
    CHECK_THROWS_WITH(parse_kitti_calib("P0: 1 0 0 0 0 1 0 0 0 0 1 0\nP1: 1 0 0 -1 0 1 zero 0 0 0 1 0\n", "c.txt"),
                      Catch::Contains("c.txt:2") && Catch::Contains("P1"));
    CHECK_THROWS_WITH(parse_kitti_calib("P0: 1 0 0 0 0 1 0 0 0 0 1 0\nP1: 1 0 0 0 0 1 0 0 0 0 1 0\n", "c.txt"),
                      Catch::Contains("baseline"));
    CHECK_THROWS_WITH(read_kitti_calib("no/such/calib.txt"), Catch::Contains("no/such/calib.txt"));
}

TEST_CASE("calib.txt written and read back gives the same projections bit for bit", "[calib]") {
    Calibration c;
    c.rectified.fx = c.rectified.fy = 535.9157339616320;
    c.rectified.cx0 = c.rectified.cx1 = 342.28315473308373;
    c.rectified.cy = 235.57082909788173;
    c.rectified.tx1 = -1.0 / 3.0 * 535.9157339616320;
    const std::string text = to_kitti_calib(c);
    const Calibration r = parse_kitti_calib(text, "round trip");
    CHECK(bit_equal(projection(r.rectified, Side::left), projection(c.rectified, Side::left)));
    CHECK(bit_equal(projection(r.rectified, Side::right), projection(c.rectified, Side::right)));
    CHECK(to_kitti_calib(r) == text);
    // The format is KITTI's: two rows of 12 numbers; KITTI's own numbers keep their value.
    CHECK(text.rfind("P0: 5.35915733961632e+02 0e+00 3.4228315473308373e+02 0e+00 ", 0) == 0);
    const Calibration k = parse_kitti_calib(kKittiFull, "kitti");
    const Calibration k2 = parse_kitti_calib(to_kitti_calib(k), "kitti rewritten");
    CHECK(bit_equal(projection(k.rectified, Side::left), projection(k2.rectified, Side::left)));
    CHECK(bit_equal(projection(k.rectified, Side::right), projection(k2.rectified, Side::right)));
    CHECK(to_kitti_calib(k).rfind("P0: 7.18856e+02 0e+00 6.071928e+02 0e+00", 0) == 0);
}

TEST_CASE("the disparity-to-depth matrix equals stereoRectify's Q", "[calib]") {
    const SyntheticRig s;
    cv::Mat R, R1, R2, P1, P2, Q;
    cv::Rodrigues(s.rvec, R);
    cv::stereoRectify(s.K1, s.D1, s.K2, s.D2, cv::Size(640, 480), R, s.T, R1, R2, P1, P2, Q,
                      cv::CALIB_ZERO_DISPARITY, 0);
    const cv::Mat q = disparity_to_depth(hc::landmarks::rig_from_projections(P1.ptr<double>(), P2.ptr<double>()));
    INFO("Q " << Q << "\nours " << q);
    CHECK(cv::norm(q, Q, cv::NORM_INF) <= 1e-12 * cv::norm(Q, cv::NORM_INF));
}

TEST_CASE("calibrating a synthetic rig from its exact corners recovers it", "[calib]") {
    // Twelve board poses seen by both cameras of SyntheticRig, projected with
    // cv::projectPoints (no noise): the calibration must return the rig itself.
    const SyntheticRig s;
    const Board board{cv::Size(9, 6), 0.025};
    std::vector<cv::Point3f> obj;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 9; ++j) obj.emplace_back(j * 0.025f, i * 0.025f, 0.f);
    cv::Mat R;
    cv::Rodrigues(s.rvec, R);
    Detection d;
    d.image_size = cv::Size(640, 480);
    for (int v = 0; v < 12; ++v) {
        const double a = 0.35 * std::sin(v * 1.3), b = 0.35 * std::cos(v * 0.7), g = 0.2 * std::sin(v * 2.1);
        const cv::Mat rv = (cv::Mat_<double>(3, 1) << a, b, g);
        const cv::Mat tv = (cv::Mat_<double>(3, 1) << -0.1 + 0.02 * std::sin(v), -0.06 + 0.02 * std::cos(v),
                            0.35 + 0.03 * (v % 4));
        cv::Mat Rb;
        cv::Rodrigues(rv, Rb);
        const cv::Mat tr = R * tv + s.T;
        cv::Mat rvr;
        cv::Rodrigues(R * Rb, rvr);
        StereoView view;
        view.name = "view " + std::to_string(v);
        cv::projectPoints(obj, rv, tv, s.K1, s.D1, view.left);
        cv::projectPoints(obj, rvr, tr, s.K2, s.D2, view.right);
        d.views.push_back(view);
    }
    const Calibration c = calibrate(d, board);
    INFO("K1 " << c.K1 << "\nK2 " << c.K2 << "\nT " << c.T << "\nrms " << c.rms);
    // float32 corners: the residual is rounding only. Measured: RMS 9e-6 px, K within 4.4e-5 px,
    // T within 7e-9.
    CHECK(c.rms < 1e-4);
    CHECK(cv::norm(c.K1, s.K1, cv::NORM_INF) < 1e-3);
    CHECK(cv::norm(c.K2, s.K2, cv::NORM_INF) < 1e-3);
    CHECK(cv::norm(c.T, s.T, cv::NORM_INF) < 1e-7);
    CHECK(c.rectified.baseline() == Approx(cv::norm(s.T)).epsilon(1e-4));
    REQUIRE(c.per_view_errors.size() == 12);
    CHECK(c.view_names[3] == "view 3");
    const RectificationCheck chk = check_rectification(c, d);
    CHECK(chk.corners == 12u * 54u);
    CHECK(chk.max_abs_dy < 1e-3);
    // The picture: both rectified images side by side, the first left corner drawn in green
    // (a ring of radius 3 around its rectified position).
    const cv::Mat grey(480, 640, CV_8U, cv::Scalar(0));
    const cv::Mat fig = rectified_pair_figure(c, grey, grey, d.views[0]);
    CHECK(fig.size() == cv::Size(1280, 480));
    CHECK(fig.type() == CV_8UC3);
    const cv::Point2f p = rectify_points(c, Side::left, {d.views[0].left[0]})[0];
    const cv::Vec3b ring = fig.at<cv::Vec3b>(cvRound(p.y), cvRound(p.x) + 3);
    INFO("pixel at (" << cvRound(p.x) + 3 << ", " << cvRound(p.y) << "): " << ring);
    CHECK(ring[1] > 100);
    CHECK(ring[2] < 50);
    CHECK_THROWS_WITH(rectified_pair_figure(c, grey(cv::Rect(0, 0, 320, 240)), grey, d.views[0]),
                      Catch::Contains("320x240"));
    // The report: the figures above, and a warning only when the rows disagree.
    const std::string report = report_markdown(c, d, board, chk);
    CHECK(report.find("over 648 corner pairs") != std::string::npos);
    CHECK(report.find("| view 3 |") != std::string::npos);
    CHECK(report.find("not usable") == std::string::npos);
    CHECK(report_markdown(c, d, board, RectificationCheck{1.5, 4.0, 648}).find("differ by 1.50 px") != std::string::npos);
    // Two views are too few.
    Detection two = d;
    two.views.resize(2);
    CHECK_THROWS_WITH(calibrate(two, board), Catch::Contains("2 stereo pairs") && Catch::Contains("at least 3"));
}

TEST_CASE("the OpenCV storage reads back what it wrote, in YAML and in JSON", "[calib]") {
    const Calibration k = parse_kitti_calib(kKittiFull, "kitti");
    Calibration c = k;
    c.rectified.width = 1241;
    c.rectified.height = 376;
    c.D1.at<double>(0, 0) = -0.1234567890123456789;
    c.rms = 0.3333333333333333;
    c.per_view_errors = {{0.1, 0.2}, {1.0 / 3.0, 2.0 / 7.0}};
    c.view_names = {"left01.jpg + right01.jpg", "a b"};
    c.sigma1 = {0.5, 0.25, 1.0 / 3.0, 0.125};
    c.sigma2 = {1, 2, 3, 4};
    for (const bool json : {false, true}) {
        const fs::path p = fs::temp_directory_path() / (json ? "hc_calib_test.json" : "hc_calib_test.yml");
        std::ofstream(p) << to_opencv_storage(c, json);
        const Calibration r = read_opencv_storage(p);
        fs::remove(p);
        CHECK(image_size(r) == image_size(c));
        for (const auto& [a, b] : {std::pair{&r.K1, &c.K1}, {&r.D1, &c.D1}, {&r.K2, &c.K2}, {&r.D2, &c.D2},
                                   {&r.R, &c.R}, {&r.T, &c.T}, {&r.R1, &c.R1}, {&r.R2, &c.R2},
                                   {&r.Q, &c.Q}})
            CHECK(bit_equal(*a, *b));
        for (const Side side : {Side::left, Side::right})
            CHECK(bit_equal(projection(r.rectified, side), projection(c.rectified, side)));
        CHECK(r.rms == c.rms);
        CHECK(r.per_view_errors == c.per_view_errors);
        CHECK(r.view_names == c.view_names);
        CHECK(r.sigma1 == c.sigma1);
        CHECK(r.sigma2 == c.sigma2);
        CHECK(r.rectified_input);
    }
    CHECK_THROWS_WITH(read_opencv_storage("no/such/calib.yml"), Catch::Contains("no/such/calib.yml"));
    const fs::path bad = fs::temp_directory_path() / "hc_calib_test_bad.yml";
    std::ofstream(bad) << "%YAML:1.0\n---\nimage_width: 640\n";
    CHECK_THROWS_WITH(read_opencv_storage(bad), Catch::Contains("hc_calib_test_bad.yml"));
    fs::remove(bad);
}

namespace {

// A 9x6-inner-corner chessboard (10 x 7 squares of `square` px) on a white image of `size`.
cv::Mat chessboard_image(cv::Size size, int square) {
    cv::Mat img(size, CV_8U, cv::Scalar(255));
    const int x0 = (size.width - 10 * square) / 2, y0 = (size.height - 7 * square) / 2;
    for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 10; ++c)
            if ((r + c) % 2 == 0)
                cv::rectangle(img, cv::Rect(x0 + c * square, y0 + r * square, square, square), cv::Scalar(0), cv::FILLED);
    return img;
}

}  // namespace

TEST_CASE("a skipped pair sets no image size, a used pair of another size is refused naming both", "[calib]") {
    const fs::path dir = fs::temp_directory_path() / "hc_calib_size_test";
    fs::create_directories(dir);
    // sorted as a glob would: the board-less pair of another size comes first (opencv-doc's
    // left.jpg / right.jpg are 612x459 before the 640x480 left01.jpg ...)
    cv::imwrite((dir / "a_blank.png").string(), cv::Mat(459, 612, CV_8U, cv::Scalar(128)));
    cv::imwrite((dir / "b_board.png").string(), chessboard_image({640, 480}, 40));
    cv::imwrite((dir / "c_board.png").string(), chessboard_image({800, 600}, 50));
    const Board board = parse_board("9x6", 1);
    const Detection d = detect_boards({dir / "a_blank.png", dir / "b_board.png"},
                                      {dir / "a_blank.png", dir / "b_board.png"}, board, DetectOptions{1, 0});
    REQUIRE(d.views.size() == 1);
    CHECK(d.views[0].name == "b_board.png + b_board.png");
    CHECK(d.skipped == std::vector<std::string>{"a_blank.png + a_blank.png: 9x6 board not found in both images"});
    CHECK(d.image_size == cv::Size(640, 480));
    CHECK_THROWS_WITH(detect_boards({dir / "b_board.png", dir / "c_board.png"},
                                    {dir / "b_board.png", dir / "c_board.png"}, board, DetectOptions{1, 0}),
                      Catch::Contains("c_board.png' is 800x600") &&
                          Catch::Contains("the first pair used (b_board.png + b_board.png) is 640x480"));
    fs::remove_all(dir);
}

TEST_CASE("pairs without a board are skipped by name, and too few pairs are refused", "[calib]") {
    const fs::path dir = fs::temp_directory_path() / "hc_calib_blank_test";
    fs::create_directories(dir);
    const cv::Mat blank(480, 640, CV_8U, cv::Scalar(128));
    cv::imwrite((dir / "l.png").string(), blank);
    cv::imwrite((dir / "r.png").string(), blank);
    cv::imwrite((dir / "small.png").string(), cv::Mat(240, 320, CV_8U, cv::Scalar(0)));
    const Board board = parse_board("9x6", 1);
    std::vector<std::string> warnings;
    const auto warn = [&](const std::string& s) { warnings.push_back(s); };
    const Detection d = detect_boards({dir / "l.png"}, {dir / "r.png"}, board, DetectOptions{0, 0}, warn);
    CHECK(d.views.empty());
    REQUIRE(d.skipped.size() == 1);
    CHECK(d.skipped[0] == "l.png + r.png: 9x6 board not found in both images");
    CHECK(warnings == std::vector<std::string>{"warning: skipping l.png + r.png: 9x6 board not found in both images"});
    CHECK_THROWS_WITH(detect_boards({dir / "l.png"}, {dir / "r.png"}, board, DetectOptions{1, 0}),
                      Catch::Contains("0 of 1 pairs") && Catch::Contains("l.png + r.png"));
    CHECK_THROWS_WITH(detect_boards({dir / "l.png"}, {dir / "small.png"}, board, DetectOptions{0, 0}),
                      Catch::Contains("small.png") && Catch::Contains("320x240"));
    CHECK_THROWS_WITH(detect_boards({dir / "l.png"}, {dir / "missing.png"}, board, DetectOptions{0, 0}),
                      Catch::Contains("missing.png"));
    CHECK_THROWS_WITH(detect_boards({dir / "l.png", dir / "l.png"}, {dir / "r.png"}, board, DetectOptions{0, 0}),
                      Catch::Contains("2 left images but 1 right"));
    CHECK_THROWS_AS(calibrate(d, board), hc::InputError);
    fs::remove_all(dir);
}
