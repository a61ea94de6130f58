// Folds or prints (docs/synthetic.md, "Plain and printed"): one drape rendered under mid-day
// light with each print kind -- plain, stripes, checks, dots; the sampled colours, period
// and angle -- and the wrinkle density P measured on each render, so that P of the printed
// renders can be compared with P of the same drape rendered plain. An evaluation, not a
// default test: it renders a scene four more times.
#pragma once

#include <drape/render/material.hpp>
#include <drape/synth/measuring.hpp>
#include <drape/synth/sampling.hpp>
#include <drape/synth/synth_options.hpp>
#include <drape/synth/synth_scene.hpp>

#include <opencv2/core.hpp>

#include <array>
#include <string>
#include <vector>

namespace drape::synth {

/// The print kinds of the comparison, in this order (index of the arrays below).
inline constexpr std::array<render::PrintKind, 4> kPrintKinds = {
    render::PrintKind::solid, render::PrintKind::stripes, render::PrintKind::checks, render::PrintKind::dots};

/// "none", "stripes", "checks", "dots" (the `drape synth --print` names; solid is "none").
const char* print_name(render::PrintKind kind);

/// One garment's P under each print kind of kPrintKinds.
struct PrintComparison {
    std::string type;                       ///< garment::garment_type_name
    int label = 0;                          ///< labels.txt id
    render::PrintKind sampled_print = render::PrintKind::solid;  ///< what the seed drew
    std::array<GarmentWrinkles, 4> wrinkles;  ///< per kind, measure_wrinkles on its render

    /// P(kind) / P(plain); 0 when P(plain) is 0.
    double ratio(std::size_t kind) const;
};

/// The mid-day renders of each print kind and what was measured on them.
struct PrintCheck {
    std::array<cv::Mat, 4> midday;          ///< CV_8UC3 per kind of kPrintKinds
    std::vector<PrintComparison> garments;  ///< per garment of the scene
    double seconds_render = 0;
    double seconds_measure = 0;
};

/// `scene` with every garment's print kind replaced by `kind` (nothing else changes).
SynthScene with_print(SynthScene scene, render::PrintKind kind);

/// Renders `made`'s drape (the body posed, the outfit draped) under mid-day light once per
/// print kind, and measures P on each (compare_prints). The labels do not depend on the
/// print: the label map is made's. `detector`: the fold detector's options (default: the
/// default detector, as truth.json's P).
/// \throw drape::InvalidInput as render::Renderer.
PrintCheck check_prints(const SynthScene& scene, const SynthResult& made, const SynthOptions& options,
                        const vision::WrinkleOptions& detector = {});

/// P of each garment of `scene` on each of the renders `midday` (per kind of kPrintKinds,
/// CV_8UC3 of the scene's size) with the label map `labels` (CV_8UC1) and the scene's
/// projected joints (from its body in its pose).
/// \throw drape::InvalidInput on images of the wrong type or size.
std::vector<PrintComparison> compare_prints(const SynthScene& scene, const std::array<cv::Mat, 4>& midday,
                                            const cv::Mat& labels, const vision::WrinkleOptions& detector = {});

}  // namespace drape::synth
