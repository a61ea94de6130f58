// Virtual try-on (paper sections 6.2 and 7, "Image-Based Garment Virtual Try-On"): garments
// recovered from one photo (or a synthetic scene's truth) put on another body, in another pose
// or another photo. Each garment keeps its fabric; its sizing G is graded to the new body
// (garment::grade_sizing); the outfit is dressed and draped through garment::dress_outfit. For
// a photo target the body is fitted from that photo first, the draped garments are rendered
// over it with the person's arms, head and hair in front, and a mask says where the person's
// own garment still shows beyond the new one (docs/tryon.md).
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/fit_body.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/cloth/material.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/grading.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/recover/outfit_meshes.hpp>
#include <drape/recover/recover.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/segmentation.hpp>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace drape::recover {

/// One garment to try on, as recovered (io::read_recovery_folder gives these).
struct TryOnGarment {
    garment::GarmentType type = garment::GarmentType::tshirt;
    std::string name;                     ///< the recovered choice ("shorts", "tank", ...) or the type's name
    garment::GarmentSizing sizing;        ///< G as made for `source_body`
    cloth::Material material;             ///< kept as is (the paper does not change it)
    std::string base_fabric;
    body::SemanticRequest source_body;    ///< the body the garment was recovered on
    std::string source;                   ///< where it came from (a result folder), for reports
};

/// The body to dress: a semantic body in a pose, or a person in a photo.
struct TryOnTarget {
    /// A body target: the semantic request (completed by the shape prior) and its pose.
    std::optional<body::SemanticRequest> body;
    body::Pose pose = body::named_pose(body::NamedPose::a_pose);
    /// A photo target (used when `body` is empty): the photo (CV_8UC3 BGR), its 14 joints and
    /// optional strokes (class ids, as RecoverInputs::strokes; empty: automatic segmentation).
    cv::Mat photo_bgr;
    vision::Joints joints;
    cv::Mat strokes;
    std::optional<double> height_m;       ///< known stature of the person in the photo
    std::optional<body::Gender> gender;
};

struct TryOnInputs {
    std::vector<TryOnGarment> garments;   ///< >= 1, inner first (pants, then a t-shirt over them)
    TryOnTarget target;
};

enum class TryOnStage { fitting_body, grading, draping, rendering };
std::string tryon_stage_name(TryOnStage s);

struct TryOnProgress {
    TryOnStage stage = TryOnStage::grading;
    int step = 0;                 ///< simulation step while draping, else 0
    double seconds = 0;           ///< since tryon() began
};

struct TryOnOptions {
    double edge_cm = 3.0;         ///< mesh edge of the drape (recover's output edge), (0.5, 20]
    int max_drape_steps = 400;    ///< dynamic steps of the drape, >= 1
    int threads = 2;              ///< body fit and overlay workers, >= 1
    garment::GradingOptions grading;
    /// False: stop after grading (TryOnTermination::graded; no mesh, drape or render), for
    /// the grading figures of every body at once.
    bool drape = true;
    /// Overlay render samples per pixel (photo targets).
    int overlay_samples = 8;
    /// Called between stages and after every simulation step: return false to stop (the
    /// summary then says cancelled).
    std::function<bool(const TryOnProgress&)> on_progress;
    bool is_valid(std::string* why = nullptr) const;
};

/// One garment on the new body.
struct TriedOnGarment {
    TryOnGarment source;
    garment::GarmentSizing sizing;        ///< graded G
    garment::GradingSummary grading;
    garment::Pattern original_pattern;    ///< of source.sizing
    garment::Pattern pattern;             ///< of the graded G
    garment::GarmentMesh mesh;
    Eigen::MatrixX3d positions;           ///< draped, world metres
    DrapeState drape;
    int class_id = 0;                     ///< labels.txt id (t-shirt 51, pants 31, skirt 42, dress 14)
};

struct TryOnResult {
    body::SemanticShape shape;            ///< the target body's semantic shape
    body::ShapedBody shaped;              ///< at rest
    body::Pose pose;                      ///< as draped (arms cleared if needed)
    Eigen::MatrixXd body_vertices;        ///< posed (#B x 3, world metres)
    std::vector<TriedOnGarment> garments; ///< inner first
    // Photo targets only:
    vision::Segmentation segmentation;    ///< of the target photo
    body::BodyFit fit;                    ///< pose, shape, camera
    cv::Mat overlay;                      ///< CV_8UC3: the new garments over the photo, arms, head and hair in front
    cv::Mat mask;                         ///< CV_8UC1 class ids of the try-on projected (as recover's mask.png)
    /// CV_8UC1 0/255: where the photo shows the person's own garment and the new outfit does
    /// not cover it (an application may inpaint or warn there).
    cv::Mat own_garment_mask;
    double own_garment_fraction = 0;      ///< own_garment_mask's pixels / the own garments' pixels
};

enum class TryOnTermination {
    draped,           ///< draped; see each garment's drape state and grading
    graded,           ///< graded only (TryOnOptions::drape false)
    body_fit_failed,  ///< the photo's body could not be fitted (or segmented)
    drape_failed,     ///< a pattern could not be meshed
    cancelled,
};

struct TryOnSummary {
    TryOnTermination termination = TryOnTermination::drape_failed;
    std::string message;
    garment::DrapeSummary drape;
    double seconds_fit = 0, seconds_grade = 0, seconds_drape = 0, seconds_render = 0, seconds = 0;
    /// Draped, every garment's drape usable (converged, seams closed, penetration within
    /// 1 mm, no self-intersection) and every grading usable (style within tolerance).
    bool usable(const TryOnResult& result) const;
    std::string brief_report() const;
};

/// The labels.txt class id the try-on gives a garment type (t-shirt 51, pants 31, skirt 42,
/// dress 14).
int tryon_class_id(garment::GarmentType type);

/// Puts the garments on the target.
/// \throw drape::InvalidInput for no garment, invalid options, a garment whose sizing does not
///        make a valid pattern or whose material is invalid (naming the garment), a photo
///        target with an empty or non-BGR photo, joints outside it or strokes of another size,
///        or an outfit the templates cannot layer (dress_outfit).
TryOnSummary tryon(const body::BodyModel& model, const TryOnInputs& inputs, const TryOnOptions& options,
                   TryOnResult& out);

/// The try-on's body and garments as plain meshes (for the glb, mask and overlay).
OutfitMeshes tryon_outfit_meshes(const body::BodyModel& model, const TryOnResult& result);

}  // namespace drape::recover
