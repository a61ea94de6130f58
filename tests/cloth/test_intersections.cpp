// Intersection checks: triangle pairs, self-intersections of folded sheets, two meshes,
// points inside a closed mesh; BVH results against brute force.
#include <drape/cloth/intersections.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include "folded_sheet_fixture.hpp"

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <random>

using namespace drape::cloth;

namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Matrix3d tri(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    Eigen::Matrix3d t;
    t << a, b, c;
    return t;
}

// A closed UV sphere: `stacks` rings between two pole vertices, `slices` around.
void uv_sphere(int stacks, int slices, double radius, const Eigen::Vector3d& centre,
               Eigen::MatrixX3d& positions, Eigen::MatrixX3i& faces) {
    const int rings = stacks - 1;
    positions.resize(2 + rings * slices, 3);
    positions.row(0) = (centre + Eigen::Vector3d(0, radius, 0)).transpose();
    positions.row(1) = (centre - Eigen::Vector3d(0, radius, 0)).transpose();
    auto ring_vertex = [&](int r, int s) { return 2 + r * slices + (s % slices); };
    for (int r = 0; r < rings; ++r) {
        const double phi = kPi * (r + 1) / stacks;
        for (int s = 0; s < slices; ++s) {
            const double theta = 2 * kPi * s / slices;
            positions.row(ring_vertex(r, s)) =
                (centre + radius * Eigen::Vector3d(std::sin(phi) * std::cos(theta), std::cos(phi),
                                                   std::sin(phi) * std::sin(theta)))
                    .transpose();
        }
    }
    faces.resize(2 * slices + 2 * (rings - 1) * slices, 3);
    int f = 0;
    for (int s = 0; s < slices; ++s) {
        faces.row(f++) << 0, ring_vertex(0, s + 1), ring_vertex(0, s);
        faces.row(f++) << 1, ring_vertex(rings - 1, s), ring_vertex(rings - 1, s + 1);
        for (int r = 0; r + 1 < rings; ++r) {
            faces.row(f++) << ring_vertex(r, s), ring_vertex(r, s + 1), ring_vertex(r + 1, s);
            faces.row(f++) << ring_vertex(r + 1, s), ring_vertex(r, s + 1),
                ring_vertex(r + 1, s + 1);
        }
    }
}

// Brute force over all non-adjacent pairs.
std::vector<std::pair<int, int>> brute_force_self(const Eigen::MatrixX3d& p,
                                                  const Eigen::MatrixX3i& faces) {
    auto corners = [&](int f) {
        return tri(p.row(faces(f, 0)), p.row(faces(f, 1)), p.row(faces(f, 2)));
    };
    std::vector<std::pair<int, int>> out;
    for (int f = 0; f < faces.rows(); ++f)
        for (int g = f + 1; g < faces.rows(); ++g) {
            bool shared = false;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) shared = shared || faces(f, i) == faces(g, j);
            if (!shared && triangles_intersect(corners(f), corners(g))) out.push_back({f, g});
        }
    return out;
}

}  // namespace

TEST_CASE("triangle pairs: crossing, separated, touching, coplanar", "[cloth][intersections]") {
    using V = Eigen::Vector3d;
    const Eigen::Matrix3d a = tri(V(0, 0, 0), V(1, 0, 0), V(0, 1, 0));
    // Piercing through the interior.
    CHECK(triangles_intersect(a, tri(V(0.2, 0.2, -1), V(0.3, 0.2, 1), V(0.2, 0.3, 1))));
    // Same but shifted out of the triangle in x + y.
    CHECK_FALSE(triangles_intersect(a, tri(V(0.8, 0.8, -1), V(0.9, 0.8, 1), V(0.8, 0.9, 1))));
    // Parallel planes.
    CHECK_FALSE(triangles_intersect(a, tri(V(0, 0, 1e-6), V(1, 0, 1e-6), V(0, 1, 1e-6))));
    // A vertex touching the interior (closed sets).
    CHECK(triangles_intersect(a, tri(V(0.2, 0.2, 0), V(0.3, 0.2, 1), V(0.2, 0.3, 1))));
    // Coplanar: overlapping, contained, disjoint.
    CHECK(triangles_intersect(a, tri(V(0.5, 0.5, 0), V(-0.5, 0.2, 0), V(0.2, -0.5, 0))));
    CHECK(triangles_intersect(a, tri(V(0.1, 0.1, 0), V(0.2, 0.1, 0), V(0.1, 0.2, 0))));
    CHECK_FALSE(triangles_intersect(a, tri(V(1, 1, 0), V(2, 1, 0), V(1, 2, 0))));
    // Edge crossing edge in a T configuration (b's edge crosses a's edge).
    CHECK(triangles_intersect(a, tri(V(0.5, -0.5, 0.5), V(0.5, 0.5, -0.5), V(0.5, -0.5, -0.5))));
    // Symmetric in its arguments.
    const Eigen::Matrix3d b = tri(V(0.2, 0.2, -1), V(0.3, 0.2, 1), V(0.2, 0.3, 1));
    CHECK(triangles_intersect(b, a));
}

TEST_CASE("two crossing squares intersect, separated ones do not", "[cloth][intersections]") {
    const ClothMesh flat = make_square_grid(8, 1.0, Eigen::Vector3d::Zero(),
                                            Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    // A vertical square through the middle of the flat one.
    const ClothMesh crossing =
        make_square_grid(8, 1.0, Eigen::Vector3d(0.013, 0.0, -0.5), Eigen::Vector3d::UnitY(),
                         Eigen::Vector3d::UnitZ());
    std::vector<std::pair<int, int>> pairs;
    const int n = count_intersections(flat.positions, flat.faces, crossing.positions,
                                      crossing.faces, &pairs);
    CHECK(n > 0);
    CHECK(n == static_cast<int>(pairs.size()));
    // Every reported pair really intersects; the crossing line x = 0.013 spans 16 rows.
    for (auto [f, g] : pairs) {
        CHECK(triangles_intersect(
            tri(flat.positions.row(flat.faces(f, 0)), flat.positions.row(flat.faces(f, 1)),
                flat.positions.row(flat.faces(f, 2))),
            tri(crossing.positions.row(crossing.faces(g, 0)),
                crossing.positions.row(crossing.faces(g, 1)),
                crossing.positions.row(crossing.faces(g, 2)))));
    }
    const ClothMesh above = make_square_grid(8, 1.0, Eigen::Vector3d(0, 0, 0.001),
                                             Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    CHECK(count_intersections(flat.positions, flat.faces, above.positions, above.faces) == 0);
    CHECK(count_self_intersections(flat.positions, flat.faces) == 0);  // coplanar, disjoint
}

TEST_CASE("a folded sheet self-intersects only when a layer passes through",
          "[cloth][intersections]") {
    const double gap = 0.004;
    ClothMesh mesh = test::folded_sheet(20, 0.2, gap, 0.11);
    CHECK(count_self_intersections(mesh.positions, mesh.faces) == 0);
    // Push a patch of the top layer through the bottom layer.
    Eigen::MatrixX3d pushed = mesh.positions;
    int moved = 0;
    for (int i = 0; i < pushed.rows(); ++i) {
        const double x = pushed(i, 0), y = pushed(i, 1);
        if (pushed(i, 2) > 0.5 * gap && std::abs(x - 0.05) < 0.025 && std::abs(y - 0.1) < 0.025) {
            pushed(i, 2) = -gap;
            ++moved;
        }
    }
    REQUIRE(moved > 4);
    std::vector<std::pair<int, int>> pairs;
    const int n = count_self_intersections(pushed, mesh.faces, &pairs);
    CHECK(n > 0);
    // The BVH finds exactly the brute-force pairs, here and on a randomly crumpled sheet.
    CHECK(pairs == brute_force_self(pushed, mesh.faces));
    Eigen::MatrixX3d crumpled = mesh.positions;
    test::jitter(crumpled, 0.006, 4);
    const auto expected = brute_force_self(crumpled, mesh.faces);
    CHECK(!expected.empty());
    CHECK(count_self_intersections(crumpled, mesh.faces, &pairs) ==
          static_cast<int>(expected.size()));
    CHECK(pairs == expected);
}

TEST_CASE("points inside a closed mesh by ray parity", "[cloth][intersections]") {
    Eigen::MatrixX3d sphere;
    Eigen::MatrixX3i faces;
    uv_sphere(24, 48, 0.5, Eigen::Vector3d(0.1, 0.2, -0.1), sphere, faces);
    CHECK(count_self_intersections(sphere, faces) == 0);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    Eigen::MatrixX3d points(2000, 3);
    std::vector<int> expected;
    int n = 0;
    while (n < points.rows()) {
        const Eigen::Vector3d offset(unit(rng), unit(rng), unit(rng));
        const double r = offset.norm();
        // Inscribed radius of the polygonal sphere is ~0.5 cos(π/24); stay clear of it.
        if (r > 0.49 && r < 0.51) continue;
        points.row(n) = (Eigen::Vector3d(0.1, 0.2, -0.1) + offset).transpose();
        if (r < 0.49) expected.push_back(n);
        ++n;
    }
    std::vector<int> inside;
    CHECK(count_points_inside_closed_mesh(points, sphere, faces, &inside) ==
          static_cast<int>(expected.size()));
    CHECK(inside == expected);
    for (int i = 0; i < 200; ++i)
        CHECK(point_inside_closed_mesh(points.row(i).transpose(), sphere, faces) ==
              std::binary_search(expected.begin(), expected.end(), i));
    // Points on the axis through the poles (the rays start at vertices' lines of symmetry).
    CHECK(point_inside_closed_mesh(Eigen::Vector3d(0.1, 0.2, -0.1), sphere, faces));
    CHECK(point_inside_closed_mesh(Eigen::Vector3d(0.1, 0.6, -0.1), sphere, faces));
    CHECK_FALSE(point_inside_closed_mesh(Eigen::Vector3d(0.1, 0.8, -0.1), sphere, faces));
}

TEST_CASE("intersection checks reject bad input", "[cloth][intersections]") {
    Eigen::MatrixX3d p(3, 3);
    p << 0, 0, 0, 1, 0, 0, 0, 1, 0;
    Eigen::MatrixX3i f(1, 3);
    f << 0, 1, 3;
    CHECK_THROWS_AS(count_self_intersections(p, f), drape::InvalidInput);
    CHECK_THROWS_AS(count_intersections(p, Eigen::MatrixX3i(0, 3), p, f), drape::InvalidInput);
    f << 0, 1, 2;
    p(1, 1) = std::nan("");
    CHECK_THROWS_AS(count_self_intersections(p, f), drape::InvalidInput);
    CHECK_THROWS_AS(point_inside_closed_mesh(Eigen::Vector3d::Zero(), p, f), drape::InvalidInput);
}

TEST_CASE("intersection benchmark: 10k x 10k triangles", "[cloth][intersections][.bench]") {
    using clock = std::chrono::steady_clock;
    auto ms = [](clock::time_point a, clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    // Two 71x71 grids (10082 triangles each), wavy, crossing along a curve.
    ClothMesh a = make_square_grid(71, 1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitY());
    ClothMesh b = a;
    for (int i = 0; i < a.positions.rows(); ++i) {
        a.positions(i, 2) = 0.05 * std::sin(12 * a.positions(i, 0));
        b.positions(i, 2) = 0.05 * std::cos(9 * b.positions(i, 1)) + 0.01;
    }
    auto t0 = clock::now();
    const int cross = count_intersections(a.positions, a.faces, b.positions, b.faces);
    auto t1 = clock::now();
    const int self = count_self_intersections(a.positions, a.faces);
    auto t2 = clock::now();
    Eigen::MatrixX3d sphere;
    Eigen::MatrixX3i faces;
    uv_sphere(72, 140, 0.5, Eigen::Vector3d(0.5, 0.5, 0), sphere, faces);
    auto t3 = clock::now();
    const int inside = count_points_inside_closed_mesh(a.positions, sphere, faces);
    auto t4 = clock::now();
    WARN("count_intersections 10082 x 10082 triangles: " << ms(t0, t1) << " ms (" << cross
         << " pairs); count_self_intersections 10082: " << ms(t1, t2) << " ms (" << self
         << "); count_points_inside_closed_mesh 5184 points vs " << faces.rows()
         << "-triangle sphere: " << ms(t3, t4) << " ms (" << inside << " inside)");
    CHECK(cross > 0);
    CHECK(self == 0);
    CHECK(inside > 0);
}
