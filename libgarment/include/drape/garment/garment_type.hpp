// The garment templates drape can make: the one garment-type vocabulary of the libraries.
// (libvision has its own image classes, drape::vision::GarmentType; the app layer maps
// them onto these templates: apps/drape/garment_classes.hpp.)
#pragma once

#include <string>
#include <vector>

namespace drape::garment {

/// A pattern template: circle skirt, four-panel pants, t-shirt (tank top with no sleeves),
/// dress (t-shirt bodice sewn to a circle skirt).
enum class GarmentType { skirt, pants, tshirt, dress };

/// "skirt", "pants", "tshirt" or "dress".
/// \throw drape::InvalidInput naming the value otherwise.
GarmentType garment_type_from_name(const std::string& name);

/// The name garment_type_from_name reads.
std::string garment_type_name(GarmentType type);

/// The garments of an outfit in the order they are dressed and draped, inner first. An
/// outfit is one garment, or a top (t-shirt) and a bottom (pants or a skirt) in either
/// order: the bottom comes first and the top is worn over its waistband (untucked).
/// \throw drape::InvalidInput naming the garments otherwise.
std::vector<GarmentType> outfit_layers(const std::vector<GarmentType>& garments);

}  // namespace drape::garment
