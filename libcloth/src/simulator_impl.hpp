// Private to libcloth: the state of a Simulator and the declarations of its parts, one
// concept per file:
//   incremental_potential.cpp  assembly of the incremental potential (elements, gravity,
//                              stitches, contact planes, friction, self-contact, drag,
//                              inertia) and the Hessian's sparsity pattern;
//   contact_state.cpp          body contacts, contact planes, lagged friction, step bounds;
//   newton_minimiser.cpp       the projected Newton minimiser with its line search;
//   simulator.cpp              the public facade (drape/cloth/simulator.hpp).
#pragma once

#include <drape/cloth/contact.hpp>
#include <drape/cloth/energies.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/cloth/simulator.hpp>

#include "self_contact.hpp"
#include "sparse_solver.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace drape::cloth {

namespace internal {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
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
    int face = -1;                                      // the obstacle's closest triangle
    Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // `point`'s barycentric weights on it
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
    // How far the obstacle's surface under the vertex moved into this step (since the last
    // step ended): the slip is measured against it, so a moving body carries the cloth.
    Eigen::Vector3d surface_motion = Eigen::Vector3d::Zero();
};

// Lagged friction between two cloth layers: a self-contact pair's frame and penalty force
// at the start of the step.
struct PairFriction {
    internal::PairFrame frame;
    double normal_force = 0;  // λ
};

}  // namespace internal

using internal::Clock;
using internal::DisjointSets;
using internal::FrictionContact;
using internal::PairFriction;
using internal::seconds_since;
using internal::VertexContact;

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
    // The obstacle's positions when the last step ended (or when it was set): friction slips
    // relative to the surface's motion since then (FrictionContact::surface_motion).
    Eigen::MatrixX3d obstacle_start;
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
    // Every term with its own Hessian in hessian_mode (bending, stitches and self-contact
    // otherwise use Gauss–Newton or PSD forms): set only by the finite-difference test hook
    // (potential_probe.hpp).
    bool exact_hessians = false;

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

    void renumber();
    // Everything construction derives from the pattern (rest shape) and the materials:
    // rest triangles, lumped masses and areas, hinge rest data and bending curves; clears
    // the frozen stretching stiffness. Needs mesh, materials, face_material, x and hinges.
    void compute_rest_state();
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
    void refresh_stiffness(const Eigen::MatrixX3d& p, bool relax = false);

    // ---- sparsity pattern -------------------------------------------------------------
    static int slot_in(const Eigen::SparseMatrix<double>& m, int r, int c);

    void add_block_entries(std::vector<Eigen::Triplet<double>>& entries, const int* verts, int n) const;

    void fill_slots(const int* verts, int n, int* out) const;

    void build_pattern();

    // Adds the blocks the current self-contact pairs need; true if the set grew.
    bool update_contact_blocks(const std::vector<internal::PairHessian>& pairs);

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
    void update_obstacle_contacts(const Eigen::MatrixX3d& p);

    // The lagged friction of a time step, from the contacts queried at its start: vertices
    // within the thickness, with their contact normal and penalty force there. A vertex
    // behind the surface counts the force it would have on the surface (k h): the penalty's
    // growth with depth is a correction, not a pressure, and friction from it held a
    // vertex that a stiff skirt had pushed 27 mm into a thigh where it was (a tangential
    // pull of 18 N could not move it).
    void lag_friction();

    // Drops the lagged friction of vertices no longer within the contact thickness.
    void drop_released_friction();

    // Signed distance of vertex i at p from contact plane `plane` (an index into planes).
    double plane_distance(int plane, const Eigen::MatrixX3d& p, int i) const;
    // True when vertex i at p lies within the layer of one of its contact planes: its contact
    // energy is active, and the step's Hessian knows of the body there.
    bool plane_active(const Eigen::MatrixX3d& p, int i) const;
    // Largest step fraction for which no free vertex at p can pass through the obstacle: a
    // point at distance d from the surface cannot cross it by moving less than d. A vertex
    // whose contact plane is active may end up to the layer's thickness inside: it is still on
    // the near side of any part of the body thicker than twice that, and its plane's energy,
    // which the line search sees, pushes it back out. With strict_body_contact, any other
    // vertex has no energy there (and the iteration may be the last of its time step), so it
    // stays outside (0.9 d); without, every vertex gets the allowance. Vertices already inside
    // are not limited.
    double obstacle_step_bound(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& dx) const;
    // Shortens the step of each vertex at p without an active contact plane to 0.9 of its
    // distance to the obstacle (its row of dx scaled down, the others kept), so that a vertex
    // falling onto the body does not shorten every vertex's step through obstacle_step_bound;
    // true if any row changed. The line search calls it only with strict_body_contact.
    bool clamp_free_approach(const Eigen::MatrixX3d& p, Eigen::MatrixX3d& dx) const;
    // The first iterate's move of a dynamic step (newton_minimiser): each vertex with body
    // friction moved with its surface's motion, as far as that is collision-safe.
    Eigen::MatrixX3d start_carry(const Eigen::MatrixX3d& p) const;
    // Strict body contact's carry of a layer lying on a carried one (start_carry): a vertex
    // the body does not carry, in cloth contact with vertices it does, takes their carry (the
    // mean over its contacts, weighted as the contact's closest points are).
    void spread_carry_to_layers(Eigen::MatrixX3d& carry) const;
    // Strict body contact's check of the carry (start_carry): drops the carry of each vertex
    // that it would take deeper into the body than the vertex is now.
    void keep_safe_carry(const Eigen::MatrixX3d& p, Eigen::MatrixX3d& carry) const;

    // The lagged cloth–cloth friction of a time step: self-contact pairs within the thickness
    // at its start, with their frames and penalty forces λ = k (h − d).
    void lag_pair_friction(const Eigen::MatrixX3d& p);

    bool friction_active() const { return step_dt > 0 || static_friction; }
    double friction_epsilon() const;

    // ---- energy ------------------------------------------------------------------------
    // Total energy of the frozen model at `p`; optionally the full gradient (3V) and, added
    // into `values` (the value array of `pattern`) and `pair_hessians`, the Hessian.
    double potential(const Eigen::MatrixX3d& p, Eigen::VectorXd* gradient, double* values,
                     std::vector<internal::PairHessian>* pair_hessians = nullptr);

    // Self-contact stiffness per pair: the contact pressure stiffness times a typical vertex
    // area (pairs do not have an area of their own).
    double self_contact_stiffness() const;

    // Pairs closer than 2h in the pattern are neighbours within one layer (see
    // SelfContact::set_rest_filter). Per pattern point (a face corner's rest position; a
    // welded seam vertex has one per panel) its vertex; pieces: connected components of the
    // pattern faces, i.e. the panels.
    void set_rest_filter();

    double max_stitch_gap(const Eigen::MatrixX3d& p) const;

    // Total incremental potential inertia_weight/2 Σ m_i |q_i − target_i|² + potential(q)
    // (inertia_weight = 1/h² for a time step, 0 for the static solve); gradient and Hessian
    // as potential (the inertia's Hessian is added by the minimiser, on the diagonal).
    double incremental_potential(const Eigen::MatrixX3d& q, const Eigen::MatrixX3d& target,
                                 double inertia_weight, Eigen::VectorXd* gradient, double* values,
                                 std::vector<internal::PairHessian>* pair_hessians);

    // ---- Newton minimiser (newton_minimiser.cpp) ----------------------------------------
    // Newton on E(p) = inertia_weight/2 Σ m_i |p_i − target_i|² + potential(p).
    // inertia_weight = 1/h² for backward Euler, 0 for the static solve.
    StepSummary minimise(Eigen::MatrixX3d& p, const Eigen::MatrixX3d& target, double inertia_weight,
                         double relative_tolerance);

    // ---- facade (simulator.cpp) ---------------------------------------------------------
    StepSummary backward_euler(double h, int halvings_left);
};

}  // namespace drape::cloth
