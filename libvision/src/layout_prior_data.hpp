// Class counts per cell of the body frame (layout_frame.hpp), generated from hand labels by
// tools/derive_layout_prior.cpp into layout_prior_data.cpp (docs/vision.md, "Segmentation").
#pragma once

#include "layout_frame.hpp"

#include <cstdint>

namespace drape::vision::detail {

/// Background, skin, hair, upper, lower, other (occluders, shoes, tights, accessories):
/// the order of AutoLabel (body_layout.hpp).
inline constexpr int kLayoutPriorClasses = 6;

extern const std::uint32_t kLayoutPriorCounts[kFrameCells][kLayoutPriorClasses];

}  // namespace drape::vision::detail
