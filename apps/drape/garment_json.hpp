// JSON forms of the garment sizing parameters G (app layer), keyed by the paper's names:
// skirt {l1, r1, r2, alpha}; pants {w1, w2, w3, w4, h1, h2, h3}; tshirt {r, w1, w2, h1,
// h2, l1}; dress {"bodice": {tshirt keys}, "skirt": {skirt keys}}. Centimetres, degrees.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/pattern.hpp>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <filesystem>
#include <string>

namespace drape::app {

enum class GarmentType { skirt, pants, tshirt, dress };

/// "skirt", "pants", "tshirt" or "dress". \throw InvalidInput naming the value otherwise.
GarmentType garment_type_from_name(const std::string& name);
std::string garment_type_name(GarmentType type);

/// A sizing of any template; only the member of `type` is used.
struct GarmentSizing {
    GarmentType type = GarmentType::skirt;
    garment::SkirtSizing skirt;
    garment::PantsSizing pants;
    garment::TShirtSizing tshirt;
    garment::DressSizing dress;
};

/// Reads G.json for `type`. Absent keys keep the template defaults; unknown keys and
/// non-numbers throw InvalidInput naming the file and key (range checks happen when the
/// pattern is made).
GarmentSizing sizing_from_json(GarmentType type, const nlohmann::json& j, const std::string& file);
nlohmann::json to_json(const GarmentSizing& sizing);

/// The sizing each template proposes for a body (garment::propose_*_sizing).
GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured);
/// The same, but a skirt's waist from `skirt_waistband_girth_m` (garment::skirt_waistband)
/// plus the skirt waist ease.
GarmentSizing proposed_sizing(GarmentType type, const body::BodyMeasurements& measured,
                              double skirt_waistband_girth_m);
/// The same with the waistband girth measured on `shaped` and a top fitted to its arms and
/// neck (fit_top_to_body).
GarmentSizing proposed_sizing(GarmentType type, const body::BodyModel& model, const body::ShapedBody& shaped,
                              const body::BodyMeasurements& measured);
/// `g` (a t-shirt or a dress; others unchanged) with the sleeve opening widened to the arm of
/// `shaped` + the sleeve ease and the neckline to its neck + the neckline ease, where
/// narrower (garment::upper_arm_girth / fit_sleeves, garment::neck_girth / fit_neckline).
GarmentSizing fit_top_to_body(GarmentSizing g, const body::BodyModel& model, const body::ShapedBody& shaped);

/// A garment mesh as OBJ: `v` = positions (#V x 3, metres: the draped garment, or the flat
/// layout (u, v, 0)), `vt` = pattern uv, one group per panel; `what` goes in the header.
/// Written atomically.
void write_garment_obj(const std::filesystem::path& path, const garment::Pattern& pattern,
                       const garment::GarmentMesh& mesh, const Eigen::MatrixX3d& positions,
                       const std::string& what);

/// The pattern of a sizing (make_circle_skirt, make_pants, make_tshirt or make_dress).
garment::Pattern make_pattern(const GarmentSizing& sizing);

}  // namespace drape::app
