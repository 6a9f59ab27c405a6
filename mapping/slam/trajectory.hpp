// trajectory.hpp: trajectories of the sequences (slam.hpp): KITTI poses and their top view,
// dead reckoning, trajectory files (KITTI and TUM, written and read), timestamps and the pairing
// of ground-truth poses with frames by time, and the 6-DoF poses of a top-view trajectory.
#pragma once

#include "mapping/slam/ekf.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace hc::slam {

/// Reads a KITTI poses file (12 numbers a line: the 3×4 [R|t] of camera 0 in the first
/// camera's frame). Throws InputError naming the file and line when absent, unreadable,
/// malformed or empty.
std::vector<Mat34> read_kitti_poses(const std::filesystem::path& file);
/// The top view of a KITTI pose: (z, −x, yaw) with yaw = atan2(−R(0,2), R(2,2)).
Pose planar_pose(const Mat34& T);
/// A KITTI pose from a top-view pose (height 0, rotation about the camera's y axis).
Mat34 kitti_pose(const Pose& r);
/// Dead reckoning: the poses that compose() integrates from `start` with `motions`.
std::vector<Pose> dead_reckoning(const Pose& start, const std::vector<Motion>& motions);

/// Trajectory files: KITTI (12 numbers a line) and TUM ("t tx ty tz qx qy qz qw", qw ≥ 0) of
/// 6-DoF poses (camera 0 in the first camera's frame: x right, y down, z forward); a top-view
/// trajectory as KITTI poses at height 0 (kitti_pose).
std::string kitti_trajectory(const std::vector<Mat34>& poses);
std::string tum_trajectory(const std::vector<Mat34>& poses, const std::vector<double>& timestamps);
std::string kitti_trajectory(const std::vector<Pose>& poses);
/// One line of each: kitti_trajectory's and tum_trajectory's line of one pose (the same text).
std::string kitti_line(const Mat34& pose);
std::string tum_line(const Mat34& pose, double timestamp);
/// Reads a trajectory file of ground-truth poses of camera 0 in the first camera's frame (KITTI's
/// convention): KITTI (12 numbers a line, read_kitti_poses) or TUM ("t tx ty tz qx qy qz qw",
/// lines starting with '#' skipped), told apart by the count of numbers on its first pose line.
/// `times` given: receives a TUM file's timestamps, one per pose (left empty for a KITTI file,
/// which has none). Throws InputError naming the file and line when absent, malformed or empty.
std::vector<Mat34> read_trajectory_file(const std::filesystem::path& file, std::vector<double>* times = nullptr);
/// The ground-truth pose of each frame by timestamp: for frame k, the pose whose time is nearest
/// `frame_times[k]` (the earlier on a tie), when within `tolerance` (s). A frame without a pose
/// within it is an InputError naming `truth_name`, the frame and its time, unless `overlap`:
/// then the poses of the frames before the first such frame are returned (those frames are
/// scored). InputError when `tolerance` is not positive or the counts of poses and times differ.
std::vector<Mat34> truth_by_timestamp(const std::vector<Mat34>& poses, const std::vector<double>& pose_times,
                                      const std::vector<double>& frame_times, double tolerance,
                                      const std::string& truth_name, bool overlap);
/// Reads timestamps, one number (s) a line (KITTI's times.txt). InputError naming the file and
/// line when absent, malformed or empty.
std::vector<double> read_timestamps(const std::filesystem::path& file);
/// The 6-DoF poses of a top-view trajectory: rotation Y(θ)·tilt[k] (tilt_of's factors), position
/// (−y, height[k], x) in the camera frame. `tilt` and `height` empty: level, height 0 (kitti_pose).
/// Throws std::invalid_argument when a non-empty `tilt` or `height` is not one per pose.
std::vector<Mat34> spatial_poses(const std::vector<Pose>& planar, const std::vector<Mat3>& tilt = {},
                                 const std::vector<double>& height = {});

}  // namespace hc::slam
