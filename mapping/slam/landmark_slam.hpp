// landmark_slam.hpp: EKF-SLAM on stereo landmark frames (slam.hpp): the association and map
// management settings, the descriptor check, the counts of a frame and the filter over frames
// (LandmarkSlam), which pairs observations with mapped landmarks by association.hpp.
#pragma once

#include "mapping/slam/ekf.hpp"
#include "mapping/slam/observations.hpp"

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hc::slam {

/// How the observations of a frame are assigned to mapped landmarks.
enum class AssociationMethod {
    Jcbb,      ///< joint compatibility branch and bound (Neira & Tardós 2001) over the gated candidates
    Nearest,   ///< individual gating: pairs taken greedily by increasing Mahalanobis distance
};

/// Data association and map management for stereo landmark frames.
struct AssociationConfig {
    AssociationMethod method = AssociationMethod::Jcbb;
    double gate_probability = 0.99;   ///< individual gate: χ²(2) quantile of this probability
    double joint_probability = 0.99;  ///< JCBB's joint gate: χ²(2k) quantile for k pairings
    long max_nodes = 20000;           ///< JCBB: nodes searched at most (the best hypothesis so far is kept)
    /// Descriptor check: Hamming distance ≤ this fraction of the descriptor's bits.
    double max_hamming_fraction = 0.25;
    bool check_descriptor = true;
    int forget_after = 10;            ///< remove landmarks unseen for this many frames (0 = keep)
    double min_range = 1.0, max_range = 60.0;   ///< m: observations outside are ignored
    /// Observations used per frame (0 = all): the most precise ones (smallest det R), as
    /// each costs an O(n²) update or adds a landmark.
    int max_observations = 60;
    /// true: an observation of a mapped landmark is gated, associated and corrected with its
    /// noise at the landmark's prediction (observation_noise_at; LandmarkSlam); false: at its
    /// measurement (the covariance the frame carries).
    bool noise_at_prediction = true;
    /// false: an observation marked odometry_inlier (an inlier of the motion into its frame) is
    /// gated and associated (a mapped landmark is not added again) but does not correct the
    /// filter, so that its pixels enter the frame's prediction (the motion) and not also its
    /// update.
    bool correct_with_odometry_inliers = true;
    /// The noise of an observation marked odometry_inlier, where it corrects the filter, is
    /// its covariance times this (≥ 1): the information its pixels gave the motion not
    /// counted again in full.
    double odometry_inlier_noise_scale = 1;
    void validate() const;
};

/// The largest Hamming distance (bits) the check accepts for descriptors of `bytes` bytes:
/// floor(fraction · 8 · bytes).
int hamming_threshold(double fraction, size_t bytes);

/// Counts of one frame.
struct FrameStats {
    int observed = 0, matched = 0, added = 0, rejected_by_descriptor = 0, removed = 0, map_size = 0;
    int matched_with_hints = 0, matched_agreeing = 0;   ///< matches where both id hints are set / equal
    int matched_not_corrected = 0;   ///< matches that did not correct (correct_with_odometry_inliers false)
    /// Scored against ground truth after the run (never used by it): matches whose observation
    /// and the landmark's first observation, placed in the world with the true poses, are
    /// farther apart than their covariances allow (χ²(2) 0.999).
    int matched_checked = 0, matched_wrong = 0;
    bool jcbb_complete = true;   ///< false when JCBB stopped at max_nodes
};

/// EKF-SLAM on stereo landmark frames: prediction with a 3-DoF motion and its covariance,
/// association of the frame's observations to mapped landmarks (individual Mahalanobis gate
/// and descriptor check give the candidates; JCBB or nearest neighbour picks among them),
/// correction with the matched ones, initialisation of the unmatched ones, removal of
/// landmarks unseen for `forget_after` frames. An observation of a mapped landmark is gated,
/// associated and corrected with its noise where the filter predicts the landmark
/// (observation_noise_at), not where it was measured: a stereo point's covariance grows with
/// its depth to the fourth power, so evaluated at the measurement it gives the points whose
/// noise put them too near the most weight, and the fused map and poses come out biased. A new
/// landmark is initialised with the covariance at its measurement (there is no prediction).
class LandmarkSlam {
public:
    LandmarkSlam(const Pose& start, const AssociationConfig& association);
    /// The first frame: observations only (no motion before it).
    FrameStats first_frame(const StereoFrame& frame);
    /// A later frame: the motion from the previous frame and its covariance, then its observations.
    FrameStats next_frame(const Motion& u, const Mat3& Q, const StereoFrame& frame);
    const Ekf& filter() const { return ekf_; }
    /// The last frame's matches: (index of the observation in the frame, landmark id).
    const std::vector<std::pair<int, int>>& last_matches() const { return last_matches_; }
    /// Where landmark `id` was first observed: (frame number, index in that frame).
    std::pair<int, int> origin(int id) const { return origin_.at(id); }
    /// The last frame's new landmarks: (index of the observation in the frame, landmark id).
    const std::vector<std::pair<int, int>>& last_added() const { return last_added_; }
    /// The landmarks the last frame removed (unseen for forget_after frames).
    const std::vector<int>& last_removed() const { return last_removed_; }

private:
    FrameStats observe(const StereoFrame& frame);
    /// The noise of observation o (rb, its range-bearing form) as a landmark the filter
    /// predicts at `at` (predicted_point): there with noise_at_prediction, else rb.R; times
    /// odometry_inlier_noise_scale for an odometry inlier.
    Mat2 noise_of(const StereoLandmarkObs& o, const RangeBearing& rb, const Vec2& at) const;
    /// Where the filter predicts landmark `id`, in the robot's frame.
    Vec2 predicted_point(int id) const;
    /// The landmarks each observation may be paired with: inside the individual gate, and the
    /// descriptor check passed; descriptor_failed[i] set when a gated landmark failed that check.
    /// noise[i][c]: the noise of observation i paired with its c-th candidate (noise_of).
    /// Each landmark's prediction is computed once for all observations.
    std::vector<std::vector<int>> gate_candidates(const StereoFrame& frame, const std::vector<RangeBearing>& obs,
                                                  const std::vector<int>& src, std::vector<char>& descriptor_failed,
                                                  std::vector<std::vector<Mat2>>& noise);
    /// Corrections with the observations paired with landmark[i] >= 0; the frame's matches and
    /// the id-hint counts of `st`.
    void correct_matched(const StereoFrame& frame, const std::vector<RangeBearing>& obs, const std::vector<int>& src,
                         const std::vector<int>& landmark, FrameStats& st);
    /// A new landmark for each unpaired observation (landmark[i] < 0).
    void add_unmatched(const StereoFrame& frame, const std::vector<RangeBearing>& obs, const std::vector<int>& src,
                       const std::vector<int>& landmark, const std::vector<char>& descriptor_failed, FrameStats& st);
    /// Removal of the landmarks unseen for forget_after frames.
    void forget_unseen(FrameStats& st);
    Ekf ekf_;
    AssociationConfig cfg_;
    double gate_;
    int frame_ = 0, next_id_ = 0;
    std::unordered_map<int, std::vector<uint8_t>> descriptors_;
    std::unordered_map<int, int> last_seen_, hints_;
    std::unordered_map<int, std::pair<int, int>> origin_;
    std::vector<std::pair<int, int>> last_matches_, last_added_;
    std::vector<int> last_removed_;
};

/// Number of differing bits; descriptors of different lengths differ in every extra bit.
int hamming_distance(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b);

}  // namespace hc::slam
