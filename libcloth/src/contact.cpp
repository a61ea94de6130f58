#include <drape/cloth/contact.hpp>

#include <cmath>

namespace drape::cloth {

double plane_contact_energy(const Eigen::Vector3d& x, const Eigen::Vector3d& point,
                            const Eigen::Vector3d& normal, double thickness_m,
                            double stiffness_n_per_m, Eigen::Vector3d* gradient,
                            Eigen::Matrix3d* hessian, double inside_factor) {
    const double d = normal.dot(x - point), gap = thickness_m - d;
    if (gap <= 0) {
        if (gradient) gradient->setZero();
        if (hessian) hessian->setZero();
        return 0;
    }
    const double depth = d < 0 ? -d : 0.0, extra = (inside_factor - 1) * stiffness_n_per_m;
    if (gradient) *gradient = -(stiffness_n_per_m * gap + extra * depth) * normal;
    if (hessian) *hessian = (stiffness_n_per_m + (depth > 0 ? extra : 0.0)) * normal * normal.transpose();
    return 0.5 * stiffness_n_per_m * gap * gap + 0.5 * extra * depth * depth;
}

double friction_energy(const Eigen::Vector3d& displacement_m, const Eigen::Vector3d& normal,
                       double normal_force_n, double friction, double epsilon_m,
                       Eigen::Vector3d* gradient, Eigen::Matrix3d* hessian, double majorize_above_m) {
    const double scale = friction * normal_force_n;
    const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - normal * normal.transpose();
    const Eigen::Vector3d u = tangent * displacement_m;
    const double y = u.norm();
    const double eps = epsilon_m;
    if (y >= eps) {
        if (gradient) *gradient = scale * u / y;
        if (hessian) {
            *hessian = scale / y * tangent;
            if (y <= majorize_above_m) *hessian -= scale / (y * y * y) * u * u.transpose();
        }
        return scale * y;
    }
    // f₀(y) = −y³/(3ε²) + y²/ε + ε/3;  f₁ = f₀' = −y²/ε² + 2y/ε;  f₁/y = 2/ε − y/ε².
    const double f1_over_y = 2 / eps - y / (eps * eps);
    if (gradient) *gradient = scale * f1_over_y * u;
    if (hessian) {
        *hessian = scale * f1_over_y * tangent;
        if (y > 0) *hessian -= scale / (eps * eps * y) * u * u.transpose();
    }
    return scale * (-y * y * y / (3 * eps * eps) + y * y / eps + eps / 3);
}

double stitch_energy(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, double rest_length_m,
                     double stiffness_n_per_m, Vector6d* gradient, Matrix6d* hessian,
                     HessianMode mode) {
    const Eigen::Vector3d d = xa - xb;
    const double len = d.norm();
    const double k = stiffness_n_per_m;
    const double stretch = len - rest_length_m;
    Eigen::Vector3d g3;
    Eigen::Matrix3d h3;
    if (rest_length_m <= 0 || len <= 0) {
        // L = 0: ½ k |d|², exactly quadratic (and smooth at d = 0).
        g3 = k * d;
        h3 = k * Eigen::Matrix3d::Identity();
    } else {
        const Eigen::Vector3d dir = d / len;
        g3 = k * stretch * dir;
        double transverse = 1 - rest_length_m / len;
        if (mode != HessianMode::exact) transverse = std::max(transverse, 0.0);
        h3 = k * (dir * dir.transpose() +
                  transverse * (Eigen::Matrix3d::Identity() - dir * dir.transpose()));
    }
    if (gradient) {
        gradient->head<3>() = g3;
        gradient->tail<3>() = -g3;
    }
    if (hessian) {
        hessian->topLeftCorner<3, 3>() = h3;
        hessian->bottomRightCorner<3, 3>() = h3;
        hessian->topRightCorner<3, 3>() = -h3;
        hessian->bottomLeftCorner<3, 3>() = -h3;
    }
    return rest_length_m <= 0 ? 0.5 * k * d.squaredNorm() : 0.5 * k * stretch * stretch;
}

}  // namespace drape::cloth
