// Changing the rest shape (pattern) and the materials of an existing simulator
// (Simulator::set_rest_positions, set_materials): the result must be the simulator a fresh
// construction with the new pattern or materials gives — forces, masses, time steps.
#include <drape/cloth/cloth_mesh.hpp>
#include <drape/cloth/simulator.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include "gray_interlock_fixture.hpp"

#include <cmath>
#include <limits>
#include <random>
#include <string>

using namespace drape::cloth;

namespace {

// A vertical patch in the x-z plane, its top row pinned, crumpled a little so that
// stretching and bending both carry force.
ClothMesh crumpled_patch(int n, double size) {
    ClothMesh mesh = make_square_grid(n, size, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d::UnitX(),
                                      -Eigen::Vector3d::UnitZ());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (Eigen::Index i = n + 1; i < mesh.positions.rows(); ++i)
        mesh.positions.row(i) += 0.01 * size * Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
    return mesh;
}

// The pattern stretched 6 % along u, shrunk 3 % along v and sheared, with noise: a new
// sizing of the same mesh.
Eigen::MatrixX2d morphed(const Eigen::MatrixX2d& pattern, double size, int n) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(-1, 1);
    Eigen::MatrixX2d out(pattern.rows(), 2);
    for (Eigen::Index i = 0; i < pattern.rows(); ++i) {
        const double u = pattern(i, 0), v = pattern(i, 1);
        out.row(i) << 1.06 * u + 0.04 * v, 0.97 * v;
        out.row(i) += 0.1 * size / n * Eigen::RowVector2d(unit(rng), unit(rng));
    }
    return out;
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return (a - b).norm() / std::max(b.norm(), std::numeric_limits<double>::min());
}

void pin_top(Simulator& sim, int n) {
    for (int i = 0; i <= n; ++i) sim.pin(i);
}

}  // namespace

TEST_CASE("set_rest_positions equals a fresh construction with the new pattern", "[cloth][simulator][rest]") {
    const int n = 8;
    const double size = 0.4;
    const ClothMesh mesh = crumpled_patch(n, size);
    const Eigen::MatrixX2d uv = morphed(mesh.pattern, size, n);
    ClothMesh fresh_mesh = mesh;
    fresh_mesh.pattern = uv;

    Simulator changed(mesh, drape::test::gray_interlock_material());
    pin_top(changed, n);
    // Step once first: the solver's symbolic analysis and the lagged stiffness exist.
    REQUIRE(changed.step().usable());
    changed.set_rest_positions(uv);
    changed.set_positions(mesh.positions);
    changed.set_velocities(Eigen::MatrixX3d::Zero(mesh.vertex_count(), 3));

    Simulator fresh(fresh_mesh, drape::test::gray_interlock_material());
    pin_top(fresh, n);

    CHECK(changed.mesh().pattern == uv);
    CHECK(relative(changed.masses(), fresh.masses()) < 1e-12);
    const Eigen::MatrixX3d f_changed = changed.forces(), f_fresh = fresh.forces();
    INFO("|f| " << f_fresh.norm() << " N");
    CHECK(f_fresh.norm() > 1e-3);
    CHECK(relative(f_changed, f_fresh) < 1e-12);
    // The change mattered: the forces at the same positions differ from the old pattern's.
    Simulator old_rest(mesh, drape::test::gray_interlock_material());
    pin_top(old_rest, n);
    CHECK(relative(f_fresh, old_rest.forces()) > 1e-2);

    // The next time step and a static solve land where the fresh simulator's do.
    const StepSummary a = changed.step(), b = fresh.step();
    REQUIRE(a.usable());
    REQUIRE(b.usable());
    CHECK(a.newton_iterations == b.newton_iterations);
    CHECK(relative(changed.positions(), fresh.positions()) < 1e-12);
    const StepSummary sa = changed.solve_static(), sb = fresh.solve_static();
    INFO(sa.brief_report());
    CHECK(sa.termination == sb.termination);
    CHECK(relative(changed.positions(), fresh.positions()) < 1e-12);
}

TEST_CASE("set_materials equals a fresh construction with the new materials", "[cloth][simulator][rest]") {
    const int n = 6;
    const double size = 0.3;
    const ClothMesh mesh = crumpled_patch(n, size);
    const Material base = drape::test::gray_interlock_material();
    Material stiff = base;
    stiff.bending_scale = 100;
    stiff.stretching_scale = 2;
    stiff.density_kg_per_m2 = 0.3;
    // Two materials per face (left and right halves), both changed.
    std::vector<int> face_material(static_cast<std::size_t>(mesh.face_count()));
    for (int f = 0; f < mesh.face_count(); ++f)
        face_material[static_cast<std::size_t>(f)] = mesh.positions(mesh.faces(f, 0), 0) < 0.5 * size ? 0 : 1;
    Material other = base;
    other.bending_scale = 3;
    Simulator changed(mesh, {base, base}, face_material);
    pin_top(changed, n);
    REQUIRE(changed.step().usable());
    changed.set_materials({stiff, other});
    changed.set_positions(mesh.positions);
    changed.set_velocities(Eigen::MatrixX3d::Zero(mesh.vertex_count(), 3));
    Simulator fresh(mesh, {stiff, other}, face_material);
    pin_top(fresh, n);

    CHECK(changed.materials()[0].bending_scale == 100);
    CHECK(relative(changed.masses(), fresh.masses()) < 1e-12);
    const Eigen::MatrixX3d f_changed = changed.forces(), f_fresh = fresh.forces();
    CHECK(relative(f_changed, f_fresh) < 1e-12);
    Simulator old_material(mesh, {base, base}, face_material);
    pin_top(old_material, n);
    CHECK(relative(f_fresh, old_material.forces()) > 1e-2);
    REQUIRE(changed.step().usable());
    REQUIRE(fresh.step().usable());
    CHECK(relative(changed.positions(), fresh.positions()) < 1e-12);
}

TEST_CASE("set_rest_positions and set_materials reject bad input, naming it, and keep the simulator",
          "[cloth][simulator][rest]") {
    const int n = 3;
    const ClothMesh mesh = crumpled_patch(n, 0.2);
    Simulator sim(mesh, drape::test::gray_interlock_material());
    const Eigen::MatrixX3d f0 = sim.forces();
    auto message = [&](auto&& call) {
        try {
            call();
        } catch (const drape::InvalidInput& e) {
            return std::string(e.what());
        }
        return std::string("no exception");
    };
    using Catch::Matchers::Contains;
    CHECK_THAT(message([&] { sim.set_rest_positions(Eigen::MatrixX2d::Zero(3, 2)); }), Contains("3 pattern rows"));
    Eigen::MatrixX2d nan = mesh.pattern;
    nan(5, 1) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THAT(message([&] { sim.set_rest_positions(nan); }), Contains("pattern row 5 is not finite"));
    // Collapse an edge of face 4: the first degenerate or flipped face is named.
    Eigen::MatrixX2d flat = mesh.pattern;
    flat.row(mesh.faces(4, 1)) = flat.row(mesh.faces(4, 0));
    int first_bad = -1;
    for (int f = 0; f < mesh.face_count() && first_bad < 0; ++f) {
        const Eigen::RowVector2d e1 = flat.row(mesh.faces(f, 1)) - flat.row(mesh.faces(f, 0));
        const Eigen::RowVector2d e2 = flat.row(mesh.faces(f, 2)) - flat.row(mesh.faces(f, 0));
        if (0.5 * (e1.x() * e2.y() - e1.y() * e2.x()) <= 1e-12) first_bad = f;
    }
    REQUIRE(first_bad >= 0);
    REQUIRE(first_bad <= 4);
    CHECK_THAT(message([&] { sim.set_rest_positions(flat); }),
               Contains("face " + std::to_string(first_bad) + " has signed area"));
    Material bad = drape::test::gray_interlock_material();
    bad.bending_scale = -1;
    CHECK_THAT(message([&] { sim.set_materials({bad}); }), Contains("material 0 is invalid"));
    CHECK_THAT(message([&] { sim.set_materials({bad, bad}); }), Contains("2 materials"));
    CHECK(sim.mesh().pattern == mesh.pattern);
    CHECK(sim.forces() == f0);
}
