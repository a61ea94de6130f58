// One outfit pipeline: body -> sizing -> pattern -> mesh -> dress -> drape -> check. The
// chain that `drape dress`, `drape eval-dress`, `drape synth` and recovery from a photo call.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/cloth/material.hpp>
#include <drape/garment/arm_clearance.hpp>
#include <drape/garment/drape_garment.hpp>
#include <drape/garment/dressing.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace drape::garment {

/// One garment of an outfit.
struct GarmentRequest {
    GarmentType type = GarmentType::skirt;
    /// The sizing to make; its type must be `type`. Empty: proposed from the body
    /// (proposed_sizing with the body's measurements, a top fitted to its arms and neck).
    std::optional<GarmentSizing> sizing;
    cloth::Material material;  ///< the garment's fabric
};

struct DressOutfitOptions {
    MeshOptions mesh;            ///< meshing of every pattern (target edge etc.)
    DressingOptions dressing;    ///< dressing of every garment
    /// The draping. Its on_progress is called after every simulation step: return false to
    /// cancel (the summary then says DressOutfitTermination::cancelled).
    DrapeOptions drape;
    /// Raise each arm just clear of the trunk before draping (clear_arms_from_trunk): where
    /// skinning passed an arm into the torso no garment vertex can be outside both. Off:
    /// the pose is draped as given.
    bool clear_arms = true;
    ArmClearanceOptions arm_clearance;
    bool is_valid(std::string* why = nullptr) const;
};

/// What dress_outfit made, one entry per garment in the order requested.
struct DressedOutfit {
    std::vector<GarmentSizing> sizings;         ///< as given or proposed
    std::vector<Pattern> patterns;
    std::vector<GarmentMesh> meshes;
    std::vector<MeshSummary> meshing;
    std::vector<DressingSummary> dressing;      ///< each garment's dressing in the rest A-pose
    std::vector<Eigen::MatrixX3d> positions;    ///< draped, #V_i x 3, world, metres
    /// check_garment_state of each draped garment on the posed body (alone: crossings
    /// between garments are in DressOutfitSummary::drape).
    std::vector<GarmentStateCheck> checks;
    body::Pose pose;                            ///< the pose draped in (arms cleared if asked)
    ArmClearanceSummary arms;                   ///< the arm clearance (zero if not asked)
    Eigen::MatrixX3d body_vertices;             ///< the body posed in `pose`, #B x 3, world
};

enum class DressOutfitTermination {
    draped,          ///< the simulation ran to its end; see drape.termination and usable()
    meshing_failed,  ///< a pattern could not be meshed (message names the garment)
    cancelled,       ///< options.drape.on_progress returned false
};

struct DressOutfitSummary {
    DressOutfitTermination termination = DressOutfitTermination::meshing_failed;
    std::string message;
    /// The joint simulation (one garment: dress_and_drape; several: dress_and_drape_outfit):
    /// vertices, stitches and self-intersections of the whole outfit.
    DrapeSummary drape;
    int garments = 0;
    int vertices = 0;          ///< all garments
    int faces = 0;             ///< all garments
    double seconds_mesh = 0;   ///< meshing, all garments
    double seconds_dress = 0;  ///< dressing, all garments
    double seconds_drape = 0;  ///< the simulation (drape.seconds)
    double seconds = 0;        ///< the whole call

    /// Draped, and the simulation's own criteria hold (DrapeSummary::usable()).
    bool usable() const { return termination == DressOutfitTermination::draped && drape.usable(); }
    /// Every garment's independent state check (DressedOutfit::checks) is within the drape
    /// tolerances: penetration <= penetration_tolerance_m, no self-intersection, every seam
    /// gap below seam_gap_tolerance_m. False if not draped.
    bool checks_pass(const DressedOutfit& outfit) const;
    std::string brief_report() const;
};

/// Dresses a body in an outfit and drapes it in `pose`: per garment the sizing (given or
/// proposed from the body), its pattern and mesh; then one garment is dressed and draped
/// with dress_and_drape, several together with dress_and_drape_outfit (layered in the given
/// order, inner first: e.g. pants, then a t-shirt over their waistband; each in its own
/// fabric); finally each draped garment is checked on the posed body (check_garment_state).
/// Expected failures (a pattern that cannot be meshed, a drape that does not settle, a
/// cancel) are in the summary; `out` holds what was made up to there.
/// \param shaped the rest body (body::shape_body or a fit).
/// \param pose the pose to drape in; the garments are dressed in the rest A-pose and the
///        body moves there (DrapeOptions::body_motion_s).
/// \param garments >= 1, inner first.
/// \throw drape::InvalidInput if garments is empty, options are invalid, a given sizing's
///        type differs from its garment's type or its pattern is invalid (naming the
///        garment), a material is invalid, or as dress_and_drape(_outfit).
DressOutfitSummary dress_outfit(const body::BodyModel& model, const body::ShapedBody& shaped, const body::Pose& pose,
                                const std::vector<GarmentRequest>& garments, const DressOutfitOptions& options,
                                DressedOutfit& out);

}  // namespace drape::garment
