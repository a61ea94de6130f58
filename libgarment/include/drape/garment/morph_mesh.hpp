// Morphing a meshed pattern to a new sizing G of the same template without re-meshing
// (paper eq. 1, u(G) = Σ ν_i (u⁰ + g_i)): the mesh keeps its vertices, faces and stitches,
// only the vertices' pattern positions move. Garment recovery evaluates hundreds of
// sizings; with the topology fixed, a simulator built once takes each new rest shape
// (cloth::Simulator::set_rest_positions) and warm-starts from the last drape.
#pragma once

#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <memory>
#include <string>

namespace drape::garment {

/// The coordinates of a garment mesh in its pattern, fixed once, to map the mesh onto the
/// pattern of another sizing of the same template.
///
/// Boundary vertices keep their edge and arc-length fraction (GarmentMesh::boundary_edge,
/// boundary_fraction): a vertex at fraction s of edge e moves by E'_e(s) − E_e(s), the
/// displacement of the edge's curve at that fraction. So a boundary vertex stays on its
/// edge (at the same chord offset from the curve as the mesher left it), corners stay
/// corners, and the two sides of a seam, which the mesher discretised at equal fractions,
/// still pair up stitch by stitch. Interior vertices move by the discrete harmonic
/// extension of the boundary displacement (cotangent weights of the original mesh, whose
/// Delaunay triangles make them non-negative): generalised barycentric coordinates of the
/// boundary vertices, fixed at construction (one sparse factorisation), which reproduce
/// affine maps exactly. Morphing to the original pattern is the identity (zero
/// displacement).
///
/// What cannot be morphed (the caller re-meshes with mesh_pattern instead): a pattern
/// whose panel structure differs (other panel names or count, edge count, seams),
/// e.g. a t-shirt with l1 = 0 (a tank top: no sleeve panels) against one with sleeves;
/// and a change so large that a triangle inverts (morph() throws, naming the face).
///
/// Thread safety: const member functions may be called from several threads at once;
/// copies are cheap (they share the immutable coordinates).
class PatternMorph {
public:
    /// \param pattern the pattern `mesh` was made from (mesh_pattern(pattern, ..., mesh)).
    /// \throw drape::InvalidInput if the pattern is invalid or the mesh does not belong to
    ///        it (per-vertex arrays of the wrong size, a panel or edge index out of range).
    PatternMorph(const Pattern& pattern, const GarmentMesh& mesh);

    /// The mesh on `new_pattern`: panel_point_cm, cloth.pattern (the new flat layout,
    /// layout_offsets, metres), uv and cloth.positions (the new placement hints) are
    /// recomputed; faces, stitches, boundary loops, edges and fractions are the original's.
    /// \throw drape::InvalidInput if new_pattern is invalid, its structure differs (the
    ///        message says how: re-mesh then), or a triangle inverts (naming the face).
    GarmentMesh morph(const Pattern& new_pattern) const;

    /// Only the new panel-frame coordinates (#V x 2, cm) of morph(); same checks.
    Eigen::MatrixX2d panel_points_cm(const Pattern& new_pattern) const;

    const Pattern& pattern() const;
    const GarmentMesh& mesh() const;

    /// True if `b` can be morphed to from a mesh of `a`: the same panel names in the same
    /// order, the same edge count per panel (a line may become an arc: edges move by their
    /// curves), the same seams. Explains the first
    /// difference in `why`.
    static bool same_structure(const Pattern& a, const Pattern& b, std::string* why = nullptr);

private:
    struct Data;
    std::shared_ptr<const Data> data_;
};

}  // namespace drape::garment
