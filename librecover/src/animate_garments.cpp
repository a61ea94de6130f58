#include <drape/recover/animate_garments.hpp>

#include <drape/core/errors.hpp>
#include <drape/garment/garment_type.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace drape::recover {

bool AnimateGarmentsOptions::is_valid(std::string* why) const {
    const auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!(std::isfinite(seconds) && seconds > 0 && seconds <= 120))
        return fail("seconds = " + std::to_string(seconds) + " must be in (0, 120]");
    if (!(std::isfinite(fps) && fps > 0 && fps <= 240)) return fail("fps = " + std::to_string(fps) + " must be in (0, 240]");
    if (!(std::isfinite(edge_cm) && edge_cm > 0 && edge_cm <= 20))
        return fail("edge_cm = " + std::to_string(edge_cm) + " must be in (0, 20]");
    if (!wind_m_per_s.allFinite()) return fail("wind_m_per_s must be finite");
    return true;
}

std::string AnimateGarmentsSummary::brief_report() const {
    std::ostringstream os;
    switch (termination) {
        case AnimateGarmentsTermination::animated: os << "animated"; break;
        case AnimateGarmentsTermination::drape_failed: os << "the outfit could not be draped"; break;
        case AnimateGarmentsTermination::stopped: os << "the animation stopped early"; break;
        case AnimateGarmentsTermination::cancelled: os << "cancelled"; break;
    }
    if (!message.empty()) os << ": " << message;
    if (termination != AnimateGarmentsTermination::drape_failed) os << "; drape: " << dress.brief_report();
    if (termination == AnimateGarmentsTermination::animated || termination == AnimateGarmentsTermination::stopped)
        os << "; " << animate.brief_report();
    return os.str();
}

AnimateGarmentsSummary animate_garments(const body::BodyModel& model, const AnimateGarmentsInputs& inputs,
                                        const AnimateGarmentsOptions& options, AnimateGarmentsResult& out) {
    std::string why;
    require(options.is_valid(&why), "animate_garments: ", why);
    require(!inputs.garments.empty(), "animate_garments: no garment to animate");
    const auto t0 = std::chrono::steady_clock::now();
    const auto since = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    out = AnimateGarmentsResult{};
    AnimateGarmentsSummary summary;

    const body::ShapeSummary shaped = body::shape_body(model, model.prior.complete(inputs.body), body::ShapeOptions{}, out.shaped);
    require(shaped.usable(), "animate_garments: the garments' body cannot be shaped: ", shaped.brief_report());
    body::Motion motion;
    if (inputs.motion == "walk") {
        motion = body::walk_cycle(out.shaped.joints, options.seconds, options.fps);
    } else {
        require(std::filesystem::path(inputs.motion).extension() == ".bvh", "animate_garments: motion '",
                inputs.motion, "' is neither 'walk' nor a .bvh file");
        motion = body::load_bvh_motion(inputs.motion, out.shaped.joints, body::BvhJointMap::standard(), &out.bvh);
    }
    out.motion_seconds = motion.duration_s();

    std::vector<garment::GarmentRequest> requests;
    std::vector<cloth::Material> materials;
    for (const AnimatedGarmentSource& g : inputs.garments) {
        requests.push_back({g.type, g.sizing, g.material});
        materials.push_back(g.material);
        out.names.push_back(garment::garment_type_name(g.type) + "_" + std::to_string(out.names.size()));
    }
    garment::DressOutfitOptions dress;
    dress.mesh.target_edge_cm = options.edge_cm;
    bool cancelled = false;
    if (options.on_progress)
        dress.drape.on_progress = [&](const garment::DrapeProgress& p) {
            AnimateGarmentsProgress q;
            q.stage = AnimateGarmentsStage::draping;
            q.step = p.step;
            q.seconds = since();
            cancelled = !options.on_progress(q);
            return !cancelled;
        };
    summary.dress = garment::dress_outfit(model, out.shaped, inputs.pose, requests, dress, out.outfit);
    if (cancelled || summary.dress.termination == garment::DressOutfitTermination::cancelled) {
        summary.termination = AnimateGarmentsTermination::cancelled;
        return summary;
    }
    if (summary.dress.termination != garment::DressOutfitTermination::draped) {
        summary.termination = AnimateGarmentsTermination::drape_failed;
        summary.message = summary.dress.message;
        return summary;
    }

    garment::AnimateOptions animate;
    animate.fps = options.fps;
    animate.seconds = options.seconds;
    animate.wind_m_per_s = options.wind_m_per_s;
    if (options.on_progress)
        animate.on_progress = [&](const garment::AnimateProgress& p) {
            AnimateGarmentsProgress q;
            q.stage = p.blending ? AnimateGarmentsStage::blending : AnimateGarmentsStage::animating;
            q.step = p.frame;
            q.frames = p.frames;
            q.seconds = p.seconds;
            return options.on_progress(q);
        };
    summary.animate = garment::animate_outfit(model, out.shaped, out.outfit, materials, motion, animate, out.animation);
    switch (summary.animate.termination) {
        case garment::AnimateTermination::completed: summary.termination = AnimateGarmentsTermination::animated; break;
        case garment::AnimateTermination::cancelled: summary.termination = AnimateGarmentsTermination::cancelled; break;
        default:
            summary.termination = AnimateGarmentsTermination::stopped;
            summary.message = summary.animate.message;
    }
    return summary;
}

}  // namespace drape::recover
