// A sizing G of any template, and the pattern it makes.
#pragma once

#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/dress.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/garment/pants.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/garment/tshirt.hpp>

#include <string>
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

/// One entry of a template's flat parameter list (sizing_parameters): the template's table
/// (ParameterSpec) with the dress's groups prefixed ("bodice.l1", "skirt.alpha").
struct SizingParameter {
    std::string name;     ///< the paper's name, prefixed by its group for a dress
    double min = 0;       ///< inclusive range, in `unit`
    double max = 0;
    std::string unit;     ///< "cm" or "deg"
    std::string meaning;
};

/// The parameters of a template in a fixed order: its table's order (skirt, pants, t-shirt);
/// a dress lists the bodice's then the skirt's. The order of sizing_values.
std::vector<SizingParameter> sizing_parameters(GarmentType type);

/// The values of `sizing`'s template, in the order of sizing_parameters(sizing.type).
std::vector<double> sizing_values(const GarmentSizing& sizing);

/// `base` with its template's values replaced by `values` (sizing_parameters order). The
/// values are not range-checked here (make_pattern checks them).
/// \throw drape::InvalidInput if values.size() differs from the template's count.
GarmentSizing with_sizing_values(GarmentSizing base, const std::vector<double>& values);

}  // namespace drape::garment
