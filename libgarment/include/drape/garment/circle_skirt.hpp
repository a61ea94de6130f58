// The circle skirt template, G_skirt = <l1, r1, r2, alpha> (paper section 5.2, Fig. 3b).
#pragma once

#include <drape/garment/parameter_spec.hpp>
#include <drape/garment/pattern.hpp>

#include <array>

namespace drape::garment {

/// Sizing of the two-panel (front, back) circle skirt. Each panel: a waist arc of length
/// l1 and radius r1 (so it sweeps l1 / r1 radians), two straight side seams of length r2
/// that open by the flare angle alpha (angle between the two side seams), and a hem arc
/// sweeping alpha. alpha = l1 / r1 (in degrees) gives the classic circle-skirt sector;
/// alpha = 0 gives parallel sides (a straight skirt with a curved waist).
struct SkirtSizing {
    double l1 = 38.0;     ///< cm, waist arc per panel = half the skirt's waist girth
    double r1 = 24.0;     ///< cm, waist arc radius (flatter waist = larger r1)
    double r2 = 55.0;     ///< cm, side-seam length = skirt length
    double alpha = 90.0;  ///< degrees, flare: angle between the two side seams of a panel

    static const std::array<ParameterSpec<SkirtSizing>, 4>& parameters();
};

/// The circle-skirt pattern: panels "front" and "back" (edges: 0 hem, 1 right side,
/// 2 waist, 3 left side), side seams sewn, waist and hem open.
/// \throw drape::InvalidInput naming the parameter and value when a parameter is out of
///        range, when the waist arc would sweep more than 180 degrees (l1 / r1 > pi), or when
///        the resulting panel self-intersects.
Pattern make_circle_skirt(const SkirtSizing& sizing);

}  // namespace drape::garment
