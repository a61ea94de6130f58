#include "wrinkle_synthesis.hpp"

#include <drape/core/errors.hpp>
#include <drape/render/camera.hpp>
#include <drape/render/lighting.hpp>
#include <drape/render/preview.hpp>
#include <drape/render/renderer.hpp>
#include <drape/vision/wrinkle_density.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace drape::recover {

double rendered_wrinkle_density(const OutfitMeshes& scene, const OutfitView& view, const vision::Joints& joints,
                                int samples, int threads) {
    std::vector<render::PreviewGarment> garments;
    for (const OutfitGarment& g : scene.garments) garments.push_back({g.V, g.F, g.UV});
    render::Scene rs = render::preview_scene(scene.body_V, scene.body_F, garments);
    rs.floor.enabled = false;
    render::RenderOptions ro;
    ro.samples_per_pixel = samples;
    ro.threads = threads;
    ro.background_srgb = Eigen::Vector3d(0.5, 0.5, 0.5);
    render::RenderImages images;
    render::render(rs, render::Camera::from_body(view.camera(), view.width(), view.height()),
                   render::lighting_preset(render::LightingPreset::midday), ro, images);
    // The candidate is the last mesh of the scene: mesh index 1 + its garment index.
    const int candidate = static_cast<int>(scene.garments.size());
    cv::Mat mask;
    cv::compare(images.mesh_index, candidate, mask, cv::CMP_EQ);
    if (cv::countNonZero(mask) == 0) return 0.0;
    try {
        const vision::WrinkleSummary w =
            vision::detect_wrinkles(images.colour, mask, cv::Mat(), joints, vision::WrinkleOptions{}, nullptr);
        return w.usable() ? w.density_per_m2 : 0.0;
    } catch (const InvalidInput&) {  // e.g. too small to measure
        return 0.0;
    }
}

SynthesisSearch search_bending_by_synthesis(double photo_p_per_m2, const std::function<double(double)>& p_at) {
    require(photo_p_per_m2 >= 0 && std::isfinite(photo_p_per_m2), "search_bending_by_synthesis: P = ",
            photo_p_per_m2, " must be >= 0");
    std::map<double, std::pair<double, double>> seen;  // x -> (objective, P)
    auto eval = [&](double x) {
        x = std::clamp(x, 0.0, 2.0);
        auto it = seen.find(x);
        if (it != seen.end()) return it->second.first;
        const double p = std::max(0.0, p_at(x));
        const double d = std::log1p(p) - std::log1p(photo_p_per_m2);
        seen[x] = {d * d, p};
        return d * d;
    };
    auto best_x = [&] {
        double bx = 0, bf = std::numeric_limits<double>::infinity();
        for (const auto& [x, v] : seen)
            if (v.first < bf) bx = x, bf = v.first;
        return bx;
    };
    for (double x : {0.0, 0.5, 1.0, 1.5, 2.0}) eval(x);
    const double b = best_x();
    eval(b - 0.25);
    eval(b + 0.25);
    SynthesisSearch out;
    out.log10_bending_scale = best_x();
    out.objective = seen[out.log10_bending_scale].first;
    out.wrinkle_density_per_m2 = seen[out.log10_bending_scale].second;
    out.evaluations = static_cast<int>(seen.size());
    out.low = out.high = out.log10_bending_scale;
    for (const auto& [x, v] : seen)
        if (v.first <= out.objective + 0.05) out.low = std::min(out.low, x), out.high = std::max(out.high, x);
    return out;
}

}  // namespace drape::recover
