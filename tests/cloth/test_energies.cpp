// Finite-difference checks of every energy, plus the uniaxial-stretch physics check.
#include <drape/cloth/energies.hpp>
#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

#include "gray_interlock_fixture.hpp"
#include <common/finite_differences.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <random>

using namespace drape::cloth;

namespace {

constexpr double kPi = 3.14159265358979323846;

template <int N>
using Vec = Eigen::Matrix<double, N, 1>;
template <int N>
using Mat = Eigen::Matrix<double, N, N>;

using drape::test::fd_gradient;
using drape::test::fd_hessian;
using drape::test::relative_error;

Eigen::Matrix3d to_cols(const Vec<9>& v) { return Eigen::Map<const Eigen::Matrix3d>(v.data()); }
Eigen::Matrix<double, 3, 4> to_cols(const Vec<12>& v) {
    return Eigen::Map<const Eigen::Matrix<double, 3, 4>>(v.data());
}

struct RandomTriangle {
    TriangleRest rest;
    Vec<9> x;
    StretchingStiffness k;
};

RandomTriangle random_triangle(std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-1, 1);
    RandomTriangle t;
    Eigen::Vector2d u[3];
    do {
        for (auto& p : u) p = 0.05 * Eigen::Vector2d(unit(rng), unit(rng));
    } while (((u[1] - u[0]).x() * (u[2] - u[0]).y() - (u[1] - u[0]).y() * (u[2] - u[0]).x()) <
             2e-4);
    t.rest = triangle_rest(u[0], u[1], u[2]);
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(3 * unit(rng), Eigen::Vector3d(unit(rng), unit(rng), 1).normalized())
            .toRotationMatrix();
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d p(u[i].x(), u[i].y(), 0);
        t.x.segment<3>(3 * i) = rotation * p + 0.02 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    }
    t.k = {100 + 300 * (unit(rng) + 1), 50 * (unit(rng) + 1), 100 + 300 * (unit(rng) + 1),
           20 + 40 * (unit(rng) + 1)};
    return t;
}

}  // namespace

TEST_CASE("stretching energy: finite-difference gradient and Hessian", "[cloth][energy][stretch]") {
    std::mt19937 rng(7);
    double worst_g = 0, worst_h = 0;
    for (int trial = 0; trial < 50; ++trial) {
        const RandomTriangle t = random_triangle(rng);
        auto energy = [&](const Vec<9>& x) { return stretching_energy(to_cols(x), t.rest, t.k); };
        auto gradient = [&](const Vec<9>& x) {
            Vec<9> g;
            stretching_energy(to_cols(x), t.rest, t.k, &g);
            return g;
        };
        Vec<9> g;
        Mat<9> h;
        const double e = stretching_energy(to_cols(t.x), t.rest, t.k, &g, &h, HessianMode::exact);
        CHECK(e == Approx(energy(t.x)));
        worst_g = std::max(worst_g, relative_error(fd_gradient(energy, t.x, 1e-7), g));
        worst_h = std::max(worst_h, relative_error(fd_hessian(gradient, t.x, 1e-7), h));
        // Projected: PSD, and equal to the exact one when that is already PSD.
        Mat<9> hp;
        stretching_energy(to_cols(t.x), t.rest, t.k, nullptr, &hp, HessianMode::projected_psd);
        const double min_eig = Eigen::SelfAdjointEigenSolver<Mat<9>>(hp).eigenvalues().minCoeff();
        CHECK(min_eig >= -1e-9 * hp.norm());
        if (Eigen::SelfAdjointEigenSolver<Mat<9>>(h).eigenvalues().minCoeff() >= 0)
            CHECK(relative_error(hp, h) < 1e-12);
    }
    INFO("worst relative errors: gradient " << worst_g << ", Hessian " << worst_h);
    CHECK(worst_g < 1e-5);
    CHECK(worst_h < 1e-5);
}

TEST_CASE("stretching energy is zero at rest and invariant under rigid motion",
          "[cloth][energy][stretch]") {
    const TriangleRest rest = triangle_rest({0, 0}, {0.1, 0}, {0.02, 0.08});
    const StretchingStiffness k{300, 40, 250, 30};
    Eigen::Matrix3d x;
    x << 0, 0.1, 0.02, 0, 0, 0.08, 0, 0, 0;
    Vec<9> g;
    CHECK(stretching_energy(x, rest, k, &g) == Approx(0).margin(1e-15));
    CHECK(g.norm() < 1e-12);
    Eigen::Matrix3d deformed = x;
    deformed(0, 1) = 0.115;
    deformed(2, 2) = 0.01;
    const Eigen::Matrix3d r = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::Matrix3d moved = (r * deformed).colwise() + Eigen::Vector3d(0.3, -2, 5);
    CHECK(stretching_energy(moved, rest, k, &g) == Approx(stretching_energy(deformed, rest, k)));
    CHECK((g.segment<3>(0) + g.segment<3>(3) + g.segment<3>(6)).norm() < 1e-9 * g.norm());
}

TEST_CASE("uniaxial stretch of a patch reproduces the table's stress", "[cloth][energy][physics]") {
    Material m = drape::test::gray_interlock_material();
    const double size = 0.2;
    const ClothMesh patch = make_square_grid(1, size, Eigen::Vector3d::Zero(),
                                             Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    for (int axis = 0; axis < 2; ++axis)
        for (double lambda : {1.02, 1.1, 1.3}) {
            INFO("axis " << axis << ", stretch " << lambda);
            Eigen::MatrixX3d x = patch.positions;
            x.col(axis) *= lambda;  // the other in-plane axis is held at its rest length
            Eigen::MatrixX3d gradient = Eigen::MatrixX3d::Zero(x.rows(), 3);
            for (int f = 0; f < patch.face_count(); ++f) {
                Eigen::Vector2d u[3];
                Eigen::Matrix3d xf;
                for (int c = 0; c < 3; ++c) {
                    u[c] = patch.pattern.row(patch.faces(f, c)).transpose();
                    xf.col(c) = x.row(patch.faces(f, c)).transpose();
                }
                const TriangleRest rest = triangle_rest(u[0], u[1], u[2]);
                const StretchingStiffness k = stretching_stiffness(m, green_strain(xf, rest));
                Vec<9> g;
                stretching_energy(xf, rest, k, &g);
                for (int c = 0; c < 3; ++c) gradient.row(patch.faces(f, c)) += g.segment<3>(3 * c).transpose();
            }
            // Force per unit rest length on the far edge (u = size, or v = size), N/m.
            double traction = 0;
            for (int i = 0; i < patch.vertex_count(); ++i)
                if (patch.pattern(i, axis) == size) traction += gradient(i, axis);
            traction /= size;
            // Table: w = λ, direction 0 (k0, row 1) or 90 degrees (k2, row 5), × 2 (ArcSim).
            const double s = std::min((lambda - 1) * 6, 1.0);
            const std::size_t row = axis == 0 ? 1 : 5, col = axis == 0 ? 0 : 2;
            const double k_table =
                2 * ((1 - s) * m.stretching_n_per_m[0][col] + s * m.stretching_n_per_m[row][col]);
            const double expected = lambda * k_table * (lambda * lambda - 1) / 2;  // P = F S
            CHECK(traction == Approx(expected).epsilon(0.01));
        }
}

TEST_CASE("dihedral angle: sign, flat and folded values", "[cloth][energy][bend]") {
    Eigen::Matrix<double, 3, 4> x;
    x.col(0) << 0, 0, 0;
    x.col(1) << 1, 0, 0;
    x.col(2) << 0.3, 1, 0;
    for (double theta : {-2.5, -1.0, 0.0, 0.4, 1.5, 3.0}) {
        // x3 rotated about the edge from the flat position (0.6, -1, 0).
        x.col(3) << 0.6, -std::cos(theta), -std::sin(theta);
        CHECK(dihedral_angle(x) == Approx(theta).margin(1e-12));
    }
}

TEST_CASE("bending energy: finite-difference gradient and Hessian", "[cloth][energy][bend]") {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(-1, 1);
    double worst_g = 0, worst_h = 0;
    for (int trial = 0; trial < 50; ++trial) {
        const double theta = 2.5 * unit(rng), l = 0.05 * (1.5 + unit(rng));
        Eigen::Matrix<double, 3, 4> x0;
        x0.col(0) << 0, 0, 0;
        x0.col(1) << l, 0, 0;
        x0.col(2) << l * 0.5 * (1 + unit(rng)), l * (0.6 + 0.3 * unit(rng)), 0;
        x0.col(3) << l * 0.5 * (1 + unit(rng)), -l * (0.6 + 0.3 * unit(rng)) * std::cos(theta),
            -l * (0.6 + 0.3 * unit(rng)) * std::sin(theta);
        Vec<12> xv = Eigen::Map<Vec<12>>(x0.data());
        for (int i = 0; i < 12; ++i) xv(i) += 0.05 * l * unit(rng);
        HingeRest rest;
        rest.rest_angle_rad = 0.3 * unit(rng);
        rest.rest_length_m = l * (1 + 0.1 * unit(rng));
        rest.rest_area_sum_m2 = l * l * (0.6 + 0.2 * unit(rng));
        const double k = 2e-5 * (1.5 + unit(rng));
        auto energy = [&](const Vec<12>& v) { return bending_energy(to_cols(v), rest, k); };
        auto gradient = [&](const Vec<12>& v) {
            Vec<12> g;
            bending_energy(to_cols(v), rest, k, &g);
            return g;
        };
        Vec<12> g;
        Mat<12> h;
        const double e = bending_energy(to_cols(xv), rest, k, &g, &h, HessianMode::exact);
        CHECK(e == Approx(energy(xv)));
        const double step = 1e-6 * l;
        worst_g = std::max(worst_g, relative_error(fd_gradient(energy, xv, step), g));
        worst_h = std::max(worst_h, relative_error(fd_hessian(gradient, xv, step), h));
        Mat<12> hgn;
        bending_energy(to_cols(xv), rest, k, nullptr, &hgn, HessianMode::gauss_newton);
        const double c = k * rest.rest_length_m * rest.rest_length_m / (8 * rest.rest_area_sum_m2);
        const Vec<12> dtheta = dihedral_angle_gradient(to_cols(xv));
        CHECK(relative_error(hgn, 2 * c * dtheta * dtheta.transpose()) < 1e-14);
        Mat<12> hp;
        bending_energy(to_cols(xv), rest, k, nullptr, &hp, HessianMode::projected_psd);
        CHECK(Eigen::SelfAdjointEigenSolver<Mat<12>>(hp).eigenvalues().minCoeff() >= -1e-9 * hp.norm());
        // Energy value: k l̄² / (8 (A0 + A1)) (θ − θ̄)².
        const double d = dihedral_angle(to_cols(xv)) - rest.rest_angle_rad;
        CHECK(e == Approx(k * rest.rest_length_m * rest.rest_length_m / (8 * rest.rest_area_sum_m2) * d * d));
    }
    INFO("worst relative errors: gradient " << worst_g << ", Hessian " << worst_h);
    CHECK(worst_g < 1e-5);
    CHECK(worst_h < 1e-5);
}

TEST_CASE("hinge rest data and curvature from the pattern", "[cloth][energy][bend]") {
    const ClothMesh mesh = make_square_grid(2, 0.1, Eigen::Vector3d::Zero(),
                                            Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
    for (const Hinge& h : build_hinges(mesh)) {
        const HingeRest rest = hinge_rest(mesh, h);
        CHECK(rest.rest_area_sum_m2 == Approx(2 * 0.5 * 0.05 * 0.05));
        CHECK((rest.rest_length_m == Approx(0.05) || rest.rest_length_m == Approx(0.05 * std::sqrt(2.0))));
        // Both sides see the same edge, traversed the same way (v0 -> v1).
        CHECK(rest.direction_rad[0] == Approx(rest.direction_rad[1]));
        Eigen::Matrix<double, 3, 4> x;
        for (int c = 0; c < 4; ++c) x.col(c) = mesh.positions.row(h.v[static_cast<std::size_t>(c)]).transpose();
        CHECK(dihedral_angle(x) == Approx(0).margin(1e-12));
        CHECK(hinge_curvature(0.5, rest) == Approx(0.5 * rest.rest_length_m / rest.rest_area_sum_m2));
    }
}

TEST_CASE("masses and gravity", "[cloth][energy][gravity]") {
    Material m;
    m.density_kg_per_m2 = 0.187;
    const ClothMesh mesh = make_square_grid(4, 1.0, Eigen::Vector3d(0, 0, 0.6),
                                            Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    const Eigen::VectorXd masses = vertex_masses(mesh, m);
    CHECK(masses.sum() == Approx(0.187));
    CHECK(masses.minCoeff() > 0);
    const Eigen::Vector3d gravity(0, 0, -9.8);
    Eigen::MatrixX3d g;
    const double e = gravity_energy(mesh.positions, masses, gravity, &g);
    CHECK(e == Approx(0.187 * 9.8 * 0.6));
    Eigen::MatrixX3d shifted = mesh.positions;
    shifted(3, 2) += 1e-3;
    CHECK(gravity_energy(shifted, masses, gravity) - e == Approx(g(3, 2) * 1e-3));
    Material bad = m;
    bad.density_kg_per_m2 = -1;
    CHECK_THROWS_AS(vertex_masses(mesh, bad), drape::InvalidInput);
}

TEST_CASE("curvature-dependent bending: finite differences and ArcSim's force",
          "[cloth][energy][bend]") {
    // gray-interlock's bending table.
    Material m;
    m.density_kg_per_m2 = 0.187;
    m.bending_n_m = {{{23.191698e-6, 32.932217e-6, 34.406498e-6, 39.014420e-6, 23.382786e-6},
                      {24.749964e-6, 18.651314e-6, 16.370552e-6, 25.095791e-6, 8.860165e-6},
                      {14.267624e-6, 7.052906e-6, 14.515154e-6, 24.665127e-6, 19.383726e-6}}};
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    double worst_g = 0, worst_h = 0;
    int tested = 0;
    for (int trial = 0; trial < 200 && tested < 50; ++trial) {
        const double l = 0.01 * (1.5 + unit(rng));
        HingeRest rest;
        rest.rest_length_m = l;
        rest.rest_area_sum_m2 = l * l * (0.6 + 0.2 * unit(rng));
        rest.direction_rad[0] = 1.5 * unit(rng);
        rest.direction_rad[1] = 1.5 * unit(rng);
        const BendingCurve curve = bending_curve(m, rest);
        const double theta = 2.5 * unit(rng);
        Eigen::Matrix<double, 3, 4> x0;
        x0.col(0) << 0, 0, 0;
        x0.col(1) << l, 0, 0;
        x0.col(2) << 0.5 * l, 0.7 * l, 0;
        x0.col(3) << 0.4 * l, -0.7 * l * std::cos(theta), -0.7 * l * std::sin(theta);
        Vec<12> xv = Eigen::Map<Vec<12>>(x0.data());
        for (int i = 0; i < 12; ++i) xv(i) += 0.05 * l * unit(rng);
        // Skip states within 1 % of a knot: the Hessian jumps there.
        const double kappa = std::abs(dihedral_angle(to_cols(xv))) * l / rest.rest_area_sum_m2;
        bool near_knot = false;
        for (int j = 0; j < curve.knot_count; ++j)
            near_knot |= std::abs(kappa - curve.curvature_per_m[static_cast<std::size_t>(j)]) < 0.01 * (1 + kappa);
        if (near_knot) continue;
        ++tested;
        auto energy = [&](const Vec<12>& v) { return bending_energy(to_cols(v), rest, curve); };
        auto gradient = [&](const Vec<12>& v) {
            Vec<12> g;
            bending_energy(to_cols(v), rest, curve, &g);
            return g;
        };
        Vec<12> g;
        Mat<12> h;
        bending_energy(to_cols(xv), rest, curve, &g, &h, HessianMode::exact);
        worst_g = std::max(worst_g, relative_error(fd_gradient(energy, xv, 1e-7 * l), g));
        worst_h = std::max(worst_h, relative_error(fd_hessian(gradient, xv, 1e-7 * l), h));
        // The force is ArcSim's: k(κ) l̄²/(4(A0+A1)) θ ∇θ with k = min over the two sides.
        const double k = std::min(bending_stiffness(m, rest.direction_rad[0], kappa),
                                  bending_stiffness(m, rest.direction_rad[1], kappa));
        const double th = dihedral_angle(to_cols(xv));
        const Vec<12> arcsim = k * l * l / (4 * rest.rest_area_sum_m2) * th * dihedral_angle_gradient(to_cols(xv));
        CHECK(relative_error(g, arcsim) < 1e-9);
    }
    INFO("tested " << tested << ", worst relative errors: gradient " << worst_g << ", Hessian " << worst_h);
    CHECK(tested >= 30);
    CHECK(worst_g < 1e-5);
    CHECK(worst_h < 1e-5);
    // A constant curve reproduces the constant-stiffness energy.
    HingeRest rest;
    rest.rest_length_m = 0.01;
    rest.rest_area_sum_m2 = 1e-4;
    Eigen::Matrix<double, 3, 4> x;
    x << 0, 0.01, 0.005, 0.004, 0, 0, 0.007, -0.006, 0, 0, 0, -0.003;
    CHECK(bending_energy(x, rest, constant_bending_curve(3e-5)) == Approx(bending_energy(x, rest, 3e-5)));
}
