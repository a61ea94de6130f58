// Per-vertex energies of body contact, friction and seams, with analytic gradients and
// Hessians (finite-difference tested like the elastic energies in energies.hpp).
//
// Body contact: each cloth vertex near the obstacle is held off the surface by a penalty on
// its distance to the tangent plane at its closest surface point (point c, outward normal
// n), refreshed every Newton iteration: E = ½ k (h − n·(x − c))² while n·(x − c) < h, h
// being the contact thickness. Friction is the smoothed Coulomb model of incremental
// potential contact (Li et al. 2020), lagged per Newton iteration: with the tangential
// displacement u = (I − nnᵀ)(x − x_ref) over the time step and the normal force λ,
// E = μ λ f₀(|u|), f₀(y) = −y³/(3ε²) + y²/ε + ε/3 below ε and y above, so that the force
// is μλ once the slip exceeds ε (static friction regularised over ε = ε_v Δt).
#pragma once

#include <drape/cloth/energies.hpp>

#include <Eigen/Core>

#include <limits>

namespace drape::cloth {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Penalty of one vertex against a contact plane: with d = n·(x − c), ½ k (h − d)² if d < h,
/// else 0, plus ½ (β − 1) k d² behind the plane (d < 0), so that the penalty is β times as
/// stiff once the vertex has crossed the surface (C¹ at d = 0). \param x vertex (world, m);
/// \param point c and \param normal n (unit) of the plane; \param thickness_m h;
/// \param stiffness_n_per_m k; \param inside_factor β >= 1. \param gradient (3) and
/// \param hessian (3 x 3; k nnᵀ, β k nnᵀ behind the plane, PSD) if not null.
double plane_contact_energy(const Eigen::Vector3d& x, const Eigen::Vector3d& point,
                            const Eigen::Vector3d& normal, double thickness_m,
                            double stiffness_n_per_m, Eigen::Vector3d* gradient = nullptr,
                            Eigen::Matrix3d* hessian = nullptr, double inside_factor = 1.0);

/// Smoothed Coulomb friction of one vertex: μ λ f₀(|(I − nnᵀ) d|), d = x − x_ref.
/// \param displacement_m d; \param normal n (unit); \param normal_force_n λ >= 0;
/// \param friction μ >= 0; \param epsilon_m ε > 0 (slip below which friction is static-like).
/// The Hessian returned is PSD (f₀ is convex along |u| and the transverse part is >= 0).
/// \param majorize_above_m where the tangential slip |u| exceeds max(ε, this), the Hessian
/// returned is the quadratic majorizer μλ/|u| (I − nnᵀ) instead of the exact μλ/|u| (I − nnᵀ −
/// ûûᵀ), which is zero along the slip (infinity, the default: always exact). The energy and
/// gradient do not change; Newton then takes bounded steps for a vertex sliding far.
double friction_energy(const Eigen::Vector3d& displacement_m, const Eigen::Vector3d& normal,
                       double normal_force_n, double friction, double epsilon_m,
                       Eigen::Vector3d* gradient = nullptr, Eigen::Matrix3d* hessian = nullptr,
                       double majorize_above_m = std::numeric_limits<double>::infinity());

/// A seam stitch between two vertices: ½ k (|xa − xb| − L)², L >= 0 the current rest length
/// (shrunk to 0 while a seam is being closed). \param gradient 6 (xa, xb); \param hessian
/// 6 x 6: exact, or PSD (the transverse factor 1 − L/|d| clamped at 0) for projected modes.
double stitch_energy(const Eigen::Vector3d& xa, const Eigen::Vector3d& xb, double rest_length_m,
                     double stiffness_n_per_m, Vector6d* gradient = nullptr,
                     Matrix6d* hessian = nullptr, HessianMode mode = HessianMode::projected_psd);

}  // namespace drape::cloth
