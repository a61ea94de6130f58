// The phases of drape_garment: set-up of the simulator and stitches, untangling the dressed
// state, stepping while the seams close (welding them), the body moves along its path and
// the cloth settles, the static solve (or its fallback by stepping), final measurements.
#include "drape_run.hpp"

#include "dressing_internal.hpp"
#include <drape/garment/untangle.hpp>

#include <drape/cloth/obstacle.hpp>
#include <drape/core/errors.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <utility>

namespace drape::garment::detail {

namespace {

// Body state at time t of a path spread evenly over `duration` (piecewise linear).
Eigen::MatrixX3d body_at(const std::vector<Eigen::MatrixX3d>& path, double t, double duration) {
    if (path.size() == 1 || t >= duration) return path.back();
    const double u = std::max(0.0, t / duration) * double(path.size() - 1);
    const size_t k = std::min(size_t(u), path.size() - 2);
    const double a = u - double(k);
    return (1 - a) * path[k] + a * path[k + 1];
}
// Welding and the twin simulators below keep the faces, so face_material holds for all.
cloth::Simulator make_simulator(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                                const std::vector<cloth::Material>& materials, const std::vector<int>& face_material,
                                const DrapeOptions& options) {
    cloth::ClothMesh cm = mesh.cloth;
    cm.positions = initial_positions;
    return cloth::Simulator(std::move(cm), materials, face_material, options.simulator);
}

}  // namespace

double kinetic_energy(const cloth::Simulator& sim) {
    return 0.5 * (sim.masses().array() * sim.velocities().rowwise().squaredNorm().array()).sum();
}

Welded weld(const cloth::ClothMesh& source, const Eigen::MatrixX3d& positions, const Eigen::MatrixX3d& velocities,
            const std::vector<std::array<int, 2>>& stitches, Eigen::MatrixX3d* welded_velocities) {
    const int nv = source.vertex_count();
    const std::vector<int> rep = detail::sewn_representatives(nv, stitches);
    Welded w;
    w.vertex_of.assign(size_t(nv), -1);
    int n = 0;
    for (int v = 0; v < nv; ++v)
        if (rep[size_t(v)] == v) w.vertex_of[size_t(v)] = n++;
    for (int v = 0; v < nv; ++v) w.vertex_of[size_t(v)] = w.vertex_of[size_t(rep[size_t(v)])];
    Eigen::MatrixX3d x = Eigen::MatrixX3d::Zero(n, 3), vel = Eigen::MatrixX3d::Zero(n, 3);
    Eigen::VectorXd count = Eigen::VectorXd::Zero(n);
    for (int v = 0; v < nv; ++v) {
        const int k = w.vertex_of[size_t(v)];
        x.row(k) += positions.row(v);
        vel.row(k) += velocities.row(v);
        count(k) += 1;
    }
    for (int k = 0; k < n; ++k) {
        x.row(k) /= count(k);
        vel.row(k) /= count(k);
    }
    w.mesh.positions = x;
    w.mesh.faces = source.faces;
    for (Eigen::Index f = 0; f < w.mesh.faces.rows(); ++f)
        for (int c = 0; c < 3; ++c) w.mesh.faces(f, c) = w.vertex_of[size_t(source.faces(f, c))];
    w.mesh.pattern = source.pattern;
    w.mesh.pattern_faces = source.pattern_faces;
    *welded_velocities = vel;
    return w;
}

void check_drape_inputs(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                        const std::vector<Eigen::MatrixX3d>& body_path, const std::vector<cloth::Material>& materials,
                        const std::vector<int>& face_material, const DrapeOptions& options) {
    std::string why;
    require(options.is_valid(&why), "drape_garment: ", why);
    require(!materials.empty(), "drape_garment: no material given");
    for (size_t k = 0; k < materials.size(); ++k)
        require(materials[k].is_valid(&why), "drape_garment: material ", k, ": ", why);
    require(face_material.size() == size_t(mesh.cloth.face_count()), "drape_garment: face_material has ",
            face_material.size(), " entries, the garment mesh has ", mesh.cloth.face_count(), " faces");
    for (size_t f = 0; f < face_material.size(); ++f)
        require(face_material[f] >= 0 && size_t(face_material[f]) < materials.size(), "drape_garment: face_material[",
                f, "] = ", face_material[f], " is out of range [0, ", materials.size(), ")");
    const int nv = mesh.cloth.vertex_count();
    require(nv > 0, "drape_garment: the garment mesh is empty");
    require(initial_positions.rows() == nv && initial_positions.allFinite(), "drape_garment: initial_positions has ",
            initial_positions.rows(), " rows (need ", nv, ", all finite)");
    require(!body_path.empty(), "drape_garment: the body path is empty");
    for (size_t k = 0; k < body_path.size(); ++k)
        require(body_path[k].rows() == body_path[0].rows() && body_path[k].allFinite(), "drape_garment: body state ",
                k, " of the path has ", body_path[k].rows(), " vertices (need ", body_path[0].rows(),
                ", all finite)");
}

DrapeRun::DrapeRun(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                   const std::vector<Eigen::MatrixX3d>& body_path, const Eigen::MatrixX3i& body_faces,
                   const std::vector<cloth::Material>& materials, const std::vector<int>& face_material,
                   const DrapeOptions& options)
    : mesh_(mesh), initial_positions_(initial_positions), body_path_(body_path), materials_(materials),
      face_material_(face_material), options_(options), nv_(mesh.cloth.vertex_count()),
      sim_(make_simulator(mesh, initial_positions, materials, face_material, options)),
      sim_vertex_(static_cast<size_t>(nv_)) {
    sim_.set_obstacle(cloth::Obstacle(body_path.front(), body_faces));
    sim_.set_stitches(garment_stitches(mesh));
    for (int v = 0; v < nv_; ++v) sim_vertex_[size_t(v)] = v;

    summary_.vertices = nv_;
    summary_.stitches = int(mesh.stitches.size());
    summary_.penetration_tolerance_m = options.penetration_tolerance_m;
    summary_.max_mean_drop_m = options.max_mean_drop_m;
    summary_.seam_gap_tolerance_m = options.seam_gap_tolerance_m;
    total_mass_ = sim_.masses().sum();
    summary_.mass_kg = total_mass_;
    {
        const cloth::ContactReport r0 = sim_.contact_report();
        summary_.initial_penetration_max_m = r0.max_penetration_m;
        summary_.initial_seam_gap_max_m = r0.max_stitch_gap_m;
        summary_.initial_self_intersections = r0.self_intersections;
    }
    moving_ = body_path.size() > 1;
    // The body moves over body_motion_s, slower if needed so that no body vertex moves more
    // than half the contact thickness in a step (a faster surface can pass through a cloth
    // vertex within one step and push it out on the wrong side).
    motion_s_ = options.body_motion_s;
    if (moving_) {
        Eigen::VectorXd travelled = Eigen::VectorXd::Zero(body_path[0].rows());
        for (size_t k = 1; k < body_path.size(); ++k)
            travelled += (body_path[k] - body_path[k - 1]).rowwise().norm();
        const double per_step = 0.5 * options.simulator.contact_thickness_m;
        motion_total_ = std::max({1, int(std::ceil(options.body_motion_s / options.simulator.time_step_s)),
                                  int(std::ceil(travelled.maxCoeff() / per_step))});
        motion_s_ = motion_total_ * options.simulator.time_step_s;
    }
}

Eigen::MatrixX3d DrapeRun::garment_positions(const Eigen::MatrixX3d& x) const {
    Eigen::MatrixX3d out(nv_, 3);
    for (int v = 0; v < nv_; ++v) out.row(v) = x.row(sim_vertex_[size_t(v)]);
    return out;
}

// Welds the stitched vertices of the simulation (seams closed).
void DrapeRun::weld_now() {
    weld_tried_ = true;
    Eigen::MatrixX3d v;
    Welded w = weld(mesh_.cloth, sim_.positions(), sim_.velocities(), mesh_.stitches, &v);
    try {
        w.mesh.validate();
    } catch (const InvalidInput& e) {
        note(std::string("seams not welded (") + e.what() + ")");
        return;
    }
    cloth::Simulator next(std::move(w.mesh), materials_, face_material_, options_.simulator);
    next.set_obstacle(*sim_.obstacle());
    next.set_velocities(v);
    sim_ = std::move(next);
    sim_vertex_ = w.vertex_of;
    summary_.welded = true;
    summary_.steps_to_weld = summary_.steps;
}

// Steps until the seams are closed, the body has reached the end of its path and the
// cloth is at rest (or `budget` runs out). Returns false when a step failed or the
// caller cancelled (the summary says which).
bool DrapeRun::run_steps(int budget, int min_steps, DrapePhase phase) {
    settled_ = false;
    rest_report_.reset();
    for (int k = 0; k < budget; ++k) {
        // The body moves once the seams are closed.
        const bool in_motion = moving_ && motion_steps_ < motion_total_ && summary_.steps_to_close_seams >= 0;
        if (in_motion) {
            ++motion_steps_;
            sim_.move_obstacle(body_at(body_path_, motion_steps_ * options_.simulator.time_step_s, motion_s_));
        }
        const cloth::StepSummary s = sim_.step();
        if (s.termination == cloth::StepTermination::cancelled) {  // options.simulator.on_iteration said stop
            summary_.termination = DrapeTermination::cancelled;
            summary_.message = "cancelled in step " + std::to_string(summary_.steps + 1);
            return false;
        }
        if (!s.usable()) {
            summary_.termination = DrapeTermination::step_failed;
            summary_.message = "step " + std::to_string(summary_.steps + 1) + ": " + s.brief_report();
            return false;
        }
        ++summary_.steps;
        const double ke = kinetic_energy(sim_);
        summary_.kinetic_energy_j = ke;
        const bool closed = s.max_stitch_gap_m < options_.seam_gap_tolerance_m;
        if (closed && summary_.steps_to_close_seams < 0) summary_.steps_to_close_seams = summary_.steps;
        if (closed && options_.weld_seams && !weld_tried_ && !sim_.stitches().empty()) weld_now();
        const DrapePhase reported = in_motion ? DrapePhase::moving_body
                                    : closed && phase == DrapePhase::closing_seams ? DrapePhase::settling
                                                                                    : phase;
        if (options_.on_progress) progress_positions_ = garment_positions(sim_.positions());
        if (options_.on_progress && !options_.on_progress({reported, summary_.steps, s.max_stitch_gap_m, ke,
                                                            s.newton_iterations, s.seconds_total,
                                                            &progress_positions_})) {
            summary_.termination = DrapeTermination::cancelled;
            summary_.message = "cancelled at step " + std::to_string(summary_.steps);
            return false;
        }
        const bool body_done = !moving_ || motion_steps_ >= motion_total_;
        if (k + 1 >= min_steps && closed && body_done && ke / total_mass_ < options_.settled_kinetic_energy_j_per_kg) {
            settled_ = true;
            return true;
        }
    }
    return true;
}

bool DrapeRun::untangle(Eigen::MatrixX3d& out_positions) {
    if (!(summary_.initial_self_intersections > 0 && options_.max_untangle_steps > 0)) return true;
    cloth::SimulatorOptions loose = options_.simulator;
    loose.self_contact = false;
    cloth::ClothMesh m0 = sim_.mesh();
    m0.positions = initial_positions_;
    cloth::Simulator untangle(std::move(m0), materials_, face_material_, loose);
    untangle.set_obstacle(*sim_.obstacle());
    untangle.set_stitches(sim_.stitches());
    while (summary_.untangle_steps < options_.max_untangle_steps) {
        const cloth::StepSummary s = untangle.step();
        if (!s.usable()) break;
        ++summary_.untangle_steps;
        if (options_.on_progress &&
            !options_.on_progress({DrapePhase::closing_seams, summary_.untangle_steps, s.max_stitch_gap_m,
                                   kinetic_energy(untangle), s.newton_iterations, s.seconds_total,
                                   &untangle.positions()})) {
            summary_.termination = DrapeTermination::cancelled;
            summary_.message = "cancelled while untangling";
            summary_.steps = summary_.untangle_steps;
            out_positions = untangle.positions();
            return false;
        }
        if (summary_.untangle_steps % 5 == 0 && untangle.contact_report().self_intersections == 0) break;
    }
    summary_.steps = summary_.untangle_steps;
    sim_.set_positions(untangle.positions());
    sim_.set_velocities(untangle.velocities());
    return true;
}

bool DrapeRun::close_seams_and_settle() {
    const bool ok = run_steps(options_.max_steps, options_.min_steps, DrapePhase::closing_seams);
    if (ok) {
        summary_.termination = settled_ ? DrapeTermination::converged : DrapeTermination::not_settled;
        if (!settled_)
            summary_.message = "seams not closed or cloth not at rest after " + std::to_string(summary_.steps) + " steps";
    }
    return ok;
}

void DrapeRun::solve_static() {
    rest_report_.reset();
    const Eigen::MatrixX3d before = sim_.positions();
    // The static solve gets its own Newton budget: a twin simulator at the settled state.
    cloth::SimulatorOptions static_options = options_.simulator;
    static_options.max_newton_iterations = options_.static_max_newton_iterations;
    cloth::ClothMesh settled_mesh = sim_.mesh();
    settled_mesh.positions = before;
    cloth::Simulator twin(std::move(settled_mesh), materials_, face_material_, static_options);
    twin.set_obstacle(*sim_.obstacle());
    twin.set_stitches(sim_.stitches());
    const cloth::StepSummary s = twin.solve_static();
    summary_.static_gradient_n = s.gradient_inf_norm_n;
    summary_.static_newton_iterations = s.newton_iterations;
    const cloth::ContactReport r = twin.contact_report();
    const bool good = s.termination == cloth::StepTermination::converged &&
                      r.max_penetration_m <= options_.penetration_tolerance_m &&
                      r.max_stitch_gap_m < options_.seam_gap_tolerance_m && r.self_intersections == 0;
    if (good) {
        sim_.set_positions(twin.positions());
        sim_.set_velocities(Eigen::MatrixX3d::Zero(sim_.positions().rows(), 3));
        return;
    }
    // Equilibrium by stepping instead, from the settled state.
    const std::string reason = "static solve: " + s.brief_report() + ", penetration " +
                               std::to_string(1000 * r.max_penetration_m) + " mm, " +
                               std::to_string(r.self_intersections) + " self-intersections";
    sim_.set_positions(before);
    sim_.set_velocities(Eigen::MatrixX3d::Zero(sim_.positions().rows(), 3));
    if (run_steps(options_.fallback_steps, 1, DrapePhase::static_solve)) {
        summary_.termination = settled_ ? DrapeTermination::converged : DrapeTermination::static_failed;
        summary_.message = reason + (settled_ ? "; equilibrium reached by stepping instead" : "");
    }
}

void DrapeRun::note(const std::string& text) { notes_ += std::string(notes_.empty() ? "" : "; ") + text; }

const cloth::ContactReport& DrapeRun::rest_report() {
    if (!rest_report_) rest_report_ = sim_.contact_report();
    return *rest_report_;
}

bool DrapeRun::retry_at_rest(const cloth::SimulatorOptions& options, const Eigen::MatrixX3d& positions,
                             const Eigen::MatrixX3d& velocities,
                             const std::function<bool(const cloth::ContactReport&)>& better, std::string* why) {
    // The same cloth (welded or not), stitches and body in a fresh simulator; the one at rest
    // is kept aside, to come back whole if the retry is not better.
    cloth::ClothMesh m = sim_.mesh();
    m.positions = positions;
    cloth::Simulator next(std::move(m), materials_, face_material_, options);
    next.set_obstacle(*sim_.obstacle());
    next.set_stitches(sim_.stitches());
    next.set_velocities(velocities);
    const DrapeSummary kept = summary_;
    std::optional<cloth::ContactReport> kept_report = std::move(rest_report_);
    cloth::Simulator previous = std::exchange(sim_, std::move(next));
    rest_report_.reset();
    const bool ran = run_steps(options_.fallback_steps, 1, DrapePhase::settling);
    if (!ran && summary_.termination == DrapeTermination::cancelled) return false;  // the state reached, as cancelled
    const cloth::ContactReport& after = rest_report();
    const bool at_rest = ran && settled_;
    if (at_rest && after.max_stitch_gap_m < options_.seam_gap_tolerance_m && better(after)) return true;
    if (why)
        *why = std::to_string(after.self_intersections) + " crossings and " +
               std::to_string(1000 * after.max_penetration_m) + " mm in the body" + (at_rest ? "" : ", not at rest");
    const int steps = summary_.steps;
    sim_ = std::move(previous);
    rest_report_ = std::move(kept_report);
    summary_ = kept;
    summary_.steps = steps;  // the steps were taken
    settled_ = true;
    return false;
}

void DrapeRun::repair_crossings() {
    if (!options_.repair_crossings || options_.fallback_steps < 1) return;
    const cloth::ContactReport before = rest_report();
    if (before.self_intersections == 0) return;
    Eigen::MatrixX3d X = garment_positions(sim_.positions());
    const cloth::Obstacle& body = *sim_.obstacle();
    const UntangleSummary u = untangle_garment(mesh_, body.positions(), body.faces(), UntangleOptions{}, X);
    if (u.self_intersections >= before.self_intersections) {
        note("the " + std::to_string(before.self_intersections) + " crossings at rest could not be untangled (" +
             std::to_string(u.self_intersections) + " left)");
        return;
    }
    // Stitched vertices moved together: each simulation vertex takes its garment vertices' place.
    Eigen::MatrixX3d x = sim_.positions();
    for (int v = 0; v < nv_; ++v) x.row(sim_vertex_[size_t(v)]) = X.row(v);
    std::string why;
    const bool kept = retry_at_rest(
        options_.simulator, x, Eigen::MatrixX3d::Zero(x.rows(), 3),
        [&](const cloth::ContactReport& after) {
            return after.self_intersections < before.self_intersections &&
                   after.max_penetration_m <= std::max(before.max_penetration_m, options_.penetration_tolerance_m);
        },
        &why);
    if (kept)
        summary_.crossings_repaired = before.self_intersections - rest_report().self_intersections;
    else if (summary_.termination != DrapeTermination::cancelled)
        note("untangled, the cloth came to rest with " + why + " (before: " +
             std::to_string(before.self_intersections) + " crossings): the rest state before is kept");
}

void DrapeRun::stiffen_contact() {
    if (!(options_.contact_stiffening > 1) || options_.fallback_steps < 1) return;
    const cloth::ContactReport before = rest_report();
    if (before.max_penetration_m <= options_.penetration_tolerance_m) return;
    cloth::SimulatorOptions stiff = options_.simulator;
    stiff.contact_inside_stiffness_factor *= options_.contact_stiffening;
    std::string why;
    const bool kept = retry_at_rest(
        stiff, sim_.positions(), sim_.velocities(),
        [&](const cloth::ContactReport& after) {
            return after.max_penetration_m < before.max_penetration_m &&
                   after.self_intersections <= before.self_intersections;
        },
        &why);
    if (kept)
        summary_.contact_stiffened = true;
    else if (summary_.termination != DrapeTermination::cancelled)
        note("a stiffer contact left the cloth with " + why + ": the rest state before it is kept");
}

void DrapeRun::measure(Eigen::MatrixX3d& out_positions) {
    // A cancelled drape returns at once: the contact report (self-intersections above all)
    // would cost a step's time, for figures of a state nobody asked for.
    if (summary_.termination != DrapeTermination::cancelled) {
        const cloth::ContactReport& r = rest_report();
        summary_.seam_gap_max_m = r.max_stitch_gap_m;
        summary_.penetration_max_m = r.max_penetration_m;
        summary_.vertices_inside = r.vertices_inside;
        summary_.self_intersections = r.self_intersections;
    }
    summary_.converged = summary_.termination == DrapeTermination::converged;
    out_positions = garment_positions(sim_.positions());
    const Eigen::Vector3d g = options_.simulator.gravity_m_per_s2;
    const Eigen::Vector3d down = g.norm() > 0 ? Eigen::Vector3d(g.normalized()) : Eigen::Vector3d(0, -1, 0);
    const double garment_sink = ((out_positions - initial_positions_) * down).mean();
    const double body_sink = ((body_path_.back() - body_path_.front()) * down).mean();
    summary_.mean_drop_m = garment_sink - body_sink;
    if (summary_.mean_drop_m > options_.max_mean_drop_m)
        note("the garment slid down the body: its vertices sank " + std::to_string(100 * summary_.mean_drop_m) +
             " cm on average (at most " +
             std::to_string(100 * options_.max_mean_drop_m) + " cm)");
    if (!notes_.empty()) summary_.message += (summary_.message.empty() ? "" : "; ") + notes_;
}

}  // namespace drape::garment::detail
