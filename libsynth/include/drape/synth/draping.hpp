// Draping a sampled scene: its garments made, meshed, dressed in the rest A-pose and draped
// on its body in its pose (garment::dress_and_drape; an outfit together with
// garment::dress_and_drape_outfit, lower garment first, each in its own fabric).
#pragma once

#include <drape/garment/drape_garment.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/synth/sampling.hpp>
#include <drape/synth/synth_options.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::synth {

/// The drape options of a scene: at most `max_steps` dynamic steps, untangling and the
/// fallback after a failed static solve at most a third of it each.
garment::DrapeOptions synth_drape_options(int max_steps);

/// What draping made, one entry per garment of the scene.
struct SynthDrape {
    std::vector<garment::Pattern> patterns;
    std::vector<garment::GarmentMesh> meshes;
    std::vector<garment::MeshSummary> meshing;
    std::vector<garment::DressingSummary> dressing;  ///< each garment's dressing in the rest A-pose
    std::vector<Eigen::MatrixX3d> positions;         ///< draped, #V_i x 3, world metres (before placement)
    /// The one simulation (an outfit's garments share it and its report).
    garment::DrapeSummary drape;
    double seconds_drape = 0;  ///< of that simulation (wall clock)
};

/// Drapes `scene`'s garments (their sampled sizings and fabrics, meshed at options.edge_cm)
/// on its body in scene.pose.
/// \throw drape::InvalidInput for invalid options or a scene without a shaped body;
///        std::runtime_error if a pattern cannot be meshed.
SynthDrape drape_synth_scene(const SynthScene& scene, const SynthOptions& options);

}  // namespace drape::synth
