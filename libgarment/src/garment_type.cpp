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

}  // namespace drape::garment
