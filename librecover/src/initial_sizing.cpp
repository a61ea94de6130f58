#include "initial_sizing.hpp"

#include <drape/core/errors.hpp>
#include <drape/garment/sizing_proposal.hpp>
#include <drape/garment/sizing_search.hpp>

#include <algorithm>
#include <cmath>

namespace drape::recover {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A feature in centimetres (the fitted stature times its share of the skeleton's body
// height), or NaN.
double feature_cm(double px, double body_height_px, double stature_m) {
    if (!std::isfinite(px) || px <= 0 || !(body_height_px > 0)) return std::nan("");
    return 100.0 * stature_m * px / body_height_px;
}

void set_if(double& field, double value) {
    if (std::isfinite(value)) field = value;
}

// Clamps every value to the template's range.
garment::GarmentSizing clamped(garment::GarmentSizing g) {
    const auto p = garment::sizing_parameters(g.type);
    auto v = garment::sizing_values(g);
    for (size_t i = 0; i < v.size(); ++i) v[i] = std::clamp(v[i], p[i].min, p[i].max);
    return garment::with_sizing_values(g, v);
}

// A circle skirt's flare from the hem width seen from the front: the hem's girth is about
// pi times its projected width, and the two panels' hem arcs make it, 2 (r1 + r2) alpha.
double skirt_flare_deg(double hem_width_cm, double r1, double r2) {
    if (!std::isfinite(hem_width_cm)) return std::nan("");
    return std::clamp(kPi * hem_width_cm / (2.0 * (r1 + r2)) * 180.0 / kPi, 20.0, 170.0);
}

// A top's or dress's length in the image: its top row to its hem, but at most
// kTopAboveShoulders x the body height above the shoulder line (the joints' row). A top's
// highest point, the high shoulder point beside the neck, lies about 0.03 H above the
// shoulder joints (the shoulder's slope: 4-6 cm at 1.70 m); what a mask shows higher is a
// collar, or a raised sleeve or arm (fashionista_000005's blouse, hands on the head: 77 cm
// long in its stroke segmentation for a hip-length blouse; 003792's blouse with one arm
// raised, 63 cm where the photo shows about 45). The cap was 0.12 H until 2026-11-28, from
// the top rows of the hand labels (-0.05 to 0.11 H above the shoulder line with the arms
// down, 017182's high collar the highest); at 0.05 H 003792's tunic over her shorts became
// a blouse at the waistband (upper IoU 0.41 -> 0.47, shorts 0.02 -> 0.44; docs/recovery.md).
constexpr double kTopAboveShoulders = 0.05;
double top_length_px(const vision::GarmentFeatures& f, double body_height_px) {
    if (!std::isfinite(f.hem_below_shoulders_px)) return f.length_px;
    return std::min(f.length_px, f.hem_below_shoulders_px + kTopAboveShoulders * body_height_px);
}

void top_from_features(garment::TShirtSizing& t, GarmentChoice choice, const vision::GarmentFeatures& f, double h,
                       double stature) {
    const double length = feature_cm(top_length_px(f, h), h, stature);
    if (std::isfinite(length)) {
        // The image length runs from the shoulder line to the hem; h2 from the neck point.
        const double h2 = length + 2.0;
        t.h1 = std::max(8.0, t.h1 + (h2 - t.h2));
        t.h2 = h2;
    }
    switch (choice) {
        case GarmentChoice::tank: t.l1 = 0; break;
        case GarmentChoice::longsleeve: {
            const double s = feature_cm(f.sleeve_length_px, h, stature);
            t.l1 = std::isfinite(s) ? std::max(40.0, s) : 58.0;
            break;
        }
        default: {
            const double s = feature_cm(f.sleeve_length_px, h, stature);
            if (std::isfinite(s)) t.l1 = std::clamp(s, 8.0, 40.0);
            break;
        }
    }
}

}  // namespace

garment::GarmentSizing initial_sizing(GarmentChoice choice, const vision::GarmentFeatures& f,
                                      const vision::GarmentShapeCues& cues,
                                      const vision::Joints& joints, const body::BodyModel& model,
                                      const body::ShapedBody& shaped, const body::BodyMeasurements& measured) {
    garment::GarmentSizing g = garment::proposed_sizing(template_of(choice), model, shaped, measured);
    const double h = joints.body_height_px();
    const double stature = measured.height_m;
    switch (g.type) {
        case garment::GarmentType::skirt: {
            set_if(g.skirt.r2, feature_cm(f.length_px, h, stature));
            set_if(g.skirt.alpha, skirt_flare_deg(feature_cm(f.hem_width_px, h, stature), g.skirt.r1, g.skirt.r2));
            break;
        }
        case garment::GarmentType::pants: {
            const double length = feature_cm(f.length_px, h, stature);
            if (choice == GarmentChoice::shorts) {
                // At least the template's 5 cm inseam below the crotch depth (hot pants; the
                // pattern's short-shorts construction matches the inseams down to there).
                const double h1_min = garment::PantsSizing::parameters()[4].min;  // h1's range
                g.pants.h1 = std::max({std::isfinite(length) ? std::min(length, 60.0) : 45.0,
                                       std::max(g.pants.h2, g.pants.h3) + 5.0, h1_min});
            } else {
                set_if(g.pants.h1, length);
            }
            break;
        }
        case garment::GarmentType::tshirt: top_from_features(g.tshirt, choice, f, h, stature); break;
        case garment::GarmentType::dress: {
            // The bodice's sleeves as an upper garment's would be read (tank, t-shirt, long).
            GarmentChoice sleeves = GarmentChoice::tshirt;
            switch (vision::classify_upper(cues)) {
                case vision::GarmentType::tank_top: sleeves = GarmentChoice::tank; break;
                case vision::GarmentType::long_sleeve_top: sleeves = GarmentChoice::longsleeve; break;
                default: break;
            }
            top_from_features(g.dress.bodice, sleeves, f, h, stature);
            const double skirt_length = feature_cm(f.length_from_waist_px, h, stature);
            if (std::isfinite(skirt_length)) g.dress.skirt.r2 = skirt_length;
            set_if(g.dress.skirt.alpha, skirt_flare_deg(feature_cm(f.hem_width_px, h, stature), g.dress.skirt.r1,
                                                        g.dress.skirt.r2));
            // The bodice ends at the waist: its length is the garment's less the skirt's.
            const double dress_length = feature_cm(top_length_px(f, h), h, stature);
            if (std::isfinite(skirt_length) && std::isfinite(dress_length)) {
                const double bodice = dress_length - skirt_length + 2.0;
                g.dress.bodice.h1 = std::max(8.0, g.dress.bodice.h1 + (bodice - g.dress.bodice.h2));
                g.dress.bodice.h2 = bodice;
            }
            break;
        }
    }
    g = garment::tie_dress_waist(clamped(g));
    // A top's sleeve must still fit the arm after the length changed.
    g = clamped(garment::fit_top_to_body(g, model, shaped));
    // Features that make a pattern the template refuses (a seam pair of unequal lengths)
    // fall back to the body's proposal: the search starts from a garment that can be made.
    try {
        garment::make_pattern(g);
    } catch (const InvalidInput&) {
        return garment::proposed_sizing(template_of(choice), model, shaped, measured);
    }
    return g;
}

std::vector<bool> free_parameters(GarmentChoice choice, const garment::GarmentSizing& start) {
    const auto params = garment::sizing_parameters(template_of(choice));
    std::vector<bool> free(params.size(), true);
    for (size_t i = 0; i < params.size(); ++i) {
        const std::string& n = params[i].name;
        const bool pants = template_of(choice) == garment::GarmentType::pants;
        if (n == "r1" || n == "skirt.r1" || n == "r" || n == "bodice.r") free[i] = false;
        if (pants && (n == "h2" || n == "h3")) free[i] = false;
        if (choice == GarmentChoice::tank && n == "l1") free[i] = false;
        if (n == "bodice.l1" && start.dress.bodice.l1 <= 0) free[i] = false;  // a sleeveless dress
        if (n == "skirt.l1") free[i] = false;
    }
    return free;
}

std::vector<double> lower_bounds(const garment::GarmentSizing& start, double min_ease_cm) {
    const auto params = garment::sizing_parameters(start.type);
    const auto values = garment::sizing_values(start);
    std::vector<double> out(params.size(), std::nan(""));
    const garment::Ease ease;  // the proposal's
    const auto over = [min_ease_cm](double e) { return std::max(0.0, e - min_ease_cm); };
    for (size_t i = 0; i < params.size(); ++i) {
        const std::string& n = params[i].name;
        double slack = -1;  // < 0: not a girth
        switch (start.type) {
            case garment::GarmentType::skirt:
                if (n == "l1") slack = over(ease.waist_cm) / 2;  // a panel's waist arc: half the girth
                break;
            case garment::GarmentType::pants:
                if (n == "w1") slack = over(ease.waist_cm);
                if (n == "w2") slack = over(ease.hip_cm);
                if (n == "w3") slack = over(ease.leg_cm);
                if (n == "w4") slack = over(ease.leg_cm);
                break;
            case garment::GarmentType::tshirt:
            case garment::GarmentType::dress:
                // w2: a panel's width, half the chest girth; w1: the sleeve opening, fitted to
                // the upper arm with the chest's ease at most.
                if (n == "w2" || n == "bodice.w2") slack = over(ease.chest_cm) / 2;
                if (n == "w1" || n == "bodice.w1") slack = over(ease.chest_cm) / 2;
                break;
        }
        if (slack >= 0) out[i] = values[i] - slack;
    }
    return out;
}

}  // namespace drape::recover
