// Test fixture: a square grid folded onto itself (a hairpin), for self-contact and
// intersection tests. Two flat layers `gap` apart joined by a half-cylinder of radius gap/2.
#pragma once

#include <drape/cloth/cloth_mesh.hpp>

#include <Eigen/Core>

#include <cmath>
#include <random>

namespace drape::cloth::test {

/// The (n+1)² grid of make_square_grid over [0, size]² in the z = 0 plane, folded about
/// the line x = fold_at_m: points with x <= fold_at_m stay; the rest wrap around a
/// half-cylinder (axis along y) and come back at z = gap_m above the bottom layer.
inline ClothMesh folded_sheet(int n, double size_m, double gap_m, double fold_at_m) {
    ClothMesh mesh = make_square_grid(n, size_m, Eigen::Vector3d::Zero(),
                                      Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
    const double radius = 0.5 * gap_m, arc = 3.14159265358979323846 * radius;
    for (int i = 0; i < mesh.positions.rows(); ++i) {
        const double u = mesh.positions(i, 0);
        if (u <= fold_at_m) continue;
        if (u < fold_at_m + arc) {
            const double theta = (u - fold_at_m) / radius;
            mesh.positions(i, 0) = fold_at_m + radius * std::sin(theta);
            mesh.positions(i, 2) = radius * (1 - std::cos(theta));
        } else {
            mesh.positions(i, 0) = fold_at_m - (u - fold_at_m - arc);
            mesh.positions(i, 2) = gap_m;
        }
    }
    return mesh;
}

/// Adds independent uniform noise in [-amplitude, amplitude] to every coordinate.
inline void jitter(Eigen::MatrixX3d& positions, double amplitude_m, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int i = 0; i < positions.rows(); ++i)
        for (int c = 0; c < 3; ++c) positions(i, c) += amplitude_m * unit(rng);
}

}  // namespace drape::cloth::test
