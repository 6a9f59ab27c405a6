// kitti.cpp: the stereo-landmark front end: camera-frame points to top-view range-bearing
// observations, KITTI poses and odometry, trajectory files, data association (Mahalanobis
// gate + descriptor check), runs over a sequence and synthetic stereo landmarks.
#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "slam/slam.hpp"
#include "stereo/stereo.hpp"

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

Vec2 odometry_between(const Pose& a, const Pose& b) {
    const double dth = wrap_angle(b(2) - a(2));
    const double h = a(2) + dth / 2;
    const Vec2 d = b.head<2>() - a.head<2>();
    return {d.x() * std::cos(h) + d.y() * std::sin(h), dth};
}

std::vector<Vec2> noisy_odometry(const std::vector<Pose>& truth, const OdometryModel& model, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<Vec2> u;
    for (size_t k = 1; k < truth.size(); ++k) {
        const Vec2 e = odometry_between(truth[k - 1], truth[k]);
        const double nx = g(rng), nt = g(rng);
        u.emplace_back(e(0) + model.sigma_dx * nx, e(1) + model.sigma_dtheta * nt);
    }
    return u;
}

std::vector<Pose> dead_reckoning(const Pose& start, const std::vector<Vec2>& odometry) {
    std::vector<Pose> out{start};
    for (const auto& u : odometry) out.push_back(move(out.back(), u, Vec2::Zero()));
    return out;
}

std::string kitti_trajectory(const std::vector<Pose>& poses) {
    std::ostringstream o;
    o << std::setprecision(9);
    for (const auto& r : poses) {
        const Mat34 T = kitti_pose(r);
        for (int i = 0; i < 12; ++i) o << (i ? " " : "") << T(i / 4, i % 4);
        o << '\n';
    }
    return o.str();
}

std::string tum_trajectory(const std::vector<Pose>& poses, const std::vector<double>& timestamps) {
    if (timestamps.size() != poses.size()) throw std::invalid_argument("tum_trajectory: one timestamp per pose");
    std::ostringstream o;
    o << std::setprecision(9);
    for (size_t k = 0; k < poses.size(); ++k) {
        const Pose& r = poses[k];
        // rotation about y by −θ: q = (0, sin(−θ/2), 0, cos(−θ/2))
        o << timestamps[k] << ' ' << -r(1) << ' ' << 0.0 << ' ' << r(0) << ' ' << 0.0 << ' ' << std::sin(-r(2) / 2)
          << ' ' << 0.0 << ' ' << std::cos(-r(2) / 2) << '\n';
    }
    return o.str();
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
    if (max_hamming < 0) throw InputError("--max-hamming must not be negative");
    if (forget_after < 0) throw InputError("--forget-after must not be negative");
    if (max_observations < 0) throw InputError("--max-observations must not be negative");
    if (!(min_range >= 0 && max_range > min_range)) throw InputError("the observation range limits are not 0 <= min < max");
}

LandmarkSlam::LandmarkSlam(const Pose& start, const OdometryModel& odometry, const AssociationConfig& association)
    : ekf_(start, Mat3::Zero(), 256), N_(odometry.covariance()),
      lateral_variance_(odometry.sigma_lateral * odometry.sigma_lateral), cfg_(association),
      gate_(chi2_quantile(association.gate_probability, 2)) {
    cfg_.validate();
    if (!(odometry.sigma_dx > 0) || !(odometry.sigma_dtheta > 0))
        throw InputError("the odometry noise must be positive");
    if (!(odometry.sigma_lateral >= 0)) throw InputError("the lateral slip must not be negative");
}

FrameStats LandmarkSlam::first_frame(const StereoFrame& frame) { return observe(frame); }

FrameStats LandmarkSlam::next_frame(const Vec2& odometry, const StereoFrame& frame) {
    ++frame_;
    ekf_.predict(odometry, N_, lateral_variance_);
    return observe(frame);
}

FrameStats LandmarkSlam::observe(const StereoFrame& frame) {
    FrameStats st;
    std::vector<RangeBearing> obs;
    std::vector<const StereoLandmarkObs*> src;
    for (const auto& o : frame) {
        if (!(o.p_cam.z() > 0)) continue;
        const RangeBearing rb = camera_to_range_bearing(o.p_cam, o.cov);
        if (rb.y(0) < cfg_.min_range || rb.y(0) > cfg_.max_range) continue;
        obs.push_back(rb);
        src.push_back(&o);
    }
    if (cfg_.max_observations > 0 && static_cast<int>(obs.size()) > cfg_.max_observations) {
        std::vector<int> order(obs.size());
        for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
        std::stable_sort(order.begin(), order.end(),
                         [&](int a, int b) { return obs[a].R.determinant() < obs[b].R.determinant(); });
        order.resize(cfg_.max_observations);
        std::sort(order.begin(), order.end());
        std::vector<RangeBearing> kept_obs;
        std::vector<const StereoLandmarkObs*> kept_src;
        for (int i : order) {
            kept_obs.push_back(obs[i]);
            kept_src.push_back(src[i]);
        }
        obs.swap(kept_obs);
        src.swap(kept_src);
    }
    st.observed = static_cast<int>(obs.size());
    struct Pair {
        double d2;
        int obs, id;
    };
    std::vector<Pair> pairs;
    std::vector<char> descriptor_failed(obs.size(), 0);
    for (int i = 0; i < static_cast<int>(obs.size()); ++i) {
        for (int id : ekf_.landmark_ids()) {
            const double d2 = ekf_.innovation(id, obs[i].y, obs[i].R).mahalanobis2;
            if (!(d2 <= gate_)) continue;
            const auto& stored = descriptors_[id];
            if (cfg_.check_descriptor && !stored.empty() && !src[i]->descriptor.empty() &&
                hamming_distance(stored, src[i]->descriptor) > cfg_.max_hamming) {
                descriptor_failed[i] = 1;
                continue;
            }
            pairs.push_back({d2, i, id});
        }
    }
    std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.d2 < b.d2; });
    std::vector<char> obs_used(obs.size(), 0);
    std::unordered_map<int, char> id_used;
    std::vector<std::pair<int, int>> matches;
    for (const auto& p : pairs) {
        if (obs_used[p.obs] || id_used[p.id]) continue;
        obs_used[p.obs] = 1;
        id_used[p.id] = 1;
        matches.emplace_back(p.obs, p.id);
    }
    for (const auto& [i, id] : matches) {
        ekf_.correct(id, obs[i].y, obs[i].R);
        last_seen_[id] = frame_;
        if (src[i]->id_hint >= 0 && hints_[id] >= 0) {
            ++st.matched_with_hints;
            st.matched_agreeing += src[i]->id_hint == hints_[id];
        }
    }
    st.matched = static_cast<int>(matches.size());
    for (int i = 0; i < static_cast<int>(obs.size()); ++i) {
        if (obs_used[i]) continue;
        st.rejected_by_descriptor += descriptor_failed[i];
        const int id = next_id_++;
        ekf_.add_landmark(id, obs[i].y, obs[i].R);
        descriptors_[id] = src[i]->descriptor;
        hints_[id] = src[i]->id_hint;
        last_seen_[id] = frame_;
        ++st.added;
    }
    if (cfg_.forget_after > 0) {
        const std::vector<int> ids = ekf_.landmark_ids();
        for (int id : ids) {
            if (frame_ - last_seen_[id] >= cfg_.forget_after) {
                ekf_.remove_landmark(id);
                descriptors_.erase(id);
                last_seen_.erase(id);
                hints_.erase(id);
                ++st.removed;
            }
        }
    }
    st.map_size = ekf_.landmark_count();
    return st;
}

SequenceRun run_sequence(const std::vector<Mat34>& poses, const std::vector<StereoFrame>& frames,
                         const OdometryModel& odometry, const AssociationConfig& association, uint64_t seed) {
    if (poses.size() < 2) throw InputError("a sequence needs at least 2 poses, got " + std::to_string(poses.size()));
    if (frames.size() != poses.size())
        throw InputError("a sequence needs one landmark frame per pose: " + std::to_string(frames.size()) +
                         " frames, " + std::to_string(poses.size()) + " poses");
    SequenceRun run;
    for (const auto& T : poses) run.truth.push_back(planar_pose(T));
    run.odometry = noisy_odometry(run.truth, odometry, seed);
    run.dead_reckoning = slam::dead_reckoning(run.truth[0], run.odometry);
    LandmarkSlam slam(run.truth[0], odometry, association);
    run.frames.push_back(slam.first_frame(frames[0]));
    run.estimate.push_back(slam.filter().pose());
    run.pose_cov.push_back(slam.filter().pose_covariance());
    for (size_t k = 1; k < frames.size(); ++k) {
        run.frames.push_back(slam.next_frame(run.odometry[k - 1], frames[k]));
        run.estimate.push_back(slam.filter().pose());
        run.pose_cov.push_back(slam.filter().pose_covariance());
    }
    run.ate_slam = absolute_trajectory_error(run.estimate, run.truth);
    run.ate_dead_reckoning = absolute_trajectory_error(run.dead_reckoning, run.truth);
    for (int id : slam.filter().landmark_ids()) {
        run.map.push_back(slam.filter().landmark(id));
        run.map_cov.push_back(slam.filter().landmark_covariance(id));
    }
    return run;
}

StereoLandmarkObs triangulate(const StereoCamera& cam, double u, double v, double d) {
    // hc::stereo's triangulation of (u_l, v_l, u_r, v_r) = (u, v, u - d, v) on the rig
    // P0 = [fx 0 cx 0; 0 fx cy 0; 0 0 1 0], P1 = P0 with tx1 = -fx b
    stereo::RectifiedRig rig;
    rig.fx = rig.fy = cam.fx;
    rig.cx0 = rig.cx1 = cam.cx;
    rig.cy = cam.cy;
    rig.tx1 = -cam.fx * cam.baseline;
    const stereo::Point3 t = stereo::triangulate(rig, u, v, u - d, v);
    // J = d(x, y, z)/d(u, v, d) = d(x, y, z)/d(u_l, v_l, u_r, v_r) * d(u_l, v_l, u_r, v_r)/d(u, v, d)
    Eigen::Matrix<double, 3, 4> J4;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 4; ++k) J4(i, k) = t.J[i][k];
    Eigen::Matrix<double, 4, 3> M;
    M << 1, 0, 0,   //
        0, 1, 0,    //
        1, 0, -1,   //
        0, 1, 0;
    const Eigen::Matrix3d J = J4 * M;
    StereoLandmarkObs o;
    o.p_cam = Eigen::Vector3d(t.p[0], t.p[1], t.p[2]);
    o.cov = cam.sigma_pixel * cam.sigma_pixel * J * J.transpose();
    return o;
}

std::vector<StereoFrame> synthesize_stereo_frames(const std::vector<Mat34>& poses, const StereoCamera& cam,
                                                  int count, int flip_bits, uint64_t seed) {
    if (poses.empty()) throw InputError("synthetic landmarks need at least one pose");
    if (count < 1) throw InputError("the synthetic world is empty: the landmark count must be at least 1");
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<int> pick(0, static_cast<int>(poses.size()) - 1), byte(0, 255), bit(0, 255);
    std::uniform_real_distribution<double> lateral(4, 30), forward(0, 40), height(-3, 1), side(0, 1);
    std::normal_distribution<double> g(0.0, cam.sigma_pixel);
    std::vector<Eigen::Vector3d> world;
    std::vector<std::vector<uint8_t>> desc;
    for (int i = 0; i < count; ++i) {
        const Mat34& T = poses[pick(rng)];
        const double s = side(rng) < 0.5 ? -1 : 1;
        const Eigen::Vector3d pc(s * lateral(rng), height(rng), forward(rng));
        world.push_back(T.leftCols<3>() * pc + T.col(3));
        std::vector<uint8_t> d(32);
        for (auto& b : d) b = static_cast<uint8_t>(byte(rng));
        desc.push_back(std::move(d));
    }
    std::vector<StereoFrame> frames;
    for (const auto& T : poses) {
        StereoFrame f;
        const Eigen::Matrix3d Rt = T.leftCols<3>().transpose();
        for (int i = 0; i < count; ++i) {
            const Eigen::Vector3d p = Rt * (world[i] - T.col(3));
            if (p.z() < 2 || p.z() > 60) continue;
            const double u = cam.fx * p.x() / p.z() + cam.cx, v = cam.fx * p.y() / p.z() + cam.cy;
            const double d = cam.fx * cam.baseline / p.z();
            if (u < 0 || u >= cam.width || u - d < 0 || v < 0 || v >= cam.height) continue;
            const double un = u + g(rng), vn = v + g(rng), dn = d + g(rng);
            if (dn < 1) continue;
            StereoLandmarkObs o = triangulate(cam, un, vn, dn);
            o.descriptor = desc[i];
            o.id_hint = i;
            for (int b = 0; b < flip_bits; ++b) {
                const int k = bit(rng);
                o.descriptor[k / 8] ^= static_cast<uint8_t>(1u << (k % 8));
            }
            f.push_back(std::move(o));
        }
        frames.push_back(std::move(f));
    }
    return frames;
}

}  // namespace hc::slam
