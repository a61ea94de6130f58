// Draping a sampled scene through the one outfit pipeline (garment::dress_outfit): its
// garments made from their sampled sizings, meshed, dressed in the rest A-pose and draped
// on its body in its pose, an outfit together (lower garment first, each in its own fabric).
#pragma once

#include <drape/garment/dress_outfit.hpp>
#include <drape/synth/sampling.hpp>
#include <drape/synth/synth_options.hpp>

namespace drape::synth {

/// The drape options of a scene: at most `max_steps` dynamic steps, untangling and the
/// fallback after a failed static solve at most a third of it each.
garment::DrapeOptions synth_drape_options(int max_steps);

struct SynthDrape {
    garment::DressedOutfit outfit;        ///< per garment: pattern, mesh, dressing, draped positions
    garment::DressOutfitSummary summary;  ///< an outfit's garments share one simulation (summary.drape)
};

/// Drapes `scene`'s garments (their sampled sizings and fabrics, meshed at options.edge_cm)
/// on its body in scene.pose. The arms are not raised again: sample_synth_scene cleared
/// them of the trunk already.
/// \throw drape::InvalidInput for invalid options or a scene without a shaped body;
///        std::runtime_error if a pattern cannot be meshed.
SynthDrape drape_synth_scene(const SynthScene& scene, const SynthOptions& options);

}  // namespace drape::synth
