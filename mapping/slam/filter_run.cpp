// filter_run.cpp: a run of the landmark filter frame by frame with its records, running
// metrics and wrong-association check, and the runs over a sequence.
#include "mapping/slam/filter_run.hpp"

#include <cmath>
#include <limits>

#include "mapping/slam/consistency.hpp"
#include "mapping/slam/odometry.hpp"
#include "mapping/slam/trajectory.hpp"

namespace hc::slam {

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
    not_corrected += f.matched_not_corrected;
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

}  // namespace hc::slam
