// The exact Euclidean distance transform of a binary image: the one implementation behind
// the body fit's silhouette term (libbody) and the garment silhouette distance (libgarment).
#pragma once

#include <cstdint>
#include <vector>

namespace drape::core {

/// Distance (pixels) from every pixel centre of a `width` x `height` row-major image to the
/// nearest pixel centre whose value is `target` (non-zero when target is true, zero when
/// false); 0 on such pixels. Exact Euclidean distance (Felzenszwalb & Huttenlocher's
/// lower-envelope algorithm, "Distance transforms of sampled functions", Theory of Computing
/// 8, 2012). If no pixel has the target value every distance is width + height.
/// \pre pixels.size() == width * height, width >= 0, height >= 0 (else an empty result).
std::vector<float> distance_transform(int width, int height, const std::vector<std::uint8_t>& pixels, bool target);

}  // namespace drape::core
