// Triangulating a sewing pattern into a simulation mesh (CGAL conforming constrained
// Delaunay triangulation + Delaunay refinement), with stitched seam vertices.
#pragma once

#include <drape/cloth/cloth_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace drape::garment {

struct MeshOptions {
    double target_edge_cm = 1.5;     ///< aimed mean edge length, cm; (0.2, 20]
    double min_angle_deg = 20.6;     ///< Delaunay refinement angle bound; (0, 20.7]
    /// false: the refinement never splits boundary segments (CGAL's mesher without edge
    /// refinement), so seams keep their pre-discretised points and one round suffices.
    /// true: conforming (Gabriel) boundary refinement; splits are mirrored onto partner
    /// edges and the panels re-meshed, up to `max_seam_rounds` rounds.
    bool refine_boundary = false;
    int max_seam_rounds = 8;         ///< rounds of seam re-synchronisation, >= 1
    bool is_valid(std::string* why = nullptr) const;
};

/// The meshed pattern. One world vertex per pattern vertex: panels are separate pieces
/// and the seams are given as `stitches` (vertex pairs to be sewn by the simulator).
struct GarmentMesh {
    /// positions: placement hint of each panel (world, metres); pattern: the flat layout
    /// (layout_offsets, metres, CCW faces, u = weft = panel x); pattern_faces == faces.
    cloth::ClothMesh cloth;
    Eigen::VectorXi panel_of_vertex;              ///< #V, index into Pattern::panels
    std::vector<std::array<int, 2>> stitches;     ///< (i, j) vertices sewn together
    std::vector<int> stitch_seam;                 ///< per stitch: index into Pattern::seams
    std::vector<std::vector<int>> boundary_loops; ///< per panel: CCW boundary vertex loop
    /// Per vertex: panel-frame coordinates (cm) and the edge/fraction of boundary vertices.
    Eigen::MatrixX2d panel_point_cm;              ///< #V x 2
    Eigen::VectorXi boundary_edge;                ///< #V, edge index or -1 (interior)
    Eigen::VectorXd boundary_fraction;            ///< #V, arc-length fraction on that edge
    Eigen::MatrixX2d uv;                          ///< #V x 2, layout scaled into [0, 1]²
};

enum class MeshTermination { converged, seam_rounds_exhausted };

struct MeshSummary {
    MeshTermination termination = MeshTermination::converged;
    std::string message;
    int vertices = 0;
    int faces = 0;
    int stitches = 0;
    int seam_rounds = 0;           ///< meshing rounds until seams agreed
    double min_angle_deg = 0;      ///< smallest triangle angle
    double mean_edge_cm = 0;
    double area_cm2 = 0;           ///< meshed pattern area
    double seconds = 0;
    bool usable() const { return termination == MeshTermination::converged; }
    std::string brief_report() const;
};

/// Meshes every panel with a constrained Delaunay triangulation refined to
/// `target_edge_cm` and `min_angle_deg` (CGAL). Seam edges are discretised identically on
/// both sides (equal arc-length fractions, respecting the seam orientation) before
/// meshing. With MeshOptions::refine_boundary, a refinement split of a seam edge is
/// mirrored on the partner edge and the panels are meshed again until both sides agree.
/// \pre pattern.validate() passes. \throw drape::InvalidInput if it does not or the
///      options are invalid.
MeshSummary mesh_pattern(const Pattern& pattern, const MeshOptions& options, GarmentMesh& out);

}  // namespace drape::garment
