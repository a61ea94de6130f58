// Private to librecover: the material search's target mean curvature K from the wrinkle
// density P measured in the photo (docs/recovery.md, "Material").
#pragma once

#include <drape/garment/garment_type.hpp>

namespace drape::recover {

struct CurvatureTarget {
    double k_per_m = 0;              ///< the target K, 1/m, > 0
    double k_low = 0, k_high = 0;    ///< its uncertainty interval
    bool has_bending = false;        ///< a direct estimate of the bending scale is known
    double log10_bending = 1.0;      ///< ... which the search starts from
};

/// K(P) for a garment of `type`; P >= 0 (0 = no fold detected).
CurvatureTarget curvature_target(garment::GarmentType type, double p_per_m2);

}  // namespace drape::recover
