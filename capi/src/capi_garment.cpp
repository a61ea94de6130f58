// The C facade, part 3: sewing patterns, garment meshes, dressing and draping (libgarment).
#include "capi_internal.hpp"

#include <drape/io/garment_json.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/material_arg.hpp>

#include <drape/body/measurements.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/garment_export.hpp>
#include <drape/garment/pattern_dxf.hpp>
#include <drape/garment/pattern_json.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <vector>

struct drape_outfit_s {
    std::vector<std::shared_ptr<const drape_pattern_s>> patterns;
    std::vector<std::shared_ptr<const drape::garment::GarmentMesh>> meshes;
    std::vector<Eigen::MatrixX3d> positions;
    Eigen::MatrixX3d body_vertices;
    nlohmann::json summary;
};

namespace drape::capi {

template <>
struct StructTraits<drape_garment_spec> {
    static constexpr const char* name = "drape_garment_spec";
    static auto fields() {
        using S = drape_garment_spec;
        return std::make_tuple(&S::garment, &S::sizing_json, &S::material);
    }
    static drape_garment_spec defaults() {
        drape_garment_spec d{};
        d.struct_size = sizeof d;
        return d;
    }
};

template <>
struct StructTraits<drape_dress_options> {
    static constexpr const char* name = "drape_dress_options";
    static auto fields() {
        using S = drape_dress_options;
        return std::make_tuple(&S::edge_cm, &S::clear_arms, &S::body_motion_s, &S::max_steps);
    }
    static drape_dress_options defaults() {
        const drape::garment::DrapeOptions drape;
        drape_dress_options d{};
        d.struct_size = sizeof d;
        d.edge_cm = 0;
        d.clear_arms = 1;
        d.body_motion_s = drape.body_motion_s;
        d.max_steps = drape.max_steps;
        return d;
    }
};

}  // namespace drape::capi

namespace {

using namespace drape::capi;
namespace dg = drape::garment;
namespace db = drape::body;

// G from JSON text. \throw drape::InvalidInput naming `what` for bad JSON or a bad key.
dg::GarmentSizing parse_sizing(dg::GarmentType type, const char* json, const std::string& what) {
    return drape::io::sizing_from_json(type, drape::io::parse_json_text(json, what), what);
}

// G as JSON text, or the template defaults for NULL.
dg::GarmentSizing sizing_or_defaults(dg::GarmentType type, const char* json, const std::string& what) {
    if (json) return parse_sizing(type, json, what);
    return drape::io::sizing_from_json(type, nlohmann::json::object(), what);
}

std::shared_ptr<drape_pattern_s> make_pattern_handle(const dg::GarmentSizing& sizing) {
    auto p = std::make_shared<drape_pattern_s>();
    p->pattern = dg::make_pattern(sizing);
    p->sizing = sizing;
    return p;
}

const char* phase_name(dg::DrapePhase p) {
    switch (p) {
        case dg::DrapePhase::closing_seams: return "closing_seams";
        case dg::DrapePhase::moving_body: return "moving_body";
        case dg::DrapePhase::settling: return "settling";
        case dg::DrapePhase::static_solve: return "static_solve";
    }
    return "draping";
}

// Pants are meshed coarser by default, as `drape dress` does (docs/dressing.md, Known problems).
constexpr double kDefaultEdgeCm = 1.5;
constexpr double kPantsEdgeCm = 2.5;

}  // namespace

namespace drape::capi {

drape_garment_mesh_s* new_garment_mesh(const drape::garment::Pattern& pattern,
                                       const drape::garment::GarmentSizing& sizing,
                                       const drape::garment::GarmentMesh& mesh, const Eigen::MatrixX3d& positions) {
    auto p = std::make_shared<drape_pattern_s>();
    p->pattern = pattern;
    p->sizing = sizing;
    auto m = std::make_unique<drape_garment_mesh_s>();
    m->pattern = std::move(p);
    m->mesh = std::make_shared<const drape::garment::GarmentMesh>(mesh);
    m->positions = positions;
    return m.release();
}

}  // namespace drape::capi

extern "C" {

drape_status drape_pattern_create(const char* garment, const char* sizing_json, drape_pattern* out_pattern) {
    DRAPE_REQUIRE_ARG(garment, "garment must not be NULL");
    DRAPE_REQUIRE_ARG(out_pattern, "out_pattern must not be NULL");
    *out_pattern = nullptr;
    return guarded(__func__, [&] {
        const dg::GarmentType type = dg::garment_type_from_name(garment);
        const auto p = make_pattern_handle(sizing_or_defaults(type, sizing_json, "sizing_json"));
        *out_pattern = new drape_pattern_s(*p);
        return DRAPE_OK;
    });
}

drape_status drape_pattern_create_for_body(const char* garment, drape_body body, drape_pattern* out_pattern) {
    DRAPE_REQUIRE_ARG(garment, "garment must not be NULL");
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    DRAPE_REQUIRE_ARG(out_pattern, "out_pattern must not be NULL");
    *out_pattern = nullptr;
    return guarded(__func__, [&] {
        const dg::GarmentType type = dg::garment_type_from_name(garment);
        const db::BodyMeasurements measured = db::measure_body(*body->model, body->shaped.vertices);
        const auto p = make_pattern_handle(dg::proposed_sizing(type, *body->model, body->shaped, measured));
        *out_pattern = new drape_pattern_s(*p);
        return DRAPE_OK;
    });
}

void drape_pattern_destroy(drape_pattern pattern) { delete pattern; }

drape_status drape_pattern_to_json(drape_pattern pattern, char** out_json) {
    DRAPE_REQUIRE_ARG(pattern, "pattern must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        nlohmann::json j = {{"name", pattern->pattern.name},
                            {"panels", pattern->pattern.panels.size()},
                            {"seams", pattern->pattern.seams.size()},
                            {"area_cm2", pattern->pattern.total_area()}};
        if (pattern->sizing) {
            j["garment"] = dg::garment_type_name(pattern->sizing->type);
            j["sizing"] = drape::io::to_json(*pattern->sizing);
        }
        *out_json = copy_string(j.dump(2));
        return DRAPE_OK;
    });
}

drape_status drape_pattern_export(drape_pattern pattern, const char* path) {
    DRAPE_REQUIRE_ARG(pattern, "pattern must not be NULL");
    DRAPE_REQUIRE_ARG(path, "path must not be NULL");
    return guarded(__func__, [&] {
        const std::filesystem::path p(path);
        const std::string ext = p.extension().string();
        if (ext == ".svg") dg::write_pattern_svg(p, pattern->pattern);
        else if (ext == ".dxf") dg::write_pattern_dxf(p, pattern->pattern);
        else if (ext == ".json") dg::write_pattern_json(p, pattern->pattern);
        else throw drape::InvalidInput("path '" + p.string() + "' must end in .svg, .dxf or .json");
        return DRAPE_OK;
    });
}

drape_status drape_garment_mesh_create(drape_pattern pattern, double edge_cm, drape_garment_mesh* out_mesh) {
    DRAPE_REQUIRE_ARG(pattern, "pattern must not be NULL");
    DRAPE_REQUIRE_ARG(out_mesh, "out_mesh must not be NULL");
    DRAPE_REQUIRE_ARG(std::isfinite(edge_cm), "edge_cm = " + std::to_string(edge_cm) + " is not finite");
    *out_mesh = nullptr;
    return guarded(__func__, [&] {
        dg::MeshOptions options;
        options.target_edge_cm = edge_cm > 0 ? edge_cm : kDefaultEdgeCm;
        std::string why;
        if (!options.is_valid(&why)) throw drape::InvalidInput("edge_cm: " + why);
        auto mesh = std::make_shared<dg::GarmentMesh>();
        const dg::MeshSummary summary = dg::mesh_pattern(pattern->pattern, options, *mesh);
        auto handle = std::make_unique<drape_garment_mesh_s>();
        handle->pattern = std::make_shared<const drape_pattern_s>(*pattern);
        handle->positions = mesh->cloth.positions;
        handle->mesh = std::move(mesh);
        *out_mesh = handle.release();
        if (!summary.usable())
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_garment_mesh_create: " + summary.brief_report(); });
        return DRAPE_OK;
    });
}

void drape_garment_mesh_destroy(drape_garment_mesh mesh) { delete mesh; }

drape_status drape_garment_mesh_get_counts(drape_garment_mesh mesh, size_t* vertex_count, size_t* face_count,
                                           size_t* stitch_count) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    if (vertex_count) *vertex_count = static_cast<size_t>(mesh->mesh->cloth.vertex_count());
    if (face_count) *face_count = static_cast<size_t>(mesh->mesh->cloth.face_count());
    if (stitch_count) *stitch_count = mesh->mesh->stitches.size();
    return DRAPE_OK;
}

drape_status drape_garment_mesh_get_vertices(drape_garment_mesh mesh, double* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_rows(mesh->positions, out, capacity, required, function); });
}

drape_status drape_garment_mesh_get_faces(drape_garment_mesh mesh, int32_t* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_rows(mesh->mesh->cloth.faces, out, capacity, required, function); });
}

drape_status drape_garment_mesh_get_pattern_coords(drape_garment_mesh mesh, double* out, size_t capacity,
                                                   size_t* required) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    return guarded(__func__, [&, function = __func__] {
        // One pattern point per vertex (pattern_faces == faces), the flat layout.
        const Eigen::MatrixX2d uv = mesh->mesh->cloth.pattern.topRows(mesh->mesh->cloth.vertex_count());
        return copy_rows(uv, out, capacity, required, function);
    });
}

drape_status drape_garment_mesh_get_stitches(drape_garment_mesh mesh, int32_t* out, size_t capacity,
                                             size_t* required) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    return guarded(__func__, [&, function = __func__] {
        const auto& st = mesh->mesh->stitches;
        Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> S(static_cast<Eigen::Index>(st.size()), 2);
        for (size_t i = 0; i < st.size(); ++i) S.row(static_cast<Eigen::Index>(i)) << st[i][0], st[i][1];
        return copy_rows(S, out, capacity, required, function);
    });
}

drape_status drape_garment_mesh_get_pattern(drape_garment_mesh mesh, drape_pattern* out_pattern) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    DRAPE_REQUIRE_ARG(out_pattern, "out_pattern must not be NULL");
    *out_pattern = nullptr;
    return guarded(__func__, [&] {
        *out_pattern = new drape_pattern_s(*mesh->pattern);
        return DRAPE_OK;
    });
}

}  // extern "C"

namespace {

// The mesh's faces with these vertices, as ".obj" (with uv and panel groups) or ".glb".
void write_mesh_file(const char* path, const drape_garment_mesh_s& mesh, const Eigen::MatrixX3d& X,
                     const char* comment) {
    const std::filesystem::path p(path);
    const std::string ext = p.extension().string();
    if (ext == ".obj")
        dg::write_garment_obj(p, mesh.pattern->pattern, *mesh.mesh, X, comment);
    else if (ext == ".glb")
        dg::write_garment_glb(p, *mesh.mesh, X);
    else
        throw drape::InvalidInput("path '" + p.string() + "' must end in .obj or .glb");
}

}  // namespace

extern "C" {

drape_status drape_garment_mesh_export(drape_garment_mesh mesh, const char* path) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    DRAPE_REQUIRE_ARG(path, "path must not be NULL");
    return guarded(__func__, [&] {
        write_mesh_file(path, *mesh, mesh->positions, "garment, world");
        return DRAPE_OK;
    });
}

drape_status drape_garment_mesh_export_flat(drape_garment_mesh mesh, const char* path) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    DRAPE_REQUIRE_ARG(path, "path must not be NULL");
    return guarded(__func__, [&] {
        write_mesh_file(path, *mesh, dg::flat_layout(*mesh->mesh), "flat layout");
        return DRAPE_OK;
    });
}

drape_status drape_garment_spec_init(drape_garment_spec* spec) { return init_struct(spec, __func__, "spec"); }
drape_status drape_dress_options_init(drape_dress_options* options) { return init_struct(options, __func__, "options"); }

drape_status drape_dress(drape_body body, const drape_garment_spec* garments, size_t garment_count,
                         const drape_dress_options* options, const drape_monitor* monitor, drape_outfit* out_outfit) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    DRAPE_REQUIRE_ARG(garments, "garments must not be NULL");
    DRAPE_REQUIRE_ARG(garment_count >= 1, "garment_count must be >= 1");
    DRAPE_REQUIRE_ARG(out_outfit, "out_outfit must not be NULL");
    *out_outfit = nullptr;
    return guarded(__func__, [&, function = __func__] {
        const drape_dress_options opt = read_struct(options, "options");
        Monitor mon(monitor, "dress");
        // Every input is read and checked before the slow work.
        std::vector<dg::GarmentRequest> requests;
        bool pants = false;
        for (size_t g = 0; g < garment_count; ++g) {
            // Specs are an array of the caller's struct: all of one struct_size, the first's.
            const auto* spec = reinterpret_cast<const drape_garment_spec*>(
                reinterpret_cast<const char*>(garments) + g * garments[0].struct_size);
            const std::string what = "garments[" + std::to_string(g) + "]";
            const drape_garment_spec s = read_struct(spec, what.c_str());
            if (!s.garment) throw drape::InvalidInput(what + ".garment must not be NULL");
            dg::GarmentRequest r;
            r.type = dg::garment_type_from_name(s.garment);
            pants = pants || r.type == dg::GarmentType::pants;
            if (s.sizing_json) r.sizing = parse_sizing(r.type, s.sizing_json, what + ".sizing_json");
            r.material = drape::io::load_material_arg(s.material ? s.material : "gray-interlock", "");
            requests.push_back(std::move(r));
        }
        dg::DressOutfitOptions o;
        o.mesh.target_edge_cm = opt.edge_cm > 0 ? opt.edge_cm : (pants ? kPantsEdgeCm : kDefaultEdgeCm);
        o.clear_arms = opt.clear_arms != 0;
        o.drape.body_motion_s = opt.body_motion_s;
        o.drape.max_steps = opt.max_steps;
        o.drape.min_steps = std::min(o.drape.min_steps, o.drape.max_steps);
        std::string why;
        if (!o.is_valid(&why)) throw drape::InvalidInput("options: " + why);
        const int max_steps = o.drape.max_steps;
        o.drape.on_progress = [&](const dg::DrapeProgress& p) {
            return mon.report(phase_name(p.phase), -1, 0, p.step, std::min(1.0, double(p.step) / max_steps));
        };
        // The flag is also checked after every Newton iteration, so a cancel does not wait for
        // the step to end (a step of a 1.5 cm mesh: several factorisations). The drape then
        // ends as a failed step; mon.cancelled() below tells it from a real failure.
        o.drape.simulator.on_iteration = [&](int, double) { return !mon.cancelled(); };
        if (!mon.report("dressing", -1, 0, 0, 0)) return cancelled(function);

        dg::DressedOutfit out;
        const dg::DressOutfitSummary s = dg::dress_outfit(*body->model, body->shaped, body->pose, requests, o, out);
        if (s.termination == dg::DressOutfitTermination::cancelled || mon.cancelled()) return cancelled(function);
        if (s.termination != dg::DressOutfitTermination::draped)
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_dress: " + s.message; });

        auto outfit = std::make_unique<drape_outfit_s>();
        const dg::DrapeSummary& d = s.drape;
        nlohmann::json garments_json = nlohmann::json::array();
        for (size_t g = 0; g < requests.size(); ++g) {
            auto p = std::make_shared<drape_pattern_s>();
            p->pattern = out.patterns[g];
            p->sizing = out.sizings[g];
            outfit->patterns.push_back(std::move(p));
            outfit->meshes.push_back(std::make_shared<const dg::GarmentMesh>(out.meshes[g]));
            outfit->positions.push_back(out.positions[g]);
            const dg::GarmentStateCheck& c = out.checks[g];
            garments_json.push_back({{"garment", dg::garment_type_name(requests[g].type)},
                                     {"sizing", drape::io::to_json(out.sizings[g])},
                                     {"vertices", out.meshes[g].cloth.vertex_count()},
                                     {"faces", out.meshes[g].cloth.face_count()},
                                     {"seam_gap_max_m", c.max_seam_gap_m},
                                     {"penetration_max_m", c.max_penetration_m},
                                     {"self_intersections", c.self_intersections},
                                     {"dressing", out.dressing[g].brief_report()}});
        }
        outfit->body_vertices = out.body_vertices;
        outfit->summary = drape::io::to_json(d);  // the keys of `drape dress`'s summary.json
        outfit->summary["edge_cm"] = o.mesh.target_edge_cm;
        outfit->summary["arms_raised_deg"] = {{"right", out.arms.right_degrees}, {"left", out.arms.left_degrees}};
        outfit->summary["garments"] = garments_json;
        outfit->summary["seconds"] = s.seconds;
        *out_outfit = outfit.release();
        if (!s.usable())
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_dress: drape not usable: " + d.brief_report(); });
        return DRAPE_OK;
    });
}

void drape_outfit_destroy(drape_outfit outfit) { delete outfit; }

drape_status drape_outfit_get_garment_count(drape_outfit outfit, size_t* count) {
    DRAPE_REQUIRE_ARG(outfit, "outfit must not be NULL");
    DRAPE_REQUIRE_ARG(count, "count must not be NULL");
    *count = outfit->meshes.size();
    return DRAPE_OK;
}

drape_status drape_outfit_get_garment_mesh(drape_outfit outfit, size_t index, drape_garment_mesh* out_mesh) {
    DRAPE_REQUIRE_ARG(outfit, "outfit must not be NULL");
    DRAPE_REQUIRE_ARG(out_mesh, "out_mesh must not be NULL");
    *out_mesh = nullptr;
    DRAPE_REQUIRE_ARG(index < outfit->meshes.size(), "index " + std::to_string(index) + " is not below the " +
                                                         std::to_string(outfit->meshes.size()) + " garments");
    return guarded(__func__, [&] {
        auto m = std::make_unique<drape_garment_mesh_s>();
        m->pattern = outfit->patterns[index];
        m->mesh = outfit->meshes[index];
        m->positions = outfit->positions[index];
        *out_mesh = m.release();
        return DRAPE_OK;
    });
}

drape_status drape_outfit_summary_json(drape_outfit outfit, char** out_json) {
    DRAPE_REQUIRE_ARG(outfit, "outfit must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        *out_json = copy_string(outfit->summary.dump(2));
        return DRAPE_OK;
    });
}

drape_status drape_outfit_get_body_vertices(drape_outfit outfit, double* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(outfit, "outfit must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_rows(outfit->body_vertices, out, capacity, required, function); });
}

}  // extern "C"
