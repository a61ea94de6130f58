#include <drape/cloth/energies.hpp>

#include <drape/core/errors.hpp>

#include "psd_projection.hpp"
#include "second_order.hpp"

#include <Eigen/Geometry>

#include <algorithm>

#include <cmath>

namespace drape::cloth {

namespace {

using S12 = internal::Second<12>;
using V12 = internal::Vec3<12>;

V12 vertex(const Eigen::Matrix<double, 3, 4>& x, int k) {
    return {{S12::variable(x(0, k), 3 * k), S12::variable(x(1, k), 3 * k + 1),
             S12::variable(x(2, k), 3 * k + 2)}};
}

double edge_direction(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d d = b - a;
    return std::atan2(d.y(), d.x());
}

// θ with its exact gradient and Hessian, by forward-mode second derivatives.
S12 theta_second_order(const Eigen::Matrix<double, 3, 4>& x) {
    const V12 x0 = vertex(x, 0), x1 = vertex(x, 1), x2 = vertex(x, 2), x3 = vertex(x, 3);
    const V12 e = x1 - x0;
    const V12 n0 = internal::cross(e, x2 - x0);
    const V12 n1 = internal::cross(x3 - x0, e);
    return internal::atan2(internal::dot(internal::cross(n0, n1), e),
                           internal::sqrt(internal::dot(e, e)) * internal::dot(n0, n1));
}

}  // namespace

double dihedral_angle(const Eigen::Matrix<double, 3, 4>& x) {
    const Eigen::Vector3d e = x.col(1) - x.col(0);
    const Eigen::Vector3d n0 = e.cross(x.col(2) - x.col(0));
    const Eigen::Vector3d n1 = (x.col(3) - x.col(0)).cross(e);
    return std::atan2(n0.cross(n1).dot(e), e.norm() * n0.dot(n1));
}

Vector12d dihedral_angle_gradient(const Eigen::Matrix<double, 3, 4>& x) {
    const Eigen::Vector3d e = x.col(1) - x.col(0);
    const Eigen::Vector3d n0 = e.cross(x.col(2) - x.col(0));
    const Eigen::Vector3d n1 = (x.col(3) - x.col(0)).cross(e);
    const double len2 = e.squaredNorm(), len = std::sqrt(len2);
    // Rotating x2 (x3) about the edge by dφ moves it by h dφ along its face normal.
    const Eigen::Vector3d g2 = -len / n0.squaredNorm() * n0;
    const Eigen::Vector3d g3 = -len / n1.squaredNorm() * n1;
    // Lever rule: the edge vertices share the reaction by where x2, x3 project on the edge.
    const double t2 = (x.col(2) - x.col(0)).dot(e) / len2;
    const double t3 = (x.col(3) - x.col(0)).dot(e) / len2;
    Vector12d g;
    g.segment<3>(0) = -(1 - t2) * g2 - (1 - t3) * g3;
    g.segment<3>(3) = -t2 * g2 - t3 * g3;
    g.segment<3>(6) = g2;
    g.segment<3>(9) = g3;
    return g;
}

HingeRest hinge_rest(const ClothMesh& mesh, const Hinge& hinge) {
    HingeRest rest;
    double area_sum = 0;
    for (int side = 0; side < 2; ++side) {
        const int f = hinge.faces[static_cast<std::size_t>(side)];
        const Eigen::Vector2d p0 = mesh.pattern.row(mesh.pattern_faces(f, 0)).transpose();
        const Eigen::Vector2d p1 = mesh.pattern.row(mesh.pattern_faces(f, 1)).transpose();
        const Eigen::Vector2d p2 = mesh.pattern.row(mesh.pattern_faces(f, 2)).transpose();
        const Eigen::Vector2d d1 = p1 - p0, d2 = p2 - p0;
        area_sum += 0.5 * (d1.x() * d2.y() - d1.y() * d2.x());
        const auto& corners = hinge.corners[static_cast<std::size_t>(side)];
        const Eigen::Vector2d a = mesh.pattern.row(mesh.pattern_faces(f, corners[0])).transpose();
        const Eigen::Vector2d b = mesh.pattern.row(mesh.pattern_faces(f, corners[1])).transpose();
        rest.direction_rad[side] = edge_direction(a, b);
        // Across a seam the two sides may disagree on the length: use the mean.
        rest.rest_length_m += 0.5 * (b - a).norm();
    }
    rest.rest_area_sum_m2 = area_sum;
    rest.rest_angle_rad = 0;
    return rest;
}

double hinge_curvature(double angle_rad, const HingeRest& rest) {
    return angle_rad * rest.rest_length_m / rest.rest_area_sum_m2;
}

double BendingCurve::at(double kappa_abs, double* slope) const {
    const int last = knot_count - 1;
    if (kappa_abs >= curvature_per_m[static_cast<std::size_t>(last)] || last == 0) {
        if (slope) *slope = 0;
        return stiffness_n_m[static_cast<std::size_t>(last)];
    }
    int j = 0;
    while (j + 1 < last && kappa_abs >= curvature_per_m[static_cast<std::size_t>(j + 1)]) ++j;
    const auto ju = static_cast<std::size_t>(j);
    const double m = (stiffness_n_m[ju + 1] - stiffness_n_m[ju]) /
                     (curvature_per_m[ju + 1] - curvature_per_m[ju]);
    if (slope) *slope = m;
    return stiffness_n_m[ju] + m * (kappa_abs - curvature_per_m[ju]);
}

BendingCurve constant_bending_curve(double stiffness_n_m) {
    BendingCurve c;
    c.knot_count = 1;
    c.curvature_per_m[0] = 0;
    c.stiffness_n_m[0] = stiffness_n_m;
    return c;
}

BendingCurve bending_curve(const Material& material, const HingeRest& rest) {
    BendingCurve c;
    c.knot_count = 0;
    auto push = [&](double kappa, double k) {
        c.curvature_per_m[static_cast<std::size_t>(c.knot_count)] = kappa;
        c.stiffness_n_m[static_cast<std::size_t>(c.knot_count)] = std::max(k, 0.0);
        ++c.knot_count;
    };
    double prev0 = 0, prev1 = 0;
    for (int j = 0; j <= 4; ++j) {
        const double kappa = 10.0 * j;
        const double k0 = bending_stiffness(material, rest.direction_rad[0], kappa);
        const double k1 = bending_stiffness(material, rest.direction_rad[1], kappa);
        if (j > 0 && (prev0 - prev1) * (k0 - k1) < 0) {
            // The sides' lines cross inside the segment: the min has a kink there.
            const double t = (prev0 - prev1) / ((prev0 - prev1) - (k0 - k1));
            push(kappa - 10.0 + 10.0 * t, prev0 + t * (k0 - prev0));
        }
        push(kappa, std::min(k0, k1));
        prev0 = k0;
        prev1 = k1;
    }
    return c;
}

double bending_energy(const Eigen::Matrix<double, 3, 4>& x, const HingeRest& rest,
                      const BendingCurve& curve, Vector12d* gradient, Matrix12d* hessian,
                      HessianMode mode) {
    const double c = rest.rest_length_m * rest.rest_length_m / (8 * rest.rest_area_sum_m2);
    const double a = rest.rest_length_m / rest.rest_area_sum_m2;  // κ = a s
    const double d = dihedral_angle(x) - rest.rest_angle_rad;
    const double s = std::abs(d);
    // E(s) = c ∫0^s 2t k(a t) dt, k piecewise linear in t with knots t_j = κ_j / a.
    double energy = 0;
    double t_lo = 0;
    for (int j = 0; j < curve.knot_count && t_lo < s; ++j) {
        const auto ju = static_cast<std::size_t>(j);
        const bool last = j + 1 == curve.knot_count;
        const double t_hi = last ? s : std::min(s, curve.curvature_per_m[ju + 1] / a);
        const double kj = curve.stiffness_n_m[ju];
        const double tj = curve.curvature_per_m[ju] / a;
        const double m = last ? 0.0
                              : (curve.stiffness_n_m[ju + 1] - kj) /
                                    ((curve.curvature_per_m[ju + 1] - curve.curvature_per_m[ju]) / a);
        // ∫ 2t (kj + m (t − tj)) dt = (kj − m tj) t² + (2/3) m t³
        auto antiderivative = [&](double t) { return (kj - m * tj) * t * t + 2.0 / 3.0 * m * t * t * t; };
        energy += c * (antiderivative(t_hi) - antiderivative(t_lo));
        t_lo = t_hi;
    }
    if (!gradient && !hessian) return energy;
    double slope_kappa = 0;
    const double k = curve.at(a * s, &slope_kappa);
    const double e1 = 2 * c * k * d;                          // dE/dd
    const double e2 = 2 * c * (k + s * a * slope_kappa);      // d²E/dd²
    if (hessian && mode == HessianMode::exact) {
        const S12 theta = theta_second_order(x);
        if (gradient) *gradient = e1 * theta.g;
        Matrix12d h = e2 * theta.g * theta.g.transpose() + e1 * theta.h;
        *hessian = 0.5 * (h + h.transpose());
        return energy;
    }
    const Vector12d dtheta = dihedral_angle_gradient(x);
    if (gradient) *gradient = e1 * dtheta;
    if (hessian) {
        if (mode == HessianMode::gauss_newton) {
            *hessian = std::max(e2, 0.0) * dtheta * dtheta.transpose();
        } else {
            const S12 theta = theta_second_order(x);
            Matrix12d h = e2 * theta.g * theta.g.transpose() + e1 * theta.h;
            *hessian = 0.5 * (h + h.transpose());
            internal::project_psd(*hessian);
        }
    }
    return energy;
}

double bending_energy(const Eigen::Matrix<double, 3, 4>& x, const HingeRest& rest,
                      double stiffness_n_m, Vector12d* gradient, Matrix12d* hessian,
                      HessianMode mode) {
    return bending_energy(x, rest, constant_bending_curve(stiffness_n_m), gradient, hessian, mode);
}

}  // namespace drape::cloth
