// The C facade, part 4: the cloth simulator on raw meshes or garment meshes (libcloth).
#include "capi_internal.hpp"

#include <drape/io/material_arg.hpp>

#include <drape/cloth/simulator.hpp>
#include <drape/garment/drape_garment.hpp>

#include <nlohmann/json.hpp>

struct drape_simulator_s {
    std::unique_ptr<drape::cloth::Simulator> sim;
    /// The monitor of the call in progress: the simulator's per-iteration callback checks it.
    drape::capi::Monitor* active = nullptr;
};

namespace drape::capi {

template <>
struct StructTraits<drape_simulator_options> {
    static constexpr const char* name = "drape_simulator_options";
    static auto fields() {
        using S = drape_simulator_options;
        return std::make_tuple(&S::time_step_s, &S::gravity_x, &S::gravity_y, &S::gravity_z, &S::air_drag_n_s_per_m3,
                               &S::contact_thickness_m, &S::obstacle_friction, &S::self_contact,
                               &S::max_newton_iterations);
    }
    static drape_simulator_options defaults() {
        const drape::cloth::SimulatorOptions o = drape::garment::DrapeOptions::default_simulator_options();
        drape_simulator_options d{};
        d.struct_size = sizeof d;
        d.time_step_s = o.time_step_s;
        d.gravity_x = o.gravity_m_per_s2.x();
        d.gravity_y = o.gravity_m_per_s2.y();
        d.gravity_z = o.gravity_m_per_s2.z();
        d.air_drag_n_s_per_m3 = o.air_drag_n_s_per_m3;
        d.contact_thickness_m = o.contact_thickness_m;
        d.obstacle_friction = o.obstacle_friction;
        d.self_contact = o.self_contact ? 1 : 0;
        d.max_newton_iterations = o.max_newton_iterations;
        return d;
    }
};

}  // namespace drape::capi

namespace {

using namespace drape::capi;
namespace dc = drape::cloth;

// The simulator's options from the caller's; on_iteration checks the active monitor.
dc::SimulatorOptions simulator_options(const drape_simulator_options* options, drape_simulator_s* handle) {
    const drape_simulator_options o = read_struct(options, "options");
    dc::SimulatorOptions s = drape::garment::DrapeOptions::default_simulator_options();
    s.time_step_s = o.time_step_s;
    s.gravity_m_per_s2 = Eigen::Vector3d(o.gravity_x, o.gravity_y, o.gravity_z);
    s.air_drag_n_s_per_m3 = o.air_drag_n_s_per_m3;
    s.contact_thickness_m = o.contact_thickness_m;
    s.obstacle_friction = o.obstacle_friction;
    s.self_contact = o.self_contact != 0;
    s.max_newton_iterations = o.max_newton_iterations;
    std::string why;
    if (!s.is_valid(&why)) throw drape::InvalidInput("options: " + why);
    s.on_iteration = [handle](int, double) { return !(handle->active && handle->active->cancelled()); };
    return s;
}

// Sets the active monitor for the duration of a call.
struct ActiveMonitor {
    ActiveMonitor(drape_simulator_s* h, Monitor* m) : handle(h) { handle->active = m; }
    ~ActiveMonitor() { handle->active = nullptr; }
    drape_simulator_s* handle;
};

}  // namespace

extern "C" {

drape_status drape_simulator_options_init(drape_simulator_options* options) {
    return init_struct(options, __func__, "options");
}

drape_status drape_simulator_create(const double* vertices, size_t vertex_count, const int32_t* faces,
                                    size_t face_count, const double* pattern_coords, const char* material,
                                    const drape_simulator_options* options, drape_simulator* out_simulator) {
    DRAPE_REQUIRE_ARG(vertices, "vertices must not be NULL");
    DRAPE_REQUIRE_ARG(faces, "faces must not be NULL");
    DRAPE_REQUIRE_ARG(pattern_coords, "pattern_coords must not be NULL");
    DRAPE_REQUIRE_ARG(vertex_count >= 3, "vertex_count = " + std::to_string(vertex_count) + " must be >= 3");
    DRAPE_REQUIRE_ARG(face_count >= 1, "face_count must be >= 1");
    DRAPE_REQUIRE_ARG(out_simulator, "out_simulator must not be NULL");
    *out_simulator = nullptr;
    return guarded(__func__, [&] {
        auto handle = std::make_unique<drape_simulator_s>();
        const dc::ClothMesh mesh = dc::ClothMesh::from_vertex_pattern(
            rows3(vertices, vertex_count, "vertices"), index_rows3(faces, face_count, vertex_count, "faces"),
            rows2(pattern_coords, vertex_count, "pattern_coords"));
        const dc::Material m = drape::io::load_material_arg(material ? material : "gray-interlock", "");
        handle->sim = std::make_unique<dc::Simulator>(mesh, m, simulator_options(options, handle.get()));
        *out_simulator = handle.release();
        return DRAPE_OK;
    });
}

drape_status drape_simulator_create_from_garment(drape_garment_mesh mesh, const char* material,
                                                 const drape_simulator_options* options,
                                                 drape_simulator* out_simulator) {
    DRAPE_REQUIRE_ARG(mesh, "mesh must not be NULL");
    DRAPE_REQUIRE_ARG(out_simulator, "out_simulator must not be NULL");
    *out_simulator = nullptr;
    return guarded(__func__, [&] {
        auto handle = std::make_unique<drape_simulator_s>();
        dc::ClothMesh cloth = mesh->mesh->cloth;
        cloth.positions = mesh->positions;
        const dc::Material m = drape::io::load_material_arg(material ? material : "gray-interlock", "");
        handle->sim = std::make_unique<dc::Simulator>(std::move(cloth), m, simulator_options(options, handle.get()));
        handle->sim->set_stitches(drape::garment::garment_stitches(*mesh->mesh));
        *out_simulator = handle.release();
        return DRAPE_OK;
    });
}

void drape_simulator_destroy(drape_simulator simulator) { delete simulator; }

drape_status drape_simulator_set_obstacle(drape_simulator simulator, const double* vertices, size_t vertex_count,
                                          const int32_t* faces, size_t face_count) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    DRAPE_REQUIRE_ARG(vertices && faces, "vertices and faces must not be NULL");
    DRAPE_REQUIRE_ARG(vertex_count >= 3 && face_count >= 1, "the obstacle needs >= 3 vertices and >= 1 face, got " +
                                                                std::to_string(vertex_count) + " and " +
                                                                std::to_string(face_count));
    return guarded(__func__, [&] {
        simulator->sim->set_obstacle(dc::Obstacle(rows3(vertices, vertex_count, "vertices"),
                                                  index_rows3(faces, face_count, vertex_count, "faces")));
        return DRAPE_OK;
    });
}

drape_status drape_simulator_set_obstacle_body(drape_simulator simulator, drape_body body) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    return guarded(__func__, [&] {
        simulator->sim->set_obstacle(dc::Obstacle(body->posed.vertices, body->model->faces));
        return DRAPE_OK;
    });
}

drape_status drape_simulator_clear_obstacle(drape_simulator simulator) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    return guarded(__func__, [&] {
        simulator->sim->clear_obstacle();
        return DRAPE_OK;
    });
}

drape_status drape_simulator_pin(drape_simulator simulator, size_t vertex) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    DRAPE_REQUIRE_ARG(vertex < static_cast<size_t>(simulator->sim->mesh().vertex_count()),
                      "vertex " + std::to_string(vertex) + " is not below the vertex count " +
                          std::to_string(simulator->sim->mesh().vertex_count()));
    return guarded(__func__, [&] {
        simulator->sim->pin(static_cast<int>(vertex));
        return DRAPE_OK;
    });
}

drape_status drape_simulator_step(drape_simulator simulator, int32_t steps, const drape_monitor* monitor) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    DRAPE_REQUIRE_ARG(steps >= 0, "steps = " + std::to_string(steps) + " must be >= 0");
    return guarded(__func__, [&, function = __func__] {
        Monitor mon(monitor, "simulate");
        const ActiveMonitor active(simulator, &mon);
        for (int32_t k = 0; k < steps; ++k) {
            if (mon.cancelled()) return cancelled(function);
            const dc::StepSummary s = simulator->sim->step();
            if (s.termination == dc::StepTermination::cancelled || mon.cancelled()) return cancelled(function);
            if (!s.usable())
                return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] {
                    return "drape_simulator_step: step " + std::to_string(k + 1) + ": " + s.brief_report();
                });
            if (!mon.report("step", -1, 0, k + 1, double(k + 1) / steps)) return cancelled(function);
        }
        return DRAPE_OK;
    });
}

drape_status drape_simulator_solve_static(drape_simulator simulator, const drape_monitor* monitor) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    return guarded(__func__, [&, function = __func__] {
        Monitor mon(monitor, "simulate");
        const ActiveMonitor active(simulator, &mon);
        if (!mon.report("static_solve", -1, 0, 0, 0)) return cancelled(function);
        const dc::StepSummary s = simulator->sim->solve_static();
        if (s.termination == dc::StepTermination::cancelled || mon.cancelled()) return cancelled(function);
        if (s.termination != dc::StepTermination::converged)
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_simulator_solve_static: " + s.brief_report(); });
        mon.report("static_solve", -1, 0, 0, 1);
        return DRAPE_OK;
    });
}

drape_status drape_simulator_get_counts(drape_simulator simulator, size_t* vertex_count, size_t* face_count) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    if (vertex_count) *vertex_count = static_cast<size_t>(simulator->sim->mesh().vertex_count());
    if (face_count) *face_count = static_cast<size_t>(simulator->sim->mesh().face_count());
    return DRAPE_OK;
}

drape_status drape_simulator_get_vertices(drape_simulator simulator, double* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_rows(simulator->sim->positions(), out, capacity, required, function); });
}

drape_status drape_simulator_set_vertices(drape_simulator simulator, const double* vertices, size_t count) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    const size_t n = static_cast<size_t>(simulator->sim->mesh().vertex_count()) * 3;
    DRAPE_REQUIRE_ARG(count == n, "count = " + std::to_string(count) + ", expected " + std::to_string(n) +
                                      " (vertex count x 3)");
    return guarded(__func__, [&] {
        const Eigen::MatrixX3d X = rows3(vertices, n / 3, "vertices");
        simulator->sim->set_positions(X);
        simulator->sim->set_velocities(Eigen::MatrixX3d::Zero(X.rows(), 3));
        return DRAPE_OK;
    });
}

drape_status drape_simulator_report_json(drape_simulator simulator, char** out_json) {
    DRAPE_REQUIRE_ARG(simulator, "simulator must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        const dc::ContactReport r = simulator->sim->contact_report();
        const nlohmann::json j = {{"max_penetration_m", r.max_penetration_m},
                                  {"vertices_inside", r.vertices_inside},
                                  {"max_stitch_gap_m", r.max_stitch_gap_m},
                                  {"self_intersections", r.self_intersections}};
        *out_json = copy_string(j.dump(2));
        return DRAPE_OK;
    });
}

}  // extern "C"

