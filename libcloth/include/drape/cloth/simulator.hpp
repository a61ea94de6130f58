// The implicit cloth simulator: backward Euler written as the minimisation of the
// incremental potential, solved by Newton's method with a backtracking line search on a
// sparse Cholesky factorisation (CHOLMOD); and a quasi-static mode that minimises the
// potential energy directly. Terms: anisotropic stretching and curvature-dependent bending
// (Wang et al. 2011 tables), gravity, air drag and wind, body contact with Coulomb
// friction against a moving obstacle mesh, self-contact, seam stitches, pinned vertices
// with prescribed motion. See docs/cloth.md.
#pragma once

#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/energies.hpp>
#include <drape/cloth/material.hpp>
#include <drape/cloth/obstacle.hpp>

#include <Eigen/Core>

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace drape::cloth {

struct SimulatorOptions {
    double time_step_s = 5e-3;                           ///< backward-Euler step, > 0
    Eigen::Vector3d gravity_m_per_s2{0.0, 0.0, -9.8};    ///< world frame
    /// Newton stops when the largest entry of the free gradient (N) is below
    /// relative_tolerance × the largest vertex weight m_i |g| (without gravity: × the initial
    /// largest free force, at least 1e-12 N).
    double relative_tolerance = 1e-6;
    int max_newton_iterations = 100;  ///< per step or per static solve, >= 1
    int max_line_search_halvings = 30;
    /// A failed step (line search failure or NaN) is retried as two half steps, recursively,
    /// at most this many levels deep (so down to time_step_s / 2^max_step_halvings).
    int max_step_halvings = 3;
    /// Newton tolerance of dynamic steps (same meaning as relative_tolerance, which the
    /// static solve uses): a time step need not be solved to machine precision.
    double step_relative_tolerance = 1e-2;
    /// A time step also ends when a full, unregularised Newton step (exact Hessian, no
    /// shift, not shortened by the line search or a contact bound) moves no vertex farther
    /// than this (m) and, at the new positions, the inertia-scaled residual
    /// max_i |g_i| dt² / m_i (what Newton would still correct, where the step's matrix is the
    /// inertia plus a positive semi-definite part) is within it too; the check costs one
    /// gradient evaluation. 0 disables it. 100 µm (2 cm/s over 5 ms) since 2026-11-24, was
    /// 10 µm without the residual check: 20-25 % fewer factorisations, same anchor rest
    /// state (docs/cloth.md, "When a time step ends").
    double step_displacement_tolerance_m = 1e-4;
    /// A time step ends (StepTermination::max_iterations, usable) after this many Newton
    /// iterations whose exact matrix was indefinite (solved with the projected one or a
    /// diagonal shift): there the incremental potential is not convex (the cloth buckles),
    /// Newton converges only linearly and could spend the whole max_newton_iterations
    /// crawling along the buckling mode (100 iterations, 28 s, in one step of the N = 64
    /// anchor scene); the next step carries on from the state reached. 0 = no limit.
    int max_nonconvex_step_iterations = 4;
    /// Newton matrix of the elastic terms in time steps. `exact`: with the inertia term the
    /// system is almost always positive definite and Newton converges quadratically; when
    /// the factorisation finds it indefinite, that iteration falls back to projected_psd.
    HessianMode step_hessian = HessianMode::exact;
    /// Newton matrix of the elastic terms in solve_static() (no inertia): gauss_newton
    /// (cheap, PSD; linear convergence where the cloth is compressed) or projected_psd.
    HessianMode static_hessian = HessianMode::gauss_newton;
    /// solve_static() damps its Newton steps with M/τ² (as a time step of τ would), which
    /// keeps them bounded along zero-energy modes; the equilibrium is unchanged. > 0.
    double static_damping_time_s = 0.05;
    /// solve_static() keeps Coulomb friction (obstacle and cloth–cloth), measured from the
    /// state it starts at, with the normal forces of that state and the slip distance
    /// friction_slip_speed_m_per_s × static_damping_time_s: an equilibrium in which every
    /// contact either sticks near its start or slides with |f_t| = μ f_n. Without it a
    /// garment held up by friction (a skirt on the hips) has no frictionless equilibrium
    /// near its draped state and slides.
    bool static_friction = true;

    /// Time steps freeze the stretching stiffness at the mean of the table's value at the
    /// step's start and the previous step's (an under-relaxed fixed point; see simulator.cpp
    /// refresh_stiffness): frozen afresh each step, a strain where the table changes fast
    /// can cycle with period 2 and never come to rest. false: the table's value alone.
    bool relax_stretching_stiffness = true;

    // ---- contact ----
    /// Cloth–obstacle and cloth–cloth contact thickness h (m): a vertex is pushed back while
    /// it is closer than h to the obstacle surface or to another part of the cloth.
    double contact_thickness_m = 5e-3;
    /// Penalty stiffness per unit vertex area (N/m³): vertex i gets k_i = this × A_i, so the
    /// penetration into the thickness layer is pressure / this, independent of resolution.
    double contact_stiffness_n_per_m3 = 1e6;
    /// The obstacle penalty is this many times as stiff behind the obstacle's surface as in
    /// the layer in front of it (plane_contact_energy's β, >= 1): a vertex pressed into the
    /// body by a tight neckline or a stiff fabric stops near the surface instead of sinking
    /// in by pressure / contact_stiffness (several mm at a neckline's edge).
    double contact_inside_stiffness_factor = 10;
    double obstacle_friction = 0.3;  ///< Coulomb μ between cloth and obstacle, >= 0
    double cloth_friction = 0.6;     ///< Coulomb μ between cloth layers (self-contact), >= 0
    /// Friction is static-like below a slip speed of this (m/s); ε = this × Δt.
    double friction_slip_speed_m_per_s = 1e-3;
    /// Body friction of a vertex that slides more than this in one step (m) gets the quadratic
    /// majorizer μλ/|u| (I − nnᵀ) as its Hessian instead of the exact one, which is zero along
    /// the slip (friction_energy's majorize_above_m). On a moving body (a walk) the exact
    /// Hessian lets Newton ask for decimetre moves of the sliding vertices, the obstacle step
    /// bound then cuts every vertex's step and Newton stops short: garments sink down the
    /// body. Below the threshold the exact Hessian keeps a held garment snapped to sticking.
    /// >= 0; infinity (the default): always exact. Garment animation uses 0.5 mm
    /// (AnimateOptions::default_simulator_options).
    double friction_majorize_slip_m = std::numeric_limits<double>::infinity();
    /// Every Newton iterate keeps a vertex without an active contact plane outside the body
    /// (its own step cut to 0.9 of its distance, the rest of the cloth's not), and a vertex
    /// whose plane overstates its distance to the body by more than half the layer (it slid
    /// round a concave fold, the armpit) gets a second plane. Off, a vertex may end a step that
    /// stops on its iteration cap up to contact_thickness_m inside (docs/cloth.md, "Body
    /// contact"). On, a step's first iterate also carries each vertex the moving body holds by
    /// friction with its surface in full (not where that would take it into another part of
    /// the body), and the cloth lying on carried cloth with it; off, one scale for the whole
    /// cloth from the step bound (docs/cloth.md, "Friction on a moving body"). Off by default:
    /// the drape figures were measured without it; garment animation turns it on
    /// (AnimateOptions::default_simulator_options).
    bool strict_body_contact = false;
    bool self_contact = true;        ///< cloth–cloth repulsion (vertex–face and edge–edge)

    // ---- seams ----
    /// Stitch stiffness per unit seam length (N/m²): stitch s gets k_s = this × l_s with l_s
    /// the seam length it represents, so the seam gap is tension / this (1e6: 0.05 mm at
    /// 50 N/m).
    double stitch_stiffness_n_per_m2 = 1e6;
    /// Open stitches are pulled closed by shrinking their rest length at this speed (m/s);
    /// closed ones are held at zero length.
    double seam_closing_speed_m_per_s = 0.5;

    // ---- air ----
    /// Linear air drag per unit area (N·s/m³): force −c A_i (v_i − wind). 0 = none.
    double air_drag_n_s_per_m3 = 0;
    Eigen::Vector3d wind_m_per_s = Eigen::Vector3d::Zero();

    /// Called after every Newton iteration with (iteration, |gradient|inf in N); return false
    /// to cancel (the step/solve ends with StepTermination::cancelled). May be empty.
    std::function<bool(int, double)> on_iteration;

    bool is_valid(std::string* why = nullptr) const;
};

enum class StepTermination {
    converged,           ///< gradient below tolerance
    max_iterations,      ///< Newton ran out of iterations; state is the last iterate
    line_search_failed,  ///< no decrease along the Newton direction; state is the last iterate
    non_finite,          ///< a NaN or infinity appeared; the state was restored
    cancelled,           ///< on_iteration returned false; state is the last iterate
};

struct StepSummary {
    StepTermination termination = StepTermination::non_finite;
    std::string message;
    int newton_iterations = 0;
    int regularised_factorisations = 0;  ///< times the Hessian needed a diagonal shift
    int factorisations = 0;              ///< Cholesky factorisations (incl. regularised)
    int substeps = 1;                    ///< > 1 when the step was split by halving
    int contacts = 0;                    ///< vertices within the thickness of the obstacle
    int self_contact_pairs = 0;          ///< active cloth–cloth pairs at the last iteration
    /// Newton iterations whose direction lost the closing motion of pressed cloth layers
    /// (pairs that held the step under 1 % of its length; docs/self-contact.md).
    int released_steps = 0;
    double max_stitch_gap_m = 0;         ///< at the returned state
    double gradient_inf_norm_n = 0;      ///< at the returned state, free vertices only
    double tolerance_n = 0;              ///< the absolute tolerance that was used
    double energy_j = 0;                 ///< incremental potential (or potential, static)
    double seconds_assembly = 0;         ///< energies, gradients, Hessians, line search
    double seconds_solve = 0;            ///< factorisation + back substitution
    /// Contact detection: body contact queries (BVH), self-contact candidates (spatial
    /// hash) and the penetration-safe step bounds.
    double seconds_contact = 0;
    double seconds_total = 0;

    bool usable() const {
        return termination == StepTermination::converged ||
               termination == StepTermination::max_iterations;
    }
    std::string brief_report() const;
};

/// Geometric checks of a state (what the acceptance criteria measure).
struct ContactReport {
    double max_penetration_m = 0;   ///< deepest cloth vertex inside the obstacle (>= 0)
    int vertices_inside = 0;        ///< cloth vertices with negative signed distance
    double min_obstacle_distance_m = 0;  ///< smallest signed distance (inf without obstacle)
    double max_stitch_gap_m = 0;    ///< largest |xa − xb| over the stitches
    int self_intersections = 0;     ///< intersecting pairs of non-adjacent cloth triangles
    int deepest_vertex = -1;        ///< the deepest cloth vertex inside the obstacle (-1: none)
    int deepest_obstacle_face = -1; ///< the obstacle face closest to it (-1: none)
};

/// A stitch of a seam: vertices a and b are pulled together and held.
struct Stitch {
    int a = -1;
    int b = -1;
    double length_m = 0;  ///< seam length this stitch stands for (for its stiffness), > 0
};

namespace internal {
class PotentialProbe;  // a test hook in libcloth/src (not part of the API)
}

/// A piece of cloth in time. Owns its state; distinct simulators may run on distinct threads.
class Simulator {
public:
    /// One material for the whole mesh (delegates to the per-face constructor).
    /// \throw drape::InvalidInput if the mesh, the material or the options are invalid.
    Simulator(ClothMesh mesh, Material material, SimulatorOptions options = {});
    /// A material per face, e.g. an outfit of several garments simulated together, one
    /// fabric each: face f is made of materials[face_material[f]] (its stretching stiffness
    /// and its density, which gives its corners ρ_f A_f / 3 of mass). A hinge between faces
    /// of two materials bends with the material of its first face (Hinge::faces[0]).
    /// \param materials at least one, each valid; \param face_material #F indices into it.
    /// \throw drape::InvalidInput if the mesh, a material, face_material (size or an index,
    /// naming the face) or the options are invalid.
    Simulator(ClothMesh mesh, std::vector<Material> materials, std::vector<int> face_material,
              SimulatorOptions options = {});
    ~Simulator();
    Simulator(Simulator&&) noexcept;
    Simulator& operator=(Simulator&&) noexcept;
    Simulator(const Simulator&) = delete;
    Simulator& operator=(const Simulator&) = delete;

    /// Holds `vertex` at its current position (its velocity is set to zero).
    /// \throw drape::InvalidInput if vertex is out of range.
    void pin(int vertex);
    /// Moves a pinned vertex (a prescribed motion); \throw drape::InvalidInput if not pinned
    /// or the position is not finite.
    void set_pinned_position(int vertex, const Eigen::Vector3d& position_m);
    const std::vector<bool>& pinned() const;

    /// Sets the obstacle (the body) the cloth collides with; replaces any previous one.
    void set_obstacle(Obstacle obstacle);
    /// Moves the obstacle's vertices (same faces) before the next step, e.g. to animate the
    /// body; cloth left inside is pushed out by the contact penalty.
    /// \throw drape::InvalidInput if there is no obstacle or the shape differs.
    void move_obstacle(const Eigen::MatrixX3d& positions_m);
    void clear_obstacle();
    const Obstacle* obstacle() const;  ///< null when none

    /// Sets the seam stitches (replacing previous ones). Open stitches close at
    /// options.seam_closing_speed_m_per_s during steps; solve_static() holds them at zero.
    /// Cloth–cloth contact between a stitch's two sides is ignored.
    /// \throw drape::InvalidInput if an index is out of range, a == b or length <= 0.
    void set_stitches(const std::vector<Stitch>& stitches);
    const std::vector<Stitch>& stitches() const;

    /// Changes the rest shape: new pattern coordinates (mesh().pattern's rows, pattern frame,
    /// metres), the same faces. Recomputes what construction derives from the pattern (rest
    /// triangles, lumped masses and areas, hinge rest lengths/areas/directions and bending
    /// curves, the self-contact rest-neighbour filter); the state (positions, velocities,
    /// pins, obstacle, stitches) and the solver's symbolic analysis (the sparsity pattern
    /// does not change) are kept, so the next step or static solve costs what any other
    /// does. For garment recovery: the sizing G changes the pattern, not its topology.
    /// \throw drape::InvalidInput if the row count differs, a coordinate is not finite or a
    ///        pattern triangle is degenerate or clockwise (naming the face), as
    ///        ClothMesh::validate; the simulator is then unchanged.
    void set_rest_positions(const Eigen::MatrixX2d& pattern_m);
    /// Changes the materials (as many as constructed; face_material() is kept): masses,
    /// stretching and bending curves are recomputed as construction does. State, stitches
    /// and the symbolic analysis are kept.
    /// \throw drape::InvalidInput if the count differs or a material is invalid (naming it);
    ///        the simulator is then unchanged.
    void set_materials(std::vector<Material> materials);

    /// Penetration, stitch gaps and self-intersections of the current state.
    ContactReport contact_report() const;

    /// One backward-Euler step of options.time_step_s; a failed solve is retried as two half
    /// steps (see max_step_halvings). If it still fails the state is unchanged and the
    /// summary says why (`usable()` is false).
    StepSummary step();
    /// Minimises the potential energy (elastic + gravity) from the current positions: the
    /// static equilibrium under gravity. Velocities are set to zero.
    StepSummary solve_static();

    const Eigen::MatrixX3d& positions() const;   ///< #V x 3, world, metres
    const Eigen::MatrixX3d& velocities() const;  ///< #V x 3, m/s
    /// \throw drape::InvalidInput on a shape mismatch or non-finite entry.
    void set_positions(const Eigen::MatrixX3d& positions_m);
    void set_velocities(const Eigen::MatrixX3d& velocities_m_per_s);
    const Eigen::VectorXd& masses() const;       ///< #V, kg
    const ClothMesh& mesh() const;
    /// The first material (the only one of a one-material simulator).
    const Material& material() const;
    const std::vector<Material>& materials() const;  ///< as constructed, >= 1
    const std::vector<int>& face_material() const;    ///< #F indices into materials()
    const SimulatorOptions& options() const;

    /// Elastic + gravity force on every vertex at the current positions (#V x 3, N), with the
    /// stiffness looked up at the current strain; on pinned vertices it is the force the
    /// pins must balance (with opposite sign).
    Eigen::MatrixX3d forces() const;

private:
    friend class internal::PotentialProbe;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace drape::cloth
