// Starting sizing parameters G from body measurements plus ease.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/tshirt.hpp>

#include <string>

namespace drape::garment {

/// Ease added to body girths (garment girth = body girth + ease), cm.
struct Ease {
    double waist_cm = 4.0;
    double hip_cm = 8.0;
    double chest_cm = 10.0;
    double leg_cm = 8.0;   ///< added to knee and ankle girth estimates

    bool is_valid(std::string* why = nullptr) const;  ///< all in [0, 60] cm
};

/// Proposals from a rest-pose body's measurements (drape::body::measure_body). Lengths not
/// measured by BodyMeasurements (neck, arm, knee) come from stature ratios; see
/// docs/garment-patterns.md. The results pass the templates' validation for adult bodies.
/// \throw drape::InvalidInput if the measurements are not positive or `ease` is invalid.
SkirtSizing propose_skirt_sizing(const body::BodyMeasurements& m, const Ease& ease = {});
PantsSizing propose_pants_sizing(const body::BodyMeasurements& m, const Ease& ease = {});
TShirtSizing propose_tshirt_sizing(const body::BodyMeasurements& m, const Ease& ease = {});
DressSizing propose_dress_sizing(const body::BodyMeasurements& m, const Ease& ease = {});

/// A pattern maker's skirt waist ease (cm): a waistband this much longer than the body
/// where it sits holds on the body.
constexpr double kSkirtWaistEaseCm = 1.5;

/// Where a skirt's waistband holds on the rest body: the smallest girth of the trunk
/// (body::section_girth of horizontal sections, 1 cm apart) between the spine joint and the
/// pelvis joint, and its height. On a body whose belly is wider than its hips the navel
/// girth is the widest section there, and a skirt sized from it slides off.
struct SkirtWaistband {
    double girth_m = 0;
    double height_m = 0;  ///< rest frame (y of the body's rest vertices), metres
};
/// \throw drape::InvalidInput if `shaped` does not fit the model.
SkirtWaistband skirt_waistband(const body::BodyModel& model, const body::ShapedBody& shaped);

/// Where a skirt waist of `waist_girth_m` sits on the rest body: the highest of the same trunk
/// sections (spine joint down to the pelvis joint) whose girth is at most that, else the
/// narrowest (skirt_waistband). dress_garment dresses a circle skirt's waist there.
/// \throw drape::InvalidInput if `shaped` does not fit the model or the girth is not positive.
SkirtWaistband skirt_waist_fit(const body::BodyModel& model, const body::ShapedBody& shaped, double waist_girth_m);

/// A skirt whose waist is `waistband_girth_m` (skirt_waistband) plus `ease_cm`;
/// its length from the stature in `m`.
/// \throw drape::InvalidInput if the measurements or the girth are not positive or the ease
///        is not in [0, 60] cm.
SkirtSizing propose_skirt_sizing(const body::BodyMeasurements& m, double waistband_girth_m,
                                 double ease_cm = kSkirtWaistEaseCm);

/// Sleeve ease (cm): a sleeve opening this much longer than the largest girth of the arm
/// it covers slides over the arm with room for the cloth's contact layer.
constexpr double kSleeveEaseCm = 6.0;

/// The largest girth (m) of the rest body's right upper arm over a sleeve of `sleeve_length_cm`:
/// sections normal to the humerus (shoulder to elbow joint) from 35 % of its length (nearer
/// the shoulder a section runs into the armpit) to the sleeve's hem, at most the elbow.
/// \throw drape::InvalidInput if `shaped` does not fit the model or the length is not
///        positive.
double upper_arm_girth(const body::BodyModel& model, const body::ShapedBody& shaped, double sleeve_length_cm);

/// `g` with its sleeve opening w1 widened to `arm_girth_m` + `ease_cm` if it is narrower
/// (the stature ratio of propose_tshirt_sizing is too narrow for a heavy arm, which then
/// passes through the sleeve). Tank tops (l1 = 0) are returned unchanged.
TShirtSizing fit_sleeves(TShirtSizing g, double arm_girth_m, double ease_cm = kSleeveEaseCm);

/// Neckline ease (cm): a neckline this much longer than the neck lies on the shoulders
/// around its base (the stature ratio of propose_tshirt_sizing made it too small for a
/// thick neck, and the bodice cut 24-42 mm into it: docs/garment-patterns.md, "Sizing from a body").
constexpr double kNecklineEaseCm = 8.0;

/// The girth (m) of the rest body's neck: the section normal to the neck (neck to head
/// joint) 30 % of the way up from the neck joint (at the joint itself the section runs into
/// the trapezius: 46-55 cm on the eval bodies, against 36-49 cm here).
/// \throw drape::InvalidInput if `shaped` does not fit the model.
double neck_girth(const body::BodyModel& model, const body::ShapedBody& shaped);

/// `g` with its neckline radius r enlarged, if needed, so that the neckline (front and back
/// arcs together) is at least `neck_girth_m` + `ease_cm`, as far as the shoulder seams keep
/// 5 cm (2 r <= w2 - 10) and r stays in its range.
TShirtSizing fit_neckline(TShirtSizing g, double neck_girth_m, double ease_cm = kNecklineEaseCm);

/// The sizing `type`'s template proposes for a body (propose_*_sizing with the default ease).
/// \throw drape::InvalidInput as propose_*_sizing.
GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured);

/// The same, but a skirt's waist from `skirt_waistband_girth_m` (skirt_waistband) plus
/// kSkirtWaistEaseCm; other templates as above.
/// \throw drape::InvalidInput as propose_*_sizing.
GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured,
                              double skirt_waistband_girth_m);

/// The same with the waistband girth measured on `shaped` and a top fitted to its arms and
/// neck (fit_top_to_body): the sizing drape dress --sizing auto and eval-dress use.
/// \param measured the measurements of `shaped` (body::measure_body, as shape_body reports).
/// \throw drape::InvalidInput if `shaped` does not fit the model, or as propose_*_sizing.
GarmentSizing proposed_sizing(GarmentType type, const body::BodyModel& model, const body::ShapedBody& shaped,
                              const body::BodyMeasurements& measured);

/// `g` (a t-shirt or a dress; others unchanged) with the sleeve opening widened to the arm
/// of `shaped` + kSleeveEaseCm and the neckline to its neck + kNecklineEaseCm, where
/// narrower (upper_arm_girth / fit_sleeves, neck_girth / fit_neckline).
/// \throw drape::InvalidInput if `shaped` does not fit the model.
GarmentSizing fit_top_to_body(GarmentSizing g, const body::BodyModel& model, const body::ShapedBody& shaped);

}  // namespace drape::garment
