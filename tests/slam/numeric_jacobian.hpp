// numeric_jacobian.hpp: central finite differences of a vector function, for the tests of
// analytic Jacobians. Output components listed in `angles` are differenced modulo 2π.
#pragma once

#include <Eigen/Core>

#include <initializer_list>

#include "mapping/slam/slam.hpp"

namespace hc::slam::test {

template <int Out, int In, class F>
Eigen::Matrix<double, Out, In> numeric_jacobian(F f, const Eigen::Matrix<double, In, 1>& x,
                                                std::initializer_list<int> angles = {}, double h = 1e-6) {
    Eigen::Matrix<double, Out, In> J;
    for (int i = 0; i < In; ++i) {
        Eigen::Matrix<double, In, 1> a = x, b = x;
        a(i) += h;
        b(i) -= h;
        Eigen::Matrix<double, Out, 1> d = f(a) - f(b);
        for (int k : angles) d(k) = wrap_angle(d(k));
        J.col(i) = d / (2 * h);
    }
    return J;
}

}  // namespace hc::slam::test
