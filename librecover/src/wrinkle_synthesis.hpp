// Private to librecover: the material by analysis by synthesis (issue 21, "Material C", the
// second approach): each candidate bending scale is draped, the drape rendered with the
// fitted camera, and its wrinkle density P measured on the render by the same detector that
// measured the photo's; the bending scale whose render's P matches the photo's is kept.
#pragma once

#include "candidate_draper.hpp"
#include "outfit_view.hpp"

#include <drape/recover/recover.hpp>
#include <drape/vision/joints.hpp>

#include <functional>
#include <vector>

namespace drape::recover {

/// P (1/m²) of the candidate garment (last in `scene`) on a render of `scene` by the view's
/// camera at the photo's size: librender's preview scene (shaded, midday light, no floor,
/// `samples` per pixel), the candidate's visible pixels measured by vision::detect_wrinkles
/// with the photo's joints and the default options (as the photo's P). 0 when no fold
/// reached the detector's limit or the garment is not visible.
double rendered_wrinkle_density(const OutfitMeshes& scene, const OutfitView& view, const vision::Joints& joints,
                                int samples, int threads);

/// One bending search by synthesis.
struct SynthesisSearch {
    double log10_bending_scale = 0;  ///< the best
    double objective = 0;            ///< (ln(1 + P) − ln(1 + P_photo))² there
    double wrinkle_density_per_m2 = 0;  ///< P of its render
    double low = 0, high = 2;        ///< log10 s_b range whose objective is within the best's + 0.05
    int evaluations = 0;
};

/// Searches log10 s_b in [0, 2]: a grid of 5 points, then the best's two neighbours at a
/// quarter step (P counts folds, so it is piecewise constant in s_b: a gradient would see
/// nothing). `p_at(x)` is P of the render at log10 s_b = x.
SynthesisSearch search_bending_by_synthesis(double photo_p_per_m2, const std::function<double(double)>& p_at);

}  // namespace drape::recover
