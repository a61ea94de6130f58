// Finite-difference check of the whole assembled incremental potential of a time step
// (ipc-toolkit's test_barrier_potential is the model): stretching, bending, gravity, air
// drag, inertia, body contact planes, obstacle friction, self-contact, cloth–cloth friction,
// stitches and pins, all active at once on a small two-layer scene, through the library's own
// assembly (internal::PotentialProbe).
#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/obstacle.hpp>
#include <drape/cloth/simulator.hpp>

#include "../../libcloth/src/potential_probe.hpp"

#include <catch2/catch.hpp>

#include "gray_interlock_fixture.hpp"
#include "two_pieces_fixture.hpp"
#include <common/finite_differences.hpp>

#include <random>
#include <vector>

using namespace drape::cloth;

namespace {

// Two square pieces in one mesh, the upper one 3.5 mm above the lower (within the 5 mm
// contact thickness) and shifted in the plane so no vertex sits above another's feature.
ClothMesh two_layers(int n, double size_m, double gap_m) {
    const ClothMesh a = make_square_grid(n, size_m, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d::UnitX(),
                                         Eigen::Vector3d::UnitZ());
    const ClothMesh b = make_square_grid(n, size_m, Eigen::Vector3d(0.0013, gap_m, 0.0021),
                                         Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
    return test::two_pieces(a, b);
}

}  // namespace

TEST_CASE("whole incremental potential: finite-difference gradient and Hessian with every term active",
          "[cloth][simulator][fd]") {
    const int n = 4;
    const ClothMesh mesh = two_layers(n, 0.04, 0.0035);
    const int per_layer = (n + 1) * (n + 1);
    SimulatorOptions options;
    options.air_drag_n_s_per_m3 = 2.0;
    options.wind_m_per_s = Eigen::Vector3d(0.3, 0, -0.2);
    // A slip distance well above the finite-difference step, so the smoothed friction is
    // resolved (ε = 0.1 m/s × 5 ms = 0.5 mm).
    options.friction_slip_speed_m_per_s = 0.1;
    Simulator sim(mesh, drape::test::gray_interlock_material(), options);

    // The body: a large plane 2 mm below the lower layer, normal +Y.
    Eigen::MatrixX3d body_v(4, 3);
    body_v << -1, -0.002, -1, -1, -0.002, 1, 1, -0.002, 1, 1, -0.002, -1;
    Eigen::MatrixX3i body_f(2, 3);
    body_f << 0, 1, 2, 0, 2, 3;
    sim.set_obstacle(Obstacle(body_v, body_f));
    // Stitches between the layers' corners (rest length: their distance now) and one pin.
    const int corner = n, far = per_layer - 1;
    sim.set_stitches({{0, per_layer, 0.01}, {corner, per_layer + corner, 0.01}, {far, per_layer + far, 0.01}});
    sim.pin(per_layer + 2 * (n + 1) + 2);  // the middle of the upper layer
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> unit(-1, 1);
    Eigen::MatrixX3d v(mesh.vertex_count(), 3);
    for (Eigen::Index i = 0; i < v.rows(); ++i) v.row(i) << 0.05 * unit(rng), 0.01 * unit(rng), 0.05 * unit(rng);
    sim.set_velocities(v);
    // Also after the rest shape or the materials changed on the constructed simulator
    // (Simulator::set_rest_positions, set_materials: a new sizing or fabric in recovery).
    const int variant = GENERATE(0, 1, 2);
    if (variant == 1) {
        Eigen::MatrixX2d uv = mesh.pattern;
        uv.col(0) = 1.05 * mesh.pattern.col(0) + 0.02 * mesh.pattern.col(1);
        uv.col(1) = 0.96 * mesh.pattern.col(1);
        sim.set_rest_positions(uv);
    } else if (variant == 2) {
        Material stiff = drape::test::gray_interlock_material();
        stiff.bending_scale = 30;
        stiff.stretching_scale = 2;
        stiff.density_kg_per_m2 *= 1.5;
        sim.set_materials({stiff});
    }
    INFO("variant " << variant << " (0 as built, 1 new rest shape, 2 new material)");

    const double thickness = options.contact_thickness_m;
    drape::cloth::internal::PotentialProbe probe(sim, 2 * thickness);
    const auto& terms = probe.terms();
    // Every term is there: a pass must not come from a missing one.
    REQUIRE(terms.faces > 0);
    REQUIRE(terms.hinges > 0);
    REQUIRE(terms.stitches == 3);
    REQUIRE(terms.pinned == 1);
    REQUIRE(terms.contact_planes >= per_layer);
    REQUIRE(terms.friction >= per_layer);
    REQUIRE(terms.pair_friction > 0);
    REQUIRE(terms.self_candidates > 0);

    // Evaluate away from the start: displacements of 0.2 mm (stretching, bending, friction
    // in both its smoothed and its sliding range), far below the layer gaps.
    Eigen::MatrixX3d q = mesh.positions;
    for (Eigen::Index i = 0; i < q.rows(); ++i) q.row(i) += 2e-4 * Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
    const int nfree = probe.free_dofs();
    REQUIRE(nfree == 3 * (mesh.vertex_count() - 1));
    // Free dofs <-> positions.
    std::vector<std::pair<int, int>> coordinate(static_cast<std::size_t>(nfree));
    for (int i = 0; i < mesh.vertex_count(); ++i)
        for (int c = 0; c < 3; ++c)
            if (probe.dof(i, c) >= 0) coordinate[static_cast<std::size_t>(probe.dof(i, c))] = {i, c};
    auto positions = [&](const Eigen::VectorXd& y) {
        Eigen::MatrixX3d p = q;
        for (int d = 0; d < nfree; ++d) p(coordinate[static_cast<std::size_t>(d)].first, coordinate[static_cast<std::size_t>(d)].second) = y(d);
        return p;
    };
    auto free_part = [&](const Eigen::VectorXd& g) {
        Eigen::VectorXd out(nfree);
        for (int d = 0; d < nfree; ++d) out(d) = g(3 * coordinate[static_cast<std::size_t>(d)].first + coordinate[static_cast<std::size_t>(d)].second);
        return out;
    };
    Eigen::VectorXd y(nfree);
    for (int d = 0; d < nfree; ++d) y(d) = q(coordinate[static_cast<std::size_t>(d)].first, coordinate[static_cast<std::size_t>(d)].second);

    Eigen::VectorXd g_full;
    Eigen::MatrixXd hessian;
    int active_pairs = 0;
    const double e = probe.evaluate(q, &g_full, &hessian, &active_pairs);
    REQUIRE(std::isfinite(e));
    REQUIRE(active_pairs > 0);  // self-contact pairs within the thickness at q
    const Eigen::VectorXd g = free_part(g_full);
    REQUIRE(g.norm() > 1e-3);  // newtons: far from a stationary point

    const double step = 1e-8;
    const Eigen::VectorXd g_fd = drape::test::fd_gradient(
        [&](const Eigen::VectorXd& z) { return probe.evaluate(positions(z)); }, y, step);
    const Eigen::MatrixXd h_fd = drape::test::fd_hessian(
        [&](const Eigen::VectorXd& z) {
            Eigen::VectorXd gz;
            probe.evaluate(positions(z), &gz);
            return Eigen::VectorXd(free_part(gz));
        },
        y, step);
    INFO("|g| " << g.norm() << ", |H| " << hessian.norm() << ", active self-contact pairs " << active_pairs);
    CHECK(drape::test::relative_error(g_fd, g) < 1e-6);
    CHECK(drape::test::relative_error(h_fd, hessian) < 1e-5);
    // Symmetric, as the Hessian of one scalar function must be.
    CHECK((hessian - hessian.transpose()).norm() <= 1e-12 * hessian.norm());
}
