// A sewing pattern: panels, their placement hints and the seams joining them.
#pragma once

#include <drape/garment/panel.hpp>
#include <drape/garment/placement.hpp>
#include <drape/garment/seam.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape::garment {

/// Largest relative length difference allowed between the two edges of a seam.
inline constexpr double kMaxSeamMismatch = 0.01;

struct Pattern {
    std::string name;                       ///< e.g. "circle_skirt"
    std::vector<Panel> panels;
    std::vector<PanelPlacement> placements; ///< one per panel
    std::vector<Seam> seams;

    /// Every panel valid (Panel::is_valid), unique panel names, one placement per panel,
    /// seam indices in range, no edge in two seams, no edge sewn to itself, and seam
    /// lengths within kMaxSeamMismatch. Explains the first failure in `why`.
    bool is_valid(std::string* why = nullptr) const;
    /// \throw drape::InvalidInput with the explanation of is_valid().
    void validate() const;

    /// Relative length mismatch |LA - LB| / max(LA, LB) of a seam.
    double seam_mismatch(const Seam& seam) const;
    /// Index of the panel with this name, or -1.
    int panel_index(const std::string& panel_name) const;
    /// Sum of panel areas, cm².
    double total_area() const;
};

/// A flat layout of the panels for printing, OBJ export and UVs: panel i is drawn at
/// (its own frame) + offsets[i], in a left-to-right row with `gap_cm` between bounding
/// boxes and all coordinates >= 0 (cm).
std::vector<Eigen::Vector2d> layout_offsets(const Pattern& pattern, double gap_cm = 5.0);

}  // namespace drape::garment
