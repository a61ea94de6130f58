// Private to the self-contact sources: fixed work chunks and per-pair helpers shared by the
// broad phase, the energy and the step bound.
#pragma once

#include "self_contact.hpp"

#include <drape/core/parallel_for.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <vector>

namespace drape::cloth::internal {

using Mat34 = Eigen::Matrix<double, 3, 4>;

// Work is split into fixed chunks so that per-chunk results concatenate in a fixed order
// whatever the thread schedule (deterministic output).
constexpr int kChunk = 256;

inline int chunk_count(int n) { return core::chunk_count(n, kChunk); }

template <class F>
void for_each_chunk(int n, F&& f) {
    core::parallel_for_chunks(n, kChunk, f);
}

// Local column sets of the two primitives of a pair.
inline int first_primitive_size(ContactPair::Kind kind) {
    return kind == ContactPair::Kind::vertex_triangle ? 1 : 2;
}

inline Mat34 gather(const Eigen::MatrixX3d& q, const ContactPair& pair) {
    Mat34 x;
    for (int c = 0; c < 4; ++c) x.col(c) = q.row(pair.v[c]).transpose();
    return x;
}

// A lower bound of a pair's distance: the gap between the bounding boxes of its two
// primitives (columns [0, na) and [na, 4) of x). Cheap, to skip exact distances of far pairs.
inline double box_gap_squared(ContactPair::Kind kind, const Mat34& x) {
    const int na = first_primitive_size(kind);
    const Eigen::Vector3d amin = x.middleCols(0, na).rowwise().minCoeff();
    const Eigen::Vector3d amax = x.middleCols(0, na).rowwise().maxCoeff();
    const Eigen::Vector3d bmin = x.middleCols(na, 4 - na).rowwise().minCoeff();
    const Eigen::Vector3d bmax = x.middleCols(na, 4 - na).rowwise().maxCoeff();
    const Eigen::Vector3d gap = (amin - bmax).cwiseMax(bmin - amax).cwiseMax(0.0);
    return gap.squaredNorm();
}

// The largest offset of a pair's two primitives (columns [0, na) and [na, 4)) summed: a
// bound of how much closer the pair can have come since the offsets' reference.
inline double pair_offset(const ContactPair& pair, const std::vector<double>& offset) {
    const int na = first_primitive_size(pair.kind);
    double a = 0, b = 0;
    for (int k = 0; k < 4; ++k) {
        double& bound = k < na ? a : b;
        bound = std::max(bound, offset[static_cast<std::size_t>(pair.v[static_cast<std::size_t>(k)])]);
    }
    return a + b;
}

}  // namespace drape::cloth::internal
