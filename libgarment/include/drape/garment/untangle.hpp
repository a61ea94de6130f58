// Removing self-intersections from a dressed garment before it is simulated: the
// simulator's penalty self-contact locks in any crossing present at the start.
#pragma once

#include <drape/garment/garment_mesh.hpp>

#include <Eigen/Core>

#include <string>

namespace drape::garment {

struct UntangleOptions {
    int max_iterations = 150;     ///< separation rounds, >= 1
    double step_m = 0.002;        ///< how far a round moves the two sides of a crossing apart, (0, 0.05] m
    double clearance_m = 0.004;   ///< the inner side is not moved closer to the body than this, >= 0 m
    bool is_valid(std::string* why = nullptr) const;
};

struct UntangleSummary {
    int initial_self_intersections = 0;  ///< crossing triangle pairs before (as check_garment_state counts them)
    int self_intersections = 0;          ///< after
    int iterations = 0;                  ///< rounds used
    int vertices_moved = 0;
    double max_displacement_m = 0;       ///< largest distance a vertex moved
    double seconds = 0;
    bool usable() const { return self_intersections == 0; }
    std::string brief_report() const;
};

/// Separates the crossing parts of a garment that lies around a body, in the spirit of
/// intersection-contour minimisation (Volino & Magnenat-Thalmann 2006; Baraff et al. 2003):
/// each round finds the intersecting triangle pairs (stitched partners as one vertex) and
/// moves the vertices of the two triangles of each pair apart along the body's outward
/// normal at the crossing, the triangle farther from the body outwards and the nearer one
/// inwards (its own layer's side), the displacement spread over one ring of neighbours so
/// that no spike forms; stitched vertices move together. The state with the fewest
/// crossings is kept.
/// \param positions #V x 3 (world, metres), changed in place.
/// \param body_vertices #B x 3, \param body_faces #F x 3: the (posed) body, closed.
/// \throw drape::InvalidInput if sizes mismatch, positions are not finite or the options
///        are invalid.
UntangleSummary untangle_garment(const GarmentMesh& mesh, const Eigen::MatrixX3d& body_vertices,
                                 const Eigen::MatrixX3i& body_faces, const UntangleOptions& options,
                                 Eigen::MatrixX3d& positions);

}  // namespace drape::garment
