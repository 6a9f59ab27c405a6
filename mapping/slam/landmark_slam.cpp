// landmark_slam.cpp: the descriptor check and the landmark filter: selection of a frame's
// observations, gating (Mahalanobis gate + descriptor check), association, correction,
// initialisation and removal of landmarks.
#include "mapping/slam/landmark_slam.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "mapping/slam/association.hpp"
#include "mapping/slam/consistency.hpp"

namespace hc::slam {

int hamming_distance(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    const size_t n = std::min(a.size(), b.size());
    int d = 8 * static_cast<int>(std::max(a.size(), b.size()) - n);
    for (size_t i = 0; i < n; ++i) d += std::popcount(static_cast<unsigned>(a[i] ^ b[i]));
    return d;
}

void AssociationConfig::validate() const {
    if (!(gate_probability > 0 && gate_probability < 1))
        throw InputError("the gate probability must be in (0, 1), got " + std::to_string(gate_probability));
    if (!(joint_probability > 0 && joint_probability < 1))
        throw InputError("the joint gate probability must be in (0, 1), got " + std::to_string(joint_probability));
    if (max_nodes < 1) throw InputError("the JCBB node limit must be at least 1");
    if (!(max_hamming_fraction >= 0 && max_hamming_fraction <= 1))
        throw InputError("--max-hamming-fraction must be in [0, 1], got " + std::to_string(max_hamming_fraction));
    if (forget_after < 0) throw InputError("--forget-after must not be negative");
    if (max_observations < 0) throw InputError("--max-observations must not be negative");
    if (!(odometry_inlier_noise_scale >= 1 && std::isfinite(odometry_inlier_noise_scale)))
        throw InputError("--odometry-inlier-noise-scale must be a finite number of at least 1, got " +
                         std::to_string(odometry_inlier_noise_scale));
    if (!(min_range >= 0 && max_range > min_range)) throw InputError("the observation range limits are not 0 <= min < max");
}

int hamming_threshold(double fraction, size_t bytes) {
    return static_cast<int>(std::floor(fraction * 8.0 * static_cast<double>(bytes) + 1e-9));
}

LandmarkSlam::LandmarkSlam(const Pose& start, const AssociationConfig& association)
    : ekf_(start, Mat3::Zero(), 256), cfg_(association), gate_(chi2_quantile(association.gate_probability, 2)) {
    cfg_.validate();
}

FrameStats LandmarkSlam::first_frame(const StereoFrame& frame) { return observe(frame); }

FrameStats LandmarkSlam::next_frame(const Motion& u, const Mat3& Q, const StereoFrame& frame) {
    ++frame_;
    ekf_.predict_motion(u, Q);
    return observe(frame);
}

namespace {
/// The frame's observations the filter uses: in front of the camera and within the range
/// limits, then at most `max_observations` of them (the smallest det R, in frame order);
/// their indices in the frame into `src`.
std::vector<RangeBearing> select_observations(const StereoFrame& frame, const AssociationConfig& cfg,
                                              std::vector<int>& src) {
    std::vector<RangeBearing> obs;
    for (int k = 0; k < static_cast<int>(frame.size()); ++k) {
        const auto& o = frame[k];
        if (!(o.p_cam.z() > 0)) continue;
        const RangeBearing rb = camera_to_range_bearing(o.p_cam, o.cov);
        if (rb.y(0) < cfg.min_range || rb.y(0) > cfg.max_range) continue;
        obs.push_back(rb);
        src.push_back(k);
    }
    if (cfg.max_observations > 0 && static_cast<int>(obs.size()) > cfg.max_observations) {
        std::vector<int> order(obs.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
        std::stable_sort(order.begin(), order.end(),
                         [&](int a, int b) { return obs[a].R.determinant() < obs[b].R.determinant(); });
        order.resize(cfg.max_observations);
        std::sort(order.begin(), order.end());
        std::vector<RangeBearing> kept_obs;
        std::vector<int> kept_src;
        for (int i : order) {
            kept_obs.push_back(obs[i]);
            kept_src.push_back(src[i]);
        }
        obs.swap(kept_obs);
        src.swap(kept_src);
    }
    return obs;
}
}  // namespace

FrameStats LandmarkSlam::observe(const StereoFrame& frame) {
    FrameStats st;
    last_added_.clear();
    last_removed_.clear();
    std::vector<int> src;   // index in the frame
    const std::vector<RangeBearing> obs = select_observations(frame, cfg_, src);
    st.observed = static_cast<int>(obs.size());
    std::vector<char> descriptor_failed(obs.size(), 0);
    std::vector<std::vector<Mat2>> noise;
    const std::vector<std::vector<int>> candidates = gate_candidates(frame, obs, src, descriptor_failed, noise);
    const Association a = cfg_.method == AssociationMethod::Jcbb
                              ? associate_jcbb(ekf_, obs, candidates, cfg_.joint_probability, cfg_.max_nodes, noise)
                              : associate_nearest(ekf_, obs, candidates, noise);
    st.jcbb_complete = a.complete;
    correct_matched(frame, obs, src, a.landmark, st);
    st.matched = a.pairings;
    add_unmatched(frame, obs, src, a.landmark, descriptor_failed, st);
    if (cfg_.forget_after > 0) forget_unseen(st);
    st.map_size = ekf_.landmark_count();
    return st;
}

Mat2 LandmarkSlam::noise_of(const StereoLandmarkObs& o, const RangeBearing& rb, const Vec2& at) const {
    const Mat2 R = cfg_.noise_at_prediction ? observation_noise_at(o, at) : rb.R;
    return o.odometry_inlier ? Mat2(cfg_.odometry_inlier_noise_scale * R) : R;
}

Vec2 LandmarkSlam::predicted_point(int id) const { return to_frame(ekf_.pose(), ekf_.landmark(id)); }

std::vector<std::vector<int>> LandmarkSlam::gate_candidates(const StereoFrame& frame,
                                                            const std::vector<RangeBearing>& obs,
                                                            const std::vector<int>& src,
                                                            std::vector<char>& descriptor_failed,
                                                            std::vector<std::vector<Mat2>>& noise) {
    std::vector<std::vector<int>> candidates(obs.size());
    noise.assign(obs.size(), {});
    // what each landmark's innovation and noise owe to the filter alone, once per frame
    const std::vector<int> ids = ekf_.landmark_ids();
    std::vector<PredictedObservation> predicted;
    std::vector<Vec2> at;   // where the filter predicts each landmark, in the robot's frame
    predicted.reserve(ids.size());
    at.reserve(ids.size());
    for (int id : ids) {
        predicted.push_back(ekf_.predicted_observation(id));
        at.push_back(predicted_point(id));
    }
    for (int i = 0; i < static_cast<int>(obs.size()); ++i) {
        const StereoLandmarkObs& o = frame[src[i]];
        for (size_t j = 0; j < ids.size(); ++j) {
            const int id = ids[j];
            const Mat2 R = noise_of(o, obs[i], at[j]);
            const double d2 = Ekf::innovation(predicted[j], obs[i].y, R).mahalanobis2;
            if (!(d2 <= gate_)) continue;
            const auto& stored = descriptors_[id];
            if (cfg_.check_descriptor && !stored.empty() && !o.descriptor.empty() &&
                hamming_distance(stored, o.descriptor) >
                    hamming_threshold(cfg_.max_hamming_fraction, std::max(stored.size(), o.descriptor.size()))) {
                descriptor_failed[i] = 1;
                continue;
            }
            candidates[i].push_back(id);
            noise[i].push_back(R);
        }
    }
    return candidates;
}

void LandmarkSlam::correct_matched(const StereoFrame& frame, const std::vector<RangeBearing>& obs,
                                   const std::vector<int>& src, const std::vector<int>& landmark, FrameStats& st) {
    last_matches_.clear();
    for (int i = 0; i < static_cast<int>(obs.size()); ++i) {
        const int id = landmark[i];
        if (id < 0) continue;
        // the noise where the filter now predicts the landmark (earlier corrections moved it)
        if (cfg_.correct_with_odometry_inliers || !frame[src[i]].odometry_inlier)
            ekf_.correct(id, obs[i].y, noise_of(frame[src[i]], obs[i], predicted_point(id)));
        else
            ++st.matched_not_corrected;
        last_seen_[id] = frame_;
        last_matches_.emplace_back(src[i], id);
        const int hint = frame[src[i]].id_hint;
        if (hint >= 0 && hints_[id] >= 0) {
            ++st.matched_with_hints;
            st.matched_agreeing += hint == hints_[id];
        }
    }
}

void LandmarkSlam::add_unmatched(const StereoFrame& frame, const std::vector<RangeBearing>& obs,
                                 const std::vector<int>& src, const std::vector<int>& landmark,
                                 const std::vector<char>& descriptor_failed, FrameStats& st) {
    for (int i = 0; i < static_cast<int>(obs.size()); ++i) {
        if (landmark[i] >= 0) continue;
        st.rejected_by_descriptor += descriptor_failed[i];
        const int id = next_id_++;
        ekf_.add_landmark(id, obs[i].y, obs[i].R);
        descriptors_[id] = frame[src[i]].descriptor;
        hints_[id] = frame[src[i]].id_hint;
        last_seen_[id] = frame_;
        origin_[id] = {frame_, src[i]};
        last_added_.emplace_back(src[i], id);
        ++st.added;
    }
}

void LandmarkSlam::forget_unseen(FrameStats& st) {
    const std::vector<int> ids = ekf_.landmark_ids();
    for (int id : ids) {
        if (frame_ - last_seen_[id] >= cfg_.forget_after) {
            ekf_.remove_landmark(id);
            descriptors_.erase(id);
            last_seen_.erase(id);
            hints_.erase(id);
            origin_.erase(id);
            last_removed_.push_back(id);
            ++st.removed;
        }
    }
}

}  // namespace hc::slam
