// Two cloth pieces in one mesh, for tests of seams and of contact between layers.
#pragma once

#include <drape/cloth/cloth_mesh.hpp>

#include <Eigen/Core>

namespace drape::cloth::test {

/// b's vertices follow a's, and b's pattern is laid 0.1 m to the right of a's so the pieces
/// do not overlap in the pattern plane.
inline ClothMesh two_pieces(const ClothMesh& a, const ClothMesh& b) {
    const int na = a.vertex_count(), nb = b.vertex_count();
    ClothMesh m;
    m.positions.resize(na + nb, 3);
    m.positions << a.positions, b.positions;
    m.faces.resize(a.face_count() + b.face_count(), 3);
    m.faces << a.faces, (b.faces.array() + na).matrix();
    const double shift = a.pattern.col(0).maxCoeff() + 0.1 - b.pattern.col(0).minCoeff();
    m.pattern.resize(na + nb, 2);
    m.pattern << a.pattern, (b.pattern.rowwise() + Eigen::RowVector2d(shift, 0)).eval();
    m.pattern_faces = m.faces;
    return m;
}

}  // namespace drape::cloth::test
