// Initial garment registration (paper section 4.3): the meshed pattern is wrapped around
// the body at rest, its skeleton rigidly aligned to the body's joints, skinned to the body
// pose (linear blend skinning with weights copied from the nearest body vertices), and
// pushed out of the body with an as-rigid-as-possible deformation under a
// non-penetration constraint.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/garment/untangle.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace drape::garment {

struct DressingOptions {
    double clearance_m = 0.008;       ///< garment-body gap enforced, (0, 0.1] m
    int max_iterations = 15;          ///< push-out + ARAP rounds, >= 1
    double constraint_weight = 50.0;  ///< weight of the push targets in the ARAP solve, > 0
    /// Last step: crossings left by wrapping and push-out are separated (untangle_garment).
    bool untangle = true;
    UntangleOptions untangle_options;
    /// Guarded passes of the radial placement, [0, 8]. 0 = automatic: 4 for a garment with
    /// sleeves (the two sides of an armhole start on one line); 1 otherwise, and 4 as well
    /// when one pass leaves crossings (the state with fewer is kept). dress_and_drape_outfit
    /// also re-dresses the garments without sleeves with 4 when the layered outfit crosses.
    int placement_passes = 0;
    bool is_valid(std::string* why = nullptr) const;
};

enum class DressingTermination { converged, penetration_left };

struct DressingSummary {
    DressingTermination termination = DressingTermination::converged;
    std::string message;
    double alignment_rms_m = 0;   ///< RMS of ||T q_i - t_i|| over the garment joints
    /// A circle skirt's waist is placed where it fits (the highest trunk section from the
    /// spine joint down whose girth is at most the skirt's waist, else the narrowest): how far
    /// below the spine joint (m; 0 for other garments).
    double skirt_waist_drop_m = 0;
    int iterations = 0;           ///< push-out rounds used
    int vertices_pushed = 0;      ///< vertices that were inside or too close at some round
    int vertices_inside = 0;      ///< after registration (inside test on the posed body)
    double max_seam_gap_m = 0;    ///< largest distance between stitched vertices
    double wrapped_seam_gap_m = 0;  ///< the same after wrapping and skinning, before push-out
    int self_intersections = 0;   ///< dressed state, as check_garment_state counts them
    double max_penetration_m = 0; ///< dressed state: deepest vertex inside the posed body
    double min_layer_distance_m = 0;  ///< dressed state: see GarmentStateCheck
    UntangleSummary untangle;     ///< the last step (crossings before and after it)
    /// How far down its arm the lowest sleeve cap starts (m; 0 without sleeves): the nearest
    /// place, from 4 cm in 1 cm steps, where the whole sleeve lies 6 mm outside the torso
    /// panels; infinity if none within 15 cm (the cap then starts 15 cm down, partly inside
    /// them). Sewing drags the cap that far up to its armhole.
    double sleeve_cap_offset_m = 0;
    /// dress_for_drape: how far both arms were raised from the rest A-pose to dress (deg).
    double arms_raised_deg = 0;
    double seconds = 0;
    bool usable() const { return vertices_inside == 0; }
    std::string brief_report() const;
};

/// Geometric checks of a garment state on a body: what the simulator's contact report
/// measures, plus how close the garment's layers are (a state to start a simulation from
/// should have no self-intersection, no penetration and layers at least the contact
/// thickness apart, else penalty self-contact locks the crossings in).
struct GarmentStateCheck {
    /// Intersecting triangle pairs that share no vertex, stitched partners counted as one
    /// vertex (as cloth::Simulator::contact_report counts them).
    int self_intersections = 0;
    double max_penetration_m = 0;  ///< deepest garment vertex inside the body (>= 0)
    int vertices_inside = 0;       ///< vertices with a negative signed distance to the body
    /// Smallest distance from a vertex to a triangle it may touch in simulation: not its own
    /// or a stitched partner's triangle, nor a triangle of its own panel within
    /// 2 x layer_gap_m in pattern space (the simulator's rest-neighbour filter). Infinity if
    /// none lies within 2 cm.
    double min_layer_distance_m = 0;
    int close_pairs = 0;           ///< such vertex–triangle pairs closer than layer_gap_m
    double max_seam_gap_m = 0;     ///< largest distance between stitched vertices
    /// No self-intersection, nothing deeper than `penetration_m` and no close pair.
    bool clean(double penetration_m = 0.001) const {
        return self_intersections == 0 && max_penetration_m <= penetration_m && close_pairs == 0;
    }
    std::string brief_report() const;
};

/// Checks `positions` (#V x 3, world, metres) of `mesh` against the body mesh.
/// \param layer_gap_m the contact thickness the state should keep between layers, > 0.
/// \throw drape::InvalidInput on size mismatches or non-finite positions.
GarmentStateCheck check_garment_state(const GarmentMesh& mesh, const Eigen::MatrixX3d& positions,
                                      const Eigen::MatrixX3d& body_vertices,
                                      const Eigen::MatrixX3i& body_faces, double layer_gap_m = 0.005);

/// The garment skeleton Q_c: the body joints a pattern's panels wrap around (torso chain
/// for torso panels, a leg chain per leg panel, an arm chain per sleeve).
std::vector<body::Joint> garment_skeleton_joints(const Pattern& pattern);

/// The rigid transform T minimising sum ||T q_i - t_i||² (Kabsch), rows of q and t paired.
/// \throw drape::InvalidInput if sizes differ or fewer than 1 row.
Eigen::Isometry3d rigid_align(const Eigen::MatrixX3d& q, const Eigen::MatrixX3d& t);

/// Initial 3D positions (#V x 3, world, metres) of `mesh` dressed on the shaped body in
/// `pose`. Panels of the built-in templates are wrapped on cylinders (cones for flared
/// panels) around the torso, leg and arm axes; panels of other patterns start at their
/// placement hints.
/// \throw drape::InvalidInput if the options, mesh or body are inconsistent.
DressingSummary dress_garment(const Pattern& pattern, const GarmentMesh& mesh,
                              const body::BodyModel& model, const body::ShapedBody& shaped,
                              const body::Pose& pose, const DressingOptions& options,
                              Eigen::MatrixX3d& positions);

/// A garment without sleeves is wrapped with its seams side by side, a few millimetres
/// apart; a dressed seam gap above this (a pants' crotch point left on the far side of the
/// other leg's panel by the push-out and untangling, 19 mm on ANSUR record 28192, whose
/// seams then took 400+ steps to close and crossed) makes dress_garment try the 4-pass
/// placement too and keep it if it has fewer crossings, or as many and a gap within this.
constexpr double kMaxSewnDressingSeamGapM = 0.005;

/// dress_for_drape raises the arms in steps of this much, at most kMaxDressingArmRaiseDeg,
/// until the dressed seam gap of a garment with sleeves is at most kMaxDressingSeamGapM.
constexpr double kDressingArmRaiseStepDeg = 5.0;
constexpr double kMaxDressingArmRaiseDeg = 30.0;
constexpr double kMaxDressingSeamGapM = 0.12;

/// The dressed state a drape starts from: dress_garment in the rest A-pose, or for a garment
/// with sleeves whose dressed seam gap there exceeds kMaxDressingSeamGapM, in the rest pose
/// with both arms raised sideways (raise_arms) by the smallest multiple of
/// kDressingArmRaiseStepDeg (at most kMaxDressingArmRaiseDeg) that brings it below. The
/// sleeves are placed where they lie clear of the torso panels, and the simulation sews the
/// caps to their armholes: on a heavy body whose arms lie against the trunk in the A-pose
/// they start 14-15 cm down the arm (seam gap 17.7 cm on a woman of 97 kg), and sewing
/// dragged the cap through the front panel at the armpit (crossings that stayed); with the
/// arms raised the cap starts nearer its armhole (10 deg: 11.4 cm). Garments without
/// sleeves are dressed in the rest pose. `dressing_pose` receives the pose dressed in, which
/// the drape's body path starts from; the summary's arms_raised_deg says how far.
/// \throw drape::InvalidInput as dress_garment.
DressingSummary dress_for_drape(const Pattern& pattern, const GarmentMesh& mesh, const body::BodyModel& model,
                                const body::ShapedBody& shaped, const DressingOptions& options,
                                Eigen::MatrixX3d& positions, body::Pose& dressing_pose);

/// The posed body vertices (#B x 3, world, metres) at `states` poses evenly spaced from
/// `from` to `to` (body::interpolate_pose), both included: the path drape_garment moves the
/// body along when a garment dressed in `from` is draped in `to`.
/// \throw drape::InvalidInput if states < 2 or a pose is invalid.
std::vector<Eigen::MatrixX3d> pose_path(const body::BodyModel& model, const body::ShapedBody& shaped,
                                        const body::Pose& from, const body::Pose& to, int states);

}  // namespace drape::garment
