#include <drape/synth/print_check.hpp>

#include <drape/body/body_model.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/render/lighting.hpp>
#include <drape/synth/rendering.hpp>

#include <chrono>

namespace drape::synth {

const char* print_name(render::PrintKind kind) {
    switch (kind) {
        case render::PrintKind::solid: return "none";
        case render::PrintKind::stripes: return "stripes";
        case render::PrintKind::checks: return "checks";
        case render::PrintKind::dots: return "dots";
    }
    return "none";
}

double PrintComparison::ratio(std::size_t kind) const {
    const double plain = wrinkles[0].summary.density_per_m2;
    return plain > 0 ? wrinkles[kind].summary.density_per_m2 / plain : 0.0;
}

SynthScene with_print(SynthScene scene, render::PrintKind kind) {
    for (SynthGarment& g : scene.garments) g.look.print.kind = kind;
    return scene;
}

std::vector<PrintComparison> compare_prints(const SynthScene& scene, const std::array<cv::Mat, 4>& midday,
                                            const cv::Mat& labels, const vision::WrinkleOptions& detector) {
    const cv::Size size(scene.width_px, scene.height_px);
    if (labels.type() != CV_8UC1 || labels.size() != size)
        throw InvalidInput("compare_prints: the label map must be CV_8UC1 of the scene's size");
    for (std::size_t k = 0; k < midday.size(); ++k)
        if (midday[k].type() != CV_8UC3 || midday[k].size() != size)
            throw InvalidInput(std::string("compare_prints: the '") + print_name(kPrintKinds[k]) +
                               "' render must be CV_8UC3 of the scene's size");
    const vision::Joints joints =
        project_joints(scene, body::pose_body(body::BodyModel::default_model(), scene.shaped, scene.pose));
    std::vector<PrintComparison> out(scene.garments.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        out[i].type = garment::garment_type_name(scene.garments[i].sizing.type);
        out[i].label = scene.garments[i].label;
        out[i].sampled_print = scene.garments[i].look.print.kind;
    }
    for (std::size_t k = 0; k < midday.size(); ++k) {
        const std::vector<GarmentWrinkles> w = measure_wrinkles(scene, midday[k], labels, joints, detector);
        for (std::size_t i = 0; i < out.size(); ++i) out[i].wrinkles[k] = w[i];
    }
    return out;
}

PrintCheck check_prints(const SynthScene& scene, const SynthResult& made, const SynthOptions& options,
                        const vision::WrinkleOptions& detector) {
    const auto t0 = std::chrono::steady_clock::now();
    PrintCheck c;
    for (std::size_t k = 0; k < kPrintKinds.size(); ++k)
        c.midday[k] = render_synth_lighting(with_print(scene, kPrintKinds[k]), made.posed.vertices, made.drape.outfit,
                                            options, render::LightingPreset::midday)
                          .colour;
    const auto t1 = std::chrono::steady_clock::now();
    c.seconds_render = std::chrono::duration<double>(t1 - t0).count();
    c.garments = compare_prints(scene, c.midday, made.images.midday.labels, detector);
    c.seconds_measure = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    return c;
}

}  // namespace drape::synth
