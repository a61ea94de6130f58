// animate_outfit: the welded outfit stepped on the moving body, frame by frame.
#include <drape/garment/animate.hpp>

#include <drape/core/errors.hpp>
#include <drape/garment/drape_garment.hpp>

#include "drape_run.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <sstream>

namespace drape::garment {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const char* termination_name(AnimateTermination t) {
    switch (t) {
        case AnimateTermination::completed: return "completed";
        case AnimateTermination::step_failed: return "step failed";
        case AnimateTermination::exploded: return "exploded";
        case AnimateTermination::cancelled: return "cancelled";
    }
    return "?";
}

// The joint that drives body face f most: the largest summed skin weight of its corners.
std::string dominant_joint(const body::BodyModel& model, int f) {
    Eigen::VectorXd w = Eigen::VectorXd::Zero(body::kJointCount);
    for (int c = 0; c < 3; ++c) {
        const int v = model.faces(f, c);
        for (int j = 0; j < body::kJointCount; ++j) w(j) += model.skin_weights.coeff(v, j);
    }
    Eigen::Index j = 0;
    w.maxCoeff(&j);
    return std::string(body::kJointNames[static_cast<std::size_t>(j)]);
}

double max_speed(const cloth::Simulator& sim) {
    return sim.velocities().rows() ? sim.velocities().rowwise().norm().maxCoeff() : 0.0;
}


}  // namespace

cloth::SimulatorOptions AnimateOptions::default_simulator_options() {
    cloth::SimulatorOptions o = DrapeOptions::default_simulator_options();
    // 8 Newton iterations per step: with 4, every step of a walking t-shirt ended unconverged
    // and the cloth rested 2-3 mm inside the moving shoulders (docs/animation.md).
    o.max_newton_iterations = 8;
    o.air_drag_n_s_per_m3 = 0.5;
    // Friction Hessian majorized for slides over 0.5 mm in a step: with the exact one, Newton
    // stopped short on the walking body every step and pants fell down (docs/cloth.md,
    // "Friction on a moving body"). Draping keeps the exact Hessian (not measured there).
    o.friction_majorize_slip_m = 0.5e-3;
    // Steps that end on their iteration cap end with the cloth outside the moving body: the
    // t-shirt's neckline and armpit ended steps 2-5.5 mm inside without (docs/cloth.md).
    o.strict_body_contact = true;
    return o;
}

bool AnimateOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!(std::isfinite(fps) && fps > 0)) return fail("AnimateOptions::fps = " + std::to_string(fps) + " must be > 0");
    if (!(std::isfinite(seconds) && seconds >= 0))
        return fail("AnimateOptions::seconds = " + std::to_string(seconds) + " must be >= 0");
    if (!(std::isfinite(blend_s) && blend_s >= 0))
        return fail("AnimateOptions::blend_s = " + std::to_string(blend_s) + " must be >= 0");
    if (!(std::isfinite(max_body_step_m) && max_body_step_m > 0))
        return fail("AnimateOptions::max_body_step_m = " + std::to_string(max_body_step_m) + " must be > 0");
    if (min_substeps < 1 || max_substeps < min_substeps)
        return fail("AnimateOptions: substeps in [" + std::to_string(min_substeps) + ", " +
                    std::to_string(max_substeps) + "], need 1 <= min_substeps <= max_substeps");
    if (!wind_m_per_s.allFinite()) return fail("AnimateOptions::wind_m_per_s is not finite");
    if (!(std::isfinite(explosion_speed_m_per_s) && explosion_speed_m_per_s > 0))
        return fail("AnimateOptions::explosion_speed_m_per_s must be > 0");
    if (!(std::isfinite(waistband_width_cm) && waistband_width_cm >= 0))
        return fail("AnimateOptions::waistband_width_cm must be >= 0");
    if (!(std::isfinite(waistband_stretching_factor) && waistband_stretching_factor >= 1))
        return fail("AnimateOptions::waistband_stretching_factor must be >= 1");
    if (!(std::isfinite(penetration_tolerance_m) && penetration_tolerance_m > 0))
        return fail("AnimateOptions::penetration_tolerance_m must be > 0");
    if (!(std::isfinite(slip_tolerance_m) && slip_tolerance_m > 0))
        return fail("AnimateOptions::slip_tolerance_m must be > 0");
    std::string w;
    if (!simulator.is_valid(&w)) return fail("AnimateOptions::simulator: " + w);
    return true;
}

std::string AnimateSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "animation usable" : "animation NOT usable") << " (" << termination_name(termination)
       << "): " << frames << " frames, " << vertices << " vertices; max penetration " << max_penetration_m * 1e3
       << " mm, max crossings " << max_self_intersections << ", max slip " << max_slip_m * 1e2 << " cm, max speed "
       << max_speed_m_per_s << " m/s; "
       << seconds_per_frame << " s/frame (CPU " << cpu_seconds_per_frame << " s), blend " << seconds_blend << " s, total " << seconds << " s";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

AnimateSummary animate_outfit(const body::BodyModel& model, const body::ShapedBody& shaped,
                              const DressedOutfit& outfit, const std::vector<cloth::Material>& materials,
                              const body::Motion& motion, const AnimateOptions& options, AnimatedOutfit& out) {
    const auto start = std::chrono::steady_clock::now();
    std::string why;
    require(options.is_valid(&why), "animate_outfit: ", why);
    require(motion.is_valid(&why), "animate_outfit: motion: ", why);
    const std::size_t n = outfit.meshes.size();
    require(n >= 1, "animate_outfit: the outfit has no garment");
    require(outfit.patterns.size() == n && outfit.positions.size() == n, "animate_outfit: the outfit has ", n,
            " meshes, ", outfit.patterns.size(), " patterns and ", outfit.positions.size(),
            " draped positions (need one each per garment)");
    require(materials.size() == n, "animate_outfit: ", materials.size(), " materials for ", n,
            " garments (need one per garment)");
    for (std::size_t g = 0; g < n; ++g) {
        require(materials[g].is_valid(&why), "animate_outfit: material of garment ", g, ": ", why);
        require(outfit.positions[g].rows() == outfit.meshes[g].cloth.vertex_count() && outfit.positions[g].allFinite(),
                "animate_outfit: garment ", g, " has ", outfit.positions[g].rows(), " draped positions for ",
                outfit.meshes[g].cloth.vertex_count(), " vertices");
    }

    // The outfit as one welded mesh at its draped state.
    std::vector<int> first;
    const GarmentMesh all = detail::concatenate(outfit.meshes, &first);
    Eigen::MatrixX3d X(all.cloth.vertex_count(), 3);
    for (std::size_t g = 0; g < n; ++g) X.middleRows(first[g], outfit.positions[g].rows()) = outfit.positions[g];
    std::vector<cloth::Material> fabrics;
    std::vector<int> face_material;
    detail::outfit_fabrics(outfit.patterns, outfit.meshes, materials, options.waistband_width_cm,
                           options.waistband_stretching_factor, fabrics, face_material);
    Eigen::MatrixX3d V0;
    detail::Welded welded = detail::weld(all.cloth, X, Eigen::MatrixX3d::Zero(X.rows(), 3), all.stitches, &V0);
    std::vector<int> vertex_of = welded.vertex_of;
    bool welded_ok = true;
    try {
        welded.mesh.validate();
    } catch (const InvalidInput&) {
        welded_ok = false;  // keep the stitches instead (as draping does)
    }
    const body::Motion frames = resample_motion(motion, options.fps, options.seconds);
    out.motion = frames;
    out.frames.clear();
    const int K = int(frames.frames.size());
    const auto body_at = [&](const body::Pose& p) -> Eigen::MatrixX3d { return body::pose_body(model, shaped, p).vertices; };
    // One step count per frame for the whole run (the simulator's time step is fixed): enough
    // for the fastest frame of the motion.
    double fastest = 0;
    {
        Eigen::MatrixX3d a = body_at(frames.frames.front());
        for (int k = 1; k < K; ++k) {
            Eigen::MatrixX3d b = body_at(frames.frames[std::size_t(k)]);
            fastest = std::max(fastest, (b - a).rowwise().norm().maxCoeff());
            a = std::move(b);
        }
    }
    const int cap = std::max(options.min_substeps, int(std::ceil(options.max_substeps * 30.0 / options.fps - 1e-9)));
    const int substeps = std::clamp(int(std::ceil(fastest / options.max_body_step_m)), options.min_substeps, cap);
    cloth::SimulatorOptions sim_options = options.simulator;
    sim_options.wind_m_per_s = options.wind_m_per_s;
    sim_options.time_step_s = 1.0 / (options.fps * substeps);
    cloth::ClothMesh sim_mesh = welded_ok ? std::move(welded.mesh) : all.cloth;
    if (!welded_ok) {
        sim_mesh.positions = X;
        for (int v = 0; v < X.rows(); ++v) vertex_of[std::size_t(v)] = v;
    }
    cloth::Simulator sim(std::move(sim_mesh), fabrics, face_material, sim_options);
    if (!welded_ok) sim.set_stitches(garment_stitches(all));

    Eigen::MatrixX3d body = body_at(outfit.pose);
    sim.set_obstacle(cloth::Obstacle(body, model.faces));

    AnimateSummary summary;
    summary.vertices = int(sim.positions().rows());
    summary.penetration_tolerance_m = options.penetration_tolerance_m;
    summary.slip_tolerance_m = options.slip_tolerance_m;
    // Each garment's top (its vertices within kTopBandM of its highest point: a waistband,
    // the shoulders), each vertex with the body vertex nearest to it as draped: the slip is
    // how far the top sank relative to those body points (AnimationFrameCheck::max_slip_m),
    // which follow the pelvis's bob and turn.
    constexpr double kTopBandM = 0.02;
    struct TopPoint {
        int cloth = 0, body = 0;
        double height = 0;  // cloth y − body y as draped
    };
    std::vector<std::vector<TopPoint>> tops(n);
    for (std::size_t g = 0; g < n; ++g) {
        const Eigen::MatrixX3d& P = outfit.positions[g];
        const double top = P.col(1).maxCoeff();
        for (Eigen::Index v = 0; v < P.rows(); ++v) {
            if (P(v, 1) < top - kTopBandM) continue;
            Eigen::Index b = 0;
            (body.rowwise() - P.row(v)).rowwise().squaredNorm().minCoeff(&b);
            tops[g].push_back({first[g] + int(v), int(b), P(v, 1) - body(b, 1)});
        }
    }
    const auto garment_frame = [&]() {
        std::vector<Eigen::MatrixX3d> gs(n);
        const Eigen::MatrixX3d& x = sim.positions();
        for (std::size_t g = 0; g < n; ++g) {
            gs[g].resize(first[g + 1] - first[g], 3);
            for (int v = first[g]; v < first[g + 1]; ++v) gs[g].row(v - first[g]) = x.row(vertex_of[std::size_t(v)]);
        }
        return gs;
    };
    int newton = 0;
    // Moves the body from pose a to pose b over dt (s) in substeps; false if a step failed or
    // the cloth exploded (the summary says which).
    const auto advance = [&](const body::Pose& a, const body::Pose& b) {
        const Eigen::MatrixX3d target = body_at(b);
        for (int s = 1; s <= substeps; ++s) {
            const Eigen::MatrixX3d B = s == substeps ? target : body_at(body::interpolate_pose(a, b, double(s) / substeps));
            sim.move_obstacle(B);
            const cloth::StepSummary step = sim.step();
            newton += step.newton_iterations;
            if (!step.usable()) {
                summary.termination = AnimateTermination::step_failed;
                summary.message = step.brief_report();
                return false;
            }
            const double speed = max_speed(sim);
            if (!(speed <= options.explosion_speed_m_per_s)) {
                summary.termination = AnimateTermination::exploded;
                std::ostringstream os;
                os << "a garment vertex reached " << speed << " m/s (limit " << options.explosion_speed_m_per_s << ")";
                summary.message = os.str();
                return false;
            }
        }
        body = target;
        return true;
    };

    // Blend from the draped pose into the motion's first pose (smoothstep), not output.
    const int blend_frames = int(std::ceil(options.blend_s * options.fps));
    const auto t_blend = std::chrono::steady_clock::now();
    body::Pose previous = outfit.pose;
    for (int k = 1; k <= blend_frames; ++k) {
        const double s = double(k) / blend_frames;
        const body::Pose next = body::interpolate_pose(outfit.pose, frames.frames.front(), s * s * (3 - 2 * s));
        if (!advance(previous, next)) {
            summary.message = "blending into the motion: " + summary.message;
            summary.seconds_blend = seconds_since(t_blend);
            summary.seconds = seconds_since(start);
            return summary;
        }
        previous = next;
        if (options.on_progress && !options.on_progress({true, k, blend_frames, seconds_since(start)})) {
            summary.termination = AnimateTermination::cancelled;
            summary.message = "cancelled while blending into the motion";
            summary.seconds = seconds_since(start);
            return summary;
        }
    }
    summary.seconds_blend = seconds_since(t_blend);
    // The motion starts at its own pace (a walk at 1.2 m/s): the cloth is given the root's
    // velocity of the first frame, as if it had been moving with the body, instead of being
    // hit by it from rest (which left the front of a skirt 4 cm inside the legs).
    if (K >= 2) {
        const Eigen::Vector3d root_velocity = (frames.frames[1].translation - frames.frames[0].translation) * options.fps;
        sim.set_velocities(sim.velocities().rowwise() + root_velocity.transpose());
    }

    double frame_seconds = 0, cpu_seconds = 0;
    for (int k = 0; k < K; ++k) {
        const auto t_frame = std::chrono::steady_clock::now();
        const std::clock_t c_frame = std::clock();
        AnimationFrameCheck check;
        check.time_s = double(k) / options.fps;
        newton = 0;
        check.substeps = k > 0 ? substeps : 0;
        if (k > 0 && !advance(frames.frames[std::size_t(k - 1)], frames.frames[std::size_t(k)])) {
            summary.message = "frame " + std::to_string(k) + ": " + summary.message;
            break;
        }
        const cloth::ContactReport report = sim.contact_report();
        check.max_penetration_m = report.max_penetration_m;
        check.vertices_inside = report.vertices_inside;
        if (report.deepest_obstacle_face >= 0) check.deepest_joint = dominant_joint(model, report.deepest_obstacle_face);
        check.self_intersections = report.self_intersections;
        check.max_speed_m_per_s = max_speed(sim);
        std::vector<Eigen::MatrixX3d> garments = garment_frame();
        for (std::size_t g = 0; g < n; ++g) {
            double sunk = 0;
            for (const TopPoint& t : tops[g])
                sunk += t.height - (sim.positions()(vertex_of[std::size_t(t.cloth)], 1) - body(t.body, 1));
            check.max_slip_m = std::max(check.max_slip_m, sunk / double(std::max<std::size_t>(tops[g].size(), 1)));
        }
        check.newton_iterations = newton;
        check.seconds = seconds_since(t_frame);
        check.cpu_seconds = double(std::clock() - c_frame) / CLOCKS_PER_SEC;
        frame_seconds += check.seconds;
        cpu_seconds += check.cpu_seconds;
        summary.checks.push_back(check);
        summary.max_penetration_m = std::max(summary.max_penetration_m, check.max_penetration_m);
        summary.max_self_intersections = std::max(summary.max_self_intersections, check.self_intersections);
        summary.max_speed_m_per_s = std::max(summary.max_speed_m_per_s, check.max_speed_m_per_s);
        summary.max_slip_m = std::max(summary.max_slip_m, check.max_slip_m);
        out.frames.push_back(std::move(garments));
        summary.frames = k + 1;
        if (options.on_progress && !options.on_progress({false, k + 1, K, seconds_since(start)})) {
            summary.termination = AnimateTermination::cancelled;
            summary.message = "cancelled after frame " + std::to_string(k + 1) + " of " + std::to_string(K);
            break;
        }
        if (k + 1 == K) summary.termination = AnimateTermination::completed;
    }
    summary.seconds_per_frame = summary.frames > 0 ? frame_seconds / summary.frames : 0;
    summary.cpu_seconds_per_frame = summary.frames > 0 ? cpu_seconds / summary.frames : 0;
    summary.seconds = seconds_since(start);
    return summary;
}

}  // namespace drape::garment
