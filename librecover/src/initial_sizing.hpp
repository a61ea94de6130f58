// Private to librecover: the starting sizing G of a garment from the image features and the
// fitted body, which parameters the sizing search moves, and the material search's target.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/recover/recover.hpp>
#include <drape/vision/classify_garment.hpp>
#include <drape/vision/garment_features.hpp>
#include <drape/vision/joints.hpp>

#include <vector>

namespace drape::recover {

/// The template's proposal for the fitted body (sizing_proposal.hpp: girths + ease, a top
/// fitted to the arms and neck), with the lengths and the flare the photo shows: image
/// features (pixels / the skeleton's body height) times the fitted stature. Features that
/// were not measured (NaN) leave the proposal's value; every value is clamped to the
/// template's range. Shorts get a short leg, a tank no sleeve, a long-sleeve top long ones;
/// a dress's bodice gets the sleeves its shape cues show (vision::classify_upper: a
/// sleeveless dress has none, as a tank).
garment::GarmentSizing initial_sizing(GarmentChoice choice, const vision::GarmentFeatures& features,
                                      const vision::GarmentShapeCues& cues,
                                      const vision::Joints& joints, const body::BodyModel& model,
                                      const body::ShapedBody& shaped, const body::BodyMeasurements& measured);

/// The parameters the sizing search moves (sizing_parameters order): those the silhouette
/// shows. Fixed: a skirt's waist radius r1, a top's neckline r, pants' crotch depths h2 and
/// h3, a tank's or a sleeveless dress's sleeve length (0 in `start`), a dress's skirt waist
/// (tied to the bodice).
std::vector<bool> free_parameters(GarmentChoice choice, const garment::GarmentSizing& start);

/// Lower bounds of the sizing search (sizing_parameters order, NaN = none): the girths the
/// body needs (a skirt's or pants' waist and hip, a leg's knee and ankle, a top's panel width
/// and sleeve opening) keep at least `min_ease_cm` of ease over the body
/// (RecoverOptions::min_ease_cm): the starting sizing, which the template's proposal made from
/// the fitted body plus its ease (garment::Ease: chest 10, waist 4, hip 8, leg 8 cm), less
/// that ease above `min_ease_cm`. A bound at the starting girth itself let the swarm only
/// widen a garment (a one-sided search: on the 30 shared photos 83 of 127 searched girths
/// grew, none shrank; docs/notes/recovery.md).
std::vector<double> lower_bounds(const garment::GarmentSizing& start, double min_ease_cm);

}  // namespace drape::recover
