// The broad phase of self-contact: candidate pairs from the core BVH over inflated
// primitive boxes, and the rest filter (pairs near in the pattern) found the same way.
#include "self_contact.hpp"
#include "self_contact_internal.hpp"

#include <drape/core/bvh.hpp>
#include <drape/core/errors.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace drape::cloth::internal {

namespace {

Eigen::AlignedBox3d box_of(const Eigen::MatrixX3d& p, const int* v, int n, double inflate) {
    Eigen::AlignedBox3d b;
    for (int k = 0; k < n; ++k) b.extend(p.row(v[k]).transpose());
    if (inflate > 0) {
        b.min().array() -= inflate;
        b.max().array() += inflate;
    }
    return b;
}

// For each query item i in [0, n): the stored boxes overlapping query_box(i), in increasing
// id order, passed to test(i, id, out); the outputs are concatenated in item order.
template <class Item, class QueryBox, class Test>
std::vector<Item> overlap_pairs(int n, const core::Bvh& index, QueryBox&& query_box, Test&& test) {
    std::vector<std::vector<Item>> parts(static_cast<std::size_t>(chunk_count(n)));
    for_each_chunk(n, [&](int c, int begin, int end) {
        std::vector<int> hits;
        for (int i = begin; i < end; ++i) {
            hits.clear();
            const Eigen::AlignedBox3d box = query_box(i);
            index.traverse([&](const Eigen::AlignedBox3d& b) { return b.intersects(box); },
                           [&](int id) { hits.push_back(id); });
            std::sort(hits.begin(), hits.end());
            for (int id : hits) test(i, id, parts[static_cast<std::size_t>(c)]);
        }
    });
    std::vector<Item> all;
    for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
}

// A pair found by find_candidates with its distance then.
struct FoundPair {
    ContactPair pair;
    double distance = 0;
};

}  // namespace

void SelfContact::set_rest_filter(const Eigen::MatrixX2d& vertex_pattern,
                                  const std::vector<int>& piece, double min_distance_m) {
    require(vertex_pattern.rows() == vertex_count_ && static_cast<int>(piece.size()) == vertex_count_,
            "SelfContact::set_rest_filter: expected ", vertex_count_, " vertices, got ",
            vertex_pattern.rows(), " pattern rows and ", piece.size(), " piece ids");
    std::vector<int> identity(static_cast<std::size_t>(vertex_count_));
    for (int v = 0; v < vertex_count_; ++v) identity[static_cast<std::size_t>(v)] = v;
    set_rest_filter(vertex_pattern, identity, faces_, piece, min_distance_m);
}

void SelfContact::set_rest_filter(const Eigen::MatrixX2d& pattern, const std::vector<int>& point_vertex,
                                  const Eigen::MatrixX3i& pattern_faces, const std::vector<int>& point_piece,
                                  double min_distance_m) {
    const int np = static_cast<int>(pattern.rows()), nf = static_cast<int>(faces_.rows());
    require(static_cast<int>(point_vertex.size()) == np && static_cast<int>(point_piece.size()) == np,
            "SelfContact::set_rest_filter: ", np, " pattern points, ", point_vertex.size(), " point vertices and ",
            point_piece.size(), " piece ids (need one each)");
    require(pattern_faces.rows() == nf, "SelfContact::set_rest_filter: ", pattern_faces.rows(),
            " pattern faces for ", nf, " faces");
    require(std::isfinite(min_distance_m) && min_distance_m >= 0,
            "SelfContact::set_rest_filter: min_distance_m = ", min_distance_m, " must be >= 0");
    require(pattern.allFinite(), "SelfContact::set_rest_filter: pattern coordinates are not finite");
    for (int i = 0; i < np; ++i)
        require(point_vertex[static_cast<std::size_t>(i)] >= 0 && point_vertex[static_cast<std::size_t>(i)] < vertex_count_,
                "SelfContact::set_rest_filter: pattern point ", i, " belongs to vertex ",
                point_vertex[static_cast<std::size_t>(i)], ", out of range [0, ", vertex_count_, ")");
    for (int f = 0; f < nf; ++f)
        for (int c = 0; c < 3; ++c) {
            const int q = pattern_faces(f, c);
            require(q >= 0 && q < np && point_vertex[static_cast<std::size_t>(q)] == faces_(f, c),
                    "SelfContact::set_rest_filter: corner ", c, " of face ", f, " is pattern point ", q,
                    ", which is not a point of its vertex ", faces_(f, c));
        }
    rest_face_start_.clear();
    rest_faces_.clear();
    rest_edge_start_.clear();
    rest_edges_.clear();
    if (min_distance_m <= 0 || vertex_count_ == 0) return;
    // The pairs are found once here (the pattern does not change), so that find_candidates
    // looks them up instead of measuring pattern distances for every pair it meets. A vertex
    // may have several pattern points (a welded seam: one per panel it joins); a face's rest
    // triangle is its pattern corners, so a pair is tested in the pattern of each panel the
    // two share, never across panels.
    Eigen::MatrixX3d rest = Eigen::MatrixX3d::Zero(np, 3);
    rest.leftCols<2>() = pattern;
    const double r2 = min_distance_m * min_distance_m;
    auto same_piece = [&](std::initializer_list<int> points) {
        const int first = point_piece[static_cast<std::size_t>(*points.begin())];
        for (int q : points)
            if (point_piece[static_cast<std::size_t>(q)] != first) return false;
        return true;
    };
    // The pattern's edges, each with its mesh edge (index into edges_).
    std::vector<std::array<int, 3>> pattern_edges;  // point a < point b, mesh edge
    for (int f = 0; f < nf; ++f)
        for (int c = 0; c < 3; ++c) {
            const int qa = pattern_faces(f, c), qb = pattern_faces(f, (c + 1) % 3);
            const std::array<int, 2> me = {std::min(faces_(f, c), faces_(f, (c + 1) % 3)),
                                           std::max(faces_(f, c), faces_(f, (c + 1) % 3))};
            const int e = static_cast<int>(std::lower_bound(edges_.begin(), edges_.end(), me) - edges_.begin());
            pattern_edges.push_back({std::min(qa, qb), std::max(qa, qb), e});
        }
    std::sort(pattern_edges.begin(), pattern_edges.end());
    pattern_edges.erase(std::unique(pattern_edges.begin(), pattern_edges.end()), pattern_edges.end());
    const int npe = static_cast<int>(pattern_edges.size());
    // Rows of (row, item) pairs, sorted and without repeats (a vertex with two pattern points
    // may find a face twice).
    auto to_rows = [](std::vector<std::array<int, 2>> found, int rows, std::vector<int>& start,
                      std::vector<int>& items) {
        std::sort(found.begin(), found.end());
        found.erase(std::unique(found.begin(), found.end()), found.end());
        start.assign(static_cast<std::size_t>(rows) + 1, 0);
        for (const auto& f : found) ++start[static_cast<std::size_t>(f[0]) + 1];
        for (int r = 0; r < rows; ++r) start[static_cast<std::size_t>(r) + 1] += start[static_cast<std::size_t>(r)];
        items.resize(found.size());
        for (std::size_t k = 0; k < found.size(); ++k) items[k] = found[k][1];
    };

    std::vector<Eigen::AlignedBox3d> tri_boxes(static_cast<std::size_t>(nf));
    for (int f = 0; f < nf; ++f) {
        const int q[3] = {pattern_faces(f, 0), pattern_faces(f, 1), pattern_faces(f, 2)};
        tri_boxes[static_cast<std::size_t>(f)] = box_of(rest, q, 3, min_distance_m);
    }
    const std::vector<std::array<int, 2>> vt = overlap_pairs<std::array<int, 2>>(
        np, core::Bvh(std::move(tri_boxes)),
        [&](int q) { return Eigen::AlignedBox3d(rest.row(q).transpose(), rest.row(q).transpose()); },
        [&](int q, int f, std::vector<std::array<int, 2>>& out) {
            const int t0 = pattern_faces(f, 0), t1 = pattern_faces(f, 1), t2 = pattern_faces(f, 2);
            if (!same_piece({q, t0, t1, t2})) return;
            if (point_triangle_distance_squared(rest.row(q), rest.row(t0), rest.row(t1), rest.row(t2)) < r2)
                out.push_back({point_vertex[static_cast<std::size_t>(q)], f});
        });
    to_rows(vt, vertex_count_, rest_face_start_, rest_faces_);

    std::vector<Eigen::AlignedBox3d> edge_boxes(static_cast<std::size_t>(npe));
    for (int e = 0; e < npe; ++e)
        edge_boxes[static_cast<std::size_t>(e)] = box_of(rest, pattern_edges[static_cast<std::size_t>(e)].data(), 2, min_distance_m);
    const std::vector<std::array<int, 2>> ee = overlap_pairs<std::array<int, 2>>(
        npe, core::Bvh(std::move(edge_boxes)),
        [&](int e) { return box_of(rest, pattern_edges[static_cast<std::size_t>(e)].data(), 2, 0.0); },
        [&](int e, int o, std::vector<std::array<int, 2>>& out) {
            const auto& a = pattern_edges[static_cast<std::size_t>(e)];
            const auto& b = pattern_edges[static_cast<std::size_t>(o)];
            if (a[2] == b[2] || !same_piece({a[0], a[1], b[0], b[1]})) return;
            if (segment_segment_distance_squared(rest.row(a[0]), rest.row(a[1]), rest.row(b[0]), rest.row(b[1])) < r2)
                out.push_back({std::min(a[2], b[2]), std::max(a[2], b[2])});
        });
    to_rows(ee, static_cast<int>(edges_.size()), rest_edge_start_, rest_edges_);
}

bool SelfContact::rest_near_vertex_triangle(int v, int f) const {
    if (rest_face_start_.empty()) return false;
    const auto begin = rest_faces_.begin() + rest_face_start_[static_cast<std::size_t>(v)];
    const auto end = rest_faces_.begin() + rest_face_start_[static_cast<std::size_t>(v) + 1];
    return std::binary_search(begin, end, f);
}

bool SelfContact::rest_near_edges(int e, int o) const {
    if (rest_edge_start_.empty()) return false;
    const auto begin = rest_edges_.begin() + rest_edge_start_[static_cast<std::size_t>(e)];
    const auto end = rest_edges_.begin() + rest_edge_start_[static_cast<std::size_t>(e) + 1];
    return std::binary_search(begin, end, o);
}

void SelfContact::find_candidates(const Eigen::MatrixX3d& p, double radius) {
    require(p.rows() == vertex_count_, "SelfContact::find_candidates: positions have ",
            p.rows(), " rows, expected ", vertex_count_);
    require(radius > 0 && std::isfinite(radius),
            "SelfContact::find_candidates: radius must be positive and finite, got ", radius);
    require(p.allFinite(), "SelfContact::find_candidates: positions are not finite");
    radius_ = radius;
    reference_ = p;
    candidates_.clear();
    reference_distance_.clear();
    const int nf = static_cast<int>(faces_.rows()), ne = static_cast<int>(edges_.size());
    if (nf == 0 || vertex_count_ == 0) return;

    const double r2 = radius * radius;

    // Vertex–triangle: triangles inflated by the radius, queried at each vertex.
    std::vector<Eigen::AlignedBox3d> tri_boxes(nf);
    for (int f = 0; f < nf; ++f) {
        const int v[3] = {faces_(f, 0), faces_(f, 1), faces_(f, 2)};
        tri_boxes[f] = box_of(p, v, 3, radius);
    }
    const core::Bvh tri_index(std::move(tri_boxes));

    const std::vector<FoundPair> vt = overlap_pairs<FoundPair>(
        vertex_count_, tri_index,
        [&](int v) { return Eigen::AlignedBox3d(p.row(v).transpose(), p.row(v).transpose()); },
        [&](int v, int f, std::vector<FoundPair>& out) {
            const int t0 = faces_(f, 0), t1 = faces_(f, 1), t2 = faces_(f, 2);
            if (excluded(v, t0) || excluded(v, t1) || excluded(v, t2)) return;
            if (rest_near_vertex_triangle(v, f)) return;
            const double d2 = point_triangle_distance_squared(p.row(v), p.row(t0), p.row(t1), p.row(t2));
            if (d2 < r2) out.push_back({{ContactPair::Kind::vertex_triangle, {v, t0, t1, t2}}, std::sqrt(d2)});
        });

    // Edge–edge: edges inflated by the radius, queried with each edge's own box.
    std::vector<Eigen::AlignedBox3d> edge_boxes(ne);
    for (int e = 0; e < ne; ++e) edge_boxes[e] = box_of(p, edges_[e].data(), 2, radius);
    const core::Bvh edge_index(std::move(edge_boxes));

    const std::vector<FoundPair> ee = overlap_pairs<FoundPair>(
        ne, edge_index, [&](int e) { return box_of(p, edges_[e].data(), 2, 0.0); },
        [&](int e, int o, std::vector<FoundPair>& out) {
            if (o <= e) return;
            const int a0 = edges_[e][0], a1 = edges_[e][1], b0 = edges_[o][0], b1 = edges_[o][1];
            if (excluded(a0, b0) || excluded(a0, b1) || excluded(a1, b0) || excluded(a1, b1))
                return;
            if (rest_near_edges(e, o)) return;
            const double d2 = segment_segment_distance_squared(p.row(a0), p.row(a1), p.row(b0), p.row(b1));
            if (d2 < r2) out.push_back({{ContactPair::Kind::edge_edge, {a0, a1, b0, b1}}, std::sqrt(d2)});
        });

    candidates_.reserve(vt.size() + ee.size());
    reference_distance_.reserve(vt.size() + ee.size());
    for (const auto* found : {&vt, &ee})
        for (const FoundPair& f : *found) {
            candidates_.push_back(f.pair);
            reference_distance_.push_back(f.distance);
        }
}

}  // namespace drape::cloth::internal
