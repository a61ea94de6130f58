// Class ids of label maps and strokes: the scheme of ../shared/data/photos/labels.txt
// (Fashionista / Clothing Co-Parsing, ids 0..58), and the role each class plays for
// garment parsing.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace drape::vision {

/// What a class is to the garment parser.
enum class LabelRole {
    background,      ///< not the person (id 0 "null")
    skin,
    hair,
    upper_garment,   ///< t-shirt, top, blouse, shirt, sweater, ...
    lower_garment,   ///< skirt, pants, jeans, shorts, leggings
    full_garment,    ///< dress, romper, jumpsuit-like one-pieces
    occluder,        ///< in front of garments: bag, purse, belt, scarf, outerwear, accessories
    other,           ///< worn but not parsed as a garment: shoes, socks, stockings, hats, ...
};

/// Id used in strokes for "unmarked".
inline constexpr int kUnmarked = 255;

/// A table id -> (name, role). Ids must be < 255 (255 is kUnmarked).
class LabelTable {
public:
    /// The 59 classes of labels.txt with their roles (docs/vision.md lists the roles).
    static const LabelTable& fashionista();

    /// Builds a table from "id name" rows: roles come from the class names (known names
    /// of the Fashionista table; unknown names get LabelRole::other).
    /// \throw drape::InvalidInput on an id outside 0..254 or a duplicate id.
    static LabelTable from_names(const std::vector<std::pair<int, std::string>>& rows);

    bool contains(int id) const;
    /// \throw drape::InvalidInput for an unknown id.
    const std::string& name(int id) const;
    LabelRole role(int id) const;  ///< LabelRole::other for unknown ids
    /// Id of a class name; -1 if absent.
    int id(std::string_view name) const;
    /// All ids with the given role, ascending.
    std::vector<int> ids_with_role(LabelRole r) const;

    int background_id() const { return id("null") >= 0 ? id("null") : 0; }
    int skin_id() const { return id("skin"); }
    int hair_id() const { return id("hair"); }

private:
    std::array<std::string, 255> names_{};
    std::array<LabelRole, 255> roles_{};
    std::array<bool, 255> present_{};
};

/// Role of a garment/body class name as libvision understands it.
LabelRole role_from_name(std::string_view name);

}  // namespace drape::vision
