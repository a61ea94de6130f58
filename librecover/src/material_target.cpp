#include "material_target.hpp"

#include <algorithm>

namespace drape::recover {

// The paper's mapping (section 5.2): K linear in P through I(1) = 1e-4 and I(50) = 1e5 1/m.
// Interim until the calibrated mapping lands; kept within the curvatures drapes reach.
CurvatureTarget curvature_target(garment::GarmentType, double p) {
    CurvatureTarget t;
    const double k = 1e-4 + (p - 1.0) * (1e5 - 1e-4) / 49.0;
    t.k_per_m = std::clamp(k, 0.5, 30.0);
    t.k_low = 0.8 * t.k_per_m;
    t.k_high = 1.2 * t.k_per_m;
    return t;
}

}  // namespace drape::recover
