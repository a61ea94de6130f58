// The garment templates drape can make: the one garment-type vocabulary of the libraries.
// (libvision has its own image classes, drape::vision::GarmentType; the app layer maps
// them onto these templates: apps/drape/garment_classes.hpp.)
#pragma once

#include <string>

namespace drape::garment {

/// A pattern template: circle skirt, four-panel pants, t-shirt (tank top with no sleeves),
/// dress (t-shirt bodice sewn to a circle skirt).
enum class GarmentType { skirt, pants, tshirt, dress };

/// "skirt", "pants", "tshirt" or "dress".
/// \throw drape::InvalidInput naming the value otherwise.
GarmentType garment_type_from_name(const std::string& name);

/// The name garment_type_from_name reads.
std::string garment_type_name(GarmentType type);

}  // namespace drape::garment
