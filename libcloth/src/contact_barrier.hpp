// Private: the self-contact penalty (barrier) of one pair of primitives, ψ(d) = ½ k (h − d)²
// below the thickness h, with exact, projected or Gauss–Newton derivatives.
#pragma once

#include <drape/cloth/energies.hpp>

#include "contact_distance.hpp"

#include <Eigen/Core>

#include <string>

namespace drape::cloth::internal {

/// Penalty parameters.
struct SelfContactParams {
    double thickness_m = 0.005;          ///< h: pairs closer than h repel
    double stiffness_n_per_m = 1000.0;   ///< k in ψ(d) = ½ k (h − d)² for d < h
    bool is_valid(std::string* why) const;
};

/// Penalty energy of one pair, ψ(d) = ½ k (h − d)² for d < h, 0 otherwise (joules).
/// \param gradient 12 (columns of x, xyz each); \param hessian 12 x 12 (HessianMode:
/// exact, projected_psd, or gauss_newton = k ∇d ∇dᵀ). Zero derivatives when d >= h.
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
