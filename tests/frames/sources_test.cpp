// sources_test: the frame sources every command that streams images shares
// (io/frames/sources.cpp): files, glob patterns, folders, a video file and a synthetic
// pattern, opened as a feed or loaded at once, with errors that name the input.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "io/frames/frames.hpp"
#include "model/util/errors.hpp"
#include "model/util/util.hpp"

using namespace hc;
namespace fs = std::filesystem;

namespace {

fs::path sources_scratch(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("hc-sources-test-" + std::to_string(::getpid())) / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

cv::Mat mat_of(const Image& im) {
    cv::Mat m(im.height, im.width, CV_8UC1);
    for (int r = 0; r < im.height; ++r)
        for (int c = 0; c < im.width; ++c) m.at<std::uint8_t>(r, c) = im.at(r, c);
    return m;
}

/// `n` frames of the blocks pattern as frame_K.png in `dir` (written in reverse order, so
/// that only a sort puts them in order).
std::vector<Image> write_frames(const fs::path& dir, int n, int w = 64, int h = 48) {
    std::vector<Image> v;
    for (int k = 0; k < n; ++k) v.push_back(make_pattern(Pattern::blocks, w, h, k));
    for (int k = n - 1; k >= 0; --k) cv::imwrite((dir / ("frame_" + std::to_string(k) + ".png")).string(), mat_of(v[k]));
    return v;
}

bool same(const Image& a, const Image& b) {
    return a == b;
}

double mean_abs_difference(const Image& a, const Image& b) {
    double s = 0;
    for (int r = 0; r < a.height; ++r)
        for (int c = 0; c < a.width; ++c) s += std::abs(int(a.at(r, c)) - int(b.at(r, c)));
    return s / (double(a.width) * a.height);
}

}  // namespace

TEST_CASE("a folder, a glob and the listed files are the same frames in name order", "[frames]") {
    const fs::path dir = sources_scratch("folder");
    const auto want = write_frames(dir, 4);
    const auto files = frames::expand_image_list({dir.string()}, "images");
    REQUIRE(files.size() == 4);
    CHECK(files[0].filename() == "frame_0.png");
    CHECK(files[3].filename() == "frame_3.png");
    CHECK(frames::expand_image_list({(dir / "frame_*.png").string()}, "images") == files);

    frames::FrameSource by_folder, by_files;
    by_folder.images = {dir.string()};
    for (const auto& f : files) by_files.images.push_back(f.string());
    const auto a = frames::load_frames(by_folder), b = frames::load_frames(by_files);
    REQUIRE(a.frames.size() == 4);
    CHECK(a.names == b.names);
    CHECK(a.description == "4 image(s)");
    for (int k = 0; k < 4; ++k) CHECK(same(a.frames[k], want[k]));

    frames::FrameFeed feed = frames::open_feed(by_folder);
    CHECK(feed.pair_index() == std::vector<int>{0, 0, 1, 1});
    CHECK(same(*feed.frame(2), want[2]));
}

TEST_CASE("the first N images make the stream with --frames N, and more than there are is bad input naming the count", "[frames]") {
    const fs::path dir = sources_scratch("first-n");
    write_frames(dir, 4);
    frames::FrameSource s;
    s.images = {dir.string()};
    s.frames = 2;
    CHECK(frames::load_frames(s).frames.size() == 2);
    s.frames = 5;
    CHECK_THROWS_WITH(frames::load_frames(s), "--frames 5 but only 4 images given");
}

TEST_CASE("a missing file, an empty glob and a folder without images are bad input naming them", "[frames]") {
    const fs::path dir = sources_scratch("bad");
    CHECK_THROWS_WITH(frames::expand_image_list({(dir / "none.png").string()}, "--left"),
                      "--left: no such image file '" + (dir / "none.png").string() + "'");
    CHECK_THROWS_WITH(frames::expand_image_list({(dir / "*.png").string()}, "--right"),
                      "--right: pattern '" + (dir / "*.png").string() + "' matches no file");
    CHECK_THROWS_WITH(frames::expand_image_list({dir.string()}, "images"), Catch::Contains("holds no image file"));
    CHECK_THROWS_AS(frames::expand_image_list({}, "--left"), InputError);
}

TEST_CASE("a missing image or a pattern matching nothing is named", "[frames]") {
    CHECK_THROWS_WITH(frames::expand_image_list({"no/such/left01.jpg"}, "--left"),
                      Catch::Contains("--left") && Catch::Contains("no/such/left01.jpg"));
    CHECK_THROWS_WITH(frames::expand_image_list({"no/such/left*.jpg"}, "--right"),
                      Catch::Contains("--right") && Catch::Contains("no/such/left*.jpg"));
    CHECK_THROWS_AS(frames::expand_image_list({}, "--left"), InputError);
}

TEST_CASE("a rig's flags open as its calibration and its pairs in order, or are bad input naming the flags", "[frames]") {
    const fs::path dir = sources_scratch("rig");
    const auto frames_written = write_frames(dir, 4);
    REQUIRE(frames_written.size() == 4);
    frames::RigSource r;
    CHECK_FALSE(r.given());
    r.calib = (dir / "calib.yml").string();
    CHECK(r.given());
    CHECK_THROWS_WITH(frames::open_rig(r), "--calib needs the rig's images: --left and --right");
    r.left = {(dir / "frame_[02].png").string()};
    CHECK_THROWS_WITH(frames::open_rig(r), "--calib needs the rig's images: --left and --right");
    r.right = {(dir / "frame_[13].png").string()};
    const frames::RigPairs p = frames::open_rig(r);
    CHECK(p.calib == dir / "calib.yml");
    REQUIRE(p.pairs() == 2);
    CHECK(p.left == std::vector<fs::path>{dir / "frame_0.png", dir / "frame_2.png"});
    CHECK(p.right == std::vector<fs::path>{dir / "frame_1.png", dir / "frame_3.png"});
    r.right = {dir.string()};
    CHECK_THROWS_WITH(frames::open_rig(r), "a rig's stereo pairs: 2 left images but 4 right images (--left, --right)");
    r.right = {(dir / "none_*.png").string()};
    CHECK_THROWS_WITH(frames::open_rig(r), Catch::Contains("--right: pattern"));
    r.calib.clear();
    CHECK(r.given());
    CHECK_THROWS_WITH(frames::open_rig(r), "--left and --right are the images of a rig: give its --calib");
}

TEST_CASE("a glob pattern expands to its files in sorted order", "[frames]") {
    const fs::path dir = fs::temp_directory_path() / "hc_frames_glob_test";
    fs::create_directories(dir);
    for (const char* n : {"b02.png", "b01.png", "a.png"}) std::ofstream(dir / n) << "x";
    const auto v = frames::expand_image_list({(dir / "b*.png").string(), (dir / "a.png").string()}, "--left");
    REQUIRE(v.size() == 3);
    CHECK(v[0].filename() == "b01.png");
    CHECK(v[1].filename() == "b02.png");
    CHECK(v[2].filename() == "a.png");
    fs::remove_all(dir);
}

TEST_CASE("a video file streams its frames in order, grey, cropped like images", "[frames]") {
    const fs::path dir = sources_scratch("video");
    const fs::path file = dir / "clip.avi";
    std::vector<Image> want;
    {
        cv::VideoWriter w(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(64, 48), false);
        REQUIRE(w.isOpened());
        for (int k = 0; k < 5; ++k) {
            want.push_back(make_pattern(Pattern::blocks, 64, 48, k));
            w.write(mat_of(want.back()));
        }
    }
    CHECK(frames::is_video_file(file));
    frames::FrameSource s;
    s.images = {file.string()};
    frames::FrameFeed feed = frames::open_feed(s);
    REQUIRE(feed.size() == 5);
    CHECK(feed.names()[4] == file.string() + "#4");
    // MJPEG is lossy: each frame is its own pattern frame, up to compression noise, and
    // clearly not its neighbour; read out of order (the reader opens the file again)
    for (int k : {3, 1, 4, 0}) {
        const auto im = feed.frame(k);
        CHECK(mean_abs_difference(*im, want[k]) < 4.0);
        CHECK(mean_abs_difference(*im, want[(k + 1) % 5]) > 4 * mean_abs_difference(*im, want[k]));
    }
    s.frames = 3;
    s.size = "32x24";
    const auto lf = frames::load_frames(s);
    REQUIRE(lf.frames.size() == 3);
    CHECK(lf.frames[0].width == 32);
    CHECK(lf.description == "3 frame(s) of video '" + file.string() + "'");

    s.images.push_back(file.string());
    CHECK_THROWS_WITH(frames::open_feed(s), Catch::Contains("is a stream of its own"));
    const fs::path corrupt = dir / "corrupt.avi";
    util::write_file_atomic(corrupt, std::string(4096, 'x'));
    s.images = {corrupt.string()};
    CHECK_THROWS_WITH(frames::open_feed(s), Catch::Contains("corrupt.avi") && Catch::Contains("cannot be opened"));
}

TEST_CASE("a pattern feed is the pattern's frames, each made when reached", "[frames]") {
    frames::FrameSource s;
    s.pattern = "random";
    s.size = "40x30";
    s.frames = 4;
    s.seed = 7;
    frames::FrameFeed feed = frames::open_feed(s);
    REQUIRE(feed.size() == 4);
    CHECK(same(*feed.frame(3), make_pattern(Pattern::random, 40, 30, 3, 7)));
    CHECK(feed.loads() == 2);   // frame 0 for the size, then frame 3
}

TEST_CASE("KITTI sequence lists are ranges or lists of two-digit names", "[frames]") {
    CHECK(frames::parse_sequences("00-03") == std::vector<std::string>{"00", "01", "02", "03"});
    CHECK(frames::parse_sequences("00,01,05") == std::vector<std::string>{"00", "01", "05"});
    CHECK_THROWS_AS(frames::parse_sequences("03-01"), InputError);
    CHECK_THROWS_AS(frames::parse_sequences("0a"), InputError);
    CHECK_THROWS_AS(frames::parse_sequences("01,01"), InputError);
}

namespace {

/// A KITTI stand-in of `pairs` stereo pairs of the blocks pattern (64x48) under `root`.
void write_kitti_standin(const fs::path& root, int pairs) {
    for (const char* side : {"image_0", "image_1"}) {
        const fs::path d = root / "sequences" / "00" / side;
        fs::create_directories(d);
        for (int k = 0; k < pairs; ++k) {
            char name[16];
            std::snprintf(name, sizeof name, "%06d.png", k);
            cv::imwrite((d / name).string(), mat_of(make_pattern(Pattern::blocks, 64, 48, 2 * k + (side[6] == '1'))));
        }
    }
}

}  // namespace

TEST_CASE("a frame count (--frames N) and a pair range (--pairs a:b) pick the same frames whatever a command streams when none is named",
          "[frames]") {
    const fs::path root = sources_scratch("kitti-standin");
    write_kitti_standin(root, 3);
    const fs::path empty = sources_scratch("no-data");
    for (const frames::WhenNone none : {frames::WhenNone::pattern, frames::WhenNone::stereo}) {
        CAPTURE(static_cast<int>(none));
        frames::FrameSource s;
        s.kitti = root.string();
        s.sequence = "00";
        s.frames = 3;
        frames::FrameFeed f = frames::open_feed(s, none);
        CHECK(f.names() == std::vector<std::string>{"00/L000000", "00/R000000", "00/L000001"});
        CHECK(f.pair_index() == std::vector<int>{0, 0, 1});
        CHECK(*f.frame(2) == make_pattern(Pattern::blocks, 64, 48, 2));
        s.pairs = "1:3";
        s.frames = 2;
        f = frames::open_feed(s, none);
        CHECK(f.names() == std::vector<std::string>{"00/L000001", "00/R000001"});
        CHECK(f.pair_index() == std::vector<int>{1, 1});
        s.pairs.clear();
        s.frames = 7;
        CHECK_THROWS_WITH(frames::open_feed(s, none), "--frames 7 but only 6 frames in --pairs (all) of KITTI sequence 00");
        s.frames = 2;   // one stereo pair: fewer than a run that needs two pairs takes
        CHECK_THROWS_WITH(frames::open_feed(s, none, 2), Catch::Contains("--pairs (all) --frames 2 gives 1 stereo pair(s)") &&
                                                             Catch::Contains("at least 2 are needed"));
    }
    // with no source named: blocks frames for `pattern`, the default stereo stream for `stereo`
    frames::FrameSource none_named;
    none_named.data = empty.string();
    none_named.frames = 3;
    CHECK(frames::open_feed(none_named, frames::WhenNone::pattern).names() ==
          std::vector<std::string>{"blocks#0", "blocks#1", "blocks#2"});
    frames::FrameFeed d = frames::open_feed(none_named, frames::WhenNone::stereo);
    REQUIRE(d.size() == 3);
    CHECK(d.pair_index() == std::vector<int>{0, 0, 1});
    CHECK(d.width() == 640);
    CHECK(d.height() == 360);
    none_named.frames = 0;
    none_named.pairs = "2:3";
    d = frames::open_feed(none_named, frames::WhenNone::stereo);
    REQUIRE(d.size() == 2);
    CHECK(d.pair_index() == std::vector<int>{2, 2});
    CHECK(d.names()[0].substr(d.names()[0].size() - 4) == "L002");
}
