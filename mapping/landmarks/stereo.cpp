// stereo.cpp: see stereo.hpp. With Z = B / D and dZ/dD = -B / D^2 = -Z / D, D = u_l - u_r - (cx0 - cx1):
//   dZ/du_l = -Z / D, dZ/du_r = Z / D; X and Y follow by the product rule, v = (v_l + v_r) / 2.
#include "mapping/landmarks/stereo.hpp"

#include "model/util/errors.hpp"

namespace hc::landmarks {

namespace {
[[noreturn]] void refuse(const std::string& why) { throw InputError("stereo calibration: " + why); }
}  // namespace

void RectifiedRig::validate() const {
    if (!(fx > 0) || !(fy > 0)) refuse("focal lengths must be positive");
    if (!(tx0 - tx1 > 0)) refuse("P1's x translation must put the right camera to the right (P0[0][3] > P1[0][3])");
}

void RectifiedRig::projections(double P0[12], double P1[12]) const {
    const double l[12] = {fx, 0, cx0, tx0, 0, fy, cy, ty, 0, 0, 1, 0};
    const double r[12] = {fx, 0, cx1, tx1, 0, fy, cy, ty, 0, 0, 1, 0};
    for (int i = 0; i < 12; ++i) {
        P0[i] = l[i];
        P1[i] = r[i];
    }
}

RectifiedRig rig_from_projections(const double P0[12], const double P1[12], int width, int height) {
    for (const double* P : {P0, P1}) {
        if (P[1] != 0 || P[4] != 0 || P[8] != 0 || P[9] != 0 || P[10] != 1 || P[11] != 0)
            refuse("P0 and P1 must be rectified projection matrices [fx 0 cx tx; 0 fy cy ty; 0 0 1 0]");
        if (!(P[0] > 0) || !(P[5] > 0)) refuse("focal lengths must be positive");
    }
    if (P0[0] != P1[0] || P0[5] != P1[5] || P0[6] != P1[6] || P0[7] != P1[7])
        refuse("P0 and P1 differ in fx, fy, cy or ty: the pair is not rectified");
    RectifiedRig r;
    r.fx = P0[0];
    r.fy = P0[5];
    r.cx0 = P0[2];
    r.cx1 = P1[2];
    r.cy = P0[6];
    r.tx0 = P0[3];
    r.tx1 = P1[3];
    r.ty = P0[7];
    r.width = width;
    r.height = height;
    r.validate();
    return r;
}

Point3 triangulate(const RectifiedRig& c, const StereoPixels& m, const PixelNoise& noise) {
    const double B = c.tx0 - c.tx1;
    const double D = m.u_l - m.u_r - (c.cx0 - c.cx1);
    Point3 t;
    if (!(D > 0)) return t;
    const double Z = B / D, v = 0.5 * (m.v_l + m.v_r);
    t.p[0] = ((m.u_l - c.cx0) * Z - c.tx0) / c.fx;
    t.p[1] = ((v - c.cy) * Z - c.ty) / c.fy;
    t.p[2] = Z;
    const double dZ_dul = -Z / D, dZ_dur = Z / D;
    const double J[3][4] = {
        {(Z + (m.u_l - c.cx0) * dZ_dul) / c.fx, 0, (m.u_l - c.cx0) * dZ_dur / c.fx, 0},
        {(v - c.cy) * dZ_dul / c.fy, Z / (2 * c.fy), (v - c.cy) * dZ_dur / c.fy, Z / (2 * c.fy)},
        {dZ_dul, 0, dZ_dur, 0},
    };
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 4; ++k) t.J[i][k] = J[i][k];
    noise.covariance(t, t.cov);
    t.valid = true;
    return t;
}

StereoPixels project(const RectifiedRig& c, const double p[3]) {
    StereoPixels m;
    m.u_l = (c.fx * p[0] + c.cx0 * p[2] + c.tx0) / p[2];
    m.u_r = (c.fx * p[0] + c.cx1 * p[2] + c.tx1) / p[2];
    m.v_l = m.v_r = (c.fy * p[1] + c.cy * p[2] + c.ty) / p[2];
    return m;
}

void PixelNoise::covariance(const Point3& t, double cov[3][3]) const {
    const double s2 = sigma_px * sigma_px;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += t.J[i][k] * t.J[j][k];
            cov[i][j] = s * s2;
        }
}

StereoPixels PixelNoise::perturb(const StereoPixels& e, std::mt19937_64& rng) const {
    std::normal_distribution<double> g(0.0, 1.0);
    StereoPixels n = e;
    n.u_l += sigma_px * g(rng);
    n.v_l += sigma_px * g(rng);
    n.u_r += sigma_px * g(rng);
    n.v_r += sigma_px * g(rng);
    return n;
}

}  // namespace hc::landmarks
