#include <drape/synth/synth_scene.hpp>

#include <drape/body/body_model.hpp>
#include <drape/garment/garment_type.hpp>

#include <algorithm>
#include <chrono>
#include <sstream>

namespace drape::synth {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

bool SynthSummary::usable() const {
    return std::all_of(garments.begin(), garments.end(), [](const SynthGarmentResult& g) { return g.usable; });
}

std::string SynthSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "usable" : "NOT usable") << ": ";
    for (const auto& g : garments) os << g.type << " (" << g.drape_report << ", " << g.seconds << " s); ";
    os << "drape " << seconds_drape << " s, render " << seconds_render << " s, total " << seconds << " s";
    return os.str();
}

SynthResult make_synth_scene(const SynthScene& scene, const SynthOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    SynthResult r;
    r.drape = drape_synth_scene(scene, options);
    r.posed = body::pose_body(body::BodyModel::default_model(), scene.shaped, scene.pose);
    for (const SynthGarment& g : scene.garments) {
        SynthGarmentResult gr;
        gr.type = garment::garment_type_name(g.sizing.type);
        gr.usable = r.drape.summary.drape.usable();
        gr.drape_report = r.drape.summary.drape.brief_report();
        gr.seconds = r.drape.summary.seconds_drape;
        r.summary.garments.push_back(gr);
    }
    r.mean_curvature_per_m = mean_curvatures(r.drape.outfit);
    r.deepest = deepest_inside(r.posed.vertices, r.drape.outfit);
    r.summary.seconds_drape = seconds_since(start);

    const auto t_render = std::chrono::steady_clock::now();
    r.images = render_synth_scene(scene, r.posed.vertices, r.drape.outfit, options);
    r.summary.seconds_render = seconds_since(t_render);

    r.joints = project_joints(scene, r.posed);
    r.wrinkles = measure_wrinkles(scene, r.images.midday.colour, r.images.midday.labels, r.joints);
    r.summary.seconds = seconds_since(start);
    return r;
}

}  // namespace drape::synth
