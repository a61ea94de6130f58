// Synthetic ground-truth scenes (the paper's section 7 "Evaluation", docs/synthetic.md): a
// sampled scene (sampling.hpp) draped (draping.hpp), rendered (rendering.hpp) and measured
// (measuring.hpp), returned as plain structs; `drape synth` writes them as files and a later
// `eval-synthetic` can compare recovery with them.
#pragma once

#include <drape/body/pose.hpp>
#include <drape/synth/draping.hpp>
#include <drape/synth/measuring.hpp>
#include <drape/synth/rendering.hpp>
#include <drape/synth/sampling.hpp>
#include <drape/synth/synth_options.hpp>

#include <string>
#include <vector>

namespace drape::synth {

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
    double seconds_drape = 0;   ///< meshing and draping
    double seconds_render = 0;  ///< both renders and the strokes
    double seconds = 0;
    bool usable() const;  ///< every drape usable
    std::string brief_report() const;
};

/// Everything made for a scene.
struct SynthResult {
    body::PosedBody posed;                    ///< the body in scene.pose (before placement)
    SynthDrape drape;
    SynthImages images;
    vision::Joints joints;                    ///< project_joints
    std::vector<double> mean_curvature_per_m; ///< mean_curvatures, per garment
    std::vector<DeepestInside> deepest;       ///< deepest_inside, per garment
    std::vector<GarmentWrinkles> wrinkles;    ///< measure_wrinkles on the mid-day render
    SynthSummary summary;
};

/// Drapes, renders and measures `scene`: the stages above in order.
/// \throw drape::InvalidInput for invalid options or a scene without a shaped body;
///        std::runtime_error if a pattern cannot be meshed.
SynthResult make_synth_scene(const SynthScene& scene, const SynthOptions& options);

}  // namespace drape::synth
