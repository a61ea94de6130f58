#include <drape/garment/drape_garment.hpp>
#include <drape/garment/arm_clearance.hpp>

#include <drape/core/errors.hpp>

#include "dressing_internal.hpp"
#include "drape_run.hpp"

#include <drape/cloth/intersections.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

namespace drape::garment {

namespace {

const char* termination_name(DrapeTermination t) {
    switch (t) {
        case DrapeTermination::converged: return "converged";
        case DrapeTermination::not_settled: return "not settled";
        case DrapeTermination::static_failed: return "static solve failed";
        case DrapeTermination::step_failed: return "step failed";
        case DrapeTermination::cancelled: return "cancelled";
    }
    return "?";
}

}  // namespace

cloth::SimulatorOptions DrapeOptions::default_simulator_options() {
    cloth::SimulatorOptions o;
    o.gravity_m_per_s2 = Eigen::Vector3d(0.0, -9.8, 0.0);
    o.time_step_s = 1e-2;
    o.air_drag_n_s_per_m3 = 2.0;
    o.max_newton_iterations = 3;
    return o;
}

bool DrapeOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& t) {
        if (why) *why = t;
        return false;
    };
    std::string sim_why;
    if (!simulator.is_valid(&sim_why)) return fail("DrapeOptions::simulator: " + sim_why);
    if (!(seam_gap_tolerance_m > 0))
        return fail("DrapeOptions::seam_gap_tolerance_m = " + std::to_string(seam_gap_tolerance_m) + " must be > 0");
    if (!(settled_kinetic_energy_j_per_kg > 0))
        return fail("DrapeOptions::settled_kinetic_energy_j_per_kg = " +
                    std::to_string(settled_kinetic_energy_j_per_kg) + " must be > 0");
    if (min_steps < 0) return fail("DrapeOptions::min_steps = " + std::to_string(min_steps) + " must be >= 0");
    if (max_steps < 1 || max_steps < min_steps)
        return fail("DrapeOptions::max_steps = " + std::to_string(max_steps) + " must be >= 1 and >= min_steps");
    if (static_max_newton_iterations < 1)
        return fail("DrapeOptions::static_max_newton_iterations = " + std::to_string(static_max_newton_iterations) +
                    " must be >= 1");
    if (max_untangle_steps < 0)
        return fail("DrapeOptions::max_untangle_steps = " + std::to_string(max_untangle_steps) + " must be >= 0");
    if (!(body_motion_s > 0 && std::isfinite(body_motion_s)))
        return fail("DrapeOptions::body_motion_s = " + std::to_string(body_motion_s) + " must be > 0");
    if (fallback_steps < 0)
        return fail("DrapeOptions::fallback_steps = " + std::to_string(fallback_steps) + " must be >= 0");
    if (!(max_mean_drop_m > 0 && std::isfinite(max_mean_drop_m)))
        return fail("DrapeOptions::max_mean_drop_m = " + std::to_string(max_mean_drop_m) + " must be > 0");
    if (!(waistband_width_cm >= 0 && std::isfinite(waistband_width_cm)))
        return fail("DrapeOptions::waistband_width_cm = " + std::to_string(waistband_width_cm) + " must be >= 0");
    if (!(waistband_stretching_factor >= 1 && std::isfinite(waistband_stretching_factor)))
        return fail("DrapeOptions::waistband_stretching_factor = " + std::to_string(waistband_stretching_factor) +
                    " must be >= 1");
    if (!(contact_stiffening >= 1 && std::isfinite(contact_stiffening)))
        return fail("DrapeOptions::contact_stiffening = " + std::to_string(contact_stiffening) + " must be >= 1");
    if (!(penetration_tolerance_m > 0))
        return fail("DrapeOptions::penetration_tolerance_m = " + std::to_string(penetration_tolerance_m) +
                    " must be > 0");
    return true;
}

std::string DrapeSummary::failed_checks() const {
    std::string out;
    const auto add = [&](const std::string& f) { out += (out.empty() ? "" : "; ") + f; };
    if (!converged) add(drape::detail::concat("not converged (", termination_name(termination), ")"));
    if (!(seam_gap_max_m < seam_gap_tolerance_m))
        add(drape::detail::concat("seam gap ", 1000 * seam_gap_max_m, " mm >= ", 1000 * seam_gap_tolerance_m, " mm"));
    if (!(penetration_max_m <= penetration_tolerance_m))
        add(drape::detail::concat("penetration ", 1000 * penetration_max_m, " mm > ", 1000 * penetration_tolerance_m,
                                  " mm"));
    if (self_intersections != 0) add(drape::detail::concat(self_intersections, " self-intersections"));
    if (!(mean_drop_m <= max_mean_drop_m))
        add(drape::detail::concat("mean drop ", 100 * mean_drop_m, " cm > ", 100 * max_mean_drop_m, " cm"));
    return out;
}

std::string DrapeSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "draped" : "draping NOT usable") << " (" << termination_name(termination) << "): "
       << "dressed state: gap " << 1000 * initial_seam_gap_max_m << " mm, penetration "
       << 1000 * initial_penetration_max_m << " mm, " << initial_self_intersections << " self-intersections; "
       << vertices << " vertices, " << stitches << " stitches, max seam gap " << 1000 * seam_gap_max_m
       << " mm, max penetration " << 1000 * penetration_max_m << " mm (" << vertices_inside
       << " vertices inside), " << self_intersections << " self-intersections, " << steps
       << " steps (seams closed at step " << steps_to_close_seams << "), static |g| " << static_gradient_n
       << " N in " << static_newton_iterations << " iterations, mean drop " << 100 * mean_drop_m << " cm, "
       << seconds << " s";
    if (crossings_repaired > 0) os << ", " << crossings_repaired << " crossings repaired at rest";
    if (contact_stiffened) os << ", contact stiffened";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

std::vector<cloth::Stitch> garment_stitches(const GarmentMesh& mesh) {
    const int nv = mesh.cloth.vertex_count();
    require(mesh.stitch_seam.size() == mesh.stitches.size(), "garment_stitches: ", mesh.stitches.size(),
            " stitches but ", mesh.stitch_seam.size(), " seam indices");
    require(mesh.cloth.pattern.rows() == nv, "garment_stitches: the mesh has ", nv, " vertices but ",
            mesh.cloth.pattern.rows(), " pattern points (per-vertex pattern expected)");
    // Boundary neighbours of every vertex on its panel's loop.
    std::vector<std::pair<int, int>> neighbours(size_t(nv), {-1, -1});
    for (const std::vector<int>& loop : mesh.boundary_loops) {
        const size_t n = loop.size();
        for (size_t k = 0; k < n; ++k) {
            require(loop[k] >= 0 && loop[k] < nv, "garment_stitches: boundary vertex ", loop[k], " out of range");
            neighbours[size_t(loop[k])] = {loop[(k + n - 1) % n], loop[(k + 1) % n]};
        }
    }
    std::set<std::pair<int, int>> on_seam;  // (vertex, seam) for side a of each stitch
    for (size_t s = 0; s < mesh.stitches.size(); ++s) on_seam.insert({mesh.stitches[s][0], mesh.stitch_seam[s]});

    auto pattern_length = [&](int i, int j) { return (mesh.cloth.pattern.row(i) - mesh.cloth.pattern.row(j)).norm(); };
    std::vector<cloth::Stitch> out;
    out.reserve(mesh.stitches.size());
    for (size_t s = 0; s < mesh.stitches.size(); ++s) {
        const auto [a, b] = mesh.stitches[s];
        require(a >= 0 && a < nv && b >= 0 && b < nv && a != b, "garment_stitches: stitch ", s, " (", a, ", ",
                b, ") is invalid");
        const auto [prev, next] = neighbours[size_t(a)];
        double length = 0, fallback = 0;
        for (int other : {prev, next}) {
            if (other < 0) continue;
            const double half = 0.5 * pattern_length(a, other);
            fallback += half;
            // Only the boundary segments that belong to this seam count.
            if (on_seam.count({other, mesh.stitch_seam[s]})) length += half;
        }
        if (!(length > 0)) length = fallback;
        if (!(length > 0)) length = 0.5 * pattern_length(a, b) + 1e-3;
        out.push_back({a, b, length});
    }
    return out;
}

DrapeSummary drape_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                           const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3i& body_faces,
                           const cloth::Material& material, const DrapeOptions& options,
                           Eigen::MatrixX3d& out_positions) {
    return drape_garment(mesh, initial_positions, std::vector<Eigen::MatrixX3d>{body_vertices}, body_faces, material,
                         options, out_positions);
}

DrapeSummary drape_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                           const std::vector<Eigen::MatrixX3d>& body_path, const Eigen::MatrixX3i& body_faces,
                           const cloth::Material& material, const DrapeOptions& options,
                           Eigen::MatrixX3d& out_positions) {
    std::string why;
    require(material.is_valid(&why), "drape_garment: material: ", why);
    return drape_garment(mesh, initial_positions, body_path, body_faces, std::vector<cloth::Material>{material},
                         std::vector<int>(size_t(mesh.cloth.face_count()), 0), options, out_positions);
}

DrapeSummary drape_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                           const std::vector<Eigen::MatrixX3d>& body_path, const Eigen::MatrixX3i& body_faces,
                           const std::vector<cloth::Material>& materials, const std::vector<int>& face_material,
                           const DrapeOptions& options, Eigen::MatrixX3d& out_positions) {
    const auto start = std::chrono::steady_clock::now();
    detail::check_drape_inputs(mesh, initial_positions, body_path, materials, face_material, options);
    detail::DrapeRun run(mesh, initial_positions, body_path, body_faces, materials, face_material, options);
    if (!run.untangle(out_positions)) return run.summary();  // cancelled
    if (run.close_seams_and_settle() && run.settled()) {
        if (options.static_solve) run.solve_static();
        if (run.settled()) run.repair_crossings();
        if (run.settled()) run.stiffen_contact();
    }
    run.measure(out_positions);
    DrapeSummary summary = run.summary();
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return summary;
}

std::vector<int> waistband_faces(const Pattern& pattern, const GarmentMesh& mesh, double width_cm) {
    require(width_cm >= 0 && std::isfinite(width_cm), "waistband_faces: width_cm = ", width_cm, " must be >= 0");
    require(mesh.panel_of_vertex.size() == mesh.cloth.vertex_count() &&
                mesh.panel_point_cm.rows() == mesh.cloth.vertex_count(),
            "waistband_faces: the mesh's per-vertex panel data do not match its ", mesh.cloth.vertex_count(),
            " vertices");
    std::vector<int> out;
    if (width_cm == 0) return out;
    // Per panel the waist as a polyline (0.5 cm chords), or empty.
    std::vector<std::vector<Eigen::Vector2d>> waist(pattern.panels.size());
    for (size_t p = 0; p < pattern.panels.size(); ++p) {
        const Panel& panel = pattern.panels[p];
        if (!(detail::role_of(pattern, p) == detail::Role::skirt && detail::is_skirt(pattern))) continue;
        const int best = detail::waist_edge(pattern, p);
        if (best < 0) continue;
        const Edge& edge = panel.edges[size_t(best)];
        const int n = std::max(2, int(std::ceil(edge.length() / 0.5)));
        for (int k = 0; k <= n; ++k) waist[p].push_back(edge.point_at_fraction(double(k) / n));
    }
    for (int f = 0; f < mesh.cloth.face_count(); ++f) {
        const int panel = mesh.panel_of_vertex(mesh.cloth.faces(f, 0));
        require(panel >= 0 && size_t(panel) < pattern.panels.size(), "waistband_faces: face ", f, " is on panel ",
                panel, ", the pattern has ", pattern.panels.size());
        const std::vector<Eigen::Vector2d>& line = waist[size_t(panel)];
        if (line.empty()) continue;
        Eigen::Vector2d c = Eigen::Vector2d::Zero();
        for (int k = 0; k < 3; ++k) c += mesh.panel_point_cm.row(mesh.cloth.faces(f, k)).transpose() / 3;
        double d2 = 1e300;
        for (size_t k = 0; k + 1 < line.size(); ++k) {
            const Eigen::Vector2d a = line[k], ab = line[k + 1] - a;
            const double t = std::clamp((c - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
            d2 = std::min(d2, (a + t * ab - c).squaredNorm());
        }
        if (d2 <= width_cm * width_cm) out.push_back(f);
    }
    return out;
}

cloth::Material waistband_material(const cloth::Material& material, double stretching_factor) {
    require(stretching_factor >= 1 && std::isfinite(stretching_factor), "waistband_material: stretching_factor = ",
            stretching_factor, " must be >= 1");
    cloth::Material band = material;
    band.stretching_scale *= stretching_factor;
    return band;
}

DrapeSummary dress_and_drape(const Pattern& pattern, const GarmentMesh& mesh, const body::BodyModel& model,
                             const body::ShapedBody& shaped, const body::Pose& pose, const cloth::Material& material,
                             const DressingOptions& dressing_options, const DrapeOptions& options,
                             Eigen::MatrixX3d& out_positions, DressingSummary* dressing) {
    std::string why;
    require(pose.is_valid(&why), "dress_and_drape: pose: ", why);
    // Dressed in the rest A-pose (arms raised if a sleeve cannot be placed clear there).
    body::Pose rest;
    Eigen::MatrixX3d X0;
    const DressingSummary dressed = dress_for_drape(pattern, mesh, model, shaped, dressing_options, X0, rest);
    if (dressing) *dressing = dressed;
    const bool at_rest = (pose.translation - rest.translation).isZero(0) && (pose.rotations - rest.rotations).isZero(0);
    const std::vector<Eigen::MatrixX3d> path =
        at_rest ? std::vector<Eigen::MatrixX3d>{body::pose_body(model, shaped, rest).vertices}
                : pose_path(model, shaped, rest, pose, 11);
    require(options.is_valid(&why), "dress_and_drape: ", why);
    require(material.is_valid(&why), "dress_and_drape: material: ", why);
    // The waistband's faces are of the stiffened fabric (DrapeOptions::waistband_width_cm).
    std::vector<int> face_material(size_t(mesh.cloth.face_count()), 0);
    for (int f : waistband_faces(pattern, mesh, options.waistband_width_cm)) face_material[size_t(f)] = 1;
    return drape_garment(mesh, X0, path, model.faces,
                         {material, waistband_material(material, options.waistband_stretching_factor)}, face_material,
                         options, out_positions);
}

namespace detail {

// The garments of an outfit as one mesh: vertices, faces, stitches and boundary loops
// renumbered one garment after the other; each garment's flat layout is shifted 10 m along
// u so that no two garments share pattern space (the self-contact rest-neighbour filter
// compares pattern positions within a connected piece).
GarmentMesh concatenate(const std::vector<GarmentMesh>& meshes, std::vector<int>* first_vertex) {
    GarmentMesh out;
    int nv = 0, nf = 0, np = 0, ns = 0, panels = 0;
    for (const GarmentMesh& m : meshes) {
        nv += m.cloth.vertex_count();
        nf += m.cloth.face_count();
        np += int(m.cloth.pattern.rows());
    }
    out.cloth.positions.resize(nv, 3);
    out.cloth.faces.resize(nf, 3);
    out.cloth.pattern.resize(np, 2);
    out.cloth.pattern_faces.resize(nf, 3);
    out.panel_of_vertex.resize(nv);
    out.panel_point_cm.resize(nv, 2);
    out.boundary_edge.resize(nv);
    out.boundary_fraction.resize(nv);
    out.uv.resize(nv, 2);
    int v0 = 0, f0 = 0, p0 = 0;
    for (size_t g = 0; g < meshes.size(); ++g) {
        const GarmentMesh& m = meshes[g];
        const int mv = m.cloth.vertex_count(), mf = m.cloth.face_count(), mp = int(m.cloth.pattern.rows());
        first_vertex->push_back(v0);
        out.cloth.positions.middleRows(v0, mv) = m.cloth.positions;
        out.cloth.faces.middleRows(f0, mf) = m.cloth.faces.array() + v0;
        out.cloth.pattern.middleRows(p0, mp) = m.cloth.pattern;
        out.cloth.pattern.middleRows(p0, mp).col(0).array() += 10.0 * double(g);
        out.cloth.pattern_faces.middleRows(f0, mf) = m.cloth.pattern_faces.array() + p0;
        out.panel_of_vertex.segment(v0, mv) = m.panel_of_vertex.array() + panels;
        out.panel_point_cm.middleRows(v0, mv) = m.panel_point_cm;
        out.boundary_edge.segment(v0, mv) = m.boundary_edge;
        out.boundary_fraction.segment(v0, mv) = m.boundary_fraction;
        out.uv.middleRows(v0, mv) = m.uv;
        for (size_t k = 0; k < m.stitches.size(); ++k) {
            out.stitches.push_back({m.stitches[k][0] + v0, m.stitches[k][1] + v0});
            out.stitch_seam.push_back(m.stitch_seam[k] + ns);
        }
        for (const std::vector<int>& loop : m.boundary_loops) {
            out.boundary_loops.push_back(loop);
            for (int& v : out.boundary_loops.back()) v += v0;
        }
        int seams = 0;
        for (int s : m.stitch_seam) seams = std::max(seams, s + 1);
        ns += seams;
        panels += m.panel_of_vertex.size() ? m.panel_of_vertex.maxCoeff() + 1 : 0;
        v0 += mv;
        f0 += mf;
        p0 += mp;
    }
    first_vertex->push_back(v0);
    return out;
}

void outfit_fabrics(const std::vector<Pattern>& patterns, const std::vector<GarmentMesh>& meshes,
                    const std::vector<cloth::Material>& materials, double waistband_width_cm,
                    double waistband_stretching_factor, std::vector<cloth::Material>& fabrics,
                    std::vector<int>& face_material) {
    const int n = int(meshes.size());
    fabrics = materials;
    for (const cloth::Material& m : materials) fabrics.push_back(waistband_material(m, waistband_stretching_factor));
    face_material.clear();
    for (int g = 0; g < n; ++g) {
        const size_t f0 = face_material.size();
        face_material.insert(face_material.end(), size_t(meshes[size_t(g)].cloth.face_count()), g);
        for (int f : waistband_faces(patterns[size_t(g)], meshes[size_t(g)], waistband_width_cm))
            face_material[f0 + size_t(f)] = n + g;
    }
}

}  // namespace detail

DrapeSummary dress_and_drape_outfit(const std::vector<Pattern>& patterns, const std::vector<GarmentMesh>& meshes,
                                    const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                    const cloth::Material& material, const DressingOptions& dressing_options,
                                    const DrapeOptions& options, std::vector<Eigen::MatrixX3d>& out_positions,
                                    std::vector<DressingSummary>* dressing) {
    return dress_and_drape_outfit(patterns, meshes, model, shaped, pose,
                                  std::vector<cloth::Material>(meshes.size(), material), dressing_options, options,
                                  out_positions, dressing);
}

DrapeSummary dress_and_drape_outfit(const std::vector<Pattern>& patterns, const std::vector<GarmentMesh>& meshes,
                                    const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                    const std::vector<cloth::Material>& materials,
                                    const DressingOptions& dressing_options, const DrapeOptions& options,
                                    std::vector<Eigen::MatrixX3d>& out_positions,
                                    std::vector<DressingSummary>* dressing) {
    require(!patterns.empty() && patterns.size() == meshes.size(), "dress_and_drape_outfit: ", patterns.size(),
            " patterns and ", meshes.size(), " meshes (need the same number, >= 1)");
    require(materials.size() == meshes.size(), "dress_and_drape_outfit: ", materials.size(), " materials for ",
            meshes.size(), " garments (need one per garment)");
    std::string why;
    for (size_t g = 0; g < materials.size(); ++g)
        require(materials[g].is_valid(&why), "dress_and_drape_outfit: material of garment ", g, ": ", why);
    require(pose.is_valid(&why), "dress_and_drape_outfit: pose: ", why);
    // Every garment is dressed in one pose: the rest A-pose, or the one dress_for_drape
    // chooses for the first garment with sleeves (its arms raised if its sleeves cannot be
    // placed clear in the rest pose); that garment's dressed state is reused below.
    body::Pose rest = body::Pose::rest();
    std::vector<std::pair<DressingSummary, Eigen::MatrixX3d>> with_sleeves(patterns.size());
    for (size_t g = 0; g < patterns.size(); ++g)
        if (detail::has_sleeves(patterns[g])) {
            with_sleeves[g].first =
                dress_for_drape(patterns[g], meshes[g], model, shaped, dressing_options, with_sleeves[g].second, rest);
            break;
        }
    const body::PosedSkeleton skel = body::forward_kinematics(shaped.joints, rest);
    const auto J = [&](body::Joint j) -> Eigen::Vector3d { return skel.joints.row(body::index(j)).transpose(); };
    const std::vector<Eigen::Vector3d> trunk = {J(body::Joint::pelvis), J(body::Joint::spine), J(body::Joint::chest),
                                                J(body::Joint::neck)};
    const double gap = options.simulator.contact_thickness_m + 0.001;
    std::vector<int> first;
    const GarmentMesh all = detail::concatenate(meshes, &first);
    // Dresses every garment (those without sleeves with `sleeveless_passes` placement
    // passes, 0 = automatic), each outside the ones before it; returns the layered state and
    // its crossings. A garment with sleeves always gets the automatic count, so its dressed
    // state is computed once and reused.
    const Eigen::MatrixX3i sewn = detail::sewn_faces(all);
    std::vector<DressingSummary> summaries;
    auto dress_all = [&](int sleeveless_passes) {
        summaries.clear();
        std::vector<Eigen::MatrixX3d> dressed(patterns.size());
        for (size_t g = 0; g < patterns.size(); ++g) {
            if (detail::has_sleeves(patterns[g])) {
                auto& [summary, X] = with_sleeves[g];
                if (X.size() == 0)
                    summary = dress_garment(patterns[g], meshes[g], model, shaped, rest, dressing_options, X);
                summaries.push_back(summary);
                dressed[g] = X;
            } else {
                DressingOptions garment_options = dressing_options;
                if (garment_options.placement_passes == 0) garment_options.placement_passes = sleeveless_passes;
                summaries.push_back(
                    dress_garment(patterns[g], meshes[g], model, shaped, rest, garment_options, dressed[g]));
            }
            if (g == 0) continue;
            // Outside every garment before it: an envelope of their vertices about the trunk.
            detail::AxisEnvelope inner(trunk, 0.8);
            for (size_t h = 0; h < g; ++h)
                for (Eigen::Index v = 0; v < dressed[h].rows(); ++v) inner.add(dressed[h].row(v).transpose());
            // Grown by 4 bins (4 cm along the axis, 20 degrees about it): a triangle of the outer
            // garment spanning the inner one's top edge must be pushed out at all its corners.
            inner.finish(4);
            for (Eigen::Index v = 0; v < dressed[g].rows(); ++v) {
                if (detail::role_of(patterns[g], size_t(meshes[g].panel_of_vertex(v))) == detail::Role::sleeve) continue;
                dressed[g].row(v) = inner.push(dressed[g].row(v).transpose(), gap, 0.01).transpose();
            }
        }
        Eigen::MatrixX3d layered(all.cloth.vertex_count(), 3);
        for (size_t g = 0; g < meshes.size(); ++g) layered.middleRows(first[g], dressed[g].rows()) = dressed[g];
        return std::make_pair(cloth::count_self_intersections(layered, sewn), layered);
    };
    auto [crossings, X0] = dress_all(0);
    // A garment without sleeves placed in one pass can leave the layered outfit crossed (the
    // t-shirt over the pants of the synthetic suite's Table 1: 8 crossings, 0 with 4 passes):
    // then the 4-pass placement is tried too and the state with fewer crossings kept.
    if (crossings > 0 && patterns.size() > 1) {
        const std::vector<DressingSummary> one_pass_summaries = summaries;
        auto [more_crossings, more_X0] = dress_all(4);
        if (more_crossings < crossings) X0 = std::move(more_X0);
        else summaries = one_pass_summaries;
    }
    if (dressing) *dressing = summaries;
    const bool at_rest = (pose.translation - rest.translation).isZero(0) && (pose.rotations - rest.rotations).isZero(0);
    const std::vector<Eigen::MatrixX3d> path =
        at_rest ? std::vector<Eigen::MatrixX3d>{body::pose_body(model, shaped, rest).vertices}
                : pose_path(model, shaped, rest, pose, 11);
    // Garment g's faces follow those of the garments before it (concatenate's order); its
    // waistband's faces are of materials[n + g], its fabric stiffened.
    require(options.is_valid(&why), "dress_and_drape_outfit: ", why);
    std::vector<cloth::Material> fabrics;
    std::vector<int> face_material;
    detail::outfit_fabrics(patterns, meshes, materials, options.waistband_width_cm,
                           options.waistband_stretching_factor, fabrics, face_material);
    Eigen::MatrixX3d X;
    const DrapeSummary s = drape_garment(all, X0, path, model.faces, fabrics, face_material, options, X);
    out_positions.clear();
    for (size_t g = 0; g < meshes.size(); ++g) out_positions.push_back(X.middleRows(first[g], first[g + 1] - first[g]));
    return s;
}

}  // namespace drape::garment
