// The C facade, part 7: animation of recovered garments (librecover's animate_garments,
// drape::io's animation files: the same animation.json and folder as `drape animate`).
#include "capi_internal.hpp"

#include <drape/io/animation_files.hpp>

#include <drape/recover/animate_garments.hpp>

#include <nlohmann/json.hpp>

struct drape_animation_s {
    std::shared_ptr<const drape::body::BodyModel> model;
    drape::recover::AnimateGarmentsResult result;
    drape::recover::AnimateGarmentsSummary summary;
    nlohmann::json json;  ///< animation.json
};

namespace drape::capi {

template <>
struct StructTraits<drape_animate_inputs> {
    static constexpr const char* name = "drape_animate_inputs";
    static auto fields() {
        using S = drape_animate_inputs;
        return std::make_tuple(&S::garments, &S::garment_count, &S::motion);
    }
    static drape_animate_inputs defaults() {
        drape_animate_inputs d{};
        d.struct_size = sizeof d;
        return d;
    }
};

template <>
struct StructTraits<drape_animate_options> {
    static constexpr const char* name = "drape_animate_options";
    static auto fields() {
        using S = drape_animate_options;
        return std::make_tuple(&S::seconds, &S::fps, &S::edge_cm, &S::wind_x, &S::wind_y, &S::wind_z);
    }
    static drape_animate_options defaults() {
        const drape::recover::AnimateGarmentsOptions o;
        drape_animate_options d{};
        d.struct_size = sizeof d;
        d.seconds = o.seconds;
        d.fps = o.fps;
        d.edge_cm = o.edge_cm;
        d.wind_x = d.wind_y = d.wind_z = 0;
        return d;
    }
};

}  // namespace drape::capi

namespace {

using namespace drape::capi;
namespace dr = drape::recover;

const char* stage_name(dr::AnimateGarmentsStage s) {
    switch (s) {
        case dr::AnimateGarmentsStage::draping: return "draping";
        case dr::AnimateGarmentsStage::blending: return "blending";
        case dr::AnimateGarmentsStage::animating: return "animating";
    }
    return "animating";
}

}  // namespace

extern "C" {

drape_status drape_animate_inputs_init(drape_animate_inputs* inputs) { return init_struct(inputs, __func__, "inputs"); }
drape_status drape_animate_options_init(drape_animate_options* options) {
    return init_struct(options, __func__, "options");
}

drape_status drape_animate(drape_body_model model, const drape_animate_inputs* inputs,
                           const drape_animate_options* options, const drape_monitor* monitor,
                           drape_animation* out_animation) {
    DRAPE_REQUIRE_ARG(inputs, "inputs must not be NULL");
    DRAPE_REQUIRE_ARG(out_animation, "out_animation must not be NULL");
    *out_animation = nullptr;
    return guarded(__func__, [&, function = __func__] {
        const drape_animate_inputs in = read_struct(inputs, "inputs");
        const drape_animate_options opt = read_struct(options, "options");
        const std::vector<std::string> specs = strings_of(in.garments, in.garment_count, "inputs->garments");
        dr::AnimateGarmentsOptions o;
        o.seconds = opt.seconds;
        o.fps = opt.fps;
        o.edge_cm = opt.edge_cm;
        o.wind_m_per_s = Eigen::Vector3d(opt.wind_x, opt.wind_y, opt.wind_z);
        std::string why;
        if (!o.is_valid(&why)) throw drape::InvalidInput("options: " + why);
        Monitor mon(monitor, "animate");
        if (!mon.report("reading", -1, 0, 0, 0)) return cancelled(function);
        const dr::AnimateGarmentsInputs a = drape::io::read_animation_inputs(specs, in.motion ? in.motion : "walk");
        o.on_progress = [&mon](const dr::AnimateGarmentsProgress& p) {
            const double fraction = p.frames > 0 ? double(p.step) / p.frames : -1;
            return mon.report(stage_name(p.stage), -1, 0, p.step, fraction);
        };
        auto an = std::make_unique<drape_animation_s>();
        an->model = model ? model->model : default_model_ptr();
        an->summary = dr::animate_garments(*an->model, a, o, an->result);
        const dr::AnimateGarmentsSummary& s = an->summary;
        if (s.termination == dr::AnimateGarmentsTermination::cancelled || mon.cancelled()) return cancelled(function);
        if (s.termination == dr::AnimateGarmentsTermination::drape_failed)
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_animate: " + s.brief_report(); });
        an->json = drape::io::animation_report(s, o, a.motion, specs);
        const bool usable = s.usable();
        *out_animation = an.release();
        if (!usable)
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_animate: " + s.brief_report(); });
        return DRAPE_OK;
    });
}

void drape_animation_destroy(drape_animation animation) { delete animation; }

drape_status drape_animation_json(drape_animation animation, char** out_json) {
    DRAPE_REQUIRE_ARG(animation, "animation must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        *out_json = copy_string(animation->json.dump(2));
        return DRAPE_OK;
    });
}

drape_status drape_animation_get_counts(drape_animation animation, size_t* frame_count, size_t* garment_count) {
    DRAPE_REQUIRE_ARG(animation, "animation must not be NULL");
    if (frame_count) *frame_count = animation->result.animation.frames.size();
    if (garment_count) *garment_count = animation->result.outfit.meshes.size();
    return DRAPE_OK;
}

#define DRAPE_REQUIRE_ANIMATED_GARMENT(animation, garment)                                               \
    DRAPE_REQUIRE_ARG(garment < animation->result.outfit.meshes.size(),                                \
                      "garment " + std::to_string(garment) + " is not below the " +                     \
                          std::to_string(animation->result.outfit.meshes.size()) + " garments animated")

drape_status drape_animation_get_frame_vertices(drape_animation animation, size_t garment, size_t frame, double* out,
                                                size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(animation, "animation must not be NULL");
    DRAPE_REQUIRE_ANIMATED_GARMENT(animation, garment);
    DRAPE_REQUIRE_ARG(frame < animation->result.animation.frames.size(),
                      "frame " + std::to_string(frame) + " is not below the " +
                          std::to_string(animation->result.animation.frames.size()) + " frames");
    return guarded(__func__, [&, function = __func__] {
        return copy_rows(animation->result.animation.frames[frame][garment], out, capacity, required, function);
    });
}

drape_status drape_animation_get_garment_mesh(drape_animation animation, size_t garment,
                                              drape_garment_mesh* out_mesh) {
    DRAPE_REQUIRE_ARG(animation, "animation must not be NULL");
    DRAPE_REQUIRE_ARG(out_mesh, "out_mesh must not be NULL");
    *out_mesh = nullptr;
    DRAPE_REQUIRE_ANIMATED_GARMENT(animation, garment);
    return guarded(__func__, [&] {
        const drape::garment::DressedOutfit& o = animation->result.outfit;
        *out_mesh = new_garment_mesh(o.patterns[garment], o.sizings[garment], o.meshes[garment], o.positions[garment]);
        return DRAPE_OK;
    });
}

drape_status drape_animation_write_folder(drape_animation animation, const char* folder, const drape_monitor* monitor) {
    DRAPE_REQUIRE_ARG(animation, "animation must not be NULL");
    DRAPE_REQUIRE_ARG(folder, "folder must not be NULL");
    return guarded(__func__, [&, function = __func__] {
        Monitor mon(monitor, "write_animation");
        if (!mon.report("writing", -1, 0, 0, 0)) return cancelled(function);
        if (animation->result.animation.frames.empty())
            throw drape::InvalidInput("the animation has no frame to write");
        const dr::AnimateGarmentsResult& r = animation->result;
        const bool moved = drape::io::write_animation(folder, *animation->model, r.shaped, r.outfit, r.animation,
                                                      r.names, animation->json,
                                                      [&] { return mon.report("moving", -1, 0, 0, 1); });
        if (!moved) return cancelled(function);
        return DRAPE_OK;
    });
}

}  // extern "C"
