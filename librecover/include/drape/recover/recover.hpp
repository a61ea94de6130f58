// Garment recovery from one photo (paper sections 5 and 6.1, Algorithms 1 and 2): the body
// from the photo fit, each garment's type, silhouette and wrinkle density from libvision, a
// starting sizing G from the image features and the fitted body, the dressing pipeline as
// the initial registration, then rounds of the sizing search (PSO on the silhouette
// distance) and the material search (L-BFGS on the mean curvature), and a final drape at the
// output resolution. The one pipeline that `drape recover`, the evaluations, try-on and the
// C API call.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/fit_body.hpp>
#include <drape/body/pose.hpp>
#include <drape/cloth/material.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/material_search.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/garment/sizing_search.hpp>
#include <drape/vision/garment_result.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/segmentation.hpp>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace drape::recover {

/// The garments a user can ask for. Each is made by one template (garment::GarmentType);
/// shorts, tank and longsleeve are variants of pants and the t-shirt (their starting sizing
/// and the parameters the search may move differ).
enum class GarmentChoice { skirt, pants, shorts, tshirt, tank, longsleeve, dress };

/// "skirt", "pants", "shorts", "tshirt", "tank", "longsleeve", "dress".
/// \throw drape::InvalidInput naming the value and the accepted names otherwise.
GarmentChoice garment_choice_from_name(const std::string& name);
std::string garment_choice_name(GarmentChoice c);
garment::GarmentType template_of(GarmentChoice c);

enum class Quality { fast, normal, fine };
/// "fast", "default" (or "normal"), "fine". \throw drape::InvalidInput otherwise.
Quality quality_from_name(const std::string& name);
std::string quality_name(Quality q);

/// What the stages are doing, for a progress display.
enum class Stage { segmenting, fitting_body, dressing, sizing, material, pose_material, final_drape, measuring };
std::string stage_name(Stage s);

struct RecoverProgress {
    Stage stage = Stage::segmenting;
    int garment = -1;              ///< index into the recovered garments, -1 = all / none
    int round = 0;                 ///< G/C alternation round (1-based), 0 outside them
    long evaluations = 0;          ///< drapes evaluated so far, all stages
    double best_objective = 0;     ///< of the current search (px² for sizing, relative² for material)
    double seconds = 0;            ///< since recover() began
    double eta_seconds = -1;       ///< estimated seconds left (-1 unknown)
};

struct RecoverInputs {
    cv::Mat image_bgr;             ///< the photo, CV_8UC3
    vision::Joints joints;         ///< its 14 joints, image frame
    /// User strokes as class ids (CV_8UC1, photo size, vision::kUnmarked = 255 where
    /// unmarked; vision::load_strokes decodes a coloured file). Empty: automatic segmentation.
    cv::Mat strokes;
    /// The garments to recover, inner first or in any order (outfit_layers orders them).
    /// Empty: those the segmentation finds (a dress, or an upper and a lower garment).
    std::vector<GarmentChoice> garments;
    std::optional<double> height_m;        ///< known stature
    std::optional<body::Gender> gender;    ///< known gender
};

/// What the material search matches (docs/material-estimation.md, "Two approaches").
enum class MaterialTarget {
    /// The mean curvature K that the calibrated mapping K(P) gives for the photo's wrinkle
    /// density P; L-BFGS on (K − K_target)² (curvature_calibration.hpp).
    calibrated_curvature,
    /// Analysis by synthesis: each candidate bending scale is draped and rendered with the
    /// fitted camera, and P is measured on the render by the photo's detector; the bending
    /// scale whose P matches the photo's is kept (a grid search: P is piecewise constant).
    wrinkle_synthesis,
};
/// Which drape the garments of the result are (DrapeState::source).
enum class OutputDrape {
    /// The output drape (dress_outfit afresh at final_edge_cm, the outfit together); a
    /// garment whose output drape is not usable, while the search's re-drape of its recovered
    /// sizing and material is, keeps that re-drape at search_edge_cm. More drapes usable
    /// (24 vs 17 of the 30 shared photos) but worse masks: not the default
    /// (docs/recovery.md, step 7).
    automatic,
    /// The output drape always, usable or not (the default: its masks measure better).
    output,
    /// The search's re-drapes only, at search_edge_cm: no output drape (quicker; a preview).
    search,
};
/// "auto", "output" or "search". \throw drape::InvalidInput otherwise.
OutputDrape output_drape_from_name(const std::string& name);
std::string output_drape_name(OutputDrape d);

/// "calibrated" or "synthesis". \throw drape::InvalidInput otherwise.
MaterialTarget material_target_from_name(const std::string& name);
std::string material_target_name(MaterialTarget t);

struct RecoverOptions {
    Quality quality = Quality::normal;
    int threads = 2;                       ///< workers for the particle swarm and the body fit, >= 1
    unsigned seed = 1;                     ///< the swarm's random draws
    /// Settings by quality (apply_quality fills them; they may be changed after):
    double search_edge_cm = 6.0;           ///< mesh edge while searching G and C
    double final_edge_cm = 3.0;            ///< mesh edge of the output drape
    int particles = 40;                    ///< the paper's swarm size
    int generations = 6;                   ///< per sizing search
    int rounds = 2;                        ///< G/C alternations at most (the paper: about 4)
    int max_drape_steps = 400;             ///< dynamic steps of a full drape (dress_outfit)
    /// Upper arms raised more than this above hanging (hands on the head or in the hair) are
    /// lowered to it before dressing (garment::lower_raised_arms): a top or dress is dragged
    /// up by its armholes on raised arms. The garments are draped, and the mask drawn, in
    /// that pose (RecoveryResult::pose); the photo fit's pose stays in RecoveryResult::fit.
    /// [0, 180]; 180 = off (docs/recovery.md).
    double max_arm_elevation_degrees = 90.0;
    /// The least ease (cm of girth over the fitted body) that the sizing search lets a
    /// garment's body girths reach (a top's chest and sleeve opening, a skirt's waist, pants'
    /// waist, hip and legs); the search starts at the proposal's ease (garment::Ease). Negative
    /// = the garment may be smaller than the body and stretch on it, as knits are worn.
    /// [-10, 10] cm (docs/recovery.md, "Sizing bounds").
    double min_ease_cm = 2.0;
    /// Which drape the result's garments are (docs/recovery.md, step 7).
    OutputDrape output_drape = OutputDrape::output;
    /// Estimate the material (false: keep the base fabric at bending ×1).
    bool estimate_material = true;
    /// The base fabric of the paper's material space (bending scale ×1…×100).
    std::string base_fabric = "gray-interlock";
    /// What the material search matches; the default is the approach that measured better on
    /// the synthetic scenes (docs/material-estimation.md).
    MaterialTarget material_target = MaterialTarget::calibrated_curvature;
    /// Samples per pixel of the renders of wrinkle_synthesis, 1..64.
    int synthesis_samples = 4;
    /// The joint material-pose search (paper Algorithm 2) after the G/C rounds: for each
    /// garment with a curvature target, the pose angles of the joints under it (about the
    /// three principal axes of each joint's parent frame, within ± pose_max_degrees) are
    /// searched by the particle swarm with C fixed, then C by L-BFGS with the pose fixed, on
    /// E = ((K − K_target) / K_target)² + pose_prior_weight · mean((Δθ / pose_max_degrees)²).
    /// The result is kept only where E falls. Off by default: it does not improve the
    /// curvature accuracy on the synthetic suite (docs/recovery.md, "Joint material-pose").
    bool joint_pose_material = false;
    int pose_particles = 12;               ///< swarm size of the pose search, >= 2
    int pose_generations = 3;              ///< its generations, >= 0
    double pose_max_degrees = 6.0;         ///< the box of each angle, (0, 30]
    double pose_prior_weight = 0.02;       ///< >= 0: keeps the pose near the photo fit's
    /// Called between stages and after every search generation / material iterate: return
    /// false to stop (the summary then says cancelled; nothing is half-made).
    std::function<bool(const RecoverProgress&)> on_progress;
    bool is_valid(std::string* why = nullptr) const;
};

/// Sets the quality-dependent fields of `options` (search and output edges, swarm size and
/// generations, rounds, drape steps) for options.quality; see docs/recovery.md.
void apply_quality(RecoverOptions& options);

/// The drape's state in the names of `drape dress`'s summary.
struct DrapeState {
    bool usable = false;
    bool converged = false;
    double penetration_max_m = 0;
    double seam_gap_max_m = 0;
    int self_intersections = 0;
    /// Which drape the garment's mesh and positions are: the output drape (dressed afresh at
    /// RecoverOptions::final_edge_cm, the outfit together), or, where that drape was not
    /// usable and the search's own re-drape of the same sizing and material was, that
    /// re-drape at search_edge_cm (on the body alone: crossings with the other garments are
    /// not checked). `edge_cm` is the mesh's target edge.
    enum class Source { output, search } source = Source::output;
    double edge_cm = 0;
    /// The output drape's own account, shared by the garments of an outfit, which are
    /// draped together: when the outfit's drape is not usable, which of its checks failed
    /// (garment::DrapeSummary::failed_checks: "the outfit's drape: not converged
    /// (not settled); 2 self-intersections"), then DrapeSummary::message in parentheses (why
    /// it is not at rest, what a repair at rest could not fix). A garment can have usable
    /// own checks (penetration, seams, crossings above) in an outfit that is not usable.
    /// Empty when the drape is usable and ended without a remark, and for the search's
    /// re-drapes.
    std::string message;
};

struct RecoveredGarment {
    GarmentChoice choice = GarmentChoice::tshirt;
    garment::GarmentType type = garment::GarmentType::tshirt;
    int label_id = 0;                      ///< the garment's class id in the photo's labels
    std::string class_name;                ///< its class name (labels.txt)
    /// False for a garment the templates cannot represent (a coat, a jumpsuit): the result
    /// is the closest template's, and `unsupported_reason` says why.
    bool supported = true;
    std::string unsupported_reason;
    garment::GarmentSizing initial_sizing; ///< from the image features and the body
    garment::GarmentSizing sizing;         ///< recovered G
    cloth::Material material;              ///< the recovered fabric (base tables × scales)
    std::string base_fabric;               ///< the base fabric's name
    double bending_low = 0, bending_high = 0;  ///< confidence range of the bending scale
    std::string nearest_fabric;            ///< the measured fabric nearest to the recovered one
    double wrinkle_density_per_m2 = 0;     ///< P measured in the photo
    double target_curvature_per_m = 0;     ///< K(P): the material search's target
    double mean_curvature_per_m = 0;       ///< K of the output drape
    double silhouette_rms_px = 0;          ///< final silhouette distance (RMS, both sides)
    std::vector<double> sizing_history;    ///< best silhouette energy (px²) after each round's search
    std::vector<double> material_history;  ///< (K − K_target)² / K_target² after each round's search
    /// E of the joint material-pose search: before it, then after its pose and material steps
    /// (empty when it did not run).
    std::vector<double> joint_history;
    double seconds_sizing = 0, seconds_material = 0;
    garment::Pattern pattern;              ///< of `sizing`
    garment::GarmentMesh mesh;             ///< output resolution
    Eigen::MatrixX3d positions;            ///< draped, world metres
    DrapeState drape;
};

struct RecoveryResult {
    vision::Segmentation segmentation;
    std::vector<vision::GarmentResult> seen;    ///< libvision's description of every garment class
    body::BodyFit fit;                          ///< pose, semantic shape, camera
    /// The body fit's mean distance of the fitted joints to the given ones, % of the
    /// skeleton's body height (vision::Joints::body_height_px).
    double joint_error_percent = 0;
    body::ShapedBody shaped;
    Eigen::MatrixXd body_vertices;              ///< posed as draped (#B x 3, world metres)
    body::Pose pose;                            ///< the pose draped in (arms cleared if needed)
    /// How the draping pose differs from the fit's: raised arms lowered to
    /// RecoverOptions::max_arm_elevation_degrees, then arms that skinning passed into the
    /// trunk turned clear of it by the turn that changes their image least (seen from the
    /// camera, +Z: a swing in depth and/or an outward turn; garment::ArmClearanceOptions).
    garment::ArmLoweringSummary arms_lowered;
    garment::ArmClearanceSummary arms_cleared;
    std::vector<RecoveredGarment> garments;     ///< inner first
    /// The recovered body and garments projected with the fitted camera, with occlusion, at
    /// the photo's size: 41 (skin) for the body, each garment's class id, 0 elsewhere.
    cv::Mat mask;
};

enum class RecoverTermination {
    recovered,         ///< every garment recovered; see each garment's drape state
    no_garment,        ///< the segmentation found no garment (or none of those asked for)
    body_fit_failed,   ///< the body could not be fitted (message says why)
    drape_failed,      ///< the final drape could not be made (meshing failed)
    cancelled,         ///< on_progress returned false
};

struct RecoverSummary {
    RecoverTermination termination = RecoverTermination::no_garment;
    std::string message;
    long evaluations = 0;              ///< candidate drapes, all searches
    double seconds_segment = 0, seconds_fit = 0, seconds_dress = 0, seconds_sizing = 0, seconds_material = 0,
           seconds_final = 0, seconds = 0;
    /// Recovered, and every garment's final drape is usable (converged, seams closed, no
    /// penetration beyond 1 mm, no self-intersection).
    bool usable(const RecoveryResult& result) const;
    std::string brief_report() const;
};

/// Recovers the body and every garment of one photo.
/// Expected failures (no garment, a body that cannot be fitted, a cancel) are in the
/// summary; `out` holds what was made up to there.
/// \throw drape::InvalidInput for an empty or non-BGR image, joints outside the image,
///        strokes of another size or type, an invalid option (naming it), or a garment asked
///        for twice / an outfit the templates cannot layer.
RecoverSummary recover(const body::BodyModel& model, const RecoverInputs& inputs, const RecoverOptions& options,
                       RecoveryResult& out);

}  // namespace drape::recover
