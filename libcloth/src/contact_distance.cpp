// Exact distances between self-contact primitives and their regimes (contact_distance.hpp).
#include "contact_distance.hpp"

#include "second_order.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::cloth::internal {

namespace {

using Mat34 = Eigen::Matrix<double, 3, 4>;
using S12 = Second<12>;
using V12 = Vec3<12>;

DistanceRegime make_regime(DistanceRegime::Type type, int i, int j, int k = 0) {
    DistanceRegime r;
    r.type = type;
    r.idx = {i, j, k};
    return r;
}

// Squared distance from p to segment a–b; ip, ia, ib are the local numbers for the regime.
double point_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b, int ip, int ia, int ib, DistanceRegime* regime) {
    const Eigen::Vector3d e = b - a;
    const double ee = e.squaredNorm();
    const double t = ee > 0 ? (p - a).dot(e) / ee : 0.0;
    if (t <= 0) {
        if (regime) *regime = make_regime(DistanceRegime::Type::point_point, ip, ia);
        return (p - a).squaredNorm();
    }
    if (t >= 1) {
        if (regime) *regime = make_regime(DistanceRegime::Type::point_point, ip, ib);
        return (p - b).squaredNorm();
    }
    if (regime) *regime = make_regime(DistanceRegime::Type::point_edge, ip, ia, ib);
    return (p - a - t * e).squaredNorm();
}

// Keeps the smaller of two (distance², regime) candidates; ties keep the first.
struct Closest {
    double d2 = std::numeric_limits<double>::infinity();
    DistanceRegime regime;
    void offer(double candidate, const DistanceRegime& r) {
        if (candidate < d2) {
            d2 = candidate;
            regime = r;
        }
    }
};

// Below this sin²(angle) two edges are treated as parallel, and a triangle whose
// |n|² < eps |e1|²|e2|² as degenerate: the interior formulas would divide by ~0, and the
// boundary minimum differs from the true one by O(sqrt(eps)) times the edge length.
constexpr double kParallelEps = 1e-14;

S12 quotient(const S12& a, const S12& b) {
    S12 r;
    r.v = a.v / b.v;
    r.g = (a.g - r.v * b.g) / b.v;
    r.h = (a.h - r.v * b.h - r.g * b.g.transpose() - b.g * r.g.transpose()) / b.v;
    return r;
}

V12 vertex(const Mat34& x, int k) {
    return {{S12::variable(x(0, k), 3 * k), S12::variable(x(1, k), 3 * k + 1),
             S12::variable(x(2, k), 3 * k + 2)}};
}

}  // namespace

double point_triangle_distance_squared(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                       const Eigen::Vector3d& t1, const Eigen::Vector3d& t2,
                                       DistanceRegime* regime) {
    const Eigen::Vector3d e1 = t1 - t0, e2 = t2 - t0, w = p - t0;
    const double d11 = e1.squaredNorm(), d22 = e2.squaredNorm(), d12 = e1.dot(e2);
    const double det = d11 * d22 - d12 * d12;  // = |e1 × e2|²
    if (det > kParallelEps * d11 * d22) {
        const double r1 = w.dot(e1), r2 = w.dot(e2);
        const double u = (d22 * r1 - d12 * r2) / det, v = (d11 * r2 - d12 * r1) / det;
        if (u > 0 && v > 0 && u + v < 1) {
            if (regime) *regime = make_regime(DistanceRegime::Type::point_plane, 0, 1, 2);
            return (w - u * e1 - v * e2).squaredNorm();
        }
    }
    // The squared distance over the triangle is a convex quadratic in (u, v): if its
    // minimiser is not interior, the minimum lies on the boundary, i.e. on an edge.
    Closest best;
    DistanceRegime r;
    best.offer(point_segment(p, t0, t1, 0, 1, 2, &r), r);
    best.offer(point_segment(p, t1, t2, 0, 2, 3, &r), r);
    best.offer(point_segment(p, t2, t0, 0, 3, 1, &r), r);
    if (regime) *regime = best.regime;
    return best.d2;
}

double segment_segment_distance_squared(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                        DistanceRegime* regime) {
    const Eigen::Vector3d ea = a1 - a0, eb = b1 - b0, w = a0 - b0;
    const double A = ea.squaredNorm(), B = ea.dot(eb), C = eb.squaredNorm();
    const double D = ea.dot(w), E = eb.dot(w);
    const double den = A * C - B * B;  // = |ea × eb|²
    if (den > kParallelEps * A * C) {
        const double s = (B * E - C * D) / den, t = (A * E - B * D) / den;
        if (s > 0 && s < 1 && t > 0 && t < 1) {
            if (regime) *regime = make_regime(DistanceRegime::Type::edge_edge, 0, 1, 2);
            return (w + s * ea - t * eb).squaredNorm();
        }
    }
    // Convexity again: otherwise the minimum is attained with an endpoint of one segment.
    Closest best;
    DistanceRegime r;
    best.offer(point_segment(a0, b0, b1, 0, 2, 3, &r), r);
    best.offer(point_segment(a1, b0, b1, 1, 2, 3, &r), r);
    best.offer(point_segment(b0, a0, a1, 2, 0, 1, &r), r);
    best.offer(point_segment(b1, a0, a1, 3, 0, 1, &r), r);
    if (regime) *regime = best.regime;
    return best.d2;
}

double pair_distance_squared(ContactPair::Kind kind, const Mat34& x, DistanceRegime* regime) {
    if (kind == ContactPair::Kind::vertex_triangle)
        return point_triangle_distance_squared(x.col(0), x.col(1), x.col(2), x.col(3), regime);
    return segment_segment_distance_squared(x.col(0), x.col(1), x.col(2), x.col(3), regime);
}

double regime_distance_squared(const DistanceRegime& regime, const Mat34& x,
                               Vector12d* gradient, Matrix12d* hessian) {
    const V12 X[4] = {vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3)};
    const auto& i = regime.idx;
    S12 s;
    switch (regime.type) {
        case DistanceRegime::Type::point_point: {
            const V12 d = X[i[0]] - X[i[1]];
            s = dot(d, d);
            break;
        }
        case DistanceRegime::Type::point_edge: {
            const V12 e = X[i[2]] - X[i[1]];
            const V12 c = cross(X[i[0]] - X[i[1]], e);
            s = quotient(dot(c, c), dot(e, e));
            break;
        }
        case DistanceRegime::Type::point_plane: {
            const V12 n = cross(X[2] - X[1], X[3] - X[1]);
            const S12 w = dot(X[0] - X[1], n);
            s = quotient(w * w, dot(n, n));
            break;
        }
        case DistanceRegime::Type::edge_edge: {
            const V12 c = cross(X[1] - X[0], X[3] - X[2]);
            const S12 w = dot(X[2] - X[0], c);
            s = quotient(w * w, dot(c, c));
            break;
        }
    }
    if (gradient) *gradient = s.g;
    if (hessian) *hessian = s.h;
    return s.v;
}

Eigen::Vector4d regime_weights(const DistanceRegime& regime, const Mat34& x) {
    Eigen::Vector4d w = Eigen::Vector4d::Zero();
    const auto& i = regime.idx;
    switch (regime.type) {
        case DistanceRegime::Type::point_point:
            w(i[0]) = 1;
            w(i[1]) = -1;
            break;
        case DistanceRegime::Type::point_edge: {
            const Eigen::Vector3d e = x.col(i[2]) - x.col(i[1]);
            const double ee = e.squaredNorm();
            const double t = ee > 0 ? (x.col(i[0]) - x.col(i[1])).dot(e) / ee : 0.0;
            w(i[0]) = 1;
            w(i[1]) = -(1 - t);
            w(i[2]) = -t;
            break;
        }
        case DistanceRegime::Type::point_plane: {
            const Eigen::Vector3d e1 = x.col(2) - x.col(1), e2 = x.col(3) - x.col(1);
            const Eigen::Vector3d r = x.col(0) - x.col(1);
            const double d11 = e1.squaredNorm(), d22 = e2.squaredNorm(), d12 = e1.dot(e2);
            const double det = d11 * d22 - d12 * d12;
            const double r1 = r.dot(e1), r2 = r.dot(e2);
            const double u = det > 0 ? (d22 * r1 - d12 * r2) / det : 0.0;
            const double v = det > 0 ? (d11 * r2 - d12 * r1) / det : 0.0;
            w << 1, -(1 - u - v), -u, -v;
            break;
        }
        case DistanceRegime::Type::edge_edge: {
            const Eigen::Vector3d ea = x.col(1) - x.col(0), eb = x.col(3) - x.col(2);
            const Eigen::Vector3d r = x.col(0) - x.col(2);
            const double A = ea.squaredNorm(), B = ea.dot(eb), C = eb.squaredNorm();
            const double D = ea.dot(r), E = eb.dot(r);
            const double den = A * C - B * B;
            const double s = den > 0 ? (B * E - C * D) / den : 0.0;
            const double t = den > 0 ? (A * E - B * D) / den : 0.0;
            w << 1 - s, s, -(1 - t), -t;
            break;
        }
    }
    return w;
}

}  // namespace drape::cloth::internal
