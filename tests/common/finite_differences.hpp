// Central finite differences for the derivative checks of every energy (one helper for all
// suites; ipc-toolkit's finite-diff is the model). Step h: about 1e-7 times the coordinates'
// scale balances truncation (O(h²)) against rounding (O(ε/h)).
#pragma once

#include <Eigen/Core>

#include <algorithm>

namespace drape::test {

/// Central differences of a scalar function: g_i = (f(x + h e_i) − f(x − h e_i)) / 2h.
/// \param f callable double(const Vector&); \param x the point (fixed or dynamic size).
template <class F, class Vector>
Vector fd_gradient(F&& f, const Vector& x, double h) {
    Vector g(x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        Vector a = x, b = x;
        a(i) += h;
        b(i) -= h;
        g(i) = (f(a) - f(b)) / (2 * h);
    }
    return g;
}

/// Central differences of a gradient, column by column: H(:, i) = (∇f(x + h e_i) −
/// ∇f(x − h e_i)) / 2h (the Hessian when `gradient` is ∇f).
/// \param gradient callable Vector(const Vector&).
template <class G, class Vector>
Eigen::Matrix<double, Vector::RowsAtCompileTime, Vector::RowsAtCompileTime> fd_hessian(
    G&& gradient, const Vector& x, double h) {
    Eigen::Matrix<double, Vector::RowsAtCompileTime, Vector::RowsAtCompileTime> m(x.size(), x.size());
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        Vector a = x, b = x;
        a(i) += h;
        b(i) -= h;
        m.col(i) = (gradient(a) - gradient(b)) / (2 * h);
    }
    return m;
}

/// |fd − analytic| / |analytic| (Frobenius), the measure the derivative checks bound.
inline double relative_error(const Eigen::MatrixXd& fd, const Eigen::MatrixXd& analytic) {
    return (fd - analytic).norm() / std::max(analytic.norm(), 1e-300);
}

}  // namespace drape::test
