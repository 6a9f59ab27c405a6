// observations.cpp: camera-frame points as top-view range-bearing observations, their noise
// carried to another point, triangulated points as observations.
#include "mapping/slam/observations.hpp"

#include <cmath>

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

StereoLandmarkObs to_observation(const landmarks::Point3& t) {
    StereoLandmarkObs o;
    o.p_cam = Eigen::Vector3d(t.p[0], t.p[1], t.p[2]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) o.cov(i, j) = t.cov[i][j];
    return o;
}

}  // namespace hc::slam
