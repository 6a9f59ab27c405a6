// landmarks.hpp: landmark acquisition downstream of the Harris co-processor (Schulz 2015,
// Figure 1, sections 4.3, 5.1, 6.1, 6.4): corners from any source -> descriptor -> stereo
// correspondence -> 3D landmarks with covariance, and the descriptor comparison of the
// thesis's Tables 6-10 scored, beyond the thesis, against ground-truth disparity.
//
// Purpose: one typed API for the `landmarks` command, the sweep (score a bit-width
// configuration by correct stereo matches) and an EKF-SLAM front end (acquire() per frame).
//
//   corners      detect_pairs(): OpenCV's Harris reference (docs/metrics.md), OpenCV's
//                SIFT (all points, or the 512 strongest), ORB, BRISK, and the co-processor
//                as `spec` (frame model), `cycle` (HarrisTop through the host driver) and
//                `rtl` (the GHDL-synthesised netlist under Verilator) for any Formats.
//   descriptors  make_descriptor(): grid (thesis or corrected), sift, orb, brisk, brief, freak
//                (hc::landmarks for grid, brief, freak; OpenCV for the others).
//   matching     hc::landmarks::match_stereo (cross-check, 2-NN ratio, epipolar |y_r - y_l| < 5).
//   scoring      a match is "correct (thesis)" when it passes all three tests; "correct
//                (ground truth)" when besides |x_l - x_r - d(x_l, y_l)| <= 1 px with d the
//                dataset's disparity at the left keypoint's pixel (0 = unknown: excluded)
//                and |y_r - y_l| <= 1 px (the x-only count is kept beside it).
//   geometry     landmarks::triangulate() through the pair's landmarks::RectifiedRig (KITTI
//                calib.txt's P0, P1, a calibrated rig's rectified pair, or Middlebury's focal
//                length, baseline and offset), covariance by Jacobian propagation of an
//                isotropic pixel noise.
//
// Errors: bad input (missing files, sizes, impossible combinations, out-of-range parameters)
// throws hc::InputError naming the input; the CLI maps it to exit status 2.
//
// The sections, each its own header, all included here:
//   corners.hpp        corner sources, InputError
//   matching.hpp       descriptors and one pair's matches
//   datasets.hpp       Middlebury, KITTI and rig datasets
//   geometry.hpp       landmarks, pixel noise, depth errors
//   pipeline.hpp       frame and dataset to landmarks, comparison, g x h study, score_formats
//   reobservation.hpp  descriptor change between consecutive frames
//   report.hpp         files, overlays, tables, plots
#pragma once

#include "mapping/landmarks/corners.hpp"
#include "mapping/landmarks/datasets.hpp"
#include "mapping/landmarks/geometry.hpp"
#include "mapping/landmarks/matching.hpp"
#include "mapping/landmarks/pipeline.hpp"
#include "mapping/landmarks/reobservation.hpp"
#include "mapping/landmarks/report.hpp"
