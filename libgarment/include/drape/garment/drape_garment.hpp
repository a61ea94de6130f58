// Draping a dressed garment on the body (paper section 4.3, last two steps): the seams are
// closed in a dynamic simulation with the body as a collision obstacle, the cloth settles
// under gravity with air drag, and a quasi-static solve takes it to static equilibrium.
#pragma once

#include <drape/cloth/material.hpp>
#include <drape/cloth/simulator.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/garment_mesh.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace drape::garment {

/// What the draping is doing, for a progress display.
enum class DrapePhase { closing_seams, moving_body, settling, static_solve };

/// Passed to DrapeOptions::on_progress after every simulation step and static solve.
struct DrapeProgress {
    DrapePhase phase = DrapePhase::closing_seams;
    int step = 0;                    ///< dynamic steps done so far
    double seam_gap_max_m = 0;       ///< largest stitch gap now
    double kinetic_energy_j = 0;     ///< ½ Σ m v² now
    int newton_iterations = 0;       ///< of the last step
    double step_seconds = 0;         ///< wall time of the last step
    /// The garment's vertex positions now (#V x 3, world, metres; stitched vertices apart
    /// until welded, then equal). Valid only during the callback.
    const Eigen::MatrixX3d* positions = nullptr;
};

struct DrapeOptions {
    /// The simulator's settings. Defaults differ from SimulatorOptions: gravity is −9.8 m/s²
    /// along −Y (the library frame), Δt = 10 ms, air drag 2 N·s/m³ so the cloth settles, and
    /// at most 3 Newton iterations per step: only the rest state matters, and a step's
    /// remaining residual is worked off by the next steps (skirt, mean female, 4 cm edges:
    /// 6.8 s with 134 steps instead of 18.6 s with 150 steps at a cap of 12; body contact with
    /// friction makes Newton slow to reach the step tolerance, 6–7 iterations per step).
    cloth::SimulatorOptions simulator = default_simulator_options();
    double seam_gap_tolerance_m = 1e-3;       ///< seams count as closed below this, > 0
    /// The dynamic phase ends when the seams are closed and the kinetic energy per unit mass
    /// ½ Σ m v² / Σ m is below this (J/kg = m²/s²; 1e-4 ≈ 1.4 cm/s RMS speed), > 0.
    double settled_kinetic_energy_j_per_kg = 1e-4;
    /// If the dressed garment intersects itself, it is first stepped without self-contact
    /// (so the intersections can pass through each other) until it is free of them, checked
    /// every 5 steps, for at most this many steps (>= 0), then draped with self-contact.
    /// It removes the skirt's 8 dressed intersections in 5 steps (mean female, 4 cm); with
    /// many intersections it may not, and the garment can slide meanwhile (docs/dressing.md).
    int max_untangle_steps = 200;
    int min_steps = 20;                       ///< dynamic steps always taken, >= 0
    int max_steps = 600;                      ///< dynamic steps at most, >= min_steps, >= 1
    /// Once every stitch gap is below seam_gap_tolerance_m, the stitched vertices are welded
    /// into one simulation vertex each (the seam becomes an ordinary edge of the cloth, with
    /// bending across it, as a sewn seam): seams then stay closed exactly (gap 0), where
    /// penalty stitches open by tension / stiffness under load (the pants' crotch: 1.7 mm).
    /// A mesh that cannot be welded (a seam joining edges of like orientation) keeps its
    /// stitches (the summary's message says so).
    bool weld_seams = true;
    /// The body moves along `body_path` (drape_garment's overload with a path) over this
    /// time (s) once the seams are closed, or longer if a body vertex would move more than
    /// half the contact thickness in a step, > 0.
    double body_motion_s = 0.6;
    /// Finish with Simulator::solve_static(). Off by default: on a body with penalty contact
    /// the static solve's outer iterations (contact planes and stiffness renewed every 8
    /// Newton iterations) cycle and rarely reach its tolerance (skirt: |g| 2.5 mN after 100
    /// iterations, 0.8 s), so equilibrium is reached by stepping to rest.
    bool static_solve = false;
    int static_max_newton_iterations = 100;   ///< Newton iterations of the static solve, >= 1
    /// Extra dynamic steps taken if the static solve fails or leaves the cloth in the body
    /// (the equilibrium is then reached by stepping), >= 0.
    int fallback_steps = 200;
    double penetration_tolerance_m = 1e-3;    ///< `usable()` allows this much, > 0
    /// A cloth at rest that is still pressed deeper than penetration_tolerance_m into the
    /// body (a tank's strap over the shoulder blade, a bodice under the arm: 1.05-1.3 mm on
    /// the photos, with simulator.contact_inside_stiffness_factor 10) is stepped on to rest
    /// with the penalty behind the body's surface this many times stiffer, at most
    /// fallback_steps steps; the stiffer state is kept only if it is at rest, lies less deep
    /// and has no more self-intersections and no open seam (the summary's
    /// `contact_stiffened`). Drapes within the tolerance are not touched. 1 = off; >= 1.
    double contact_stiffening = 10;
    /// A cloth at rest whose layers cross (a fold pinched under a raised arm, a sleeve
    /// squeezed against the trunk: the penalty self-contact then holds the crossing) is
    /// separated by untangle_garment (intersection-contour style, against the final body)
    /// and stepped on to rest with self-contact, at most fallback_steps steps; the new state
    /// is kept only if it is at rest with fewer crossings, no deeper in the body (or within
    /// penetration_tolerance_m) and the seams closed (the summary's `crossings_repaired`).
    bool repair_crossings = true;
    /// `usable()` requires the garment to stay on the body: its vertices may sink along
    /// gravity by at most this much on average (m) from the dressed state, relative to the
    /// body's own mean sink along the path, > 0. Measured (4 cm edges): pants 0.4 cm, t-shirt
    /// and dress −2 to −4 cm (they rise as the sleeve seams close), a t-shirt over a skirt 7.8
    /// cm, a loose skirt that settled from the waist onto the hips 15 cm; skirts that slid
    /// off to the floor 93 cm — and those pass every other check.
    double max_mean_drop_m = 0.25;
    /// Skirts are sewn with a waistband: the strip of their panels along the open top edge
    /// (the waist) is stiffened as a doubled, interfaced band is, so that the waist keeps its
    /// length under the skirt's weight instead of stretching over the hips (the
    /// 95th-percentile man's knit skirt stretched its waist 16 % and slid to the floor).
    /// Pants hang from the crotch and keep their waist as cut (docs/dressing.md). Used by
    /// dress_and_drape and dress_and_drape_outfit (they know the pattern; see
    /// waistband_faces). Width 0 turns it off.
    double waistband_width_cm = 3.0;         ///< strip width from the waist edge, >= 0
    double waistband_stretching_factor = 4;  ///< band stretching stiffness / fabric's, >= 1
    /// Called after every step; return false to cancel. May be empty.
    std::function<bool(const DrapeProgress&)> on_progress;

    static cloth::SimulatorOptions default_simulator_options();
    bool is_valid(std::string* why = nullptr) const;
};

enum class DrapeTermination {
    converged,           ///< seams closed, settled, static equilibrium reached
    not_settled,         ///< max_steps ran out before seams closed and the cloth came to rest
    static_failed,       ///< the final equilibrium solve did not converge
    step_failed,         ///< a simulation step failed (non-finite or line search)
    cancelled,           ///< on_progress (or the simulator's on_iteration) returned false
};

struct DrapeSummary {
    DrapeTermination termination = DrapeTermination::step_failed;
    std::string message;
    double seam_gap_max_m = 0;        ///< largest stitch gap at the end
    double penetration_max_m = 0;     ///< deepest garment vertex inside the body (>= 0)
    int vertices_inside = 0;          ///< garment vertices inside the body
    int self_intersections = 0;       ///< intersecting non-adjacent triangle pairs
    /// The same three at the initial (dressed) positions, to tell dressing from draping faults.
    double initial_penetration_max_m = 0;
    double initial_seam_gap_max_m = 0;
    int initial_self_intersections = 0;
    bool converged = false;           ///< termination == converged
    int vertices = 0;
    int stitches = 0;
    double mass_kg = 0;               ///< of the cloth: Σ ρ A over its faces' fabrics
    bool welded = false;              ///< the seams were welded (see DrapeOptions::weld_seams)
    /// The rest state came from the stiffened contact (DrapeOptions::contact_stiffening).
    bool contact_stiffened = false;
    /// Crossing triangle pairs of the rest state removed by DrapeOptions::repair_crossings.
    int crossings_repaired = 0;
    int steps_to_weld = -1;           ///< step at which they were, -1: never
    int steps = 0;                    ///< dynamic steps taken (untangling included)
    int untangle_steps = 0;           ///< of which without self-contact
    int steps_to_close_seams = -1;    ///< first step with all gaps below tolerance, -1: never
    double kinetic_energy_j = 0;      ///< at the end of the dynamic phase
    double static_gradient_n = 0;     ///< |gradient|inf after the static solve (0 if none)
    int static_newton_iterations = 0;
    /// Mean sink of the garment's vertices along gravity from the dressed state, minus the
    /// body's mean sink along its path (m; negative: rose). See DrapeOptions::max_mean_drop_m.
    double mean_drop_m = 0;
    double max_mean_drop_m = 0.25;          ///< copied from the options, for usable()
    double penetration_tolerance_m = 1e-3;  ///< copied from the options, for usable()
    double seam_gap_tolerance_m = 1e-3;     ///< copied from the options, for usable()
    double seconds = 0;

    /// Converged with closed seams, no penetration beyond the tolerance and no
    /// self-intersection (the acceptance criteria), and not slid down the body
    /// (mean_drop_m <= max_mean_drop_m).
    bool usable() const {
        return converged && seam_gap_max_m < seam_gap_tolerance_m &&
               penetration_max_m <= penetration_tolerance_m && self_intersections == 0 &&
               mean_drop_m <= max_mean_drop_m;
    }
    /// The checks of usable() that fail, each with its value and limit, joined by "; "
    /// (e.g. "not converged (not settled); mean drop 31.2 cm > 25 cm"); empty when usable().
    std::string failed_checks() const;
    std::string brief_report() const;
};

/// The stitches of a garment mesh for the simulator: one per GarmentMesh::stitches pair,
/// its length the seam length the pair stands for (half the pattern lengths of the two
/// boundary segments at vertex a).
std::vector<cloth::Stitch> garment_stitches(const GarmentMesh& mesh);

/// The faces of a skirt's waistband: on the panels of a circle skirt, those whose pattern
/// centroid lies within `width_cm` of the panel's waist, its open edge (in no seam) highest
/// in the panel's pattern frame. A dress's skirt is sewn to the bodice at its top, so it has
/// none; other patterns (pants, tops) have none. Sorted face indices.
/// \throw drape::InvalidInput if width_cm < 0 or not finite, or mesh is not of pattern.
std::vector<int> waistband_faces(const Pattern& pattern, const GarmentMesh& mesh, double width_cm);

/// `material` as a waistband of it (DrapeOptions::waistband_stretching_factor): the stretching
/// scale multiplied by `stretching_factor` (>= 1).
cloth::Material waistband_material(const cloth::Material& material, double stretching_factor);

/// Sews and drapes `mesh` on a body: a cloth simulation from `initial_positions` (as
/// dress_garment returns them) with the body as obstacle, the seams pulled closed, the
/// cloth settled under gravity, then a static solve to equilibrium.
/// \param mesh the meshed pattern (its pattern coordinates give the rest shape).
/// \param initial_positions #V x 3, world, metres.
/// \param body_vertices #B x 3, world, metres (the posed body); \param body_faces #F x 3,
///        counter-clockwise seen from outside.
/// \param out_positions receives #V x 3 draped positions (world, metres), also when the
///        summary is not usable (the last state).
/// \throw drape::InvalidInput if the options, material, mesh, positions or body are invalid.
DrapeSummary drape_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                           const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3i& body_faces,
                           const cloth::Material& material, const DrapeOptions& options,
                           Eigen::MatrixX3d& out_positions);

/// The same with a moving body: the garment is sewn on body_path.front() (the pose it was
/// dressed in), then the body moves through the path's states, evenly spaced over
/// options.body_motion_s, and the garment settles on body_path.back(). For draping in a
/// pose where dressing cannot start clean (arms down: a sleeve around an arm that touches
/// the torso) — dress in the rest A-pose, move to the pose (see pose_path()).
/// \param body_path >= 1 body states, each #B x 3 with the same faces.
/// \throw drape::InvalidInput as above, or if the path is empty or its shapes differ.
DrapeSummary drape_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                           const std::vector<Eigen::MatrixX3d>& body_path, const Eigen::MatrixX3i& body_faces,
                           const cloth::Material& material, const DrapeOptions& options,
                           Eigen::MatrixX3d& out_positions);

/// The same with a fabric per face (an outfit of garments of different fabrics): face f of
/// mesh.cloth is made of materials[face_material[f]] (cloth::Simulator's per-face
/// constructor; a hinge between two fabrics bends as its first face's). Welding the seams
/// keeps the faces, so face_material holds throughout.
/// \param materials >= 1, each valid; \param face_material #F indices into materials.
/// \throw drape::InvalidInput as above, or if a material, the size of face_material or one
/// of its indices (named) is invalid.
DrapeSummary drape_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& initial_positions,
                           const std::vector<Eigen::MatrixX3d>& body_path, const Eigen::MatrixX3i& body_faces,
                           const std::vector<cloth::Material>& materials, const std::vector<int>& face_material,
                           const DrapeOptions& options, Eigen::MatrixX3d& out_positions);

/// Dresses `pattern`'s mesh on the shaped body and drapes it in `pose`: dressed in the rest
/// A-pose (where dressing starts without crossings: docs/dressing.md), sewn there, then the
/// body moves to `pose` over options.body_motion_s (11 interpolated poses) and the garment
/// settles. With `pose` = the rest pose the body does not move.
/// \param dressing receives the dressing summary if not null.
/// \throw drape::InvalidInput as dress_garment and drape_garment.
DrapeSummary dress_and_drape(const Pattern& pattern, const GarmentMesh& mesh, const body::BodyModel& model,
                             const body::ShapedBody& shaped, const body::Pose& pose, const cloth::Material& material,
                             const DressingOptions& dressing_options, const DrapeOptions& options,
                             Eigen::MatrixX3d& out_positions, DressingSummary* dressing = nullptr);

/// An outfit: several garments dressed and draped together in one simulation (here one
/// fabric for all; the overload below takes one per garment), layered in the given order,
/// inner first (e.g. pants, then a t-shirt worn over their waistband). Each garment is
/// dressed alone in the rest A-pose; every later garment is then moved radially (about the
/// trunk axis, so it keeps its own shape and cannot cross itself) to lie at least the contact thickness + 1 mm outside the dressed garments
/// before it; the garments are sewn, welded and moved to `pose` together, their layers kept
/// apart by self-contact.
/// \param out_positions receives one #V_i x 3 matrix per garment.
/// \param dressing receives one dressing summary per garment if not null.
/// \return the summary of the joint simulation (vertices, stitches: of the whole outfit;
///         self-intersections include those between garments).
/// \throw drape::InvalidInput if patterns and meshes differ in number, or as dress_and_drape.
DrapeSummary dress_and_drape_outfit(const std::vector<Pattern>& patterns, const std::vector<GarmentMesh>& meshes,
                                    const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                    const cloth::Material& material, const DressingOptions& dressing_options,
                                    const DrapeOptions& options, std::vector<Eigen::MatrixX3d>& out_positions,
                                    std::vector<DressingSummary>* dressing = nullptr);

/// The same with one fabric per garment: garment g is made of materials[g] (its stretching,
/// bending and density; no hinge joins two garments, they only touch through self-contact).
/// \param materials one per garment, in the order of `patterns`.
/// \throw drape::InvalidInput as above, or if materials is not one per garment or one is
/// invalid (naming the garment).
DrapeSummary dress_and_drape_outfit(const std::vector<Pattern>& patterns, const std::vector<GarmentMesh>& meshes,
                                    const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                    const std::vector<cloth::Material>& materials,
                                    const DressingOptions& dressing_options, const DrapeOptions& options,
                                    std::vector<Eigen::MatrixX3d>& out_positions,
                                    std::vector<DressingSummary>* dressing = nullptr);

}  // namespace drape::garment
