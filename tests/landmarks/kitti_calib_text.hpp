// kitti_calib_text.hpp: the grey stereo pair's camera matrices of a KITTI odometry calib.txt
// (sequence 00's numbers) as text, for the tests and fuzz seeds of the calib.txt reader.
#pragma once

namespace hc::landmarks::test {

/// Lines P0 and P1 of sequence 00's calib.txt: f = 718.856 px, principal point
/// (607.1928, 185.2157), baseline 386.1448 / 718.856 = 0.537 m.
inline constexpr const char* kKitti00P0P1 =
    "P0: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 0.000000000000e+00 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 0.000000000000e+00\n"
    "P1: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.861448000000e+02 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 0.000000000000e+00\n";

}  // namespace hc::landmarks::test
