// A sizing G of any template, and the pattern it makes.
#pragma once

#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/garment/tshirt.hpp>

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

}  // namespace drape::garment
