// synthetic.hpp: synthetic inputs of the filter (slam.hpp): noisy odometry on a true
// trajectory, and stereo landmarks of a synthetic world seen through KITTI's rectified rig
// (mapping/landmarks/stereo.hpp) along a trajectory.
#pragma once

#include "mapping/slam/ekf.hpp"
#include "mapping/slam/observations.hpp"
#include "mapping/landmarks/stereo.hpp"

#include <cstdint>
#include <random>
#include <vector>

namespace hc::slam {

/// Synthetic odometry on a real trajectory: the exact relative pose between consecutive
/// ground-truth poses (between()) with Gaussian noise of these standard deviations added.
struct SyntheticOdometry {
    double sigma_dx = 0.1;        ///< m per frame, forward
    double sigma_dy = 0.02;       ///< m per frame, sideways
    double sigma_dtheta = 0.002;  ///< rad per frame
    Mat3 covariance() const;
    void validate() const;        ///< InputError unless every σ is positive
};
/// between(truth[k-1], truth[k]) plus noise of `model` (seeded), one motion per step.
std::vector<Motion> noisy_odometry(const std::vector<Pose>& truth, const SyntheticOdometry& model, uint64_t seed);

/// The rig of the synthetic landmarks: KITTI's rectified cameras 0 and 1 (sequences 00-02):
/// fx = fy = 718.856 px, principal point (607.1928, 185.2157) px for both, the right camera
/// 0.5372 m to the right (tx1 = -fx * 0.5372), images 1241 x 376.
landmarks::RectifiedRig synthetic_rig();
/// Synthetic stereo landmarks along a trajectory: `count` world points scattered on both
/// sides of the path (lateral 4..30 m, height -3..1 m in camera y), each with a random
/// 256-bit descriptor; frame k lists the points in front of camera k (z 2..60 m) that
/// project inside both images of `rig` (landmarks::project), measured with `noise` (drawn on
/// u_l, v_l, u_r, v_r; a point whose noisy disparity is below 1 px is dropped), triangulated
/// (landmarks::triangulate, with their first-order covariance under `noise`), and the descriptor
/// with `flip_bits` random bits flipped; id_hint = the world point's index (to score the
/// association, never used by it). Throws InputError when the rig has no image size.
std::vector<StereoFrame> synthesize_stereo_frames(const std::vector<Mat34>& poses, const landmarks::RectifiedRig& rig,
                                                  const landmarks::PixelNoise& noise, int count, int flip_bits,
                                                  uint64_t seed);
/// synthesize_stereo_frames frame by frame (the same frames, drawn as they are asked for):
/// the world is laid out on construction (InputError as above), next() gives frame k of
/// poses[k].
class SyntheticFrames {
public:
    SyntheticFrames(std::vector<Mat34> poses, const landmarks::RectifiedRig& rig, const landmarks::PixelNoise& noise,
                    int count, int flip_bits, uint64_t seed);
    bool next(StereoFrame& frame);

private:
    std::vector<Mat34> poses_;
    landmarks::RectifiedRig rig_;
    landmarks::PixelNoise noise_;
    int flip_bits_;
    std::mt19937_64 rng_;
    std::vector<Eigen::Vector3d> world_;
    std::vector<std::vector<uint8_t>> desc_;
    size_t next_ = 0;
};

}  // namespace hc::slam
