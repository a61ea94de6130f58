// Rendering a draped scene: the body lowered by scene.placement (the camera at its height)
// and its garments on a studio cove, seen by the scene's camera under mid-day and sunset
// light, with the label map and the simulated strokes of a person marking it.
#pragma once

#include <drape/synth/draping.hpp>
#include <drape/render/renderer.hpp>
#include <drape/render/lighting.hpp>
#include <drape/render/scene.hpp>
#include <drape/synth/sampling.hpp>
#include <drape/synth/synth_options.hpp>

#include <opencv2/core.hpp>

#include <Eigen/Core>

namespace drape::synth {

/// The render scene: the body (label 41, skin colour) and each draped garment (its look
/// and label, pattern coordinates as UV, Phong-tessellated render::kSimulatedGarmentSubdivisions
/// times) moved by scene.placement, on a floor under the lowest point and a backdrop.
/// \param body_vertices the posed body, #B x 3 world metres (before placement).
render::Scene synth_render_scene(const SynthScene& scene, const Eigen::MatrixXd& body_vertices,
                                 const garment::DressedOutfit& outfit);

/// Renders synth_render_scene with the scene's camera under one lighting preset at
/// options.samples_per_pixel on options.threads.
/// \throw drape::InvalidInput as render::Renderer.
render::RenderImages render_synth_lighting(const SynthScene& scene, const Eigen::MatrixXd& body_vertices,
                                           const garment::DressedOutfit& outfit, const SynthOptions& options,
                                           render::LightingPreset preset);

struct SynthImages {
    render::RenderImages midday;  ///< colour, labels, depth, ... under LightingPreset::midday
    render::RenderImages sunset;  ///< under LightingPreset::sunset
    cv::Mat strokes;              ///< CV_8UC1, vision::simulate_strokes of midday.labels
};

/// Renders synth_render_scene with the scene's camera at options.samples_per_pixel on
/// options.threads (the bytes do not depend on the thread count).
/// \throw drape::InvalidInput as render::Renderer.
SynthImages render_synth_scene(const SynthScene& scene, const Eigen::MatrixXd& body_vertices,
                               const garment::DressedOutfit& outfit, const SynthOptions& options);

}  // namespace drape::synth
