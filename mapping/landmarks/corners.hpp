// corners.hpp: the corner sources of the landmark chain (part of mapping/landmarks/landmarks.hpp):
// OpenCV's Harris reference, SIFT, ORB, BRISK and the co-processor (spec, cycle, rtl) for any
// Formats, and the library's InputError.
#pragma once

#include "model/util/errors.hpp"
#include "model/harris/harris_pkg.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

namespace hc::landmarks {

// ---- corner sources -------------------------------------------------------------------

enum class Detector {
    opencv,    ///< OpenCV Harris reference: hc::spec::opencv_corners (docs/metrics.md)
    sift,      ///< cv::SIFT detector, all points
    sift512,   ///< cv::SIFT detector, the 512 strongest points by response (thesis 6.4.1)
    orb,       ///< cv::ORB detector (nfeatures = CornerOptions::orb_features)
    brisk,     ///< cv::BRISK detector
    // the co-processor's sources: the rows of hc::corners::source_table() in its order, from
    // here on (a source added there follows rtl without a name of its own here)
    spec,      ///< frame-level spec model (hc::spec::SpecModel)
    cycle,     ///< cycle model hc::HarrisTop through the host driver
    rtl,       ///< Verilator netlist of rtl/ (GHDL synthesis), after its gate, in lock step with the cycle model
};

struct CornerOptions {
    Formats formats{};          ///< bit widths of spec/cycle/rtl (thesis defaults)
    float keypoint_size = 7.f;  ///< cv::KeyPoint::size given to Harris and hardware corners
                                ///< (the 7x7 window a co-processor corner is decided on)
    int orb_features = 2000;    ///< cv::ORB nfeatures
    bool progress = false;      ///< progress lines on stderr for cycle/rtl
};

/// One row of the corner-source table (corners.cpp), the one list of corner sources: names,
/// parsing, the help texts and the docs' list are made from it (docs/architecture.md, "Adding
/// a corner source").
struct DetectorInfo {
    Detector id;
    const char* name;    ///< the flag value and the reports' name
    const char* help;    ///< what the help text says of it after its name ("": nothing)
    /// the corners of one 8-bit grey image, as the source gives them (pt, size, response,
    /// octave); null for the co-processor's sources (spec, cycle, rtl), which a stream drives
    /// with the threshold carried from frame to frame (PairCornerStream over hc::corners::CornerStream)
    std::vector<cv::KeyPoint> (*detect)(const cv::Mat& grey, const CornerOptions& o);
};
/// Every corner source, in the order of the enum.
const std::vector<DetectorInfo>& detector_table();
const DetectorInfo& detector_info(Detector d);
Detector parse_detector(const std::string& s);   ///< a table name; InputError naming the known ones
std::string detector_name(Detector d);
/// The co-processor's sources (spec, cycle, rtl): the rows without `detect`.
bool is_hardware(Detector d);
std::vector<Detector> all_detectors();           ///< the table's, in order
/// The names joined by ", " (with_help: each followed by its help in parentheses, where it has one).
std::string detector_list(bool with_help = false);
/// The names of `ds` joined by ", ".
std::string detector_names(const std::vector<Detector>& ds);

/// The corners of one image, with where they come from. Each point's `pt` is the pixel
/// (x = column, y = row; integer for Harris and hardware sources), `class_id` the frame.
struct FrameKeypoints {
    Detector source = Detector::opencv;
    int frame = 0;                       ///< index of the image in the caller's stream
    std::string name;                    ///< e.g. "Aloe/L" or "01/L000003"
    std::vector<cv::KeyPoint> points;
};

struct StereoImages {
    cv::Mat left, right;   ///< 8-bit grey, same size
    std::string name;
};

struct PairKeypoints {
    FrameKeypoints left, right;
};

/// Corners of each stereo pair. All pairs must have one size for the hardware sources, whose
/// threshold comes from the previous frame's maximum: they stream the first pair once more
/// in front as a seed (not returned), and cycle/rtl append the last pair once more as a
/// flush (its windows come back only while later pixels are written), as docs/metrics.md's
/// protocol does. Frame numbers are 2k (left) and 2k+1 (right) of pair k. (PairCornerStream
/// over the pairs.)
std::vector<PairKeypoints> detect_pairs(Detector d, const std::vector<StereoImages>& pairs,
                                        const CornerOptions& o = {});

/// detect_pairs pair by pair over a stream whose pairs are loaded as they are reached
/// (`pair_at(k)`, asked in order): the same corners, with at most three pairs held (a hardware
/// source's threshold carried from frame to frame within one run of the spec model, or one
/// stream through the cycle model or the netlist, which asks for a frame before the previous
/// one's reads are done). InputError as detect_pairs, for a pair when it is reached.
class PairCornerStream {
public:
    using PairAt = std::function<StereoImages(int pair)>;
    PairCornerStream(Detector d, int pairs, PairAt pair_at, const CornerOptions& o = {});
    ~PairCornerStream();
    PairCornerStream(const PairCornerStream&) = delete;
    PairCornerStream& operator=(const PairCornerStream&) = delete;
    /// The next pair's images and corners; false after the last pair.
    bool next(StereoImages& images, PairKeypoints& corners);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace hc::landmarks
