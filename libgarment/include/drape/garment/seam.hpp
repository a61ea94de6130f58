// A seam: two panel edges sewn together.
#pragma once

#include <string>

namespace drape::garment {

/// How the two edges of a seam run. With `reversed`, the start of edge A meets the end of
/// edge B (the usual case for two counter-clockwise panels sewn right side to right side);
/// with `same`, start meets start.
enum class SeamOrientation { same, reversed };

/// Edge `edge_a` of panel `panel_a` is sewn to edge `edge_b` of panel `panel_b` (indices
/// into Pattern::panels and Panel::edges). A panel may be sewn to itself (a sleeve tube).
struct Seam {
    int panel_a = 0;
    int edge_a = 0;
    int panel_b = 0;
    int edge_b = 0;
    SeamOrientation orientation = SeamOrientation::reversed;
};

/// Arc-length fraction on edge B that meets fraction `s` of edge A.
inline double partner_fraction(const Seam& seam, double s) {
    return seam.orientation == SeamOrientation::same ? s : 1.0 - s;
}

}  // namespace drape::garment
