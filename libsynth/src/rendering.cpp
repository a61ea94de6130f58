#include <drape/synth/rendering.hpp>

#include <drape/body/body_model.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/render/camera.hpp>
#include <drape/render/lighting.hpp>
#include <drape/vision/strokes.hpp>

#include <algorithm>

namespace drape::synth {

render::Scene synth_render_scene(const SynthScene& scene, const Eigen::MatrixXd& body_vertices,
                                 const garment::DressedOutfit& outfit) {
    const body::BodyModel& model = body::BodyModel::default_model();
    const Eigen::RowVector3d shift = scene.placement.transpose();
    render::Scene rs;
    render::Mesh b;
    b.name = "body";
    b.V = body_vertices.rowwise() + shift;
    b.F = model.faces;
    b.material.colour_srgb = scene.skin_srgb;
    b.material.roughness = 0.6;
    b.label = 41;  // labels.txt "skin"
    double floor_y = b.V.col(1).minCoeff();
    rs.meshes.push_back(std::move(b));
    for (std::size_t i = 0; i < scene.garments.size(); ++i) {
        const garment::GarmentMesh& mesh = outfit.meshes[i];
        render::Mesh g;
        g.name = garment::garment_type_name(scene.garments[i].sizing.type);
        g.V = outfit.positions[i].rowwise() + shift;
        g.F = mesh.cloth.faces;
        // Pattern coordinates in metres, so print periods are real sizes on the cloth.
        g.UV = mesh.cloth.pattern.rows() == g.V.rows() ? Eigen::MatrixXd(mesh.cloth.pattern)
                                                       : Eigen::MatrixXd(mesh.uv);
        g.material = scene.garments[i].look;
        g.label = scene.garments[i].label;
        // Drawn on its Phong-tessellated surface: the simulated mesh's flat triangles cut
        // chords through the body (drape::render::phong_tessellate).
        g.smooth_subdivisions = render::kSimulatedGarmentSubdivisions;
        floor_y = std::min(floor_y, g.V.col(1).minCoeff());
        rs.meshes.push_back(std::move(g));
    }
    rs.floor.enabled = true;
    rs.floor.height_m = floor_y;
    rs.backdrop.enabled = true;
    rs.backdrop.distance_m = 1.6;
    return rs;
}

namespace {

render::RenderOptions render_options(const SynthOptions& options) {
    render::RenderOptions ro;
    ro.samples_per_pixel = options.samples_per_pixel;
    ro.threads = options.threads;
    return ro;
}

}  // namespace

render::RenderImages render_synth_lighting(const SynthScene& scene, const Eigen::MatrixXd& body_vertices,
                                           const garment::DressedOutfit& outfit, const SynthOptions& options,
                                           render::LightingPreset preset) {
    const render::Renderer renderer(synth_render_scene(scene, body_vertices, outfit));
    render::RenderImages images;
    renderer.render(render::Camera::from_body(scene.camera, scene.width_px, scene.height_px),
                    render::lighting_preset(preset), render_options(options), images);
    return images;
}

SynthImages render_synth_scene(const SynthScene& scene, const Eigen::MatrixXd& body_vertices,
                               const garment::DressedOutfit& outfit, const SynthOptions& options) {
    // One renderer (one BVH) for both lightings.
    const render::Renderer renderer(synth_render_scene(scene, body_vertices, outfit));
    const render::Camera camera = render::Camera::from_body(scene.camera, scene.width_px, scene.height_px);
    const render::RenderOptions ro = render_options(options);
    SynthImages images;
    renderer.render(camera, render::lighting_preset(render::LightingPreset::midday), ro, images.midday);
    renderer.render(camera, render::lighting_preset(render::LightingPreset::sunset), ro, images.sunset);
    images.strokes = vision::simulate_strokes(images.midday.labels);
    return images;
}

}  // namespace drape::synth
