// overlay.png: the recovered body and garments rendered with the fitted camera over the
// photo they were recovered from, so a user sees the fit (docs/recovery.md, "Output
// files"). It is librender's studio preview scene (render/preview.hpp: the body in a
// neutral skin tone, garments blue, terracotta, olive, ... on their Phong-tessellated
// surfaces, without the floor), ray traced with shading and composited
// (render/overlay.hpp) with the body more transparent than the garments.
#pragma once

#include <drape/body/camera.hpp>
#include <drape/recover/outfit_meshes.hpp>
#include <drape/render/lighting.hpp>

#include <opencv2/core.hpp>

#include <string>

namespace drape::recover {

enum class OverlayLayout {
    blended,       ///< the render over the photo, the photo's size
    side_by_side,  ///< the photo on the left, the blended image on the right (twice as wide)
};

struct OverlayOptions {
    double body_opacity = 0.45;     ///< [0, 1]: 0 shows only the photo where the body is
    double garment_opacity = 0.85;  ///< [0, 1]
    int samples_per_pixel = 8;      ///< 1..4096 (render::RenderOptions)
    int threads = 0;                ///< 0 = all hardware threads
    render::LightingPreset lighting = render::LightingPreset::studio;
    OverlayLayout layout = OverlayLayout::blended;

    bool is_valid(std::string* why = nullptr) const;
};

/// Renders `outfit` seen by `camera` (the fitted photo camera, render::Camera::from_body)
/// at the photo's size and composites it over `photo`: where the body is the nearest
/// surface at a pixel, opacity body_opacity; elsewhere garment_opacity (times the render's
/// coverage of the pixel, so silhouettes are anti-aliased).
/// \param photo CV_8UC3 BGR.
/// \return CV_8UC3 BGR, the photo's size (blended) or twice its width (side_by_side).
/// \throw drape::InvalidInput naming the problem: an empty or non-BGR photo, an invalid
///        outfit (OutfitMeshes::validate), camera or options.
cv::Mat render_overlay(const cv::Mat& photo, const OutfitMeshes& outfit, const body::Camera& camera,
                       const OverlayOptions& options = {});

}  // namespace drape::recover
