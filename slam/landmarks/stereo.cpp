// stereo.cpp: see stereo.hpp. With Z = B / D and dZ/dD = -B / D^2 = -Z / D, D = u_l - u_r - (cx0 - cx1):
//   dZ/du_l = -Z / D, dZ/du_r = Z / D; X and Y follow by the product rule, v = (v_l + v_r) / 2.
#include "slam/landmarks/stereo.hpp"

namespace hc::stereo {

Point3 triangulate(const RectifiedRig& c, double u_l, double v_l, double u_r, double v_r) {
    const double B = c.tx0 - c.tx1;
    const double D = u_l - u_r - (c.cx0 - c.cx1);
    Point3 t;
    if (!(D > 0)) return t;
    const double Z = B / D, v = 0.5 * (v_l + v_r);
    t.p[0] = ((u_l - c.cx0) * Z - c.tx0) / c.fx;
    t.p[1] = ((v - c.cy) * Z - c.ty) / c.fy;
    t.p[2] = Z;
    const double dZ_dul = -Z / D, dZ_dur = Z / D;
    const double J[3][4] = {
        {(Z + (u_l - c.cx0) * dZ_dul) / c.fx, 0, (u_l - c.cx0) * dZ_dur / c.fx, 0},
        {(v - c.cy) * dZ_dul / c.fy, Z / (2 * c.fy), (v - c.cy) * dZ_dur / c.fy, Z / (2 * c.fy)},
        {dZ_dul, 0, dZ_dur, 0},
    };
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 4; ++k) t.J[i][k] = J[i][k];
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

}  // namespace hc::stereo
