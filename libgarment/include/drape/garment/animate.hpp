// Animating a dressed outfit (paper section 7): the draped garments follow a body motion in
// a dynamic cloth simulation with the moving body as obstacle, optionally in wind, with
// per-frame checks of what the acceptance measures (docs/animation.md).
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/motion.hpp>
#include <drape/cloth/material.hpp>
#include <drape/cloth/simulator.hpp>
#include <drape/garment/dress_outfit.hpp>

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace drape::garment {

/// Passed to AnimateOptions::on_progress after every frame (and every blend frame).
struct AnimateProgress {
    bool blending = false;  ///< still moving from the draped pose into the motion
    int frame = 0;          ///< frames done (of the phase)
    int frames = 0;         ///< frames in the phase
    double seconds = 0;     ///< wall time so far
};

struct AnimateOptions {
    double fps = 30;        ///< output frame rate, > 0
    /// Length of the animation (s): the motion is resampled at fps over this; 0 = the
    /// motion's whole duration. >= 0.
    double seconds = 0;
    /// Before the first frame, the body moves from the pose the outfit was draped in to the
    /// motion's first pose over this time (s, smoothstep, simulated, not output), >= 0. The
    /// cloth then gets the root's velocity of the motion's first frame (a walk starts at
    /// walking speed, not from rest).
    double blend_s = 0.5;
    /// Simulation steps per frame (the same for the whole run): enough that in the motion's
    /// fastest frame no body vertex moves farther than max_body_step_m in one step, within
    /// [min_substeps, the cap]. The cap is max_substeps per 1/30 s of motion: a frame of
    /// 1/fps s gets at most ceil(max_substeps · 30 / fps) steps (8 at 30 fps, 16 at 15 fps), so
    /// the shortest step (4.2 ms by default) does not depend on the frame rate; a fixed count
    /// let the body move 10 mm per step at 15 fps, through the 5 mm contact layer (a skirt
    /// walking 0.4 s at a 4 cm edge: 57 mm deep, 4 crossings; now as at 30 fps).
    /// (Leaving the root's translation out, as the cloth keeps its speed by inertia, was
    /// tried: with air drag the skirt fell behind and the legs walked 4-6 cm into it at 4
    /// steps per 15 fps frame.)
    double max_body_step_m = 5e-3;
    int min_substeps = 2;
    int max_substeps = 8;
    /// The simulator: DrapeOptions::default_simulator_options() with gravity along −Y, 8
    /// Newton iterations per step, light air drag (0.5 N·s/m³: a skirt walking at 1 m/s is
    /// not blown back as by the draping's 2) and the friction Hessian majorized for slides
    /// over 0.5 mm per step (friction_majorize_slip_m). Its time step is set from fps and
    /// substeps.
    cloth::SimulatorOptions simulator = default_simulator_options();
    Eigen::Vector3d wind_m_per_s = Eigen::Vector3d::Zero();  ///< world frame, m/s
    /// A vertex faster than this (m/s) means the simulation exploded: the run stops.
    double explosion_speed_m_per_s = 30;
    /// Skirt waistbands stiffened as in draping (DrapeOptions::waistband_width_cm, factor).
    double waistband_width_cm = 3.0;
    double waistband_stretching_factor = 4;
    double penetration_tolerance_m = 2e-3;  ///< `usable()` allows this much in every frame, > 0
    /// `usable()` allows a garment to sink this far down the body (AnimationFrameCheck::
    /// max_slip_m), > 0. 5 cm: more than a waistband's width (3 cm here), so a waistband that
    /// slipped this far no longer sits where it was draped: the garment is falling off. Worn
    /// garments settle 1–3 cm in the 5 s walks (docs/animation.md).
    double slip_tolerance_m = 0.05;
    /// Called after every frame; return false to cancel. May be empty.
    std::function<bool(const AnimateProgress&)> on_progress;

    static cloth::SimulatorOptions default_simulator_options();
    bool is_valid(std::string* why = nullptr) const;
};

/// The checks of one output frame.
struct AnimationFrameCheck {
    double time_s = 0;
    double max_penetration_m = 0;  ///< deepest garment vertex inside the body (>= 0)
    int vertices_inside = 0;
    /// Where the deepest vertex is: the body joint that most drives the body surface it is
    /// under (its closest face's skin weights), e.g. "left_shoulder"; empty when none is inside.
    std::string deepest_joint;
    /// Intersecting pairs of non-adjacent cloth triangles of the whole outfit (within a
    /// garment and between garments): crossings.
    int self_intersections = 0;
    double max_speed_m_per_s = 0;  ///< fastest garment vertex
    /// How far a garment has sunk down the body since it was draped (the most of any
    /// garment, >= 0): the mean drop of its top (the vertices within 2 cm of its highest
    /// point as draped: a waistband, the shoulders) relative to the body vertex nearest to
    /// each as draped, which moves with the body.
    double max_slip_m = 0;
    int substeps = 0;              ///< simulation steps into this frame (0 for the first)
    int newton_iterations = 0;     ///< over the frame's steps
    double seconds = 0;            ///< wall time of the frame (simulation + checks)
    /// Processor time of the frame, all threads (std::clock): on a shared machine the wall
    /// time also counts waiting for a core.
    double cpu_seconds = 0;
};

enum class AnimateTermination {
    completed,    ///< every frame simulated
    step_failed,  ///< a simulation step failed (non-finite, line search)
    exploded,     ///< a vertex got faster than explosion_speed_m_per_s
    cancelled,    ///< on_progress returned false
};

struct AnimateSummary {
    AnimateTermination termination = AnimateTermination::step_failed;
    std::string message;
    int frames = 0;                     ///< output frames made (also when stopped early)
    int vertices = 0;                   ///< simulated vertices (welded outfit)
    std::vector<AnimationFrameCheck> checks;  ///< one per output frame
    double max_penetration_m = 0;       ///< over all frames
    int max_self_intersections = 0;     ///< over all frames
    double max_speed_m_per_s = 0;       ///< over all frames
    double max_slip_m = 0;              ///< over all frames
    double seconds_blend = 0;           ///< the blend into the motion
    double seconds = 0;                 ///< the whole call
    double seconds_per_frame = 0;       ///< mean over the output frames (simulation + checks)
    double cpu_seconds_per_frame = 0;   ///< mean processor time (all threads) per output frame
    double penetration_tolerance_m = 2e-3;  ///< copied from the options, for usable()
    double slip_tolerance_m = 0.05;         ///< copied from the options, for usable()

    /// Completed, no frame deeper in the body than the tolerance, no crossing in any frame,
    /// and no garment sunk further down the body than the slip tolerance (fallen off).
    bool usable() const {
        return termination == AnimateTermination::completed && max_penetration_m <= penetration_tolerance_m &&
               max_self_intersections == 0 && max_slip_m <= slip_tolerance_m;
    }
    std::string brief_report() const;
};

/// The animation's frames.
struct AnimatedOutfit {
    body::Motion motion;  ///< the body's pose per output frame (at AnimateOptions::fps)
    /// frames[k][g]: garment g's vertices (#V_g x 3, world, metres) at output frame k.
    std::vector<std::vector<Eigen::MatrixX3d>> frames;
};

/// Animates a dressed outfit (dress_outfit's output, draped in outfit.pose) along `motion`:
/// the garments are welded at their seams and simulated together (one fabric each, skirt
/// waistbands stiffened) on the body as a moving obstacle; first the body blends from
/// outfit.pose into the motion's first pose, then each output frame is reached in
/// substeps with the body's pose interpolated between frames; every frame is checked.
/// Expected failures (a failed step, an explosion, a cancel) are in the summary and `out`
/// holds the frames made until then.
/// \param materials one per garment of the outfit.
/// \throw drape::InvalidInput if the options, the motion or a material are invalid, the
///        materials are not one per garment, or the outfit is empty or inconsistent.
AnimateSummary animate_outfit(const body::BodyModel& model, const body::ShapedBody& shaped,
                              const DressedOutfit& outfit, const std::vector<cloth::Material>& materials,
                              const body::Motion& motion, const AnimateOptions& options, AnimatedOutfit& out);

}  // namespace drape::garment
