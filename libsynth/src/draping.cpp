#include <drape/synth/draping.hpp>

#include <drape/body/body_model.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_sizing.hpp>

#include <algorithm>
#include <chrono>
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
    const std::size_t n = scene.garments.size();
    require(n >= 1, "drape synth: the scene has no garment");
    SynthDrape d;
    d.meshes.resize(n);
    d.meshing.resize(n);
    std::vector<cloth::Material> materials;
    for (std::size_t i = 0; i < n; ++i) {
        d.patterns.push_back(garment::make_pattern(scene.garments[i].sizing));
        materials.push_back(scene.garments[i].material);
        garment::MeshOptions mesh_options;
        mesh_options.target_edge_cm = options.edge_cm;
        d.meshing[i] = garment::mesh_pattern(d.patterns[i], mesh_options, d.meshes[i]);
        if (!d.meshing[i].usable())
            throw std::runtime_error("drape synth: meshing failed: " + d.meshing[i].brief_report());
    }
    const garment::DrapeOptions drape_options = synth_drape_options(options.max_steps);
    d.positions.resize(n);
    d.dressing.resize(n);
    const auto t0 = std::chrono::steady_clock::now();
    // A single garment is dressed in the rest A-pose and moved to the scene's pose with the
    // body (starts without crossings); an outfit's garments are dressed and draped together.
    d.drape = n == 1 ? garment::dress_and_drape(d.patterns[0], d.meshes[0], model, scene.shaped, scene.pose,
                                                materials[0], garment::DressingOptions{}, drape_options,
                                                d.positions[0], &d.dressing[0])
                     : garment::dress_and_drape_outfit(d.patterns, d.meshes, model, scene.shaped, scene.pose,
                                                       materials, garment::DressingOptions{}, drape_options,
                                                       d.positions, &d.dressing);
    d.seconds_drape = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return d;
}

}  // namespace drape::synth
