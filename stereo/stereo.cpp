// stereo.cpp: see stereo.hpp. With Z = B / D and dZ/dD = -B / D^2 = -Z / D, D = u_l - u_r - (cx0 - cx1):
//   dZ/du_l = -Z / D, dZ/du_r = Z / D; X and Y follow by the product rule, v = (v_l + v_r) / 2.
#include "stereo/stereo.hpp"

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

}  // namespace hc::stereo
