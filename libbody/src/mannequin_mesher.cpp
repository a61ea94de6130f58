// Meshing of the mannequin's implicit body: narrow-band marching tetrahedra on a
// Freudenthal-split cubic grid (topologically safe: the piecewise-linear level set of a
// consistent tetrahedral grid is a closed 2-manifold), then isotropic remeshing with a
// compact half-edge structure (split long edges, collapse short ones, flip towards
// valence 6, tangential relaxation, Newton projection onto the implicit surface).
#include "mannequin.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace drape::body::detail {
namespace {

using Eigen::Vector3d;

// ---- marching tetrahedra ----------------------------------------------------------------

struct Grid {
    Vector3d origin;
    double h = 0;
    int nx = 0, ny = 0, nz = 0;  // points per axis
    int64_t id(int i, int j, int k) const {
        return (static_cast<int64_t>(k) * ny + j) * nx + i;
    }
    Vector3d point(int i, int j, int k) const { return origin + h * Vector3d(i, j, k); }
};

// Corner offsets of a cube (bit 0 = x, bit 1 = y, bit 2 = z) and its six Freudenthal
// tetrahedra, all sharing the main diagonal 0-7.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                             {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

std::vector<int> largest_component(const SurfaceMesh& mesh) {
    const int nv = static_cast<int>(mesh.vertices.size());
    std::vector<int> parent(static_cast<size_t>(nv));
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
        while (parent[static_cast<size_t>(x)] != x) {
            parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
            x = parent[static_cast<size_t>(x)];
        }
        return x;
    };
    for (const auto& f : mesh.faces) {
        for (int e = 0; e < 3; ++e) {
            const int a = find(f[static_cast<size_t>(e)]), b = find(f[static_cast<size_t>((e + 1) % 3)]);
            if (a != b) parent[static_cast<size_t>(a)] = b;
        }
    }
    std::vector<int> count(static_cast<size_t>(nv), 0);
    for (const auto& f : mesh.faces) ++count[static_cast<size_t>(find(f[0]))];
    const int best = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
    std::vector<int> keep;
    for (size_t i = 0; i < mesh.faces.size(); ++i)
        if (find(mesh.faces[i][0]) == best) keep.push_back(static_cast<int>(i));
    return keep;
}

// ---- half-edge mesh ---------------------------------------------------------------------

class HalfedgeMesh {
public:
    std::vector<Vector3d> pos;
    std::vector<double> target;  // target edge length per vertex
    std::vector<int> to, opp, vhe;
    std::vector<char> face_dead, vert_dead;

    static int next(int h) { return h % 3 == 2 ? h - 2 : h + 1; }
    static int prev(int h) { return h % 3 == 0 ? h + 2 : h - 1; }
    int tail(int h) const { return to[static_cast<size_t>(prev(h))]; }
    /// True for exactly one half-edge of each live edge (the smaller of h and its twin),
    /// so that a loop over half-edges visits every edge once.
    bool is_edge_key(int h) const {
        return !face_dead[static_cast<size_t>(h / 3)] && h < opp[static_cast<size_t>(h)];
    }
    int face_count() const { return static_cast<int>(face_dead.size()); }

    void build(const SurfaceMesh& mesh) {
        pos = mesh.vertices;
        const size_t nf = mesh.faces.size();
        to.resize(3 * nf);
        opp.assign(3 * nf, -1);
        face_dead.assign(nf, 0);
        vert_dead.assign(pos.size(), 0);
        vhe.assign(pos.size(), -1);
        // Outgoing halfedges per vertex (CSR), then each opposite is found in the ring
        // of the head vertex.
        std::vector<int> start(pos.size() + 1, 0);
        for (size_t f = 0; f < nf; ++f)
            for (int i = 0; i < 3; ++i) ++start[static_cast<size_t>(mesh.faces[f][static_cast<size_t>(i)]) + 1];
        for (size_t v = 0; v < pos.size(); ++v) start[v + 1] += start[v];
        std::vector<int> fill(start.begin(), start.end() - 1), out(3 * nf);
        for (size_t f = 0; f < nf; ++f) {
            for (int i = 0; i < 3; ++i) {
                const int a = mesh.faces[f][static_cast<size_t>(i)];
                const int b = mesh.faces[f][static_cast<size_t>((i + 1) % 3)];
                const int h = static_cast<int>(3 * f) + i;
                to[static_cast<size_t>(h)] = b;
                vhe[static_cast<size_t>(a)] = h;
                out[static_cast<size_t>(fill[static_cast<size_t>(a)]++)] = h;
            }
        }
        for (size_t h = 0; h < to.size(); ++h) {
            const int a = tail(static_cast<int>(h)), b = to[h];
            for (int k = start[static_cast<size_t>(b)]; k < start[static_cast<size_t>(b) + 1]; ++k) {
                const int g = out[static_cast<size_t>(k)];
                if (to[static_cast<size_t>(g)] == a) {
                    opp[h] = g;
                    break;
                }
            }
        }
    }

    void link(int a, int b) {
        opp[static_cast<size_t>(a)] = b;
        opp[static_cast<size_t>(b)] = a;
    }
    void set_face(int f, int a, int b, int c) {
        to[static_cast<size_t>(3 * f)] = b;
        to[static_cast<size_t>(3 * f + 1)] = c;
        to[static_cast<size_t>(3 * f + 2)] = a;
    }
    int add_face() {
        face_dead.push_back(0);
        to.resize(to.size() + 3);
        opp.resize(opp.size() + 3, -1);
        return face_count() - 1;
    }
    int add_vertex(const Vector3d& p, double t) {
        pos.push_back(p);
        target.push_back(t);
        vhe.push_back(-1);
        vert_dead.push_back(0);
        return static_cast<int>(pos.size()) - 1;
    }

    template <class Fn>
    void for_ring(int v, const Fn& fn) const {  // fn(outgoing halfedge)
        const int h0 = vhe[static_cast<size_t>(v)];
        int h = h0;
        int guard = 0;
        do {
            fn(h);
            h = opp[static_cast<size_t>(prev(h))];
        } while (h != h0 && ++guard < 1000);
    }
    int valence(int v) const {
        int n = 0;
        for_ring(v, [&](int) { ++n; });
        return n;
    }
    Vector3d face_normal(int f) const {  // not normalised (2 * area)
        const Vector3d& a = pos[static_cast<size_t>(to[static_cast<size_t>(3 * f + 2)])];
        const Vector3d& b = pos[static_cast<size_t>(to[static_cast<size_t>(3 * f)])];
        const Vector3d& c = pos[static_cast<size_t>(to[static_cast<size_t>(3 * f + 1)])];
        return (b - a).cross(c - a);
    }
    bool has_edge(int a, int b) const {
        bool found = false;
        for_ring(a, [&](int h) { found = found || to[static_cast<size_t>(h)] == b; });
        return found;
    }

    // Edge a->b (h) in (a, b, c), opp b->a in (b, a, d): new vertex m in the middle.
    int split(int h, const Vector3d& p, double t) {
        const int o = opp[static_cast<size_t>(h)];
        const int a = tail(h), b = to[static_cast<size_t>(h)];
        const int c = to[static_cast<size_t>(next(h))], d = to[static_cast<size_t>(next(o))];
        const int e_bc = opp[static_cast<size_t>(next(h))], e_ca = opp[static_cast<size_t>(prev(h))];
        const int e_ad = opp[static_cast<size_t>(next(o))], e_db = opp[static_cast<size_t>(prev(o))];
        const int f0 = h / 3, f1 = o / 3;
        const int m = add_vertex(p, t);
        const int f2 = add_face(), f3 = add_face();
        set_face(f0, a, m, c);
        set_face(f2, m, b, c);
        set_face(f1, b, m, d);
        set_face(f3, m, a, d);
        link(3 * f0, 3 * f3);
        link(3 * f0 + 1, 3 * f2 + 2);
        link(3 * f0 + 2, e_ca);
        link(3 * f2, 3 * f1);
        link(3 * f2 + 1, e_bc);
        link(3 * f1 + 1, 3 * f3 + 2);
        link(3 * f1 + 2, e_db);
        link(3 * f3 + 1, e_ad);
        vhe[static_cast<size_t>(a)] = 3 * f0;
        vhe[static_cast<size_t>(b)] = 3 * f2 + 1;
        vhe[static_cast<size_t>(c)] = 3 * f0 + 2;
        vhe[static_cast<size_t>(d)] = 3 * f1 + 2;
        vhe[static_cast<size_t>(m)] = 3 * f0 + 1;
        return m;
    }

    // Collapses a->b (h) into b placed at p, if topology and geometry allow it.
    bool collapse(int h, const Vector3d& p, double max_len) {
        const int o = opp[static_cast<size_t>(h)];
        const int a = tail(h), b = to[static_cast<size_t>(h)];
        const int c = to[static_cast<size_t>(next(h))], d = to[static_cast<size_t>(next(o))];
        if (c == d) return false;
        if (valence(c) <= 3 || valence(d) <= 3) return false;
        if (valence(a) + valence(b) - 4 < 3) return false;
        // Link condition: the common neighbours of a and b are exactly c and d.
        int common = 0;
        bool link_ok = true;
        for_ring(a, [&](int ha) {
            const int x = to[static_cast<size_t>(ha)];
            if (x == b) return;
            bool shared = false;
            for_ring(b, [&](int hb) { shared = shared || to[static_cast<size_t>(hb)] == x; });
            if (shared) {
                ++common;
                if (x != c && x != d) link_ok = false;
            }
        });
        if (!link_ok || common != 2) return false;
        // Geometry: no flipped or needle faces, no long edges around the new vertex.
        const int f0 = h / 3, f1 = o / 3;
        bool ok = true;
        auto check = [&](int v) {
            for_ring(v, [&](int hv) {
                const int f = hv / 3;
                if (!ok || f == f0 || f == f1) return;
                const int x = to[static_cast<size_t>(hv)];
                const int y = to[static_cast<size_t>(next(hv))];
                const Vector3d n_old = face_normal(f);
                const Vector3d& px = pos[static_cast<size_t>(x)];
                const Vector3d& py = pos[static_cast<size_t>(y)];
                const Vector3d n_new = (px - p).cross(py - p);
                if (n_new.dot(n_old) <= 0.2 * n_old.norm() * n_new.norm()) ok = false;
                if ((px - p).norm() > max_len) ok = false;
                // Avoid creating needles (smallest angle below ~8 degrees).
                const double l0 = (px - p).norm(), l1 = (py - px).norm(), l2 = (p - py).norm();
                const double lmax = std::max({l0, l1, l2});
                if (n_new.norm() < 0.15 * lmax * lmax) ok = false;
            });
        };
        check(a);
        if (ok) check(b);
        if (!ok) return false;
        // Re-point the halfedges entering a.
        for_ring(a, [&](int ha) { to[static_cast<size_t>(prev(ha))] = b; });
        const int x0 = opp[static_cast<size_t>(next(h))], y0 = opp[static_cast<size_t>(prev(h))];
        const int x1 = opp[static_cast<size_t>(next(o))], y1 = opp[static_cast<size_t>(prev(o))];
        link(x0, y0);
        link(x1, y1);
        face_dead[static_cast<size_t>(f0)] = face_dead[static_cast<size_t>(f1)] = 1;
        vert_dead[static_cast<size_t>(a)] = 1;
        pos[static_cast<size_t>(b)] = p;
        vhe[static_cast<size_t>(b)] = y0;
        vhe[static_cast<size_t>(c)] = x0;
        vhe[static_cast<size_t>(d)] = x1;
        return true;
    }

    // Flips a->b (h) of (a, b, c) / (b, a, d) into c-d.
    void flip(int h) {
        const int o = opp[static_cast<size_t>(h)];
        const int a = tail(h), b = to[static_cast<size_t>(h)];
        const int c = to[static_cast<size_t>(next(h))], d = to[static_cast<size_t>(next(o))];
        const int e_bc = opp[static_cast<size_t>(next(h))], e_ca = opp[static_cast<size_t>(prev(h))];
        const int e_ad = opp[static_cast<size_t>(next(o))], e_db = opp[static_cast<size_t>(prev(o))];
        const int f0 = h / 3, f1 = o / 3;
        set_face(f0, a, d, c);
        set_face(f1, d, b, c);
        link(3 * f0, e_ad);
        link(3 * f0 + 1, 3 * f1 + 2);
        link(3 * f0 + 2, e_ca);
        link(3 * f1, e_db);
        link(3 * f1 + 1, e_bc);
        vhe[static_cast<size_t>(a)] = 3 * f0;
        vhe[static_cast<size_t>(d)] = 3 * f0 + 1;
        vhe[static_cast<size_t>(c)] = 3 * f0 + 2;
        vhe[static_cast<size_t>(b)] = 3 * f1 + 1;
    }

    bool flip_ok(int h, double min_cos) const {
        const int o = opp[static_cast<size_t>(h)];
        const int a = tail(h), b = to[static_cast<size_t>(h)];
        const int c = to[static_cast<size_t>(next(h))], d = to[static_cast<size_t>(next(o))];
        if (c == d || has_edge(c, d)) return false;
        if (valence(a) <= 3 || valence(b) <= 3) return false;
        const Vector3d& pa = pos[static_cast<size_t>(a)];
        const Vector3d& pb = pos[static_cast<size_t>(b)];
        const Vector3d& pc = pos[static_cast<size_t>(c)];
        const Vector3d& pd = pos[static_cast<size_t>(d)];
        const Vector3d n0 = (pd - pa).cross(pc - pa);
        const Vector3d n1 = (pb - pd).cross(pc - pd);
        const Vector3d m0 = (pb - pa).cross(pc - pa);
        const Vector3d m1 = (pa - pb).cross(pd - pb);
        const Vector3d avg = m0.normalized() + m1.normalized();
        if (n0.norm() < 1e-14 || n1.norm() < 1e-14) return false;
        if (n0.normalized().dot(n1.normalized()) < min_cos) return false;
        if (n0.dot(avg) <= 0 || n1.dot(avg) <= 0) return false;
        return true;
    }

    SurfaceMesh compact() const {
        SurfaceMesh out;
        std::vector<int> map(pos.size(), -1);
        for (size_t v = 0; v < pos.size(); ++v) {
            if (vert_dead[v]) continue;
            map[v] = static_cast<int>(out.vertices.size());
            out.vertices.push_back(pos[v]);
        }
        for (int f = 0; f < face_count(); ++f) {
            if (face_dead[static_cast<size_t>(f)]) continue;
            out.faces.push_back({map[static_cast<size_t>(to[static_cast<size_t>(3 * f + 2)])],
                                 map[static_cast<size_t>(to[static_cast<size_t>(3 * f)])],
                                 map[static_cast<size_t>(to[static_cast<size_t>(3 * f + 1)])]});
        }
        return out;
    }
};

double angle_at(const Vector3d& a, const Vector3d& b, const Vector3d& c) {  // angle at a
    const Vector3d u = b - a, v = c - a;
    return std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

// ---- projection -------------------------------------------------------------------------

Vector3d project_onto_implicit(const MannequinImplicit& body, Vector3d p, int max_iterations,
                               double tolerance) {
    // Forward differences: 4 evaluations per step; the O(h) gradient error only slows the
    // last digits of Newton's convergence.
    const double h = 1e-6;
    double f = body.value(p);
    for (int it = 0; it < max_iterations && std::abs(f) >= tolerance; ++it) {
        Vector3d g;
        for (int i = 0; i < 3; ++i) {
            Vector3d q = p;
            q[i] += h;
            g[i] = (body.value(q) - f) / h;
        }
        const double g2 = g.squaredNorm();
        if (g2 < 1e-12) break;
        Vector3d step = f * g / g2;
        const double n = step.norm();
        if (n > 0.01) step *= 0.01 / n;
        p -= step;
        f = body.value(p);
    }
    return p;
}

// ---- polygonisation ---------------------------------------------------------------------

SurfaceMesh polygonize_implicit(const MannequinImplicit& body, double cell_size) {
    constexpr int B = 3;  // cells per block side
    Grid grid;
    grid.h = cell_size;
    const Eigen::AlignedBox3d& box = body.bounds();
    const double block = B * cell_size;
    grid.origin = box.min() - Vector3d::Constant(1.5 * cell_size);
    const Vector3d size = box.max() - grid.origin + Vector3d::Constant(1.5 * cell_size);
    const int bx = static_cast<int>(std::ceil(size.x() / block));
    const int by = static_cast<int>(std::ceil(size.y() / block));
    const int bz = static_cast<int>(std::ceil(size.z() / block));
    grid.nx = bx * B + 1;
    grid.ny = by * B + 1;
    grid.nz = bz * B + 1;
    const size_t npts = static_cast<size_t>(grid.nx) * grid.ny * grid.nz;
    std::vector<float> values(npts, std::numeric_limits<float>::quiet_NaN());

    // Block corners first.
    std::vector<int64_t> pending;
    for (int k = 0; k <= bz; ++k)
        for (int j = 0; j <= by; ++j)
            for (int i = 0; i <= bx; ++i) pending.push_back(grid.id(i * B, j * B, k * B));
    auto evaluate = [&](const std::vector<int64_t>& ids) {
        parallel_for(static_cast<int>(ids.size()), [&](int n) {
            const int64_t id = ids[static_cast<size_t>(n)];
            const int i = static_cast<int>(id % grid.nx);
            const int j = static_cast<int>((id / grid.nx) % grid.ny);
            const int k = static_cast<int>(id / (static_cast<int64_t>(grid.nx) * grid.ny));
            values[static_cast<size_t>(id)] = static_cast<float>(body.value(grid.point(i, j, k)));
        });
    };
    evaluate(pending);

    // Active blocks: a sign change at the corners or a corner close enough to the surface
    // (value() is about 1-Lipschitz, so a surface inside the block is within its diagonal).
    const double near = 1.1 * std::sqrt(3.0) * block;
    std::vector<std::array<int, 3>> active;
    for (int k = 0; k < bz; ++k)
        for (int j = 0; j < by; ++j)
            for (int i = 0; i < bx; ++i) {
                bool neg = false, pos = false, close = false;
                for (int c = 0; c < 8; ++c) {
                    const float v = values[static_cast<size_t>(
                        grid.id((i + (c & 1)) * B, (j + ((c >> 1) & 1)) * B, (k + ((c >> 2) & 1)) * B))];
                    neg = neg || v < 0;
                    pos = pos || v >= 0;
                    close = close || std::abs(v) < near;
                }
                if ((neg && pos) || close) active.push_back({i, j, k});
            }
    pending.clear();
    std::vector<char> mark(npts, 0);
    for (const auto& b : active)
        for (int k = 0; k <= B; ++k)
            for (int j = 0; j <= B; ++j)
                for (int i = 0; i <= B; ++i) {
                    const int64_t id = grid.id(b[0] * B + i, b[1] * B + j, b[2] * B + k);
                    if (mark[static_cast<size_t>(id)] || !std::isnan(values[static_cast<size_t>(id)]))
                        continue;
                    mark[static_cast<size_t>(id)] = 1;
                    pending.push_back(id);
                }
    evaluate(pending);

    SurfaceMesh mesh;
    std::unordered_map<int64_t, int> edge_vertex;
    edge_vertex.reserve(200000);
    const int64_t n_total = static_cast<int64_t>(npts);
    auto vertex_on = [&](int64_t ia, int64_t ib, const Vector3d& pa, const Vector3d& pb) {
        const int64_t key = std::min(ia, ib) * n_total + std::max(ia, ib);
        auto it = edge_vertex.find(key);
        if (it != edge_vertex.end()) return it->second;
        const double fa = values[static_cast<size_t>(ia)], fb = values[static_cast<size_t>(ib)];
        const double t = std::clamp(fa / (fa - fb), 0.02, 0.98);
        const int id = static_cast<int>(mesh.vertices.size());
        mesh.vertices.push_back(pa + t * (pb - pa));
        edge_vertex.emplace(key, id);
        return id;
    };
    for (const auto& b : active)
        for (int ck = 0; ck < B; ++ck)
            for (int cj = 0; cj < B; ++cj)
                for (int ci = 0; ci < B; ++ci) {
                    const int i = b[0] * B + ci, j = b[1] * B + cj, k = b[2] * B + ck;
                    int64_t ids[8];
                    float f[8];
                    Vector3d p[8];
                    bool any_neg = false, any_pos = false;
                    for (int c = 0; c < 8; ++c) {
                        const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
                        ids[c] = grid.id(i + di, j + dj, k + dk);
                        f[c] = values[static_cast<size_t>(ids[c])];
                        p[c] = grid.point(i + di, j + dj, k + dk);
                        any_neg = any_neg || f[c] < 0;
                        any_pos = any_pos || f[c] >= 0;
                    }
                    if (!(any_neg && any_pos)) continue;
                    for (const auto& tet : kTets) {
                        int in[4], out[4], ni = 0, no = 0;
                        for (int q = 0; q < 4; ++q) {
                            if (f[tet[q]] < 0) in[ni++] = tet[q];
                            else out[no++] = tet[q];
                        }
                        if (ni == 0 || no == 0) continue;
                        Vector3d cin = Vector3d::Zero(), cout = Vector3d::Zero();
                        for (int q = 0; q < ni; ++q) cin += p[in[q]] / ni;
                        for (int q = 0; q < no; ++q) cout += p[out[q]] / no;
                        const Vector3d outward = cout - cin;
                        // Orientation decided on the midpoint polygon: exact and never
                        // degenerate, so every triangle agrees with its neighbours.
                        auto emit = [&](std::array<std::pair<int, int>, 3> e) {
                            Vector3d m[3];
                            for (int q = 0; q < 3; ++q) m[q] = 0.5 * (p[e[static_cast<size_t>(q)].first] + p[e[static_cast<size_t>(q)].second]);
                            if ((m[1] - m[0]).cross(m[2] - m[0]).dot(outward) < 0) std::swap(e[1], e[2]);
                            std::array<int, 3> tri;
                            for (int q = 0; q < 3; ++q) {
                                const auto& ed = e[static_cast<size_t>(q)];
                                tri[static_cast<size_t>(q)] = vertex_on(ids[ed.first], ids[ed.second], p[ed.first], p[ed.second]);
                            }
                            mesh.faces.push_back(tri);
                        };
                        if (ni == 1) {
                            emit({{{in[0], out[0]}, {in[0], out[1]}, {in[0], out[2]}}});
                        } else if (no == 1) {
                            emit({{{in[0], out[0]}, {in[1], out[0]}, {in[2], out[0]}}});
                        } else {
                            // Quad a-c, a-d, b-d, b-c.
                            emit({{{in[0], out[0]}, {in[0], out[1]}, {in[1], out[1]}}});
                            emit({{{in[0], out[0]}, {in[1], out[1]}, {in[1], out[0]}}});
                        }
                    }
                }

    const std::vector<int> keep = largest_component(mesh);
    SurfaceMesh out;
    std::vector<int> map(mesh.vertices.size(), -1);
    for (int fi : keep) {
        std::array<int, 3> tri;
        for (int q = 0; q < 3; ++q) {
            int& m = map[static_cast<size_t>(mesh.faces[static_cast<size_t>(fi)][static_cast<size_t>(q)])];
            if (m < 0) {
                m = static_cast<int>(out.vertices.size());
                out.vertices.push_back(mesh.vertices[static_cast<size_t>(mesh.faces[static_cast<size_t>(fi)][static_cast<size_t>(q)])]);
            }
            tri[static_cast<size_t>(q)] = m;
        }
        out.faces.push_back(tri);
    }
    return out;
}

// ---- remeshing --------------------------------------------------------------------------

void remesh_on_implicit(const MannequinImplicit& body, int target_vertices, int iterations,
                        SurfaceMesh& mesh) {
    // Base edge length from the sizing-weighted area: an equilateral mesh has
    // #V ~ (2 / sqrt 3) * sum(area / (L0 s)^2).
    double weighted_area = 0.0;
    for (const auto& f : mesh.faces) {
        const Vector3d& a = mesh.vertices[static_cast<size_t>(f[0])];
        const Vector3d& b = mesh.vertices[static_cast<size_t>(f[1])];
        const Vector3d& c = mesh.vertices[static_cast<size_t>(f[2])];
        const double s = body.relative_edge_length((a + b + c) / 3.0);
        weighted_area += 0.5 * (b - a).cross(c - a).norm() / (s * s);
    }
    const double L0 = std::sqrt(2.0 / std::sqrt(3.0) * weighted_area / target_vertices);

    HalfedgeMesh hm;
    hm.build(mesh);
    hm.target.resize(hm.pos.size());
    for (size_t v = 0; v < hm.pos.size(); ++v) hm.target[v] = L0 * body.relative_edge_length(hm.pos[v]);

    auto edge_target = [&](int a, int b) {
        return 0.5 * (hm.target[static_cast<size_t>(a)] + hm.target[static_cast<size_t>(b)]);
    };

    auto relax = [&](double lambda, int newton_steps) {
        const int nv = static_cast<int>(hm.pos.size());
        std::vector<Vector3d> normal(static_cast<size_t>(nv), Vector3d::Zero());
        for (int f = 0; f < hm.face_count(); ++f) {
            if (hm.face_dead[static_cast<size_t>(f)]) continue;
            const Vector3d n = hm.face_normal(f);
            for (int q = 0; q < 3; ++q) normal[static_cast<size_t>(hm.to[static_cast<size_t>(3 * f + q)])] += n;
        }
        std::vector<Vector3d> next(hm.pos);
        parallel_for(nv, [&](int v) {
            if (hm.vert_dead[static_cast<size_t>(v)]) return;
            Vector3d c = Vector3d::Zero();
            double wsum = 0.0;
            // Weight neighbours by their target length so that small-target regions keep
            // their density.
            hm.for_ring(v, [&](int h) {
                const int w = hm.to[static_cast<size_t>(h)];
                const double wt = 1.0 / hm.target[static_cast<size_t>(w)];
                c += wt * hm.pos[static_cast<size_t>(w)];
                wsum += wt;
            });
            c /= wsum;
            const Vector3d n = normal[static_cast<size_t>(v)].normalized();
            Vector3d d = c - hm.pos[static_cast<size_t>(v)];
            d -= n.dot(d) * n;
            next[static_cast<size_t>(v)] =
                project_onto_implicit(body, hm.pos[static_cast<size_t>(v)] + lambda * d, newton_steps, 1e-7);
        });
        hm.pos.swap(next);
        parallel_for(nv, [&](int v) {
            if (!hm.vert_dead[static_cast<size_t>(v)])
                hm.target[static_cast<size_t>(v)] = L0 * body.relative_edge_length(hm.pos[static_cast<size_t>(v)]);
        });
    };

    for (int it = 0; it < iterations; ++it) {
        // Split long edges.
        for (int pass = 0; pass < 2; ++pass) {
            const int nh = 3 * hm.face_count();
            for (int h = 0; h < nh; ++h) {
                if (!hm.is_edge_key(h)) continue;
                const int a = hm.tail(h), b = hm.to[static_cast<size_t>(h)];
                const double len = (hm.pos[static_cast<size_t>(a)] - hm.pos[static_cast<size_t>(b)]).norm();
                if (len > 4.0 / 3.0 * edge_target(a, b)) {
                    const Vector3d m = 0.5 * (hm.pos[static_cast<size_t>(a)] + hm.pos[static_cast<size_t>(b)]);
                    hm.split(h, m, L0 * body.relative_edge_length(m));
                }
            }
        }
        // Collapse short edges.
        for (int pass = 0; pass < 3; ++pass) {
            const int nh = 3 * hm.face_count();
            int done = 0;
            for (int h = 0; h < nh; ++h) {
                if (!hm.is_edge_key(h)) continue;
                const int a = hm.tail(h), b = hm.to[static_cast<size_t>(h)];
                const double target = edge_target(a, b);
                const double len = (hm.pos[static_cast<size_t>(a)] - hm.pos[static_cast<size_t>(b)]).norm();
                if (len < 0.8 * target) {
                    const Vector3d m = 0.5 * (hm.pos[static_cast<size_t>(a)] + hm.pos[static_cast<size_t>(b)]);
                    if (hm.collapse(h, m, 4.0 / 3.0 * target)) {
                        hm.target[static_cast<size_t>(b)] = target;
                        ++done;
                    }
                }
            }
            if (done == 0) break;
        }
        // Flip towards valence 6.
        for (int pass = 0; pass < 2; ++pass) {
            const int nh = 3 * hm.face_count();
            for (int h = 0; h < nh; ++h) {
                if (!hm.is_edge_key(h)) continue;
                const int o = hm.opp[static_cast<size_t>(h)];
                const int a = hm.tail(h), b = hm.to[static_cast<size_t>(h)];
                const int c = hm.to[static_cast<size_t>(HalfedgeMesh::next(h))];
                const int d = hm.to[static_cast<size_t>(HalfedgeMesh::next(o))];
                const int va = hm.valence(a), vb = hm.valence(b), vc = hm.valence(c), vd = hm.valence(d);
                const int before = std::abs(va - 6) + std::abs(vb - 6) + std::abs(vc - 6) + std::abs(vd - 6);
                const int after = std::abs(va - 7) + std::abs(vb - 7) + std::abs(vc - 5) + std::abs(vd - 5);
                if (after < before && hm.flip_ok(h, 0.5)) hm.flip(h);
            }
        }
        const bool last = it + 1 == iterations;
        for (int r = 0; r < (last ? 2 : 1); ++r) relax(0.6, 1);
    }
    // Delaunay-style flips on nearly flat edge pairs: remove remaining obtuse needles.
    for (int pass = 0; pass < 3; ++pass) {
        int flips = 0;
        const int nh = 3 * hm.face_count();
        for (int h = 0; h < nh; ++h) {
            if (!hm.is_edge_key(h)) continue;
            const int o = hm.opp[static_cast<size_t>(h)];
            const int a = hm.tail(h), b = hm.to[static_cast<size_t>(h)];
            const int c = hm.to[static_cast<size_t>(HalfedgeMesh::next(h))];
            const int d = hm.to[static_cast<size_t>(HalfedgeMesh::next(o))];
            const Vector3d& pa = hm.pos[static_cast<size_t>(a)];
            const Vector3d& pb = hm.pos[static_cast<size_t>(b)];
            const Vector3d& pc = hm.pos[static_cast<size_t>(c)];
            const Vector3d& pd = hm.pos[static_cast<size_t>(d)];
            const double opposite = angle_at(pc, pa, pb) + angle_at(pd, pa, pb);
            if (opposite <= 3.14159265358979 + 1e-9) continue;
            const double before = std::min({angle_at(pa, pb, pc), angle_at(pb, pc, pa), angle_at(pc, pa, pb),
                                            angle_at(pa, pd, pb), angle_at(pb, pa, pd), angle_at(pd, pb, pa)});
            const double after = std::min({angle_at(pa, pd, pc), angle_at(pd, pc, pa), angle_at(pc, pa, pd),
                                           angle_at(pd, pb, pc), angle_at(pb, pc, pd), angle_at(pc, pd, pb)});
            if (after > before && hm.flip_ok(h, 0.8)) {
                hm.flip(h);
                ++flips;
            }
        }
        if (flips == 0) break;
    }
    relax(0.5, 2);
    // Exact projection.
    parallel_for(static_cast<int>(hm.pos.size()), [&](int v) {
        if (!hm.vert_dead[static_cast<size_t>(v)])
            hm.pos[static_cast<size_t>(v)] = project_onto_implicit(body, hm.pos[static_cast<size_t>(v)], 30, 1e-10);
    });
    mesh = hm.compact();
}

}  // namespace drape::body::detail
