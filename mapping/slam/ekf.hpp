// ekf.hpp: the filter of the 2-D top-view EKF-SLAM (slam.hpp): the geometry and the events of
// the thesis's Figure 8 with their Jacobians, and the filter itself (Ekf).
//
// Conventions
// - Robot pose r = (x, y, θ), θ in radians, wrapped to (-π, π]; robot frame: x forward,
//   y left. Landmarks are 2-D points p = (x, y) in the world frame.
// - Observation y = (range, bearing), bearing in the robot frame, wrapped.
// - Every event function returns its value and, when asked (non-null pointers), its
//   Jacobians, named from the math as in Solà's slamtb: `R_r` = ∂r'/∂r, `R_n` = ∂r'/∂n,
//   `Y_r` = ∂y/∂r, `Y_p` = ∂y/∂p, `P_r` = ∂p/∂r, `P_y` = ∂p/∂y.
// - The filter (Ekf) stores the covariance's lower triangle only (the upper one is not
//   maintained); covariance() returns the full symmetric matrix.
// - Errors in user input (bad configuration values, unreadable pose files) throw
//   hc::InputError, which the command line maps to exit status 2.
#pragma once

#include "model/util/errors.hpp"
#include <Eigen/Core>
#include <Eigen/Dense>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace hc::slam {

using Pose = Eigen::Vector3d;   ///< (x, y, θ)
using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Mat23 = Eigen::Matrix<double, 2, 3>;
using Mat32 = Eigen::Matrix<double, 3, 2>;
using Mat34 = Eigen::Matrix<double, 3, 4>;

// ---- geometry and the events of the filter (thesis Figure 8) ----------------------------

/// The angle a wrapped to (-π, π].
double wrap_angle(double a);

/// p (world) expressed in frame F = (x, y, θ) (slamtb toFrame). PF_f = ∂/∂F, PF_p = ∂/∂p.
Vec2 to_frame(const Pose& F, const Vec2& p, Mat23* PF_f = nullptr, Mat2* PF_p = nullptr);
/// pf (in frame F) expressed in the world (slamtb fromFrame). PW_f = ∂/∂F, PW_pf = ∂/∂pf.
Vec2 from_frame(const Pose& F, const Vec2& pf, Mat23* PW_f = nullptr, Mat2* PW_pf = nullptr);
/// Cartesian point -> (range, bearing) (slamtb scan). Y_p = ∂y/∂p. p must not be the origin.
Vec2 scan(const Vec2& p, Mat2* Y_p = nullptr);
/// (range, bearing) -> Cartesian point (slamtb invScan). P_y = ∂p/∂y.
Vec2 inv_scan(const Vec2& y, Mat2* P_y = nullptr);

/// Motion with odometry u = (dx, dθ) and perturbation n (added to u): the robot turns by
/// (dθ+nθ)/2, advances dx+nx, turns the other half (exact for arcs of constant curvature;
/// Solà's course code advances along the old heading, then turns).
Pose move(const Pose& r, const Vec2& u, const Vec2& n, Mat3* R_r = nullptr, Mat32* R_n = nullptr);
/// Observation of world point p from pose r: scan(to_frame(r, p)).
Vec2 observe(const Pose& r, const Vec2& p, Mat23* Y_r = nullptr, Mat2* Y_p = nullptr);
/// Inverse observation: the world point seen at y from pose r: from_frame(r, inv_scan(y)).
Vec2 inv_observe(const Pose& r, const Vec2& y, Mat23* P_r = nullptr, Mat2* P_y = nullptr);

/// A relative motion u = (dx, dy, dθ): the pose of the new robot frame in the old one.
using Motion = Eigen::Vector3d;
/// r ⊕ u: position r + R(θ)·(dx, dy), heading θ + dθ (wrapped). R_r = ∂/∂r, R_u = ∂/∂u.
/// The 3-DoF motion model of sequences (stereo odometry); exact for any planar motion.
Pose compose(const Pose& r, const Motion& u, Mat3* R_r = nullptr, Mat3* R_u = nullptr);
/// The motion u with compose(a, u) = b: u = (R(θa)ᵀ(b − a), wrap(θb − θa)).
Motion between(const Pose& a, const Pose& b);

// ---- the filter ---------------------------------------------------------------------------

/// How correct() updates the covariance. All give the same state and covariance up to
/// rounding; they differ in cost:
/// - Structured: P·Hᵀ from the 5 non-zero columns of H (robot + one landmark), then the
///   symmetric rank-2 update P ← P − W·Wᵀ with W = P·Hᵀ·L⁻ᵀ, Z = L·Lᵀ, on the lower
///   triangle. O(n²) per update, half the memory traffic of a full update.
/// - DenseKzk: dense 2×n H, K = P·Hᵀ·Z⁻¹, P ← P − K·Z·Kᵀ (the thesis's eq. 2.18). O(n²).
/// - Dense: dense 2×n H, K = P·Hᵀ·Z⁻¹, P ← (I − K·H)·P, an n×n by n×n product. O(n³).
enum class UpdateForm { Structured, DenseKzk, Dense };

/// An innovation: z = y − h(x̂) (bearing wrapped), its covariance Z and zᵀZ⁻¹z.
struct Innovation {
    Vec2 z = Vec2::Zero();
    Mat2 Z = Mat2::Zero();
    double mahalanobis2 = 0;
};

/// What a landmark's innovation owes to the filter alone, not to the observation: its
/// predicted measurement h(x̂) and H·P·Hᵀ (the innovation covariance without the noise).
struct PredictedObservation {
    Vec2 y = Vec2::Zero();
    Mat2 HPHt = Mat2::Zero();
};

/// EKF-SLAM: state x = (r, p_1, ..., p_m), joint covariance P (thesis eq. 2.10).
class Ekf {
public:
    /// Map initialisation (eq. 2.11 with the defaults: pose 0, zero covariance).
    /// `capacity` landmarks are reserved; the map grows beyond it when needed.
    explicit Ekf(const Pose& r0 = Pose::Zero(), const Mat3& P0 = Mat3::Zero(), int capacity = 64);

    /// Prediction (eqs. 2.12, 2.13): r ← move(r, u, 0), P_rr ← R_r P_rr R_rᵀ + R_n N R_nᵀ,
    /// P_rm ← R_r P_rm. N is the covariance of the perturbation of u.
    void predict(const Vec2& u, const Mat2& N);
    /// Prediction with a 3-DoF motion u and its covariance Q: r ← compose(r, u),
    /// P_rr ← R_r P_rr R_rᵀ + R_u Q R_uᵀ, P_rm ← R_r P_rm.
    void predict_motion(const Motion& u, const Mat3& Q);

    /// The innovation of observing landmark `id` at y with noise covariance R, without
    /// changing the filter (for gating). Throws std::out_of_range for an unknown id.
    Innovation innovation(int id, const Vec2& y, const Mat2& R) const;
    /// Landmark `id`'s predicted observation, computed once for many observations (gating).
    /// Throws std::out_of_range for an unknown id.
    PredictedObservation predicted_observation(int id) const;
    /// The innovation of observing y with noise R against `p`: the same value, to the bit, as
    /// innovation(id, y, R) with p = predicted_observation(id).
    static Innovation innovation(const PredictedObservation& p, const Vec2& y, const Mat2& R);

    /// Correction with the observation y of landmark `id` (eqs. 2.14-2.18). Returns the
    /// innovation used. Throws std::out_of_range for an unknown id.
    Innovation correct(int id, const Vec2& y, const Mat2& R, UpdateForm form = UpdateForm::Structured);

    /// Landmark initialisation by inverse observation (eqs. 2.19-2.21). Throws
    /// std::invalid_argument when `id` is already mapped.
    void add_landmark(int id, const Vec2& y, const Mat2& R);

    /// Removes landmark `id` and its rows and columns (no effect if absent).
    void remove_landmark(int id);

    bool has_landmark(int id) const { return index_.count(id) != 0; }
    int landmark_count() const { return static_cast<int>(ids_.size()); }
    int dimension() const { return n_; }
    /// Landmark ids in state order.
    const std::vector<int>& landmark_ids() const { return ids_; }
    /// Index in the state of landmark `id`'s x coordinate. Throws std::out_of_range.
    int state_index(int id) const;

    Pose pose() const { return x_.head<3>(); }
    Mat3 pose_covariance() const;
    Vec2 landmark(int id) const { return x_.segment<2>(state_index(id)); }
    Mat2 landmark_covariance(int id) const;
    Eigen::VectorXd mean() const { return x_.head(n_); }
    /// The full symmetric covariance (n×n).
    Eigen::MatrixXd covariance() const;
    /// The symmetric sub-matrix P(idx, idx) of the given state indices (read from the lower
    /// triangle), e.g. robot and candidate landmarks for a joint compatibility test.
    Eigen::MatrixXd covariance_of(const std::vector<int>& idx) const;

private:
    void reserve(int dim);
    /// Columns j and j+1.. (k columns) of the symmetric P, read from its lower triangle.
    void symmetric_columns(int j, int k, Eigen::Ref<Eigen::MatrixXd> out) const;
    Eigen::MatrixXd full_covariance() const;

    Eigen::VectorXd x_;
    Eigen::MatrixXd P_;   ///< capacity × capacity; lower triangle of the top-left n×n used
    int n_ = 3;
    std::vector<int> ids_;
    std::unordered_map<int, int> index_;   ///< id -> position in ids_
};

}  // namespace hc::slam
