#include "frame_source.hpp"

#include <filesystem>

#include "frames.hpp"
#include "harris/harris_pkg.hpp"

namespace hc::tools {

namespace fs = std::filesystem;

void add_frame_source_options(CLI::App* cmd, FrameSourceOptions& o) {
    cmd->add_option("images", o.images, "8-bit image files streamed as chained frames, in order");
    cmd->add_option("--pattern", o.pattern, "synthetic frames: flat, checkerboard, random, extremes, blocks");
    cmd->add_option("--size", o.size, "WxH: size of synthetic frames, or a centred crop of images/KITTI frames");
    cmd->add_option("--frames", o.frames, "number of chained frames (patterns: default 3; images/KITTI: the first N)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--kitti", o.kitti, "KITTI odometry root (holds sequences/NN); default <data>/kitti");
    cmd->add_option("--sequence", o.sequence, "KITTI sequence (with --kitti or --pairs)")->capture_default_str();
    cmd->add_option("--pairs", o.pairs, "a:b stereo pairs of the KITTI sequence, streamed L R L R ...");
    cmd->add_option("--data", o.data, "data directory (default $HARRIS_COSIM_DATA, else ../shared/data)");
    cmd->add_option("--seed", o.seed, "seed of random patterns")->capture_default_str();
}

std::pair<int, int> parse_size(const std::string& s) {
    const auto x = s.find('x');
    try {
        if (x == std::string::npos) throw std::invalid_argument("no x");
        size_t a = 0, b = 0;
        const int w = std::stoi(s.substr(0, x), &a);
        const int h = std::stoi(s.substr(x + 1), &b);
        if (a != x || b != s.size() - x - 1 || w <= 0 || h <= 0) throw std::invalid_argument("bad");
        return {w, h};
    } catch (const std::exception&) {
        throw InputError("--size '" + s + "' is not WIDTHxHEIGHT (e.g. 1241x376)");
    }
}

namespace {
std::pair<int, int> parse_range(const std::string& s) {
    const auto c = s.find(':');
    try {
        if (c == std::string::npos) throw std::invalid_argument("no colon");
        const int a = std::stoi(s.substr(0, c));
        const int b = std::stoi(s.substr(c + 1));
        if (a < 0 || b <= a) throw std::invalid_argument("empty");
        return {a, b};
    } catch (const std::exception&) {
        throw InputError("--pairs '" + s + "' is not FIRST:LAST with FIRST < LAST (LAST excluded)");
    }
}
}  // namespace

LoadedFrames load_frames(const FrameSourceOptions& o) {
    LoadedFrames out;
    const int sources = (!o.images.empty()) + (!o.pattern.empty()) + (!o.kitti.empty() || !o.pairs.empty());
    if (sources > 1) throw InputError("choose one frame source: image files, --pattern, or --kitti/--pairs");
    int cw = 0, ch = 0;
    if (!o.size.empty()) std::tie(cw, ch) = parse_size(o.size);

    if (!o.images.empty()) {
        const size_t n = o.frames > 0 ? static_cast<size_t>(o.frames) : o.images.size();
        if (n > o.images.size())
            throw InputError("--frames " + std::to_string(n) + " but only " + std::to_string(o.images.size()) +
                             " images given");
        for (size_t k = 0; k < n; ++k) {
            out.frames.push_back(crop(load_image(o.images[k]), cw, ch, "image '" + o.images[k] + "'"));
            out.names.push_back(o.images[k]);
        }
        out.description = std::to_string(n) + " image(s)";
    } else if (!o.kitti.empty() || !o.pairs.empty()) {
        fs::path root;
        if (!o.kitti.empty()) root = o.kitti;
        else {
            const auto d = data_dir(o.data);
            if (!d) throw InputError("no data directory: give --kitti DIR, --data DIR or set HARRIS_COSIM_DATA");
            root = *d / "kitti";
        }
        const KittiSequence seq = open_kitti(root, o.sequence);
        auto [a, b] = o.pairs.empty() ? std::pair<int, int>{0, 1 << 30} : parse_range(o.pairs);
        const auto paths = stereo_stream(seq, a, b);
        if (paths.empty()) throw InputError("KITTI sequence " + o.sequence + " has no stereo pair in " + o.pairs);
        const size_t n = o.frames > 0 ? std::min<size_t>(static_cast<size_t>(o.frames), paths.size()) : paths.size();
        for (size_t k = 0; k < n; ++k) {
            out.frames.push_back(crop(load_image(paths[k]), cw, ch, "KITTI frame '" + paths[k].string() + "'"));
            out.names.push_back(paths[k].string());
        }
        out.description = "KITTI " + o.sequence + ", " + std::to_string(n) + " frame(s) (L R L R ...)";
    } else {
        const Pattern p = parse_pattern(o.pattern.empty() ? "blocks" : o.pattern);
        const int w = cw > 0 ? cw : 64, h = ch > 0 ? ch : 36;
        const int n = o.frames > 0 ? o.frames : 3;
        for (int k = 0; k < n; ++k) {
            out.frames.push_back(make_pattern(p, w, h, k, o.seed));
            out.names.push_back(pattern_name(p) + "#" + std::to_string(k));
        }
        out.description = std::to_string(n) + " synthetic '" + pattern_name(p) + "' frame(s)";
    }
    const Image& f0 = out.frames.front();
    for (size_t k = 1; k < out.frames.size(); ++k)
        if (out.frames[k].width != f0.width || out.frames[k].height != f0.height)
            throw InputError("frame '" + out.names[k] + "' is " + std::to_string(out.frames[k].width) + "x" +
                             std::to_string(out.frames[k].height) + " but '" + out.names[0] + "' is " +
                             std::to_string(f0.width) + "x" + std::to_string(f0.height) +
                             "; a stream has one size");
    try {
        Geometry{f0.width, f0.height}.validate();
    } catch (const std::invalid_argument& e) {
        throw InputError("'" + out.names[0] + "': " + e.what());
    }
    return out;
}

}  // namespace hc::tools
