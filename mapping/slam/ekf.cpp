// ekf.cpp: the geometry of the 2-D EKF-SLAM events (frame transforms, range-bearing scan,
// motion, observation and inverse observation, each with its Jacobians) and the filter
// itself: prediction, correction in three covariance forms, landmark initialisation and
// removal (thesis section 2.5, Figure 8).
#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>

#include "mapping/slam/ekf.hpp"

namespace hc::slam {

double wrap_angle(double a) {
    constexpr double pi = std::numbers::pi;
    a = std::fmod(a + pi, 2 * pi);   // (-2π, 2π)
    if (a <= 0) a += 2 * pi;         // (0, 2π]
    return a - pi;                   // (-π, π]
}

Vec2 to_frame(const Pose& F, const Vec2& p, Mat23* PF_f, Mat2* PF_p) {
    const double c = std::cos(F(2)), s = std::sin(F(2));
    const Vec2 d = p - F.head<2>();
    // pf = Rᵀ (p − t), R = [c −s; s c]
    const Vec2 pf(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    if (PF_f) *PF_f << -c, -s, -s * d.x() + c * d.y(),   //
                        s, -c, -c * d.x() - s * d.y();
    if (PF_p) *PF_p << c, s, -s, c;
    return pf;
}

Vec2 from_frame(const Pose& F, const Vec2& pf, Mat23* PW_f, Mat2* PW_pf) {
    const double c = std::cos(F(2)), s = std::sin(F(2));
    // p = R pf + t
    const Vec2 p(c * pf.x() - s * pf.y() + F(0), s * pf.x() + c * pf.y() + F(1));
    if (PW_f) *PW_f << 1, 0, -s * pf.x() - c * pf.y(),   //
                       0, 1, c * pf.x() - s * pf.y();
    if (PW_pf) *PW_pf << c, -s, s, c;
    return p;
}

Vec2 scan(const Vec2& p, Mat2* Y_p) {
    const double r2 = p.squaredNorm(), r = std::sqrt(r2);
    if (Y_p) *Y_p << p.x() / r, p.y() / r, -p.y() / r2, p.x() / r2;
    return {r, std::atan2(p.y(), p.x())};
}

Vec2 inv_scan(const Vec2& y, Mat2* P_y) {
    const double c = std::cos(y(1)), s = std::sin(y(1));
    if (P_y) *P_y << c, -y(0) * s, s, y(0) * c;
    return {y(0) * c, y(0) * s};
}

Pose move(const Pose& r, const Vec2& u, const Vec2& n, Mat3* R_r, Mat32* R_n) {
    const double dx = u(0) + n(0), da = u(1) + n(1);
    const double a = r(2) + da / 2;   // heading of the chord of the arc
    const double c = std::cos(a), s = std::sin(a);
    if (R_r) *R_r << 1, 0, -dx * s, 0, 1, dx * c, 0, 0, 1;
    if (R_n) *R_n << c, -dx * s / 2, s, dx * c / 2, 0, 1;
    return {r(0) + dx * c, r(1) + dx * s, wrap_angle(r(2) + da)};
}

Vec2 observe(const Pose& r, const Vec2& p, Mat23* Y_r, Mat2* Y_p) {
    Mat23 PF_r;
    Mat2 PF_p, Y_pf;
    const Vec2 y = scan(to_frame(r, p, &PF_r, &PF_p), &Y_pf);
    if (Y_r) *Y_r = Y_pf * PF_r;
    if (Y_p) *Y_p = Y_pf * PF_p;
    return y;
}

Vec2 inv_observe(const Pose& r, const Vec2& y, Mat23* P_r, Mat2* P_y) {
    Mat2 PF_y, P_pf;
    const Vec2 p = from_frame(r, inv_scan(y, &PF_y), P_r, &P_pf);
    if (P_y) *P_y = P_pf * PF_y;
    return p;
}

Pose compose(const Pose& r, const Motion& u, Mat3* R_r, Mat3* R_u) {
    const double c = std::cos(r(2)), s = std::sin(r(2));
    if (R_r) *R_r << 1, 0, -s * u(0) - c * u(1),   //
                     0, 1, c * u(0) - s * u(1),    //
                     0, 0, 1;
    if (R_u) *R_u << c, -s, 0, s, c, 0, 0, 0, 1;
    return {r(0) + c * u(0) - s * u(1), r(1) + s * u(0) + c * u(1), wrap_angle(r(2) + u(2))};
}

Motion between(const Pose& a, const Pose& b) {
    const double c = std::cos(a(2)), s = std::sin(a(2));
    const Vec2 d = b.head<2>() - a.head<2>();
    return {c * d.x() + s * d.y(), -s * d.x() + c * d.y(), wrap_angle(b(2) - a(2))};
}

// ---- the filter ---------------------------------------------------------------------------

Ekf::Ekf(const Pose& r0, const Mat3& P0, int capacity)
    : x_(Eigen::VectorXd::Zero(3 + 2 * std::max(capacity, 0))),
      P_(Eigen::MatrixXd::Zero(x_.size(), x_.size())) {
    x_.head<3>() = r0;
    x_(2) = wrap_angle(r0(2));
    P_.topLeftCorner<3, 3>() = (P0 + P0.transpose()) / 2;
}

int Ekf::state_index(int id) const {
    const auto it = index_.find(id);
    if (it == index_.end()) throw std::out_of_range("landmark " + std::to_string(id) + " is not in the map");
    return 3 + 2 * it->second;
}

Mat3 Ekf::pose_covariance() const { return P_.topLeftCorner<3, 3>().selfadjointView<Eigen::Lower>(); }

Mat2 Ekf::landmark_covariance(int id) const {
    const int l = state_index(id);
    return P_.block<2, 2>(l, l).selfadjointView<Eigen::Lower>();
}

Eigen::MatrixXd Ekf::full_covariance() const {
    Eigen::MatrixXd F = P_.topLeftCorner(n_, n_).selfadjointView<Eigen::Lower>();
    return F;
}

Eigen::MatrixXd Ekf::covariance() const { return full_covariance(); }

void Ekf::reserve(int dim) {
    if (dim <= P_.rows()) return;
    const int cap = std::max<int>(dim, 2 * static_cast<int>(P_.rows()));
    Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(cap, cap);
    Q.topLeftCorner(n_, n_) = P_.topLeftCorner(n_, n_);
    P_.swap(Q);
    x_.conservativeResize(cap);
}

void Ekf::symmetric_columns(int j, int k, Eigen::Ref<Eigen::MatrixXd> out) const {
    for (int c = 0; c < k; ++c) {
        const int col = j + c;
        // above the diagonal: row `col` of the lower triangle; from it down: column `col`
        out.col(c).head(col) = P_.row(col).head(col).transpose();
        out.col(c).segment(col, n_ - col) = P_.col(col).segment(col, n_ - col);
    }
}

void Ekf::predict(const Vec2& u, const Mat2& N) {
    Mat3 R_r;
    Mat32 R_n;
    const Mat3 Prr = pose_covariance();
    x_.head<3>() = move(x_.head<3>(), u, Vec2::Zero(), &R_r, &R_n);
    const Mat3 Q = R_r * Prr * R_r.transpose() + R_n * N * R_n.transpose();
    P_.topLeftCorner<3, 3>() = (Q + Q.transpose()) / 2;
    // P_mr = P_rmᵀ ← (R_r P_rm)ᵀ = P_mr R_rᵀ (the product is evaluated into a temporary)
    if (n_ > 3) P_.block(3, 0, n_ - 3, 3) = P_.block(3, 0, n_ - 3, 3) * R_r.transpose();
}

void Ekf::predict_motion(const Motion& u, const Mat3& Q) {
    Mat3 R_r, R_u;
    const Mat3 Prr = pose_covariance();
    x_.head<3>() = compose(x_.head<3>(), u, &R_r, &R_u);
    const Mat3 Pn = R_r * Prr * R_r.transpose() + R_u * Q * R_u.transpose();
    P_.topLeftCorner<3, 3>() = (Pn + Pn.transpose()) / 2;
    if (n_ > 3) P_.block(3, 0, n_ - 3, 3) = P_.block(3, 0, n_ - 3, 3) * R_r.transpose();
}

Eigen::MatrixXd Ekf::covariance_of(const std::vector<int>& idx) const {
    const int m = static_cast<int>(idx.size());
    Eigen::MatrixXd S(m, m);
    for (int a = 0; a < m; ++a)
        for (int b = 0; b <= a; ++b) {
            const int i = std::max(idx[a], idx[b]), j = std::min(idx[a], idx[b]);
            S(a, b) = S(b, a) = P_(i, j);
        }
    return S;
}

Innovation Ekf::innovation(int id, const Vec2& y, const Mat2& R) const {
    return innovation(predicted_observation(id), y, R);
}

PredictedObservation Ekf::predicted_observation(int id) const {
    const int l = state_index(id);
    Mat23 H_r;
    Mat2 H_l;
    PredictedObservation p;
    p.y = observe(x_.head<3>(), x_.segment<2>(l), &H_r, &H_l);
    const Mat3 Prr = pose_covariance();
    const Mat23 Plr = P_.block<2, 3>(l, 0);
    const Mat2 Pll = P_.block<2, 2>(l, l).selfadjointView<Eigen::Lower>();
    const Mat2 cross = H_l * Plr * H_r.transpose();
    p.HPHt = H_r * Prr * H_r.transpose() + cross + cross.transpose() + H_l * Pll * H_l.transpose();
    return p;
}

Innovation Ekf::innovation(const PredictedObservation& p, const Vec2& y, const Mat2& R) {
    Innovation inn;
    inn.z = y - p.y;
    inn.z(1) = wrap_angle(inn.z(1));
    inn.Z = p.HPHt + R;
    inn.Z = (inn.Z + inn.Z.transpose()) / 2;
    inn.mahalanobis2 = inn.z.dot(inn.Z.ldlt().solve(inn.z));
    return inn;
}

Innovation Ekf::correct(int id, const Vec2& y, const Mat2& R, UpdateForm form) {
    const int l = state_index(id);
    const int n = n_;
    Mat23 H_r;
    Mat2 H_l;
    const Vec2 yh = observe(x_.head<3>(), x_.segment<2>(l), &H_r, &H_l);
    Innovation inn;
    inn.z = y - yh;
    inn.z(1) = wrap_angle(inn.z(1));

    if (form == UpdateForm::Structured) {
        // P·Hᵀ from the 5 columns of P where H is non-zero
        Eigen::Matrix<double, Eigen::Dynamic, 5> C(n, 5);
        symmetric_columns(0, 3, C.leftCols<3>());
        symmetric_columns(l, 2, C.rightCols<2>());
        const Eigen::Matrix<double, Eigen::Dynamic, 2> PHt = C.leftCols<3>() * H_r.transpose() +
                                                             C.rightCols<2>() * H_l.transpose();
        inn.Z = H_r * PHt.topRows<3>() + H_l * PHt.middleRows<2>(l) + R;
        inn.Z = (inn.Z + inn.Z.transpose()) / 2;
        // Z = L Lᵀ; W = P Hᵀ L⁻ᵀ; K = P Hᵀ Z⁻¹ = W L⁻¹; P − K Z Kᵀ = P − W Wᵀ
        const Eigen::LLT<Mat2> llt(inn.Z);
        const Mat2 Linv = llt.matrixL().solve(Mat2::Identity());
        const Eigen::Matrix<double, Eigen::Dynamic, 2> W = PHt * Linv.transpose();
        const Vec2 Linv_z = Linv * inn.z;
        inn.mahalanobis2 = Linv_z.squaredNorm();
        x_.head(n).noalias() += W * Linv_z;
        auto Pn = P_.topLeftCorner(n, n);
        Pn.selfadjointView<Eigen::Lower>().rankUpdate(W, -1.0);
    } else {
        Eigen::MatrixXd P = full_covariance();
        Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
        H.leftCols<3>() = H_r;
        H.middleCols<2>(l) = H_l;
        const Eigen::MatrixXd PHt = P * H.transpose();
        inn.Z = H * PHt + R;
        const Mat2 Zinv = inn.Z.inverse();
        const Eigen::MatrixXd K = PHt * Zinv;
        inn.mahalanobis2 = inn.z.dot(Zinv * inn.z);
        x_.head(n) += K * inn.z;
        if (form == UpdateForm::DenseKzk) {
            P.noalias() -= K * inn.Z * K.transpose();
            P_.topLeftCorner(n, n) = P;
        } else {
            const Eigen::MatrixXd I_KH = Eigen::MatrixXd::Identity(n, n) - K * H;
            P_.topLeftCorner(n, n).noalias() = I_KH * P;
        }
    }
    x_(2) = wrap_angle(x_(2));
    return inn;
}

void Ekf::add_landmark(int id, const Vec2& y, const Mat2& R) {
    if (has_landmark(id)) throw std::invalid_argument("landmark " + std::to_string(id) + " is already in the map");
    reserve(n_ + 2);
    Mat23 G_r;
    Mat2 G_y;
    const Vec2 p = inv_observe(x_.head<3>(), y, &G_r, &G_y);
    const Mat3 Prr = pose_covariance();
    const int n = n_;
    // P_Lx = G_r [P_rr P_rm] (eq. 2.20), stored as the new rows of the lower triangle
    P_.block<2, 3>(n, 0) = G_r * Prr;
    if (n > 3) P_.block(n, 3, 2, n - 3) = G_r * P_.block(3, 0, n - 3, 3).transpose();
    const Mat2 Pll = G_r * Prr * G_r.transpose() + G_y * R * G_y.transpose();
    P_.block<2, 2>(n, n) = (Pll + Pll.transpose()) / 2;
    x_.segment<2>(n) = p;
    index_[id] = static_cast<int>(ids_.size());
    ids_.push_back(id);
    n_ += 2;
}

void Ekf::remove_landmark(int id) {
    const auto it = index_.find(id);
    if (it == index_.end()) return;
    const int k = it->second, l = 3 + 2 * k;
    const int m = n_ - 2;
    // rows and columns l, l+1 taken out of the lower triangle in place (the only part read):
    // new (i, j) = old (i + 2 if i >= l, j + 2 if j >= l); columns in increasing order, rows
    // downwards, so no source is overwritten before it is read
    for (int j = 0; j < m; ++j) {
        const int sj = j < l ? j : j + 2;
        for (int i = std::max(j, l); i < m; ++i) P_(i, j) = P_(i + 2, sj);
    }
    for (int i = l; i < m; ++i) x_(i) = x_(i + 2);
    ids_.erase(ids_.begin() + k);
    index_.erase(it);
    for (int j = k; j < static_cast<int>(ids_.size()); ++j) index_[ids_[j]] = j;
    n_ = m;
}

}  // namespace hc::slam
