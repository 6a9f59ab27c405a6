// sources.cpp: the frame sources of every command that reads images (frames.hpp: FrameSource):
// image files, glob patterns, folders, a video file, a KITTI sequence or a synthetic pattern,
// opened as a FrameFeed that reads each frame when the run reaches it.
#include <glob.h>

#include <algorithm>
#include <cctype>
#include <mutex>
#include <set>

#include <fmt/format.h>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "io/frames/frames.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/harris_pkg.hpp"

namespace fs = std::filesystem;

namespace hc::frames {

namespace {

std::string lower_extension(const fs::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
}

/// Files, glob patterns and folders as a list of paths; `check_files`: a plain name must be
/// an existing file (else its loader names it when it is read).
std::vector<fs::path> expand(const std::vector<std::string>& items, const std::string& what, bool check_files) {
    std::vector<fs::path> out;
    for (const auto& item : items) {
        if (fs::is_directory(item)) {
            const auto found = image_files_in(item);
            if (found.empty())
                throw InputError(what + ": folder '" + item + "' holds no image file (.png, .pgm, .jpg, .bmp, .tif, ...)");
            out.insert(out.end(), found.begin(), found.end());
        } else if (item.find_first_of("*?[") != std::string::npos) {
            glob_t g{};
            const int rc = ::glob(item.c_str(), 0, nullptr, &g);
            std::vector<fs::path> found;
            if (rc == 0)
                for (size_t i = 0; i < g.gl_pathc; ++i) found.emplace_back(g.gl_pathv[i]);
            ::globfree(&g);
            if (found.empty()) throw InputError(what + ": pattern '" + item + "' matches no file");
            std::sort(found.begin(), found.end());
            out.insert(out.end(), found.begin(), found.end());
        } else {
            if (check_files && !fs::is_regular_file(item)) throw InputError(what + ": no such image file '" + item + "'");
            out.emplace_back(item);
        }
    }
    if (out.empty()) throw InputError(what + ": no image given");
    return out;
}

/// A video read in order, shared by the feed's loading threads: asking for an earlier frame
/// than the last one read opens the file again.
class VideoReader {
public:
    explicit VideoReader(fs::path file) : file_(std::move(file)) { open(); }
    /// Frames in the file (counted by reading through it when the container does not say).
    int count() {
        const std::lock_guard<std::mutex> lock(mu_);
        const double stated = cap_.get(cv::CAP_PROP_FRAME_COUNT);
        if (stated >= 1) return static_cast<int>(stated);
        int n = 0;
        while (cap_.grab()) ++n;
        open();
        return n;
    }
    Image frame(int k) {
        const std::lock_guard<std::mutex> lock(mu_);
        if (k < next_) open();
        for (; next_ < k; ++next_)
            if (!cap_.grab()) throw ended(k);
        cv::Mat m;
        if (!cap_.read(m) || m.empty()) throw ended(k);
        ++next_;
        if (m.depth() != CV_8U) throw InputError("video '" + file_.string() + "' is not 8-bit");
        return image_of(m);
    }

private:
    void open() {
        cap_.release();
        // OpenCV logs each back end it tries on a file it cannot read; the error below names it once
        const auto level = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
        const bool opened = cap_.open(file_.string()) && cap_.isOpened();
        cv::utils::logging::setLogLevel(level);
        if (!opened)
            throw InputError("video '" + file_.string() + "' cannot be opened (missing, corrupt or not a video OpenCV reads)");
        next_ = 0;
    }
    InputError ended(int k) const {
        return InputError("video '" + file_.string() + "' ends before frame " + std::to_string(k) + " it said it has");
    }
    fs::path file_;
    std::mutex mu_;
    cv::VideoCapture cap_;
    int next_ = 0;
};

/// How many frames of `available` a run takes: --frames N, or all.
std::size_t first_n(int frames, std::size_t available, const std::string& what) {
    if (frames <= 0) return available;
    if (static_cast<std::size_t>(frames) > available)
        throw InputError("--frames " + std::to_string(frames) + " but only " + std::to_string(available) + " " + what);
    return static_cast<std::size_t>(frames);
}

std::vector<int> pairs_of(std::size_t n) {
    std::vector<int> v(n);
    for (std::size_t k = 0; k < n; ++k) v[k] = static_cast<int>(k / 2);
    return v;
}

FrameFeed image_feed(const FrameSource& o, int cw, int ch) {
    if (o.images.size() == 1 && fs::is_regular_file(o.images[0]) && is_video_file(o.images[0])) {
        const fs::path file = o.images[0];
        auto video = std::make_shared<VideoReader>(file);
        const std::size_t n = first_n(o.frames, static_cast<std::size_t>(video->count()), "frames in video '" + file.string() + "'");
        if (n == 0) throw InputError("video '" + file.string() + "' has no frame");
        std::vector<std::string> names;
        for (std::size_t k = 0; k < n; ++k) names.push_back(file.string() + "#" + std::to_string(k));
        return FrameFeed(std::move(names), pairs_of(n), std::to_string(n) + " frame(s) of video '" + file.string() + "'",
                         [video, file, cw, ch](int k) {
                             return crop(video->frame(k), cw, ch, "video '" + file.string() + "'");
                         });
    }
    for (const auto& item : o.images)
        if (is_video_file(item) && fs::is_regular_file(item))
            throw InputError("video '" + item + "' is a stream of its own: give it alone, not with other images");
    const auto paths = expand(o.images, "images", false);
    const std::size_t n = first_n(o.frames, paths.size(), "images given");
    std::vector<std::string> names(paths.begin(), paths.begin() + static_cast<long>(n));
    return FrameFeed(names, pairs_of(n), std::to_string(n) + " image(s)", [names, cw, ch](int k) {
        const std::string& f = names[static_cast<std::size_t>(k)];
        return crop(load_image(f), cw, ch, "image '" + f + "'");
    });
}

FrameFeed kitti_feed(const fs::path& root, const FrameSource& o, int cw, int ch, int min_pairs) {
    return open_kitti_feed(root, o.sequence, pair_range(o), pairs_flag(o), min_pairs, {o.frames, cw, ch});
}

/// Frames [0, n) of a stream of paths (names `names`, stereo pairs from `first_pair`), each
/// loaded and cropped when reached.
FrameFeed stereo_path_feed(std::vector<fs::path> paths, std::vector<std::string> names, int first_pair, int cw, int ch) {
    std::vector<int> pairs;
    for (std::size_t i = 0; i < names.size(); ++i) pairs.push_back(first_pair + static_cast<int>(i / 2));
    return FrameFeed(std::move(names), std::move(pairs), "", [paths = std::move(paths), cw, ch](int i) {
        const fs::path& f = paths[static_cast<std::size_t>(i)];
        return crop(load_image(f), cw, ch, "KITTI frame '" + f.string() + "'");
    });
}

bool all_digits(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

Image image_of(const cv::Mat& m) {
    cv::Mat g;
    if (m.channels() == 3) cv::cvtColor(m, g, cv::COLOR_BGR2GRAY);
    else if (m.channels() == 4) cv::cvtColor(m, g, cv::COLOR_BGRA2GRAY);
    else g = m;
    Image im(g.cols, g.rows);
    for (int r = 0; r < g.rows; ++r) std::copy_n(g.ptr<std::uint8_t>(r), g.cols, &im.at(r, 0));
    return im;
}

std::vector<fs::path> image_files_in(const fs::path& dir) {
    static const std::set<std::string> ext{".png", ".pgm", ".ppm", ".pbm", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp"};
    std::vector<fs::path> v;
    if (!fs::is_directory(dir)) return v;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file() && ext.count(lower_extension(e.path()))) v.push_back(e.path());
    std::sort(v.begin(), v.end());
    return v;
}

std::vector<std::string> parse_sequences(const std::string& s) {
    const auto bad = [&](const std::string& why) {
        return InputError("--sequences '" + s + "': " + why + " (give a range like 00-21 or a list like 00,01,05)");
    };
    std::vector<std::string> out;
    const auto dash = s.find('-');
    if (dash != std::string::npos) {
        const std::string a = s.substr(0, dash), b = s.substr(dash + 1);
        if (!all_digits(a) || !all_digits(b) || a.size() != b.size()) throw bad("not a range of sequence numbers");
        const int x = std::stoi(a), y = std::stoi(b);
        if (x > y) throw bad("the range is empty");
        for (int k = x; k <= y; ++k) out.push_back(std::string(a.size() - std::min(a.size(), std::to_string(k).size()), '0') + std::to_string(k));
        return out;
    }
    for (const auto& t : util::split_csv(s)) {
        if (!all_digits(t)) throw bad("'" + t + "' is not a sequence number");
        if (std::find(out.begin(), out.end(), t) != out.end()) throw bad("'" + t + "' is listed twice");
        out.push_back(t);
    }
    if (out.empty()) throw bad("no sequence");
    return out;
}

std::string pairs_flag(const FrameSource& o) {
    return "--pairs " + (o.pairs.empty() ? std::string("(all)") : o.pairs);
}

util::Range pair_range(const FrameSource& o) {
    return o.pairs.empty() ? util::Range{0, 1 << 30} : util::parse_range(o.pairs, "--pairs");
}

util::Range job_pair_range(const FrameSource& o) {
    if (o.frames > 0)
        throw InputError("--frames " + std::to_string(o.frames) +
                         " counts the frames of one stream; --sequences and sharded runs take stereo pairs: give --pairs a:b");
    return pair_range(o);
}

bool is_video_file(const fs::path& p) {
    static const std::set<std::string> ext{".avi", ".mp4", ".mkv", ".mov", ".mpg", ".mpeg", ".webm", ".m4v", ".wmv", ".ogv"};
    return ext.count(lower_extension(p)) > 0;
}

std::vector<fs::path> expand_image_list(const std::vector<std::string>& items, const std::string& what) {
    return expand(items, what, true);
}

RigPairs open_rig(const RigSource& r) {
    if (r.calib.empty()) throw InputError("--left and --right are the images of a rig: give its --calib");
    if (r.left.empty() || r.right.empty()) throw InputError("--calib needs the rig's images: --left and --right");
    RigPairs p{r.calib, expand_image_list(r.left, "--left"), expand_image_list(r.right, "--right")};
    if (p.left.size() != p.right.size())
        throw InputError("a rig's stereo pairs: " + std::to_string(p.left.size()) + " left images but " +
                         std::to_string(p.right.size()) + " right images (--left, --right)");
    return p;
}

FrameFeed open_kitti_feed(const fs::path& kitti_dir, const std::string& sequence, util::Range r, const std::string& what,
                          int min_pairs, const FeedCut& cut) {
    const KittiSequence k = open_kitti(kitti_dir, sequence);
    const auto paths = stereo_stream(k, r, what);
    const std::size_t n = first_n(cut.frames, paths.size(), "frames in " + what + " of KITTI sequence " + sequence);
    const int spanned = static_cast<int>((n + 1) / 2);
    if (spanned < min_pairs)
        throw InputError(what + (cut.frames > 0 ? " --frames " + std::to_string(cut.frames) : std::string()) + " gives " +
                         std::to_string(spanned) + " stereo pair(s) of KITTI sequence '" + k.root.string() +
                         "'; at least " + std::to_string(min_pairs) + " are needed");
    std::vector<std::string> names;
    for (std::size_t i = 0; i < n; ++i) names.push_back(sequence + "/" + (i % 2 ? "R" : "L") + paths[i].stem().string());
    FrameFeed feed = stereo_path_feed({paths.begin(), paths.begin() + static_cast<long>(n)}, std::move(names), r.first,
                                      cut.width, cut.height);
    feed.describe("KITTI sequence " + sequence + " (" + k.root.string() + "), stereo pairs " + std::to_string(r.first) +
                  ".." + std::to_string(r.first + spanned - 1) + ": " + std::to_string(n) + " frames " +
                  std::to_string(feed.width()) + "x" + std::to_string(feed.height()) +
                  (cut.width > 0 ? " (centre crop)" : ""));
    return feed;
}

FrameFeed default_stereo_feed(util::Range r, int frames) {
    const std::string video = HC_OPENCV_SAMPLE_VIDEO;
    constexpr int kPairs = 12, kWidth = 640, kHeight = 360;
    const int last = std::min(r.last, kPairs);
    if (last - r.first <= 0) throw InputError("--pairs selects no pair of the default 12-pair stream");
    Stream s;
    cv::VideoCapture cap;
    if (!video.empty() && fs::exists(video) && cap.open(video)) {
        cv::Mat f;
        for (int k = 0; k < 2 * last && cap.read(f); ++k) {
            if (k < 2 * r.first) continue;
            s.frames.push_back(crop(image_of(f), kWidth, kHeight, video));
            s.names.push_back(fmt::format("vtest/{}{:03}", k % 2 ? 'R' : 'L', k / 2));
            s.pair_index.push_back(k / 2);
        }
        s.description = fmt::format("default stream: {} frame pairs of {} (grey, {}x{} centre crop); no KITTI data found",
                                    s.frames.size() / 2, video, kWidth, kHeight);
    }
    if (s.frames.size() < 4) {
        s = {};
        for (int k = 2 * r.first; k < 2 * last; ++k) {
            s.frames.push_back(make_pattern(Pattern::blocks, kWidth, kHeight, k));
            s.names.push_back(fmt::format("blocks/{}{:03}", k % 2 ? 'R' : 'L', k / 2));
            s.pair_index.push_back(k / 2);
        }
        s.description = fmt::format("default stream: generated 'blocks' pattern {}x{} (no KITTI data, no opencv-doc video)",
                                    kWidth, kHeight);
    }
    const std::size_t n = first_n(frames, s.frames.size(), "frames in the default stream");
    s.frames.resize(n);
    s.names.resize(n);
    s.pair_index.resize(n);
    auto held = std::make_shared<const Stream>(std::move(s));
    return FrameFeed(held->names, held->pair_index, held->description, [held](int k) {
        return held->frames[static_cast<std::size_t>(k)];
    });
}

FrameFeed open_feed(const FrameSource& o, WhenNone none, int min_pairs) {
    const int sources = (!o.images.empty()) + (!o.pattern.empty()) + (!o.kitti.empty() || !o.pairs.empty());
    if (sources > 1) throw InputError("choose one frame source: image files, --pattern, or --kitti/--pairs");
    int cw = 0, ch = 0;
    if (!o.size.empty()) std::tie(cw, ch) = util::parse_size(o.size);
    if (!o.images.empty()) return image_feed(o, cw, ch);
    if (o.pattern.empty()) {
        if (!o.kitti.empty() || (!o.pairs.empty() && none == WhenNone::pattern))
            return kitti_feed(require_kitti_root(o.kitti, o.data, "a KITTI stream needs KITTI data"), o, cw, ch, min_pairs);
        if (none == WhenNone::stereo) {
            const fs::path root = kitti_root(o.kitti, o.data);
            if (!root.empty()) return kitti_feed(root, o, cw, ch, min_pairs);
            return default_stereo_feed(pair_range(o),
                                       o.frames);
        }
    }
    const Pattern p = parse_pattern(o.pattern.empty() ? "blocks" : o.pattern);
    const int w = cw > 0 ? cw : 64, h = ch > 0 ? ch : 36;
    const int n = o.frames > 0 ? o.frames : 3;
    std::vector<std::string> names;
    for (int k = 0; k < n; ++k) names.push_back(pattern_name(p) + "#" + std::to_string(k));
    const std::uint32_t seed = o.seed;
    return FrameFeed(std::move(names), pairs_of(static_cast<std::size_t>(n)),
                     std::to_string(n) + " synthetic '" + pattern_name(p) + "' frame(s)",
                     [p, w, h, seed](int k) { return make_pattern(p, w, h, k, seed); });
}

LoadedFrames load_frames(const FrameSource& o) {
    FrameFeed feed = open_feed(o);
    LoadedFrames out;
    out.names = feed.names();
    out.description = feed.description();
    for (int k = 0; k < feed.size(); ++k) {
        out.frames.push_back(*feed.frame(k));
        feed.release_below(k + 1);
    }
    const Geometry g{feed.width(), feed.height()};
    try {
        g.validate();
    } catch (const std::invalid_argument& e) {
        throw InputError("'" + out.names[0] + "': " + e.what());
    }
    try {   // the host driver's own checks (e.g. chaining), before any simulator starts
        HostDriver check(g, pointers(out.frames));
    } catch (const std::invalid_argument& e) {
        throw InputError(out.description + ": " + e.what());
    }
    return out;
}

}  // namespace hc::frames
