// Private: cloth self-contact. Proximity pairs (vertex–triangle, edge–edge) found with the
// core BVH (contact_broad_phase.cpp), exact unsigned distances per closest-feature regime
// (contact_distance.hpp), a penalty energy with exact or PSD-projected derivatives
// (contact_barrier.hpp), and a conservative step bound for the line search (this class).
// See docs/self-contact.md for the formulas and the guarantees.
#pragma once

#include <drape/cloth/energies.hpp>

#include "contact_barrier.hpp"
#include "contact_distance.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace drape::cloth::internal {

/// Per-vertex lengths of the displacements `d` (#V x 3) less one common translation T: T = 0
/// or the mean of d, whichever gives the smaller maximum. A common translation brings no two
/// points closer, so |d_a − T| + |d_b − T| bounds how much closer points a and b came.
std::vector<double> translation_reduced_lengths(const Eigen::MatrixX3d& d);

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
    /// \param limiting if not null, receives (in candidate order) the candidates whose own
    /// safe step is below `limit_alpha`: the pairs that hold the step back.
    double max_safe_step(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& dx,
                         double fraction = 0.9, double min_separation_m = 0.0,
                         std::vector<int>* limiting = nullptr, double limit_alpha = 0.0) const;

    /// Removes from dx, for each candidate in `pairs`, the part that closes the pair's gap
    /// to first order, by the least-norm change: with the closest-point weights w and unit
    /// normal n at p, Δx_c = −λ w_c n with λ = n · Σ_c w_c dx_c / Σ_c w_c², applied only
    /// where the pair closes (λ < 0). A common motion of the pair is kept, so two layers
    /// pressed together can still move with whatever presses them. Vertices with
    /// movable[v] == 0 keep their dx (their weights count as 0). `sweeps` Gauss–Seidel passes
    /// over the pairs, which share vertices. Returns how many pair corrections were applied.
    /// \throw drape::InvalidInput on shape errors or an index out of range.
    int remove_closing_motion(const Eigen::MatrixX3d& p, Eigen::MatrixX3d& dx, const std::vector<int>& pairs,
                              const std::vector<char>& movable, int sweeps = 3) const;

    /// Makes the candidates in `pairs` move as one: pairs that share a vertex form a group, and
    /// every movable vertex of a group takes the group's mean dx (or, if the group has a vertex
    /// that is not movable, that vertex's dx), so the distances within each group stay as they
    /// are along the step. For pressed pairs that still hold the step after
    /// remove_closing_motion: layers sliding fast over each other at a tiny gap, which the
    /// conservative bound cannot certify far. Returns how many vertices were changed.
    /// \throw drape::InvalidInput on shape errors or an index out of range.
    int move_pairs_together(Eigen::MatrixX3d& dx, const std::vector<int>& pairs, const std::vector<char>& movable) const;

    /// Ignores pairs that are close in the rest shape: both primitives on the same pattern
    /// piece and closer than `min_distance_m` in pattern coordinates (vertex to triangle,
    /// or edge to edge). Such pairs are neighbours within one layer, not two layers, and a
    /// repulsion between them would fight the elastic forces of a fine mesh.
    /// \param vertex_pattern #V x 2 pattern coordinates (m); \param piece #V piece ids.
    /// \throw drape::InvalidInput on a size mismatch or a negative distance.
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
