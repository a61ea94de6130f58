// The self-contact penalty of one pair (contact_barrier.hpp).
#include "contact_barrier.hpp"

#include <drape/core/errors.hpp>

#include "psd_projection.hpp"

#include <cmath>

namespace drape::cloth::internal {

using Mat34 = Eigen::Matrix<double, 3, 4>;

bool SelfContactParams::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!(thickness_m > 0) || !std::isfinite(thickness_m))
        return fail("thickness_m must be positive and finite, got " +
                    std::to_string(thickness_m));
    if (!(stiffness_n_per_m > 0) || !std::isfinite(stiffness_n_per_m))
        return fail("stiffness_n_per_m must be positive and finite, got " +
                    std::to_string(stiffness_n_per_m));
    return true;
}

double pair_energy(ContactPair::Kind kind, const Mat34& x, const SelfContactParams& params,
                   Vector12d* gradient, Matrix12d* hessian, HessianMode mode) {
    if (gradient) gradient->setZero();
    if (hessian) hessian->setZero();
    DistanceRegime regime;
    const double d2 = pair_distance_squared(kind, x, &regime);
    const double h = params.thickness_m, k = params.stiffness_n_per_m;
    const double d = std::sqrt(d2);
    if (!(d < h)) return 0;
    const double energy = 0.5 * k * (h - d) * (h - d);
    if ((!gradient && !hessian) || !(d > 0)) return energy;

    // Envelope theorem: ∇d = n̂ ⊗ w, with w the closest points' weights (r = x w, n̂ = r/|r|).
    const Eigen::Vector4d w = regime_weights(regime, x);
    const Eigen::Vector3d normal = (x * w).normalized();
    Vector12d grad_d;
    for (int c = 0; c < 4; ++c) grad_d.segment<3>(3 * c) = w(c) * normal;
    // ψ' = −k(h − d), ψ'' = k.
    const double dpsi = -k * (h - d);
    if (gradient) *gradient = dpsi * grad_d;
    if (hessian) {
        *hessian = k * grad_d * grad_d.transpose();
        if (mode != HessianMode::gauss_newton) {
            // d = sqrt(s): ∇²d = ∇²s / 2d − ∇s∇sᵀ / 4d³ with ∇s = 2d ∇d.
            Matrix12d hs;
            regime_distance_squared(regime, x, nullptr, &hs);
            *hessian += dpsi * (hs - 2 * grad_d * grad_d.transpose()) / (2 * d);
            if (mode == HessianMode::projected_psd) project_psd<12>(*hessian);
        }
    }
    return energy;
}

}  // namespace drape::cloth::internal
