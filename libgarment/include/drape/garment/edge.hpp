// One edge of a sewing-pattern panel boundary: a straight line, a circular arc or a cubic
// Bézier curve, in the panel's 2D frame (centimetres).
#pragma once

#include <Eigen/Core>

#include <vector>

namespace drape::garment {

enum class EdgeKind { line, arc, cubic };

/// A boundary edge from `start` to `end` (panel frame, cm).
///
/// Arcs use the DXF "bulge" convention: bulge = tan(sweep / 4), where sweep is the signed
/// angle swept from start to end; positive = counter-clockwise (the arc bulges to the right
/// of the chord direction start -> end), negative = clockwise. |bulge| < 1 is a minor arc,
/// 1 a half circle; |bulge| must stay below ~50 (sweep below 357 degrees).
/// Cubic Béziers have the two inner control points `control1`, `control2` (panel frame, cm).
struct Edge {
    EdgeKind kind = EdgeKind::line;
    Eigen::Vector2d start = Eigen::Vector2d::Zero();
    Eigen::Vector2d end = Eigen::Vector2d::Zero();
    double bulge = 0.0;                                   ///< arc only
    Eigen::Vector2d control1 = Eigen::Vector2d::Zero();   ///< cubic only
    Eigen::Vector2d control2 = Eigen::Vector2d::Zero();   ///< cubic only

    static Edge line(const Eigen::Vector2d& a, const Eigen::Vector2d& b);
    /// \pre a != b and bulge != 0 (use line() for a straight edge).
    static Edge arc(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double bulge);
    static Edge cubic(const Eigen::Vector2d& a, const Eigen::Vector2d& c1,
                      const Eigen::Vector2d& c2, const Eigen::Vector2d& b);

    /// The same curve traversed from `end` to `start`.
    Edge reversed() const;
    /// The curve mirrored by x -> -x (keeps the direction start -> end).
    Edge mirrored_x() const;

    /// Exact length (lines, arcs) or adaptive-quadrature length (cubics), cm.
    double length() const;
    /// Point at curve parameter t in [0, 1] (arcs: angle-uniform = length-uniform).
    Eigen::Vector2d point(double t) const;
    /// Point at arc-length fraction s in [0, 1] (0 = start, 1 = end).
    Eigen::Vector2d point_at_fraction(double s) const;
    /// Unit tangent at arc-length fraction s, direction start -> end.
    Eigen::Vector2d tangent_at_fraction(double s) const;
    /// Signed area contribution (1/2) ∫ (x dy - y dx) along the edge, cm² (exact for lines,
    /// arcs and cubics); summing it over a closed loop gives the enclosed signed area.
    double area_term() const;
    /// Points at arc-length fractions 0, 1/n, ..., 1 (n + 1 rows, n >= 1).
    std::vector<Eigen::Vector2d> sample_uniform(int n) const;
    /// Polyline with chords no longer than `max_chord_cm` and angular deviation below about
    /// 2 degrees per chord; includes both end points.
    std::vector<Eigen::Vector2d> polyline(double max_chord_cm) const;
    /// For arcs: centre, radius (cm) and start angle/sweep (radians). \pre kind == arc.
    void arc_geometry(Eigen::Vector2d* centre, double* radius, double* start_angle,
                      double* sweep) const;
};

}  // namespace drape::garment
