// Size grading: a sizing G made for one body, re-made for another as a pattern maker grades
// a pattern to another size (docs/tryon.md, "Grading rules"): the ease over each girth is
// kept, lengths follow the body's proportions, style parameters (a skirt's flare, a sleeve's
// length for the arm, a trouser leg's taper) stay fixed and nothing else of the pattern moves.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/garment/garment_sizing.hpp>

#include <string>
#include <vector>

namespace drape::garment {

/// The body dimensions grading reads (centimetres, rest pose). measure_for_grading takes
/// them from a body; tests may set them directly.
struct GradingBody {
    double height_cm = 0;           ///< stature
    double chest_girth_cm = 0;      ///< bust / chest (body::BodyMeasurements)
    double waist_girth_cm = 0;      ///< at the navel
    double hip_girth_cm = 0;        ///< at the buttocks
    double thigh_girth_cm = 0;      ///< right thigh
    double shoulder_height_cm = 0;  ///< floor to acromion
    double crotch_height_cm = 0;    ///< floor to crotch
    double waistband_girth_cm = 0;  ///< narrowest trunk girth, where a skirt holds (skirt_waistband)
    double neck_girth_cm = 0;       ///< neck_girth
    double upper_arm_girth_cm = 0;  ///< largest girth of the upper arm, shoulder to elbow (upper_arm_girth)
    double arm_length_cm = 0;       ///< shoulder to wrist joint along the elbow

    /// Every dimension finite and positive, crotch < navel (0.6 x stature) < shoulder <
    /// stature. Names the first that is not.
    bool is_valid(std::string* why = nullptr) const;
};

/// The grading dimensions of a rest body.
/// \throw drape::InvalidInput if `shaped` does not fit the model.
GradingBody measure_for_grading(const body::BodyModel& model, const body::ShapedBody& shaped);

/// A size chart: the body girth that designates a garment's size and the step between
/// consecutive sizes. The default is EN 13402-3 (Size designation of clothes - Part 3:
/// Measurements and intervals, CEN 2004/2013): sizes are designated by the primary body
/// girth (bust or chest girth for tops and dresses; waist girth for trousers and skirts,
/// EN 13402-2) in fixed intervals of 4 cm over the standard's main range (its coarser
/// intervals at the largest sizes are not modelled). docs/tryon.md, "Size chart".
struct SizeChart {
    std::string name = "EN 13402-3";
    double girth_step_cm = 4.0;  ///< one size, in the primary girth
    bool is_valid(std::string* why = nullptr) const;  ///< step finite and in [1, 20] cm
};

/// The primary girth of a garment type under `chart`: "chest" (t-shirt, dress) or "waist"
/// (skirt, pants).
std::string primary_dimension(GarmentType type);

struct GradingOptions {
    SizeChart chart;
    /// A style parameter (GradingSummary::style) may change by at most this fraction before
    /// the grading is called unusable (the acceptance: 2 %).
    double style_tolerance = 0.02;
    bool is_valid(std::string* why = nullptr) const;
};

/// One parameter of G, before and after.
struct GradedParameter {
    std::string name;        ///< sizing_parameters' name ("l1", "bodice.w2")
    std::string unit;        ///< "cm" or "deg"
    double original = 0;
    double graded = 0;       ///< after clamping to the template's range
    double unclamped = 0;    ///< what the rule asked for
    bool clamped = false;    ///< the rule's value was outside [min, max] of the template
    std::string rule;        ///< "ease over waistband girth", "follows leg length", "style" ...
};

/// A style quantity of the design, before and after (dimensionless or degrees).
struct StyleParameter {
    std::string name;             ///< "alpha (flare)", "sleeve length / arm length", ...
    double original = 0;
    double graded = 0;
    double relative_change = 0;   ///< |graded - original| / |original|
};

/// An ease (garment girth minus body girth) before and after, centimetres.
struct EaseCheck {
    std::string name;             ///< "waist", "chest", ...
    double original_cm = 0;
    double graded_cm = 0;
};

/// The size grade between the two bodies under the chart.
struct SizeGrade {
    std::string chart;
    std::string dimension;        ///< "chest" or "waist"
    double from_cm = 0, to_cm = 0;///< the bodies' primary girths
    int sizes = 0;                ///< round((to - from) / step): +2 = two sizes up
    std::string text;             ///< "two sizes up", "same size", "one size down", ...
};

enum class GradingTermination {
    graded,           ///< every rule's value within the template's ranges
    clamped,          ///< some value was clamped to its range (see parameters)
    invalid_pattern,  ///< the graded G makes no valid pattern (message says why)
};

struct GradingSummary {
    GradingTermination termination = GradingTermination::invalid_pattern;
    std::string message;
    std::vector<GradedParameter> parameters;  ///< sizing_parameters order
    std::vector<StyleParameter> style;
    std::vector<EaseCheck> ease;
    SizeGrade grade;
    double max_style_change = 0;   ///< the largest StyleParameter::relative_change
    double style_tolerance = 0.02; ///< from the options
    int clamped = 0;               ///< parameters clamped

    /// A valid pattern whose style parameters all changed by at most the tolerance.
    bool usable() const {
        return termination != GradingTermination::invalid_pattern && max_style_change <= style_tolerance;
    }
    std::string brief_report() const;
};

/// "two sizes up" for +2, "one size down" for -1, "same size" for 0.
std::string size_grade_text(int sizes);

/// Grades `sizing`, made for `from`, to the body `to`:
///  - girths: the garment girth minus the body girth under it (the ease) is kept (skirt
///    waist over the waistband girth, pants waist/seat/knee over waist/hip/thigh, t-shirt
///    width over the chest, sleeve opening over the upper arm, neckline over the neck);
///  - lengths scale with the body length they span: skirt and trouser length with the navel
///    height (0.6 x stature, the proposal's convention), the rise with navel minus crotch
///    height, a t-shirt's lengths with shoulder minus crotch height, a bodice's with
///    shoulder minus navel height, the sleeve with the arm;
///  - style: a skirt's flare alpha and its waist-arc curvature r1 / l1, a trouser leg's
///    taper w4 / w3, a sleeve's length for the arm are fixed; a dress's waist seam keeps
///    skirt.l1 = bodice.w2;
///  - values outside the template's range are clamped and reported.
/// \param graded receives the graded G (the original's type), also when clamped; on
///        invalid_pattern it holds the clamped values that failed.
/// \throw drape::InvalidInput if a body or the options are invalid, or `sizing` makes no
///        valid pattern (naming the parameter).
GradingSummary grade_sizing(const GarmentSizing& sizing, const GradingBody& from, const GradingBody& to,
                            const GradingOptions& options, GarmentSizing& graded);

/// The size grade alone (the chart's primary girth of `type` on both bodies).
/// \throw drape::InvalidInput if a body or the chart is invalid.
SizeGrade size_grade(GarmentType type, const GradingBody& from, const GradingBody& to, const SizeChart& chart = {});

}  // namespace drape::garment
