// The pants template, G_pants = <w1, w2, w3, w4, h1, h2, h3> (paper section 5.2, Fig. 3d).
#pragma once

#include <drape/garment/parameter_spec.hpp>
#include <drape/garment/pattern.hpp>

#include <array>

namespace drape::garment {

/// Sizing of four-panel pants (front/back x left/right). Girths are garment girths (body
/// plus ease). Short inseams (h1 - h3 < 40 cm) give shorts: the knee line is then below
/// the hem and w3 is not used.
struct PantsSizing {
    double w1 = 84.0;   ///< cm, waist girth of the garment
    double w2 = 104.0;  ///< cm, bottom (seat / hip) girth of the garment
    double w3 = 48.0;   ///< cm, knee girth of one leg
    double w4 = 42.0;   ///< cm, ankle (leg opening) girth of one leg
    double h1 = 102.0;  ///< cm, total length: waist to hem along the side seam
    double h2 = 31.0;   ///< cm, back upper length: crotch line to centre-back waist
    double h3 = 26.0;   ///< cm, front upper length: crotch line to centre-front waist

    static const std::array<ParameterSpec<PantsSizing>, 7>& parameters();
};

/// The pants pattern: panels "front_right", "front_left", "back_right", "back_left";
/// side seams, inseams and crotch seams sewn; waist and hems open.
/// \throw drape::InvalidInput naming the parameter and value when out of range or when
///        the lengths are inconsistent (inseam h1 - h3 < 5 cm, back rise h2 < h3 - 5).
Pattern make_pants(const PantsSizing& sizing);

}  // namespace drape::garment
