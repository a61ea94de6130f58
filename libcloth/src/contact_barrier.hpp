// Private: the self-contact penalty (barrier) of one pair of primitives, ψ(d) = ½ k (h − d)²
// below the thickness h plus an inner log barrier close to contact, with exact, projected or
// Gauss–Newton derivatives.
#pragma once

#include <drape/cloth/energies.hpp>

#include "contact_distance.hpp"

#include <Eigen/Core>

#include <string>

namespace drape::cloth::internal {

/// Penalty parameters.
///
/// The quadratic penalty alone pushes back with at most k h (at d = 0): a stitch closing a
/// seam or a moving body that presses harder squeezes the pair towards d = 0, where only
/// the step bound (each Newton step may close at most 90 % of a pair's gap) holds it, and
/// the pair ends touching or, by rounding, crossed (docs/notes/dressing.md, 2026-11-26 b).
/// Below d̂ = inner_fraction · h the energy therefore gains κ b(d) with IPC's barrier
/// b(d) = −(d − d̂)² ln(d / d̂) (zero with its first two derivatives at d̂, infinite at 0)
/// and κ = inner_stiffness_factor · k: the repulsion grows without bound as d → 0.
/// Off by default (inner_fraction = 0): the proposed setting 0.2 (d̂ = 1 mm at h = 5 mm) is
/// unit-tested but was not yet evaluated on the garment tables (docs/notes/dressing.md).
struct SelfContactParams {
    double thickness_m = 0.005;          ///< h: pairs closer than h repel
    double stiffness_n_per_m = 1000.0;   ///< k in ψ(d) = ½ k (h − d)² for d < h
    double inner_fraction = 0;           ///< d̂ / h, in [0, 1]; 0: no inner barrier
    double inner_stiffness_factor = 100; ///< κ / k, >= 0
    bool is_valid(std::string* why) const;
};

/// ψ(d) and its first two derivatives with respect to d (zero for d >= h; below 1e-9 d̂
/// the value at 1e-9 d̂ with zero derivatives).
struct ContactPotential {
    double psi = 0, dpsi = 0, d2psi = 0;
};
ContactPotential contact_potential(double d, const SelfContactParams& params);

/// Penalty energy of one pair, ψ(d) = ½ k (h − d)² for d < h (plus the inner barrier below
/// d̂), 0 otherwise (joules).
/// \param gradient 12 (columns of x, xyz each); \param hessian 12 x 12 (HessianMode:
/// exact, projected_psd, or gauss_newton = ψ''(d) ∇d ∇dᵀ). Zero derivatives when d >= h.
/// \pre d > 0 (the penalty is not differentiable through d = 0; the step bound keeps pairs
/// apart).
double pair_energy(ContactPair::Kind kind, const Eigen::Matrix<double, 3, 4>& x,
                   const SelfContactParams& params, Vector12d* gradient = nullptr,
                   Matrix12d* hessian = nullptr,
                   HessianMode mode = HessianMode::projected_psd);

/// One pair's Hessian block for assembly: rows/cols 3 v[c] + i ↔ 3 c + i.
struct PairHessian {
    ContactPair pair;
    Matrix12d hessian;
};

}  // namespace drape::cloth::internal
