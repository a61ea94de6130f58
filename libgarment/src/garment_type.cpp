#include <drape/garment/garment_type.hpp>

#include <drape/core/errors.hpp>

namespace drape::garment {

GarmentType garment_type_from_name(const std::string& name) {
    if (name == "skirt") return GarmentType::skirt;
    if (name == "pants") return GarmentType::pants;
    if (name == "tshirt") return GarmentType::tshirt;
    if (name == "dress") return GarmentType::dress;
    throw InvalidInput("unknown garment '" + name + "' (expected skirt, pants, tshirt or dress)");
}

std::string garment_type_name(GarmentType type) {
    switch (type) {
        case GarmentType::skirt: return "skirt";
        case GarmentType::pants: return "pants";
        case GarmentType::tshirt: return "tshirt";
        case GarmentType::dress: return "dress";
    }
    return "?";
}

std::vector<GarmentType> outfit_layers(const std::vector<GarmentType>& garments) {
    const auto is_top = [](GarmentType t) { return t == GarmentType::tshirt; };
    const auto is_bottom = [](GarmentType t) { return t == GarmentType::pants || t == GarmentType::skirt; };
    if (garments.size() == 1) return garments;
    if (garments.size() == 2) {
        if (is_bottom(garments[0]) && is_top(garments[1])) return garments;
        if (is_top(garments[0]) && is_bottom(garments[1])) return {garments[1], garments[0]};
    }
    std::string names;
    for (GarmentType t : garments) names += (names.empty() ? "" : "+") + garment_type_name(t);
    throw InvalidInput("outfit '" + names +
                       "': an outfit is one garment, or a top and a bottom (tshirt+pants or tshirt+skirt)");
}

}  // namespace drape::garment
