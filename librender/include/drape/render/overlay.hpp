// Compositing a render over a photo (e.g. a fitted body or recovered garments over the
// image they were recovered from).
#pragma once

#include <drape/render/renderer.hpp>

#include <opencv2/core.hpp>

namespace drape::render {

/// out = a F + (1 - a) P per channel (8-bit, rounded), with a = opacity x alpha / 255,
/// F = render.foreground and P = photo.
/// \param photo CV_8UC3 BGR with the render's size.
/// \param opacity in [0, 1].
/// \throw drape::InvalidInput on size / type mismatch or opacity outside [0, 1].
cv::Mat composite_over(const cv::Mat& photo, const RenderImages& render, double opacity = 1.0);

}  // namespace drape::render
