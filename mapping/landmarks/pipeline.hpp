// pipeline.hpp: the landmark pipeline and its evaluation (part of mapping/landmarks/landmarks.hpp):
// one frame or a dataset to landmarks, the descriptor comparison, the g x h study of the grid
// and the downstream score of a bit-width configuration.
#pragma once

#include "mapping/landmarks/datasets.hpp"
#include "mapping/landmarks/geometry.hpp"
#include "mapping/landmarks/matching.hpp"

#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hc::landmarks {

struct PipelineOptions {
    Detector detector = Detector::opencv;
    Descriptor descriptor = Descriptor::grid;
    GridParams grid{};
    MatchParams match{};
    CornerOptions corners{};
    PixelNoise noise{};
    double min_disparity = 0.5;   ///< px; closer to 0 the point is dropped (depth unbounded)
};

/// One stereo frame to landmarks: corners, description, matching (all three tests), and
/// triangulation of each correct match. Throws InputError for images of different sizes or
/// not 8-bit. (Hardware sources stream the pair with a seed and a flush, see detect_pairs.)
std::vector<Landmark> acquire(const cv::Mat& left, const cv::Mat& right, const landmarks::RectifiedRig& calib,
                              const PipelineOptions& o);
/// The same from matches already computed (the command's path, which also scores them).
std::vector<Landmark> landmarks_from(const PairResult& r, const landmarks::RectifiedRig& calib, const PipelineOptions& o);

// ---- evaluation: comparison and the g x h study ------------------------------------------

struct Totals {
    long all = 0, correct = 0, truth_known = 0, truth_correct = 0;
    long truth_correct_x = 0;   ///< x within 1 px, y not checked (PairResult::truth_correct_x)
    long keypoints = 0;
    double seconds = 0;
    int pairs = 0;
    void add(const PairResult& r);
};
/// Totals as JSON and back, as a sweep point carries them (results_json.cpp): every count but
/// truth_correct_x, which no sweep report shows.
void to_json(nlohmann::json& j, const Totals& t);
void from_json(const nlohmann::json& j, Totals& t);

/// Summed counts of one descriptor on one detector's corners over a set of pairs.
struct ComparisonRow {
    Descriptor descriptor = Descriptor::grid;
    Detector detector = Detector::opencv;
    GridParams grid{};
    int descriptor_bytes = 0;
    Totals totals;
    std::vector<PairResult> pairs;   ///< per pair (matches kept for overlays and landmarks)
};

/// Landmarks of every pair of a dataset, pair by pair: the corners of all pairs first (a
/// hardware source streams them once, carrying its state from frame to frame as the
/// co-processor does, see detect_dataset), then description, matching and triangulation of
/// each pair with its own calibration.
std::vector<std::vector<Landmark>> acquire_dataset(const Dataset& ds, const PipelineOptions& o);
/// The same from the corners of every pair already detected (`kp`, one per pair of `ds`:
/// detect_dataset's); InputError when their counts differ.
std::vector<std::vector<Landmark>> acquire_dataset(const Dataset& ds, const std::vector<PairKeypoints>& kp,
                                                   const PipelineOptions& o);

struct ComparisonOptions {
    std::vector<Detector> detectors{Detector::sift512, Detector::sift, Detector::opencv};
    std::vector<Descriptor> descriptors = comparison_descriptors();
    GridParams grid{16, 3};
    MatchParams match{};
    CornerOptions corners{};
    std::function<void(const std::string&)> progress;   ///< one line per finished row
    int threads = 0;   ///< workers over (descriptor, pair) tasks, each on one thread (0: all cores)
};
/// Corners of every pair of a dataset. Hardware sources stream the pairs of one size together
/// (seed and flush as detect_pairs), and a dataset of several sizes scene by scene.
std::vector<PairKeypoints> detect_dataset(const Dataset& ds, Detector d, const CornerOptions& o = {});

/// Corners once per detector, then every descriptor on them; each pair's extraction and
/// matching on one thread (cv::setNumThreads(1)), `threads` pairs at once. `keypoints`, when given, receives the corners
/// of each detector (o.detectors order) for reuse, e.g. by study().
std::vector<ComparisonRow> compare(const Dataset& ds, const ComparisonOptions& o,
                                   std::vector<std::vector<PairKeypoints>>* keypoints = nullptr);

/// Correct matches (thesis and ground truth) of the grid descriptor over g x h.
struct StudyCell {
    int g = 0, h = 0;
    long all = 0, correct = 0, truth_correct = 0;
    long truth_correct_x = 0;                 ///< x within 1 px, y not checked
    std::vector<long> pair_correct, pair_truth_correct;   ///< per pair of the dataset
};
struct StudyResult {
    Detector detector = Detector::opencv;
    std::vector<StudyCell> cells;   ///< g-major
    StudyCell best_correct() const;         ///< most thesis-correct matches (ties: smaller g, h)
    StudyCell best_truth() const;           ///< most ground-truth-correct matches
    /// The same study restricted to the pairs `pairs` (indices into the dataset): every cell's
    /// correct and truth_correct summed over those pairs only (all, truth_correct_x: 0).
    StudyResult on_pairs(const std::vector<size_t>& pairs) const;
};

/// (g, h) chosen on some pairs and scored on others: the cell with the most ground-truth-correct
/// matches over `choose` (`by_truth`; else thesis-correct), its counts over `report`, and for
/// comparison the best cell of `report` itself (what choosing on the scored pairs would claim).
struct HeldOutChoice {
    StudyCell chosen;        ///< counts over `choose`
    StudyCell on_report;     ///< the chosen (g, h), counts over `report`
    StudyCell report_best;   ///< the best cell of `report` by the same criterion
};
HeldOutChoice held_out_choice(const StudyResult& s, const std::vector<size_t>& choose,
                              const std::vector<size_t>& report, bool by_truth);
struct StudyOptions {
    int g_min = 4, g_max = 32, h_min = 0, h_max = 5;
    bool corrected = false;                 ///< the corrected g x g grid instead of the thesis's
    MatchParams match{};
    CornerOptions corners{};
    int threads = 0;                        ///< 0: all cores (cells in parallel)
};
StudyResult study(const Dataset& ds, Detector d, const StudyOptions& o);
/// The same on keypoints already detected (one entry per pair of ds).
StudyResult study(const Dataset& ds, Detector d, const std::vector<PairKeypoints>& kp, const StudyOptions& o);

/// Scoring a bit-width configuration downstream (for the sweep): the co-processor's corners
/// (spec model, or cycle) with `formats` on a dataset, grid descriptor (g, h), matched with the
/// thesis's tests. Returns the summed totals (correct = thesis, truth_correct = ground truth).
Totals score_formats(const Dataset& ds, const Formats& formats, Detector source = Detector::spec,
                     const GridParams& gp = {16, 3}, const MatchParams& mp = {});

/// Depth errors over all pairs of a comparison row (pairs without ground truth skipped).
DepthError depth_error(const ComparisonRow& row, const Dataset& ds);

}  // namespace hc::landmarks
