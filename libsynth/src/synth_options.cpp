#include <drape/synth/synth_options.hpp>

#include <drape/core/errors.hpp>

#include <cmath>

namespace drape::synth {

bool SynthOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!(edge_cm > 0 && edge_cm <= 20)) return fail("edge " + std::to_string(edge_cm) + " cm must be in (0, 20]");
    if (max_steps < 20) return fail("max_steps " + std::to_string(max_steps) + " must be >= 20");
    if (width_px < 64 || width_px > 8192) return fail("width " + std::to_string(width_px) + " px must be in [64, 8192]");
    if (height_px < 600 || height_px > 8192)
        return fail("height " + std::to_string(height_px) + " px must be in [600, 8192]");
    if (samples_per_pixel < 1 || samples_per_pixel > 4096)
        return fail("samples " + std::to_string(samples_per_pixel) + " must be in [1, 4096]");
    if (threads < 0) return fail("threads must be >= 0");
    if (!std::isfinite(bending_scale) || bending_scale > 1e4)
        return fail("bending scale " + std::to_string(bending_scale) + " must be finite and <= 1e4");
    if (!garments.empty()) {
        try {
            if (garment::outfit_layers(garments) != garments) return fail("an outfit's garments come inner first");
        } catch (const InvalidInput& e) {
            return fail(e.what());
        }
    }
    if (pose && *pose == body::NamedPose::t_pose) return fail("pose must be a_pose, arms_down or walking");
    return true;
}

}  // namespace drape::synth
