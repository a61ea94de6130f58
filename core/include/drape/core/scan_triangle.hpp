// The pixels a projected triangle covers: the one scan conversion behind the body fit's
// silhouettes (body::render_silhouette) and the label rasteriser (render::rasterize).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace drape::core {

/// Calls `fn(x, y, wa, wb, wc)` for every pixel (x, y) of a `width` x `height` image whose
/// centre (x + 0.5, y + 0.5) lies inside the triangle (a, b, c) or on one of its edges, in
/// rows from the top and left to right within a row. Either winding counts. `wa`, `wb`,
/// `wc` are the barycentric weights of corners a, b and c at that centre (each >= 0, sum 1
/// up to rounding).
///
/// \param a, b, c the corners in the image frame: pixels, x right, y down, origin at the
///        top-left corner of the top-left pixel (so pixel (x, y)'s centre is at +0.5).
/// \param width, height the image size (>= 0); pixels outside it are never visited.
/// \note A degenerate (zero-area) or non-finite triangle covers no pixel. The weights are
///       stepped incrementally along a row, so a centre lying exactly on an edge may fall
///       either side of it by rounding.
/// \throw nothing itself (only what `fn` throws).
template <class Fn>
void scan_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, int width,
                   int height, Fn&& fn) {
    const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (!(area != 0.0) || !std::isfinite(area)) return;
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}) - 0.5)));
    const int x1 = std::min(width - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}) - 0.5)));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}) - 0.5)));
    const int y1 = std::min(height - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}) - 0.5)));
    if (x0 > x1 || y0 > y1) return;
    // The weight of a corner is the edge function of the opposite edge over the signed
    // area, linear in the pixel position: stepped by its x coefficient along a row.
    const double inv = 1.0 / area;
    const double dwa = (c.y() - b.y()) * inv, dwb = (a.y() - c.y()) * inv, dwc = (b.y() - a.y()) * inv;
    for (int y = y0; y <= y1; ++y) {
        const double py = y + 0.5, px0 = x0 + 0.5;
        double wa = ((c.x() - b.x()) * (py - b.y()) - (c.y() - b.y()) * (px0 - b.x())) * inv;
        double wb = ((a.x() - c.x()) * (py - c.y()) - (a.y() - c.y()) * (px0 - c.x())) * inv;
        double wc = ((b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px0 - a.x())) * inv;
        for (int x = x0; x <= x1; ++x, wa -= dwa, wb -= dwb, wc -= dwc)
            if (wa >= 0 && wb >= 0 && wc >= 0) fn(x, y, wa, wb, wc);
    }
}

}  // namespace drape::core
