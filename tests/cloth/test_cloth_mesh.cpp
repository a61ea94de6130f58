#include <drape/cloth/cloth_mesh.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <set>

using namespace drape::cloth;
using Catch::Matchers::Contains;

namespace {
ClothMesh grid(int n) {
    return make_square_grid(n, 1.0, Eigen::Vector3d(0, 0, 0.6), Eigen::Vector3d::UnitX(),
                            Eigen::Vector3d::UnitY());
}
}  // namespace

TEST_CASE("a square grid is valid and has the expected hinges", "[cloth][mesh]") {
    for (int n : {1, 2, 5, 32}) {
        const ClothMesh mesh = grid(n);
        CHECK(mesh.vertex_count() == (n + 1) * (n + 1));
        CHECK(mesh.face_count() == 2 * n * n);
        CHECK_NOTHROW(mesh.validate());
        const auto hinges = build_hinges(mesh);
        CHECK(static_cast<int>(hinges.size()) == 3 * n * n - 2 * n);  // interior edges
        for (const Hinge& h : hinges) {
            const std::set<int> distinct(h.v.begin(), h.v.end());
            CHECK(distinct.size() == 4);
            // faces[0] is (v0, v1, v2) counter-clockwise: v1 follows v0 in it.
            const int f = h.faces[0];
            const int c0 = h.corners[0][0];
            CHECK(mesh.faces(f, c0) == h.v[0]);
            CHECK(mesh.faces(f, (c0 + 1) % 3) == h.v[1]);
            CHECK(mesh.faces(h.faces[1], h.corners[1][0]) == h.v[0]);
            CHECK(mesh.faces(h.faces[1], h.corners[1][1]) == h.v[1]);
        }
    }
}

TEST_CASE("bad meshes are rejected naming the element", "[cloth][mesh]") {
    SECTION("NaN position") {
        ClothMesh mesh = grid(2);
        mesh.positions(4, 1) = std::nan("");
        CHECK_THROWS_WITH(mesh.validate(), Contains("vertex 4") && Contains("not finite"));
    }
    SECTION("degenerate pattern triangle") {
        ClothMesh mesh = grid(2);
        mesh.pattern.row(mesh.faces(3, 2)) = mesh.pattern.row(mesh.faces(3, 1));
        CHECK_THROWS_AS(mesh.validate(), drape::InvalidInput);
        CHECK_THROWS_WITH(mesh.validate(), Contains("pattern triangle of face"));
    }
    SECTION("clockwise pattern triangle") {
        ClothMesh mesh = grid(1);
        mesh.pattern.col(0) *= -1;  // mirror: every triangle flips
        CHECK_THROWS_WITH(mesh.validate(), Contains("face 0") && Contains("clockwise"));
    }
    SECTION("non-manifold edge") {
        ClothMesh mesh = grid(1);  // faces (0,1,3) and (0,3,2)
        Eigen::MatrixX3d x(5, 3);
        x.topRows(4) = mesh.positions;
        x.row(4) << 0.5, 0.5, 1.0;
        Eigen::MatrixX2d uv(5, 2);
        uv.topRows(4) = mesh.pattern;
        uv.row(4) << 2.0, 0.0;  // (4, 3, 0) is counter-clockwise in the pattern
        Eigen::MatrixX3i f(3, 3);
        f << 0, 1, 3, 0, 3, 2, 4, 3, 0;  // a third face on edge (0, 3)
        mesh = ClothMesh::from_vertex_pattern(x, f, uv);
        CHECK_THROWS_WITH(mesh.validate(), Contains("edge (0, 3) is non-manifold"));
    }
    SECTION("inconsistent orientation") {
        ClothMesh mesh = grid(1);
        mesh.faces.row(1) << 0, 2, 3;  // traverses 3->0 like face (0, 1, 3)
        mesh.pattern_faces = mesh.faces;
        mesh.pattern.row(2) << 2.0, 0.5;  // keep (0, 2, 3) counter-clockwise in the pattern
        CHECK_THROWS_WITH(mesh.validate(), Contains("same direction"));
    }
    SECTION("out-of-range index and shape mismatch") {
        ClothMesh mesh = grid(1);
        mesh.faces(1, 2) = 17;
        mesh.pattern_faces = mesh.faces;
        CHECK_THROWS_WITH(mesh.validate(), Contains("face 1") && Contains("17"));
        ClothMesh other = grid(1);
        other.pattern_faces.resize(1, 3);
        CHECK_THROWS_WITH(other.validate(), Contains("pattern_faces"));
    }
    CHECK_THROWS_AS(make_square_grid(0, 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                     Eigen::Vector3d::UnitY()),
                    drape::InvalidInput);
}
