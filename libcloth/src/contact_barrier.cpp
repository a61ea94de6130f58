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
    if (!(inner_fraction >= 0 && inner_fraction <= 1))
        return fail("inner_fraction must be in [0, 1], got " + std::to_string(inner_fraction));
    if (!(inner_stiffness_factor >= 0) || !std::isfinite(inner_stiffness_factor))
        return fail("inner_stiffness_factor must be >= 0 and finite, got " +
                    std::to_string(inner_stiffness_factor));
    return true;
}

ContactPotential contact_potential(double d, const SelfContactParams& params) {
    ContactPotential c;
    const double h = params.thickness_m, k = params.stiffness_n_per_m;
    if (!(d < h)) return c;
    c.psi = 0.5 * k * (h - d) * (h - d);
    c.dpsi = -k * (h - d);
    c.d2psi = k;
    const double dh = params.inner_fraction * h, kappa = params.inner_stiffness_factor * k;
    if (d < dh && kappa > 0) {
        // At d = 0 (no direction to push along) the energy stays finite, the barrier's value at
        // 1e-9 d̂, so that a state that starts touching can still be stepped from.
        if (!(d > 1e-9 * dh)) {
            const double e = 1e-9 * dh - dh, l = std::log(1e-9);
            c.psi += kappa * (-e * e * l);
            c.dpsi = c.d2psi = 0;
            return c;
        }
        // b = −(d − d̂)² ln(d/d̂); b' = −2(d − d̂) ln(d/d̂) − (d − d̂)²/d;
        // b'' = −2 ln(d/d̂) − 4(d − d̂)/d + (d − d̂)²/d².
        const double e = d - dh, l = std::log(d / dh);
        c.psi += kappa * (-e * e * l);
        c.dpsi += kappa * (-2 * e * l - e * e / d);
        c.d2psi += kappa * (-2 * l - 4 * e / d + e * e / (d * d));
    }
    return c;
}

double pair_energy(ContactPair::Kind kind, const Mat34& x, const SelfContactParams& params,
                   Vector12d* gradient, Matrix12d* hessian, HessianMode mode) {
    if (gradient) gradient->setZero();
    if (hessian) hessian->setZero();
    DistanceRegime regime;
    const double d2 = pair_distance_squared(kind, x, &regime);
    const double d = std::sqrt(d2);
    if (!(d < params.thickness_m)) return 0;
    const ContactPotential pot = contact_potential(d, params);
    const double energy = pot.psi;
    if ((!gradient && !hessian) || !(d > 0)) return energy;

    // Envelope theorem: ∇d = n̂ ⊗ w, with w the closest points' weights (r = x w, n̂ = r/|r|).
    const Eigen::Vector4d w = regime_weights(regime, x);
    const Eigen::Vector3d normal = (x * w).normalized();
    Vector12d grad_d;
    for (int c = 0; c < 4; ++c) grad_d.segment<3>(3 * c) = w(c) * normal;
    const double dpsi = pot.dpsi;
    if (gradient) *gradient = dpsi * grad_d;
    if (hessian) {
        *hessian = pot.d2psi * grad_d * grad_d.transpose();
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
