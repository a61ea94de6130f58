// The t-shirt template, G_tshirt = <r, w1, w2, h1, h2, l1> (paper section 5.2, Fig. 3f).
#pragma once

#include <drape/garment/parameter_spec.hpp>
#include <drape/garment/pattern.hpp>

#include <array>

namespace drape::garment {

/// Shoulder drop of the t-shirt's shoulder seams (neck point to shoulder tip), cm.
inline constexpr double kTShirtShoulderDrop = 3.5;

/// Sizing of a boxy t-shirt: front and back body panels (straight sides, width w2) and two
/// sleeve tubes. l1 = 0 gives a tank top (no sleeve panels, open armholes).
struct TShirtSizing {
    double r = 9.0;    ///< cm, neckline radius (half the neck opening width)
    double w1 = 34.0;  ///< cm, sleeve width: girth of the sleeve opening at the cuff
    double w2 = 54.0;  ///< cm, shoulder width: width of each body panel (shoulder tip to tip)
    double h1 = 45.0;  ///< cm, bottom length: hem to underarm along the side seam
    double h2 = 70.0;  ///< cm, total length: hem to the neck point (high shoulder)
    double l1 = 20.0;  ///< cm, sleeve length (0 = tank top)

    static const std::array<ParameterSpec<TShirtSizing>, 6>& parameters();
};

/// The t-shirt pattern: "front", "back" (edges: 0 hem, 1 left side, 2 left armhole,
/// 3 left shoulder, 4 neckline, 5 right shoulder, 6 right armhole, 7 right side; "left" =
/// +x in the panel frame) and, when l1 > 0, "left_sleeve", "right_sleeve" (edges: 0 cuff,
/// 1 underarm, 2 cap half, 3 cap half, 4 underarm).
/// \throw drape::InvalidInput naming the parameter and value when out of range or
///        inconsistent (armhole depth h2 - 3.5 - h1 outside [10, 40] cm; 2r > w2 - 10;
///        0 < l1 < 5).
Pattern make_tshirt(const TShirtSizing& sizing);

}  // namespace drape::garment
