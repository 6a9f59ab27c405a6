// corners.cpp: the corner sources of landmarks.hpp. OpenCV's Harris is the project's
// reference detector (hc::spec::opencv_corners); the co-processor's corners come from the
// spec model (hc::spec::SpecModel::run), or from a design the host driver's bus writes are
// streamed through, with each read's four corner bits decoded to pixels: the cycle model
// (hc::HarrisTop) or the Verilator netlist of rtl/.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

#include <opencv2/features2d.hpp>

#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"
#include "cosim/verilator/gate.hpp"
#include "slam/landmarks/corners.hpp"
#include "cosim/verilator/netlist.hpp"
#include "model/spec/opencv_reference.hpp"
#include "model/spec/spec_model.hpp"

namespace hc::landmarks {

Detector parse_detector(const std::string& s) {
    for (Detector d : all_detectors())
        if (detector_name(d) == s) return d;
    throw InputError("unknown corner source '" + s + "' (opencv, sift, sift512, orb, brisk, spec, cycle or rtl)");
}

std::string detector_name(Detector d) {
    switch (d) {
    case Detector::opencv: return "opencv";
    case Detector::sift: return "sift";
    case Detector::sift512: return "sift512";
    case Detector::orb: return "orb";
    case Detector::brisk: return "brisk";
    case Detector::spec: return "spec";
    case Detector::cycle: return "cycle";
    case Detector::rtl: return "rtl";
    }
    return "?";
}

bool is_hardware(Detector d) { return d == Detector::spec || d == Detector::cycle || d == Detector::rtl; }

std::vector<Detector> all_detectors() {
    return {Detector::opencv, Detector::sift, Detector::sift512, Detector::orb,
            Detector::brisk,  Detector::spec, Detector::cycle,   Detector::rtl};
}

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

/// Streams `frames` through a design as the thesis's host does (HostDriver: bus writes of
/// 4 pixels, a read of the 4 corner bits when a window row completes): `write` takes a data
/// word, `corner` returns the corner word the host reads after it.
template <class Write, class ReadCorner>
std::vector<std::vector<std::uint8_t>> stream_masks(const std::vector<Image>& frames, Write&& write, ReadCorner&& corner,
                                                    const char* what, bool progress) {
    const Geometry g{frames.at(0).width, frames.at(0).height};
    std::vector<const Image*> ptrs;
    for (const auto& im : frames) ptrs.push_back(&im);
    HostDriver drv(g, ptrs);
    const size_t npix = static_cast<size_t>(g.width) * static_cast<size_t>(g.height);
    std::vector<std::vector<std::uint8_t>> masks(frames.size(), std::vector<std::uint8_t>(npix, 0));
    std::vector<Corner> cs;
    BusEvent ev;
    int last_frame = -1;
    const auto t0 = std::chrono::steady_clock::now();
    while (drv.next(ev)) {
        write(ev.data);
        if (ev.read) {
            cs.clear();
            drv.decode(*ev.read, corner(), cs);
            for (const Corner& c : cs) masks[static_cast<size_t>(c.frame)][static_cast<size_t>(c.y) * g.width + c.x] = 1;
        }
        if (progress && ev.pos.frame != last_frame) {
            last_frame = ev.pos.frame;
            std::fprintf(stderr, "landmarks: %s frame %d/%zu, %.0f s\n", what, last_frame + 1, frames.size(),
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
    }
    return masks;
}

std::vector<std::vector<std::uint8_t>> cycle_masks(const std::vector<Image>& frames, const Formats& f, bool progress) {
    HarrisTop top(Geometry{frames.at(0).width, frames.at(0).height}, f);
    return stream_masks(frames, [&](std::uint32_t d) { top.write(d); }, [&] { return top.corner(); }, "cycle", progress);
}

/// The Verilator netlist of rtl/ for `f`, trusted only after the GHDL/Verilator/model gate
/// passes for these formats (cached per design, cosim/verilator/gate.hpp).
std::vector<std::vector<std::uint8_t>> rtl_masks(const std::vector<Image>& frames, const Formats& f, bool progress) {
    std::string why;
    if (!vl::toolchain_available(&why)) throw InputError("corner source rtl needs GHDL and Verilator: " + why);
    const auto cache = vl::default_cache_dir();
    bool cached = false;
    const vl::GateResult gate = vl::run_gate_cached(f, {}, cache, std::cerr, &cached);
    if (gate.verdict != vl::GateVerdict::pass)
        throw std::runtime_error(std::string("corner source rtl: the GHDL/Verilator/model gate did not pass (") +
                                 vl::verdict_name(gate.verdict) + "): " + gate.first);
    const vl::NetlistConfig nc{Geometry{frames.at(0).width, frames.at(0).height}, f, false, {}};
    vl::VerilatedDesign dut(vl::build_netlist(nc, cache, std::cerr), vl::config_key(nc));
    return stream_masks(frames, [&](std::uint32_t d) { dut.write(d); }, [&] { return dut.corner(); }, "rtl", progress);
}

std::vector<std::vector<std::uint8_t>> spec_masks(const std::vector<Image>& frames, const Formats& f) {
    spec::Options so;
    so.formats = f;
    const spec::SpecModel m(so);
    std::vector<const Image*> ptrs;
    for (const auto& im : frames) ptrs.push_back(&im);
    std::int64_t prev = m.reset_max();
    std::vector<std::vector<std::uint8_t>> masks;
    for (auto& fc : m.run(ptrs, prev, 0)) masks.push_back(std::move(fc.mask));
    return masks;
}

std::vector<cv::KeyPoint> opencv_detect(Detector d, const cv::Mat& img, const CornerOptions& o) {
    std::vector<cv::KeyPoint> kp;
    switch (d) {
    case Detector::sift:
    case Detector::sift512: {
        cv::SIFT::create()->detect(img, kp);
        if (d == Detector::sift512) cv::KeyPointsFilter::retainBest(kp, 512);
        break;
    }
    case Detector::orb: cv::ORB::create(o.orb_features)->detect(img, kp); break;
    case Detector::brisk: cv::BRISK::create()->detect(img, kp); break;
    default: throw std::logic_error("opencv_detect: not an OpenCV feature detector");
    }
    return kp;
}

}  // namespace

std::vector<PairKeypoints> detect_pairs(Detector d, const std::vector<StereoImages>& pairs, const CornerOptions& o) {
    std::vector<PairKeypoints> out(pairs.size());
    for (size_t k = 0; k < pairs.size(); ++k) {
        const auto& p = pairs[k];
        if (p.left.empty() || p.right.empty()) throw InputError("pair '" + p.name + "': an image is empty");
        if (p.left.size() != p.right.size())
            throw InputError("pair '" + p.name + "': left " + std::to_string(p.left.cols) + "x" + std::to_string(p.left.rows) +
                             " and right " + std::to_string(p.right.cols) + "x" + std::to_string(p.right.rows) +
                             " images differ in size");
        if (p.left.type() != CV_8UC1 || p.right.type() != CV_8UC1)
            throw InputError("pair '" + p.name + "': images must be 8-bit grey");
        for (int side = 0; side < 2; ++side) {
            FrameKeypoints& f = side ? out[k].right : out[k].left;
            f.source = d;
            f.frame = static_cast<int>(2 * k) + side;
            f.name = p.name + (side ? "/R" : "/L");
        }
    }
    if (pairs.empty()) return out;

    if (!is_hardware(d)) {
        for (size_t k = 0; k < pairs.size(); ++k)
            for (int side = 0; side < 2; ++side) {
                FrameKeypoints& f = side ? out[k].right : out[k].left;
                const cv::Mat& img = side ? pairs[k].right : pairs[k].left;
                if (d == Detector::opencv) {
                    std::vector<std::uint8_t> mask;
                    spec::opencv_corners(to_image(img), spec::ReferenceOptions{}, mask);
                    f.points = mask_keypoints(mask, img.cols, o.keypoint_size, f.frame);
                } else {
                    f.points = opencv_detect(d, img, o);
                    for (auto& kp : f.points) kp.class_id = f.frame;
                }
            }
        return out;
    }

    // hardware: one stream, seed pair in front, flush pair behind (cycle, rtl)
    for (const auto& p : pairs)
        if (p.left.size() != pairs[0].left.size())
            throw InputError("corner source " + detector_name(d) + " streams one image size: pair '" + p.name +
                             "' differs from '" + pairs[0].name + "'");
    try {
        o.formats.validate();
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string("formats: ") + e.what());
    }
    std::vector<Image> frames;
    auto push = [&](const StereoImages& p) {
        frames.push_back(to_image(p.left));
        frames.push_back(to_image(p.right));
    };
    const size_t first = 1;   // stream pair index of pairs[0], after the seed
    push(pairs.front());
    for (const auto& p : pairs) push(p);
    if (d != Detector::spec) push(pairs.back());   // flush
    std::vector<std::vector<std::uint8_t>> masks;
    try {
        masks = d == Detector::spec    ? spec_masks(frames, o.formats)
                : d == Detector::cycle ? cycle_masks(frames, o.formats, o.progress)
                                       : rtl_masks(frames, o.formats, o.progress);
    } catch (const std::invalid_argument& e) {   // the host driver's geometry checks
        throw InputError("corner source " + detector_name(d) + " on '" + pairs[0].name + "': " + e.what());
    }
    const int w = pairs[0].left.cols;
    for (size_t k = 0; k < pairs.size(); ++k) {
        out[k].left.points = mask_keypoints(masks[2 * (k + first)], w, o.keypoint_size, out[k].left.frame);
        out[k].right.points = mask_keypoints(masks[2 * (k + first) + 1], w, o.keypoint_size, out[k].right.frame);
    }
    return out;
}

}  // namespace hc::landmarks
