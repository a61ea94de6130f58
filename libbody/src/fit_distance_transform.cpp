#include "fit_distance_transform.hpp"

#include <drape/core/distance_transform.hpp>

namespace drape::body::detail {

DistanceField distance_transform(const Mask& mask, bool target) {
    DistanceField out;
    out.width = mask.width;
    out.height = mask.height;
    out.values = core::distance_transform(mask.width, mask.height, mask.pixels, target);
    return out;
}

}  // namespace drape::body::detail
