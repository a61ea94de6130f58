// Self-contact: exact distances, finite-difference checks of the pair penalty in every
// closest-feature regime, the broad phase against brute force, and the step bound.
#include <drape/cloth/intersections.hpp>
#include <drape/core/errors.hpp>

// The self-contact API is private to libcloth (namespace internal).
#include "../../libcloth/src/self_contact.hpp"

#include <catch2/catch.hpp>

#include "folded_sheet_fixture.hpp"
#include <common/finite_differences.hpp>

#include <Eigen/Eigenvalues>

#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <random>

using namespace drape::cloth;
using namespace drape::cloth::internal;

namespace {

using Mat34 = Eigen::Matrix<double, 3, 4>;
using Regime = DistanceRegime::Type;
using Kind = ContactPair::Kind;

Mat34 to_cols(const Vector12d& v) { return Eigen::Map<const Mat34>(v.data()); }
Vector12d to_vec(const Mat34& x) { return Eigen::Map<const Vector12d>(x.data()); }

using drape::test::relative_error;

// Brute-force distances by dense sampling of the parameter domains.
double sampled_point_triangle(const Mat34& x, int n) {
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; i + j <= n; ++j) {
            const double u = double(i) / n, v = double(j) / n;
            const Eigen::Vector3d y = x.col(1) + u * (x.col(2) - x.col(1)) + v * (x.col(3) - x.col(1));
            best = std::min(best, (x.col(0) - y).norm());
        }
    return best;
}

double sampled_segment_segment(const Mat34& x, int n) {
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double s = double(i) / n, t = double(j) / n;
            const Eigen::Vector3d a = x.col(0) + s * (x.col(1) - x.col(0));
            const Eigen::Vector3d b = x.col(2) + t * (x.col(3) - x.col(2));
            best = std::min(best, (a - b).norm());
        }
    return best;
}

double diameter(const Mat34& x) {
    double d = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) d = std::max(d, (x.col(i) - x.col(j)).norm());
    return d;
}

std::string regime_name(Kind kind, const DistanceRegime& r) {
    std::string s = kind == Kind::vertex_triangle ? "VT/" : "EE/";
    switch (r.type) {
        case Regime::point_point: s += "point_point"; break;
        case Regime::point_edge: s += "point_edge"; break;
        case Regime::point_plane: s += "point_plane"; break;
        case Regime::edge_edge: s += "edge_edge"; break;
    }
    for (int i : r.idx) s += "," + std::to_string(i);
    return s;
}

// Central-difference gradient of the pair energy and Hessian (difference of gradients).
void check_pair_derivatives(Kind kind, const Mat34& x, const SelfContactParams& params) {
    Vector12d g;
    Matrix12d hess;
    pair_energy(kind, x, params, &g, &hess, HessianMode::exact);
    const Vector12d x0 = to_vec(x);
    const double step = 1e-8;
    const Vector12d g_fd = drape::test::fd_gradient(
        [&](const Vector12d& y) { return pair_energy(kind, to_cols(y), params); }, x0, step);
    const Matrix12d h_fd = drape::test::fd_hessian(
        [&](const Vector12d& y) {
            Vector12d gy;
            pair_energy(kind, to_cols(y), params, &gy);
            return gy;
        },
        x0, step);
    INFO("gradient " << g.transpose() << "\nfd " << g_fd.transpose());
    CHECK(relative_error(g_fd, g) < 1e-5);
    CHECK(relative_error(h_fd, hess) < 1e-4);
    // The projected Hessian is PSD and the Gauss–Newton one is k ∇d ∇dᵀ.
    Matrix12d projected, gauss_newton;
    pair_energy(kind, x, params, nullptr, &projected, HessianMode::projected_psd);
    pair_energy(kind, x, params, nullptr, &gauss_newton, HessianMode::gauss_newton);
    Eigen::SelfAdjointEigenSolver<Matrix12d> eig(projected);
    CHECK(eig.eigenvalues().minCoeff() > -1e-8 * std::max(1.0, projected.norm()));
    // Gauss–Newton: ψ''(d) ∇d ∇dᵀ, and g = ψ'(d) ∇d.
    const ContactPotential c = contact_potential(std::sqrt(pair_distance_squared(kind, x)), params);
    const double gn = c.d2psi * g.squaredNorm() / (c.dpsi * c.dpsi);
    CHECK(gauss_newton.trace() == Approx(gn).epsilon(1e-9));
}

// Folded sheet of the tests: 1 m / n grid, layers `gap` apart.
ClothMesh test_fold(int n, double size, double gap, double noise, unsigned seed) {
    ClothMesh mesh = test::folded_sheet(n, size, gap, 0.55 * size);
    test::jitter(mesh.positions, noise, seed);
    return mesh;
}

// All admissible pairs closer than `radius` by O(n²) enumeration, in SelfContact's order.
// A rest filter for brute_force_pairs: pairs on one piece closer than min_distance in the
// pattern are left out.
struct RestFilter {
    Eigen::MatrixX3d pattern;  // #V x 3 (z = 0)
    std::vector<int> piece;
    double min_distance = 0;
};

// All admissible pairs closer than `radius` by O(n²) enumeration, in SelfContact's order,
// leaving out vertex v / face f with rest_vt(v, f) and edges e < o with rest_ee(e, o).
std::vector<ContactPair> brute_force_pairs_filtered(const SelfContact& sc, const Eigen::MatrixX3d& p,
                                                    const Eigen::MatrixX3i& faces, double radius,
                                                    const std::vector<std::pair<int, int>>& excluded,
                                                    const std::function<bool(int, int)>& rest_vt,
                                                    const std::function<bool(int, int)>& rest_ee) {
    auto excl = [&](int a, int b) {
        if (a == b) return true;
        for (auto [i, j] : excluded)
            if ((i == a && j == b) || (i == b && j == a)) return true;
        return false;
    };
    std::vector<ContactPair> out;
    for (int v = 0; v < p.rows(); ++v)
        for (int f = 0; f < faces.rows(); ++f) {
            const int t0 = faces(f, 0), t1 = faces(f, 1), t2 = faces(f, 2);
            if (excl(v, t0) || excl(v, t1) || excl(v, t2)) continue;
            if (rest_vt(v, f)) continue;
            if (point_triangle_distance_squared(p.row(v), p.row(t0), p.row(t1), p.row(t2)) <
                radius * radius)
                out.push_back({Kind::vertex_triangle, {v, t0, t1, t2}});
        }
    const auto& edges = sc.edges();
    for (std::size_t e = 0; e < edges.size(); ++e)
        for (std::size_t o = e + 1; o < edges.size(); ++o) {
            const int a0 = edges[e][0], a1 = edges[e][1], b0 = edges[o][0], b1 = edges[o][1];
            if (excl(a0, b0) || excl(a0, b1) || excl(a1, b0) || excl(a1, b1)) continue;
            if (rest_ee(int(e), int(o))) continue;
            if (segment_segment_distance_squared(p.row(a0), p.row(a1), p.row(b0), p.row(b1)) <
                radius * radius)
                out.push_back({Kind::edge_edge, {a0, a1, b0, b1}});
        }
    return out;
}

std::vector<ContactPair> brute_force_pairs(const SelfContact& sc, const Eigen::MatrixX3d& p,
                                           const Eigen::MatrixX3i& faces, double radius,
                                           const std::vector<std::pair<int, int>>& excluded,
                                           const RestFilter* rest = nullptr) {
    auto one_piece = [&](int a, int b, int c, int d) {
        const auto& pc = rest->piece;
        return pc[a] == pc[b] && pc[a] == pc[c] && pc[a] == pc[d];
    };
    const double rest2 = rest ? rest->min_distance * rest->min_distance : 0.0;
    const auto& edges = sc.edges();
    return brute_force_pairs_filtered(
        sc, p, faces, radius, excluded,
        [&](int v, int f) {
            const int t0 = faces(f, 0), t1 = faces(f, 1), t2 = faces(f, 2);
            return rest && one_piece(v, t0, t1, t2) &&
                   point_triangle_distance_squared(rest->pattern.row(v), rest->pattern.row(t0),
                                                   rest->pattern.row(t1), rest->pattern.row(t2)) < rest2;
        },
        [&](int e, int o) {
            const int a0 = edges[size_t(e)][0], a1 = edges[size_t(e)][1], b0 = edges[size_t(o)][0],
                      b1 = edges[size_t(o)][1];
            return rest && one_piece(a0, a1, b0, b1) &&
                   segment_segment_distance_squared(rest->pattern.row(a0), rest->pattern.row(a1),
                                                    rest->pattern.row(b0), rest->pattern.row(b1)) < rest2;
        });
}

bool same_pairs(const std::vector<ContactPair>& a, const std::vector<ContactPair>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].kind != b[i].kind || a[i].v != b[i].v) return false;
    return true;
}

// Minimum distance over every admissible pair (not only candidates), brute force.
double min_pair_distance(const SelfContact& sc, const Eigen::MatrixX3d& p,
                         const Eigen::MatrixX3i& faces) {
    const double big = 1e3;
    double best = 1e300;
    for (const ContactPair& pair : brute_force_pairs(sc, p, faces, big, {})) {
        Mat34 x;
        for (int c = 0; c < 4; ++c) x.col(c) = p.row(pair.v[c]).transpose();
        best = std::min(best, std::sqrt(pair_distance_squared(pair.kind, x)));
    }
    return best;
}

}  // namespace

TEST_CASE("self-contact distances match dense sampling", "[cloth][self_contact]") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int trial = 0; trial < 150; ++trial) {
        Mat34 x;
        for (int c = 0; c < 4; ++c) x.col(c) = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
        const int n = 400;
        const double vt = std::sqrt(pair_distance_squared(Kind::vertex_triangle, x));
        const double vt_sampled = sampled_point_triangle(x, n);
        const double ee = std::sqrt(pair_distance_squared(Kind::edge_edge, x));
        const double ee_sampled = sampled_segment_segment(x, n);
        // Exact <= any sample; the nearest sample is within one grid step of the optimum.
        CHECK(vt <= vt_sampled + 1e-12);
        CHECK(vt_sampled - vt <= 2.0 * diameter(x) / n);
        CHECK(ee <= ee_sampled + 1e-12);
        CHECK(ee_sampled - ee <= 2.0 * diameter(x) / n);
        // The regime formula reproduces the distance.
        for (Kind kind : {Kind::vertex_triangle, Kind::edge_edge}) {
            DistanceRegime r;
            const double d2 = pair_distance_squared(kind, x, &r);
            CHECK(regime_distance_squared(r, x, nullptr, nullptr) ==
                  Approx(d2).epsilon(1e-9).margin(1e-15));
        }
    }
}

TEST_CASE("self-contact distances in degenerate configurations", "[cloth][self_contact]") {
    Mat34 x;
    // Parallel overlapping edges 0.3 apart: the distance is 0.3 (non-unique closest points).
    x << 0, 1, 0.5, 1.5, 0, 0, 0.3, 0.3, 0, 0, 0, 0;
    CHECK(std::sqrt(pair_distance_squared(Kind::edge_edge, x)) == Approx(0.3).epsilon(1e-14));
    // Collinear disjoint edges: endpoint to endpoint.
    x << 0, 1, 1.5, 2.5, 0, 0, 0, 0, 0, 0, 0, 0;
    DistanceRegime r;
    CHECK(std::sqrt(pair_distance_squared(Kind::edge_edge, x, &r)) == Approx(0.5).epsilon(1e-14));
    CHECK(r.type == Regime::point_point);
    // Zero-length edge (a point) against a segment.
    x << 0.5, 0.5, 0, 1, 0.2, 0.2, 0, 0, 0, 0, 0, 0;
    CHECK(std::sqrt(pair_distance_squared(Kind::edge_edge, x)) == Approx(0.2).epsilon(1e-14));
    // Point over a degenerate (collinear) triangle: distance to the segment it spans.
    x << 0.5, 0, 1, 2, 0.4, 0, 0, 0, 0, 0, 0, 0;
    CHECK(std::sqrt(pair_distance_squared(Kind::vertex_triangle, x, &r)) ==
          Approx(0.4).epsilon(1e-14));
    CHECK(r.type == Regime::point_edge);
    // Point in the plane of the triangle, inside it: distance 0.
    x << 0.2, 0, 1, 0, 0.2, 0, 0, 1, 0, 0, 0, 0;
    CHECK(pair_distance_squared(Kind::vertex_triangle, x) == Approx(0).margin(1e-30));
}

TEST_CASE("self-contact penalty: finite-difference gradient and Hessian in every regime",
          "[cloth][self_contact]") {
    SelfContactParams params;
    params.thickness_m = 0.005;
    params.stiffness_n_per_m = 2000;
    params.inner_fraction = 0.2;  // the inner barrier on: d in [0.5, 1) mm tests it
    std::string why;
    REQUIRE(params.is_valid(&why));
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1, 1);
    std::map<std::string, int> seen;
    // Random pairs of centimetre primitives; keep those within the thickness (and not too
    // close to 0), until every regime has been checked several times.
    int tested = 0;
    for (int trial = 0; trial < 400000 && tested < 600; ++trial) {
        Mat34 x;
        for (int c = 0; c < 4; ++c)
            x.col(c) = 0.006 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
        for (Kind kind : {Kind::vertex_triangle, Kind::edge_edge}) {
            DistanceRegime r;
            const double d = std::sqrt(pair_distance_squared(kind, x, &r));
            if (d < 0.1 * params.thickness_m || d > 0.95 * params.thickness_m) continue;
            const std::string name = regime_name(kind, r);
            if (seen[name] >= 20) continue;
            ++seen[name];
            ++tested;
            INFO(name << "\nx =\n" << x);
            check_pair_derivatives(kind, x, params);
        }
    }
    // Vertex–triangle: 3 vertex, 3 edge, 1 face regime; edge–edge: 4 vertex–vertex,
    // 4 vertex–edge, 1 interior.
    int vt = 0, ee = 0;
    for (const auto& [name, count] : seen) {
        INFO(name << ": " << count);
        CHECK(count >= 5);
        (name.rfind("VT", 0) == 0 ? vt : ee) += 1;
    }
    CHECK(vt == 7);
    CHECK(ee == 9);

    // Nearly parallel edges (angle 1e-3 rad) with unique closest points still differentiate.
    Mat34 x;
    x << 0, 0.01, 0.012, 0.022, 0, 1e-5, 0.003, 0.003, 0, 0, 0.001, 0.001;
    DistanceRegime r;
    pair_distance_squared(Kind::edge_edge, x, &r);
    INFO(regime_name(Kind::edge_edge, r));
    check_pair_derivatives(Kind::edge_edge, x, params);

    // Beyond the thickness the energy and its derivatives vanish.
    x << 0, 0.01, 0, 0.01, 0, 0, 0.01, 0.01, 0, 0, 0, 0;
    Vector12d g;
    Matrix12d hess;
    CHECK(pair_energy(Kind::edge_edge, x, params, &g, &hess) == 0);
    CHECK(g.norm() == 0);
    CHECK(hess.norm() == 0);
}

TEST_CASE("self-contact penalty: the inner barrier holds against any force", "[cloth][self_contact]") {
    SelfContactParams params;
    params.thickness_m = 0.005;
    params.stiffness_n_per_m = 2000;
    CHECK(params.inner_fraction == 0);  // off by default (not yet evaluated on the garments)
    params.inner_fraction = 0.2;
    const double h = params.thickness_m, k = params.stiffness_n_per_m, dh = params.inner_fraction * h;
    REQUIRE(dh == Approx(0.001));
    // Above d̂ the quadratic penalty alone; it pushes back with at most k h.
    for (double d : {0.0012, 0.003, 0.0049}) {
        const ContactPotential c = contact_potential(d, params);
        CHECK(c.psi == Approx(0.5 * k * (h - d) * (h - d)));
        CHECK(c.dpsi == Approx(-k * (h - d)));
        CHECK(c.d2psi == k);
    }
    // C² at d̂: value and derivatives agree from both sides.
    const ContactPotential below = contact_potential(dh * (1 - 1e-7), params), at = contact_potential(dh, params);
    CHECK(below.psi == Approx(at.psi).epsilon(1e-6));
    CHECK(below.dpsi == Approx(at.dpsi).epsilon(1e-6));
    CHECK(below.d2psi == Approx(at.d2psi).epsilon(1e-4));
    // Below d̂ the repulsion grows without bound: 10x, 100x, 1000x the penalty's largest force.
    CHECK(-contact_potential(1e-4, params).dpsi > 10 * k * h);
    CHECK(-contact_potential(1e-5, params).dpsi > 100 * k * h);
    CHECK(-contact_potential(1e-6, params).dpsi > 1000 * k * h);
    // The energy keeps rising (convex) towards contact.
    double last = 0;
    for (double d = 0.001; d > 1e-8; d /= 2) {
        const ContactPotential c = contact_potential(d, params);
        CHECK(c.psi > last);
        CHECK(c.d2psi > 0);
        last = c.psi;
    }
    // Off (inner_fraction 0): the old penalty, k h at most.
    SelfContactParams off = params;
    off.inner_fraction = 0;
    CHECK(contact_potential(1e-6, off).dpsi == Approx(-k * (h - 1e-6)));
    std::string why;
    off.inner_fraction = 1.5;
    CHECK_FALSE(off.is_valid(&why));
    CHECK(why.find("inner_fraction") != std::string::npos);
}

TEST_CASE("self-contact broad phase finds exactly the brute-force pairs",
          "[cloth][self_contact]") {
    for (unsigned seed : {1u, 2u, 3u}) {
        const ClothMesh mesh = test_fold(14, 0.1, 0.004, 0.0025, seed);
        std::vector<std::pair<int, int>> excluded;
        if (seed == 3) excluded = {{0, 20}, {5, 200}, {17, 18}};
        SelfContact sc(mesh.faces, mesh.vertex_count(), excluded);
        for (double radius : {0.002, 0.005, 0.012}) {
            sc.find_candidates(mesh.positions, radius);
            const auto expected =
                brute_force_pairs(sc, mesh.positions, mesh.faces, radius, excluded);
            INFO("seed " << seed << " radius " << radius << ": " << sc.candidates().size()
                         << " found, " << expected.size() << " expected");
            CHECK(expected.size() > 20);
            CHECK(same_pairs(sc.candidates(), expected));
        }
        // Deterministic: a second search gives the same list.
        const auto first = sc.candidates();
        sc.find_candidates(mesh.positions, 0.012);
        CHECK(same_pairs(first, sc.candidates()));
    }
    SelfContact sc(Eigen::MatrixX3i(0, 3), 0);
    sc.find_candidates(Eigen::MatrixX3d(0, 3), 0.01);
    CHECK(sc.candidates().empty());
}

TEST_CASE("self-contact rest filter leaves out exactly the pairs near in the pattern",
          "[cloth][self_contact]") {
    // The fold's flat layout is its pattern; two pieces (left and right half), so pairs
    // across the split are never filtered.
    const ClothMesh mesh = test_fold(14, 0.1, 0.004, 0.0025, 4);
    RestFilter rest;
    REQUIRE(mesh.pattern.rows() == mesh.vertex_count());  // one pattern point per vertex
    rest.pattern = Eigen::MatrixX3d::Zero(mesh.vertex_count(), 3);
    rest.pattern.leftCols<2>() = mesh.pattern;
    for (int v = 0; v < mesh.vertex_count(); ++v) rest.piece.push_back(mesh.pattern(v, 0) < 0.047 ? 0 : 1);
    SelfContact sc(mesh.faces, mesh.vertex_count());
    for (double min_distance : {0.0, 0.008, 0.02}) {
        rest.min_distance = min_distance;
        sc.set_rest_filter(rest.pattern.leftCols<2>(), rest.piece, min_distance);
        for (double radius : {0.005, 0.012}) {
            sc.find_candidates(mesh.positions, radius);
            const auto expected = brute_force_pairs(sc, mesh.positions, mesh.faces, radius, {}, &rest);
            INFO("min distance " << min_distance << " radius " << radius << ": "
                                 << sc.candidates().size() << " found, " << expected.size() << " expected");
            CHECK(expected.size() > 20);
            CHECK(same_pairs(sc.candidates(), expected));
        }
    }
    // The filter removes pairs: at 2 cm every in-layer pair within 1.2 cm is gone, only
    // pairs across the fold's two layers remain.
    const auto unfiltered = brute_force_pairs(sc, mesh.positions, mesh.faces, 0.012, {});
    CHECK(sc.candidates().size() < 0.6 * unfiltered.size());
    CHECK_THROWS_AS(sc.set_rest_filter(rest.pattern.leftCols<2>(), {0, 1}, 0.01), drape::InvalidInput);
    CHECK_THROWS_AS(sc.set_rest_filter(rest.pattern.leftCols<2>(), rest.piece, -1.0), drape::InvalidInput);
}

TEST_CASE("self-contact rest filter of a welded seam compares pairs in each panel's own pattern",
          "[cloth][self_contact]") {
    // Two 5 x 5 cm panels, laid out 3 cm apart in the pattern, welded along A's right edge =
    // B's left edge; in 3D B is folded back over A (a sharp fold at the seam, like a crotch
    // seam pinched between the thighs), its layer 3-6 mm above A's. The seam vertices have
    // one pattern point per panel. Pairs across the fold are near in 3D and far along the
    // cloth: none of them may be left out as rest neighbours.
    const int n = 5;
    const double cell = 0.01, gap = 0.03;
    const int side = n + 1;
    Eigen::MatrixX2d pattern(2 * side * side, 2);
    std::vector<int> point_vertex(size_t(2 * side * side)), point_piece(size_t(2 * side * side));
    const int nv = side * side + n * side;  // B's left column is A's right column
    Eigen::MatrixX3d x(nv, 3);
    auto a_vertex = [&](int i, int j) { return j * side + i; };
    auto b_vertex = [&](int i, int j) { return i == 0 ? a_vertex(n, j) : side * side + j * n + (i - 1); };
    for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
            const int qa = j * side + i, qb = side * side + j * side + i;
            pattern.row(qa) << i * cell, j * cell;
            pattern.row(qb) << n * cell + gap + i * cell, j * cell;
            point_vertex[size_t(qa)] = a_vertex(i, j);
            point_vertex[size_t(qb)] = b_vertex(i, j);
            point_piece[size_t(qa)] = 0;
            point_piece[size_t(qb)] = 1;
            x.row(a_vertex(i, j)) << i * cell, j * cell, 0.0;
            // B runs back over A from the seam, rising 0.6 mm per cm of cloth.
            const double s = i * cell;
            x.row(b_vertex(i, j)) << n * cell - s * std::cos(0.06), j * cell, s * std::sin(0.06);
        }
    Eigen::MatrixX3i faces(4 * n * n, 3), pattern_faces(4 * n * n, 3);
    int f = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int qa = j * side + i, qb = side * side + j * side + i;
            pattern_faces.row(f) << qa, qa + 1, qa + side + 1;
            pattern_faces.row(f + 1) << qa, qa + side + 1, qa + side;
            pattern_faces.row(f + 2) << qb, qb + 1, qb + side + 1;
            pattern_faces.row(f + 3) << qb, qb + side + 1, qb + side;
            for (int k = 0; k < 4; ++k)
                for (int c = 0; c < 3; ++c) faces(f + k, c) = point_vertex[size_t(pattern_faces(f + k, c))];
            f += 4;
        }
    const double min_distance = 0.008, radius = 0.008;
    SelfContact sc(faces, nv);
    sc.set_rest_filter(pattern, point_vertex, pattern_faces, point_piece, min_distance);
    sc.find_candidates(x, radius);
    // Reference: near at rest if some pattern point of the vertex lies on the face's panel
    // within min_distance of its pattern triangle (edges: some pattern edge of each).
    const auto& edges = sc.edges();
    std::vector<std::vector<std::array<int, 3>>> pattern_edges_of(edges.size());  // (qa, qb, piece)
    for (int g = 0; g < faces.rows(); ++g)
        for (int c = 0; c < 3; ++c) {
            const int a = faces(g, c), b = faces(g, (c + 1) % 3);
            const std::array<int, 2> key = {std::min(a, b), std::max(a, b)};
            const size_t e = size_t(std::lower_bound(edges.begin(), edges.end(), key) - edges.begin());
            pattern_edges_of[e].push_back({pattern_faces(g, c), pattern_faces(g, (c + 1) % 3),
                                           point_piece[size_t(pattern_faces(g, c))]});
        }
    const double r2 = min_distance * min_distance;
    auto pat = [&](int q) { return Eigen::Vector3d(pattern(q, 0), pattern(q, 1), 0.0); };
    const auto expected = brute_force_pairs_filtered(
        sc, x, faces, radius, {},
        [&](int v, int g) {
            for (int q = 0; q < pattern.rows(); ++q)
                if (point_vertex[size_t(q)] == v && point_piece[size_t(q)] == point_piece[size_t(pattern_faces(g, 0))] &&
                    point_triangle_distance_squared(pat(q), pat(pattern_faces(g, 0)), pat(pattern_faces(g, 1)),
                                                    pat(pattern_faces(g, 2))) < r2)
                    return true;
            return false;
        },
        [&](int e, int o) {
            for (const auto& pa : pattern_edges_of[size_t(e)])
                for (const auto& pb : pattern_edges_of[size_t(o)])
                    if (pa[2] == pb[2] &&
                        segment_segment_distance_squared(pat(pa[0]), pat(pa[1]), pat(pb[0]), pat(pb[1])) < r2)
                        return true;
            return false;
        });
    INFO(sc.candidates().size() << " found, " << expected.size() << " expected");
    CHECK(same_pairs(sc.candidates(), expected));
    // Pairs across the fold are found: A's vertex (3, 2), 2 cm from the seam, lies 1.2 mm
    // under B's layer.
    auto across_fold = [&](const std::vector<ContactPair>& pairs) {
        int count = 0;
        for (const ContactPair& pr : pairs)
            if (pr.kind == Kind::vertex_triangle && pr.v[0] == a_vertex(3, 2) &&
                std::min({pr.v[1], pr.v[2], pr.v[3]}) >= side * side)
                ++count;
        return count;
    };
    CHECK(across_fold(sc.candidates()) > 0);
    // In-layer neighbours at the seam are not pairs: a seam vertex and a face of B that does
    // not hold it but lies within min_distance of its point in B's pattern.
    auto in_layer_at_seam = [&](const std::vector<ContactPair>& pairs) {
        int count = 0;
        for (const ContactPair& pr : pairs) {
            if (pr.kind != Kind::vertex_triangle || pr.v[0] % side != n || pr.v[0] >= side * side) continue;
            const Eigen::Vector3d q = pat(side * side + (pr.v[0] / side) * side);  // its point in B
            for (int g = 0; g < faces.rows(); ++g)
                if (faces(g, 0) == pr.v[1] && faces(g, 1) == pr.v[2] && faces(g, 2) == pr.v[3] &&
                    point_piece[size_t(pattern_faces(g, 0))] == 1 &&
                    point_triangle_distance_squared(q, pat(pattern_faces(g, 0)), pat(pattern_faces(g, 1)),
                                                    pat(pattern_faces(g, 2))) < r2)
                    ++count;
        }
        return count;
    };
    CHECK(in_layer_at_seam(sc.candidates()) == 0);
    // With one pattern point per vertex (the first corner's: A's for the seam) and one piece
    // for the welded cloth, as before 2026-11-24, the seam vertices are compared with B's
    // faces in A's layout: B's faces beside the seam become contact pairs of the seam's own
    // vertices, a repulsion within one layer at every seam (the walking pants crossed
    // themselves at the crotch, where four panels meet).
    Eigen::MatrixX2d first_corner(nv, 2);
    for (int q = int(pattern.rows()) - 1; q >= 0; --q) first_corner.row(point_vertex[size_t(q)]) = pattern.row(q);
    sc.set_rest_filter(first_corner, std::vector<int>(size_t(nv), 0), min_distance);
    sc.find_candidates(x, radius);
    CHECK(in_layer_at_seam(sc.candidates()) > 0);
    // Bad input is named.
    std::vector<int> wrong = point_vertex;
    wrong[0] = 7;
    CHECK_THROWS_AS(sc.set_rest_filter(pattern, wrong, pattern_faces, point_piece, min_distance), drape::InvalidInput);
    CHECK_THROWS_AS(sc.set_rest_filter(pattern, point_vertex, pattern_faces, {0, 1}, min_distance), drape::InvalidInput);
}

TEST_CASE("self-contact candidates reused after the cloth moved give the fresh results",
          "[cloth][self_contact]") {
    // Candidates collected at p0 with a generous radius, then used at p1 = p0 + a large
    // translation + a small relative motion: the energy, its gradient and blocks, and the
    // contact frames equal those of a fresh search at p1 (the per-vertex offsets may only
    // skip pairs that cannot be within the thickness).
    const ClothMesh mesh = test_fold(12, 0.1, 0.004, 0.0008, 9);
    const Eigen::MatrixX3d& p0 = mesh.positions;
    SelfContactParams params;
    const double h = params.thickness_m;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (const Eigen::RowVector3d& translation : {Eigen::RowVector3d(0, 0, 0), Eigen::RowVector3d(0.3, -0.2, 0.5)}) {
        Eigen::MatrixX3d p1 = p0;
        for (int i = 0; i < p1.rows(); ++i)
            p1.row(i) += translation + 0.0003 * Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
        SelfContact reused(mesh.faces, mesh.vertex_count()), fresh(mesh.faces, mesh.vertex_count());
        reused.find_candidates(p0, 3 * h);
        // The translation does not count against the covered radius.
        const double relative = 2 * (p1 - p0).rowwise().norm().maxCoeff();
        CHECK(reused.covered_radius(p1) >= 3 * h - 2 * 0.0003 * std::sqrt(3.0) * (1 + 1e-9));
        if (translation.norm() > 0) CHECK(reused.covered_radius(p1) > 3 * h - relative);
        REQUIRE(reused.covered_radius(p1) > h);
        fresh.find_candidates(p1, 1.01 * h);
        const int n = 3 * mesh.vertex_count();
        Eigen::VectorXd g_reused = Eigen::VectorXd::Zero(n), g_fresh = Eigen::VectorXd::Zero(n);
        std::vector<PairHessian> b_reused, b_fresh;
        const double e_reused = reused.energy(p1, params, &g_reused, &b_reused);
        const double e_fresh = fresh.energy(p1, params, &g_fresh, &b_fresh);
        INFO("translation " << translation << ": " << reused.candidates().size() << " vs "
                            << fresh.candidates().size() << " candidates");
        REQUIRE(e_fresh > 0);
        CHECK(e_reused == Approx(e_fresh).epsilon(1e-12));
        CHECK((g_reused - g_fresh).norm() <= 1e-12 * g_fresh.norm());
        CHECK(b_reused.size() == b_fresh.size());
        CHECK(reused.contact_frames(p1, h).size() == fresh.contact_frames(p1, h).size());
        // The step bound from p1 stays conservative with the reused list.
        Eigen::MatrixX3d dx(p1.rows(), 3);
        for (int i = 0; i < p1.rows(); ++i) {
            dx.row(i) << 0.002 * unit(rng), 0.002 * unit(rng), 0.002 * unit(rng);
            if (p0(i, 2) > 0.0015) dx(i, 2) -= 0.008;  // the top layer through the bottom one
        }
        REQUIRE(min_pair_distance(reused, p1, mesh.faces) > 0.0005);
        const double alpha = reused.max_safe_step(p1, dx, 0.9, 0.0005);
        REQUIRE(alpha > 0);
        CHECK(alpha < 1);
        for (int k = 1; k <= 8; ++k)
            CHECK(min_pair_distance(reused, p1 + alpha * k / 8.0 * dx, mesh.faces) >= 0.0005);
    }
}

TEST_CASE("self-contact energy gradient matches finite differences over a mesh",
          "[cloth][self_contact]") {
    const ClothMesh mesh = test_fold(10, 0.1, 0.004, 0.001, 5);
    SelfContact sc(mesh.faces, mesh.vertex_count());
    SelfContactParams params;
    sc.find_candidates(mesh.positions, 2 * params.thickness_m);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * mesh.vertex_count());
    std::vector<PairHessian> blocks;
    const double e = sc.energy(mesh.positions, params, &g, &blocks);
    REQUIRE(e > 0);
    REQUIRE(!blocks.empty());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(-1, 1);
    Eigen::MatrixX3d dir(mesh.vertex_count(), 3);
    for (int i = 0; i < dir.rows(); ++i) dir.row(i) << unit(rng), unit(rng), unit(rng);
    const double step = 1e-8;
    const double fd = (sc.energy(mesh.positions + step * dir, params, nullptr, nullptr) -
                       sc.energy(mesh.positions - step * dir, params, nullptr, nullptr)) /
                      (2 * step);
    Eigen::VectorXd dir_flat(3 * dir.rows());
    for (int i = 0; i < dir.rows(); ++i) dir_flat.segment<3>(3 * i) = dir.row(i).transpose();
    CHECK(fd == Approx(g.dot(dir_flat)).epsilon(1e-5));
    // Every block is PSD and belongs to a pair within the thickness.
    for (const PairHessian& b : blocks) {
        Eigen::SelfAdjointEigenSolver<Matrix12d> eig(b.hessian);
        CHECK(eig.eigenvalues().minCoeff() > -1e-8 * b.hessian.norm());
    }
    SelfContactParams bad;
    bad.thickness_m = -1;
    CHECK_THROWS_AS(sc.energy(mesh.positions, bad, nullptr, nullptr), drape::InvalidInput);
    CHECK_THROWS_AS(sc.find_candidates(mesh.positions, 0.0), drape::InvalidInput);
    CHECK_THROWS_AS(SelfContact(mesh.faces, 3), drape::InvalidInput);
}

TEST_CASE("self-contact step bound is conservative", "[cloth][self_contact]") {
    const double gap = 0.004, separation = 0.0005;
    const ClothMesh mesh = test_fold(12, 0.1, gap, 0.0008, 9);
    const Eigen::MatrixX3d& p = mesh.positions;
    SelfContact sc(mesh.faces, mesh.vertex_count());
    const double d0 = min_pair_distance(sc, p, mesh.faces);
    REQUIRE(d0 > separation);
    REQUIRE(drape::cloth::count_self_intersections(p, mesh.faces) == 0);

    std::mt19937 rng(21);
    std::uniform_real_distribution<double> unit(-1, 1);
    int would_cross = 0;
    for (int trial = 0; trial < 12; ++trial) {
        // The top layer moves down through the bottom one (crossing at α = 1) plus noise,
        // or (odd trials) a random smooth motion.
        Eigen::MatrixX3d dx(p.rows(), 3);
        const double amp = 0.002 * (1 + trial % 4);
        for (int i = 0; i < p.rows(); ++i) {
            const bool top = p(i, 2) > 0.5 * gap;
            dx.row(i) << amp * unit(rng), amp * unit(rng), amp * unit(rng);
            if (trial % 2 == 0 && top) dx(i, 2) -= 2.5 * gap;
            if (trial % 2 == 1) dx.row(i) += Eigen::RowVector3d(std::sin(40 * p(i, 0)), 0,
                                                                std::cos(50 * p(i, 1))) * amp;
        }
        const double motion = 2 * dx.rowwise().norm().maxCoeff();
        sc.find_candidates(p, 0.005 + motion);
        const double alpha = sc.max_safe_step(p, dx, 0.9, separation);
        INFO("trial " << trial << " alpha " << alpha);
        REQUIRE(alpha > 0);
        REQUIRE(alpha <= 1);
        if (trial % 2 == 0) {
            CHECK(alpha > 0.05);  // not trivially small
            // Without the bound, the layers would meet somewhere along the full step.
            double closest = 1e300;
            for (int k = 1; k <= 16; ++k)
                closest = std::min(closest, min_pair_distance(sc, p + k / 16.0 * dx, mesh.faces));
            if (closest < separation) ++would_cross;
        }
        for (int k = 1; k <= 8; ++k) {
            const double a = alpha * k / 8.0;
            CHECK(min_pair_distance(sc, p + a * dx, mesh.faces) >= separation);
        }
    }
    CHECK(would_cross == 6);

    // A rigid translation never brings pairs closer: the full step is safe.
    Eigen::MatrixX3d shift(p.rows(), 3);
    shift.rowwise() = Eigen::RowVector3d(0.3, -0.2, 0.5);
    sc.find_candidates(p, 0.01);
    CHECK(sc.max_safe_step(p, shift, 0.9, separation) == 1.0);
    // Too small a radius for the motion shortens the step instead of missing pairs.
    Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(p.rows(), 3);
    for (int i = 0; i < p.rows(); ++i)
        if (p(i, 2) > 0.5 * gap) dx(i, 2) = -3 * gap;
    sc.find_candidates(p, 0.001);
    const double alpha = sc.max_safe_step(p, dx, 0.9, separation);
    CHECK(alpha > 0);
    for (int k = 1; k <= 8; ++k)
        CHECK(min_pair_distance(sc, p + alpha * k / 8.0 * dx, mesh.faces) >= separation);
    // A radius below the separation certifies only rigid motions.
    sc.find_candidates(p, 0.5 * separation);
    CHECK(sc.max_safe_step(p, dx, 0.9, separation) == 0.0);
    CHECK(sc.max_safe_step(p, shift, 0.9, separation) == 1.0);
    CHECK_THROWS_AS(sc.max_safe_step(p, dx, 0.0, separation), drape::InvalidInput);
}

TEST_CASE("self-contact pressed layers: the closing motion is removed, the common motion kept",
          "[cloth][self_contact]") {
    const double gap = 0.004;
    const ClothMesh mesh = test_fold(12, 0.1, gap, 0.0003, 5);
    const Eigen::MatrixX3d& p = mesh.positions;
    SelfContact sc(mesh.faces, mesh.vertex_count());
    // The top layer is pressed down through the bottom one while the whole sheet slides
    // along x: the pairs between the layers hold the step back.
    const Eigen::RowVector3d slide(0.01, 0.004, 0);
    Eigen::MatrixX3d dx(p.rows(), 3);
    for (int i = 0; i < p.rows(); ++i) {
        dx.row(i) = slide;
        if (p(i, 2) > 0.75 * gap) dx(i, 2) = -6 * gap;
    }
    sc.find_candidates(p, 0.005 + 2 * dx.rowwise().norm().maxCoeff());
    std::vector<int> holding;
    const double limit = 0.5;
    const double alpha = sc.max_safe_step(p, dx, 0.9, 0.0, &holding, limit);
    INFO("alpha " << alpha << ", " << holding.size() << " holding pairs");
    REQUIRE(alpha < 0.5);
    REQUIRE(!holding.empty());
    for (std::size_t k = 1; k < holding.size(); ++k) CHECK(holding[k] > holding[k - 1]);  // candidate order
    // With no limit nothing is listed.
    std::vector<int> none{7};
    CHECK(sc.max_safe_step(p, dx, 0.9, 0.0, &none, 0.0) == alpha);
    CHECK(none.empty());

    // The first column of vertices (on the bottom layer) is pinned: its rows stay as they are.
    std::vector<char> movable(static_cast<std::size_t>(p.rows()), 1);
    for (int i = 0; i < p.rows(); ++i)
        if (p(i, 0) < 0.005) movable[static_cast<std::size_t>(i)] = 0;
    Eigen::MatrixX3d released = dx;
    const int applied = sc.remove_closing_motion(p, released, holding, movable);
    CHECK(applied > 0);
    for (int i = 0; i < p.rows(); ++i)
        if (!movable[static_cast<std::size_t>(i)]) CHECK((released.row(i) - dx.row(i)).norm() == 0.0);

    // The pairs' closing rates along their normals fall to (nearly) zero; nothing moves apart
    // faster than it did.
    auto closing_rate = [&](int i, const Eigen::MatrixX3d& d) {
        const ContactPair& pair = sc.candidates()[static_cast<std::size_t>(i)];
        Mat34 x, dd;
        for (int c = 0; c < 4; ++c) {
            x.col(c) = p.row(pair.v[static_cast<std::size_t>(c)]).transpose();
            dd.col(c) = d.row(pair.v[static_cast<std::size_t>(c)]).transpose();
        }
        DistanceRegime regime;
        pair_distance_squared(pair.kind, x, &regime);
        const Eigen::Vector4d w = regime_weights(regime, x);
        return -(x * w).normalized().dot(dd * w);  // > 0: the gap closes
    };
    double before = 0, after = 0;
    for (int i : holding) {
        before = std::max(before, closing_rate(i, dx));
        after = std::max(after, closing_rate(i, released));
    }
    INFO("largest closing rate before " << before << " m, after " << after << " m");
    CHECK(before > 0.5 * gap);
    CHECK(after < 0.01 * before);
    // The slide survives: the vertices' mean motion along the layers is kept.
    const Eigen::RowVector3d mean_before = dx.colwise().mean(), mean_after = released.colwise().mean();
    CHECK(std::abs(mean_after(0) - mean_before(0)) < 0.02 * slide(0));
    CHECK(std::abs(mean_after(1) - mean_before(1)) < 0.02 * slide(1));
    // And the step that the released direction certifies is much longer.
    const double released_alpha = sc.max_safe_step(p, released, 0.9, 0.0);
    INFO("released alpha " << released_alpha);
    CHECK(released_alpha > 3 * alpha);
    for (int k = 1; k <= 8; ++k)
        CHECK(min_pair_distance(sc, p + released_alpha * k / 8.0 * released, mesh.faces) > 0.05 * gap);

    // Pairs that move as one keep their distance: their corners share one displacement, so
    // the bound certifies far more of the step than along the plain direction.
    Eigen::MatrixX3d together = dx;
    CHECK(sc.move_pairs_together(together, holding, movable) > 0);
    double spread_before = 0, spread_after = 0;
    for (int i : holding) {
        const ContactPair& pair = sc.candidates()[static_cast<std::size_t>(i)];
        Eigen::RowVector3d mean_dx = Eigen::RowVector3d::Zero(), mean_together = Eigen::RowVector3d::Zero();
        for (int c = 0; c < 4; ++c) {
            mean_dx += 0.25 * dx.row(pair.v[static_cast<std::size_t>(c)]);
            mean_together += 0.25 * together.row(pair.v[static_cast<std::size_t>(c)]);
        }
        for (int c = 0; c < 4; ++c) {
            spread_before = std::max(spread_before, (dx.row(pair.v[static_cast<std::size_t>(c)]) - mean_dx).norm());
            spread_after =
                std::max(spread_after, (together.row(pair.v[static_cast<std::size_t>(c)]) - mean_together).norm());
        }
    }
    INFO("largest corner spread of a holding pair: " << spread_before << " m before, " << spread_after << " after");
    CHECK(spread_after <= 1e-12 * spread_before);  // groups move exactly as one
    for (int i = 0; i < p.rows(); ++i)
        if (!movable[static_cast<std::size_t>(i)]) CHECK((together.row(i) - dx.row(i)).norm() == 0.0);
    CHECK(sc.max_safe_step(p, together, 0.9, 0.0) > 3 * alpha);
    CHECK_THROWS_AS(sc.move_pairs_together(together, {-1}, movable), drape::InvalidInput);

    // Layers moving apart are left alone.
    Eigen::MatrixX3d opening = -dx, untouched = -dx;
    CHECK(sc.remove_closing_motion(p, untouched, holding, movable) == 0);
    CHECK((untouched - opening).norm() == 0.0);
    // Bad input is named.
    CHECK_THROWS_AS(sc.remove_closing_motion(p, untouched, {static_cast<int>(sc.candidates().size())}, movable),
                    drape::InvalidInput);
    CHECK_THROWS_AS(sc.remove_closing_motion(p, untouched, holding, std::vector<char>(3, 1)),
                    drape::InvalidInput);
}

TEST_CASE("self-contact benchmark: folded 64x64 grid", "[cloth][self_contact][.bench]") {
    using clock = std::chrono::steady_clock;
    auto ms = [](clock::time_point a, clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    const ClothMesh mesh = test_fold(64, 1.0, 0.004, 0.0005, 1);
    SelfContact sc(mesh.faces, mesh.vertex_count());
    SelfContactParams params;
    // Best of `reps` runs (the machine is shared): the cost without interference.
    const int reps = 20;
    double find_ms = 1e300, gn_ms = 1e300, psd_ms = 1e300, step_ms = 1e300;
    auto best_of = [&](double& best, auto&& f) {
        for (int r = 0; r < reps; ++r) {
            const auto t0 = clock::now();
            f();
            best = std::min(best, ms(t0, clock::now()));
        }
    };
    best_of(find_ms, [&] { sc.find_candidates(mesh.positions, 1.5 * params.thickness_m); });
    Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * mesh.vertex_count());
    std::vector<PairHessian> blocks;
    best_of(gn_ms, [&] {
        blocks.clear();
        sc.energy(mesh.positions, params, &g, &blocks);
    });
    best_of(psd_ms, [&] {
        blocks.clear();
        sc.energy(mesh.positions, params, &g, &blocks, HessianMode::projected_psd);
    });
    Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(mesh.vertex_count(), 3);
    dx.col(2).setConstant(-0.001);
    for (int i = 0; i < dx.rows(); ++i)
        if (mesh.positions(i, 2) < 0.002) dx(i, 2) = 0;
    best_of(step_ms, [&] { sc.max_safe_step(mesh.positions, dx, 0.9, 0.0005); });
    const auto t3 = clock::now();
    const int tris = drape::cloth::count_self_intersections(mesh.positions, mesh.faces);
    const auto t4 = clock::now();
    WARN("folded N=64 (4225 vertices, 8192 triangles), radius 7.5 mm, best of " << reps
         << ": " << sc.candidates().size() << " candidates, " << blocks.size()
         << " active; find_candidates " << find_ms << " ms, energy+gradient+Hessians "
         << "gauss_newton " << gn_ms << " ms, projected_psd " << psd_ms
         << " ms, max_safe_step " << step_ms << " ms, count_self_intersections "
         << ms(t3, t4) << " ms (" << tris << ")");
    CHECK(tris == 0);
}
