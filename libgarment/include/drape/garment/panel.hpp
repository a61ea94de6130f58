// A sewing-pattern panel (pattern piece): a closed, counter-clockwise boundary of edges in
// the panel's own 2D frame (centimetres), a grain line, notches and internal lines.
#pragma once

#include <drape/garment/edge.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape::garment {

/// A notch: a short cut into the seam allowance marking where two pieces meet.
struct Notch {
    int edge = 0;          ///< index into Panel::edges
    double fraction = 0;   ///< arc-length fraction along that edge, [0, 1]
};

/// A marking inside the piece (centre line, dart leg, placement line), straight, cm.
struct InternalLine {
    Eigen::Vector2d a = Eigen::Vector2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
};

/// A pattern piece. Frame: the panel's 2D frame in centimetres; x is the weft (u) axis, y
/// the warp (v) axis of the cloth simulator when the grain runs along y.
struct Panel {
    std::string name;          ///< unique in its pattern, e.g. "front", "left_sleeve"
    std::vector<Edge> edges;   ///< closed loop: edges[i].end == edges[i+1].start; CCW
    Eigen::Vector2d grain = Eigen::Vector2d(0, 1);  ///< grain line direction (warp), unit
    std::vector<Notch> notches;
    std::vector<InternalLine> internal_lines;

    /// Checks the loop: at least 2 edges, finite numbers, consecutive edges joined (within
    /// 1e-6 cm), counter-clockwise (area > 0), no self-intersection (on a polyline with
    /// 0.5 cm chords), notches on existing edges, grain non-zero. Explains the first
    /// failure in `why` (prefixed with the panel name).
    bool is_valid(std::string* why = nullptr) const;

    double area() const;        ///< exact enclosed area, cm² (positive when CCW)
    double perimeter() const;   ///< sum of edge lengths, cm
    /// Closed boundary polyline (last point not repeated), chords <= max_chord_cm.
    std::vector<Eigen::Vector2d> outline(double max_chord_cm) const;
    /// Axis-aligned bounds of the outline (min, max), cm.
    void bounds(Eigen::Vector2d* lo, Eigen::Vector2d* hi) const;

    /// The mirror image x -> -x, still counter-clockwise: edge i of this panel becomes edge
    /// (n - 1 - i) of the mirror, traversed in the opposite direction. Notches and lines
    /// are mirrored too. `new_name` names the result.
    Panel mirrored(const std::string& new_name) const;
    /// Index of edge i of this panel in mirrored(): n - 1 - i.
    int mirrored_edge_index(int i) const { return static_cast<int>(edges.size()) - 1 - i; }
};

}  // namespace drape::garment
