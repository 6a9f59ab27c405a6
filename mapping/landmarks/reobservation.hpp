// reobservation.hpp: how much a descriptor changes between consecutive frames of one camera
// (part of mapping/landmarks/landmarks.hpp).
#pragma once

#include "mapping/landmarks/datasets.hpp"
#include "mapping/landmarks/matching.hpp"

#include <cstdint>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

namespace hc::landmarks {

// ---- re-observations between consecutive frames --------------------------------------------

/// How much a descriptor changes between consecutive frames of one camera (the left images of
/// a dataset's pairs, e.g. a KITTI sequence driving forward), measured without descriptors:
/// corners of frame k tracked into frame k+1 by pyramidal Lucas-Kanade optical flow (21 x 21
/// window, 3 levels), kept when the backward track comes back within `max_fb_px` and a corner
/// of frame k+1 lies within `max_corner_px` of the tracked point (a corner claimed by two
/// tracks is dropped). No ground truth is used.
struct ReobservationOptions {
    Detector detector = Detector::opencv;
    std::vector<Descriptor> descriptors = reobservation_descriptors();
    GridParams grid{16, 3};
    double max_fb_px = 0.5;
    double max_corner_px = 1.0;
    std::uint64_t seed = 1;   ///< random pairs
    CornerOptions corners{};
};
/// Per descriptor: Hamming distances (as a fraction of the descriptor's bits) between the two
/// descriptors of each re-observed corner, against a random pair per re-observation (the same
/// corner of frame k and a random other corner of frame k+1).
struct ReobservationRow {
    Descriptor descriptor = Descriptor::grid;
    int bits = 0;
    long frames = 0;               ///< consecutive frame pairs with re-observations
    long reobservations = 0;       ///< re-observed corners described in both frames
    double same_median = 0, same_mean = 0;       ///< re-observations
    double random_median = 0, random_mean = 0;   ///< random pairs
    long below_random_median = 0;  ///< re-observations closer than the random pairs' median
    long nearest = 0;              ///< re-observations whose nearest frame-(k+1) descriptor is their own
};
/// Indices (i into ka, j into kb) of the corners of image a re-observed in image b.
std::vector<std::pair<int, int>> track_corners(const cv::Mat& a, const cv::Mat& b, const std::vector<cv::KeyPoint>& ka,
                                               const std::vector<cv::KeyPoint>& kb, const ReobservationOptions& o);
/// The rows above over the consecutive left images of `ds`; InputError for fewer than two
/// frames or a float descriptor (SIFT).
std::vector<ReobservationRow> reobservation_study(const Dataset& ds, const ReobservationOptions& o);

}  // namespace hc::landmarks
