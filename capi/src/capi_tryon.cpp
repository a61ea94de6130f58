// The C facade, part 6: virtual try-on (librecover's tryon, drape::io's try-on files: the same
// tryon.json and folder as `drape tryon`).
#include "capi_internal.hpp"

#include <drape/io/recovery_files.hpp>
#include <drape/io/tryon_files.hpp>

#include <drape/recover/tryon.hpp>

#include <nlohmann/json.hpp>

struct drape_tryon_s {
    std::shared_ptr<const drape::body::BodyModel> model;
    drape::recover::TryOnInputs inputs;
    drape::recover::TryOnOptions options;
    drape::recover::TryOnResult result;
    drape::recover::TryOnSummary summary;
    nlohmann::json json;  ///< tryon.json
};

namespace drape::capi {

template <>
struct StructTraits<drape_tryon_inputs> {
    static constexpr const char* name = "drape_tryon_inputs";
    static auto fields() {
        using S = drape_tryon_inputs;
        return std::make_tuple(&S::garments, &S::garment_count, &S::body, &S::image_path, &S::joints_path,
                               &S::strokes_path, &S::palette_path, &S::height_m, &S::gender);
    }
    static drape_tryon_inputs defaults() {
        drape_tryon_inputs d{};
        d.struct_size = sizeof d;
        d.height_m = kNaN;
        d.gender = DRAPE_GENDER_UNSPECIFIED;
        return d;
    }
};

template <>
struct StructTraits<drape_tryon_options> {
    static constexpr const char* name = "drape_tryon_options";
    static auto fields() {
        using S = drape_tryon_options;
        return std::make_tuple(&S::edge_cm, &S::max_drape_steps, &S::threads);
    }
    static drape_tryon_options defaults() {
        const drape::recover::TryOnOptions o;
        drape_tryon_options d{};
        d.struct_size = sizeof d;
        d.edge_cm = o.edge_cm;
        d.max_drape_steps = o.max_drape_steps;
        d.threads = o.threads;
        return d;
    }
};

}  // namespace drape::capi

namespace {

using namespace drape::capi;
namespace dr = drape::recover;

// The body target of a body handle: every semantic value of its shape (so the prior completes
// nothing) and its pose.
drape::body::SemanticRequest request_of(const drape::body::SemanticShape& shape) {
    drape::body::SemanticRequest r;
    r.gender = shape.gender;
    for (int k = 0; k < drape::body::kSemanticCount; ++k) r.values[size_t(k)] = shape.values[k];
    return r;
}

// The photo target of the inputs (read_recover_inputs reads and checks the photo, joints,
// strokes and palette as `drape recover` does).
void read_photo_target(const drape_tryon_inputs& in, dr::TryOnTarget& t) {
    if (!in.joints_path)
        throw drape::InvalidInput("inputs->image_path '" + std::string(in.image_path) +
                                  "' needs inputs->joints_path (its 14 joints)");
    dr::RecoverInputs r = drape::io::read_recover_inputs(in.image_path, in.joints_path, str(in.strokes_path),
                                                         str(in.palette_path), "auto");
    t.photo_bgr = std::move(r.image_bgr);
    t.joints = std::move(r.joints);
    t.strokes = std::move(r.strokes);
    if (!std::isnan(in.height_m)) t.height_m = in.height_m;
    t.gender = gender_of(in.gender, "inputs->gender");
}

}  // namespace

extern "C" {

drape_status drape_tryon_inputs_init(drape_tryon_inputs* inputs) { return init_struct(inputs, __func__, "inputs"); }
drape_status drape_tryon_options_init(drape_tryon_options* options) { return init_struct(options, __func__, "options"); }

drape_status drape_tryon(drape_body_model model, const drape_tryon_inputs* inputs, const drape_tryon_options* options,
                         const drape_monitor* monitor, drape_tryon_result* out_result) {
    DRAPE_REQUIRE_ARG(inputs, "inputs must not be NULL");
    DRAPE_REQUIRE_ARG(out_result, "out_result must not be NULL");
    *out_result = nullptr;
    return guarded(__func__, [&, function = __func__] {
        const drape_tryon_inputs in = read_struct(inputs, "inputs");
        const drape_tryon_options opt = read_struct(options, "options");
        const std::vector<std::string> specs = strings_of(in.garments, in.garment_count, "inputs->garments");
        if ((in.body != nullptr) == (in.image_path != nullptr))
            throw drape::InvalidInput("inputs: give either body (a body target) or image_path (a photo target)");
        if (in.body && (in.joints_path || in.strokes_path || in.palette_path))
            throw drape::InvalidInput("inputs: joints_path, strokes_path and palette_path belong to a photo target, "
                                      "not to a body");
        Monitor mon(monitor, "tryon");
        auto t = std::make_unique<drape_tryon_s>();
        t->model = model ? model->model : in.body ? in.body->model : default_model_ptr();
        if (in.body && in.body->model != t->model)
            throw drape::InvalidInput("inputs->body was made with another model than the one given");
        if (!mon.report("reading", -1, 0, 0, 0)) return cancelled(function);
        t->inputs.garments = drape::io::read_tryon_garments(specs);
        if (in.body) {
            t->inputs.target.body = request_of(in.body->shape);
            t->inputs.target.pose = in.body->pose;
        } else {
            read_photo_target(in, t->inputs.target);
        }
        dr::TryOnOptions& o = t->options;
        o.edge_cm = opt.edge_cm;
        o.max_drape_steps = opt.max_drape_steps;
        o.threads = opt.threads;
        std::string why;
        if (!o.is_valid(&why)) throw drape::InvalidInput("options: " + why);
        o.on_progress = [&mon](const dr::TryOnProgress& p) {
            return mon.report(dr::tryon_stage_name(p.stage), -1, 0, p.step);
        };
        t->summary = dr::tryon(*t->model, t->inputs, o, t->result);
        o.on_progress = nullptr;  // it refers to this call's monitor
        const dr::TryOnSummary& s = t->summary;
        if (s.termination == dr::TryOnTermination::cancelled || mon.cancelled()) return cancelled(function);
        if (s.termination != dr::TryOnTermination::draped)
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_tryon: " + s.brief_report(); });
        t->json = drape::io::tryon_json(t->inputs, o, t->result, s);
        const bool usable = s.usable(t->result);
        *out_result = t.release();
        if (!usable)
            return fail(DRAPE_ERROR_NO_CONVERGENCE,
                        [&] { return "drape_tryon: a drape or a grading is not usable (see the result's JSON)"; });
        return DRAPE_OK;
    });
}

void drape_tryon_destroy(drape_tryon_result result) { delete result; }

drape_status drape_tryon_json(drape_tryon_result result, char** out_json) {
    DRAPE_REQUIRE_ARG(result, "result must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        *out_json = copy_string(result->json.dump(2));
        return DRAPE_OK;
    });
}

drape_status drape_tryon_get_garment_count(drape_tryon_result result, size_t* count) {
    DRAPE_REQUIRE_ARG(result, "result must not be NULL");
    DRAPE_REQUIRE_ARG(count, "count must not be NULL");
    *count = result->result.garments.size();
    return DRAPE_OK;
}

drape_status drape_tryon_get_garment_mesh(drape_tryon_result result, size_t index, drape_garment_mesh* out_mesh) {
    DRAPE_REQUIRE_ARG(result, "result must not be NULL");
    DRAPE_REQUIRE_ARG(out_mesh, "out_mesh must not be NULL");
    *out_mesh = nullptr;
    DRAPE_REQUIRE_ARG(index < result->result.garments.size(),
                      "index " + std::to_string(index) + " is not below the " +
                          std::to_string(result->result.garments.size()) + " garments tried on");
    return guarded(__func__, [&] {
        const dr::TriedOnGarment& g = result->result.garments[index];
        *out_mesh = new_garment_mesh(g.pattern, g.sizing, g.mesh, g.positions);
        return DRAPE_OK;
    });
}

drape_status drape_tryon_get_body(drape_tryon_result result, drape_body* out_body) {
    DRAPE_REQUIRE_ARG(result, "result must not be NULL");
    DRAPE_REQUIRE_ARG(out_body, "out_body must not be NULL");
    *out_body = nullptr;
    return guarded(__func__, [&] {
        *out_body = new_body(result->model, result->result.shape, result->result.shaped, result->result.pose);
        return DRAPE_OK;
    });
}

drape_status drape_tryon_write_folder(drape_tryon_result result, const char* folder, const drape_monitor* monitor) {
    DRAPE_REQUIRE_ARG(result, "result must not be NULL");
    DRAPE_REQUIRE_ARG(folder, "folder must not be NULL");
    return guarded(__func__, [&, function = __func__] {
        Monitor mon(monitor, "write_tryon");
        if (!mon.report("writing", -1, 0, 0, 0)) return cancelled(function);
        const bool moved = drape::io::write_tryon(folder, *result->model, result->inputs, result->options,
                                                  result->result, result->summary,
                                                  [&] { return mon.report("moving", -1, 0, 0, 1); });
        if (!moved) return cancelled(function);
        return DRAPE_OK;
    });
}

}  // extern "C"
