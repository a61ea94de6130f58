// Private: exact unsigned distances between the primitives of cloth self-contact
// (vertex–triangle, edge–edge), per closest-feature regime, with the regime's derivatives.
// See docs/self-contact.md for the formulas.
#pragma once

#include <drape/cloth/energies.hpp>

#include <Eigen/Core>

#include <array>

namespace drape::cloth::internal {

/// A pair of primitives that may touch. vertex_triangle: v = {p, t0, t1, t2} with p not a
/// corner of the triangle; edge_edge: v = {a0, a1, b0, b1} with no shared vertex.
struct ContactPair {
    enum class Kind { vertex_triangle, edge_edge };
    Kind kind = Kind::vertex_triangle;
    std::array<int, 4> v{};
};

/// Which closest-feature formula gives the squared distance of a pair. Indices are local
/// (0..3, the columns of the pair's 3 x 4 coordinates).
struct DistanceRegime {
    enum class Type {
        point_point,  ///< |x_i − x_j|²                                       (i = idx[0], j = idx[1])
        point_edge,   ///< |(x_i − x_j) × (x_k − x_j)|² / |x_k − x_j|²          (i; edge j–k)
        point_plane,  ///< ((x_0 − x_1)·n)² / |n|², n = (x_2 − x_1) × (x_3 − x_1)
        edge_edge,    ///< ((x_2 − x_0)·c)² / |c|², c = (x_1 − x_0) × (x_3 − x_2)
    };
    Type type = Type::point_point;
    std::array<int, 3> idx{};
};

/// Closest points and squared distance between point p and triangle (t0, t1, t2), handling
/// degenerate (zero-area) triangles. Unsigned. \param regime if not null, receives the
/// regime in the local numbering {p, t0, t1, t2} = {0, 1, 2, 3}.
double point_triangle_distance_squared(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                       const Eigen::Vector3d& t1, const Eigen::Vector3d& t2,
                                       DistanceRegime* regime = nullptr);

/// Squared distance between segments a0–a1 and b0–b1, robust to parallel and zero-length
/// segments. \param regime local numbering {a0, a1, b0, b1} = {0, 1, 2, 3}.
double segment_segment_distance_squared(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                        DistanceRegime* regime = nullptr);

/// Squared distance of a pair with coordinates x (3 x 4, columns in ContactPair::v order).
double pair_distance_squared(ContactPair::Kind kind, const Eigen::Matrix<double, 3, 4>& x,
                             DistanceRegime* regime = nullptr);

/// The squared distance by a fixed regime's formula, with its gradient (12) and Hessian
/// (12 x 12) with respect to x. Smooth within the regime; equals the true squared distance
/// when the regime is the one the classifier returns.
double regime_distance_squared(const DistanceRegime& regime,
                               const Eigen::Matrix<double, 3, 4>& x, Vector12d* gradient,
                               Matrix12d* hessian);

/// Weights w of the closest points in a regime: r = Σ_c w_c x_c is the vector between the
/// two closest points (one primitive's weights >= 0 summing to 1, the other's <= 0 summing
/// to −1), so that ∇d = w ⊗ r/|r| (envelope theorem).
Eigen::Vector4d regime_weights(const DistanceRegime& regime,
                               const Eigen::Matrix<double, 3, 4>& x);

}  // namespace drape::cloth::internal
