// corners.cpp: the corner sources of landmarks.hpp. OpenCV's Harris is the project's
// reference detector (hc::spec::opencv_corners); the co-processor's sources (spec, cycle,
// rtl) are the rows of hc::corners::source_table(), streamed by hc::corners::CornerStream.
#include <algorithm>
#include <map>
#include <optional>

#include <opencv2/features2d.hpp>

#include "cosim/corners/corners.hpp"
#include "mapping/landmarks/corners.hpp"
#include "model/spec/opencv_reference.hpp"
#include "model/util/table.hpp"

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

/// The co-processor's source of a hardware detector: the rows from Detector::spec on follow
/// corners::source_table() in its order.
corners::Source hardware_source(Detector d) {
    return static_cast<corners::Source>(static_cast<int>(d) - static_cast<int>(Detector::spec));
}

}  // namespace

const std::vector<DetectorInfo>& detector_table() {
    static const std::vector<DetectorInfo> table = [] {
        std::vector<DetectorInfo> t{
            {Detector::opencv, "opencv", "OpenCV's Harris, the reference", detect_harris},
            {Detector::sift, "sift", "", detect_sift},
            {Detector::sift512, "sift512", "SIFT's 512 strongest", detect_sift512},
            {Detector::orb, "orb", "", detect_orb},
            {Detector::brisk, "brisk", "", detect_brisk},
        };
        for (const corners::SourceInfo& r : corners::source_table())
            t.push_back({static_cast<Detector>(static_cast<int>(Detector::spec) + static_cast<int>(r.id)), r.name, r.help,
                         nullptr});
        return t;
    }();
    return table;
}

const DetectorInfo& detector_info(Detector d) { return util::row_of(detector_table(), d, "a corner source"); }

Detector parse_detector(const std::string& s) { return util::row_named(detector_table(), s, "corner source"); }

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

std::string detector_list(bool with_help) { return util::row_names(detector_table(), with_help); }

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

}  // namespace

/// The stream: pair by pair; for a hardware source one corners::CornerStream over the seed
/// pair, the pairs and (cycle-accurate sources) a flush pair: stream frames 0-1, 2k+2 and 2k+3
/// for pair k, then 2n+2 and 2n+3, loaded as the stream reaches them (spec: a pair at a time). A frame's corners are
/// complete once the next frame's body (not its preload) starts, so the last pair is complete
/// when the flush pair's body starts, and the stream stops there.
struct PairCornerStream::Impl {
    Detector d;
    int n;
    PairAt pair_at;
    CornerOptions o;
    int next_pair = 0;
    std::optional<StereoImages> first;          // pair 0: the seed, and the stream's size
    std::map<int, StereoImages> held;           // hardware: pairs loaded and not yet passed on
    std::unique_ptr<corners::CornerStream> stream;

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
        corners::StreamRequest r;
        r.geometry = Geometry{first->left.cols, first->left.rows};
        r.frames = corners::source_info(hardware_source(d)).cycle_accurate ? 2 * n + 4 : 2 * n + 2;
        r.batch = 2;   // spec: a pair at a time
        r.formats = o.formats;
        r.progress = o.progress ? "landmarks" : "";
        r.frame_at = [this](int f) {
            const int k = f < 2 ? 0 : std::min(f / 2 - 1, n - 1);
            const StereoImages& p = pair(k);
            return std::make_shared<const Image>(to_image(f % 2 ? p.right : p.left));
        };
        try {
            stream = corners::open_stream(hardware_source(d), std::move(r));
        } catch (const std::invalid_argument& e) {   // the host driver's geometry checks
            throw InputError("corner source " + detector_name(d) + " on '" + first->name + "': " + e.what());
        }
        corners::StreamFrame seed;
        for (int side = 0; side < 2; ++side) take(seed);
    }
    /// The stream's next frame; InternalError when it has none.
    void take(corners::StreamFrame& f) {
        if (!stream->next(f)) throw InternalError("corner source " + detector_name(d) + ": the stream ended early");
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
        corners::StreamFrame left, right;
        s.take(left);
        s.take(right);
        images = s.pair(k);
        const int w = images.left.cols;
        kp.left.points = mask_keypoints(left.mask, w, s.o.keypoint_size, kp.left.frame);
        kp.right.points = mask_keypoints(right.mask, w, s.o.keypoint_size, kp.right.frame);
        s.held.erase(s.held.begin(), s.held.lower_bound(k));
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
        corners::check_formats(o.formats);
    }
    PairCornerStream stream(d, static_cast<int>(pairs.size()), [&pairs](int k) { return pairs.at(static_cast<size_t>(k)); },
                            o);
    std::vector<PairKeypoints> out(pairs.size());
    StereoImages images;
    for (auto& kp : out) stream.next(images, kp);
    return out;
}

}  // namespace hc::landmarks
