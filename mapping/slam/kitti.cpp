// kitti.cpp: the stereo-landmark front end: camera-frame points to top-view range-bearing
// observations, KITTI poses and odometry, trajectory files, data association (Mahalanobis
// gate + descriptor check), runs over a sequence and synthetic stereo landmarks.
#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "mapping/slam/slam.hpp"
#include "mapping/landmarks/stereo.hpp"

namespace hc::slam {

RangeBearing camera_to_range_bearing(const Eigen::Vector3d& p, const Eigen::Matrix3d& cov,
                                     Eigen::Matrix<double, 2, 3>* Y_p) {
    // robot frame: forward = z_cam, left = −x_cam
    const double r2 = p.x() * p.x() + p.z() * p.z(), r = std::sqrt(r2);
    Eigen::Matrix<double, 2, 3> J;
    J << p.x() / r, 0, p.z() / r,   //
        -p.z() / r2, 0, p.x() / r2;
    if (Y_p) *Y_p = J;
    RangeBearing rb;
    rb.y = Vec2(r, std::atan2(-p.x(), p.z()));
    rb.R = J * cov * J.transpose();
    rb.R = (rb.R + rb.R.transpose()) / 2;
    return rb;
}

Mat2 observation_noise_at(const StereoLandmarkObs& o, const Vec2& q) {
    const Eigen::Vector3d p(-q.y(), 0, q.x());   // the camera's x and z
    if (!(q.x() > 0) || !(o.p_cam.z() > 0)) return camera_to_range_bearing(o.p_cam, o.cov).R;
    // ∂(a, w)/∂(x, z) at the measurement, and its inverse ∂(x, z)/∂(a, w) at q
    const double xm = o.p_cam.x(), zm = o.p_cam.z();
    Mat2 K_m, Kinv_q;
    K_m << 1 / zm, -xm / (zm * zm), 0, -1 / (zm * zm);
    Kinv_q << p.z(), -p.x() * p.z(), 0, -p.z() * p.z();
    const Mat2 T = Kinv_q * K_m;
    Mat2 C;
    C << o.cov(0, 0), o.cov(0, 2), o.cov(2, 0), o.cov(2, 2);
    const Mat2 Cq = T * C * T.transpose();
    Eigen::Matrix3d C3 = Eigen::Matrix3d::Zero();   // the height does not enter the top view
    C3(0, 0) = Cq(0, 0);
    C3(0, 2) = Cq(0, 1);
    C3(2, 0) = Cq(1, 0);
    C3(2, 2) = Cq(1, 1);
    return camera_to_range_bearing(p, C3).R;
}

std::vector<Mat34> read_kitti_poses(const std::filesystem::path& file) {
    std::ifstream f(file);
    if (!f) throw InputError("cannot read the poses file '" + file.string() + "'");
    std::vector<Mat34> poses;
    std::string line;
    int lineno = 0;
    while (std::getline(f, line)) {
        ++lineno;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream ss(line);
        Mat34 T;
        for (int i = 0; i < 12; ++i) {
            if (!(ss >> T(i / 4, i % 4)) || !std::isfinite(T(i / 4, i % 4)))
                throw InputError("'" + file.string() + "' line " + std::to_string(lineno) +
                                 ": expected 12 numbers (a 3x4 pose)");
        }
        std::string extra;
        if (ss >> extra)
            throw InputError("'" + file.string() + "' line " + std::to_string(lineno) + ": more than 12 numbers");
        poses.push_back(T);
    }
    if (poses.empty()) throw InputError("the poses file '" + file.string() + "' holds no pose");
    return poses;
}

Pose planar_pose(const Mat34& T) { return {T(2, 3), -T(0, 3), std::atan2(-T(0, 2), T(2, 2))}; }

Mat34 kitti_pose(const Pose& r) {
    const double c = std::cos(r(2)), s = std::sin(r(2));
    Mat34 T;
    // rotation about the camera's y axis by −θ; camera position (−y, 0, x)
    T << c, 0, -s, -r(1),   //
        0, 1, 0, 0,         //
        s, 0, c, r(0);
    return T;
}

Mat3 SyntheticOdometry::covariance() const {
    return Eigen::Vector3d(sigma_dx * sigma_dx, sigma_dy * sigma_dy, sigma_dtheta * sigma_dtheta).asDiagonal();
}

void SyntheticOdometry::validate() const {
    if (!(sigma_dx > 0) || !(sigma_dy > 0) || !(sigma_dtheta > 0))
        throw InputError("the synthetic odometry noise (--sigma-dx, --sigma-dy, --sigma-dtheta) must be positive");
}

std::vector<Motion> noisy_odometry(const std::vector<Pose>& truth, const SyntheticOdometry& model, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Motion> u;
    for (size_t k = 1; k < truth.size(); ++k) {
        const Motion e = between(truth[k - 1], truth[k]);
        const double nx = g(rng), ny = g(rng), nt = g(rng);
        u.emplace_back(e(0) + model.sigma_dx * nx, e(1) + model.sigma_dy * ny, e(2) + model.sigma_dtheta * nt);
    }
    return u;
}

std::vector<Pose> dead_reckoning(const Pose& start, const std::vector<Motion>& motions) {
    std::vector<Pose> out{start};
    for (const auto& u : motions) out.push_back(compose(out.back(), u));
    return out;
}

std::string kitti_trajectory(const std::vector<Pose>& poses) {
    std::vector<Mat34> T;
    T.reserve(poses.size());
    for (const auto& r : poses) T.push_back(kitti_pose(r));
    return kitti_trajectory(T);
}

std::string kitti_line(const Mat34& T) {
    std::ostringstream o;
    o << std::setprecision(9);
    for (int i = 0; i < 12; ++i) o << (i ? " " : "") << T(i / 4, i % 4);
    o << '\n';
    return o.str();
}

std::string tum_line(const Mat34& T, double timestamp) {
    Eigen::Quaterniond q(Mat3(T.leftCols<3>()));
    q.normalize();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    std::ostringstream o;
    o << std::setprecision(9) << timestamp << ' ' << T(0, 3) << ' ' << T(1, 3) << ' ' << T(2, 3) << ' ' << q.x() << ' '
      << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
    return o.str();
}

std::string kitti_trajectory(const std::vector<Mat34>& poses) {
    std::string s;
    for (const auto& T : poses) s += kitti_line(T);
    return s;
}

std::string tum_trajectory(const std::vector<Mat34>& poses, const std::vector<double>& timestamps) {
    if (timestamps.size() != poses.size()) throw std::invalid_argument("tum_trajectory: one timestamp per pose");
    std::string s;
    for (size_t k = 0; k < poses.size(); ++k) s += tum_line(poses[k], timestamps[k]);
    return s;
}

namespace {
/// The numbers of a line, or nullopt at the first word that is not a finite number.
std::optional<std::vector<double>> numbers_of(const std::string& line) {
    std::istringstream ss(line);
    std::vector<double> v;
    std::string w;
    while (ss >> w) {
        char* end = nullptr;
        const double x = std::strtod(w.c_str(), &end);
        if (end != w.c_str() + w.size() || !std::isfinite(x)) return std::nullopt;
        v.push_back(x);
    }
    return v;
}
}  // namespace

std::vector<Mat34> read_trajectory_file(const std::filesystem::path& file, std::vector<double>* times) {
    if (times) times->clear();
    std::ifstream f(file);
    if (!f) throw InputError("cannot read the ground-truth file '" + file.string() + "'");
    std::vector<Mat34> poses;
    std::string line;
    int lineno = 0;
    size_t width = 0;   // 12: KITTI, 8: TUM
    while (std::getline(f, line)) {
        ++lineno;
        const size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        const auto v = numbers_of(line);
        const std::string where = "'" + file.string() + "' line " + std::to_string(lineno);
        if (!v) throw InputError(where + ": not a number");
        if (width == 0) {
            if (v->size() != 12 && v->size() != 8)
                throw InputError(where + ": " + std::to_string(v->size()) +
                                 " numbers, neither a KITTI pose (12) nor a TUM pose (8: t tx ty tz qx qy qz qw)");
            width = v->size();
        }
        if (v->size() != width)
            throw InputError(where + ": " + std::to_string(v->size()) + " numbers, the file's poses have " +
                             std::to_string(width));
        Mat34 T;
        if (width == 12) {
            for (int i = 0; i < 12; ++i) T(i / 4, i % 4) = (*v)[i];
        } else {
            const Eigen::Quaterniond q((*v)[7], (*v)[4], (*v)[5], (*v)[6]);
            if (!(q.norm() > 0.5 && q.norm() < 2)) throw InputError(where + ": the quaternion is not of unit length");
            T << q.normalized().toRotationMatrix(), Eigen::Vector3d((*v)[1], (*v)[2], (*v)[3]);
            if (times) times->push_back((*v)[0]);
        }
        poses.push_back(T);
    }
    if (poses.empty()) throw InputError("the ground-truth file '" + file.string() + "' holds no pose");
    return poses;
}

std::vector<Mat34> truth_by_timestamp(const std::vector<Mat34>& poses, const std::vector<double>& pose_times,
                                      const std::vector<double>& frame_times, double tolerance,
                                      const std::string& truth_name, bool overlap) {
    if (!(tolerance > 0)) throw InputError("the ground truth's time tolerance must be positive");
    if (pose_times.size() != poses.size())
        throw InputError("the ground truth " + truth_name + " has " + std::to_string(poses.size()) + " poses but " +
                         std::to_string(pose_times.size()) + " timestamps");
    std::vector<Mat34> out;
    for (size_t k = 0; k < frame_times.size(); ++k) {
        size_t best = poses.size();
        double gap = 0;
        for (size_t i = 0; i < pose_times.size(); ++i) {
            const double d = std::abs(pose_times[i] - frame_times[k]);
            if (best == poses.size() || d < gap) best = i, gap = d;
        }
        if (best == poses.size() || !(gap <= tolerance)) {
            if (overlap) break;
            std::ostringstream msg;
            msg << "the ground truth " << truth_name << " has no pose within " << tolerance << " s of frame " << k
                << " (time " << frame_times[k] << " s); give --score-overlap to score the frames before it only, or "
                << "a larger --truth-time-tolerance";
            throw InputError(msg.str());
        }
        out.push_back(poses[best]);
    }
    return out;
}

std::vector<double> read_timestamps(const std::filesystem::path& file) {
    std::ifstream f(file);
    if (!f) throw InputError("cannot read the timestamps file '" + file.string() + "'");
    std::vector<double> t;
    std::string line;
    int lineno = 0;
    while (std::getline(f, line)) {
        ++lineno;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const auto v = numbers_of(line);
        if (!v || v->size() != 1)
            throw InputError("'" + file.string() + "' line " + std::to_string(lineno) + ": expected one number (s)");
        t.push_back(v->front());
    }
    if (t.empty()) throw InputError("the timestamps file '" + file.string() + "' holds no timestamp");
    return t;
}

std::vector<Mat34> spatial_poses(const std::vector<Pose>& planar, const std::vector<Mat3>& tilt,
                                 const std::vector<double>& height) {
    if ((!tilt.empty() && tilt.size() != planar.size()) || (!height.empty() && height.size() != planar.size()))
        throw std::invalid_argument("spatial_poses: one tilt and one height per pose");
    std::vector<Mat34> out;
    out.reserve(planar.size());
    for (size_t k = 0; k < planar.size(); ++k) {
        Mat34 T = kitti_pose(planar[k]);
        if (!tilt.empty()) T.leftCols<3>() = Mat3(T.leftCols<3>()) * tilt[k];
        if (!height.empty()) T(1, 3) = height[k];
        out.push_back(T);
    }
    return out;
}

double absolute_trajectory_error_3d(const std::vector<Mat34>& estimate, const std::vector<Mat34>& truth) {
    if (estimate.size() != truth.size() || truth.empty())
        throw std::invalid_argument("absolute_trajectory_error_3d: trajectories of different or zero length");
    double s = 0;
    for (size_t k = 0; k < truth.size(); ++k) s += (estimate[k].col(3) - truth[k].col(3)).squaredNorm();
    return std::sqrt(s / static_cast<double>(truth.size()));
}

double absolute_trajectory_error(const std::vector<Pose>& estimate, const std::vector<Pose>& truth) {
    if (estimate.size() != truth.size() || truth.empty())
        throw std::invalid_argument("absolute_trajectory_error: trajectories of different or zero length");
    double s = 0;
    for (size_t k = 0; k < truth.size(); ++k) s += (estimate[k] - truth[k]).head<2>().squaredNorm();
    return std::sqrt(s / truth.size());
}

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
    return cfg_.noise_at_prediction ? observation_noise_at(o, at) : rb.R;
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
        ekf_.correct(id, obs[i].y, noise_of(frame[src[i]], obs[i], predicted_point(id)));
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

namespace {
/// A frame's observation placed in the world with the true pose: top-view point, covariance.
std::pair<Vec2, Mat2> world_point(const StereoLandmarkObs& o, const Pose& truth) {
    const auto [q, C] = top_view(o);
    const double c = std::cos(truth(2)), s = std::sin(truth(2));
    Mat2 R;
    R << c, -s, s, c;
    return {truth.head<2>() + R * q, R * C * R.transpose()};
}
}  // namespace

namespace {
/// The metrics of a run's running sums, with the per-frame NEES when they were kept.
TrajectoryMetrics finished_metrics(const TrajectoryScore& score, std::vector<double> nees) {
    TrajectoryMetrics m = score.metrics();
    m.nees = std::move(nees);
    return m;
}
/// A 6-DoF pose of a top-view pose with a tilt and a height (spatial_poses of one pose), or
/// level at height 0 without (`tilt` nullptr).
Mat34 spatial_pose(const Pose& planar, const Mat3* tilt, double height) {
    Mat34 T = kitti_pose(planar);
    if (!tilt) return T;
    T.leftCols<3>() = Mat3(T.leftCols<3>()) * *tilt;
    T(1, 3) = height;
    return T;
}
}  // namespace

void RunTotals::add(const FrameStats& f) {
    matched += f.matched;
    observed += f.observed;
    peak = std::max(peak, f.map_size);
    final_map_size = f.map_size;
    hinted += f.matched_with_hints;
    agreeing += f.matched_agreeing;
    checked += f.matched_checked;
    wrong += f.matched_wrong;
    jcbb_cut += f.jcbb_complete ? 0 : 1;
}

FrameSource frames_of(const std::vector<StereoFrame>& frames) {
    return [&frames, k = size_t{0}](StereoFrame& f) mutable {
        if (k >= frames.size()) return false;
        f = frames[k++];
        return true;
    };
}

FilterRun::FilterRun(const Pose& start, const AssociationConfig& association, std::vector<Pose> truth,
                     RunRecord record)
    : slam_(start, association), truth_(std::move(truth)), record_(std::move(record)), dead_reckoning_(start),
      wrong_gate_(chi2_quantile(0.999, 2)) {}

void FilterRun::set_spatial(const Mat3& tilt, double height) {
    tilt_ = tilt;
    height_ = height;
    spatial_ = true;
}

void FilterRun::first_frame(const StereoFrame& frame) { after_frame(slam_.first_frame(frame), frame); }

void FilterRun::next_frame(const Motion& u, const Mat3& Q, const StereoFrame& frame) {
    if (record_.keep) {
        run_.odometry.push_back(u);
        run_.odometry_cov.push_back(Q);
    }
    Mat3 R_r, R_u;   // the odometry alone: its pose and covariance integrated
    dead_reckoning_ = compose(dead_reckoning_, u, &R_r, &R_u);
    dead_reckoning_cov_ = R_r * dead_reckoning_cov_ * R_r.transpose() + R_u * Q * R_u.transpose();
    after_frame(slam_.next_frame(u, Q, frame), frame);
}

void FilterRun::after_frame(const FrameStats& stats, const StereoFrame& frame) {
    const size_t k = run_.frame_count;
    FrameRecord rec;
    rec.frame = k;
    rec.stats = stats;
    FrameStats& st = rec.stats;
    if (k < truth_.size()) {   // scored: each match against its landmark's first observation
        for (const auto& [i, id] : slam_.last_matches()) {
            const auto& [p0, C0] = first_seen_.at(id);
            const auto [p, C] = world_point(frame[static_cast<size_t>(i)], truth_[k]);
            const Vec2 e = p - p0;
            ++st.matched_checked;
            st.matched_wrong += e.dot((C + C0).ldlt().solve(e)) > wrong_gate_;
        }
        for (const auto& [i, id] : slam_.last_added())
            first_seen_.emplace(id, world_point(frame[static_cast<size_t>(i)], truth_[k]));
    }
    for (int id : slam_.last_removed()) first_seen_.erase(id);
    rec.estimate = slam_.filter().pose();
    rec.pose_cov = slam_.filter().pose_covariance();
    rec.dead_reckoning = dead_reckoning_;
    rec.nees_slam = rec.nees_odometry = std::numeric_limits<double>::quiet_NaN();
    if (k < truth_.size()) {   // the metrics' running sums
        rec.truth = &truth_[k];
        rec.nees_slam = slam_score_.add(rec.estimate, truth_[k], &rec.pose_cov);
        rec.nees_odometry = odometry_score_.add(dead_reckoning_, truth_[k], &dead_reckoning_cov_);
    }
    record_frame(rec);
}

void FilterRun::record_frame(FrameRecord& rec) {
    const size_t k = rec.frame;
    rec.estimate_3d = spatial_pose(rec.estimate, spatial_ ? &tilt_ : nullptr, height_);
    rec.dead_reckoning_3d = spatial_pose(rec.dead_reckoning, spatial_ ? &tilt_ : nullptr, height_);
    if (rec.truth && k < record_.truth_3d.size()) {   // the 3-D APE's sums
        rec.truth_3d = &record_.truth_3d[k];
        ape_3d_slam_ss_ += (rec.estimate_3d.col(3) - rec.truth_3d->col(3)).squaredNorm();
        ape_3d_odometry_ss_ += (rec.dead_reckoning_3d.col(3) - rec.truth_3d->col(3)).squaredNorm();
        ++scored_3d_;
    }
    ++run_.frame_count;
    run_.scored_frames += rec.truth != nullptr;
    run_.totals.add(rec.stats);
    if (record_.keep) {
        run_.frames.push_back(rec.stats);
        run_.estimate.push_back(rec.estimate);
        run_.pose_cov.push_back(rec.pose_cov);
        run_.dead_reckoning.push_back(rec.dead_reckoning);
        run_.estimate_3d.push_back(rec.estimate_3d);
        run_.dead_reckoning_3d.push_back(rec.dead_reckoning_3d);
        if (rec.truth) {
            slam_nees_.push_back(rec.nees_slam);
            odometry_nees_.push_back(rec.nees_odometry);
        }
        if (rec.truth_3d) run_.truth_3d.push_back(*rec.truth_3d);
    }
    if (record_.sink) record_.sink(rec);
}

SequenceRun FilterRun::finish() {
    const size_t n = run_.frame_count;
    if (n < 2) throw InputError("a sequence needs at least 2 frames, got " + std::to_string(n));
    if (truth_.size() > n)
        throw InputError("a sequence needs at most one landmark frame per pose: " + std::to_string(n) + " frames, " +
                         std::to_string(truth_.size()) + " poses");
    for (int id : slam_.filter().landmark_ids()) {
        run_.map.push_back(slam_.filter().landmark(id));
        run_.map_cov.push_back(slam_.filter().landmark_covariance(id));
    }
    // the scores summed as the frames came
    if (record_.keep) run_.truth = truth_;
    if (!truth_.empty()) {
        run_.slam_metrics = finished_metrics(slam_score_, std::move(slam_nees_));
        run_.odometry_metrics = finished_metrics(odometry_score_, std::move(odometry_nees_));
        run_.ate_slam = run_.slam_metrics.ape;
        run_.ate_dead_reckoning = run_.odometry_metrics.ape;
    }
    if (scored_3d_ > 0) {
        run_.ape_3d_slam = std::sqrt(ape_3d_slam_ss_ / static_cast<double>(scored_3d_));
        run_.ape_3d_dead_reckoning = std::sqrt(ape_3d_odometry_ss_ / static_cast<double>(scored_3d_));
    }
    return std::move(run_);
}

SequenceRun run_filter(const std::vector<StereoFrame>& frames, const std::vector<Motion>& motions,
                       const std::vector<Mat3>& motion_cov, const Pose& start, const AssociationConfig& association,
                       const std::vector<Pose>& truth) {
    if (frames.size() < 2) throw InputError("a sequence needs at least 2 frames, got " + std::to_string(frames.size()));
    if (motions.size() + 1 != frames.size() || motion_cov.size() != motions.size())
        throw InputError("a sequence needs one motion and covariance between consecutive frames");
    if (truth.size() > frames.size())
        throw InputError("a sequence needs at most one landmark frame per pose: " + std::to_string(frames.size()) +
                         " frames, " + std::to_string(truth.size()) + " poses");
    FilterRun run(start, association, truth);
    run.first_frame(frames[0]);
    for (size_t k = 1; k < frames.size(); ++k) run.next_frame(motions[k - 1], motion_cov[k - 1], frames[k]);
    return run.finish();
}

SequenceRun run_sequence(const std::vector<Mat34>& poses, const std::vector<StereoFrame>& frames,
                         const SyntheticOdometry& odometry, const AssociationConfig& association, uint64_t seed) {
    if (poses.size() >= 2 && frames.size() != poses.size())
        throw InputError("a sequence needs one landmark frame per pose: " + std::to_string(frames.size()) +
                         " frames, " + std::to_string(poses.size()) + " poses");
    return run_sequence(poses, frames_of(frames), odometry, association, seed);
}

SequenceRun run_sequence(const std::vector<Mat34>& poses, const FrameSource& frames, const SyntheticOdometry& odometry,
                         const AssociationConfig& association, uint64_t seed, RunRecord record) {
    if (poses.size() < 2) throw InputError("a sequence needs at least 2 poses, got " + std::to_string(poses.size()));
    odometry.validate();
    std::vector<Pose> truth;
    for (const auto& T : poses) truth.push_back(planar_pose(T));
    const std::vector<Motion> u = noisy_odometry(truth, odometry, seed);
    const Mat3 Q = odometry.covariance();
    record.truth_3d = poses;
    FilterRun run(truth[0], association, truth, std::move(record));
    StereoFrame frame;
    size_t count = 0;
    for (; frames(frame); ++count) {
        if (count >= poses.size()) continue;   // counted, not run: refused below
        if (count == 0) run.first_frame(frame);
        else run.next_frame(u[count - 1], Q, frame);
    }
    if (count != poses.size())
        throw InputError("a sequence needs one landmark frame per pose: " + std::to_string(count) + " frames, " +
                         std::to_string(poses.size()) + " poses");
    return run.finish();
}

landmarks::RectifiedRig synthetic_rig() {
    const double fx = 718.856, baseline = 0.5372;
    landmarks::RectifiedRig r;
    r.fx = r.fy = fx;
    r.cx0 = r.cx1 = 607.1928;
    r.cy = 185.2157;
    r.tx1 = -fx * baseline;
    r.width = 1241;
    r.height = 376;
    return r;
}

StereoLandmarkObs to_observation(const landmarks::Point3& t) {
    StereoLandmarkObs o;
    o.p_cam = Eigen::Vector3d(t.p[0], t.p[1], t.p[2]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) o.cov(i, j) = t.cov[i][j];
    return o;
}

SyntheticFrames::SyntheticFrames(std::vector<Mat34> poses, const landmarks::RectifiedRig& rig,
                                 const landmarks::PixelNoise& noise, int count, int flip_bits, uint64_t seed)
    : poses_(std::move(poses)), rig_(rig), noise_(noise), flip_bits_(flip_bits), rng_(seed) {
    if (poses_.empty()) throw InputError("synthetic landmarks need at least one pose");
    if (rig.width < 1 || rig.height < 1) throw InputError("synthetic landmarks need a rig with an image size");
    if (count < 1) throw InputError("the synthetic world is empty: the landmark count must be at least 1");
    std::uniform_int_distribution<int> pick(0, static_cast<int>(poses_.size()) - 1), byte(0, 255);
    std::uniform_real_distribution<double> lateral(4, 30), forward(0, 40), height(-3, 1), side(0, 1);
    for (int i = 0; i < count; ++i) {
        const Mat34& T = poses_[pick(rng_)];
        const double s = side(rng_) < 0.5 ? -1 : 1;
        const Eigen::Vector3d pc(s * lateral(rng_), height(rng_), forward(rng_));
        world_.push_back(T.leftCols<3>() * pc + T.col(3));
        std::vector<uint8_t> d(32);
        for (auto& b : d) b = static_cast<uint8_t>(byte(rng_));
        desc_.push_back(std::move(d));
    }
}

bool SyntheticFrames::next(StereoFrame& f) {
    if (next_ >= poses_.size()) return false;
    const Mat34& T = poses_[next_++];
    std::uniform_int_distribution<int> bit(0, 255);
    f.clear();
    const Eigen::Matrix3d Rt = T.leftCols<3>().transpose();
    for (size_t i = 0; i < world_.size(); ++i) {
        const Eigen::Vector3d p = Rt * (world_[i] - T.col(3));
        if (p.z() < 2 || p.z() > 60) continue;
        const double q[3] = {p.x(), p.y(), p.z()};
        const landmarks::StereoPixels m = landmarks::project(rig_, q);
        if (m.u_l < 0 || m.u_l >= rig_.width || m.u_r < 0 || m.v_l < 0 || m.v_l >= rig_.height) continue;
        const landmarks::StereoPixels n = noise_.perturb(m, rng_);
        if (n.u_l - n.u_r < 1) continue;
        StereoLandmarkObs o = to_observation(landmarks::triangulate(rig_, n, noise_));
        o.descriptor = desc_[i];
        o.id_hint = static_cast<int>(i);
        for (int b = 0; b < flip_bits_; ++b) {
            const int k = bit(rng_);
            o.descriptor[static_cast<size_t>(k / 8)] ^= static_cast<uint8_t>(1u << (k % 8));
        }
        f.push_back(std::move(o));
    }
    return true;
}

std::vector<StereoFrame> synthesize_stereo_frames(const std::vector<Mat34>& poses, const landmarks::RectifiedRig& rig,
                                                  const landmarks::PixelNoise& noise, int count, int flip_bits,
                                                  uint64_t seed) {
    SyntheticFrames source(poses, rig, noise, count, flip_bits, seed);
    std::vector<StereoFrame> frames;
    StereoFrame f;
    while (source.next(f)) frames.push_back(std::move(f));
    return frames;
}

}  // namespace hc::slam
