// The geometry layer of drape::core against brute force.
#include <drape/core/bvh.hpp>
#include <drape/core/closest_point_triangle.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/parallel_for.hpp>
#include <drape/core/point_in_mesh.hpp>
#include <drape/core/scan_triangle.hpp>
#include <drape/core/vertex_normals.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace {

using drape::core::Box3;

// A UV sphere of radius r (closed, faces counter-clockwise seen from outside).
void uv_sphere(int rings, int segments, double r, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
    const double pi = 3.14159265358979323846;
    V.resize(2 + (rings - 1) * segments, 3);
    V.row(0) << 0, 0, r;
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double t = pi * i / rings, p = 2 * pi * j / segments;
            V.row(1 + (i - 1) * segments + j) << r * std::sin(t) * std::cos(p),
                r * std::sin(t) * std::sin(p), r * std::cos(t);
        }
    const int south = static_cast<int>(V.rows()) - 1;
    V.row(south) << 0, 0, -r;
    std::vector<Eigen::Vector3i> faces;
    auto at = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
    for (int j = 0; j < segments; ++j) faces.emplace_back(0, at(1, j), at(1, j + 1));
    for (int i = 1; i + 1 < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            faces.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            faces.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    for (int j = 0; j < segments; ++j) faces.emplace_back(south, at(rings - 1, j + 1), at(rings - 1, j));
    F.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t k = 0; k < faces.size(); ++k) F.row(static_cast<Eigen::Index>(k)) = faces[k].transpose();
}

}  // namespace

TEST_CASE("closest point on a triangle matches dense sampling", "[core][closest_point]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
        const Eigen::Vector3d p = 2 * Eigen::Vector3d(u(rng), u(rng), u(rng));
        drape::core::TriangleFeature feature{};
        Eigen::Vector3d w;
        const Eigen::Vector3d q = drape::core::closest_point_on_triangle(p, a, b, c, &feature, &w);
        // The weights give the point back, each >= 0, summing to 1.
        CHECK((w(0) * a + w(1) * b + w(2) * c - q).norm() <= 1e-12);
        CHECK(w.minCoeff() >= -1e-12);
        CHECK(w.sum() == Approx(1).epsilon(1e-12));
        double best = std::numeric_limits<double>::infinity();
        const int n = 200;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                const Eigen::Vector3d s = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
                best = std::min(best, (p - s).norm());
            }
        CHECK((p - q).norm() <= best + 1e-12);
        CHECK((p - q).norm() >= best - 2e-2);
        // The feature holds the point.
        switch (feature) {
            case drape::core::TriangleFeature::vertex_a: CHECK(q == a); break;
            case drape::core::TriangleFeature::vertex_b: CHECK(q == b); break;
            case drape::core::TriangleFeature::vertex_c: CHECK(q == c); break;
            case drape::core::TriangleFeature::edge_ab: CHECK(w(2) == 0); break;
            case drape::core::TriangleFeature::edge_bc: CHECK(w(0) == Approx(0).margin(1e-15)); break;
            case drape::core::TriangleFeature::edge_ca: CHECK(w(1) == 0); break;
            default: break;
        }
    }
}

TEST_CASE("vertex normals: area and angle weighting, isolated vertices", "[core][normals]") {
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    uv_sphere(12, 16, 1.0, V, F);
    const Eigen::MatrixXd area = drape::core::vertex_normals(V, F);
    drape::core::VertexNormalOptions angle;
    angle.weighting = drape::core::NormalWeighting::angle;
    const Eigen::MatrixXd ang = drape::core::vertex_normals(V, F, angle);
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
        CHECK(area.row(i).norm() == Approx(1).epsilon(1e-12));
        CHECK(area.row(i).dot(V.row(i)) > 0.99);  // outward on a sphere
        CHECK(ang.row(i).dot(V.row(i)) > 0.99);
    }
    // A vertex no face uses keeps the `isolated` normal.
    Eigen::MatrixXd V2(4, 3);
    V2 << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5;
    Eigen::MatrixXi F2(1, 3);
    F2 << 0, 1, 2;
    CHECK(drape::core::vertex_normals(V2, F2).row(3).norm() == 0);
    drape::core::VertexNormalOptions up;
    up.isolated = Eigen::Vector3d::UnitY();
    CHECK(drape::core::vertex_normals(V2, F2, up).row(3) == Eigen::RowVector3d(0, 1, 0));
    CHECK(drape::core::vertex_normals(V2, F2, up).row(0) == Eigen::RowVector3d(0, 0, 1));
}

TEST_CASE("bvh: overlap and nearest queries match brute force", "[core][bvh]") {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Box3> boxes;
    for (int i = 0; i < 500; ++i) {
        const Eigen::Vector3d lo(u(rng), u(rng), u(rng));
        boxes.emplace_back(lo, lo + 0.05 * Eigen::Vector3d(u(rng), u(rng), u(rng)));
    }
    for (int leaf : {1, 4}) {
        const drape::core::Bvh bvh(boxes, leaf);
        for (int q = 0; q < 50; ++q) {
            const Eigen::Vector3d lo(u(rng), u(rng), u(rng));
            const Box3 query(lo, lo + 0.1 * Eigen::Vector3d::Ones());
            std::vector<int> brute;
            for (int i = 0; i < 500; ++i)
                if (boxes[static_cast<std::size_t>(i)].intersects(query)) brute.push_back(i);
            CHECK(bvh.overlapping(query) == brute);
            // Nearest box (distance 0 inside).
            const Eigen::Vector3d p(u(rng), u(rng), u(rng));
            double best = std::numeric_limits<double>::infinity();
            bvh.nearest(p, best, [&](int id, double& b) {
                b = std::min(b, drape::core::squared_distance(boxes[static_cast<std::size_t>(id)], p));
            });
            double brute_best = std::numeric_limits<double>::infinity();
            for (const Box3& b : boxes) brute_best = std::min(brute_best, drape::core::squared_distance(b, p));
            CHECK(best == brute_best);
        }
    }
    // Refit keeps the tree and answers for the moved boxes.
    drape::core::Bvh bvh(boxes, 1);
    std::vector<Box3> moved = boxes;
    for (Box3& b : moved) b.translate(Eigen::Vector3d(2, 0, 0));
    bvh.refit(moved);
    const Box3 query(Eigen::Vector3d(2, 0, 0), Eigen::Vector3d(3, 1, 1));
    std::vector<int> all(500);
    std::iota(all.begin(), all.end(), 0);
    CHECK(bvh.overlapping(query) == all);
    CHECK_THROWS_AS(bvh.refit({}), drape::InvalidInput);
    CHECK_THROWS_AS(drape::core::Bvh(boxes, 0), drape::InvalidInput);
}

TEST_CASE("point in a closed mesh: one-off and indexed tests agree", "[core][point_in_mesh]") {
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    uv_sphere(16, 24, 1.0, V, F);
    const drape::core::ClosedMeshInside index(V, F);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.3, 1.3);
    Eigen::MatrixXd points(400, 3);
    for (Eigen::Index i = 0; i < points.rows(); ++i) points.row(i) << u(rng), u(rng), u(rng);
    std::vector<int> expected;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
        const Eigen::Vector3d p = points.row(i).transpose();
        const bool in = drape::core::point_inside_closed_mesh(p, V, F);
        CHECK(in == index.inside(p));
        if (p.norm() < 0.95) CHECK(in);
        if (p.norm() > 1.0) CHECK_FALSE(in);
        if (in) expected.push_back(static_cast<int>(i));
    }
    CHECK(index.inside_indices(points) == expected);
    Eigen::MatrixXi bad = F;
    bad(0, 0) = static_cast<int>(V.rows());
    CHECK_THROWS_AS(drape::core::point_inside_closed_mesh(Eigen::Vector3d::Zero(), V, bad), drape::InvalidInput);
    CHECK_THROWS_AS(index.inside(Eigen::Vector3d::Constant(std::nan(""))), drape::InvalidInput);
}

TEST_CASE("parallel loops: every index once, chunks concatenated in order", "[core][parallel]") {
    std::vector<int> hits(10000, 0);
    drape::core::parallel_for(10000, [&](int i) { hits[static_cast<std::size_t>(i)] += 1; });
    CHECK(std::all_of(hits.begin(), hits.end(), [](int h) { return h == 1; }));
    const std::vector<int> odd = drape::core::parallel_collect<int>(
        10000, 256, [](int i, std::vector<int>& out) { if (i % 2) out.push_back(i); });
    REQUIRE(odd.size() == 5000);
    for (std::size_t k = 0; k < odd.size(); ++k) CHECK(odd[k] == static_cast<int>(2 * k + 1));
    CHECK(drape::core::chunk_count(0, 256) == 0);
    CHECK(drape::core::chunk_count(257, 256) == 2);
    drape::core::parallel_for(0, [](int) { FAIL("no index in an empty range"); });
}

TEST_CASE("scan_triangle visits exactly the pixel centres inside a triangle, with barycentric weights",
          "[core][raster]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> coord(-5.0, 45.0);
    const int W = 40, H = 30;
    int visited_total = 0;
    for (int t = 0; t < 200; ++t) {
        const Eigen::Vector2d a(coord(rng), coord(rng)), b(coord(rng), coord(rng)), c(coord(rng), coord(rng));
        std::vector<int> hits(size_t(W * H), 0);
        drape::core::scan_triangle(a, b, c, W, H, [&](int x, int y, double wa, double wb, double wc) {
            REQUIRE((x >= 0 && x < W && y >= 0 && y < H));
            ++hits[size_t(y * W + x)];
            CHECK(std::abs(wa + wb + wc - 1.0) < 1e-9);
            const Eigen::Vector2d p = wa * a + wb * b + wc * c;  // the weights interpolate the centre
            CHECK((p - Eigen::Vector2d(x + 0.5, y + 0.5)).norm() < 1e-7);
        });
        // Brute force with exact edge functions; centres within 1e-9 of an edge may go either way.
        const auto edge = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
            return (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
        };
        const double area = edge(a, b, c);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const Eigen::Vector2d p(x + 0.5, y + 0.5);
                const double e0 = edge(b, c, p) / area, e1 = edge(c, a, p) / area, e2 = edge(a, b, p) / area;
                const double margin = std::min({e0, e1, e2});
                const int h = hits[size_t(y * W + x)];
                CHECK(h <= 1);
                if (margin > 1e-9) CHECK(h == 1);
                if (margin < -1e-9) CHECK(h == 0);
                visited_total += h;
            }
    }
    CHECK(visited_total > 1000);  // not a vacuous pass: the triangles cover many pixels
    int degenerate = 0;
    drape::core::scan_triangle({1, 1}, {5, 5}, {9, 9}, W, H, [&](int, int, double, double, double) { ++degenerate; });
    CHECK(degenerate == 0);
}
