#include <drape/cloth/energies.hpp>

#include <drape/core/errors.hpp>

#include "psd_projection.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace drape::cloth {

namespace {

Eigen::Matrix2d stress(const Eigen::Matrix2d& g, const StretchingStiffness& k) {
    Eigen::Matrix2d s;
    s(0, 0) = k.k_uu * g(0, 0) + k.k_uv * g(1, 1);
    s(1, 1) = k.k_uv * g(0, 0) + k.k_vv * g(1, 1);
    s(0, 1) = s(1, 0) = k.k_shear * g(0, 1);
    return s;
}

}  // namespace

TriangleRest triangle_rest(const Eigen::Vector2d& u0, const Eigen::Vector2d& u1,
                           const Eigen::Vector2d& u2) {
    require(u0.allFinite() && u1.allFinite() && u2.allFinite(),
            "triangle_rest: a pattern coordinate is not finite");
    Eigen::Matrix2d dm;
    dm.col(0) = u1 - u0;
    dm.col(1) = u2 - u0;
    const double area = 0.5 * dm.determinant();
    require(area > 1e-12, "triangle_rest: pattern triangle has signed area ", area,
            " m² (degenerate or clockwise)");
    TriangleRest rest;
    rest.dm_inverse = dm.inverse();
    rest.area_m2 = area;
    return rest;
}

Eigen::Matrix2d green_strain(const Eigen::Matrix3d& x, const TriangleRest& rest) {
    Eigen::Matrix<double, 3, 2> ds;
    ds.col(0) = x.col(1) - x.col(0);
    ds.col(1) = x.col(2) - x.col(0);
    const Eigen::Matrix<double, 3, 2> f = ds * rest.dm_inverse;
    return 0.5 * (f.transpose() * f - Eigen::Matrix2d::Identity());
}

double stretching_energy(const Eigen::Matrix3d& x, const TriangleRest& rest,
                         const StretchingStiffness& k, Vector9d* gradient, Matrix9d* hessian,
                         HessianMode mode) {
    Eigen::Matrix<double, 3, 2> ds;
    ds.col(0) = x.col(1) - x.col(0);
    ds.col(1) = x.col(2) - x.col(0);
    const Eigen::Matrix<double, 3, 2> f = ds * rest.dm_inverse;
    const Eigen::Matrix2d g = 0.5 * (f.transpose() * f - Eigen::Matrix2d::Identity());
    const double a = rest.area_m2;
    const double psi = 0.5 * k.k_uu * g(0, 0) * g(0, 0) + k.k_uv * g(0, 0) * g(1, 1) +
                       0.5 * k.k_vv * g(1, 1) * g(1, 1) + k.k_shear * g(0, 1) * g(0, 1);
    if (!gradient && !hessian) return a * psi;

    // ∂F/∂x_i = e_c ⊗ grad_i, with grad_i the shape-function gradients in the pattern.
    Eigen::Matrix<double, 2, 3> shape;
    shape.col(1) = rest.dm_inverse.row(0).transpose();
    shape.col(2) = rest.dm_inverse.row(1).transpose();
    shape.col(0) = -shape.col(1) - shape.col(2);
    const Eigen::Matrix2d s = stress(g, k);
    const Eigen::Matrix<double, 3, 2> p = f * s;  // first Piola-Kirchhoff stress

    if (gradient)
        for (int i = 0; i < 3; ++i) gradient->segment<3>(3 * i) = a * p * shape.col(i);

    if (hessian) {
        // Gauss-Newton split: material part (F ∂S/∂G F, PSD when ψ is convex in G) plus the
        // geometric part ∇Nᵢᵀ S ∇Nⱼ I₃, made PSD by clamping S's negative eigenvalues (the
        // compressed directions) — no 9 x 9 eigen-decomposition.
        const bool convex = k.k_uu >= 0 && k.k_vv >= 0 && k.k_shear >= 0 &&
                            k.k_uu * k.k_vv >= k.k_uv * k.k_uv;
        const bool gauss_newton = mode == HessianMode::gauss_newton && convex;
        Eigen::Matrix2d s_geo = s;
        if (gauss_newton) {
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(s);
            s_geo = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
                    eig.eigenvectors().transpose();
        }
        for (int j = 0; j < 3; ++j)
            for (int c = 0; c < 3; ++c) {
                Eigen::Matrix<double, 3, 2> df = Eigen::Matrix<double, 3, 2>::Zero();
                df.row(c) = shape.col(j).transpose();
                const Eigen::Matrix2d dg = 0.5 * (df.transpose() * f + f.transpose() * df);
                const Eigen::Matrix<double, 3, 2> dp = df * s_geo + f * stress(dg, k);
                for (int i = 0; i < 3; ++i)
                    hessian->block<3, 1>(3 * i, 3 * j + c) = a * dp * shape.col(i);
            }
        *hessian = 0.5 * (*hessian + hessian->transpose()).eval();
        if (mode != HessianMode::exact && !gauss_newton) internal::project_psd(*hessian);
    }
    return a * psi;
}

}  // namespace drape::cloth
