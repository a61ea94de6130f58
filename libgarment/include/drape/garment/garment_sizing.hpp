// A sizing G of any template, and the pattern it makes.
#pragma once

#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/garment/tshirt.hpp>

#include <vector>

namespace drape::garment {

/// A sizing of any template; only the member of `type` is used (centimetres, degrees, as
/// each template's sizing struct).
struct GarmentSizing {
    GarmentType type = GarmentType::skirt;
    SkirtSizing skirt;
    PantsSizing pants;
    TShirtSizing tshirt;
    DressSizing dress;
};

/// The pattern of a sizing (make_circle_skirt, make_pants, make_tshirt or make_dress).
/// \throw drape::InvalidInput as the template's maker, naming the parameter and value.
Pattern make_pattern(const GarmentSizing& sizing);

/// The values of the template's sizing parameters (cm, degrees) in the order of its
/// ParameterSpec table; a dress: the bodice's six (TShirtSizing), then the skirt's four.
/// For optimisers that see G as a vector.
std::vector<double> sizing_values(const GarmentSizing& sizing);

/// `sizing` with its template's parameters set to `values` (ordered as sizing_values).
/// Ranges are not checked here (make_pattern does).
/// \throw drape::InvalidInput if the count differs from the template's.
GarmentSizing with_sizing_values(GarmentSizing sizing, const std::vector<double>& values);

}  // namespace drape::garment
