// Animation of recovered garments (paper section 7): the garments, as recovered on a body,
// dressed on that body and animated along a motion (a built-in walk or a BVH file), with
// optional wind. The one call behind `drape animate` and drape_animate (C API): shape the
// body, read the motion, dress and drape the outfit (garment::dress_outfit), animate it
// (garment::animate_outfit). docs/animation.md.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/motion.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/cloth/material.hpp>
#include <drape/garment/animate.hpp>
#include <drape/garment/dress_outfit.hpp>
#include <drape/garment/garment_sizing.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace drape::recover {

/// One garment to animate, as recovered (io::read_recovery_folder gives these).
struct AnimatedGarmentSource {
    garment::GarmentType type = garment::GarmentType::skirt;
    garment::GarmentSizing sizing;
    cloth::Material material;
};

struct AnimateGarmentsInputs {
    std::vector<AnimatedGarmentSource> garments;  ///< >= 1, inner first
    body::SemanticRequest body;                   ///< the body they were recovered on
    body::Pose pose;                              ///< the pose they are draped in first
    /// "walk" (body::walk_cycle) or the path of a .bvh file (body::load_bvh_motion with the
    /// standard joint map; a motion shorter than `seconds` holds its last pose).
    std::string motion = "walk";
};

enum class AnimateGarmentsStage { draping, blending, animating };

struct AnimateGarmentsProgress {
    AnimateGarmentsStage stage = AnimateGarmentsStage::draping;
    int step = 0;          ///< draping: the simulation step; else the frame done
    int frames = 0;        ///< frames of the phase (blending, animating), else 0
    double seconds = 0;    ///< since the call began (draping), or of the animation
};

struct AnimateGarmentsOptions {
    double seconds = 5;    ///< length, (0, 120] s
    double fps = 30;       ///< frame rate, (0, 240]
    double edge_cm = 3.0;  ///< mesh edge of the garments, (0, 20] cm (the recovery's output edge)
    Eigen::Vector3d wind_m_per_s = Eigen::Vector3d::Zero();  ///< world frame, finite
    /// Called after every drape step and every animation frame: return false to stop (the
    /// summary then says cancelled).
    std::function<bool(const AnimateGarmentsProgress&)> on_progress;
    bool is_valid(std::string* why = nullptr) const;
};

struct AnimateGarmentsResult {
    body::ShapedBody shaped;              ///< the body at rest
    garment::DressedOutfit outfit;        ///< dressed and draped in inputs.pose
    garment::AnimatedOutfit animation;    ///< the body's motion and each garment's frames
    std::vector<std::string> names;       ///< per garment: "<type>_<index>" (glTF node names)
    body::BvhRetargetSummary bvh;         ///< for a BVH motion
    double motion_seconds = 0;            ///< the motion's own duration (a BVH may be shorter)
};

enum class AnimateGarmentsTermination {
    animated,       ///< every frame made; see animate.usable()
    drape_failed,   ///< the outfit could not be dressed and draped (message)
    stopped,        ///< the animation stopped early (a failed step, an explosion; frames kept)
    cancelled,
};

struct AnimateGarmentsSummary {
    AnimateGarmentsTermination termination = AnimateGarmentsTermination::drape_failed;
    std::string message;
    garment::DressOutfitSummary dress;
    garment::AnimateSummary animate;
    bool usable() const { return termination == AnimateGarmentsTermination::animated && animate.usable(); }
    std::string brief_report() const;
};

/// Dresses the garments on their body and animates them.
/// \throw drape::InvalidInput for no garment, invalid options, a motion that is neither
///        "walk" nor a .bvh file, a BVH that does not parse or whose joints do not fit (naming
///        the file), a body that cannot be shaped; drape::IoError for an unreadable file.
AnimateGarmentsSummary animate_garments(const body::BodyModel& model, const AnimateGarmentsInputs& inputs,
                                        const AnimateGarmentsOptions& options, AnimateGarmentsResult& out);

}  // namespace drape::recover
