// frames.cpp: see frames.hpp.
#include "io/frames/frames.hpp"
#include "io/frames/pairs.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "model/driver/host_driver.hpp"
#include "model/harris/harris_pkg.hpp"

namespace fs = std::filesystem;

namespace hc::frames {

Image load_image(const fs::path& p) {
    if (!fs::exists(p)) throw InputError("image '" + p.string() + "' does not exist");
    if (!fs::is_regular_file(p)) throw InputError("image '" + p.string() + "' is not a file");
    cv::Mat m = cv::imread(p.string(), cv::IMREAD_UNCHANGED);
    if (m.empty()) throw InputError("image '" + p.string() + "' cannot be decoded (corrupt or not an image)");
    if (m.depth() != CV_8U)
        throw InputError("image '" + p.string() + "' is not 8-bit (depth code " + std::to_string(m.depth()) +
                         "); the co-processor takes 8-bit grey pixels");
    if (m.channels() != 1 && m.channels() != 3 && m.channels() != 4)
        throw InputError("image '" + p.string() + "' has " + std::to_string(m.channels()) + " channels");
    return image_of(m);
}

Image crop(const Image& img, int width, int height, const std::string& what) {
    const int w = width > 0 ? width : img.width;
    const int h = height > 0 ? height : img.height;
    if (w > img.width || h > img.height)
        throw InputError(what + " is " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                         ", smaller than the requested " + std::to_string(w) + "x" + std::to_string(h));
    if (w == img.width && h == img.height) return img;
    const int x0 = (img.width - w) / 2, y0 = (img.height - h) / 2;
    Image out(w, h);
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) out.at(r, c) = img.at(y0 + r, x0 + c);
    return out;
}

std::optional<fs::path> data_dir(const std::string& flag_value) {
    if (!flag_value.empty()) {
        if (!fs::is_directory(flag_value)) throw InputError("data directory '" + flag_value + "' does not exist");
        return fs::path(flag_value);
    }
    if (const char* env = std::getenv("HARRIS_COSIM_DATA"); env && *env) {
        if (!fs::is_directory(env))
            throw InputError(std::string("HARRIS_COSIM_DATA='") + env + "' is not a directory");
        return fs::path(env);
    }
#ifdef HC_DEFAULT_DATA_DIR
    if (fs::is_directory(HC_DEFAULT_DATA_DIR)) return fs::path(HC_DEFAULT_DATA_DIR);
#endif
    return std::nullopt;
}

fs::path kitti_sequences_dir(const fs::path& kitti_root) { return kitti_root / "sequences"; }

fs::path kitti_sequence_dir(const fs::path& kitti_root, const std::string& sequence) {
    return kitti_sequences_dir(kitti_root) / sequence;
}

bool is_kitti_sequence(const fs::path& kitti_root, const std::string& sequence) {
    const fs::path s = kitti_sequence_dir(kitti_root, sequence);
    return fs::is_directory(s / "image_0") && fs::is_directory(s / "image_1");
}

void check_kitti_sequences(const fs::path& kitti_root, const std::vector<std::string>& seqs) {
    std::string missing;
    for (const auto& q : seqs)
        if (!is_kitti_sequence(kitti_root, q))
            missing += (missing.empty() ? "" : ", ") + q;
    if (!missing.empty())
        throw InputError("--sequences: no KITTI sequence " + missing + " under " +
                         kitti_sequences_dir(kitti_root).string() + " (each needs image_0/ and image_1/)");
}

fs::path kitti_poses_file(const fs::path& kitti_root, const std::string& sequence) {
    return kitti_root / "poses" / (sequence + ".txt");
}

KittiSequence open_kitti(const fs::path& kitti_dir, const std::string& sequence) {
    KittiSequence s;
    s.root = kitti_sequence_dir(kitti_dir, sequence);
    if (!fs::is_directory(s.root))
        throw InputError("KITTI sequence directory '" + s.root.string() + "' does not exist");
    s.left = image_files_in(s.root / "image_0");
    s.right = image_files_in(s.root / "image_1");
    if (s.left.empty()) throw InputError("'" + (s.root / "image_0").string() + "' holds no images");
    return s;
}

util::Range pairs_within(util::Range r, int n, const std::string& what, const std::string& of, int open_end) {
    if (r.last != open_end && r.last > n)
        throw InputError(what + " reaches past the data: " + of + " has " + std::to_string(n) +
                         " stereo pairs, the last is pair " + std::to_string(n - 1) + " (a range " +
                         std::to_string(std::min(r.first, n - 1)) + ":" + std::to_string(n) + " ends there)");
    if (r.first >= n)
        throw InputError(what + " starts past the data: " + of + " has " + std::to_string(n) +
                         " stereo pairs, the last is pair " + std::to_string(n - 1));
    return {r.first, std::min(r.last, n)};
}

std::vector<fs::path> stereo_stream(const KittiSequence& s, util::Range r, const std::string& what, int open_end) {
    const int n = s.pairs();
    pairs_within(r, n, what, "KITTI sequence '" + s.root.string() + "'", open_end);
    std::vector<fs::path> out;
    for (int k = r.first; k < std::min(r.last, n); ++k) {
        out.push_back(s.left[k]);
        out.push_back(s.right[k]);
    }
    return out;
}

Stream load_kitti_stream(const fs::path& kitti_dir, const std::string& sequence, util::Range r,
                         const std::string& what, int threads, int min_pairs) {
    const KittiSequence k = open_kitti(kitti_dir, sequence);
    const auto paths = stereo_stream(k, r, what);
    if (static_cast<int>(paths.size()) < 2 * min_pairs)
        throw InputError(what + " gives " + std::to_string(paths.size() / 2) + " stereo pair(s) of KITTI sequence '" +
                         k.root.string() + "'; at least " + std::to_string(min_pairs) + " are needed");
    Stream s;
    s.frames.resize(paths.size());
    std::vector<std::string> errors(paths.size());
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(std::size_t{0}, paths.size(), [&](std::size_t i) {
            try {
                s.frames[i] = load_image(paths[i]);
            } catch (const std::exception& e) {
                errors[i] = e.what();
            }
        });
    });
    for (const auto& e : errors)
        if (!e.empty()) throw InputError(e);
    for (std::size_t i = 0; i < paths.size(); ++i) {
        if (s.frames[i].width != s.frames[0].width || s.frames[i].height != s.frames[0].height)
            throw InputError("image '" + paths[i].string() + "' differs in size from '" + paths[0].string() + "'");
        s.names.push_back(sequence + "/" + (i % 2 ? "R" : "L") + paths[i].stem().string());
        s.pair_index.push_back(r.first + static_cast<int>(i / 2));
    }
    s.description = "KITTI sequence " + sequence + " (" + k.root.string() + "), stereo pairs " +
                    std::to_string(r.first) + ".." + std::to_string(r.first + static_cast<int>(paths.size() / 2) - 1) +
                    ": " + std::to_string(paths.size()) + " frames " + std::to_string(s.frames[0].width) + "x" +
                    std::to_string(s.frames[0].height);
    return s;
}

fs::path kitti_root(const std::string& kitti_flag, const std::string& data_flag) {
    if (!kitti_flag.empty()) return kitti_flag;
    if (const auto d = data_dir(data_flag); d && fs::is_directory(*d / "kitti")) return *d / "kitti";
    return {};
}

fs::path require_kitti_root(const std::string& kitti_flag, const std::string& data_flag, const std::string& needs) {
    fs::path root = kitti_root(kitti_flag, data_flag);
    if (root.empty())
        throw InputError(needs + ": give --kitti DIR (holding sequences/NN) or --data DIR (holding kitti/), or set "
                         "HARRIS_COSIM_DATA");
    return root;
}

FrameFeed::FrameFeed(std::vector<std::string> names, std::vector<int> pair_index, std::string description,
                     std::function<Image(int)> load)
    : names_(std::move(names)), pair_index_(std::move(pair_index)), description_(std::move(description)),
      state_(std::make_shared<State>()) {
    if (names_.empty()) throw InputError("a stream of no frames");
    if (pair_index_.size() != names_.size()) throw std::invalid_argument("frame feed: names and pair numbers differ in count");
    state_->load = std::move(load);
    state_->names = names_;
    const auto f0 = frame(0);
    width_ = state_->width = f0->width;
    height_ = state_->height = f0->height;
}

FrameFeed FrameFeed::of(const Stream& s) {
    return FrameFeed(s.names, s.pair_index, s.description, [&s](int k) { return s.frames.at(static_cast<std::size_t>(k)); });
}

std::shared_ptr<const Image> FrameFeed::load_checked(State& st, int k) {
    auto im = std::make_shared<const Image>(st.load(k));
    if (st.width && (im->width != st.width || im->height != st.height))
        throw InputError("frame '" + st.names[static_cast<std::size_t>(k)] + "' is " + std::to_string(im->width) + "x" +
                         std::to_string(im->height) + " but '" + st.names[0] + "' is " + std::to_string(st.width) + "x" +
                         std::to_string(st.height) + "; a stream has one size");
    const std::lock_guard<std::mutex> lock(st.mu);
    ++st.loads;
    return im;
}

std::shared_ptr<const Image> FrameFeed::frame(int k) {
    if (k < 0 || k >= size())
        throw std::out_of_range("frame " + std::to_string(k) + " of a stream of " + std::to_string(size()));
    std::promise<std::shared_ptr<const Image>> mine;
    Loaded f;
    bool load_here = false;
    {
        const std::lock_guard<std::mutex> lock(state_->mu);
        if (auto it = state_->held.find(k); it != state_->held.end()) {
            f = it->second;
        } else {
            f = mine.get_future().share();
            state_->held.emplace(k, f);
            load_here = true;
        }
    }
    if (load_here) {   // outside the lock: loads of different frames run in parallel
        try {
            mine.set_value(load_checked(*state_, k));
        } catch (...) {
            mine.set_exception(std::current_exception());
        }
    }
    return f.get();
}

void FrameFeed::prefetch(int k) {
    if (k < 0 || k >= size()) return;
    std::promise<std::shared_ptr<const Image>> p;
    {
        const std::lock_guard<std::mutex> lock(state_->mu);
        if (state_->held.count(k)) return;
        state_->held.emplace(k, p.get_future().share());
    }
    std::erase_if(loading_, [](const std::future<void>& f) {
        return f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
    });
    loading_.push_back(std::async(std::launch::async, [st = state_, k, p = std::move(p)]() mutable {
        try {
            p.set_value(load_checked(*st, k));
        } catch (...) {
            p.set_exception(std::current_exception());
        }
    }));
}

void FrameFeed::release_below(int k) {
    const std::lock_guard<std::mutex> lock(state_->mu);
    state_->held.erase(state_->held.begin(), state_->held.lower_bound(k));
}

long FrameFeed::loads() const {
    const std::lock_guard<std::mutex> lock(state_->mu);
    return state_->loads;
}

std::vector<const Image*> pointers(const std::vector<Image>& frames) {
    std::vector<const Image*> v;
    for (const auto& f : frames) v.push_back(&f);
    return v;
}

}  // namespace hc::frames
