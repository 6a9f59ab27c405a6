// landmark_frames.cpp: landmarks::Landmark -> slam::StereoLandmarkObs, and a KITTI sequence
// through the filter on the pipeline's or synthetic landmarks.
#include "mapping/slam/landmark_frames.hpp"
#include "mapping/slam/trajectory.hpp"

#include <algorithm>
#include <sstream>

#include "io/frames/frames.hpp"
#include "io/frames/pairs.hpp"

namespace hc::slam {

landmarks::PipelineOptions kitti_pipeline_defaults() {
    landmarks::PipelineOptions o;
    o.descriptor = landmarks::Descriptor::brief;
    return o;
}

StereoLandmarkObs to_observation(const landmarks::Landmark& l) {
    StereoLandmarkObs o;
    o.p_cam = Eigen::Vector3d(l.p_cam[0], l.p_cam[1], l.p_cam[2]);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) o.cov(r, c) = l.cov(r, c);
    o.descriptor = l.descriptor;
    return o;
}

namespace {
std::vector<StereoFrame> as_frames(const std::vector<std::vector<landmarks::Landmark>>& landmarks) {
    std::vector<StereoFrame> frames;
    for (const auto& frame : landmarks) {
        StereoFrame f;
        f.reserve(frame.size());
        for (const auto& l : frame) f.push_back(to_observation(l));
        frames.push_back(std::move(f));
    }
    return frames;
}
}  // namespace

std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const landmarks::PipelineOptions& o) {
    return as_frames(landmarks::acquire_dataset(ds, o));
}

std::vector<StereoFrame> landmark_frames(const landmarks::Dataset& ds, const std::vector<landmarks::PairKeypoints>& kp,
                                         const landmarks::PipelineOptions& o) {
    return as_frames(landmarks::acquire_dataset(ds, kp, o));
}

FrameSource landmark_stream(int pairs, landmarks::PairCornerStream::PairAt pair_at, const landmarks::RectifiedRig& calib,
                            const landmarks::PipelineOptions& o, std::shared_ptr<const landmarks::Calibration> rig) {
    auto one = std::make_shared<landmarks::Dataset>();
    one->calib = {calib};
    one->rig = std::move(rig);
    one->pairs.resize(1);
    auto corners = std::make_shared<landmarks::PairCornerStream>(o.detector, pairs, std::move(pair_at), o.corners);
    return [one, corners, o](StereoFrame& frame) {
        landmarks::PairKeypoints kp;
        if (!corners->next(one->pairs.front(), kp)) return false;
        const auto l = landmarks::acquire_dataset(*one, {kp}, o);
        frame.clear();
        frame.reserve(l.front().size());
        for (const auto& x : l.front()) frame.push_back(to_observation(x));
        return true;
    };
}

namespace {

/// A file's name in quotes, for messages.
std::string quoted(const std::filesystem::path& p) {
    std::string s = "'";
    s += p.string();
    s += '\'';
    return s;
}

/// InputError unless the pipeline's options are valid and its descriptor binary.
void check_pipeline(const landmarks::PipelineOptions& po) {
    landmarks::validate(po.grid);
    landmarks::check_combination(po.descriptor, po.detector, landmarks::Norm::automatic);
    if (landmarks::make_descriptor(po.descriptor, po.grid)->descriptorType() != CV_8U)
        throw InputError("--descriptor " + landmarks::descriptor_name(po.descriptor) +
                         " is not binary: visual odometry and the association compare Hamming distances");
}

void report_landmarks(const KittiRunOptions& o, int pairs, const std::string& of) {
    const landmarks::PipelineOptions& po = o.pipeline;
    if (o.progress)
        o.progress("landmarks of " + std::to_string(pairs) + " stereo pairs of " + of + " (" +
                   landmarks::detector_name(po.detector) + " corners, " + landmarks::descriptor_name(po.descriptor) +
                   " descriptor)");
}

/// The landmark pipeline on the sequence's stereo pairs `r` (landmark_stream); `rig`, the first
/// pair's calibration (the sequence's calib.txt).
FrameSource stereo_frames(const std::filesystem::path& kitti, const std::string& sequence, util::Range r,
                          const KittiRunOptions& o, landmarks::RectifiedRig& rig) {
    report_landmarks(o, r.last - r.first, sequence);
    rig = landmarks::kitti_dataset(kitti, sequence, {r.first, r.first + 1}).calib.front();
    return landmark_stream(
        r.last - r.first,
        [kitti, sequence, first = r.first](int k) {
            return landmarks::kitti_dataset(kitti, sequence, {first + k, first + k + 1}).pairs.front();
        },
        rig, o.pipeline);
}

/// The pairs o.pairs picks of `n` (all when empty), checked against them (frames::pairs_within).
util::Range picked_pairs(const KittiRunOptions& o, int n, const std::string& of) {
    const util::Range all{0, 1 << 30};
    return frames::pairs_within(o.pairs.empty() ? all : util::parse_range(o.pairs, "--pairs"), n,
                                "--pairs " + o.pairs, of);
}

/// The poses of the pairs `r`: truth[r.first, r.last), as many of them as `truth` holds, in the
/// frame of the run's first camera as the run's estimate is (truth[r.first]⁻¹ · truth[k]; the
/// truth is in pair 0's camera frame, so a range from pair 0 keeps it as it is).
std::vector<Mat34> truth_of_pairs(const std::vector<Mat34>& truth, util::Range r) {
    const auto end = std::min(truth.size(), static_cast<size_t>(r.last));
    const auto first = std::min(end, static_cast<size_t>(r.first));
    std::vector<Mat34> out(truth.begin() + static_cast<long>(first), truth.begin() + static_cast<long>(end));
    if (first == 0 || out.empty()) return out;
    const Mat3 to_first = out.front().leftCols<3>().transpose();
    const Eigen::Vector3d origin = out.front().col(3);
    for (Mat34& T : out) {
        T.leftCols<3>() = (to_first * T.leftCols<3>()).eval();
        T.col(3) = to_first * (T.col(3) - origin);
    }
    return out;
}

/// The ground truth a run scores with, for `frames` frames: `truth` itself when it has one
/// pose per frame or none; with o.score_overlap, its first `frames` poses when longer (a
/// shorter one is scored on its own length); else InputError naming both counts.
std::vector<Mat34> reconcile_truth(std::vector<Mat34> truth, size_t frames, const std::string& truth_name,
                                   const KittiRunOptions& o) {
    if (truth.empty() || truth.size() == frames) return truth;
    if (!o.score_overlap)
        throw InputError("the ground truth " + truth_name + " has " + std::to_string(truth.size()) + " poses for " +
                         std::to_string(frames) + " stereo pairs; give --score-overlap to score the first " +
                         std::to_string(std::min(truth.size(), frames)) + " frames only");
    if (truth.size() > frames) truth.resize(frames);
    return truth;
}

/// Validates the options that do not depend on the frames; the rig of visual odometry on
/// pixel residuals starts as synthetic_rig() (the synthetic landmarks' rig).
VisualOdometryConfig checked_options(const KittiRunOptions& o) {
    o.association.validate();
    VisualOdometryConfig vo = o.vo;
    vo.rig = synthetic_rig();
    vo.validate();
    if (!o.visual_odometry) o.synthetic.validate();
    if (o.stereo_landmarks) check_pipeline(o.pipeline);
    if (!(o.frame_period > 0)) throw InputError("--frame-period must be positive");
    if (!(o.truth_time_tolerance > 0)) throw InputError("--truth-time-tolerance must be positive");
    return vo;
}

/// The TUM timestamps of a run's frames: a times.txt's, or frame index × a period.
struct FrameTimes {
    std::vector<double> times;   // empty: index × period
    double period = 0.1;
    std::string from;
    size_t first = 0;            // the run's first pair: frame k is pair first + k
    double at(size_t k) const {
        return times.empty() ? static_cast<double>(first + k) * period : times[first + k];
    }
};

/// The first `n` timestamps of a times.txt; InputError when it has fewer.
std::vector<double> frame_times(const std::filesystem::path& times, size_t n) {
    std::vector<double> t = read_timestamps(times);
    if (t.size() < n)
        throw InputError(quoted(times) + " has " + std::to_string(t.size()) + " timestamps for " + std::to_string(n) +
                         " frames");
    t.resize(n);
    return t;
}

/// The timestamps of the pairs `r`: from `times` when it exists, else pair index × o.frame_period.
FrameTimes timestamps_of(const std::filesystem::path& times, util::Range r, const KittiRunOptions& o) {
    FrameTimes t;
    t.period = o.frame_period;
    t.first = static_cast<size_t>(r.first);
    if (!times.empty() && std::filesystem::exists(times)) {
        t.times = frame_times(times, static_cast<size_t>(r.last));
        t.from = "the sequence's times.txt";
        return t;
    }
    std::ostringstream period;
    period << o.frame_period;
    t.from = "frame index × " + period.str() + " s (no times.txt)";
    return t;
}

/// The filter over `frames` with the odometry of `o`, scored against `truth` (none, one per
/// frame, or the first frames'); each frame's record to o.sink with its timestamp.
KittiRun run_frames(const FrameSource& frames, size_t count, const std::vector<Mat34>& truth,
                    const VisualOdometryConfig& vo, const KittiRunOptions& o, const FrameTimes& times) {
    RunRecord record;
    record.keep = o.keep_frames;
    record.truth_3d = truth;
    if (o.sink)
        record.sink = [&times, &sink = o.sink](const FrameRecord& f) {
            FrameRecord stamped = f;
            stamped.timestamp = times.at(f.frame);
            sink(stamped);
        };
    KittiRun r;
    if (o.visual_odometry) {
        std::vector<Pose> planar;
        for (const auto& T : truth) planar.push_back(planar_pose(T));
        r.run = run_visual_stream(frames, planar, vo, o.association, &r.vo, std::move(record));
    } else {
        if (truth.size() != count)
            throw InputError("--odometry synthetic is made from the ground truth: it needs one true pose per frame, "
                             "got " + std::to_string(truth.size()) + " poses for " + std::to_string(count) +
                             " frames");
        r.run = run_sequence(truth, frames, o.synthetic, o.association, o.seed, std::move(record));
    }
    r.run.timestamps_from = times.from;
    if (o.keep_frames)
        for (size_t k = 0; k < r.run.frame_count; ++k) r.run.timestamps.push_back(times.at(k));
    return r;
}

}  // namespace

KittiRun run_kitti_sequence(const std::filesystem::path& kitti, const std::string& sequence, const KittiRunOptions& o) {
    const std::filesystem::path poses_file = frames::kitti_poses_file(kitti, sequence);
    const std::filesystem::path times_file = frames::kitti_sequence_dir(kitti, sequence) / "times.txt";
    const bool own_truth = o.truth.empty() && std::filesystem::exists(poses_file);
    std::vector<double> truth_times;   // a TUM file's
    std::vector<Mat34> truth = !o.truth.empty() ? read_trajectory_file(o.truth, &truth_times)
                               : own_truth      ? read_kitti_poses(poses_file)
                                                : std::vector<Mat34>{};
    const std::string truth_name = quoted(own_truth ? poses_file : o.truth);
    VisualOdometryConfig vo = checked_options(o);
    std::string pairing = "in file order";
    FrameSource frames;
    size_t count = 0;
    util::Range r;
    const frames::KittiSequence seq = o.stereo_landmarks ? frames::open_kitti(kitti, sequence) : frames::KittiSequence{};
    if (o.stereo_landmarks) {
        const int pairs = seq.pairs();
        r = picked_pairs(o, pairs, "KITTI sequence '" + seq.root.string() + "'");
        if (r.last - r.first < 2)
            throw InputError("KITTI sequence " + sequence + " has fewer than 2 stereo pairs" +
                             (o.pairs.empty() ? "" : " in --pairs " + o.pairs));
        if (!truth_times.empty() && std::filesystem::exists(times_file)) {
            truth = truth_by_timestamp(truth, truth_times, frame_times(times_file, static_cast<size_t>(pairs)),
                                       o.truth_time_tolerance, truth_name, o.score_overlap);
            std::ostringstream tol;
            tol << o.truth_time_tolerance;
            pairing = "by timestamp (the nearest pose within " + tol.str() + " s of each frame's time in times.txt)";
        }
        truth = truth_of_pairs(reconcile_truth(std::move(truth), static_cast<size_t>(pairs), truth_name, o), r);
        frames = stereo_frames(kitti, sequence, r, o, *vo.rig);
        count = static_cast<size_t>(r.last - r.first);
    } else {
        if (truth.empty())
            throw InputError("--landmarks-from synthetic lays its points along the ground truth: sequence " + sequence +
                             " has no " + poses_file.string() + "; give --truth FILE");
        r = picked_pairs(o, static_cast<int>(truth.size()), "the ground truth " + truth_name);
        truth = truth_of_pairs(truth, r);
        if (truth.size() < 2) throw InputError("sequence " + sequence + " has fewer than 2 poses");
        if (o.flip_bits < 0) throw InputError("--flip-bits must not be negative");
        auto synthetic = std::make_shared<SyntheticFrames>(truth, *vo.rig, landmarks::PixelNoise{}, o.synthetic_count,
                                                           o.flip_bits, o.seed);
        frames = [synthetic](StereoFrame& f) { return synthetic->next(f); };
        count = truth.size();
    }
    KittiRun run = run_frames(frames, count, truth, vo, o, timestamps_of(times_file, r, o));
    if (!truth.empty()) run.run.truth_pairing = pairing;
    return run;
}

KittiRun run_rig_sequence(const frames::RigSource& rig, const KittiRunOptions& o) {
    if (!o.stereo_landmarks)
        throw InputError("--landmarks-from synthetic makes its own frames: leave out --left, --right and --calib");
    const frames::RigPairs lists = frames::open_rig(rig);
    std::vector<Mat34> truth = o.truth.empty() ? std::vector<Mat34>{} : read_trajectory_file(o.truth);
    VisualOdometryConfig vo = checked_options(o);
    const auto calibration = std::make_shared<const landmarks::Calibration>(landmarks::read_rig_calibration(lists.calib));
    const std::vector<std::filesystem::path>& left = lists.left;
    const std::vector<std::filesystem::path>& right = lists.right;
    const util::Range r = picked_pairs(o, static_cast<int>(left.size()), "the rig's --left/--right");
    const int pairs = r.last - r.first;
    if (pairs < 2)
        throw InputError("the rig's --left/--right give fewer than 2 stereo pairs" +
                         (o.pairs.empty() ? std::string() : " in --pairs " + o.pairs));
    truth = truth_of_pairs(reconcile_truth(std::move(truth), left.size(), quoted(o.truth), o), r);
    report_landmarks(o, pairs, "the rig");
    vo.rig = calibration->rectified;
    // each pair read (and checked against the calibration) when the corner stream reaches it
    const auto pair_at = [left, right, calibration, first = r.first](int k) {
        const auto i = static_cast<size_t>(first + k);
        return landmarks::rig_dataset({left[i]}, {right[i]}, *calibration).pairs.front();
    };
    const FrameSource frames = landmark_stream(pairs, pair_at, calibration->rectified, o.pipeline, calibration);
    KittiRun run = run_frames(frames, static_cast<size_t>(pairs), truth, vo, o, timestamps_of({}, r, o));
    if (!truth.empty()) run.run.truth_pairing = "in file order (a rig has no frame times)";
    return run;
}

}  // namespace hc::slam
