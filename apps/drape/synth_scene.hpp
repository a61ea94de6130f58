// Synthetic ground-truth scenes (issue 6, the paper's section 7 "Evaluation"): a body
// sampled from the ANSUR II prior in a natural standing pose, dressed in garments of known
// sizing G and material, draped by simulation and rendered under mid-day and sunset light,
// with the answers written beside the images (docs/synthetic.md).
//
// Everything random is drawn from independent streams derived from one seed with our own
// generator (splitmix64, no std:: distributions), and the renderer is deterministic, so a
// scene is the same bytes on the same build.
#pragma once

#include "garment_json.hpp"

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/cloth/material.hpp>
#include <drape/render/material.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::app {

/// What `drape synth` is asked for; "random" picks from the seed.
struct SynthOptions {
    std::uint64_t seed = 0;
    /// "skirt", "pants", "tshirt", "dress", "tshirt+pants", "tshirt+skirt" or "random".
    std::string garment = "random";
    std::string pose = "random";      ///< "a" (A-pose), "b" (arms down), "c" (walking), "random"
    std::string material = "random";  ///< a built-in measured fabric name, or "random"
    /// Bending scale s_b; <= 0 = the default (random material: log-uniform in [1, 100];
    /// named material: 1).
    double bending_scale = 0;
    double edge_cm = 4.0;      ///< mesh target edge length, (0, 20] cm
    /// Dynamic steps of each drape at most (>= 20); untangling and the fallback after a
    /// failed static solve are capped at a third of it each.
    int max_steps = 600;
    int width_px = 600;        ///< image size; height >= 600
    int height_px = 900;
    int samples_per_pixel = 16;  ///< 1..4096
    int threads = 0;           ///< render threads (0 = all); the output does not depend on it
    bool is_valid(std::string* why = nullptr) const;
};

/// One garment of a scene, as sampled.
struct SynthGarment {
    GarmentSizing sizing;
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

/// Samples a scene from `options` (body, pose, sizing, material, look, camera).
/// \throw drape::InvalidInput for invalid options or an unknown garment/pose/material.
SynthScene sample_synth_scene(const SynthOptions& options);

/// Per-garment outcome of a drape.
struct SynthGarmentResult {
    std::string type;
    bool usable = false;
    std::string drape_report;  ///< an outfit's garments share one drape and its report
    double seconds = 0;        ///< of that drape
};

/// Outcome of make_synth_scene.
struct SynthSummary {
    std::vector<SynthGarmentResult> garments;
    double seconds_drape = 0;
    double seconds_render = 0;
    double seconds = 0;
    bool usable() const;  ///< every drape usable
    std::string brief_report() const;
};

/// Drapes and renders `scene` and writes into `dir`: image_midday.png, image_sunset.png,
/// labels.png, strokes.png, joints.json, truth.json, summary.json (docs/synthetic.md).
/// Files hold no timings (they are in the returned summary only).
/// \throw drape::InvalidInput, drape::IoError; std::runtime_error if body shaping fails.
SynthSummary make_synth_scene(const SynthScene& scene, const SynthOptions& options,
                              const std::filesystem::path& dir);

}  // namespace drape::app
