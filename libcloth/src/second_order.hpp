// Private: a forward-mode number carrying value, gradient and Hessian with respect to N
// inputs, for energies whose closed-form Hessian is long (the dihedral angle). Exact to
// rounding; cost O(N²) per operation, so keep expressions short.
#pragma once

#include <Eigen/Core>

#include <cmath>

namespace drape::cloth::internal {

template <int N>
struct Second {
    using Vec = Eigen::Matrix<double, N, 1>;
    using Mat = Eigen::Matrix<double, N, N>;
    double v = 0;
    Vec g = Vec::Zero();
    Mat h = Mat::Zero();

    static Second constant(double value) {
        Second s;
        s.v = value;
        return s;
    }
    static Second variable(double value, int index) {
        Second s;
        s.v = value;
        s.g(index) = 1;
        return s;
    }
};

template <int N>
Second<N> operator+(const Second<N>& a, const Second<N>& b) {
    Second<N> r;
    r.v = a.v + b.v;
    r.g = a.g + b.g;
    r.h = a.h + b.h;
    return r;
}

template <int N>
Second<N> operator-(const Second<N>& a, const Second<N>& b) {
    Second<N> r;
    r.v = a.v - b.v;
    r.g = a.g - b.g;
    r.h = a.h - b.h;
    return r;
}

template <int N>
Second<N> operator*(const Second<N>& a, const Second<N>& b) {
    Second<N> r;
    r.v = a.v * b.v;
    r.g = a.v * b.g + b.v * a.g;
    r.h = a.v * b.h + b.v * a.h + a.g * b.g.transpose() + b.g * a.g.transpose();
    return r;
}

template <int N>
Second<N> sqrt(const Second<N>& a) {
    Second<N> r;
    r.v = std::sqrt(a.v);
    const double d1 = 0.5 / r.v;
    const double d2 = -0.25 / (a.v * r.v);
    r.g = d1 * a.g;
    r.h = d1 * a.h + d2 * a.g * a.g.transpose();
    return r;
}

/// atan2(y, x) with the chain rule through both arguments. \pre x² + y² > 0.
template <int N>
Second<N> atan2(const Second<N>& y, const Second<N>& x) {
    Second<N> r;
    r.v = std::atan2(y.v, x.v);
    const double r2 = x.v * x.v + y.v * y.v;
    const double r4 = r2 * r2;
    const double ty = x.v / r2, tx = -y.v / r2;
    const double tyy = -2 * x.v * y.v / r4, txx = 2 * x.v * y.v / r4;
    const double txy = (y.v * y.v - x.v * x.v) / r4;
    r.g = tx * x.g + ty * y.g;
    r.h = tx * x.h + ty * y.h + txx * x.g * x.g.transpose() + tyy * y.g * y.g.transpose() +
          txy * (x.g * y.g.transpose() + y.g * x.g.transpose());
    return r;
}

template <int N>
struct Vec3 {
    Second<N> c[3];
};

template <int N>
Vec3<N> operator-(const Vec3<N>& a, const Vec3<N>& b) {
    return {{a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]}};
}

template <int N>
Vec3<N> cross(const Vec3<N>& a, const Vec3<N>& b) {
    return {{a.c[1] * b.c[2] - a.c[2] * b.c[1], a.c[2] * b.c[0] - a.c[0] * b.c[2],
             a.c[0] * b.c[1] - a.c[1] * b.c[0]}};
}

template <int N>
Second<N> dot(const Vec3<N>& a, const Vec3<N>& b) {
    return a.c[0] * b.c[0] + a.c[1] * b.c[1] + a.c[2] * b.c[2];
}

}  // namespace drape::cloth::internal
