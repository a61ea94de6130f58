// The C facade, part 5: garment recovery from a photo, its JSON, meshes and files (librecover,
// drape::io's recovery files: the same result.json and folder as `drape recover`).
#include "capi_internal.hpp"

#include <drape/io/recovery_files.hpp>

#include <drape/recover/outfit_glb.hpp>
#include <drape/recover/recovery_report.hpp>
#include <drape/recover/recover.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>

struct drape_recovery_s {
    std::shared_ptr<const drape::body::BodyModel> model;
    std::string image;
    drape::recover::RecoverInputs inputs;
    drape::recover::RecoverOptions options;
    drape::recover::RecoveryResult result;
    drape::recover::RecoverSummary summary;
    nlohmann::json json;  ///< result.json
};

namespace drape::capi {

template <>
struct StructTraits<drape_recover_inputs> {
    static constexpr const char* name = "drape_recover_inputs";
    static auto fields() {
        using S = drape_recover_inputs;
        return std::make_tuple(&S::image_path, &S::joints_path, &S::strokes_path, &S::palette_path, &S::garments,
                               &S::height_m, &S::gender);
    }
    static drape_recover_inputs defaults() {
        drape_recover_inputs d{};
        d.struct_size = sizeof d;
        d.height_m = kNaN;
        d.gender = DRAPE_GENDER_UNSPECIFIED;
        return d;
    }
};

template <>
struct StructTraits<drape_recover_options> {
    static constexpr const char* name = "drape_recover_options";
    static auto fields() {
        using S = drape_recover_options;
        return std::make_tuple(&S::quality, &S::threads, &S::seed, &S::particles, &S::generations, &S::rounds,
                               &S::estimate_material, &S::output_drape, &S::material_target, &S::base_fabric,
                               &S::max_arm_elevation_degrees, &S::min_ease_cm, &S::joint_pose);
    }
    static drape_recover_options defaults() {
        const drape::recover::RecoverOptions o;
        drape_recover_options d{};
        d.struct_size = sizeof d;
        d.quality = nullptr;
        d.threads = o.threads;
        d.seed = o.seed;
        d.particles = 0;
        d.generations = 0;
        d.rounds = 0;
        d.estimate_material = o.estimate_material ? 1 : 0;
        d.output_drape = nullptr;
        d.material_target = nullptr;
        d.base_fabric = nullptr;
        d.max_arm_elevation_degrees = o.max_arm_elevation_degrees;
        d.min_ease_cm = o.min_ease_cm;
        d.joint_pose = o.joint_pose_material ? 1 : 0;
        return d;
    }
};

}  // namespace drape::capi

namespace {

using namespace drape::capi;
namespace dr = drape::recover;

}  // namespace

extern "C" {

drape_status drape_recover_inputs_init(drape_recover_inputs* inputs) { return init_struct(inputs, __func__, "inputs"); }
drape_status drape_recover_options_init(drape_recover_options* options) {
    return init_struct(options, __func__, "options");
}

drape_status drape_recover(drape_body_model model, const drape_recover_inputs* inputs,
                           const drape_recover_options* options, const drape_monitor* monitor,
                           drape_recovery* out_recovery) {
    DRAPE_REQUIRE_ARG(inputs, "inputs must not be NULL");
    DRAPE_REQUIRE_ARG(out_recovery, "out_recovery must not be NULL");
    *out_recovery = nullptr;
    return guarded(__func__, [&, function = __func__] {
        const drape_recover_inputs in = read_struct(inputs, "inputs");
        const drape_recover_options opt = read_struct(options, "options");
        if (!in.image_path) throw drape::InvalidInput("inputs->image_path must not be NULL");
        if (!in.joints_path) throw drape::InvalidInput("inputs->joints_path must not be NULL");
        Monitor mon(monitor, "recover");
        auto r = std::make_unique<drape_recovery_s>();
        r->model = model ? model->model : default_model_ptr();
        r->image = in.image_path;
        r->inputs = drape::io::read_recover_inputs(in.image_path, in.joints_path, str(in.strokes_path),
                                                   str(in.palette_path), in.garments ? in.garments : "auto");
        if (!std::isnan(in.height_m)) r->inputs.height_m = in.height_m;
        r->inputs.gender = gender_of(in.gender, "inputs->gender");
        dr::RecoverOptions& o = r->options;
        o.quality = dr::quality_from_name(opt.quality ? opt.quality : "default");
        dr::apply_quality(o);
        o.threads = opt.threads;
        o.seed = opt.seed;
        if (opt.particles) o.particles = opt.particles;
        if (opt.generations) o.generations = opt.generations;
        if (opt.rounds) o.rounds = opt.rounds;
        o.estimate_material = opt.estimate_material != 0;
        if (opt.output_drape) o.output_drape = dr::output_drape_from_name(opt.output_drape);
        if (opt.material_target) o.material_target = dr::material_target_from_name(opt.material_target);
        if (opt.base_fabric) o.base_fabric = opt.base_fabric;
        o.max_arm_elevation_degrees = opt.max_arm_elevation_degrees;
        o.min_ease_cm = opt.min_ease_cm;
        o.joint_pose_material = opt.joint_pose != 0;
        std::string why;
        if (!o.is_valid(&why)) throw drape::InvalidInput("options: " + why);
        o.on_progress = [&mon](const dr::RecoverProgress& p) {
            return mon.report(dr::stage_name(p.stage), p.garment, p.round, p.evaluations, -1, p.eta_seconds);
        };
        if (!mon.report("reading", -1, 0, 0, 0)) return cancelled(function);

        r->summary = dr::recover(*r->model, r->inputs, o, r->result);
        o.on_progress = nullptr;  // it refers to this call's monitor
        const dr::RecoverSummary& s = r->summary;
        if (s.termination == dr::RecoverTermination::cancelled || mon.cancelled()) return cancelled(function);
        if (s.termination == dr::RecoverTermination::no_garment)
            return fail(DRAPE_ERROR_INVALID_ARGUMENT, [&] {
                return "drape_recover: no garment found in '" + r->image + "': " + s.message;
            });
        if (s.termination != dr::RecoverTermination::recovered)
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_recover: " + s.brief_report(); });
        r->json = drape::io::recovery_json(r->image, r->inputs, o, r->result, s);
        const bool usable = s.usable(r->result);
        *out_recovery = r.release();
        if (!usable)
            return fail(DRAPE_ERROR_NO_CONVERGENCE,
                        [&] { return "drape_recover: a drape is not usable (see the recovery's JSON)"; });
        return DRAPE_OK;
    });
}

void drape_recovery_destroy(drape_recovery recovery) { delete recovery; }

drape_status drape_recovery_json(drape_recovery recovery, char** out_json) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        *out_json = copy_string(recovery->json.dump(2));
        return DRAPE_OK;
    });
}

drape_status drape_recovery_get_garment_count(drape_recovery recovery, size_t* count) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(count, "count must not be NULL");
    *count = recovery->result.garments.size();
    return DRAPE_OK;
}

#define DRAPE_REQUIRE_GARMENT(recovery, index)                                                              \
    DRAPE_REQUIRE_ARG(index < recovery->result.garments.size(),                                           \
                      "index " + std::to_string(index) + " is not below the " +                          \
                          std::to_string(recovery->result.garments.size()) + " recovered garments")

drape_status drape_recovery_garment_json(drape_recovery recovery, size_t index, char** out_json) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    DRAPE_REQUIRE_GARMENT(recovery, index);
    return guarded(__func__, [&] {
        *out_json = copy_string(recovery->json.at("garments").at(index).dump(2));
        return DRAPE_OK;
    });
}

namespace {
drape_status garment_member_json(drape_recovery recovery, size_t index, const char* member, char** out_json,
                                 const char* function) {
    return guarded(function, [&] {
        *out_json = copy_string(recovery->json.at("garments").at(index).at(member).dump(2));
        return DRAPE_OK;
    });
}
}  // namespace

drape_status drape_recovery_garment_sizing_json(drape_recovery recovery, size_t index, char** out_json) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    DRAPE_REQUIRE_GARMENT(recovery, index);
    return garment_member_json(recovery, index, "sizing", out_json, __func__);
}

drape_status drape_recovery_garment_material_json(drape_recovery recovery, size_t index, char** out_json) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    DRAPE_REQUIRE_GARMENT(recovery, index);
    return garment_member_json(recovery, index, "material", out_json, __func__);
}

drape_status drape_recovery_get_garment_mesh(drape_recovery recovery, size_t index, drape_garment_mesh* out_mesh) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(out_mesh, "out_mesh must not be NULL");
    *out_mesh = nullptr;
    DRAPE_REQUIRE_GARMENT(recovery, index);
    return guarded(__func__, [&] {
        const dr::RecoveredGarment& g = recovery->result.garments[index];
        *out_mesh = new_garment_mesh(g.pattern, g.sizing, g.mesh, g.positions);
        return DRAPE_OK;
    });
}

drape_status drape_recovery_get_body(drape_recovery recovery, drape_body* out_body) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(out_body, "out_body must not be NULL");
    *out_body = nullptr;
    return guarded(__func__, [&] {
        drape_body_s* b =
            new_body(recovery->model, recovery->result.fit.shape, recovery->result.shaped, recovery->result.pose);
        // The photo's camera, so that drape_render can draw the body over the photo.
        b->camera = recovery->result.fit.camera;
        b->image_width = recovery->result.mask.cols;
        b->image_height = recovery->result.mask.rows;
        *out_body = b;
        return DRAPE_OK;
    });
}

drape_status drape_recovery_export(drape_recovery recovery, const char* path) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(path, "path must not be NULL");
    return guarded(__func__, [&] {
        const std::filesystem::path p(path);
        if (p.extension() != ".glb") throw drape::InvalidInput("path '" + p.string() + "' must end in .glb");
        dr::write_outfit_glb(p, dr::outfit_meshes(*recovery->model, recovery->result));
        return DRAPE_OK;
    });
}

drape_status drape_recovery_write_folder(drape_recovery recovery, const char* folder, const drape_monitor* monitor) {
    DRAPE_REQUIRE_ARG(recovery, "recovery must not be NULL");
    DRAPE_REQUIRE_ARG(folder, "folder must not be NULL");
    return guarded(__func__, [&, function = __func__] {
        Monitor mon(monitor, "write_recovery");
        if (!mon.report("writing", -1, 0, 0, 0)) return cancelled(function);
        const bool moved = drape::io::write_recovery(folder, recovery->image, *recovery->model, recovery->inputs,
                                                     recovery->options, recovery->result, recovery->summary,
                                                     [&] { return mon.report("moving", -1, 0, 0, 1); });
        if (!moved) return cancelled(function);
        return DRAPE_OK;
    });
}

}  // extern "C"
