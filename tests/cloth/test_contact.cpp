// Body contact, friction, seams: finite-difference checks of every energy, the obstacle's
// closest-point queries against brute force, and physics scenes with numbers (a stitched
// seam closing, a skirt draping on a cone-and-cylinder body, an elastica cantilever).
#include <drape/cloth/contact.hpp>
#include <drape/cloth/intersections.hpp>
#include <drape/cloth/local_curvature.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/fixtures/cloth_scenes.hpp>
#include <drape/cloth/simulator.hpp>
#include <drape/core/errors.hpp>

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>

#include "gray_interlock_fixture.hpp"
#include "../../libcloth/src/potential_probe.hpp"
#include "two_pieces_fixture.hpp"
#include <common/finite_differences.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

using namespace drape::cloth;

namespace {

constexpr double kPi = 3.14159265358979323846;

using drape::test::fd_gradient;

// Closest point on a triangle soup by brute force (dense sampling is not needed: we test the
// BVH traversal, so the reference uses the same exact point-triangle routine via 1-face
// obstacles).
double brute_distance(const TriangleMesh& m, const Eigen::Vector3d& p) {
    double best = 1e300;
    for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
        Eigen::MatrixX3d v(3, 3);
        for (int c = 0; c < 3; ++c) v.row(c) = m.positions.row(m.faces(f, c));
        Eigen::MatrixX3i one(1, 3);
        one << 0, 1, 2;
        best = std::min(best, std::abs(Obstacle(v, one).closest(p, 1e300).signed_distance_m));
    }
    return best;
}

}  // namespace

TEST_CASE("plane contact energy: finite differences and the thickness", "[cloth][contact]") {
    const Eigen::Vector3d c(0.1, -0.2, 0.3), n = Eigen::Vector3d(0.3, 0.4, 0.866).normalized();
    const double h = 5e-3, k = 800;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-4e-3, 4e-3);
    for (int trial = 0; trial < 20; ++trial) {
        const Eigen::Vector3d x = c + n * (0.5 * h + u(rng)) + Eigen::Vector3d(u(rng), u(rng), u(rng));
        Eigen::Vector3d g;
        Eigen::Matrix3d H;
        plane_contact_energy(x, c, n, h, k, &g, &H);
        auto e = [&](const Eigen::Vector3d& y) { return plane_contact_energy(y, c, n, h, k); };
        CHECK((fd_gradient(e, x, 1e-7) - g).norm() <= 1e-6 * (1 + g.norm()));
        Eigen::Matrix3d Hfd;
        for (int i = 0; i < 3; ++i) {
            auto gi = [&](const Eigen::Vector3d& y) {
                Eigen::Vector3d gy;
                plane_contact_energy(y, c, n, h, k, &gy);
                return gy;
            };
            Eigen::Vector3d a = x, b = x;
            a(i) += 1e-7;
            b(i) -= 1e-7;
            Hfd.col(i) = (gi(a) - gi(b)) / 2e-7;
        }
        CHECK((Hfd - H).norm() <= 1e-5 * (1 + H.norm()));
    }
    // Zero outside the thickness, ½ k h² on the plane.
    CHECK(plane_contact_energy(c + 1.01 * h * n, c, n, h, k) == 0);
    CHECK(plane_contact_energy(c, c, n, h, k) == Approx(0.5 * k * h * h));
}

TEST_CASE("plane contact energy: beta times as stiff behind the surface, C1 at the surface",
          "[cloth][contact]") {
    const Eigen::Vector3d c(0.1, -0.2, 0.3), n = Eigen::Vector3d(-0.2, 0.5, 0.8).normalized();
    const double h = 5e-3, k = 800, beta = 10;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-4e-3, 4e-3);
    for (int trial = 0; trial < 40; ++trial) {
        // Half the points behind the plane (d in [-4, 0) mm), half in the layer.
        const double d = trial % 2 ? -std::abs(u(rng)) - 1e-5 : std::abs(u(rng)) + 1e-5;
        const Eigen::Vector3d x = c + d * n + Eigen::Vector3d(u(rng), u(rng), u(rng)).cross(n);
        Eigen::Vector3d g;
        Eigen::Matrix3d H;
        plane_contact_energy(x, c, n, h, k, &g, &H, beta);
        auto e = [&](const Eigen::Vector3d& y) { return plane_contact_energy(y, c, n, h, k, nullptr, nullptr, beta); };
        CHECK((fd_gradient(e, x, 1e-8) - g).norm() <= 1e-6 * (1 + g.norm()));
        // The force: k (h - d) in the layer, k (h - d) + (beta - 1) k |d| behind the surface.
        const double expected = k * (h - d) + (d < 0 ? (beta - 1) * k * -d : 0.0);
        CHECK(-g.dot(n) == Approx(expected).epsilon(1e-9));
        CHECK((H - (d < 0 ? beta : 1.0) * k * n * n.transpose()).norm() <= 1e-9 * k);
    }
    // Continuous value and slope at the surface; beta = 1 is the plain penalty.
    const Eigen::Vector3d eps = 1e-9 * n;
    CHECK(plane_contact_energy(c - eps, c, n, h, k, nullptr, nullptr, beta) ==
          Approx(plane_contact_energy(c + eps, c, n, h, k, nullptr, nullptr, beta)).epsilon(1e-6));
    Eigen::Vector3d g_in, g_out;
    plane_contact_energy(c - eps, c, n, h, k, &g_in, nullptr, beta);
    plane_contact_energy(c + eps, c, n, h, k, &g_out, nullptr, beta);
    CHECK((g_in - g_out).norm() <= 1e-4 * g_out.norm());
    const Eigen::Vector3d behind = c - 2e-3 * n;
    CHECK(plane_contact_energy(behind, c, n, h, k, nullptr, nullptr, 1.0) == Approx(0.5 * k * 7e-3 * 7e-3));
    CHECK(plane_contact_energy(behind, c, n, h, k, nullptr, nullptr, beta) ==
          Approx(0.5 * k * 7e-3 * 7e-3 + 0.5 * (beta - 1) * k * 2e-3 * 2e-3));
}

TEST_CASE("friction energy: finite differences in the static and sliding regimes, Coulomb force",
          "[cloth][contact][friction]") {
    const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1).normalized();
    const double lambda = 0.02, mu = 0.3, eps = 1e-4;
    std::mt19937 rng(5);
    std::normal_distribution<double> u(0, 1);
    for (double scale : {0.3 * eps, 0.9 * eps, 3 * eps, 50 * eps}) {
        for (int trial = 0; trial < 10; ++trial) {
            const Eigen::Vector3d d = scale * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
            Eigen::Vector3d g;
            Eigen::Matrix3d H;
            friction_energy(d, n, lambda, mu, eps, &g, &H);
            auto e = [&](const Eigen::Vector3d& y) { return friction_energy(y, n, lambda, mu, eps); };
            const double step = 1e-3 * scale;
            CHECK((fd_gradient(e, d, step) - g).norm() <= 1e-5 * mu * lambda);
            Eigen::Matrix3d Hfd;
            for (int i = 0; i < 3; ++i) {
                Eigen::Vector3d a = d, b = d, ga, gb;
                a(i) += step;
                b(i) -= step;
                friction_energy(a, n, lambda, mu, eps, &ga);
                friction_energy(b, n, lambda, mu, eps, &gb);
                Hfd.col(i) = (ga - gb) / (2 * step);
            }
            CHECK((Hfd - H).norm() <= 1e-3 * H.norm() + 1e-9);
            CHECK(H.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() >= -1e-9 * H.norm());
            // Never more than μλ; exactly μλ when sliding; no normal component.
            CHECK(g.norm() <= mu * lambda * (1 + 1e-12));
            if (scale > eps) CHECK(g.norm() == Approx(mu * lambda).epsilon(1e-9));
            CHECK(std::abs(g.dot(n)) <= 1e-12);
        }
    }
}

TEST_CASE("friction energy: above the majorize threshold the Hessian is a quadratic majorizer, exact below",
          "[cloth][contact][friction]") {
    // SimulatorOptions::friction_majorize_slip_m: a slide longer than the threshold gets
    // μλ/|u| (I − nnᵀ); then E(d + s) <= E(d) + g·s + ½ sᵀ H s for every s (the model never
    // under-estimates the energy, so Newton's step is bounded; up to μλε/3, the smoothing's
    // excess over |u| where the slide ends within ε of zero), with the same energy and
    // gradient. At or below the threshold the exact Hessian is returned unchanged.
    const Eigen::Vector3d n = Eigen::Vector3d(-0.3, 0.2, 1).normalized();
    const double lambda = 0.05, mu = 0.3, eps = 1e-5, threshold = 5e-4;
    std::mt19937 rng(11);
    std::normal_distribution<double> u(0, 1);
    int majorized = 0, exact = 0;
    for (double scale : {0.3 * threshold, 0.9 * threshold, 1.5 * threshold, 20 * threshold}) {
        for (int trial = 0; trial < 10; ++trial) {
            const Eigen::Vector3d d = scale * Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
            const double slide = (d - n.dot(d) * n).norm();
            Eigen::Vector3d g, g_exact;
            Eigen::Matrix3d H, H_exact;
            const double e0 = friction_energy(d, n, lambda, mu, eps, &g, &H, threshold);
            CHECK(e0 == friction_energy(d, n, lambda, mu, eps, &g_exact, &H_exact));
            CHECK(g == g_exact);
            CHECK(H.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() >= -1e-9 * H.norm());
            if (slide <= threshold) {
                CHECK(H == H_exact);
                ++exact;
                continue;
            }
            ++majorized;
            const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - n * n.transpose();
            CHECK((H - mu * lambda / slide * tangent).norm() <= 1e-12 * H.norm());
            // Along the slide the exact Hessian is 0; the majorizer is μλ/|u| there.
            const Eigen::Vector3d along = (tangent * d).normalized();
            CHECK(along.dot(H_exact * along) == Approx(0).margin(1e-9 * H.norm()));
            CHECK(along.dot(H * along) == Approx(mu * lambda / slide));
            for (int k = 0; k < 20; ++k) {
                const Eigen::Vector3d s = 3 * scale * Eigen::Vector3d(u(rng), u(rng), u(rng));
                const double model = e0 + g.dot(s) + 0.5 * s.dot(H * s);
                CHECK(friction_energy(d + s, n, lambda, mu, eps) <= model + mu * lambda * eps / 3);
            }
        }
    }
    CHECK(majorized >= 15);
    CHECK(exact >= 15);
}

TEST_CASE("stitch energy: finite differences with and without rest length", "[cloth][contact][seam]") {
    std::mt19937 rng(7);
    std::normal_distribution<double> u(0, 0.01);
    for (double rest : {0.0, 0.004, 0.03}) {
        for (int trial = 0; trial < 10; ++trial) {
            Vector6d x;
            for (int i = 0; i < 6; ++i) x(i) = u(rng);
            auto e = [&](const Vector6d& y) {
                return stitch_energy(y.head<3>(), y.tail<3>(), rest, 500.0);
            };
            Vector6d g;
            Matrix6d H;
            stitch_energy(x.head<3>(), x.tail<3>(), rest, 500.0, &g, &H, HessianMode::exact);
            CHECK((fd_gradient(e, x, 1e-7) - g).norm() <= 1e-6 * (1 + g.norm()));
            Matrix6d Hfd;
            for (int i = 0; i < 6; ++i) {
                Vector6d a = x, b = x, ga, gb;
                a(i) += 1e-7;
                b(i) -= 1e-7;
                stitch_energy(a.head<3>(), a.tail<3>(), rest, 500.0, &ga);
                stitch_energy(b.head<3>(), b.tail<3>(), rest, 500.0, &gb);
                Hfd.col(i) = (ga - gb) / 2e-7;
            }
            CHECK((Hfd - H).norm() <= 1e-5 * (1 + H.norm()));
            Matrix6d P;
            stitch_energy(x.head<3>(), x.tail<3>(), rest, 500.0, nullptr, &P, HessianMode::projected_psd);
            CHECK(P.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff() >= -1e-9);
        }
    }
}

TEST_CASE("obstacle: closest points and signed distances match brute force", "[cloth][contact][obstacle]") {
    const TriangleMesh sphere = make_icosphere(2, 0.5, Eigen::Vector3d(0.1, 0.2, -0.1));
    REQUIRE(sphere.positions.rows() == 162);
    const Obstacle obstacle(sphere.positions, sphere.faces);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-0.8, 0.8);
    int inside = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Eigen::Vector3d p = Eigen::Vector3d(0.1, 0.2, -0.1) + Eigen::Vector3d(u(rng), u(rng), u(rng));
        const ObstacleQuery q = obstacle.closest(p, 1e300);
        REQUIRE(q.found);
        CHECK(std::abs(q.signed_distance_m) == Approx(brute_distance(sphere, p)).margin(1e-12));
        // Sign = inside test of the closed mesh.
        const bool in = point_inside_closed_mesh(p, sphere.positions, sphere.faces);
        CHECK((q.signed_distance_m < 0) == in);
        inside += in;
    }
    CHECK(inside > 10);
    // A search radius excludes far points; moving the obstacle moves the answers.
    CHECK_FALSE(obstacle.closest(Eigen::Vector3d(3, 0, 0), 0.5).found);
    Obstacle moved = obstacle;
    moved.set_positions(sphere.positions.rowwise() + Eigen::RowVector3d(1, 0, 0));
    const Eigen::Vector3d p(1.1, 0.2, 0.7);
    CHECK(moved.closest(p, 1e300).signed_distance_m ==
          Approx(obstacle.closest(p - Eigen::Vector3d(1, 0, 0), 1e300).signed_distance_m));
    // Bad input.
    Eigen::MatrixX3i bad = sphere.faces;
    bad(0, 0) = 1000;
    CHECK_THROWS_AS(Obstacle(sphere.positions, bad), drape::InvalidInput);
    CHECK_THROWS_AS(moved.set_positions(Eigen::MatrixX3d::Zero(3, 3)), drape::InvalidInput);
}

TEST_CASE("a cloth square dropped on a sphere rests on it, outside, without crossing itself",
          "[cloth][contact][simulator]") {
    // A 16 x 16 version of the anchor scene, 0.6 s.
    AnchorScene scene = make_anchor_scene(16);
    Simulator sim(scene.cloth, drape::test::gray_interlock_material(), scene.options);
    sim.set_obstacle(Obstacle(scene.sphere.positions, scene.sphere.faces));
    int failed = 0;
    for (int k = 0; k < 120; ++k) failed += sim.step().usable() ? 0 : 1;
    CHECK(failed == 0);
    const ContactReport r = sim.contact_report();
    CHECK(r.max_penetration_m <= 1e-3);
    CHECK(r.self_intersections == 0);
    // The centre rests on the sphere's top at about the thickness (within 1.5 mm).
    const double top = scene.sphere.positions.col(2).maxCoeff();
    CHECK(sim.positions()(scene.centre_vertex, 2) - top == Approx(scene.options.contact_thickness_m).margin(1.5e-3));
    // Friction holds the cloth: the centre has not slid off the top.
    CHECK(sim.positions().row(scene.centre_vertex).head<2>().norm() < 0.01);
}

TEST_CASE("a patch deeper inside the obstacle than the contact query radius is pushed back out",
          "[cloth][contact][simulator]") {
    // A 10 cm patch is put 30 mm inside the top of a 0.5 m sphere, twice as deep as the 15 mm
    // within which contacts are searched. Without gravity, nothing but the contact can move
    // it. A vertex found only within the query radius had no contact at all there and stayed
    // inside for good (a stiff skirt pushed 51 mm into a thigh); the simulator now searches
    // farther for vertices whose previous distance was within the radius or unknown, so the
    // patch is pushed out, first from a fresh simulator, then again after set_positions
    // puts it back in (its previous distances, out of reach by then, no longer count).
    const TriangleMesh sphere = make_icosphere(3, 0.5);
    SimulatorOptions options;
    options.gravity_m_per_s2.setZero();
    const double depth = 0.03, top = sphere.positions.col(2).maxCoeff();
    const ClothMesh m = make_square_grid(4, 0.1, Eigen::Vector3d(-0.05, -0.05, top - depth), Eigen::Vector3d::UnitX(),
                                         Eigen::Vector3d::UnitY());
    Simulator sim(m, drape::test::gray_interlock_material(), options);
    sim.set_obstacle(Obstacle(sphere.positions, sphere.faces));
    REQUIRE(sim.contact_report().max_penetration_m > 0.025);
    for (int round = 0; round < 2; ++round) {
        for (int k = 0; k < 40; ++k) REQUIRE(sim.step().usable());
        const ContactReport r = sim.contact_report();
        INFO("round " << round << ": deepest " << 1000 * r.max_penetration_m << " mm, " << r.vertices_inside
                      << " inside");
        CHECK(r.vertices_inside == 0);
        CHECK(r.min_obstacle_distance_m > 0);
        if (round == 0) {
            // Flat again, 30 mm inside the top (the push sent it up and away).
            Eigen::MatrixX3d in = m.positions;
            sim.set_positions(in);
            sim.set_velocities(Eigen::MatrixX3d::Zero(in.rows(), 3));
            REQUIRE(sim.contact_report().max_penetration_m > 0.025);
        }
    }
}

TEST_CASE("buckling steps end after max_nonconvex_step_iterations regularised iterations",
          "[cloth][contact][simulator]") {
    // The 32 x 32 anchor scene buckles as it drapes over the sphere: some steps' exact
    // Newton matrices are indefinite. With the limit those steps end early (usable), the
    // drape still comes to rest on the sphere as without it, with fewer Newton iterations.
    struct Run {
        int iterations = 0, limited_steps = 0, failed = 0;
        Eigen::MatrixX3d x;
        ContactReport report;
    };
    auto run = [](int limit) {
        AnchorScene scene = make_anchor_scene(32);
        scene.options.max_nonconvex_step_iterations = limit;
        Simulator sim(scene.cloth, drape::test::gray_interlock_material(), scene.options);
        sim.set_obstacle(Obstacle(scene.sphere.positions, scene.sphere.faces));
        Run r;
        for (int k = 0; k < 100; ++k) {  // 0.5 s: falls, wraps the sphere and buckles
            const StepSummary s = sim.step();
            r.iterations += s.newton_iterations;
            r.failed += s.usable() ? 0 : 1;
            if (s.message.find("not convex") != std::string::npos) {
                ++r.limited_steps;
                // Each counted iteration needed at least one regularised factorisation.
                CHECK(s.regularised_factorisations >= limit);
                CHECK(s.termination == StepTermination::max_iterations);
            }
        }
        r.x = sim.positions();
        r.report = sim.contact_report();
        return r;
    };
    const Run limited = run(1), unlimited = run(0);
    INFO("Newton iterations: limit 1 " << limited.iterations << ", no limit " << unlimited.iterations
                                       << "; steps ended by the limit: " << limited.limited_steps);
    CHECK(unlimited.limited_steps == 0);
    REQUIRE(limited.limited_steps > 0);
    CHECK(limited.iterations < unlimited.iterations);
    for (const Run* r : {&limited, &unlimited}) {
        CHECK(r->failed == 0);
        CHECK(r->report.max_penetration_m <= 1e-3);
        CHECK(r->report.self_intersections == 0);
    }
    // Same rest state on the sphere's top (centre node within 1 mm).
    const int centre = make_anchor_scene(32).centre_vertex;
    CHECK((limited.x.row(centre) - unlimited.x.row(centre)).norm() < 1e-3);
}

namespace {

using test::two_pieces;

}  // namespace

TEST_CASE("an open seam is pulled closed and then held", "[cloth][contact][seam]") {
    // Two 0.2 m squares side by side with a 4 cm gap, stitched along the facing edges.
    const int n = 8;
    ClothMesh a = make_square_grid(n, 0.2, Eigen::Vector3d(-0.22, 0, 0), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    ClothMesh b = make_square_grid(n, 0.2, Eigen::Vector3d(0.02, 0, 0), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    const int na = a.vertex_count();
    const ClothMesh m = two_pieces(a, b);
    SimulatorOptions options;
    options.gravity_m_per_s2.setZero();
    options.air_drag_n_s_per_m3 = 0.5;
    Simulator sim(m, drape::test::gray_interlock_material(), options);
    std::vector<Stitch> stitches;
    for (int j = 0; j <= n; ++j)  // right column of a (u = 0.2) to left column of b (u = 0)
        stitches.push_back({j * (n + 1) + n, na + j * (n + 1), 0.2 / n});
    sim.set_stitches(stitches);
    CHECK(sim.contact_report().max_stitch_gap_m == Approx(0.04));
    StepSummary s;
    for (int k = 0; k < 60; ++k) {
        s = sim.step();
        REQUIRE(s.usable());
    }
    INFO(s.brief_report());
    CHECK(s.max_stitch_gap_m < 1e-3);
    // Held: a static solve keeps it closed, and the pieces did not crumple.
    const StepSummary st = sim.solve_static();
    CHECK(st.termination == StepTermination::converged);
    const ContactReport r = sim.contact_report();
    CHECK(r.max_stitch_gap_m < 1e-4);
    CHECK(r.self_intersections == 0);
    CHECK_THROWS_AS(sim.set_stitches({{0, 0, 0.01}}), drape::InvalidInput);
    CHECK_THROWS_AS(sim.set_stitches({{0, 100000, 0.01}}), drape::InvalidInput);
}

namespace {

// A closed surface of revolution about z: (z, r) profile from top to bottom, capped.
TriangleMesh revolve(const std::vector<std::pair<double, double>>& profile, int segments) {
    const int rings = static_cast<int>(profile.size());
    TriangleMesh m;
    m.positions.resize(rings * segments + 2, 3);
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double t = 2 * kPi * j / segments;
            m.positions.row(i * segments + j) << profile[static_cast<std::size_t>(i)].second * std::cos(t),
                profile[static_cast<std::size_t>(i)].second * std::sin(t), profile[static_cast<std::size_t>(i)].first;
        }
    const int top = rings * segments, bottom = top + 1;
    m.positions.row(top) << 0, 0, profile.front().first;
    m.positions.row(bottom) << 0, 0, profile.back().first;
    std::vector<Eigen::Vector3i> f;
    for (int j = 0; j < segments; ++j) {
        const int j1 = (j + 1) % segments;
        f.emplace_back(top, j, j1);
        for (int i = 0; i + 1 < rings; ++i) {
            const int a = i * segments + j, b = i * segments + j1, c = (i + 1) * segments + j,
                      d = (i + 1) * segments + j1;
            f.emplace_back(a, c, d);
            f.emplace_back(a, d, b);
        }
        f.emplace_back(bottom, (rings - 1) * segments + j1, (rings - 1) * segments + j);
    }
    m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (std::size_t i = 0; i < f.size(); ++i) m.faces.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
    return m;
}

}  // namespace

TEST_CASE("a skirt with a stitched seam drapes on a cone-and-cylinder body", "[cloth][contact][skirt]") {
    // Body: a cone (hips) from r = 0.10 m at z = 1.0 to r = 0.20 m at z = 0.8, then a
    // cylinder to z = 0.3. Skirt: a half-annulus pattern (inner radius 0.34 m, 0.4 m long),
    // wrapped into a cone frustum (waist r ≈ 0.17, hem r ≈ 0.37) whose two straight edges
    // are stitched; it starts open by 2 cm and above the hips, and is dropped.
    const TriangleMesh body = revolve({{1.0, 0.10}, {0.9, 0.15}, {0.8, 0.20}, {0.55, 0.20}, {0.3, 0.20}}, 48);
    const int nr = 8, nt = 48;
    const double a = 0.34, len = 0.4, phi = kPi;
    const double wrap = (2 * kPi - 0.02 / 0.17) / phi;  // angle scale in 3D: leaves a 2 cm gap
    Eigen::MatrixX3d x((nr + 1) * (nt + 1), 3);
    Eigen::MatrixX2d uv((nr + 1) * (nt + 1), 2);
    for (int i = 0; i <= nr; ++i)
        for (int j = 0; j <= nt; ++j) {
            const double s = a + len * i / nr, t = phi * j / nt;
            const int id = i * (nt + 1) + j;
            uv.row(id) << s * std::cos(t), s * std::sin(t);
            // Developable cone: slant distance s maps to radius s·phi/2π, height drops.
            const double r = s * phi / (2 * kPi), drop = std::sqrt(s * s - r * r) - std::sqrt(a * a - std::pow(a * phi / (2 * kPi), 2));
            const double ang = t * wrap;
            x.row(id) << r * std::cos(ang), r * std::sin(ang), 1.02 - drop;
        }
    Eigen::MatrixX3i faces(2 * nr * nt, 3);
    int f = 0;
    for (int i = 0; i < nr; ++i)
        for (int j = 0; j < nt; ++j) {
            const int p = i * (nt + 1) + j, q = p + 1, r = p + nt + 1, s = r + 1;
            // Counter-clockwise in the pattern (u, v) = s(cos t, sin t).
            if ((i + j) % 2 == 0) {
                faces.row(f++) << p, r, s;
                faces.row(f++) << p, s, q;
            } else {
                faces.row(f++) << p, r, q;
                faces.row(f++) << q, r, s;
            }
        }
    const ClothMesh skirt = ClothMesh::from_vertex_pattern(x, faces, uv);
    SimulatorOptions options;
    options.air_drag_n_s_per_m3 = 3.0;  // damps the swing (at rest after ≈ 2.4 s)
    Simulator sim(skirt, drape::test::gray_interlock_material(), options);
    sim.set_obstacle(Obstacle(body.positions, body.faces));
    std::vector<Stitch> stitches;
    for (int i = 0; i <= nr; ++i) stitches.push_back({i * (nt + 1), i * (nt + 1) + nt, len / nr});
    sim.set_stitches(stitches);
    int failed = 0;
    StepSummary s;
    const auto rms_speed = [&] { return std::sqrt(sim.velocities().rowwise().squaredNorm().mean()); };
    int k = 0, calm = 0;
    for (; k < 2000 && calm < 20; ++k) {
        s = sim.step();
        failed += s.usable() ? 0 : 1;
        calm = k >= 250 && rms_speed() < 0.002 ? calm + 1 : 0;
        if (std::getenv("DRAPE_DEBUG_SKIRT") && k % 10 == 0)
            std::printf("step %d waist z %.4f r %.4f rms %.4f: %s\n", k, sim.positions()(0, 2),
                        sim.positions().row(0).head<2>().norm(), rms_speed(), s.brief_report().c_str());
    }
    INFO("at rest (rms speed < 2 mm/s for 20 steps) after " << k << " steps");
    INFO(s.brief_report());
    CHECK(failed == 0);
    const ContactReport before = sim.contact_report();
    INFO("after the dynamic phase: " << before.self_intersections << " self-intersections, gap "
         << before.max_stitch_gap_m << " m, penetration " << before.max_penetration_m << " m");
    CHECK(before.self_intersections == 0);
    // The last steps converged and the cloth came to rest (drag and friction): its rms
    // speed stayed under 2 mm/s for 20 steps (0.1 s) within 10 s of simulated time.
    CHECK(s.termination == StepTermination::converged);
    const double speed = rms_speed();
    INFO("rms speed " << speed << " m/s, max " << sim.velocities().rowwise().norm().maxCoeff());
    CHECK(calm >= 20);
    CHECK(speed < 0.002);
    const ContactReport r = sim.contact_report();
    CHECK(r.max_stitch_gap_m < 1e-3);
    CHECK(r.max_penetration_m <= 1e-3);
    CHECK(r.self_intersections == 0);
    // It hangs from the hips: the waist settled where the cone is as wide as the waist.
    double waist_z = 0;
    for (int j = 0; j <= nt; ++j) waist_z += sim.positions()(j, 2) / (nt + 1);
    CHECK(waist_z > 0.8);
    CHECK(waist_z < 0.95);
    // Folds: the hem's radius oscillates around the body (at least 4 waves).
    int maxima = 0;
    const int hem = nr * (nt + 1);
    auto radius = [&](int j) { return sim.positions().row(hem + (j + nt) % nt).head<2>().norm(); };
    for (int j = 0; j < nt; ++j)
        if (radius(j) > radius(j - 1) && radius(j) > radius(j + 1)) ++maxima;
    CHECK(maxima >= 4);
}

TEST_CASE("friction between cloth layers stops a sliding layer as Coulomb's law predicts",
          "[cloth][contact][self_contact][friction]") {
    // A 0.14 m square dropped 0.5 mm onto a pinned 0.3 m one settles at the 5 mm thickness, then
    // slides at 0.5 m/s along x under gravity. With μ = 0.6 it stops after v²/(2μg) ≈ 2.1 cm
    // in v/(μg) ≈ 0.085 s; without friction it keeps its speed.
    auto slide = [](double mu, double* speed) {
        const int n = 4;
        ClothMesh a = make_square_grid(n, 0.3, Eigen::Vector3d(-0.05, -0.05, 0), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
        // Turned by 0.3 rad and shifted, so that no edge lies exactly above a parallel one.
        const double turn = 0.3;
        ClothMesh b = make_square_grid(n, 0.14, Eigen::Vector3d(0.05, 0.02, 0.0055),
                                       Eigen::Vector3d(std::cos(turn), std::sin(turn), 0),
                                       Eigen::Vector3d(-std::sin(turn), std::cos(turn), 0));
        const int na = a.vertex_count();
        const ClothMesh m = two_pieces(a, b);
        SimulatorOptions options;
        options.cloth_friction = mu;
        options.air_drag_n_s_per_m3 = 0;
        Simulator sim(m, drape::test::gray_interlock_material(), options);
        for (int i = 0; i < na; ++i) sim.pin(i);
        for (int k = 0; k < 30; ++k) REQUIRE(sim.step().usable());  // lands and settles
        const Eigen::MatrixX3d start = sim.positions();
        Eigen::MatrixX3d v = Eigen::MatrixX3d::Zero(2 * na, 3);
        v.bottomRows(na).col(0).setConstant(0.5);
        sim.set_velocities(v);
        for (int k = 0; k < 30; ++k) {  // 0.15 s
            const StepSummary s = sim.step();
            INFO(s.brief_report());
            REQUIRE(s.usable());
        }
        *speed = sim.velocities().bottomRows(na).col(0).mean();
        CHECK(sim.contact_report().self_intersections == 0);
        CHECK(sim.positions().bottomRows(na).col(2).minCoeff() > 0);  // still above the lower layer
        return sim.positions().bottomRows(na).col(0).mean() - start.bottomRows(na).col(0).mean();
    };
    double speed_free = 0, speed_friction = 0;
    const double free = slide(0.0, &speed_free);
    const double held = slide(0.6, &speed_friction);
    INFO("slid " << free * 100 << " cm without friction (speed " << speed_free << " m/s), " << held * 100
                 << " cm with mu = 0.6 (speed " << speed_friction << " m/s)");
    CHECK(free == Approx(0.075).margin(0.005));
    CHECK(speed_free == Approx(0.5).margin(0.02));
    CHECK(held == Approx(0.5 * 0.5 / (2 * 0.6 * 9.8)).epsilon(0.3));
    CHECK(std::abs(speed_friction) < 0.02);
}

TEST_CASE("solve_static keeps Coulomb friction: a patch sticks on a slope below the friction angle",
          "[cloth][contact][friction][static]") {
    // A 0.2 m patch rests on a plane tilted 12 degrees (tan = 0.21). With obstacle friction
    // 0.4 the static equilibrium holds it where it lies; with 0.1 (or with the static solve's
    // friction off) no equilibrium exists near it and it slides down the slope.
    const double tilt = 12.0 * kPi / 180;
    const Eigen::Vector3d down_slope(0, -std::cos(tilt), -std::sin(tilt));  // in the plane, downhill
    const Eigen::Vector3d across(1, 0, 0), normal = across.cross(-down_slope).normalized();
    Eigen::MatrixX3d plane(4, 3);
    plane.row(0) = (-across - down_slope).transpose();
    plane.row(1) = (across - down_slope).transpose();
    plane.row(2) = (across + down_slope).transpose();
    plane.row(3) = (-across + down_slope).transpose();
    Eigen::MatrixX3i quad(2, 3);
    quad << 0, 1, 2, 0, 2, 3;
    // Counter-clockwise seen from above (the obstacle's outside).
    if ((plane.row(1) - plane.row(0)).cross(plane.row(2) - plane.row(0)).z() < 0) quad << 0, 2, 1, 0, 3, 2;
    auto run = [&](double mu, bool static_friction) {
        SimulatorOptions options;
        options.obstacle_friction = mu;
        options.static_friction = static_friction;
        options.max_newton_iterations = 200;
        const Eigen::Vector3d up = normal.z() > 0 ? normal : Eigen::Vector3d(-normal);
        ClothMesh m = make_square_grid(6, 0.2, 0.0049 * up - 0.1 * across + 0.1 * down_slope, across, -down_slope);
        // Settled first by time steps with friction that holds it (its normal forces then
        // balance its weight), then solved for equilibrium with the options under test.
        SimulatorOptions settle;
        settle.obstacle_friction = 0.4;
        Simulator first(m, drape::test::gray_interlock_material(), settle);
        first.set_obstacle(Obstacle(plane, quad));
        for (int k = 0; k < 40; ++k) REQUIRE(first.step().usable());
        m.positions = first.positions();
        Simulator sim(m, drape::test::gray_interlock_material(), options);
        sim.set_obstacle(Obstacle(plane, quad));
        const Eigen::MatrixX3d start = sim.positions();
        const StepSummary s = sim.solve_static();
        INFO("mu " << mu << ", static friction " << static_friction << ": " << s.brief_report());
        REQUIRE(s.termination != StepTermination::non_finite);
        const Eigen::MatrixX3d d = sim.positions() - start;
        return std::make_pair(s, (d * down_slope).mean());
    };
    const auto [held, held_slide] = run(0.4, true);
    INFO("held: " << held.brief_report() << ", slid " << 1000 * held_slide << " mm");
    CHECK(held.termination == StepTermination::converged);
    CHECK(std::abs(held_slide) < 0.5e-3);
    const auto [free, free_slide] = run(0.4, false);
    INFO("frictionless static solve slid " << 1000 * free_slide << " mm (" << free.brief_report() << ")");
    CHECK(free_slide > 0.01);
    const auto [weak, weak_slide] = run(0.1, true);
    INFO("mu 0.1 slid " << 1000 * weak_slide << " mm (" << weak.brief_report() << ")");
    CHECK(weak_slide > 0.01);
}

TEST_CASE("obstacle friction ends when a vertex leaves the contact layer within a step",
          "[cloth][contact][friction]") {
    // A 0.2 m patch lies 2.5 mm above a horizontal plane (inside the 5 mm contact layer,
    // pressed against it: its friction is lagged with λ = k A h/2) and is thrown up and
    // sideways at (1, 0, 2) m/s without gravity. It leaves the layer about 1 ms into the
    // 5 ms step; from then on nothing touches it, so its sideways motion over the step is
    // the free flight's 5 mm less only what friction took in that first millisecond.
    // Friction kept over the whole step from the contacts at its start (the old lagging)
    // held it almost in place sideways (< 1 mm) — and at the edge of the layer that
    // lingering friction made a draped dress chatter without ever coming to rest.
    Eigen::MatrixX3d plane(4, 3);
    plane << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0;
    Eigen::MatrixX3i quad(2, 3);
    quad << 0, 1, 2, 0, 2, 3;
    SimulatorOptions options;
    options.gravity_m_per_s2.setZero();
    options.obstacle_friction = 0.6;
    const double h = options.contact_thickness_m;
    ClothMesh m = make_square_grid(4, 0.2, Eigen::Vector3d(-0.1, -0.1, 0.5 * h), Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitY());
    Simulator sim(m, drape::test::gray_interlock_material(), options);
    sim.set_obstacle(Obstacle(plane, quad));
    Eigen::MatrixX3d v(sim.positions().rows(), 3);
    v.rowwise() = Eigen::RowVector3d(1.0, 0.0, 2.0);
    sim.set_velocities(v);
    const Eigen::MatrixX3d start = sim.positions();
    const StepSummary s = sim.step();
    REQUIRE(s.usable());
    const Eigen::MatrixX3d d = sim.positions() - start;
    INFO(s.brief_report() << "; mean sideways " << 1000 * d.col(0).mean() << " mm, up " << 1000 * d.col(2).mean()
                          << " mm");
    CHECK(d.col(2).minCoeff() > 0.5 * h);                 // every vertex left the layer
    CHECK(d.col(0).mean() > 0.6 * 1.0 * options.time_step_s);  // kept most of its 5 mm sideways
    CHECK(d.col(0).mean() <= 1.0 * options.time_step_s + 1e-6);  // friction never pushes it
}

TEST_CASE("obstacle friction carries cloth along a moving obstacle, and holds it on a still one",
          "[cloth][contact][friction]") {
    // A 0.2 m patch rests on a horizontal plate under gravity. The plate then slides along +X
    // at 0.3 m/s for 0.4 s (12 cm). Friction acts on the slip relative to the plate's surface:
    // with mu = 0.6 the patch reaches the plate's speed within about 0.3 / (0.6 g) = 0.05 s and
    // rides on it, so it travels nearly as far as the plate (about 12 cm less the 0.8 cm slip
    // while it catches up). Friction measured against the patch's motion in the world instead
    // (the plate's motion ignored) holds it where it lies: it would not move at all. Without
    // friction it stays where it is, as nothing else pushes it sideways. Going back and forth
    // does not make it creep: a plate that bobs up and down 2 cm carries the patch up and down
    // with it and leaves it where it was sideways.
    const auto plate = [](double x, double z) {
        Eigen::MatrixX3d v(4, 3);
        v << -1 + x, -1, z, 1 + x, -1, z, 1 + x, 1, z, -1 + x, 1, z;
        return v;
    };
    Eigen::MatrixX3i quad(2, 3);
    quad << 0, 1, 2, 0, 2, 3;
    const auto run = [&](double mu, double speed) {
        SimulatorOptions options;
        options.obstacle_friction = mu;
        const double h = options.contact_thickness_m;
        ClothMesh m = make_square_grid(6, 0.2, Eigen::Vector3d(-0.1, -0.1, 0.5 * h), Eigen::Vector3d::UnitX(),
                                       Eigen::Vector3d::UnitY());
        Simulator sim(m, drape::test::gray_interlock_material(), options);
        sim.set_obstacle(Obstacle(plate(0, 0), quad));
        for (int k = 0; k < 20; ++k) REQUIRE(sim.step().usable());  // settles on the plate
        const Eigen::MatrixX3d start = sim.positions();
        const int steps = static_cast<int>(std::lround(0.4 / options.time_step_s));
        for (int k = 1; k <= steps; ++k) {
            sim.move_obstacle(plate(speed * k * options.time_step_s, 0));
            const StepSummary s = sim.step();
            INFO("step " << k << ": " << s.brief_report());
            REQUIRE(s.usable());
        }
        return Eigen::RowVector3d((sim.positions() - start).colwise().mean());
    };
    const Eigen::RowVector3d carried = run(0.6, 0.3), frictionless = run(0.0, 0.3);
    INFO("mu 0.6: moved " << 1000 * carried << " mm; mu 0: " << 1000 * frictionless << " mm");
    CHECK(carried.x() > 0.105);
    CHECK(carried.x() < 0.12 + 1e-3);
    CHECK(std::abs(carried.y()) < 1e-3);
    CHECK(std::abs(frictionless.x()) < 2e-3);

    // Bobbing: 2 cm up and down twice a second for 1 s, the patch carried by the contact.
    SimulatorOptions options;
    options.obstacle_friction = 0.6;
    ClothMesh m = make_square_grid(6, 0.2, Eigen::Vector3d(-0.1, -0.1, 0.5 * options.contact_thickness_m),
                                   Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    Simulator sim(m, drape::test::gray_interlock_material(), options);
    sim.set_obstacle(Obstacle(plate(0, 0), quad));
    for (int k = 0; k < 20; ++k) REQUIRE(sim.step().usable());
    const Eigen::MatrixX3d start = sim.positions();
    const int steps = static_cast<int>(std::lround(1.0 / options.time_step_s));
    double highest = -1;
    for (int k = 1; k <= steps; ++k) {
        const double t = k * options.time_step_s, z = 0.01 * (1 - std::cos(4 * kPi * t));
        sim.move_obstacle(plate(0, z));
        REQUIRE(sim.step().usable());
        highest = std::max(highest, (sim.positions() - start).col(2).mean());
    }
    const Eigen::RowVector3d bobbed = (sim.positions() - start).colwise().mean();
    INFO("after bobbing: moved " << 1000 * bobbed << " mm, highest " << 1000 * highest << " mm");
    CHECK(highest > 0.018);
    CHECK(std::abs(bobbed.z()) < 2e-3);
    CHECK(std::abs(bobbed.x()) < 1e-3);
    CHECK(std::abs(bobbed.y()) < 1e-3);
}

TEST_CASE("a patch pinched between two facing surfaces comes to rest between them", "[cloth][contact]") {
    // Two obstacle planes 8 mm apart face each other (z = 0 facing up, z = 8 mm facing
    // down), closer than twice the 5 mm contact layer; a patch lies in the middle, without
    // gravity. With one contact plane per vertex and step, each step pushed the patch out of
    // the layer of the surface that was closest at the step's start into the other's, and
    // the next step back: a period-2 chatter of ~2 mm per step that never came to rest (the
    // underarm of a t-shirt between arm and torso: docs/dressing.md). With a second plane
    // for the facing surface the patch settles where the two layers balance.
    const double gap = 0.008;
    Eigen::MatrixX3d V(8, 3);
    V << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, -1, -1, gap, 1, -1, gap, 1, 1, gap, -1, 1, gap;
    Eigen::MatrixX3i F(4, 3);
    F << 0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6;  // lower faces +z, upper faces -z
    SimulatorOptions options;
    options.gravity_m_per_s2.setZero();
    const double h = options.contact_thickness_m;
    REQUIRE(gap < 2 * h);
    ClothMesh m = make_square_grid(4, 0.2, Eigen::Vector3d(-0.1, -0.1, 0.45 * gap), Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitY());
    Simulator sim(m, drape::test::gray_interlock_material(), options);
    sim.set_obstacle(Obstacle(V, F));
    Eigen::MatrixX3d before = sim.positions();
    double last_move = 0;
    for (int k = 0; k < 60; ++k) {
        before = sim.positions();
        REQUIRE(sim.step().usable());
        last_move = (sim.positions() - before).rowwise().norm().maxCoeff();
    }
    INFO("last step moved up to " << 1000 * last_move << " mm; z " << 1000 * sim.positions().col(2).minCoeff() << "-"
                                  << 1000 * sim.positions().col(2).maxCoeff() << " mm");
    CHECK(last_move < 1e-5);
    CHECK(sim.positions().col(2).minCoeff() > 0.4 * gap);
    CHECK(sim.positions().col(2).maxCoeff() < 0.6 * gap);
}

TEST_CASE("a vertex falling onto the body stops outside it, without holding back the rest of the cloth",
          "[cloth][contact][simulator]") {
    // Two patches fall at 1.5 m/s; a floor lies under the first only, 8 mm below it, beyond
    // the 5 mm contact layer. The step moves 12.5 mm, and Newton gets one iteration (a time
    // step that ends early). With strict_body_contact, a vertex without an active contact
    // plane, which has no energy that would push it back out, may go only 0.9 of its distance
    // towards the body: the first patch ends outside the floor. The cut is its own: the second
    // patch, with nothing under it, still takes its full free-flight step. Without it (the
    // default) one step length for the whole cloth lets the first patch end 4.2 mm inside
    // the floor and holds the second to 12.2 mm.
    const double height = 0.008, speed = 1.5;
    const ClothMesh a = make_square_grid(3, 0.04, Eigen::Vector3d(-0.12, -0.02, height), Eigen::Vector3d::UnitX(),
                                         Eigen::Vector3d::UnitY());
    const ClothMesh b = make_square_grid(3, 0.04, Eigen::Vector3d(0.12, -0.02, height), Eigen::Vector3d::UnitX(),
                                         Eigen::Vector3d::UnitY());
    Eigen::MatrixX3d floor(4, 3);
    floor << -0.2, -0.1, 0, 0, -0.1, 0, 0, 0.1, 0, -0.2, 0.1, 0;
    Eigen::MatrixX3i faces(2, 3);
    faces << 0, 1, 2, 0, 2, 3;
    for (const bool strict : {true, false}) {
        SimulatorOptions options;
        options.gravity_m_per_s2.setZero();
        options.time_step_s = 1.0 / 120;
        options.max_newton_iterations = 1;
        options.strict_body_contact = strict;
        Simulator sim(drape::cloth::test::two_pieces(a, b), drape::test::gray_interlock_material(), options);
        sim.set_obstacle(Obstacle(floor, faces));
        sim.set_velocities(Eigen::MatrixX3d::Zero(sim.positions().rows(), 3).rowwise() +
                           Eigen::RowVector3d(0, 0, -speed));
        const Eigen::MatrixX3d before = sim.positions();
        sim.step();
        const Eigen::MatrixX3d& x = sim.positions();
        const int na = a.vertex_count();
        const double a_low = x.topRows(na).col(2).minCoeff();
        const Eigen::VectorXd b_fall = before.bottomRows(x.rows() - na).col(2) - x.bottomRows(x.rows() - na).col(2);
        INFO("strict " << strict << ": first patch's lowest vertex at " << 1e3 * a_low << " mm; second patch fell "
                       << 1e3 * b_fall.minCoeff() << "-" << 1e3 * b_fall.maxCoeff() << " mm of "
                       << 1e3 * speed * options.time_step_s);
        if (strict) {
            CHECK(a_low > 0.05 * height);
            CHECK(a_low < 0.5 * height);  // it did move most of the way
            CHECK(b_fall.minCoeff() > 0.999 * speed * options.time_step_s);
            CHECK(b_fall.maxCoeff() < 1.001 * speed * options.time_step_s);
        } else {
            CHECK(a_low < -0.003);
            CHECK(b_fall.maxCoeff() < 0.99 * speed * options.time_step_s);
        }
    }
}

TEST_CASE("a vertex sliding into a concave corner within a step is held by the second surface",
          "[cloth][contact][simulator]") {
    // A floor (z = 0, facing up) meets a wall (x = 0, facing -x) at a right angle: a concave
    // corner, like the armpit's fold between chest and arm. A patch pressed into the floor's
    // layer (a soft contact: it rests 1.2 mm deep in it) glides towards the wall 1 cm away at
    // 1 m/s, frictionless. Its vertices' contact planes are the floor's, made at the step's
    // start; the wall's normal is 90 degrees from the floor's, not facing it, so no pinch
    // plane is made, and the floor's plane let the patch through the wall (10.8 mm deep; the
    // walking t-shirt's armpit went 5.5 mm into the chest this way). A vertex whose plane
    // overstates its distance to the body by more than half the layer now gets a second
    // plane, where it is (1.0 mm deep at most).
    SimulatorOptions options;
    options.time_step_s = 1.0 / 60;
    options.obstacle_friction = 0;
    options.contact_stiffness_n_per_m3 = 2e3;
    options.strict_body_contact = true;
    const double speed = 1.0;
    const ClothMesh m = make_square_grid(3, 0.04, Eigen::Vector3d(-0.05, -0.02, 0.003), Eigen::Vector3d::UnitX(),
                                         Eigen::Vector3d::UnitY());
    Simulator sim(m, drape::test::gray_interlock_material(), options);
    Eigen::MatrixX3d V(8, 3);
    V << -0.3, -0.3, 0, 0, -0.3, 0, 0, 0.3, 0, -0.3, 0.3, 0,  // floor
        0, -0.3, 0, 0, 0.3, 0, 0, 0.3, 0.3, 0, -0.3, 0.3;      // wall
    Eigen::MatrixX3i F(4, 3);
    F << 0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6;  // floor faces +z, wall faces -x
    const Obstacle corner(V, F);
    REQUIRE(corner.closest(Eigen::Vector3d(-0.01, 0, 0.1), 1).signed_distance_m > 0);
    REQUIRE(corner.closest(Eigen::Vector3d(-0.1, 0, 0.01), 1).signed_distance_m > 0);
    sim.set_obstacle(corner);
    sim.set_velocities(Eigen::MatrixX3d::Zero(m.positions.rows(), 3).rowwise() + Eigen::RowVector3d(speed, 0, 0));
    double deepest = 0, closest_to_wall = -1;
    for (int k = 0; k < 8; ++k) {
        REQUIRE(sim.step().usable());
        closest_to_wall = std::max(closest_to_wall, sim.positions().col(0).maxCoeff());
        for (Eigen::Index i = 0; i < sim.positions().rows(); ++i)
            deepest = std::max(deepest, -corner.closest(sim.positions().row(i).transpose(), 0.05).signed_distance_m);
    }
    INFO("deepest " << 1e3 * deepest << " mm; the patch came to x = " << 1e3 * closest_to_wall << " mm");
    CHECK(closest_to_wall > -0.002);  // it did reach the wall
    CHECK(deepest < 2e-3);
}

TEST_CASE("with strict_body_contact a body moving along its surface carries its cloth and the layer on it in full",
          "[cloth][contact][simulator]") {
    // A plate slides along +X at 1.5 m/s, 12.5 mm per 1/120 s step; a patch rests on it under
    // gravity, and a second patch rests on the first. Newton gets one iteration per step. The
    // body's friction carries the cloth it holds: Newton starts with those vertices moved along
    // with the surface. Bounded as a motion towards a body standing still, that carry was cut
    // to (0.9 d + h) / 12.5 mm of itself, one cut for all the cloth, and the patch on top, which
    // the body does not touch, was not carried at all. With strict_body_contact each vertex is
    // carried with its surface in full, and the patch on top, held by cloth friction, with the
    // patch under it.
    const double speed = 1.5;
    const auto plate = [](double x) {
        Eigen::MatrixX3d v(4, 3);
        v << -1 + x, -1, 0, 1 + x, -1, 0, 1 + x, 1, 0, -1 + x, 1, 0;
        return v;
    };
    Eigen::MatrixX3i faces(2, 3);
    faces << 0, 1, 2, 0, 2, 3;
    for (const bool strict : {true, false}) {
        SimulatorOptions options;
        options.time_step_s = 1.0 / 120;
        options.max_newton_iterations = 1;
        options.obstacle_friction = 0.6;
        options.cloth_friction = 0.6;
        options.strict_body_contact = strict;
        const double h = options.contact_thickness_m;
        const ClothMesh lower = make_square_grid(4, 0.1, Eigen::Vector3d(-0.05, -0.05, 0.5 * h),
                                                 Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
        const ClothMesh upper = make_square_grid(4, 0.1, Eigen::Vector3d(-0.05, -0.05, 1.3 * h),
                                                 Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
        Simulator sim(drape::cloth::test::two_pieces(lower, upper), drape::test::gray_interlock_material(), options);
        sim.set_obstacle(Obstacle(plate(0), faces));
        for (int k = 0; k < 20; ++k) REQUIRE(sim.step().usable());  // settles on the plate
        const Eigen::MatrixX3d start = sim.positions();
        const int n = lower.vertex_count();
        const double step_m = speed * options.time_step_s;
        sim.move_obstacle(plate(step_m));
        REQUIRE(sim.step().usable());
        const Eigen::MatrixX3d moved = sim.positions() - start;
        const double lower_x = moved.topRows(n).col(0).mean(), upper_x = moved.bottomRows(n).col(0).mean();
        INFO("strict " << strict << ": lower patch carried " << 1e3 * lower_x << " mm, upper " << 1e3 * upper_x
                       << " mm of " << 1e3 * step_m << "; heights after settling " << 1e3 * start.topRows(n).col(2).mean()
                       << " and " << 1e3 * start.bottomRows(n).col(2).mean() << " mm");
        if (strict) {
            CHECK(lower_x > 0.95 * step_m);
            CHECK(lower_x < 1.02 * step_m);
            CHECK(upper_x > 0.9 * step_m);
        } else {
            CHECK(lower_x < 0.8 * step_m);
            CHECK(upper_x < 0.2 * step_m);
        }
    }
}

TEST_CASE("with strict_body_contact the carry stops at another part of the body", "[cloth][contact][simulator]") {
    // A plate (one part of the body, ending at x = 0.10) has moved 12.5 mm along +X since the
    // last step, towards a closed box standing still at x = 0.12 (another part). A patch lies
    // on the plate, 2.5 mm above it, its front row at x = 0.11. The step's first iterate moves
    // every patch vertex with the plate, except the front row: carried, it would be 2.5 mm
    // inside the box.
    const double shift = 0.0125;
    const auto body = [](double x) {
        Eigen::MatrixX3d v(12, 3);
        v << -1 + x, -1, 0, 0.10 + x, -1, 0, 0.10 + x, 1, 0, -1 + x, 1, 0,  // the plate, facing +z
            0.12, -1, -0.05, 0.2, -1, -0.05, 0.2, 1, -0.05, 0.12, 1, -0.05,  // the box's corners
            0.12, -1, 0.05, 0.2, -1, 0.05, 0.2, 1, 0.05, 0.12, 1, 0.05;
        return v;
    };
    Eigen::MatrixX3i faces(14, 3);
    faces << 0, 1, 2, 0, 2, 3,                 // plate
        4, 6, 5, 4, 7, 6, 8, 9, 10, 8, 10, 11,  // box bottom (-z), top (+z)
        4, 5, 9, 4, 9, 8, 6, 7, 11, 6, 11, 10,  // y = -1 (-y), y = 1 (+y)
        4, 8, 11, 4, 11, 7, 5, 6, 10, 5, 10, 9; // x = 0.12 (-x), x = 0.2 (+x)
    for (const bool strict : {true, false}) {
        SimulatorOptions options;
        options.time_step_s = 1.0 / 120;
        options.obstacle_friction = 0.6;
        options.strict_body_contact = strict;
        options.self_contact = false;  // a flat patch: only the body bounds its carry
        const double h = options.contact_thickness_m;
        const ClothMesh patch = make_square_grid(4, 0.1, Eigen::Vector3d(0.01, -0.05, 0.5 * h),
                                                 Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
        Simulator sim(patch, drape::test::gray_interlock_material(), options);
        sim.set_obstacle(Obstacle(body(0), faces));
        {
            const Obstacle o(body(shift), faces);
            const ObstacleQuery q = o.closest(Eigen::Vector3d(0.11 + shift, 0, 0.5 * h), 0.1);
            REQUIRE(q.found);
            REQUIRE(q.signed_distance_m < 0);  // the front row, carried, would be in the box
        }
        sim.move_obstacle(body(shift));
        const drape::cloth::internal::PotentialProbe probe(sim, 2 * h);
        const Eigen::MatrixX3d carry = probe.start_carry();
        const Eigen::MatrixX3d& x = sim.positions();
        double front = 0, rest_min = 1, rest_max = 0;
        for (Eigen::Index v = 0; v < x.rows(); ++v) {
            const double c = carry.row(v).norm();
            if (x(v, 0) > 0.109) front = std::max(front, c);
            else rest_min = std::min(rest_min, c), rest_max = std::max(rest_max, c);
        }
        INFO("strict " << strict << ": front row carried up to " << 1e3 * front << " mm, the others "
                       << 1e3 * rest_min << "-" << 1e3 * rest_max << " mm of " << 1e3 * shift);
        if (strict) {
            CHECK(front == 0);
            CHECK(rest_min > 0.999 * shift);
            CHECK(rest_max < 1.001 * shift);
        } else {
            // One cut for all: (0.9 d + h) / 12.5 mm with d = 2.5 mm.
            CHECK(rest_max < 0.65 * shift);
        }
    }
}
