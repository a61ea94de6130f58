#include "self_contact.hpp"

#include <drape/core/errors.hpp>

#include "psd_projection.hpp"
#include "second_order.hpp"

#include <drape/core/bvh.hpp>
#include <drape/core/parallel_for.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace drape::cloth::internal {

namespace {

using Mat34 = Eigen::Matrix<double, 3, 4>;
using S12 = Second<12>;
using V12 = Vec3<12>;

// Work is split into fixed chunks so that per-chunk results concatenate in a fixed order
// whatever the thread schedule (deterministic output).
constexpr int kChunk = 256;

int chunk_count(int n) { return core::chunk_count(n, kChunk); }

template <class F>
void for_each_chunk(int n, F&& f) {
    core::parallel_for_chunks(n, kChunk, f);
}

DistanceRegime make_regime(DistanceRegime::Type type, int i, int j, int k = 0) {
    DistanceRegime r;
    r.type = type;
    r.idx = {i, j, k};
    return r;
}

// Squared distance from p to segment a–b; ip, ia, ib are the local numbers for the regime.
double point_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b, int ip, int ia, int ib, DistanceRegime* regime) {
    const Eigen::Vector3d e = b - a;
    const double ee = e.squaredNorm();
    const double t = ee > 0 ? (p - a).dot(e) / ee : 0.0;
    if (t <= 0) {
        if (regime) *regime = make_regime(DistanceRegime::Type::point_point, ip, ia);
        return (p - a).squaredNorm();
    }
    if (t >= 1) {
        if (regime) *regime = make_regime(DistanceRegime::Type::point_point, ip, ib);
        return (p - b).squaredNorm();
    }
    if (regime) *regime = make_regime(DistanceRegime::Type::point_edge, ip, ia, ib);
    return (p - a - t * e).squaredNorm();
}

// Keeps the smaller of two (distance², regime) candidates; ties keep the first.
struct Closest {
    double d2 = std::numeric_limits<double>::infinity();
    DistanceRegime regime;
    void offer(double candidate, const DistanceRegime& r) {
        if (candidate < d2) {
            d2 = candidate;
            regime = r;
        }
    }
};

// Below this sin²(angle) two edges are treated as parallel, and a triangle whose
// |n|² < eps |e1|²|e2|² as degenerate: the interior formulas would divide by ~0, and the
// boundary minimum differs from the true one by O(sqrt(eps)) times the edge length.
constexpr double kParallelEps = 1e-14;

S12 quotient(const S12& a, const S12& b) {
    S12 r;
    r.v = a.v / b.v;
    r.g = (a.g - r.v * b.g) / b.v;
    r.h = (a.h - r.v * b.h - r.g * b.g.transpose() - b.g * r.g.transpose()) / b.v;
    return r;
}

V12 vertex(const Mat34& x, int k) {
    return {{S12::variable(x(0, k), 3 * k), S12::variable(x(1, k), 3 * k + 1),
             S12::variable(x(2, k), 3 * k + 2)}};
}

// Local column sets of the two primitives of a pair.
int first_primitive_size(ContactPair::Kind kind) {
    return kind == ContactPair::Kind::vertex_triangle ? 1 : 2;
}

Mat34 gather(const Eigen::MatrixX3d& q, const ContactPair& pair) {
    Mat34 x;
    for (int c = 0; c < 4; ++c) x.col(c) = q.row(pair.v[c]).transpose();
    return x;
}

// A lower bound of a pair's distance: the gap between the bounding boxes of its two
// primitives (columns [0, na) and [na, 4) of x). Cheap, to skip exact distances of far pairs.
double box_gap_squared(ContactPair::Kind kind, const Mat34& x) {
    const int na = first_primitive_size(kind);
    const Eigen::Vector3d amin = x.middleCols(0, na).rowwise().minCoeff();
    const Eigen::Vector3d amax = x.middleCols(0, na).rowwise().maxCoeff();
    const Eigen::Vector3d bmin = x.middleCols(na, 4 - na).rowwise().minCoeff();
    const Eigen::Vector3d bmax = x.middleCols(na, 4 - na).rowwise().maxCoeff();
    const Eigen::Vector3d gap = (amin - bmax).cwiseMax(bmin - amax).cwiseMax(0.0);
    return gap.squaredNorm();
}

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

// The largest offset of a pair's two primitives (columns [0, na) and [na, 4)) summed: a
// bound of how much closer the pair can have come since the offsets' reference.
double pair_offset(const ContactPair& pair, const std::vector<double>& offset) {
    const int na = first_primitive_size(pair.kind);
    double a = 0, b = 0;
    for (int k = 0; k < 4; ++k) {
        double& bound = k < na ? a : b;
        bound = std::max(bound, offset[static_cast<std::size_t>(pair.v[static_cast<std::size_t>(k)])]);
    }
    return a + b;
}

}  // namespace

double point_triangle_distance_squared(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                       const Eigen::Vector3d& t1, const Eigen::Vector3d& t2,
                                       DistanceRegime* regime) {
    const Eigen::Vector3d e1 = t1 - t0, e2 = t2 - t0, w = p - t0;
    const double d11 = e1.squaredNorm(), d22 = e2.squaredNorm(), d12 = e1.dot(e2);
    const double det = d11 * d22 - d12 * d12;  // = |e1 × e2|²
    if (det > kParallelEps * d11 * d22) {
        const double r1 = w.dot(e1), r2 = w.dot(e2);
        const double u = (d22 * r1 - d12 * r2) / det, v = (d11 * r2 - d12 * r1) / det;
        if (u > 0 && v > 0 && u + v < 1) {
            if (regime) *regime = make_regime(DistanceRegime::Type::point_plane, 0, 1, 2);
            return (w - u * e1 - v * e2).squaredNorm();
        }
    }
    // The squared distance over the triangle is a convex quadratic in (u, v): if its
    // minimiser is not interior, the minimum lies on the boundary, i.e. on an edge.
    Closest best;
    DistanceRegime r;
    best.offer(point_segment(p, t0, t1, 0, 1, 2, &r), r);
    best.offer(point_segment(p, t1, t2, 0, 2, 3, &r), r);
    best.offer(point_segment(p, t2, t0, 0, 3, 1, &r), r);
    if (regime) *regime = best.regime;
    return best.d2;
}

double segment_segment_distance_squared(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                        DistanceRegime* regime) {
    const Eigen::Vector3d ea = a1 - a0, eb = b1 - b0, w = a0 - b0;
    const double A = ea.squaredNorm(), B = ea.dot(eb), C = eb.squaredNorm();
    const double D = ea.dot(w), E = eb.dot(w);
    const double den = A * C - B * B;  // = |ea × eb|²
    if (den > kParallelEps * A * C) {
        const double s = (B * E - C * D) / den, t = (A * E - B * D) / den;
        if (s > 0 && s < 1 && t > 0 && t < 1) {
            if (regime) *regime = make_regime(DistanceRegime::Type::edge_edge, 0, 1, 2);
            return (w + s * ea - t * eb).squaredNorm();
        }
    }
    // Convexity again: otherwise the minimum is attained with an endpoint of one segment.
    Closest best;
    DistanceRegime r;
    best.offer(point_segment(a0, b0, b1, 0, 2, 3, &r), r);
    best.offer(point_segment(a1, b0, b1, 1, 2, 3, &r), r);
    best.offer(point_segment(b0, a0, a1, 2, 0, 1, &r), r);
    best.offer(point_segment(b1, a0, a1, 3, 0, 1, &r), r);
    if (regime) *regime = best.regime;
    return best.d2;
}

double pair_distance_squared(ContactPair::Kind kind, const Mat34& x, DistanceRegime* regime) {
    if (kind == ContactPair::Kind::vertex_triangle)
        return point_triangle_distance_squared(x.col(0), x.col(1), x.col(2), x.col(3), regime);
    return segment_segment_distance_squared(x.col(0), x.col(1), x.col(2), x.col(3), regime);
}

double regime_distance_squared(const DistanceRegime& regime, const Mat34& x,
                               Vector12d* gradient, Matrix12d* hessian) {
    const V12 X[4] = {vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3)};
    const auto& i = regime.idx;
    S12 s;
    switch (regime.type) {
        case DistanceRegime::Type::point_point: {
            const V12 d = X[i[0]] - X[i[1]];
            s = dot(d, d);
            break;
        }
        case DistanceRegime::Type::point_edge: {
            const V12 e = X[i[2]] - X[i[1]];
            const V12 c = cross(X[i[0]] - X[i[1]], e);
            s = quotient(dot(c, c), dot(e, e));
            break;
        }
        case DistanceRegime::Type::point_plane: {
            const V12 n = cross(X[2] - X[1], X[3] - X[1]);
            const S12 w = dot(X[0] - X[1], n);
            s = quotient(w * w, dot(n, n));
            break;
        }
        case DistanceRegime::Type::edge_edge: {
            const V12 c = cross(X[1] - X[0], X[3] - X[2]);
            const S12 w = dot(X[2] - X[0], c);
            s = quotient(w * w, dot(c, c));
            break;
        }
    }
    if (gradient) *gradient = s.g;
    if (hessian) *hessian = s.h;
    return s.v;
}

bool SelfContactParams::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!(thickness_m > 0) || !std::isfinite(thickness_m))
        return fail("thickness_m must be positive and finite, got " +
                    std::to_string(thickness_m));
    if (!(stiffness_n_per_m > 0) || !std::isfinite(stiffness_n_per_m))
        return fail("stiffness_n_per_m must be positive and finite, got " +
                    std::to_string(stiffness_n_per_m));
    return true;
}

Eigen::Vector4d regime_weights(const DistanceRegime& regime, const Mat34& x) {
    Eigen::Vector4d w = Eigen::Vector4d::Zero();
    const auto& i = regime.idx;
    switch (regime.type) {
        case DistanceRegime::Type::point_point:
            w(i[0]) = 1;
            w(i[1]) = -1;
            break;
        case DistanceRegime::Type::point_edge: {
            const Eigen::Vector3d e = x.col(i[2]) - x.col(i[1]);
            const double ee = e.squaredNorm();
            const double t = ee > 0 ? (x.col(i[0]) - x.col(i[1])).dot(e) / ee : 0.0;
            w(i[0]) = 1;
            w(i[1]) = -(1 - t);
            w(i[2]) = -t;
            break;
        }
        case DistanceRegime::Type::point_plane: {
            const Eigen::Vector3d e1 = x.col(2) - x.col(1), e2 = x.col(3) - x.col(1);
            const Eigen::Vector3d r = x.col(0) - x.col(1);
            const double d11 = e1.squaredNorm(), d22 = e2.squaredNorm(), d12 = e1.dot(e2);
            const double det = d11 * d22 - d12 * d12;
            const double r1 = r.dot(e1), r2 = r.dot(e2);
            const double u = det > 0 ? (d22 * r1 - d12 * r2) / det : 0.0;
            const double v = det > 0 ? (d11 * r2 - d12 * r1) / det : 0.0;
            w << 1, -(1 - u - v), -u, -v;
            break;
        }
        case DistanceRegime::Type::edge_edge: {
            const Eigen::Vector3d ea = x.col(1) - x.col(0), eb = x.col(3) - x.col(2);
            const Eigen::Vector3d r = x.col(0) - x.col(2);
            const double A = ea.squaredNorm(), B = ea.dot(eb), C = eb.squaredNorm();
            const double D = ea.dot(r), E = eb.dot(r);
            const double den = A * C - B * B;
            const double s = den > 0 ? (B * E - C * D) / den : 0.0;
            const double t = den > 0 ? (A * E - B * D) / den : 0.0;
            w << 1 - s, s, -(1 - t), -t;
            break;
        }
    }
    return w;
}

double pair_energy(ContactPair::Kind kind, const Mat34& x, const SelfContactParams& params,
                   Vector12d* gradient, Matrix12d* hessian, HessianMode mode) {
    if (gradient) gradient->setZero();
    if (hessian) hessian->setZero();
    DistanceRegime regime;
    const double d2 = pair_distance_squared(kind, x, &regime);
    const double h = params.thickness_m, k = params.stiffness_n_per_m;
    const double d = std::sqrt(d2);
    if (!(d < h)) return 0;
    const double energy = 0.5 * k * (h - d) * (h - d);
    if ((!gradient && !hessian) || !(d > 0)) return energy;

    // Envelope theorem: ∇d = n̂ ⊗ w, with w the closest points' weights (r = x w, n̂ = r/|r|).
    const Eigen::Vector4d w = regime_weights(regime, x);
    const Eigen::Vector3d normal = (x * w).normalized();
    Vector12d grad_d;
    for (int c = 0; c < 4; ++c) grad_d.segment<3>(3 * c) = w(c) * normal;
    // ψ' = −k(h − d), ψ'' = k.
    const double dpsi = -k * (h - d);
    if (gradient) *gradient = dpsi * grad_d;
    if (hessian) {
        *hessian = k * grad_d * grad_d.transpose();
        if (mode != HessianMode::gauss_newton) {
            // d = sqrt(s): ∇²d = ∇²s / 2d − ∇s∇sᵀ / 4d³ with ∇s = 2d ∇d.
            Matrix12d hs;
            regime_distance_squared(regime, x, nullptr, &hs);
            *hessian += dpsi * (hs - 2 * grad_d * grad_d.transpose()) / (2 * d);
            if (mode == HessianMode::projected_psd) project_psd<12>(*hessian);
        }
    }
    return energy;
}

SelfContact::SelfContact(const Eigen::MatrixX3i& faces, int vertex_count,
                         const std::vector<std::pair<int, int>>& excluded)
    : faces_(faces), vertex_count_(vertex_count), partners_(std::max(vertex_count, 0)) {
    require(vertex_count >= 0, "SelfContact: vertex_count must be >= 0, got ", vertex_count);
    for (int f = 0; f < faces.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            const int v = faces(f, c);
            require(v >= 0 && v < vertex_count, "SelfContact: faces(", f, ", ", c, ") = ", v,
                    " is out of range [0, ", vertex_count, ")");
        }
        for (int c = 0; c < 3; ++c) {
            const int a = faces(f, c), b = faces(f, (c + 1) % 3);
            edges_.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    std::sort(edges_.begin(), edges_.end());
    edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
    for (std::size_t e = 0; e < excluded.size(); ++e) {
        const auto [a, b] = excluded[e];
        require(a >= 0 && a < vertex_count && b >= 0 && b < vertex_count,
                "SelfContact: excluded pair ", e, " = (", a, ", ", b, ") is out of range [0, ",
                vertex_count, ")");
        partners_[a].push_back(b);
        partners_[b].push_back(a);
    }
    for (auto& list : partners_) {
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
    }
}

bool SelfContact::excluded(int a, int b) const {
    return a == b || std::binary_search(partners_[a].begin(), partners_[a].end(), b);
}

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

std::vector<double> translation_reduced_lengths(const Eigen::MatrixX3d& d) {
    // T = 0 suits cloth resting on a body, T = the mean a falling sheet.
    if (d.rows() == 0) return {};
    const Eigen::RowVector3d mean = d.colwise().mean();
    const Eigen::VectorXd still = d.rowwise().norm();
    const Eigen::VectorXd relative = (d.rowwise() - mean).rowwise().norm();
    const Eigen::VectorXd& best = relative.maxCoeff() < still.maxCoeff() ? relative : still;
    return {best.data(), best.data() + best.size()};
}

std::vector<double> SelfContact::vertex_offsets(const Eigen::MatrixX3d& q) const {
    return translation_reduced_lengths(q - reference_);
}

double SelfContact::energy(const Eigen::MatrixX3d& q, const SelfContactParams& params,
                           Eigen::VectorXd* gradient, std::vector<PairHessian>* hessians,
                           HessianMode mode) const {
    std::string why;
    require(params.is_valid(&why), "SelfContact::energy: ", why);
    require(q.rows() == vertex_count_, "SelfContact::energy: positions have ", q.rows(),
            " rows, expected ", vertex_count_);
    require(!gradient || gradient->size() == 3 * vertex_count_,
            "SelfContact::energy: gradient has size ", gradient ? gradient->size() : 0,
            ", expected ", 3 * vertex_count_);

    // Pass 1: which pairs are within the thickness (distances only). Pass 2 writes each
    // active pair's gradient and block straight into place, so that a caller reusing its
    // `hessians` vector pays no reallocation or page faults.
    const int n = static_cast<int>(candidates_.size());
    const double h2 = params.thickness_m * params.thickness_m;
    // Candidates that were too far to have come within h since find_candidates are skipped
    // without looking at their coordinates (most of them, with a generous radius).
    const std::vector<double> moved = n > 0 ? vertex_offsets(q) : std::vector<double>();
    const double reach = params.thickness_m * (1 + 1e-9);
    std::vector<std::vector<int>> active(chunk_count(n));
    for_each_chunk(n, [&](int c, int begin, int end) {
        for (int i = begin; i < end; ++i) {
            if (reference_distance_[static_cast<std::size_t>(i)] - pair_offset(candidates_[i], moved) >= reach)
                continue;
            const Mat34 x = gather(q, candidates_[i]);
            if (box_gap_squared(candidates_[i].kind, x) < h2 &&
                pair_distance_squared(candidates_[i].kind, x) < h2)
                active[c].push_back(i);
        }
    });
    std::vector<int> order;
    for (const auto& list : active) order.insert(order.end(), list.begin(), list.end());
    const int m = static_cast<int>(order.size());
    const std::size_t offset = hessians ? hessians->size() : 0;
    if (hessians) hessians->resize(offset + m);
    std::vector<Vector12d> gradients(gradient ? m : 0);
    std::vector<double> energies(m);
    core::parallel_for(m, [&](int j) {
        const ContactPair& pair = candidates_[order[j]];
        energies[j] = pair_energy(pair.kind, gather(q, pair), params,
                                  gradient ? &gradients[j] : nullptr,
                                  hessians ? &(*hessians)[offset + j].hessian : nullptr, mode);
        if (hessians) (*hessians)[offset + j].pair = pair;
    }, 1);
    double total = 0;
    for (int j = 0; j < m; ++j) {
        total += energies[j];
        if (gradient)
            for (int k = 0; k < 4; ++k)
                gradient->segment<3>(3 * candidates_[order[j]].v[k]) +=
                    gradients[j].segment<3>(3 * k);
    }
    return total;
}

std::vector<PairFrame> SelfContact::contact_frames(const Eigen::MatrixX3d& q, double thickness_m) const {
    require(q.rows() == vertex_count_, "SelfContact::contact_frames: positions have ", q.rows(),
            " rows, expected ", vertex_count_);
    const double h2 = thickness_m * thickness_m;
    std::vector<PairFrame> frames;
    const std::vector<double> offset = candidates_.empty() ? std::vector<double>() : vertex_offsets(q);
    for (std::size_t i = 0; i < candidates_.size(); ++i) {
        const ContactPair& pair = candidates_[i];
        if (reference_distance_[i] - pair_offset(pair, offset) >= thickness_m * (1 + 1e-9)) continue;
        const Mat34 x = gather(q, pair);
        if (box_gap_squared(pair.kind, x) >= h2) continue;
        DistanceRegime regime;
        const double d2 = pair_distance_squared(pair.kind, x, &regime);
        if (!(d2 < h2 && d2 > 0)) continue;
        PairFrame f;
        f.pair = pair;
        f.weights = regime_weights(regime, x);
        const Eigen::Vector3d r = x * f.weights;
        if (!(r.norm() > 0)) continue;
        f.normal = r.normalized();
        f.distance_m = std::sqrt(d2);
        frames.push_back(f);
    }
    return frames;
}

double SelfContact::covered_radius(const Eigen::MatrixX3d& q) const {
    if (radius_ <= 0 || q.rows() != reference_.rows()) return 0.0;
    const std::vector<double> offsets = vertex_offsets(q);
    const double moved = offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end());
    return std::max(0.0, radius_ - 2 * moved);
}

double SelfContact::max_safe_step(const Eigen::MatrixX3d& p, const Eigen::MatrixX3d& dx,
                                  double fraction, double min_separation_m) const {
    require(p.rows() == vertex_count_ && dx.rows() == vertex_count_,
            "SelfContact::max_safe_step: positions/dx have ", p.rows(), "/", dx.rows(),
            " rows, expected ", vertex_count_);
    require(fraction > 0 && fraction <= 1, "SelfContact::max_safe_step: fraction must be in "
            "(0, 1], got ", fraction);
    require(min_separation_m >= 0 && std::isfinite(min_separation_m),
            "SelfContact::max_safe_step: min_separation_m must be >= 0, got ", min_separation_m);
    require(dx.allFinite(), "SelfContact::max_safe_step: dx is not finite");
    const double s = min_separation_m;
    auto floor_of = [&](double d0) {
        return d0 > s ? s + (1 - fraction) * (d0 - s) : (1 - fraction) * d0;
    };

    // Pairs that are not candidates were at distance >= radius; any two points of the
    // cloth approach each other at most at 2 max_v |dx_v − m| per unit α (any m).
    double alpha = 1.0;
    const double covered = covered_radius(p);
    if (vertex_count_ > 0) {
        const Eigen::RowVector3d mean = dx.colwise().mean();
        const double lmax = 2 * (dx.rowwise() - mean).rowwise().norm().maxCoeff();
        // With radius <= s nothing but a rigid motion (up to rounding in the mean) can be
        // certified.
        if (lmax > 1e-12 * dx.rowwise().norm().maxCoeff())
            alpha = covered > s ? std::min(1.0, (covered - floor_of(covered)) / lmax) : 0.0;
    }

    // Per candidate pair: additive CCD. The distance between the primitives moving linearly
    // decreases at most at rate l = max_{a∈A}|Δa − m| + max_{b∈B}|Δb − m| (m: mean of the 4
    // displacements; translating all four by m leaves the distance unchanged), because every
    // point of a primitive moves by a convex combination of its vertices' displacements.
    // From α_i with distance d_i, [α_i, α_i + (d_i − F)/l] is therefore safe; iterate.
    // A pair at distance d0 >= s + l / fraction stays above its floor over all of [0, 1]
    // (below). Per-vertex bounds decide that for most pairs without touching coordinates:
    // d0 >= (distance at find_candidates) − (offsets since), and l <= the largest |dx − T|
    // of each primitive summed, T one common translation of dx (any will do).
    const int n = static_cast<int>(candidates_.size());
    std::vector<double> offset, spread;
    if (n > 0) {
        offset = vertex_offsets(p);
        spread = translation_reduced_lengths(dx);
    }
    std::vector<double> chunk_alpha(chunk_count(n), 1.0);
    for_each_chunk(n, [&](int c, int begin, int end) {
        double best = 1.0;
        for (int i = begin; i < end; ++i) {
            const ContactPair& pair = candidates_[i];
            const double d0_bound = reference_distance_[static_cast<std::size_t>(i)] - pair_offset(pair, offset);
            if (d0_bound >= (s + pair_offset(pair, spread) / fraction) * (1 + 1e-9) + 1e-12) continue;
            const Mat34 x0 = gather(p, pair), d = gather(dx, pair);
            const Mat34 rel = d.colwise() - d.rowwise().mean();
            const int na = first_primitive_size(pair.kind);
            double la = 0, lb = 0;
            for (int k = 0; k < 4; ++k) {
                double& bound = k < na ? la : lb;
                bound = std::max(bound, rel.col(k).norm());
            }
            const double l = la + lb;
            if (!(l > 0)) continue;
            // The distance stays >= d0 − α l >= the floor over all of [0, 1] when
            // d0 >= s + l / fraction; the box gap bounds d0 from below.
            const double clear = s + l / fraction;
            if (box_gap_squared(pair.kind, x0) >= clear * clear) continue;
            const double d0 = std::sqrt(pair_distance_squared(pair.kind, x0));
            if (!(d0 > 0)) continue;
            const double floor = floor_of(d0);
            double a = 0, dist = d0;
            for (int iter = 0; iter < 64 && a < best; ++iter) {
                const double step = (dist - floor) / l;
                if (!(step > 0)) break;
                a += step;
                if (a >= 1) {
                    a = 1;
                    break;
                }
                dist = std::sqrt(pair_distance_squared(pair.kind, x0 + a * d));
                if (dist - floor < 1e-3 * (d0 - floor)) break;  // converged onto the floor
            }
            best = std::min(best, a);
        }
        chunk_alpha[c] = best;
    });
    for (double a : chunk_alpha) alpha = std::min(alpha, a);
    return alpha;
}

}  // namespace drape::cloth::internal
