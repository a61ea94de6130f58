#include <drape/vision/garment_type.hpp>

#include <array>

namespace drape::vision {

namespace {
constexpr std::array<std::string_view, kGarmentTypeCount> kNames = {
    "t-shirt", "tank-top", "long-sleeve-top", "dress", "skirt", "pants", "shorts"};
}

std::string_view to_string(GarmentType t) { return kNames[static_cast<size_t>(t)]; }

std::optional<GarmentType> parse_garment_type(std::string_view name) {
    for (size_t i = 0; i < kNames.size(); ++i)
        if (kNames[i] == name) return static_cast<GarmentType>(i);
    if (name == "tank_top" || name == "tanktop") return GarmentType::tank_top;
    if (name == "long_sleeve_top") return GarmentType::long_sleeve_top;
    if (name == "tshirt" || name == "t_shirt") return GarmentType::t_shirt;
    return std::nullopt;
}

GarmentPart part_of(GarmentType t) {
    switch (t) {
        case GarmentType::t_shirt:
        case GarmentType::tank_top:
        case GarmentType::long_sleeve_top: return GarmentPart::upper;
        case GarmentType::dress: return GarmentPart::full;
        case GarmentType::skirt:
        case GarmentType::pants:
        case GarmentType::shorts: return GarmentPart::lower;
    }
    return GarmentPart::upper;
}

int label_id_of(GarmentType t) {
    switch (t) {
        case GarmentType::t_shirt: return 51;
        case GarmentType::tank_top: return 54;
        case GarmentType::long_sleeve_top: return 38;
        case GarmentType::dress: return 14;
        case GarmentType::skirt: return 42;
        case GarmentType::pants: return 31;
        case GarmentType::shorts: return 40;
    }
    return 0;
}

}  // namespace drape::vision
