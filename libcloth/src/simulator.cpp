#include <drape/cloth/simulator.hpp>

#include <drape/cloth/contact.hpp>
#include <drape/cloth/energies.hpp>
#include <drape/cloth/intersections.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/parallel_for.hpp>

#include "self_contact.hpp"
#include "sparse_solver.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <map>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

namespace drape::cloth {

namespace {

using Clock = std::chrono::steady_clock;
// Self-contact candidates are collected this many thicknesses beyond the radius a Newton
// iteration needs, so that they can be reused while the cloth moves less than half of it.
constexpr double kCandidateMargin = 1.0;
// A vertex's second contact plane of a step is made only for a surface facing the first
// one: normals more than 90 degrees apart (a pinch), not a neighbouring patch of one surface.
constexpr double kFacingPlanesCos = 0.0;
// How far a vertex that was near the obstacle at the previous contact update is searched
// for when it is no longer within the query radius (update_obstacle_contacts): deeper than
// the half-thickness of most body parts, so a vertex pushed that far in is still found.
constexpr double kLostContactRadius = 0.15;
double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

const char* to_string(StepTermination t) {
    switch (t) {
        case StepTermination::converged: return "converged";
        case StepTermination::max_iterations: return "max_iterations";
        case StepTermination::line_search_failed: return "line_search_failed";
        case StepTermination::non_finite: return "non_finite";
        case StepTermination::cancelled: return "cancelled";
    }
    return "unknown";
}

// Union-find over vertex ids (pieces of a mesh, stitched vertex groups).
struct DisjointSets {
    std::vector<int> parent;
    explicit DisjointSets(int n) : parent(static_cast<std::size_t>(n)) {
        for (int i = 0; i < n; ++i) parent[static_cast<std::size_t>(i)] = i;
    }
    int find(int i) {
        while (parent[static_cast<std::size_t>(i)] != i)
            i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
        return i;
    }
    /// Joins the sets of a and b; the smaller root id represents both.
    void join(int a, int b) {
        a = find(a);
        b = find(b);
        if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
};

// A body-contact record of one free vertex for the current Newton iteration.
struct VertexContact {
    int vertex = -1;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double distance = std::numeric_limits<double>::infinity();  // signed, at query time
    double stiffness = 0;
};

// Friction data of one vertex, lagged over a whole time step (taken at its start), so that
// the incremental potential is a fixed function during the step's Newton iterations.
struct FrictionContact {
    int vertex = -1;
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double normal_force = 0;  // λ
};

// Lagged friction between two cloth layers: a self-contact pair's frame and penalty force
// at the start of the step.
struct PairFriction {
    internal::PairFrame frame;
    double normal_force = 0;  // λ
};

}  // namespace

bool SimulatorOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& reason) {
        if (why) *why = reason;
        return false;
    };
    auto nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
    if (!(std::isfinite(time_step_s) && time_step_s > 0))
        return fail(detail::concat("time_step_s = ", time_step_s, " must be > 0"));
    if (!gravity_m_per_s2.allFinite()) return fail("gravity_m_per_s2 is not finite");
    if (!(std::isfinite(relative_tolerance) && relative_tolerance > 0))
        return fail(detail::concat("relative_tolerance = ", relative_tolerance, " must be > 0"));
    if (!(std::isfinite(step_relative_tolerance) && step_relative_tolerance > 0))
        return fail(detail::concat("step_relative_tolerance = ", step_relative_tolerance, " must be > 0"));
    if (!(std::isfinite(step_displacement_tolerance_m) && step_displacement_tolerance_m >= 0))
        return fail(detail::concat("step_displacement_tolerance_m = ", step_displacement_tolerance_m,
                                   " must be >= 0"));
    if (max_nonconvex_step_iterations < 0)
        return fail(detail::concat("max_nonconvex_step_iterations = ", max_nonconvex_step_iterations,
                                   " must be >= 0"));
    if (max_newton_iterations < 1)
        return fail(detail::concat("max_newton_iterations = ", max_newton_iterations, " must be >= 1"));
    if (max_step_halvings < 0 || max_step_halvings > 20)
        return fail(detail::concat("max_step_halvings = ", max_step_halvings, " must be in [0, 20]"));
    if (max_line_search_halvings < 0)
        return fail(detail::concat("max_line_search_halvings = ", max_line_search_halvings,
                                   " must be >= 0"));
    if (!(std::isfinite(static_damping_time_s) && static_damping_time_s > 0))
        return fail(detail::concat("static_damping_time_s = ", static_damping_time_s, " must be > 0"));
    if (!(std::isfinite(contact_thickness_m) && contact_thickness_m > 0))
        return fail(detail::concat("contact_thickness_m = ", contact_thickness_m, " must be > 0"));
    if (!(std::isfinite(contact_inside_stiffness_factor) && contact_inside_stiffness_factor >= 1))
        return fail(detail::concat("contact_inside_stiffness_factor = ", contact_inside_stiffness_factor,
                                   " must be >= 1"));
    if (!(std::isfinite(contact_stiffness_n_per_m3) && contact_stiffness_n_per_m3 > 0))
        return fail(detail::concat("contact_stiffness_n_per_m3 = ", contact_stiffness_n_per_m3,
                                   " must be > 0"));
    if (!nonneg(obstacle_friction))
        return fail(detail::concat("obstacle_friction = ", obstacle_friction, " must be >= 0"));
    if (!nonneg(cloth_friction))
        return fail(detail::concat("cloth_friction = ", cloth_friction, " must be >= 0"));
    if (!(std::isfinite(friction_slip_speed_m_per_s) && friction_slip_speed_m_per_s > 0))
        return fail(detail::concat("friction_slip_speed_m_per_s = ", friction_slip_speed_m_per_s,
                                   " must be > 0"));
    if (!(std::isfinite(stitch_stiffness_n_per_m2) && stitch_stiffness_n_per_m2 > 0))
        return fail(detail::concat("stitch_stiffness_n_per_m2 = ", stitch_stiffness_n_per_m2,
                                   " must be > 0"));
    if (!(std::isfinite(seam_closing_speed_m_per_s) && seam_closing_speed_m_per_s > 0))
        return fail(detail::concat("seam_closing_speed_m_per_s = ", seam_closing_speed_m_per_s,
                                   " must be > 0"));
    if (!nonneg(air_drag_n_s_per_m3))
        return fail(detail::concat("air_drag_n_s_per_m3 = ", air_drag_n_s_per_m3, " must be >= 0"));
    if (!wind_m_per_s.allFinite()) return fail("wind_m_per_s is not finite");
    return true;
}

std::string StepSummary::brief_report() const {
    std::ostringstream os;
    os << to_string(termination) << ": " << newton_iterations << " Newton iterations, |g|inf "
       << gradient_inf_norm_n << " N (tol " << tolerance_n << "), E " << energy_j << " J, "
       << contacts << " contacts, " << self_contact_pairs << " self-contact pairs, stitch gap "
       << max_stitch_gap_m * 1e3 << " mm, " << seconds_total * 1e3 << " ms (assembly "
       << seconds_assembly * 1e3 << ", solve " << seconds_solve * 1e3 << ", contact "
       << seconds_contact * 1e3 << ")";
    os << ", " << factorisations << " factorisations (" << regularised_factorisations << " regularised)";
    if (substeps > 1) os << ", " << substeps << " substeps";
    if (!message.empty()) os << "; " << message;
    return os.str();
}

struct Simulator::Impl {
    ClothMesh mesh;
    std::vector<Material> materials;  // >= 1
    std::vector<int> face_material;   // per face, index into materials
    SimulatorOptions options;
    Eigen::MatrixX3d x, v;
    Eigen::VectorXd mass;
    Eigen::VectorXd area;  // rest area per vertex (Σ A/3)
    std::vector<bool> pinned;
    std::vector<TriangleRest> triangles;
    std::vector<Hinge> hinges;
    std::vector<HingeRest> hinge_rests;
    std::vector<StretchingStiffness> k_stretch;  // frozen for the current Newton iteration
    std::vector<StretchingStiffness> k_lagged;   // what the last time step used (refresh_stiffness)
    std::vector<BendingCurve> bend_curves;       // per hinge, fixed: bending is conservative

    std::optional<Obstacle> obstacle;
    std::vector<Stitch> stitches;
    std::vector<double> stitch_rest;  // current rest length per stitch
    internal::SelfContact self_contact{Eigen::MatrixX3i(0, 3), 0};

    // Free-dof numbering: dof_index[3 i + c] = column in the reduced system or -1 (pinned).
    std::vector<int> dof_index;
    int free_dofs = 0;
    internal::SparseSpdSolver solver;
    // Fixed pattern of the free-dof Hessian (elements, stitches, vertex blocks) with, for
    // every element entry (column-major in its dense block), the index into the value array
    // or -1 if a pinned dof is involved. Rebuilt when pins or stitches change.
    Eigen::SparseMatrix<double> pattern;
    std::vector<int> face_slots, hinge_slots, stitch_slots, vertex_slots, diagonal_slots;
    bool pattern_ready = false;
    // Extra 3x3 blocks between vertex pairs (a < b) for self-contact, kept across iterations
    // so that the symbolic factorisation can be reused while no new pair appears.
    std::set<std::pair<int, int>> contact_blocks;
    Eigen::SparseMatrix<double> contact_pattern;  // free-dof, zeros at contact_blocks
    bool analysed_with_contacts = false;

    // Per-iteration state.
    std::vector<VertexContact> contacts;  // one per free vertex
    std::vector<FrictionContact> friction;  // lagged over the step
    std::vector<PairFriction> pair_friction;  // cloth–cloth, lagged over the step
    // Contact planes, made when a vertex first comes within the thickness during a step (at
    // its closest surface point) and kept until the step ends, so that the step's
    // incremental potential changes only when a plane is added (Newton then converges
    // quadratically; the exact distance with its Gauss-Newton Hessian converged linearly).
    // The static solve renews them every few iterations as the cloth slides.
    // A vertex squeezed between two surfaces that face each other (the armpit, between arm
    // and torso) gets a second plane when, during the step, its closest point moves to the
    // other surface: with one plane per step it was pushed out of one surface into the
    // other, and out of that one at the next step, a period-2 chatter that never came to
    // rest (docs/cloth.md).
    std::vector<std::array<int, 2>> plane_of_vertex;  // -1: none
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> planes;  // (point, normal)
    double query_radius = 0;
    Eigen::MatrixX3d step_start;          // x at the start of the step (friction, drag)
    double step_dt = 0;                   // 0 in the static solve (no drag)
    // The static solve's friction: displacements are measured from the state it starts at
    // and the slip distance ε is that of the damping time (stiction around that state).
    bool static_friction = false;
    HessianMode hessian_mode = HessianMode::gauss_newton;  // of the elastic terms, this iteration

    // Element buffers (filled in parallel, scattered serially for determinism).
    std::vector<double> face_energy, hinge_energy;
    std::vector<Vector9d> face_grad;
    std::vector<Matrix9d> face_hess;
    std::vector<Vector12d> hinge_grad;
    std::vector<Matrix12d> hinge_hess;

    Impl() = default;
    // Copies carry the state, not the factorisation (used by the const forces()).
    Impl(const Impl& o)
        : mesh(o.mesh), materials(o.materials), face_material(o.face_material), options(o.options),
          x(o.x), v(o.v), mass(o.mass), area(o.area), pinned(o.pinned), triangles(o.triangles), hinges(o.hinges),
          hinge_rests(o.hinge_rests), k_stretch(o.k_stretch), bend_curves(o.bend_curves),
          obstacle(o.obstacle), stitches(o.stitches), stitch_rest(o.stitch_rest),
          self_contact(o.self_contact), dof_index(o.dof_index), free_dofs(o.free_dofs) {}

    void renumber() {
        solver.reset();
        pattern_ready = false;
        analysed_with_contacts = false;
        contact_blocks.clear();
        dof_index.assign(static_cast<std::size_t>(3 * x.rows()), -1);
        free_dofs = 0;
        for (Eigen::Index i = 0; i < x.rows(); ++i)
            if (!pinned[static_cast<std::size_t>(i)])
                for (int c = 0; c < 3; ++c) dof_index[static_cast<std::size_t>(3 * i + c)] = free_dofs++;
    }
    const Material& material_of(int face) const {
        return materials[static_cast<std::size_t>(face_material[static_cast<std::size_t>(face)])];
    }
    int dof(int vertex, int c) const { return dof_index[static_cast<std::size_t>(3 * vertex + c)]; }

    Eigen::Matrix3d face_positions(const Eigen::MatrixX3d& p, int f) const {
        Eigen::Matrix3d xf;
        for (int c = 0; c < 3; ++c) xf.col(c) = p.row(mesh.faces(f, c)).transpose();
        return xf;
    }
    Eigen::Matrix<double, 3, 4> hinge_positions(const Eigen::MatrixX3d& p, const Hinge& h) const {
        Eigen::Matrix<double, 3, 4> xh;
        for (int c = 0; c < 4; ++c) xh.col(c) = p.row(h.v[static_cast<std::size_t>(c)]).transpose();
        return xh;
    }

    // Looks the stretching table up at the strain of `p` (ArcSim also evaluates k at the
    // current state and treats it as constant when differentiating). Bending needs no
    // refresh: its curvature dependence is integrated into the energy (BendingCurve).
    //
    // Time steps (`relax`) use the mean of the table's stiffness at the step's start and the
    // stiffness the previous step used: an under-relaxed fixed point. Frozen afresh at each
    // step's start, the stiffness of a face whose strain sits where the table changes fast
    // (its principal direction flipping between two 22.5° samples near isotropic strain)
    // made a period-2 cycle across steps — strain A gave the stiffness that led to B and B
    // the one that led back to A — with every step's Newton fully converged: a t-shirt's
    // underarm vertex alternated 1.7 mm for 400 steps and kept the garment from rest.
    void refresh_stiffness(const Eigen::MatrixX3d& p, bool relax = false) {
        k_stretch.resize(triangles.size());
        core::parallel_for(mesh.face_count(), [&](int f) {
            k_stretch[static_cast<std::size_t>(f)] = stretching_stiffness(
                material_of(f), green_strain(face_positions(p, f), triangles[static_cast<std::size_t>(f)]));
        });
        if (!relax) return;
        if (k_lagged.size() == k_stretch.size())
            for (std::size_t f = 0; f < k_stretch.size(); ++f) {
                StretchingStiffness& k = k_stretch[f];
                const StretchingStiffness& o = k_lagged[f];
                k.k_uu = 0.5 * (k.k_uu + o.k_uu);
                k.k_uv = 0.5 * (k.k_uv + o.k_uv);
                k.k_vv = 0.5 * (k.k_vv + o.k_vv);
                k.k_shear = 0.5 * (k.k_shear + o.k_shear);
            }
        k_lagged = k_stretch;
    }

    // ---- sparsity pattern -------------------------------------------------------------
    static int slot_in(const Eigen::SparseMatrix<double>& m, int r, int c) {
        const int* inner = m.innerIndexPtr();
        const int* begin = inner + m.outerIndexPtr()[c];
        const int* end = inner + m.outerIndexPtr()[c + 1];
        const int* it = std::lower_bound(begin, end, r);
        return (it != end && *it == r) ? static_cast<int>(it - inner) : -1;
    }

    void add_block_entries(std::vector<Eigen::Triplet<double>>& entries, const int* verts, int n) const {
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b)
                for (int ca = 0; ca < 3; ++ca)
                    for (int cb = 0; cb < 3; ++cb) {
                        const int r = dof(verts[a], ca), c = dof(verts[b], cb);
                        if (r >= 0 && c >= 0) entries.emplace_back(r, c, 0.0);
                    }
    }

    void fill_slots(const int* verts, int n, int* out) const {
        for (int b = 0; b < n; ++b)
            for (int cb = 0; cb < 3; ++cb)
                for (int a = 0; a < n; ++a)
                    for (int ca = 0; ca < 3; ++ca) {
                        const int r = dof(verts[a], ca), c = dof(verts[b], cb);
                        out[(3 * b + cb) * 3 * n + 3 * a + ca] = (r >= 0 && c >= 0) ? slot_in(pattern, r, c) : -1;
                    }
    }

    void build_pattern() {
        std::vector<Eigen::Triplet<double>> entries;
        for (int f = 0; f < mesh.face_count(); ++f) {
            const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
            add_block_entries(entries, verts, 3);
        }
        for (const Hinge& h : hinges) add_block_entries(entries, h.v.data(), 4);
        for (const Stitch& st : stitches) {
            const int verts[2] = {st.a, st.b};
            add_block_entries(entries, verts, 2);
        }
        for (int i = 0; i < mesh.vertex_count(); ++i) add_block_entries(entries, &i, 1);
        pattern.resize(free_dofs, free_dofs);
        pattern.setFromTriplets(entries.begin(), entries.end());
        pattern.makeCompressed();
        face_slots.assign(static_cast<std::size_t>(81 * mesh.face_count()), -1);
        core::parallel_for(mesh.face_count(), [&](int f) {
            const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
            fill_slots(verts, 3, face_slots.data() + 81 * f);
        });
        hinge_slots.assign(144 * hinges.size(), -1);
        core::parallel_for(static_cast<int>(hinges.size()), [&](int h) {
            fill_slots(hinges[static_cast<std::size_t>(h)].v.data(), 4,
                       hinge_slots.data() + 144 * h);
        });
        stitch_slots.assign(36 * stitches.size(), -1);
        for (std::size_t k = 0; k < stitches.size(); ++k) {
            const int verts[2] = {stitches[k].a, stitches[k].b};
            fill_slots(verts, 2, stitch_slots.data() + 36 * k);
        }
        vertex_slots.assign(static_cast<std::size_t>(9 * mesh.vertex_count()), -1);
        for (int i = 0; i < mesh.vertex_count(); ++i) fill_slots(&i, 1, vertex_slots.data() + 9 * i);
        diagonal_slots.resize(static_cast<std::size_t>(free_dofs));
        for (int d = 0; d < free_dofs; ++d) diagonal_slots[static_cast<std::size_t>(d)] = slot_in(pattern, d, d);
        contact_pattern.resize(free_dofs, free_dofs);
        contact_pattern.setZero();
        contact_blocks.clear();
        analysed_with_contacts = false;
        solver.reset();
        pattern_ready = true;
    }

    // Adds the blocks the current self-contact pairs need; true if the set grew.
    bool update_contact_blocks(const std::vector<internal::PairHessian>& pairs) {
        bool grew = false;
        for (const internal::PairHessian& ph : pairs)
            for (int a = 0; a < 4; ++a)
                for (int b = a + 1; b < 4; ++b) {
                    int va = ph.pair.v[static_cast<std::size_t>(a)], vb = ph.pair.v[static_cast<std::size_t>(b)];
                    if (va == vb || pinned[static_cast<std::size_t>(va)] || pinned[static_cast<std::size_t>(vb)]) continue;
                    if (va > vb) std::swap(va, vb);
                    grew |= contact_blocks.emplace(va, vb).second;
                }
        if (grew) {
            std::vector<Eigen::Triplet<double>> entries;
            for (const auto& [a, b] : contact_blocks) {
                const int verts[2] = {a, b};
                add_block_entries(entries, verts, 2);
            }
            contact_pattern.resize(free_dofs, free_dofs);
            contact_pattern.setFromTriplets(entries.begin(), entries.end());
            contact_pattern.makeCompressed();
        }
        return grew;
    }

    // ---- contact queries -------------------------------------------------------------
    // Refreshes, for every free vertex, the closest obstacle point within the query radius
    // and the lagged friction force.
    //
    // A vertex that was within the query radius at the previous update (or whose previous
    // distance is unknown: the first update of this simulator, or a changed vertex count) and
    // is not found within it now is searched again out to kLostContactRadius: it may have
    // been pushed deeper into the obstacle than the query radius (a stiff fabric pressed
    // against the body harder than the penalty holds), and without a contact it would stay
    // inside for good, with no force pushing it out.
    void update_obstacle_contacts(const Eigen::MatrixX3d& p) {
        if (!obstacle) {
            contacts.clear();
            return;
        }
        const double h = options.contact_thickness_m;
        query_radius = h + std::max(2 * h, 0.01);
        // Each vertex's entry still holds its previous distance until it is overwritten.
        const bool known = contacts.size() == static_cast<std::size_t>(p.rows());
        if (!known) contacts.assign(static_cast<std::size_t>(p.rows()), VertexContact{});
        core::parallel_for(static_cast<int>(p.rows()), [&](int i) {
            VertexContact& c = contacts[static_cast<std::size_t>(i)];
            const double previous = known ? c.distance : -std::numeric_limits<double>::infinity();
            c = VertexContact{};
            c.vertex = i;
            if (pinned[static_cast<std::size_t>(i)]) return;
            ObstacleQuery q = obstacle->closest(p.row(i).transpose(), query_radius);
            if (!q.found && previous < query_radius)
                q = obstacle->closest(p.row(i).transpose(), kLostContactRadius);
            if (!q.found) return;
            c.point = q.point;
            c.normal = q.normal;
            c.distance = q.signed_distance_m;
            // Contact plane: through the closest point, along the direction to the vertex
            // when it is well defined (so the plane is the true distance's tangent plane).
            const Eigen::Vector3d d = p.row(i).transpose() - q.point;
            if (d.norm() > 1e-9) c.normal = (q.signed_distance_m < 0 ? -d : d).normalized();
            c.stiffness = options.contact_stiffness_n_per_m3 * area(i);
        }, 64);
        {
            plane_of_vertex.resize(static_cast<std::size_t>(p.rows()), {-1, -1});
            for (const VertexContact& c : contacts) {
                if (c.vertex < 0 || c.stiffness <= 0 || c.distance >= h) continue;
                std::array<int, 2>& own = plane_of_vertex[static_cast<std::size_t>(c.vertex)];
                const bool add = own[0] < 0 ||
                                 (own[1] < 0 && planes[static_cast<std::size_t>(own[0])].second.dot(c.normal) <
                                                    kFacingPlanesCos);
                if (!add) continue;
                own[own[0] < 0 ? 0 : 1] = static_cast<int>(planes.size());
                planes.emplace_back(c.point, c.normal);
            }
        }
    }

    // The lagged friction of a time step, from the contacts queried at its start: vertices
    // within the thickness, with their contact normal and penalty force there. A vertex
    // behind the surface counts the force it would have on the surface (k h): the penalty's
    // growth with depth is a correction, not a pressure, and friction from it held a
    // vertex that a stiff skirt had pushed 27 mm into a thigh where it was (a tangential
    // pull of 18 N could not move it).
    void lag_friction() {
        friction.clear();
        if (!friction_active() || !obstacle || options.obstacle_friction <= 0) return;
        const double h = options.contact_thickness_m;
        for (const VertexContact& c : contacts)
            if (c.vertex >= 0 && c.stiffness > 0 && c.distance < h)
                friction.push_back({c.vertex, c.normal, c.stiffness * (h - std::max(c.distance, 0.0))});
    }

    // Drops the lagged friction of vertices no longer within the contact thickness.
    void drop_released_friction() {
        if (friction.empty() || contacts.empty()) return;
        const double h = options.contact_thickness_m;
        std::size_t w = 0;
        for (std::size_t k = 0; k < friction.size(); ++k) {
            const VertexContact& c = contacts[static_cast<std::size_t>(friction[k].vertex)];
            if (c.stiffness > 0 && c.distance < h) friction[w++] = friction[k];
        }
        friction.resize(w);
    }

    // Largest step fraction for which no free vertex can pass through the obstacle: a point
    // at distance d from the surface cannot cross it by moving less than d, and a vertex that
    // ends up to `allowed_depth_m` inside is still on the near side of any part of the body
    // thicker than twice that, so the penalty (with its signed distance) pushes it back out.
    // Vertices already inside are not limited.
    double obstacle_step_bound(const Eigen::MatrixX3d& dx) const {
        if (contacts.empty()) return 1.0;
        const double allowed_depth_m = options.contact_thickness_m;
        double alpha = 1.0;
        for (const VertexContact& c : contacts) {
            if (c.vertex < 0 || pinned[static_cast<std::size_t>(c.vertex)]) continue;
            const double move = dx.row(c.vertex).norm();
            if (move <= 0) continue;
            const double free_distance = std::isfinite(c.distance) ? c.distance : query_radius;
            if (free_distance <= 0) continue;
            alpha = std::min(alpha, (0.9 * free_distance + allowed_depth_m) / move);
        }
        return alpha;
    }

    // The lagged cloth–cloth friction of a time step: self-contact pairs within the thickness
    // at its start, with their frames and penalty forces λ = k (h − d).
    void lag_pair_friction(const Eigen::MatrixX3d& p) {
        pair_friction.clear();
        if (!friction_active() || !options.self_contact || options.cloth_friction <= 0) return;
        const double h = options.contact_thickness_m, k = self_contact_stiffness();
        for (const internal::PairFrame& f : self_contact.contact_frames(p, h))
            pair_friction.push_back({f, k * (h - f.distance_m)});
    }

    bool friction_active() const { return step_dt > 0 || static_friction; }
    double friction_epsilon() const {
        return options.friction_slip_speed_m_per_s * (step_dt > 0 ? step_dt : options.static_damping_time_s);
    }

    // ---- energy ------------------------------------------------------------------------
    // Total energy of the frozen model at `p`; optionally the full gradient (3V) and, added
    // into `values` (the value array of `pattern`) and `pair_hessians`, the Hessian.
    double potential(const Eigen::MatrixX3d& p, Eigen::VectorXd* gradient, double* values,
                     std::vector<internal::PairHessian>* pair_hessians = nullptr) {
        const bool want_g = gradient != nullptr, want_h = values != nullptr;
        const int nf = mesh.face_count();
        const int nh = static_cast<int>(hinges.size());
        face_energy.resize(static_cast<std::size_t>(nf));
        hinge_energy.resize(static_cast<std::size_t>(nh));
        if (want_g) {
            face_grad.resize(static_cast<std::size_t>(nf));
            hinge_grad.resize(static_cast<std::size_t>(nh));
        }
        if (want_h) {
            face_hess.resize(static_cast<std::size_t>(nf));
            hinge_hess.resize(static_cast<std::size_t>(nh));
        }
        core::parallel_for(nf, [&](int f) {
            const auto fs = static_cast<std::size_t>(f);
            face_energy[fs] = stretching_energy(face_positions(p, f), triangles[fs], k_stretch[fs],
                                                want_g ? &face_grad[fs] : nullptr,
                                                want_h ? &face_hess[fs] : nullptr,
                                                hessian_mode);
        }, 128);
        // Bending's exact Hessian needs the dihedral angle's second derivatives (forward-mode
        // numbers, ~4x the cost); its Gauss-Newton matrix is exact up to (θ−θ̄)∇²θ, small for
        // cloth, so time steps use it while stretching (whose compressed elements are what
        // make the projected Newton converge only linearly) stays exact.
        const HessianMode bending_mode =
            hessian_mode == HessianMode::exact ? HessianMode::gauss_newton : hessian_mode;
        core::parallel_for(nh, [&](int h) {
            const auto hs = static_cast<std::size_t>(h);
            hinge_energy[hs] = bending_energy(hinge_positions(p, hinges[hs]), hinge_rests[hs],
                                              bend_curves[hs], want_g ? &hinge_grad[hs] : nullptr,
                                              want_h ? &hinge_hess[hs] : nullptr, bending_mode);
        }, 128);

        double e = 0;
        if (gradient) gradient->setZero(3 * p.rows());
        auto scatter = [&](const int* verts, int n, const double* g, const double* hm, const int* slots) {
            if (want_g)
                for (int a = 0; a < n; ++a)
                    for (int ca = 0; ca < 3; ++ca) (*gradient)(3 * verts[a] + ca) += g[3 * a + ca];
            if (want_h)
                for (int k = 0; k < 9 * n * n; ++k)
                    if (slots[k] >= 0) values[slots[k]] += hm[k];
        };
        for (int f = 0; f < nf; ++f) {
            const auto fs = static_cast<std::size_t>(f);
            e += face_energy[fs];
            if (want_g || want_h) {
                const int verts[3] = {mesh.faces(f, 0), mesh.faces(f, 1), mesh.faces(f, 2)};
                scatter(verts, 3, want_g ? face_grad[fs].data() : nullptr,
                        want_h ? face_hess[fs].data() : nullptr,
                        want_h ? face_slots.data() + 81 * f : nullptr);
            }
        }
        for (int h = 0; h < nh; ++h) {
            const auto hs = static_cast<std::size_t>(h);
            e += hinge_energy[hs];
            if (want_g || want_h)
                scatter(hinges[hs].v.data(), 4, want_g ? hinge_grad[hs].data() : nullptr,
                        want_h ? hinge_hess[hs].data() : nullptr,
                        want_h ? hinge_slots.data() + 144 * h : nullptr);
        }
        // Gravity.
        for (Eigen::Index i = 0; i < p.rows(); ++i) {
            e -= mass(i) * options.gravity_m_per_s2.dot(p.row(i).transpose());
            if (want_g) gradient->segment<3>(3 * i) -= mass(i) * options.gravity_m_per_s2;
        }
        // Stitches.
        Vector6d g6;
        Matrix6d h6;
        for (std::size_t k = 0; k < stitches.size(); ++k) {
            const Stitch& st = stitches[k];
            const double ks = options.stitch_stiffness_n_per_m2 * st.length_m;
            e += stitch_energy(p.row(st.a).transpose(), p.row(st.b).transpose(), stitch_rest[k], ks,
                               want_g ? &g6 : nullptr, want_h ? &h6 : nullptr);
            const int verts[2] = {st.a, st.b};
            if (want_g || want_h)
                scatter(verts, 2, want_g ? g6.data() : nullptr, want_h ? h6.data() : nullptr,
                        want_h ? stitch_slots.data() + 36 * k : nullptr);
        }
        // Obstacle contact: ½ k (h − n·(x − c))² against each contact plane (see planes).
        Eigen::Vector3d g3, gf;
        Eigen::Matrix3d h3, hf;
        const double eps = friction_epsilon();
        if (obstacle) {
            // The contact planes of this step or static solve (exact quadratic energies).
            for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(plane_of_vertex.size()); ++i) {
                for (const int plane : plane_of_vertex[static_cast<std::size_t>(i)]) {
                    if (plane < 0) continue;
                    const int vi = static_cast<int>(i);
                    const auto& [point, normal] = planes[static_cast<std::size_t>(plane)];
                    const double ei = plane_contact_energy(p.row(i).transpose(), point, normal,
                                                           options.contact_thickness_m,
                                                           options.contact_stiffness_n_per_m3 * area(i),
                                                           want_g ? &g3 : nullptr, want_h ? &h3 : nullptr,
                                                           options.contact_inside_stiffness_factor);
                    if (ei <= 0) continue;
                    e += ei;
                    scatter(&vi, 1, want_g ? g3.data() : nullptr, want_h ? h3.data() : nullptr,
                            want_h ? vertex_slots.data() + 9 * i : nullptr);
                }
            }
        }
        if (friction_active())
            for (const FrictionContact& c : friction) {
                const int i = c.vertex;
                e += friction_energy((p.row(i) - step_start.row(i)).transpose(), c.normal, c.normal_force,
                                     options.obstacle_friction, eps, want_g ? &gf : nullptr,
                                     want_h ? &hf : nullptr);
                if (want_g || want_h)
                    scatter(&i, 1, want_g ? gf.data() : nullptr, want_h ? hf.data() : nullptr,
                            want_h ? vertex_slots.data() + 9 * i : nullptr);
            }
        // Self-contact.
        if (options.self_contact && !self_contact.candidates().empty()) {
            internal::SelfContactParams params{options.contact_thickness_m, self_contact_stiffness()};
            e += self_contact.energy(p, params, gradient, want_h ? pair_hessians : nullptr);
        }
        // Cloth–cloth friction: μ λ f₀ of the closest points' relative slip u = Σ w_c Δx_c
        // (frame lagged); gradient w_c ∇f₀, Hessian (w wᵀ) ⊗ ∇²f₀ (PSD).
        if (friction_active())
            for (const PairFriction& pf : pair_friction) {
                const auto& v = pf.frame.pair.v;
                const Eigen::Vector4d& w = pf.frame.weights;
                Eigen::Vector3d u = Eigen::Vector3d::Zero();
                for (int c = 0; c < 4; ++c) u += w(c) * (p.row(v[static_cast<std::size_t>(c)]) - step_start.row(v[static_cast<std::size_t>(c)])).transpose();
                e += friction_energy(u, pf.frame.normal, pf.normal_force, options.cloth_friction, eps,
                                     want_g ? &gf : nullptr, want_h ? &hf : nullptr);
                if (want_g)
                    for (int c = 0; c < 4; ++c) gradient->segment<3>(3 * v[static_cast<std::size_t>(c)]) += w(c) * gf;
                if (want_h && pair_hessians) {
                    internal::PairHessian ph;
                    ph.pair = pf.frame.pair;
                    for (int a = 0; a < 4; ++a)
                        for (int b = 0; b < 4; ++b) ph.hessian.block<3, 3>(3 * a, 3 * b) = w(a) * w(b) * hf;
                    pair_hessians->push_back(ph);
                }
            }
        // Air drag: c A/(2Δt) |x − x₀ − Δt w|², whose gradient is c A (v − w).
        if (step_dt > 0 && options.air_drag_n_s_per_m3 > 0) {
            for (Eigen::Index i = 0; i < p.rows(); ++i) {
                const double c = options.air_drag_n_s_per_m3 * area(i) / step_dt;
                const Eigen::Vector3d d = (p.row(i) - step_start.row(i)).transpose() - step_dt * options.wind_m_per_s;
                e += 0.5 * c * d.squaredNorm();
                if (want_g) gradient->segment<3>(3 * i) += c * d;
                if (want_h)
                    for (int k = 0; k < 3; ++k) {
                        const int s = vertex_slots[static_cast<std::size_t>(9 * i + 4 * k)];
                        if (s >= 0) values[s] += c;
                    }
            }
        }
        return e;
    }

    // Self-contact stiffness per pair: the contact pressure stiffness times a typical vertex
    // area (pairs do not have an area of their own).
    double self_contact_stiffness() const {
        return options.contact_stiffness_n_per_m3 * (area.size() ? area.mean() : 0.0);
    }

    // Pairs closer than 2h in the pattern are neighbours within one layer (see
    // SelfContact::set_rest_filter). Per pattern point (a face corner's rest position; a
    // welded seam vertex has one per panel) its vertex; pieces: connected components of the
    // pattern faces, i.e. the panels.
    void set_rest_filter() {
        const int np = static_cast<int>(mesh.pattern.rows());
        std::vector<int> point_vertex(static_cast<std::size_t>(np), -1);
        DisjointSets pieces(np);
        for (int f = 0; f < mesh.face_count(); ++f)
            for (int c = 0; c < 3; ++c) {
                point_vertex[static_cast<std::size_t>(mesh.pattern_faces(f, c))] = mesh.faces(f, c);
                pieces.join(mesh.pattern_faces(f, c), mesh.pattern_faces(f, (c + 1) % 3));
            }
        // Points no face uses take vertex 0 on a piece of their own (never near anything).
        std::vector<int> piece(static_cast<std::size_t>(np));
        for (int i = 0; i < np; ++i) {
            piece[static_cast<std::size_t>(i)] = pieces.find(i);
            if (point_vertex[static_cast<std::size_t>(i)] < 0) point_vertex[static_cast<std::size_t>(i)] = 0;
        }
        self_contact.set_rest_filter(mesh.pattern, point_vertex, mesh.pattern_faces, piece,
                                     2 * options.contact_thickness_m);
    }

    double max_stitch_gap(const Eigen::MatrixX3d& p) const {
        double gap = 0;
        for (const Stitch& st : stitches) gap = std::max(gap, (p.row(st.a) - p.row(st.b)).norm());
        return gap;
    }

    StepSummary backward_euler(double h, int halvings_left);
    StepSummary minimise(Eigen::MatrixX3d& p, const Eigen::MatrixX3d& target, double inertia_weight,
                         double relative_tolerance);
};

// Newton on E(p) = inertia_weight/2 Σ m_i |p_i − target_i|² + potential(p).
// inertia_weight = 1/h² for backward Euler, 0 for the static solve.
StepSummary Simulator::Impl::minimise(Eigen::MatrixX3d& p, const Eigen::MatrixX3d& target,
                                      double inertia_weight, double relative_tolerance) {
    const auto t_start = Clock::now();
    StepSummary s;
    const double weight = mass.maxCoeff() * options.gravity_m_per_s2.norm();
    s.tolerance_n = weight > 0 ? relative_tolerance * weight : 1e-12;
    const Eigen::MatrixX3d p_start = p;
    const double h = options.contact_thickness_m;
    const bool use_self = options.self_contact;
    std::vector<internal::PairHessian> pair_hessians;
    double last_move = 0;
    // The last iteration was a full, unregularised Newton step that moved no vertex farther
    // than step_displacement_tolerance_m: the step may end here (confirmed below).
    bool small_full_step = false;
    bool renew_next = false;
    // How far the cloth moves relative to itself (up to a common translation, which brings
    // no two of its points closer): what the self-contact candidates must cover.
    auto spread = [](const Eigen::MatrixX3d& d) {
        const std::vector<double> lengths = internal::translation_reduced_lengths(d);
        return lengths.empty() ? 0.0 : *std::max_element(lengths.begin(), lengths.end());
    };
    double last_spread = 0;
    const double v_spread = inertia_weight > 0 ? spread(v) : 0.0;

    auto total = [&](const Eigen::MatrixX3d& q, Eigen::VectorXd* g, double* values,
                     std::vector<internal::PairHessian>* ph) {
        double e = potential(q, g, values, ph);
        if (inertia_weight > 0) {
            const Eigen::MatrixX3d d = q - target;
            e += 0.5 * inertia_weight * (mass.transpose() * d.rowwise().squaredNorm()).value();
            if (g)
                for (Eigen::Index i = 0; i < q.rows(); ++i)
                    g->segment<3>(3 * i) += inertia_weight * mass(i) * d.row(i).transpose();
        }
        return e;
    };
    // Largest per-vertex move the inertia term alone would answer the gradient with.
    auto inertia_scaled_residual = [&](const Eigen::VectorXd& g, double w) {
        double r = 0;
        for (Eigen::Index i = 0; i < mass.size(); ++i) {
            if (!(mass(i) > 0)) continue;
            double n2 = 0;
            for (int c = 0; c < 3; ++c)
                if (dof(static_cast<int>(i), c) >= 0) n2 += g(3 * i + c) * g(3 * i + c);
            r = std::max(r, std::sqrt(n2) / (w * mass(i)));
        }
        return r;
    };
    auto free_inf_norm = [&](const Eigen::VectorXd& g) {
        double n = 0;
        for (std::size_t k = 0; k < dof_index.size(); ++k)
            if (dof_index[k] >= 0) n = std::max(n, std::abs(g(static_cast<Eigen::Index>(k))));
        return n;
    };

    if (!pattern_ready) build_pattern();
    Eigen::SparseMatrix<double> hessian = pattern;
    Eigen::VectorXd g;
    double shift = 0;  // Levenberg-style diagonal shift, × mass-like scale
    int nonconvex_iterations = 0;  // time-step iterations that needed a PSD fallback or shift
    const double mass_scale = mass.maxCoeff();
    for (int it = 0;; ++it) {
        auto t0 = Clock::now();
        // Dynamic steps look the stretching table up once, at the step's start (like ArcSim's
        // one linearised solve per step): with k frozen over the step the incremental
        // potential is one fixed function and Newton converges quadratically, where
        // re-freezing k every iteration can cycle between two strain states.
        // The static solve renews the stiffness and the contact planes every few iterations
        // (outer fixed-point iterations around Newton on a fixed energy).
        const bool renew = it == 0 || (inertia_weight == 0 && (it % 8 == 0 || renew_next));
        renew_next = false;
        if (renew) {
            refresh_stiffness(p, inertia_weight > 0 && options.relax_stretching_stiffness);
            planes.clear();
            plane_of_vertex.assign(static_cast<std::size_t>(p.rows()), {-1, -1});
        }
        auto tc = Clock::now();
        update_obstacle_contacts(p);
        // The obstacle friction is lagged at the step's start (contact normal and normal
        // force); a vertex that leaves the contact layer during the step loses its friction
        // at the next iteration. Kept, the friction of a contact that no longer exists
        // pumps energy into vertices at the edge of the layer: a period-2 chatter that
        // never came to rest (docs/cloth.md). Contacts made during the step get their
        // friction at the next step, as before.
        if (it == 0) {
            lag_friction();
        } else {
            drop_released_friction();
        }
        // Self-contact candidates within h + twice the expected motion of this iteration
        // (the last step's, or the velocity's over the step, both less any common
        // translation of the whole cloth): the energy ignores pairs
        // beyond h, and the step bound below shortens any step that could bring an
        // uncollected pair (farther than the radius now) within reach.
        // The candidates are reused while they still cover that radius at p (vertices moved
        // less than half the extra margin since they were collected).
        if (use_self) {
            double expected = last_spread;
            if (it == 0) expected = step_dt > 0 ? v_spread * step_dt : 0.0;
            const double needed = h + 2 * std::min(expected, 4 * h) + 1e-9;
            if (self_contact.covered_radius(p) < needed)
                self_contact.find_candidates(p, needed + kCandidateMargin * h);
        }
        if (it == 0) lag_pair_friction(p);
        const double contact_seconds = seconds_since(tc);
        s.seconds_contact += contact_seconds;
        if (small_full_step) {
            // Confirm before assembling and factoring again: the correction Newton would still
            // make is about |g_i| / (m_i / dt²) per vertex, a bound where the step's matrix is
            // the inertia plus a positive semi-definite part. Where Newton is in its quadratic
            // regime this is far below the step just taken; where the energy is much stiffer
            // than the step's model (smoothed friction sticking at the step's start) it is
            // not, and Newton goes on.
            const auto t_check = Clock::now();
            Eigen::VectorXd g_now;
            const double e_now = total(p, &g_now, nullptr, nullptr);
            const bool done = std::isfinite(e_now) && g_now.allFinite() &&
                              inertia_scaled_residual(g_now, inertia_weight) <= options.step_displacement_tolerance_m;
            s.seconds_assembly += seconds_since(t_check);
            if (done) {
                s.energy_j = e_now;
                s.gradient_inf_norm_n = free_inf_norm(g_now);
                s.newton_iterations = it;
                s.termination = StepTermination::converged;
                break;
            }
            small_full_step = false;
        }
        hessian_mode = inertia_weight > 0 ? options.step_hessian : options.static_hessian;
        std::fill(hessian.valuePtr(), hessian.valuePtr() + hessian.nonZeros(), 0.0);
        pair_hessians.clear();
        const double e = total(p, &g, hessian.valuePtr(), &pair_hessians);
        s.seconds_assembly += seconds_since(t0) - contact_seconds;
        s.energy_j = e;
        s.gradient_inf_norm_n = free_inf_norm(g);
        // Without gravity there is no natural force scale: take the initial unbalance.
        if (it == 0 && weight <= 0)
            s.tolerance_n = std::max(1e-12, relative_tolerance * s.gradient_inf_norm_n);
        s.newton_iterations = it;
        s.self_contact_pairs = static_cast<int>(pair_hessians.size());
        if (!std::isfinite(e) || !g.allFinite()) {
            p = p_start;
            s.termination = StepTermination::non_finite;
            s.message = "energy or gradient is not finite";
            break;
        }
        if (s.gradient_inf_norm_n <= s.tolerance_n) {
            // The static solve converged on a frozen stiffness: confirm with a fresh one.
            if (inertia_weight == 0 && !renew) {
                renew_next = true;
                continue;
            }
            s.termination = StepTermination::converged;
            break;
        }
        if (it >= options.max_newton_iterations) {
            s.termination = StepTermination::max_iterations;
            break;
        }
        if (options.on_iteration && !options.on_iteration(it, s.gradient_inf_norm_n)) {
            s.termination = StepTermination::cancelled;
            s.message = "cancelled by the caller";
            break;
        }
        t0 = Clock::now();
        Eigen::VectorXd rhs(free_dofs);
        for (std::size_t k = 0; k < dof_index.size(); ++k)
            if (dof_index[k] >= 0) rhs(dof_index[k]) = -g(static_cast<Eigen::Index>(k));
        Eigen::SparseMatrix<double> full;
        bool use_full = false;
        // Inertia on the diagonal; self-contact blocks in a second matrix with their own
        // (growing) pattern, summed into `full`.
        // The static solve has no inertia; a mass-proportional damping M/τ² in the Newton
        // matrix (Levenberg-Marquardt) keeps its steps bounded along zero-energy modes (a
        // skirt turning about a round body) without changing the equilibrium it finds.
        const double newton_weight =
            inertia_weight > 0 ? inertia_weight
                               : 1 / (options.static_damping_time_s * options.static_damping_time_s);
        auto add_inertia_and_pairs = [&]() {
            for (Eigen::Index i = 0; i < p.rows(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const int d = dof(static_cast<int>(i), c);
                    if (d >= 0) hessian.valuePtr()[diagonal_slots[static_cast<std::size_t>(d)]] += newton_weight * mass(i);
                }
            const bool has_pairs = !pair_hessians.empty();
            if (has_pairs && update_contact_blocks(pair_hessians)) solver.reset();
            if (has_pairs || analysed_with_contacts) {
                Eigen::SparseMatrix<double> extra = contact_pattern;
                std::fill(extra.valuePtr(), extra.valuePtr() + extra.nonZeros(), 0.0);
                for (const internal::PairHessian& ph : pair_hessians)
                    for (int a = 0; a < 4; ++a)
                        for (int b = 0; b < 4; ++b) {
                            const int va = ph.pair.v[static_cast<std::size_t>(a)], vb = ph.pair.v[static_cast<std::size_t>(b)];
                            if (va == vb) continue;  // vertex blocks are in the main pattern
                            for (int ca = 0; ca < 3; ++ca)
                                for (int cb = 0; cb < 3; ++cb) {
                                    const int r = dof(va, ca), c = dof(vb, cb);
                                    if (r < 0 || c < 0) continue;
                                    const int slot = slot_in(extra, r, c);
                                    if (slot >= 0) extra.valuePtr()[slot] += ph.hessian(3 * a + ca, 3 * b + cb);
                                }
                        }
                // Same-vertex blocks of the pairs (a == b) go into the main pattern.
                for (const internal::PairHessian& ph : pair_hessians)
                    for (int a = 0; a < 4; ++a)
                        for (int b = 0; b < 4; ++b) {
                            const int va = ph.pair.v[static_cast<std::size_t>(a)];
                            if (va != ph.pair.v[static_cast<std::size_t>(b)]) continue;
                            for (int k = 0; k < 9; ++k) {
                                const int slot = vertex_slots[static_cast<std::size_t>(9 * va + k)];
                                if (slot >= 0)
                                    hessian.valuePtr()[slot] += ph.hessian(3 * a + k % 3, 3 * b + k / 3);
                            }
                        }
                full = hessian + extra;
                if (!analysed_with_contacts) solver.reset();
                analysed_with_contacts = true;
            }
            use_full = has_pairs || analysed_with_contacts;
        };
        add_inertia_and_pairs();
        Eigen::VectorXd step;
        for (int attempt = 0; attempt < 12; ++attempt) {
            Eigen::SparseMatrix<double> shifted;
            if (shift > 0) {
                shifted = use_full ? full : hessian;
                for (Eigen::Index i = 0; i < p.rows(); ++i)
                    for (int c = 0; c < 3; ++c) {
                        const int d = dof(static_cast<int>(i), c);
                        if (d >= 0) shifted.coeffRef(d, d) += shift * mass(i) / mass_scale;
                    }
            }
            const Eigen::SparseMatrix<double>& base = use_full ? full : hessian;
            const Eigen::SparseMatrix<double>& matrix = shift > 0 ? shifted : base;
            ++s.factorisations;
            if (solver.factorize(matrix)) {
                step = solver.solve(rhs);
                if (step.allFinite() && step.dot(rhs) > 0) break;
            }
            step.resize(0);
            if (hessian_mode == HessianMode::exact) {
                // Indefinite: assemble the projected (PSD) element Hessians instead.
                hessian_mode = HessianMode::projected_psd;
                std::fill(hessian.valuePtr(), hessian.valuePtr() + hessian.nonZeros(), 0.0);
                pair_hessians.clear();
                Eigen::VectorXd unused;
                total(p, &unused, hessian.valuePtr(), &pair_hessians);
                add_inertia_and_pairs();
                ++s.regularised_factorisations;
                continue;
            }
            if (shift > 0) {
                shift *= 10;
            } else {
                const Eigen::VectorXd diagonal = (use_full ? full : hessian).diagonal();
                shift = 1e-8 * diagonal.cwiseAbs().maxCoeff() + 1e-12;
            }
            ++s.regularised_factorisations;
        }
        s.seconds_solve += seconds_since(t0);
        if (step.size() == 0) {
            s.termination = StepTermination::line_search_failed;
            s.message = "no positive-definite regularisation of the Hessian found";
            break;
        }
        const bool unregularised = shift == 0 && hessian_mode == HessianMode::exact;
        if (inertia_weight > 0 && options.step_hessian == HessianMode::exact && !unregularised)
            ++nonconvex_iterations;
        shift /= 10;  // let it decay once things are well conditioned
        if (shift < 1e-14) shift = 0;

        // Backtracking (Armijo) line search on the frozen model, from the largest step that
        // keeps contacts safe (no crossing of the obstacle or of another cloth layer).
        Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(p.rows(), 3);
        for (Eigen::Index i = 0; i < p.rows(); ++i)
            for (int c = 0; c < 3; ++c) {
                const int d = dof(static_cast<int>(i), c);
                if (d >= 0) dx(i, c) = step(d);
            }
        tc = Clock::now();
        double alpha = obstacle_step_bound(dx);
        if (use_self) alpha = std::min(alpha, self_contact.max_safe_step(p, dx * alpha, 0.9) * alpha);
        s.seconds_contact += seconds_since(tc);
        const double slope = -step.dot(rhs);
        const bool pure_newton = alpha >= 1 && unregularised;
        bool accepted = false, full_step = false;
        t0 = Clock::now();
        for (int k = 0; k <= options.max_line_search_halvings; ++k, alpha /= 2) {
            const Eigen::MatrixX3d trial = p + alpha * dx;
            const double et = total(trial, nullptr, nullptr, nullptr);
            if (std::isfinite(et) && et <= e + 1e-4 * alpha * slope) {
                p = trial;
                last_move = alpha * dx.rowwise().norm().maxCoeff();
                if (use_self) last_spread = alpha * spread(dx);
                accepted = true;
                full_step = pure_newton && k == 0;
                break;
            }
        }
        s.seconds_assembly += seconds_since(t0);
        if (!accepted) {
            s.termination = StepTermination::line_search_failed;
            s.message = "no energy decrease along the Newton direction";
            break;
        }
        small_full_step = inertia_weight > 0 && full_step && last_move <= options.step_displacement_tolerance_m;
        // Where the step's incremental potential is not convex (buckling), the projected
        // Newton matrix converges only linearly and can crawl along the unstable mode for
        // the whole iteration budget; the step ends instead and the next step goes on from
        // here (docs/cloth.md, "Nonconvex steps").
        if (inertia_weight > 0 && options.max_nonconvex_step_iterations > 0 &&
            nonconvex_iterations >= options.max_nonconvex_step_iterations) {
            s.newton_iterations = it + 1;
            s.termination = StepTermination::max_iterations;
            s.message = detail::concat("ended after ", nonconvex_iterations,
                                       " regularised Newton iterations (not convex)");
            break;
        }
    }
    s.contacts = 0;
    for (const VertexContact& c : contacts)
        if (c.vertex >= 0 && c.distance < h) ++s.contacts;
    s.max_stitch_gap_m = max_stitch_gap(p);
    s.seconds_total = seconds_since(t_start);
    return s;
}

Simulator::Simulator(ClothMesh mesh, Material material, SimulatorOptions options)
    // `mesh` is copied, not moved: the face count is read in the same argument list, whose
    // evaluation order is unspecified (the copy is negligible next to any simulation).
    : Simulator(mesh, std::vector<Material>{std::move(material)},
                std::vector<int>(static_cast<std::size_t>(mesh.faces.rows()), 0), std::move(options)) {}

Simulator::Simulator(ClothMesh mesh, std::vector<Material> materials, std::vector<int> face_material,
                     SimulatorOptions options)
    : impl_(std::make_unique<Impl>()) {
    std::string why;
    require(options.is_valid(&why), "Simulator: options are invalid: ", why);
    require(!materials.empty(), "Simulator: materials is empty (need at least one)");
    for (std::size_t k = 0; k < materials.size(); ++k)
        require(materials[k].is_valid(&why), "Simulator: material ", k, " is invalid: ", why);
    mesh.validate();
    require(face_material.size() == static_cast<std::size_t>(mesh.face_count()),
            "Simulator: face_material has ", face_material.size(), " entries, the mesh has ",
            mesh.face_count(), " faces");
    for (std::size_t f = 0; f < face_material.size(); ++f)
        require(face_material[f] >= 0 && static_cast<std::size_t>(face_material[f]) < materials.size(),
                "Simulator: face_material[", f, "] = ", face_material[f], " is out of range [0, ",
                materials.size(), ")");
    Impl& m = *impl_;
    m.mesh = std::move(mesh);
    m.materials = std::move(materials);
    m.face_material = std::move(face_material);
    m.options = std::move(options);
    m.x = m.mesh.positions;
    m.v = Eigen::MatrixX3d::Zero(m.x.rows(), 3);
    m.pinned.assign(static_cast<std::size_t>(m.x.rows()), false);
    // Lumped masses and rest areas: each face gives ρ_f A_f / 3 and A_f / 3 to its corners.
    m.mass = Eigen::VectorXd::Zero(m.x.rows());
    m.area = Eigen::VectorXd::Zero(m.x.rows());
    for (int f = 0; f < m.mesh.face_count(); ++f) {
        Eigen::Vector2d u[3];
        for (int c = 0; c < 3; ++c) u[c] = m.mesh.pattern.row(m.mesh.pattern_faces(f, c)).transpose();
        m.triangles.push_back(triangle_rest(u[0], u[1], u[2]));
        const double third = m.triangles.back().area_m2 / 3;
        for (int c = 0; c < 3; ++c) {
            m.area(m.mesh.faces(f, c)) += third;
            m.mass(m.mesh.faces(f, c)) += m.material_of(f).density_kg_per_m2 * third;
        }
    }
    m.hinges = build_hinges(m.mesh);
    for (const Hinge& h : m.hinges) {
        m.hinge_rests.push_back(hinge_rest(m.mesh, h));
        // A hinge between two materials bends with its first face's (documented in the header).
        m.bend_curves.push_back(bending_curve(m.material_of(h.faces[0]), m.hinge_rests.back()));
    }
    m.self_contact = internal::SelfContact(m.mesh.faces, m.mesh.vertex_count());
    m.set_rest_filter();
    m.renumber();
}

Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

void Simulator::pin(int vertex) {
    require(vertex >= 0 && vertex < impl_->x.rows(), "Simulator::pin: vertex ", vertex,
            " is out of range [0, ", impl_->x.rows(), ")");
    impl_->pinned[static_cast<std::size_t>(vertex)] = true;
    impl_->v.row(vertex).setZero();
    impl_->renumber();
}

void Simulator::set_pinned_position(int vertex, const Eigen::Vector3d& position_m) {
    require(vertex >= 0 && vertex < impl_->x.rows() && impl_->pinned[static_cast<std::size_t>(vertex)],
            "Simulator::set_pinned_position: vertex ", vertex, " is not a pinned vertex");
    require(position_m.allFinite(), "Simulator::set_pinned_position: position is not finite");
    impl_->x.row(vertex) = position_m.transpose();
}

const std::vector<bool>& Simulator::pinned() const { return impl_->pinned; }

void Simulator::set_obstacle(Obstacle obstacle) { impl_->obstacle = std::move(obstacle); }

void Simulator::move_obstacle(const Eigen::MatrixX3d& positions_m) {
    require(impl_->obstacle.has_value(), "Simulator::move_obstacle: there is no obstacle");
    impl_->obstacle->set_positions(positions_m);
}

void Simulator::clear_obstacle() { impl_->obstacle.reset(); }

const Obstacle* Simulator::obstacle() const {
    return impl_->obstacle ? &*impl_->obstacle : nullptr;
}

void Simulator::set_stitches(const std::vector<Stitch>& stitches) {
    Impl& m = *impl_;
    const int n = m.mesh.vertex_count();
    for (std::size_t k = 0; k < stitches.size(); ++k) {
        const Stitch& s = stitches[k];
        require(s.a >= 0 && s.a < n && s.b >= 0 && s.b < n, "Simulator::set_stitches: stitch ", k,
                " joins vertices (", s.a, ", ", s.b, "), out of range [0, ", n, ")");
        require(s.a != s.b, "Simulator::set_stitches: stitch ", k, " joins vertex ", s.a, " to itself");
        require(std::isfinite(s.length_m) && s.length_m > 0, "Simulator::set_stitches: stitch ", k,
                " has length_m = ", s.length_m, ", must be > 0");
    }
    m.stitches = stitches;
    m.stitch_rest.resize(stitches.size());
    // Contact is ignored between any two vertices of a stitched group (transitively: where
    // three or four panels meet, as at an underarm, the corners not stitched directly to
    // each other would otherwise hold the seam open by the contact thickness).
    DisjointSets groups(n);
    for (std::size_t k = 0; k < stitches.size(); ++k) {
        m.stitch_rest[k] = (m.x.row(stitches[k].a) - m.x.row(stitches[k].b)).norm();
        groups.join(stitches[k].a, stitches[k].b);
    }
    std::map<int, std::vector<int>> members;
    for (const Stitch& st : stitches)
        for (int v : {st.a, st.b}) members[groups.find(v)].push_back(v);
    std::vector<std::pair<int, int>> excluded;
    for (auto& [root, list] : members) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        for (std::size_t i = 0; i < list.size(); ++i)
            for (std::size_t j = i + 1; j < list.size(); ++j) excluded.emplace_back(list[i], list[j]);
    }
    m.self_contact = internal::SelfContact(m.mesh.faces, n, excluded);
    m.set_rest_filter();
    m.pattern_ready = false;
    m.solver.reset();
}

const std::vector<Stitch>& Simulator::stitches() const { return impl_->stitches; }

ContactReport Simulator::contact_report() const {
    const Impl& m = *impl_;
    ContactReport r;
    r.min_obstacle_distance_m = std::numeric_limits<double>::infinity();
    if (m.obstacle) {
        for (Eigen::Index i = 0; i < m.x.rows(); ++i) {
            const ObstacleQuery q = m.obstacle->closest(m.x.row(i).transpose(),
                                                        std::numeric_limits<double>::infinity());
            if (!q.found) continue;
            r.min_obstacle_distance_m = std::min(r.min_obstacle_distance_m, q.signed_distance_m);
            if (q.signed_distance_m < 0) {
                ++r.vertices_inside;
                r.max_penetration_m = std::max(r.max_penetration_m, -q.signed_distance_m);
            }
        }
    }
    r.max_stitch_gap_m = m.max_stitch_gap(m.x);
    // A sewn garment is one surface: stitched vertices count as one (else the triangles on
    // the two sides of a closed seam, which touch along it, would count as intersecting).
    DisjointSets sewn(static_cast<int>(m.x.rows()));
    for (const Stitch& st : m.stitches) sewn.join(st.a, st.b);
    Eigen::MatrixX3i merged = m.mesh.faces;
    for (Eigen::Index f = 0; f < merged.rows(); ++f)
        for (int c = 0; c < 3; ++c) merged(f, c) = sewn.find(merged(f, c));
    r.self_intersections = count_self_intersections(m.x, merged);
    return r;
}

namespace {

// Sums the counters of `part` into `total` (termination/energy/norms come from the last part).
void accumulate(StepSummary& total, const StepSummary& part) {
    total.newton_iterations += part.newton_iterations;
    total.regularised_factorisations += part.regularised_factorisations;
    total.factorisations += part.factorisations;
    total.seconds_assembly += part.seconds_assembly;
    total.seconds_solve += part.seconds_solve;
    total.seconds_contact += part.seconds_contact;
    total.termination = part.termination;
    total.message = part.message;
    total.gradient_inf_norm_n = part.gradient_inf_norm_n;
    total.tolerance_n = part.tolerance_n;
    total.energy_j = part.energy_j;
    total.contacts = part.contacts;
    total.self_contact_pairs = part.self_contact_pairs;
    total.max_stitch_gap_m = part.max_stitch_gap_m;
}

}  // namespace

StepSummary Simulator::step() {
    const auto t0 = Clock::now();
    StepSummary s = impl_->backward_euler(impl_->options.time_step_s,
                                          impl_->options.max_step_halvings);
    s.seconds_total = seconds_since(t0);
    return s;
}

StepSummary Simulator::Impl::backward_euler(double h, int halvings_left) {
    Impl& m = *this;
    Eigen::MatrixX3d target = m.x + h * m.v;
    for (std::size_t i = 0; i < m.pinned.size(); ++i)
        if (m.pinned[i]) target.row(static_cast<Eigen::Index>(i)) = m.x.row(static_cast<Eigen::Index>(i));
    // Open seams close at the closing speed; the rest lengths only shrink.
    const std::vector<double> rest_before = m.stitch_rest;
    for (double& r : m.stitch_rest) r = std::max(0.0, r - m.options.seam_closing_speed_m_per_s * h);
    m.step_start = m.x;
    m.step_dt = h;
    // Start from the current positions: the inertial prediction could jump through the
    // obstacle or another layer, while every Newton step from here is kept collision-safe.
    Eigen::MatrixX3d p = m.x;
    StepSummary s = m.minimise(p, target, 1 / (h * h), m.options.step_relative_tolerance);
    m.step_dt = 0;
    if (s.usable()) {
        m.v = (p - m.x) / h;
        m.x = p;
        return s;
    }
    m.stitch_rest = rest_before;
    if (halvings_left == 0 || s.termination == StepTermination::cancelled) return s;
    // Retry as two half steps from the unchanged state.
    const Eigen::MatrixX3d x0 = m.x, v0 = m.v;
    StepSummary total = s;
    total.substeps = 0;
    for (int half = 0; half < 2; ++half) {
        const StepSummary part = backward_euler(h / 2, halvings_left - 1);
        accumulate(total, part);
        total.substeps += part.substeps;
        if (!part.usable()) {
            m.x = x0;
            m.v = v0;
            m.stitch_rest = rest_before;
            total.message = "failed even after halving the step: " + part.message;
            return total;
        }
    }
    total.message = detail::concat("step split into ", total.substeps, " substeps after: ", s.message);
    return total;
}

StepSummary Simulator::solve_static() {
    Impl& m = *impl_;
    Eigen::MatrixX3d p = m.x;
    std::fill(m.stitch_rest.begin(), m.stitch_rest.end(), 0.0);
    m.step_dt = 0;
    m.step_start = m.x;
    m.static_friction = m.options.static_friction;
    StepSummary s = m.minimise(p, m.x, 0, m.options.relative_tolerance);
    m.static_friction = false;
    if (s.termination != StepTermination::non_finite) {
        m.x = p;
        m.v.setZero();
    }
    return s;
}

const Eigen::MatrixX3d& Simulator::positions() const { return impl_->x; }
const Eigen::MatrixX3d& Simulator::velocities() const { return impl_->v; }

void Simulator::set_positions(const Eigen::MatrixX3d& positions_m) {
    require(positions_m.rows() == impl_->x.rows(), "Simulator::set_positions: ", positions_m.rows(),
            " rows, expected ", impl_->x.rows());
    require(positions_m.allFinite(), "Simulator::set_positions: positions are not finite");
    impl_->x = positions_m;
    impl_->k_lagged.clear();
    // The vertices may have jumped anywhere: their previous obstacle distances are unknown,
    // so the next contact update searches every vertex beyond the query radius too.
    impl_->contacts.clear();
}

void Simulator::set_velocities(const Eigen::MatrixX3d& velocities_m_per_s) {
    require(velocities_m_per_s.rows() == impl_->v.rows(), "Simulator::set_velocities: ",
            velocities_m_per_s.rows(), " rows, expected ", impl_->v.rows());
    require(velocities_m_per_s.allFinite(), "Simulator::set_velocities: velocities are not finite");
    impl_->v = velocities_m_per_s;
    for (std::size_t i = 0; i < impl_->pinned.size(); ++i)
        if (impl_->pinned[i]) impl_->v.row(static_cast<Eigen::Index>(i)).setZero();
}

const Eigen::VectorXd& Simulator::masses() const { return impl_->mass; }
const ClothMesh& Simulator::mesh() const { return impl_->mesh; }
const Material& Simulator::material() const { return impl_->materials.front(); }
const std::vector<Material>& Simulator::materials() const { return impl_->materials; }
const std::vector<int>& Simulator::face_material() const { return impl_->face_material; }
const SimulatorOptions& Simulator::options() const { return impl_->options; }

Eigen::MatrixX3d Simulator::forces() const {
    Impl copy = Impl(*impl_);  // refresh_stiffness mutates the frozen stiffness cache
    copy.refresh_stiffness(copy.x);
    copy.contacts.clear();
    Eigen::VectorXd g;
    const bool self = copy.options.self_contact;
    copy.options.self_contact = false;
    copy.potential(copy.x, &g, nullptr);
    copy.options.self_contact = self;
    Eigen::MatrixX3d f(copy.x.rows(), 3);
    for (Eigen::Index i = 0; i < f.rows(); ++i) f.row(i) = -g.segment<3>(3 * i).transpose();
    return f;
}

}  // namespace drape::cloth
