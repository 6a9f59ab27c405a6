// trajectory.cpp: KITTI poses, dead reckoning, trajectory files and timestamps, 6-DoF poses of
// a top-view trajectory.
#include "mapping/slam/trajectory.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

namespace hc::slam {

namespace {
/// Calls `fn(line, where)` on each line of `file` that holds more than white space (with
/// `skip_comments`, nor starts with '#'), `where` naming the file and line for an error
/// message; `what` names the file when it cannot be read.
template <class Fn>
void for_each_line(const std::filesystem::path& file, const std::string& what, bool skip_comments, Fn&& fn) {
    std::ifstream f(file);
    if (!f) throw InputError("cannot read the " + what + " '" + file.string() + "'");
    std::string line;
    int lineno = 0;
    while (std::getline(f, line)) {
        ++lineno;
        const size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || (skip_comments && line[first] == '#')) continue;
        fn(line, "'" + file.string() + "' line " + std::to_string(lineno));
    }
}
}  // namespace

std::vector<Mat34> read_kitti_poses(const std::filesystem::path& file) {
    std::vector<Mat34> poses;
    for_each_line(file, "poses file", false, [&](const std::string& line, const std::string& where) {
        std::istringstream ss(line);
        Mat34 T;
        for (int i = 0; i < 12; ++i) {
            if (!(ss >> T(i / 4, i % 4)) || !std::isfinite(T(i / 4, i % 4)))
                throw InputError(where + ": expected 12 numbers (a 3x4 pose)");
        }
        std::string extra;
        if (ss >> extra) throw InputError(where + ": more than 12 numbers");
        poses.push_back(T);
    });
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
    std::vector<Mat34> poses;
    size_t width = 0;   // 12: KITTI, 8: TUM
    for_each_line(file, "ground-truth file", true, [&](const std::string& line, const std::string& where) {
        const auto v = numbers_of(line);
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
    });
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
    std::vector<double> t;
    for_each_line(file, "timestamps file", false, [&](const std::string& line, const std::string& where) {
        const auto v = numbers_of(line);
        if (!v || v->size() != 1) throw InputError(where + ": expected one number (s)");
        t.push_back(v->front());
    });
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

}  // namespace hc::slam
