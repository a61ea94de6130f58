// JSON forms of the garment sizing parameters G, keyed by the paper's names:
// skirt {l1, r1, r2, alpha}; pants {w1, w2, w3, w4, h1, h2, h3}; tshirt {r, w1, w2, h1,
// h2, l1}; dress {"bodice": {tshirt keys}, "skirt": {skirt keys}}. Centimetres, degrees.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/garment/drape_garment.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <drape/cloth/material.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace drape::io {

// The vocabulary is libgarment's (drape/garment/garment_type.hpp, garment_sizing.hpp,
// sizing_proposal.hpp). These using-declarations keep the app's unqualified names (synth).
using garment::fit_top_to_body;
using garment::garment_type_from_name;
using garment::garment_type_name;
using garment::GarmentSizing;
using garment::GarmentType;
using garment::make_pattern;
using garment::proposed_sizing;

/// Reads G.json for `type`. Absent keys keep the template defaults; unknown keys and
/// non-numbers throw InvalidInput naming the file and key (range checks happen when the
/// pattern is made).
GarmentSizing sizing_from_json(GarmentType type, const nlohmann::json& j, const std::string& file);
nlohmann::json to_json(const GarmentSizing& sizing);

/// A garment's fabric as truth.json and result.json hold it: the scales, the base fabric's
/// name, its unscaled tables (SI, ArcSim layout) and density.
nlohmann::json material_to_json(const cloth::Material& material, const std::string& base_fabric);
/// The inverse of material_to_json (the base fabric's name goes to `*base_fabric` if given).
/// \throw InvalidInput naming the file and the field for a missing or non-finite number, a
/// table of the wrong shape, or a scale or density that is not positive.
cloth::Material material_from_json(const nlohmann::json& j, const std::string& file,
                                   std::string* base_fabric = nullptr);

/// A drape's figures as `drape dress` writes them in summary.json: vertices, stitches,
/// seam_gap_max_m, penetration_max_m, vertices_inside, self_intersections, mean_drop_m,
/// converged, usable, steps, steps_to_close_seams, welded, message, seconds_drape.
nlohmann::json to_json(const garment::DrapeSummary& d);

/// The garments of `--garment` ("skirt", "tshirt+pants", ...: template names joined by '+')
/// in layering order, inner first (garment::outfit_layers).
/// \throw InvalidInput naming the option and its value for an unknown name or outfit.
std::vector<GarmentType> outfit_from_spec(const std::string& spec);

}  // namespace drape::io
