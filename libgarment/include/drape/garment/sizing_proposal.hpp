// Starting sizing parameters G from body measurements plus ease.
#pragma once

#include <drape/body/measurements.hpp>
#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
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

}  // namespace drape::garment
