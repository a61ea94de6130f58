// The dress template: a t-shirt-style bodice joined at the waist to a circle skirt.
#pragma once

#include <drape/garment/circle_skirt.hpp>
#include <drape/garment/pattern.hpp>
#include <drape/garment/tshirt.hpp>

namespace drape::garment {

/// Sizing groups "bodice" (t-shirt parameters; its h1/h2 end at the waist) and "skirt"
/// (circle-skirt parameters). The waist seam needs skirt.l1 == bodice.w2 (within 1 %).
struct DressSizing {
    TShirtSizing bodice{9.0, 34.0, 50.0, 22.0, 44.0, 18.0};
    SkirtSizing skirt{50.0, 32.0, 60.0, 90.0};
};

/// The dress pattern: the bodice panels of make_tshirt (names prefixed "bodice_") and the
/// skirt panels of make_circle_skirt ("skirt_front", "skirt_back"), with the waist seams.
/// \throw drape::InvalidInput as make_tshirt / make_circle_skirt (parameter names are
///        prefixed "bodice." / "skirt."), or when skirt.l1 and bodice.w2 differ by > 1 %.
Pattern make_dress(const DressSizing& sizing);

}  // namespace drape::garment
