// datasets.hpp: the stereo datasets of the landmark chain (part of mapping/landmarks/landmarks.hpp):
// Middlebury 2006 scenes, KITTI odometry pairs and a user's own rig, each pair with its rectified rig.
#pragma once

#include "io/frames/frames.hpp"
#include "mapping/landmarks/calib.hpp"
#include "mapping/landmarks/corners.hpp"
#include "mapping/landmarks/stereo.hpp"
#include "model/util/util.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace hc::landmarks {

// ---- datasets -------------------------------------------------------------------------

/// A Middlebury 2006 scene folder: view1.png (left), view5.png (right), disp1.png (ground
/// truth of the left view), dmin.txt (full-size disparity offset).
struct MiddleburyScene {
    std::string name;
    StereoImages images;        ///< grey
    cv::Mat disparity;          ///< CV_32F disparity in this image's pixels, 0 = unknown
    double scale = 0.5;         ///< image size / full size
    double dmin_full = 0;       ///< dmin.txt
};
/// How disp1.png encodes disparity: the 2006 set stores the disparity of the image's own
/// size times the reduction factor (full 1, half 2, third 3), so d = value * scale; 0 unknown.
float middlebury_disparity(std::uint8_t value, double scale);
/// The scale of a Middlebury 2006 folder from its height (1110 full, 555 half, 370 third).
double middlebury_scale(int height);
/// Loads a scene; throws InputError naming the missing file (e.g. disp1.png) or the size
/// mismatch. `need_truth` false reads no disp1.png (disparity left empty).
MiddleburyScene load_middlebury(const std::filesystem::path& dir, bool need_truth = true);
/// The scene folders under `root` (sorted; those holding view1.png).
std::vector<std::filesystem::path> middlebury_scenes(const std::filesystem::path& root);

/// A dataset: stereo pairs with optional ground truth and a calibration per pair.
struct Dataset {
    std::string name;                    ///< "middlebury-half", "kitti-01", "rig"
    std::vector<StereoImages> pairs;
    std::vector<cv::Mat> disparity;      ///< per pair, empty if unknown
    std::vector<landmarks::RectifiedRig> calib;   ///< per pair: the rectified rig
    /// Set when the pairs are a user's rig's unrectified images: every step that matches them
    /// (compare, study, acquire_dataset, score_formats) rectifies keypoints with it (match_pair).
    std::shared_ptr<const landmarks::Calibration> rig;
};
/// All scenes under `root`; InputError for a scene without disp1.png unless `need_truth` is
/// false (then its ground-truth columns stay empty).
Dataset middlebury_dataset(const std::filesystem::path& root, bool need_truth = true);
/// KITTI odometry pairs [pairs.first, pairs.last) of a sequence (calib.txt of the sequence), by
/// frames::stereo_stream's rule: an open end (util::parse_range's) takes every pair to the end,
/// a range past the data is an InputError naming `what` and the sequence's length.
Dataset kitti_dataset(const std::filesystem::path& kitti_root, const std::string& sequence, util::Range pairs,
                      const std::string& what = "the stereo pair range");
/// A calibration file of a user's rig: `harris-cosim calibrate`'s OpenCV storage (.yml, .yaml,
/// .json: intrinsics, distortion, rectifying rotations and projections) or a KITTI-style
/// calib.txt (any other name: images already rectified). Throws hc::InputError naming it.
landmarks::Calibration read_rig_calibration(const std::filesystem::path& file);
/// Stereo pairs left[i], right[i] of a user's rig (unrectified images, read as grey), with
/// `rig` to rectify their keypoints. InputError naming an image that is missing, unreadable or
/// of another size than the calibration's, or when the lists differ in length or are empty.
Dataset rig_dataset(const std::vector<std::filesystem::path>& left, const std::vector<std::filesystem::path>& right,
                    const landmarks::Calibration& rig);

/// A dataset as the `landmarks` command chooses it (its flags in brackets): a user's rig
/// (--calib with --left and --right), else Middlebury (--middlebury, default
/// <data>/middlebury2006/half) or KITTI (--kitti, default <data>/kitti) by --dataset.
struct DatasetChoice {
    frames::RigSource rig;                  ///< a user's rig (--calib, --left, --right), when given
    std::string dataset = "middlebury";     ///< middlebury or kitti
    std::string middlebury, kitti;          ///< the dataset's folder ("": under the data directory)
    std::string data;                       ///< the data directory (--data; "": frames::data_dir's default)
    bool need_truth = true;                 ///< Middlebury: require disp1.png (false: --no-truth)
    std::string sequence = "01";            ///< KITTI sequence
    std::string pairs = "0:10";             ///< KITTI stereo pair range a:b (--pairs)
};
/// The chosen dataset; `root` receives its folder (left empty for a rig). InputError naming
/// the flags for a rig without its images, images without a rig, no folder and no data
/// directory, or another --dataset.
Dataset open_dataset(const DatasetChoice& c, std::filesystem::path& root);

}  // namespace hc::landmarks
