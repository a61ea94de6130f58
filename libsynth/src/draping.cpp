#include <drape/synth/draping.hpp>

#include <drape/body/body_model.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <stdexcept>

namespace drape::synth {

garment::DrapeOptions synth_drape_options(int max_steps) {
    garment::DrapeOptions o;
    o.max_steps = max_steps;
    o.max_untangle_steps = std::min(o.max_untangle_steps, max_steps / 3);
    o.fallback_steps = std::min(o.fallback_steps, max_steps / 3);
    o.min_steps = std::min(o.min_steps, max_steps);
    return o;
}

SynthDrape drape_synth_scene(const SynthScene& scene, const SynthOptions& options) {
    std::string why;
    require(options.is_valid(&why), "drape synth: ", why);
    const body::BodyModel& model = body::BodyModel::default_model();
    require(scene.shaped.vertices.rows() == model.vertex_count(), "drape synth: the scene has no shaped body");
    std::vector<garment::GarmentRequest> requests;
    for (const SynthGarment& g : scene.garments) {
        garment::GarmentRequest r;
        r.type = g.sizing.type;
        r.sizing = g.sizing;
        r.material = g.material;
        requests.push_back(r);
    }
    garment::DressOutfitOptions o;
    o.mesh.target_edge_cm = options.edge_cm;
    o.drape = synth_drape_options(options.max_steps);
    o.clear_arms = false;
    SynthDrape d;
    d.summary = garment::dress_outfit(model, scene.shaped, scene.pose, requests, o, d.outfit);
    if (d.summary.termination == garment::DressOutfitTermination::meshing_failed)
        throw std::runtime_error("drape synth: " + d.summary.message);
    return d;
}

}  // namespace drape::synth
