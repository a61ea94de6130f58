#include <drape/cloth/cloth_mesh.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

namespace drape::cloth {

namespace {

std::uint64_t edge_key(int a, int b) {
    const auto lo = static_cast<std::uint64_t>(std::min(a, b));
    const auto hi = static_cast<std::uint64_t>(std::max(a, b));
    return (hi << 32) | lo;
}

struct EdgeUse {
    int face;
    int corner_from;  // corner index (0..2) of the edge's first vertex in traversal order
    int from, to;
};

}  // namespace

ClothMesh ClothMesh::from_vertex_pattern(const Eigen::MatrixX3d& positions,
                                         const Eigen::MatrixX3i& faces,
                                         const Eigen::MatrixX2d& pattern) {
    ClothMesh mesh;
    mesh.positions = positions;
    mesh.faces = faces;
    mesh.pattern = pattern;
    mesh.pattern_faces = faces;
    return mesh;
}

void ClothMesh::validate() const {
    const Eigen::Index nv = positions.rows();
    const Eigen::Index np = pattern.rows();
    require(faces.rows() > 0, "ClothMesh: faces is empty");
    require(pattern_faces.rows() == faces.rows(), "ClothMesh: pattern_faces has ",
            pattern_faces.rows(), " rows, faces has ", faces.rows());
    for (Eigen::Index i = 0; i < nv; ++i)
        require(positions.row(i).allFinite(), "ClothMesh: positions row ", i, " (vertex ", i,
                ") is not finite");
    for (Eigen::Index i = 0; i < np; ++i)
        require(pattern.row(i).allFinite(), "ClothMesh: pattern row ", i, " is not finite");
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
        for (int k = 0; k < 3; ++k) {
            require(faces(f, k) >= 0 && faces(f, k) < nv, "ClothMesh: face ", f, " corner ", k,
                    " = ", faces(f, k), " is out of range [0, ", nv, ")");
            require(pattern_faces(f, k) >= 0 && pattern_faces(f, k) < np, "ClothMesh: face ", f,
                    " pattern corner ", k, " = ", pattern_faces(f, k), " is out of range [0, ",
                    np, ")");
        }
        require(faces(f, 0) != faces(f, 1) && faces(f, 1) != faces(f, 2) &&
                    faces(f, 0) != faces(f, 2),
                "ClothMesh: face ", f, " repeats a vertex (", faces(f, 0), ", ", faces(f, 1),
                ", ", faces(f, 2), ")");
        const Eigen::RowVector2d a = pattern.row(pattern_faces(f, 0));
        const Eigen::RowVector2d b = pattern.row(pattern_faces(f, 1));
        const Eigen::RowVector2d c = pattern.row(pattern_faces(f, 2));
        const Eigen::RowVector2d e1 = b - a, e2 = c - a;
        const double area = 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
        require(area > 1e-12, "ClothMesh: pattern triangle of face ", f, " has signed area ",
                area, " m² (degenerate or clockwise; must be > 1e-12)");
    }
    // A pattern point is the rest position of one vertex (a vertex may have several: one
    // per panel of a seam).
    std::vector<int> point_vertex(static_cast<std::size_t>(np), -1);
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            int& v = point_vertex[static_cast<std::size_t>(pattern_faces(f, k))];
            require(v < 0 || v == faces(f, k), "ClothMesh: pattern point ", pattern_faces(f, k),
                    " is a corner of vertex ", v, " and of vertex ", faces(f, k), " (face ", f,
                    " corner ", k, "); a pattern point belongs to one vertex");
            v = faces(f, k);
        }
    std::map<std::uint64_t, std::vector<std::pair<int, int>>> uses;  // key -> (face, from)
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = faces(f, k), b = faces(f, (k + 1) % 3);
            auto& list = uses[edge_key(a, b)];
            list.emplace_back(static_cast<int>(f), a);
            require(list.size() <= 2, "ClothMesh: edge (", std::min(a, b), ", ", std::max(a, b),
                    ") is non-manifold: it has more than two faces (", list[0].first, ", ",
                    list[1].first, ", ", f, ")");
            if (list.size() == 2)
                require(list[0].second != list[1].second, "ClothMesh: faces ", list[0].first,
                        " and ", f, " traverse edge (", std::min(a, b), ", ", std::max(a, b),
                        ") in the same direction (inconsistent orientation)");
        }
}

std::vector<Hinge> build_hinges(const ClothMesh& mesh) {
    mesh.validate();
    std::map<std::uint64_t, std::vector<EdgeUse>> uses;
    for (int f = 0; f < mesh.face_count(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = mesh.faces(f, k), b = mesh.faces(f, (k + 1) % 3);
            uses[edge_key(a, b)].push_back({f, k, a, b});
        }
    std::vector<Hinge> hinges;
    for (const auto& [key, list] : uses) {
        if (list.size() != 2) continue;
        const EdgeUse& s0 = list[0];
        const EdgeUse& s1 = list[1];
        Hinge h;
        h.v[0] = s0.from;
        h.v[1] = s0.to;
        h.v[2] = mesh.faces(s0.face, (s0.corner_from + 2) % 3);
        h.v[3] = mesh.faces(s1.face, (s1.corner_from + 2) % 3);
        h.faces = {s0.face, s1.face};
        // s1 traverses the edge as v[1] -> v[0].
        h.corners[0] = {s0.corner_from, (s0.corner_from + 1) % 3};
        h.corners[1] = {(s1.corner_from + 1) % 3, s1.corner_from};
        hinges.push_back(h);
    }
    return hinges;
}

ClothMesh make_square_grid(int n, double size_m, const Eigen::Vector3d& origin,
                           const Eigen::Vector3d& axis_u, const Eigen::Vector3d& axis_v) {
    require(n >= 1, "make_square_grid: n = ", n, " must be >= 1");
    require(size_m > 0 && std::isfinite(size_m), "make_square_grid: size_m = ", size_m,
            " must be > 0");
    const int side = n + 1;
    Eigen::MatrixX3d x(side * side, 3);
    Eigen::MatrixX2d uv(side * side, 2);
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const double u = size_m * i / n, v = size_m * j / n;
            const int id = j * side + i;
            uv.row(id) << u, v;
            x.row(id) = (origin + u * axis_u + v * axis_v).transpose();
        }
    Eigen::MatrixX3i faces(2 * n * n, 3);
    int f = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * side + i, b = a + 1, c = a + side, d = c + 1;
            if ((i + j) % 2 == 0) {
                faces.row(f++) << a, b, d;
                faces.row(f++) << a, d, c;
            } else {
                faces.row(f++) << a, b, c;
                faces.row(f++) << b, d, c;
            }
        }
    return ClothMesh::from_vertex_pattern(x, faces, uv);
}

}  // namespace drape::cloth
