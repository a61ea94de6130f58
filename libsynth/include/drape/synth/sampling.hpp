// Sampling a synthetic scene before any simulation (docs/synthetic.md, "Protocol"): a body
// from the ANSUR II prior, a natural standing pose, garment sizings G around each template's
// proposal, measured fabrics, colours and prints, and a pinhole camera. Every draw comes from
// its own stream of the seed (rng.hpp).
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/body/shape_prior.hpp>
#include <drape/cloth/material.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/render/material.hpp>
#include <drape/synth/rng.hpp>
#include <drape/synth/synth_options.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace drape::synth {

/// One garment of a scene, as sampled.
struct SynthGarment {
    garment::GarmentSizing sizing;
    std::string base_fabric;      ///< built-in measured fabric the tables come from
    cloth::Material material;     ///< the fabric's tables with the sampled scales
    render::Material look;        ///< colour and print
    int label = 0;                ///< labels.txt id
};

/// Everything sampled for a scene before any simulation.
struct SynthScene {
    std::uint64_t seed = 0;
    body::SemanticShape shape;
    body::ShapedBody shaped;      ///< the body shaped for `shape` (rest pose)
    std::string shaping_report;   ///< body::ShapeSummary::brief_report of that shaping
    std::string pose_name;        ///< a_pose, arms_down or walking
    body::Pose pose;              ///< as simulated (feet on y = 0, no translation)
    /// Root translation applied after draping for the render (the camera stands at the
    /// origin's height); the truth pose is `pose` plus this translation.
    Eigen::Vector3d placement = Eigen::Vector3d::Zero();
    body::Camera camera;          ///< pinhole, the `drape fit-body` camera convention
    int width_px = 600;
    int height_px = 900;
    Eigen::Vector3d skin_srgb{0.8, 0.74, 0.67};
    std::vector<SynthGarment> garments;  ///< layered in this order (lower garments first)
};

/// The ten fabrics measured by Wang et al. 2011 (the built-ins but paper and aluminium).
std::vector<std::string> measured_fabrics();

/// The outfit `options` asks for, or one drawn from the six of SynthOptions::garments.
std::vector<garment::GarmentType> sample_garments(Rng& rng, const std::vector<garment::GarmentType>& asked);

/// A body shape from the prior: a random gender, then each semantic value from the
/// gender's Gaussian with 2-sigma truncated draws, redrawn until inside the survey's range.
body::SemanticShape sample_body(Rng& rng, const body::ShapePrior& prior);

/// "a_pose", "arms_down", "walking" (as summary.json names them).
std::string pose_name(body::NamedPose pose);

/// The named pose with about 1 degree of variation on the joints a standing person moves and
/// a turn of up to 20 degrees left or right of the camera.
body::Pose sample_pose(Rng& rng, body::NamedPose pose);

/// The template's proposal for the body with seeded ease, then seeded length and flare
/// changes; a variation the template rejects is redrawn (the proposal after 20 tries).
/// \param skirt_waistband_girth_m garment::skirt_waistband's girth (used by skirts only).
garment::GarmentSizing sample_sizing(Rng& rng, garment::GarmentType type, const body::BodyMeasurements& measured,
                                     double skirt_waistband_girth_m);

/// A colour from a palette of 12, a roughness and a print (solid, stripes, checks or dots).
render::Material sample_look(Rng& rng);

/// The labels.txt id of a template's garments (skirt 42, pants 31, t-shirt 51, dress 14).
int garment_label(garment::GarmentType type);

/// A pinhole camera (the fit-body convention: centre (0, 0, d), looking down -Z) with a
/// 28-degree vertical view framing a body of `height_m` with its height plus 25 %, the
/// camera at a drawn height above the floor; `placement` is the root translation that
/// lowers the body to it.
body::Camera sample_camera(Rng& rng, double height_m, int width_px, int height_px, Eigen::Vector3d& placement);

/// Samples a scene from `options` (body, pose, sizing, material, look, camera).
/// \throw drape::InvalidInput for invalid options or an unknown fabric;
///        std::runtime_error if body shaping fails.
SynthScene sample_synth_scene(const SynthOptions& options);

}  // namespace drape::synth
