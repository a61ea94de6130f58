// The garment types libvision recognises (the garment templates of libgarment).
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace drape::vision {

enum class GarmentType { t_shirt, tank_top, long_sleeve_top, dress, skirt, pants, shorts };

inline constexpr int kGarmentTypeCount = 7;

/// Where a garment sits on the body.
enum class GarmentPart { upper, lower, full };

/// "t-shirt", "tank-top", "long-sleeve-top", "dress", "skirt", "pants", "shorts".
std::string_view to_string(GarmentType t);
/// Parses the names of to_string (also "tank_top", "long_sleeve_top", "tshirt").
/// \return std::nullopt for an unknown name.
std::optional<GarmentType> parse_garment_type(std::string_view name);
GarmentPart part_of(GarmentType t);

/// The labels.txt id written for an automatically found garment of this type:
/// t-shirt 51, tank top 54 ("top"), long-sleeve top 38 ("shirt"), dress 14, skirt 42,
/// pants 31, shorts 40.
int label_id_of(GarmentType t);

}  // namespace drape::vision
