// corners.cpp: the corner sources of landmarks.hpp. OpenCV's Harris is the project's
// reference detector (hc::spec::opencv_corners); the co-processor's corners come from the
// spec model (hc::spec::SpecModel::run), or from a design the host driver's bus writes are
// streamed through, with each read's four corner bits decoded to pixels: the cycle model
// (hc::HarrisTop) or the Verilator netlist of rtl/.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>

#include <tbb/task_arena.h>

#include <opencv2/features2d.hpp>

#include "model/driver/bus_loop.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"
#include "cosim/verilator/gate.hpp"
#include "mapping/landmarks/corners.hpp"
#include "cosim/verilator/netlist.hpp"
#include "model/spec/opencv_reference.hpp"
#include "model/spec/spec_model.hpp"

namespace hc::landmarks {

namespace {

Image to_image(const cv::Mat& m) {
    if (m.type() != CV_8UC1) throw InputError("corner sources need 8-bit grey images");
    Image im(m.cols, m.rows);
    for (int r = 0; r < m.rows; ++r) std::copy_n(m.ptr<std::uint8_t>(r), m.cols, &im.at(r, 0));
    return im;
}

std::vector<cv::KeyPoint> mask_keypoints(const std::vector<std::uint8_t>& mask, int width, float size, int frame) {
    std::vector<cv::KeyPoint> kp;
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) {
            const int x = static_cast<int>(i % static_cast<size_t>(width)), y = static_cast<int>(i / static_cast<size_t>(width));
            kp.emplace_back(cv::Point2f(static_cast<float>(x), static_cast<float>(y)), size, 0.f, 0.f, 0, frame);
        }
    return kp;
}

std::vector<cv::KeyPoint> detect_harris(const cv::Mat& img, const CornerOptions& o) {
    std::vector<std::uint8_t> mask;
    spec::opencv_corners(to_image(img), spec::ReferenceOptions{}, mask);
    return mask_keypoints(mask, img.cols, o.keypoint_size, 0);
}
std::vector<cv::KeyPoint> detect_sift(const cv::Mat& img, const CornerOptions&) {
    std::vector<cv::KeyPoint> kp;
    cv::SIFT::create()->detect(img, kp);
    return kp;
}
std::vector<cv::KeyPoint> detect_sift512(const cv::Mat& img, const CornerOptions& o) {
    std::vector<cv::KeyPoint> kp = detect_sift(img, o);
    cv::KeyPointsFilter::retainBest(kp, 512);
    return kp;
}
std::vector<cv::KeyPoint> detect_orb(const cv::Mat& img, const CornerOptions& o) {
    std::vector<cv::KeyPoint> kp;
    cv::ORB::create(o.orb_features)->detect(img, kp);
    return kp;
}
std::vector<cv::KeyPoint> detect_brisk(const cv::Mat& img, const CornerOptions&) {
    std::vector<cv::KeyPoint> kp;
    cv::BRISK::create()->detect(img, kp);
    return kp;
}

}  // namespace

const std::vector<DetectorInfo>& detector_table() {
    static const std::vector<DetectorInfo> table{
        {Detector::opencv, "opencv", "OpenCV's Harris, the reference", detect_harris},
        {Detector::sift, "sift", "", detect_sift},
        {Detector::sift512, "sift512", "SIFT's 512 strongest", detect_sift512},
        {Detector::orb, "orb", "", detect_orb},
        {Detector::brisk, "brisk", "", detect_brisk},
        {Detector::spec, "spec", "the co-processor's frame-level spec model", nullptr},
        {Detector::cycle, "cycle", "its cycle model", nullptr},
        {Detector::rtl, "rtl", "its netlist under Verilator", nullptr},
    };
    return table;
}

const DetectorInfo& detector_info(Detector d) {
    const auto& t = detector_table();
    const auto it = std::find_if(t.begin(), t.end(), [d](const DetectorInfo& r) { return r.id == d; });
    if (it == t.end()) throw std::logic_error("detector_info: a corner source without a row in the table");
    return *it;
}

Detector parse_detector(const std::string& s) {
    for (const auto& r : detector_table())
        if (s == r.name) return r.id;
    throw InputError("unknown corner source '" + s + "' (one of: " + detector_list() + ")");
}

std::string detector_name(Detector d) { return detector_info(d).name; }

bool is_hardware(Detector d) { return detector_info(d).detect == nullptr; }

std::vector<Detector> all_detectors() {
    std::vector<Detector> out;
    for (const auto& r : detector_table()) out.push_back(r.id);
    return out;
}

std::string detector_names(const std::vector<Detector>& ds) {
    std::string out;
    for (Detector d : ds) out += (out.empty() ? "" : ", ") + detector_name(d);
    return out;
}

std::string detector_list(bool with_help) {
    std::string out;
    for (const auto& r : detector_table()) {
        if (!out.empty()) out += ", ";
        out += r.name;
        if (with_help && *r.help) out += std::string(" (") + r.help + ")";
    }
    return out;
}

namespace {

/// InputError unless the pair's images are non-empty, of one size and 8-bit grey.
void check_pair(const StereoImages& p) {
    if (p.left.empty() || p.right.empty()) throw InputError("pair '" + p.name + "': an image is empty");
    if (p.left.size() != p.right.size())
        throw InputError("pair '" + p.name + "': left " + std::to_string(p.left.cols) + "x" + std::to_string(p.left.rows) +
                         " and right " + std::to_string(p.right.cols) + "x" + std::to_string(p.right.rows) +
                         " images differ in size");
    if (p.left.type() != CV_8UC1 || p.right.type() != CV_8UC1)
        throw InputError("pair '" + p.name + "': images must be 8-bit grey");
}

/// InputError unless a hardware source's pair has the stream's one size (the first pair's).
void check_stream_size(Detector d, const StereoImages& p, const StereoImages& first) {
    if (p.left.size() != first.left.size())
        throw InputError("corner source " + detector_name(d) + " streams one image size: pair '" + p.name +
                         "' differs from '" + first.name + "'");
}

void check_formats(const Formats& f) {
    try {
        f.validate();
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string("formats: ") + e.what());
    }
}

/// The netlist of rtl/ for `f`, trusted only after the GHDL/Verilator/model gate passes for
/// these formats (cached per design, cosim/verilator/gate.hpp).
std::unique_ptr<vl::VerilatedDesign> rtl_design(const Geometry& g, const Formats& f) {
    std::string why;
    if (!vl::toolchain_available(&why)) throw InputError("corner source rtl needs GHDL and Verilator: " + why);
    const auto cache = vl::default_cache_dir();
    bool cached = false;
    const vl::GateResult gate = vl::run_gate_cached(f, {}, cache, std::cerr, &cached);
    if (gate.verdict != vl::GateVerdict::pass)
        throw std::runtime_error(std::string("corner source rtl: the GHDL/Verilator/model gate did not pass (") +
                                 vl::verdict_name(gate.verdict) + "): " + gate.first);
    const vl::NetlistConfig nc{g, f, false, {}};
    return std::make_unique<vl::VerilatedDesign>(vl::build_netlist(nc, cache, std::cerr), vl::config_key(nc));
}

}  // namespace

/// The design a cycle or rtl stream writes: the cycle model or the netlist.
struct StreamDevice {
    HarrisTop* top = nullptr;
    vl::VerilatedDesign* dut = nullptr;
    void write(std::uint32_t data) {
        if (top) top->write(data);
        else dut->write(data);
    }
    std::uint32_t corner() const { return top ? top->corner() : dut->corner(); }
};

/// The stream: for spec, the model run pair by pair with the previous frame's maximum carried;
/// for cycle and rtl, one host-driver stream (seed pair, the pairs, flush pair: stream frames
/// 0-1, 2k+2 and 2k+3 for pair k, then 2n+2 and 2n+3) whose frames are loaded as it reaches
/// them; a frame's corners are complete once the next frame's body (not its preload) starts, so
/// the last pair is complete when the flush pair's body starts, and the stream stops there.
struct PairCornerStream::Impl {
    Detector d;
    int n;
    PairAt pair_at;
    CornerOptions o;
    int next_pair = 0;
    std::optional<StereoImages> first;          // pair 0: the seed, and the stream's size
    std::map<int, StereoImages> held;           // cycle/rtl: pairs loaded and not yet passed on
    std::unique_ptr<spec::SpecStream> spec;
    std::unique_ptr<tbb::task_arena> arena;
    std::unique_ptr<HarrisTop> top;
    std::unique_ptr<vl::VerilatedDesign> dut;
    std::unique_ptr<FeedDriver> feed;
    std::map<int, std::vector<std::uint8_t>> masks;   // cycle/rtl: stream frame -> corners so far
    StreamDevice device;
    std::unique_ptr<BusLoop<FeedDriver, StreamDevice>> loop;   // holds the event that completed the last pair
    int last_frame = -1;
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();

    Impl(Detector d_, int n_, PairAt at, const CornerOptions& o_) : d(d_), n(n_), pair_at(std::move(at)), o(o_) {}
    StereoImages load(int k) {
        StereoImages p = pair_at(k);
        check_pair(p);
        if (is_hardware(d) && first) check_stream_size(d, p, *first);
        return p;
    }
    const StereoImages& pair(int k) {
        auto it = held.find(k);
        if (it == held.end()) it = held.emplace(k, k == 0 ? *first : load(k)).first;
        return it->second;
    }
    void start_hardware() {
        first = load(0);
        check_formats(o.formats);
        const Geometry g{first->left.cols, first->left.rows};
        if (d == Detector::spec) {
            spec::Options so;
            so.formats = o.formats;
            spec = std::make_unique<spec::SpecStream>(so);
            arena = std::make_unique<tbb::task_arena>(tbb::task_arena::automatic);
            const Image l = to_image(first->left), r = to_image(first->right);
            spec->run({&l, &r}, *arena);   // the seed
            return;
        }
        const int total = 2 * n + 4;
        try {
            if (d == Detector::cycle) top = std::make_unique<HarrisTop>(g, o.formats);
            else dut = rtl_design(g, o.formats);
            feed = std::make_unique<FeedDriver>(g, total, [this](int f) {
                const int k = f < 2 ? 0 : std::min(f / 2 - 1, n - 1);
                const StereoImages& p = pair(k);
                return std::make_shared<const Image>(to_image(f % 2 ? p.right : p.left));
            });
            device = {top.get(), dut.get()};
            loop = std::make_unique<BusLoop<FeedDriver, StreamDevice>>(*feed, device);
        } catch (const std::invalid_argument& e) {   // the host driver's geometry checks
            throw InputError("corner source " + detector_name(d) + " on '" + first->name + "': " + e.what());
        }
    }
    /// A cycle or rtl stream's writes and reads: the corners into their frames' masks, a
    /// progress line per frame; the loop stops before the first write of a frame after `last`.
    struct StreamHooks : BusHooks {
        Impl& s;
        int last;
        bool before(const BusEvent& ev) const { return ev.pos.tail || ev.pos.frame <= last; }
        void after(const BusEvent& ev) {
            if (s.o.progress && ev.pos.frame != s.last_frame) {
                s.last_frame = ev.pos.frame;
                std::fprintf(stderr, "landmarks: %s frame %d/%d, %.0f s\n", detector_name(s.d).c_str(), s.last_frame + 1,
                             2 * s.n + 4, std::chrono::duration<double>(std::chrono::steady_clock::now() - s.t0).count());
            }
        }
        void read(const BusEvent&, std::uint32_t, const std::vector<Corner>& corners) {
            const size_t w = static_cast<size_t>(s.first->left.cols);
            const size_t npix = w * static_cast<size_t>(s.first->left.rows);
            for (const Corner& c : corners) {
                auto& m = s.masks[c.frame];
                if (m.empty()) m.assign(npix, 0);
                m[static_cast<size_t>(c.y) * w + static_cast<size_t>(c.x)] = 1;
            }
        }
    };
    /// Streams until stream frame `last` is complete (or the stream ends).
    void stream_through(int last) {
        StreamHooks h{{}, *this, last};
        loop->run(h);
    }
    std::vector<cv::KeyPoint> take_mask(int frame, int w, int id) {
        auto it = masks.find(frame);
        if (it == masks.end()) return {};
        std::vector<cv::KeyPoint> kp = mask_keypoints(it->second, w, o.keypoint_size, id);
        masks.erase(masks.begin(), std::next(it));
        return kp;
    }
};

PairCornerStream::PairCornerStream(Detector d, int pairs, PairAt pair_at, const CornerOptions& o)
    : impl_(std::make_unique<Impl>(d, pairs, std::move(pair_at), o)) {}

PairCornerStream::~PairCornerStream() = default;

bool PairCornerStream::next(StereoImages& images, PairKeypoints& kp) {
    Impl& s = *impl_;
    const int k = s.next_pair;
    if (k >= s.n) return false;
    for (int side = 0; side < 2; ++side) {
        FrameKeypoints& f = side ? kp.right : kp.left;
        f.source = s.d;
        f.frame = 2 * k + side;
        f.points.clear();
    }
    if (!is_hardware(s.d)) {
        images = s.load(k);
        for (int side = 0; side < 2; ++side) {
            FrameKeypoints& f = side ? kp.right : kp.left;
            const cv::Mat& img = side ? images.right : images.left;
            f.points = detector_info(s.d).detect(img, s.o);
            for (auto& p : f.points) p.class_id = f.frame;
        }
    } else {
        if (k == 0) s.start_hardware();
        if (s.spec) {
            images = k == 0 ? *s.first : s.load(k);
            const Image l = to_image(images.left), r = to_image(images.right);
            const std::vector<spec::FrameCorners> fc = s.spec->run({&l, &r}, *s.arena);
            kp.left.points = mask_keypoints(fc[0].mask, images.left.cols, s.o.keypoint_size, kp.left.frame);
            kp.right.points = mask_keypoints(fc[1].mask, images.left.cols, s.o.keypoint_size, kp.right.frame);
        } else {
            s.stream_through(2 * k + 3);
            images = s.pair(k);
            const int w = images.left.cols;
            kp.left.points = s.take_mask(2 * k + 2, w, kp.left.frame);
            kp.right.points = s.take_mask(2 * k + 3, w, kp.right.frame);
            s.held.erase(s.held.begin(), s.held.lower_bound(k));
        }
    }
    kp.left.name = images.name + "/L";
    kp.right.name = images.name + "/R";
    ++s.next_pair;
    return true;
}

std::vector<PairKeypoints> detect_pairs(Detector d, const std::vector<StereoImages>& pairs, const CornerOptions& o) {
    for (const auto& p : pairs) check_pair(p);
    if (is_hardware(d) && !pairs.empty()) {
        for (const auto& p : pairs) check_stream_size(d, p, pairs[0]);
        check_formats(o.formats);
    }
    PairCornerStream stream(d, static_cast<int>(pairs.size()), [&pairs](int k) { return pairs.at(static_cast<size_t>(k)); },
                            o);
    std::vector<PairKeypoints> out(pairs.size());
    StereoImages images;
    for (auto& kp : out) stream.next(images, kp);
    return out;
}

}  // namespace hc::landmarks
