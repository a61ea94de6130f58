// Private: cloth self-contact. Proximity pairs (vertex–triangle, edge–edge) found with a
// uniform grid, exact unsigned distances per closest-feature regime, a penalty
// energy with exact or PSD-projected derivatives, and a conservative step bound for the
// line search. See docs/self-contact.md for the formulas and the guarantees.
#pragma once

#include <drape/cloth/energies.hpp>

#include <Eigen/Core>

#include <array>
#include <string>
#include <utility>
#include <vector>

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
/// Per-vertex lengths of the displacements `d` (#V x 3) less one common translation T: T = 0
/// or the mean of d, whichever gives the smaller maximum. A common translation brings no two
/// points closer, so |d_a − T| + |d_b − T| bounds how much closer points a and b came.
std::vector<double> translation_reduced_lengths(const Eigen::MatrixX3d& d);

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

/// Penalty parameters.
struct SelfContactParams {
    double thickness_m = 0.005;          ///< h: pairs closer than h repel
    double stiffness_n_per_m = 1000.0;   ///< k in ψ(d) = ½ k (h − d)² for d < h
    bool is_valid(std::string* why) const;
};

/// Penalty energy of one pair, ψ(d) = ½ k (h − d)² for d < h, 0 otherwise (joules).
/// \param gradient 12 (columns of x, xyz each); \param hessian 12 x 12 (HessianMode:
/// exact, projected_psd, or gauss_newton = k ∇d ∇dᵀ). Zero derivatives when d >= h.
/// \pre d > 0 (the penalty is not differentiable through d = 0; the step bound keeps pairs
/// apart).
double pair_energy(ContactPair::Kind kind, const Eigen::Matrix<double, 3, 4>& x,
                   const SelfContactParams& params, Vector12d* gradient = nullptr,
                   Matrix12d* hessian = nullptr,
                   HessianMode mode = HessianMode::projected_psd);

/// One pair's Hessian block for assembly: rows/cols 3 v[c] + i ↔ 3 c + i.
struct PairHessian {
    ContactPair pair;
    Matrix12d hessian;
};

/// The frame of a pair in contact, for lagged friction: relative displacement of the two
/// closest points = Σ_c weights_c Δx_{v[c]}; unit normal from the second primitive's closest
/// point to the first's; distance d.
struct PairFrame {
    ContactPair pair;
    Eigen::Vector4d weights = Eigen::Vector4d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    double distance_m = 0;
};

/// Self-contact of one cloth mesh. Topology (edges, exclusions) is fixed at construction;
/// positions are arguments. Not thread-safe for concurrent find_candidates calls.
class SelfContact {
public:
    /// \param faces #F x 3; \param vertex_count #V; \param excluded vertex pairs (i, j) to be
    /// treated as one vertex for adjacency (stitched seam partners): a vertex is never paired
    /// with a triangle that has it or a partner as a corner, nor an edge with an edge that
    /// shares a vertex or a partner. \throw drape::InvalidInput on out-of-range indices.
    SelfContact(const Eigen::MatrixX3i& faces, int vertex_count,
                const std::vector<std::pair<int, int>>& excluded = {});

    /// Collects every admissible pair at distance < radius at positions p (#V x 3), in a
    /// deterministic order: vertex–triangle pairs by (vertex, triangle), then edge–edge
    /// pairs by (edge, edge) in edges() order. Contract: call with
    /// radius >= h + (the largest distance a pair can close in the coming step), so that the
    /// energy and max_safe_step see every pair that can come within h.
    /// \throw drape::InvalidInput if p has the wrong row count or radius <= 0 / not finite.
    void find_candidates(const Eigen::MatrixX3d& p, double radius);

    const std::vector<ContactPair>& candidates() const { return candidates_; }
    /// The distance below which every admissible pair at positions q is a candidate:
    /// candidate_radius() − 2 max_v |q_v − p_v − T| (p: the last find_candidates positions;
    /// T: no translation or the mean displacement, whichever gives the smaller maximum),
    /// at least 0; 0 before the first call or on a row-count mismatch. The candidates may be
    /// reused at q while this is at least the radius the caller needs.
    double covered_radius(const Eigen::MatrixX3d& q) const;
    /// The candidates within `thickness_m` at q (0 < d < h), with their frames, in
    /// candidate order.
    std::vector<PairFrame> contact_frames(const Eigen::MatrixX3d& q, double thickness_m) const;
    const std::vector<std::array<int, 2>>& edges() const { return edges_; }
    /// The radius of the last find_candidates call (0 before the first).
    double candidate_radius() const { return radius_; }

    /// Sum of pair_energy over the candidates at positions q (#V x 3).
    /// \param gradient if not null, 3V (vertex-major xyz), the gradient is added into it.
    /// \param hessians if not null, one block per pair with d < h is appended (reuse the
    /// vector across calls, after clear(), to keep its capacity).
    /// \param mode of the blocks: gauss_newton (default) k ∇d∇dᵀ is PSD and ~100x cheaper
    /// than projected_psd (an eigen-decomposition per pair); see docs/self-contact.md.
    double energy(const Eigen::MatrixX3d& q, const SelfContactParams& params,
                  Eigen::VectorXd* gradient, std::vector<PairHessian>* hessians,
                  HessianMode mode = HessianMode::gauss_newton) const;

    /// Largest α in (0, 1] (conservative) such that along p + α' dx, α' ∈ [0, α], every
    /// candidate pair with initial distance d0 > 0 keeps a distance >= its floor
    /// F = s + (1 − fraction)(d0 − s) if d0 > s, else (1 − fraction) d0, where
    /// s = min_separation_m; and every non-candidate pair (distance >= covered_radius(p)
    /// at p) keeps a distance >= s. Pairs with d0 = 0 cannot be certified and are skipped.
    /// Returns 0 if dx moves the cloth non-rigidly and covered_radius(p) <= s (nothing can
    /// be certified; also before the first find_candidates), and 1 for a rigid translation.
    /// \param fraction in (0, 1]. \throw drape::InvalidInput on shape or range errors.
    double max_safe_step(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& dx,
                         double fraction = 0.9, double min_separation_m = 0.0) const;

    /// Ignores pairs that are close in the rest shape: both primitives on the same pattern
    /// piece and closer than `min_distance_m` in pattern coordinates (vertex to triangle,
    /// or edge to edge). Such pairs are neighbours within one layer, not two layers, and a
    /// repulsion between them would fight the elastic forces of a fine mesh.
    /// \param vertex_pattern #V x 2 pattern coordinates (m); \param piece #V piece ids.
    /// 	hrow drape::InvalidInput on a size mismatch or a negative distance.
    void set_rest_filter(const Eigen::MatrixX2d& vertex_pattern, const std::vector<int>& piece,
                         double min_distance_m);
    /// The same for a mesh whose vertices may have several pattern points (a welded seam
    /// joins panels: its vertices have one point per panel): a vertex and a face (or two
    /// edges) are near at rest if some pattern point of the vertex and the face's pattern
    /// corners lie on one piece within `min_distance_m`. Pairs are never compared across
    /// pieces (one panel's layout says nothing about where another's lies).
    /// \param pattern P x 2 points (m); \param point_vertex the vertex of each point;
    /// \param pattern_faces #F x 3, face f's corners as points (point_vertex of corner c is
    /// faces(f, c)); \param point_piece P piece ids.
    /// \throw drape::InvalidInput on sizes, indices out of range or corners not of their vertex.
    void set_rest_filter(const Eigen::MatrixX2d& pattern, const std::vector<int>& point_vertex,
                         const Eigen::MatrixX3i& pattern_faces, const std::vector<int>& point_piece,
                         double min_distance_m);

private:
    bool excluded(int a, int b) const;
    // Whether (vertex v, face f) / (edge e, edge o > e) is in the rest filter's lists.
    bool rest_near_vertex_triangle(int v, int f) const;
    bool rest_near_edges(int e, int o) const;

    Eigen::MatrixX3i faces_;
    int vertex_count_ = 0;
    std::vector<std::array<int, 2>> edges_;
    std::vector<std::vector<int>> partners_;  // per vertex, sorted
    // The rest filter's pairs, fixed with the pattern: per vertex the faces, per edge the
    // edges of higher index that are rest-near (compressed rows, sorted within a row).
    std::vector<int> rest_face_start_, rest_faces_, rest_edge_start_, rest_edges_;
    // Per-vertex bound of how far each vertex has moved from reference_ at q, up to one
    // common translation of the whole cloth (which moves no pair closer).
    std::vector<double> vertex_offsets(const Eigen::MatrixX3d& q) const;

    std::vector<ContactPair> candidates_;
    std::vector<double> reference_distance_;  // per candidate, its distance at reference_
    double radius_ = 0;
    Eigen::MatrixX3d reference_;              // positions of the last find_candidates call
};

}  // namespace drape::cloth::internal
