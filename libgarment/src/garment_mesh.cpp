// The only translation unit that includes CGAL (slow to compile; keep it that way).
#include <drape/garment/garment_mesh.hpp>

#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace drape::garment {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using Point = CDT::Point;

constexpr double kPi = 3.14159265358979323846;
constexpr double kFractionTol = 1e-9;
// Longest-edge bound of the size criterion relative to the aimed mean edge length: CGAL
// bounds the longest edge; refined pattern meshes have a mean edge ~0.7 of that bound.
constexpr double kLongestEdgeFactor = 1.42;

// The discretisation of one panel edge: `base` points at uniform arc-length fractions
// k / n on the curve; any other fraction lies on the chord between two base points.
struct EdgeSamples {
    std::vector<Eigen::Vector2d> base;  // n + 1 points
    std::vector<double> fractions;      // sorted, includes 0 and 1
    Eigen::Vector2d at(double f) const {
        const int n = static_cast<int>(base.size()) - 1;
        const double x = std::clamp(f, 0.0, 1.0) * n;
        const int k = std::min(n - 1, static_cast<int>(std::floor(x + kFractionTol)));
        const double t = x - k;
        if (std::abs(t) < kFractionTol) return base[k];
        return (1 - t) * base[k] + t * base[k + 1];
    }
};

bool insert_fraction(std::vector<double>& list, double f) {
    const auto it = std::lower_bound(list.begin(), list.end(), f - kFractionTol);
    if (it != list.end() && std::abs(*it - f) <= kFractionTol) return false;
    list.insert(it, f);
    return true;
}

struct PanelMesh {
    std::vector<Eigen::Vector2d> points;     // panel frame, cm
    std::vector<int> edge;                   // per point: edge index or -1
    std::vector<double> fraction;            // per point
    std::vector<std::array<int, 3>> faces;   // CCW
    std::vector<std::vector<int>> edge_points;  // per edge: point ids at its fractions
};

// Meshes one panel whose boundary is given by `samples`; appends Steiner points that the
// refinement put on the boundary to `samples[e].fractions`, and reports whether it did.
PanelMesh mesh_panel(std::vector<EdgeSamples>& samples, const MeshOptions& options,
                     bool* boundary_changed) {
    CDT cdt;
    struct Tag {
        int edge;
        double fraction;
    };
    std::vector<std::pair<CDT::Vertex_handle, Tag>> loop;
    for (size_t e = 0; e < samples.size(); ++e) {
        const auto& fr = samples[e].fractions;
        for (size_t k = 0; k + 1 < fr.size(); ++k) {
            const Eigen::Vector2d p = samples[e].at(fr[k]);
            loop.push_back({cdt.insert(Point(p.x(), p.y())), Tag{int(e), fr[k]}});
        }
    }
    for (size_t i = 0; i < loop.size(); ++i)
        cdt.insert_constraint(loop[i].first, loop[(i + 1) % loop.size()].first);
    const double b = std::pow(std::sin(options.min_angle_deg * kPi / 180.0), 2);
    const Criteria criteria(b, kLongestEdgeFactor * options.target_edge_cm);
    if (options.refine_boundary)
        CGAL::refine_Delaunay_mesh_2(cdt, criteria);
    else {
        // As CGAL::refine_Delaunay_mesh_2_without_edge_refinement, but with clear_seeds()
        // first: that mesher's constructor leaves its seeds_mark flag uninitialised (CGAL 5.5;
        // Delaunay_mesher_2's sets it), and init() reads it, which UBSan reports as an
        // invalid bool load. Without seeds the flag does not change the result.
        CGAL::Delaunay_mesher_no_edge_refinement_2<CDT, Criteria> mesher(cdt, criteria);
        mesher.clear_seeds();
        mesher.init();
        mesher.refine_mesh();
    }

    std::map<CDT::Vertex_handle, Tag> tags;
    for (const auto& [v, tag] : loop) tags[v] = tag;
    PanelMesh mesh;
    std::map<CDT::Vertex_handle, int> id;
    *boundary_changed = false;
    // Boundary segments of the loop, to place Steiner points found on the boundary.
    std::vector<std::array<Eigen::Vector2d, 2>> segs;
    std::vector<std::array<double, 2>> seg_fr;
    std::vector<int> seg_edge;
    for (size_t e = 0; e < samples.size(); ++e) {
        const auto& fr = samples[e].fractions;
        for (size_t k = 0; k + 1 < fr.size(); ++k) {
            segs.push_back({samples[e].at(fr[k]), samples[e].at(fr[k + 1])});
            seg_fr.push_back({fr[k], fr[k + 1]});
            seg_edge.push_back(int(e));
        }
    }
    std::vector<std::pair<int, double>> new_boundary;
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
        const Eigen::Vector2d p(v->point().x(), v->point().y());
        int edge = -1;
        double fraction = 0;
        if (auto it = tags.find(v); it != tags.end()) {
            edge = it->second.edge;
            fraction = it->second.fraction;
        } else {
            // Is it on a constrained edge (a boundary split)?
            bool on_boundary = false;
            auto ec = cdt.incident_edges(v), done = ec;
            if (ec != nullptr) do {
                    if (cdt.is_constrained(*ec)) on_boundary = true;
                } while (++ec != done);
            if (on_boundary) {
                double best = 1e300;
                for (size_t s = 0; s < segs.size(); ++s) {
                    const Eigen::Vector2d d = segs[s][1] - segs[s][0];
                    const double t = std::clamp((p - segs[s][0]).dot(d) / d.squaredNorm(), 0.0, 1.0);
                    const double dist = (segs[s][0] + t * d - p).norm();
                    if (dist < best) {
                        best = dist;
                        edge = seg_edge[s];
                        fraction = seg_fr[s][0] + t * (seg_fr[s][1] - seg_fr[s][0]);
                    }
                }
                new_boundary.emplace_back(edge, fraction);
            }
        }
        id[v] = static_cast<int>(mesh.points.size());
        mesh.points.push_back(p);
        mesh.edge.push_back(edge);
        mesh.fraction.push_back(fraction);
    }
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (!f->is_in_domain()) continue;
        mesh.faces.push_back({id[f->vertex(0)], id[f->vertex(1)], id[f->vertex(2)]});
    }
    for (const auto& [e, f] : new_boundary)
        if (insert_fraction(samples[e].fractions, f)) *boundary_changed = true;
    // Point ids along each edge in fraction order (corners at both ends).
    mesh.edge_points.assign(samples.size(), {});
    std::map<std::pair<int, long long>, int> by_key;
    const auto key = [](int e, double f) { return std::pair<int, long long>(e, std::llround(f * 1e8)); };
    for (size_t i = 0; i < mesh.points.size(); ++i)
        if (mesh.edge[i] >= 0) by_key[key(mesh.edge[i], mesh.fraction[i])] = int(i);
    for (size_t e = 0; e < samples.size(); ++e) {
        for (double f : samples[e].fractions) {
            auto it = by_key.find(f >= 1.0 - kFractionTol ? key(int((e + 1) % samples.size()), 0.0)
                                                          : key(int(e), f));
            mesh.edge_points[e].push_back(it == by_key.end() ? -1 : it->second);
        }
    }
    return mesh;
}

double triangle_min_angle_deg(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                              const Eigen::Vector2d& c) {
    const Eigen::Vector2d p[3] = {a, b, c};
    double m = 180;
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
        m = std::min(m, std::acos(std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0)) * 180 / kPi);
    }
    return m;
}

}  // namespace

bool MeshOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& t) {
        if (why) *why = t;
        return false;
    };
    if (!(target_edge_cm > 0.2 && target_edge_cm <= 20))
        return fail("MeshOptions::target_edge_cm = " + std::to_string(target_edge_cm) +
                    " must be in (0.2, 20] cm");
    if (!(min_angle_deg > 0 && min_angle_deg <= 20.7))
        return fail("MeshOptions::min_angle_deg = " + std::to_string(min_angle_deg) +
                    " must be in (0, 20.7] degrees (CGAL's termination bound)");
    if (max_seam_rounds < 1)
        return fail("MeshOptions::max_seam_rounds = " + std::to_string(max_seam_rounds) +
                    " must be >= 1");
    return true;
}

std::string MeshSummary::brief_report() const {
    std::ostringstream os;
    os << (usable() ? "mesh ok" : "mesh NOT usable") << ": " << vertices << " vertices, " << faces
       << " faces, " << stitches << " stitches, min angle " << min_angle_deg
       << " deg, mean edge " << mean_edge_cm << " cm, area " << area_cm2 << " cm², "
       << seam_rounds << " seam round(s), " << seconds << " s";
    if (!message.empty()) os << " (" << message << ")";
    return os.str();
}

MeshSummary mesh_pattern(const Pattern& pattern, const MeshOptions& options, GarmentMesh& out) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why;
    require(options.is_valid(&why), "mesh_pattern: ", why);
    pattern.validate();
    // Refuse a mesh beyond the vertex limit before triangulating (docs/hardening.md,
    // "Resource limits"): about one vertex per area of two equilateral triangles of the
    // target edge inside, one per target edge along each outline.
    {
        const double h = options.target_edge_cm;
        double estimate = 0;
        for (const Panel& panel : pattern.panels)
            estimate += std::abs(panel.area()) / (std::sqrt(3.0) / 2.0 * h * h) + panel.perimeter() / h;
        require(std::isfinite(estimate) && estimate <= double(limits::kMaxMeshVertices), "mesh_pattern: pattern '",
                pattern.name, "' at target_edge_cm = ", h, " would have about ", estimate,
                " vertices, more than the limit of ", limits::kMaxMeshVertices, " (docs/hardening.md)");
    }

    // Partner edge of each seam edge.
    std::map<std::pair<int, int>, std::pair<std::pair<int, int>, const Seam*>> partner;
    for (const Seam& s : pattern.seams) {
        partner[{s.panel_a, s.edge_a}] = {{s.panel_b, s.edge_b}, &s};
        partner[{s.panel_b, s.edge_b}] = {{s.panel_a, s.edge_a}, &s};
    }
    // Identical discretisation of both sides of every seam.
    std::vector<std::vector<EdgeSamples>> samples(pattern.panels.size());
    for (size_t p = 0; p < pattern.panels.size(); ++p)
        for (size_t e = 0; e < pattern.panels[p].edges.size(); ++e) {
            int n = std::max(1, int(std::lround(pattern.panels[p].edges[e].length() / options.target_edge_cm)));
            if (auto it = partner.find({int(p), int(e)}); it != partner.end()) {
                const auto [q, f] = it->second.first;
                n = std::max(n, int(std::lround(pattern.panels[q].edges[f].length() / options.target_edge_cm)));
            }
            EdgeSamples s;
            s.base = pattern.panels[p].edges[e].sample_uniform(n);
            for (int k = 0; k <= n; ++k) s.fractions.push_back(double(k) / n);
            samples[p].push_back(std::move(s));
        }

    MeshSummary summary;
    std::vector<PanelMesh> meshes(pattern.panels.size());
    std::vector<bool> dirty(pattern.panels.size(), true);
    bool agreed = false;
    for (int round = 1; round <= options.max_seam_rounds && !agreed; ++round) {
        summary.seam_rounds = round;
        for (size_t p = 0; p < pattern.panels.size(); ++p) {
            if (!dirty[p]) continue;
            bool changed = false;
            meshes[p] = mesh_panel(samples[p], options, &changed);
        }
        std::fill(dirty.begin(), dirty.end(), false);
        // Mirror every seam edge's fractions onto its partner.
        agreed = true;
        for (const Seam& s : pattern.seams) {
            auto& fa = samples[s.panel_a][s.edge_a].fractions;
            auto& fb = samples[s.panel_b][s.edge_b].fractions;
            const std::vector<double> a = fa, b = fb;
            for (double f : a)
                if (insert_fraction(fb, partner_fraction(s, f))) dirty[s.panel_b] = true;
            for (double f : b)
                if (insert_fraction(fa, partner_fraction(s, f))) dirty[s.panel_a] = true;
        }
        // A panel whose boundary gained a point must be meshed again (its previous mesh did
        // not contain the point) — detect by comparing point lists.
        for (size_t p = 0; p < pattern.panels.size(); ++p)
            for (size_t e = 0; e < samples[p].size(); ++e)
                if (meshes[p].edge_points[e].size() != samples[p][e].fractions.size() ||
                    std::count(meshes[p].edge_points[e].begin(), meshes[p].edge_points[e].end(), -1) > 0)
                    dirty[p] = true;
        agreed = std::none_of(dirty.begin(), dirty.end(), [](bool d) { return d; });
    }
    if (!agreed) {
        summary.termination = MeshTermination::seam_rounds_exhausted;
        summary.message = "seam discretisations did not agree after " +
                          std::to_string(options.max_seam_rounds) + " rounds";
    }

    // Assemble.
    const std::vector<Eigen::Vector2d> offsets = layout_offsets(pattern);
    std::vector<int> first(pattern.panels.size() + 1, 0);
    std::size_t nf = 0;
    for (size_t p = 0; p < meshes.size(); ++p) {
        first[p + 1] = first[p] + static_cast<int>(meshes[p].points.size());
        nf += meshes[p].faces.size();
    }
    const int nv = first.back();
    GarmentMesh g;
    Eigen::MatrixX3d positions(nv, 3);
    Eigen::MatrixX2d layout(nv, 2);
    Eigen::MatrixX3i faces(static_cast<Eigen::Index>(nf), 3);
    g.panel_of_vertex.resize(nv);
    g.panel_point_cm.resize(nv, 2);
    g.boundary_edge.resize(nv);
    g.boundary_fraction.resize(nv);
    Eigen::Index fi = 0;
    double min_angle = 180, edge_sum = 0, area = 0;
    long edge_count = 0;
    for (size_t p = 0; p < meshes.size(); ++p) {
        const PanelMesh& m = meshes[p];
        for (size_t i = 0; i < m.points.size(); ++i) {
            const int v = first[p] + int(i);
            positions.row(v) = pattern.placements[p].to_world_m(m.points[i]).transpose();
            layout.row(v) = 0.01 * (m.points[i] + offsets[p]).transpose();
            g.panel_of_vertex(v) = int(p);
            g.panel_point_cm.row(v) = m.points[i].transpose();
            g.boundary_edge(v) = m.edge[i];
            g.boundary_fraction(v) = m.fraction[i];
        }
        for (const auto& f : m.faces) {
            faces.row(fi++) << first[p] + f[0], first[p] + f[1], first[p] + f[2];
            const Eigen::Vector2d &a = m.points[f[0]], &b = m.points[f[1]], &c = m.points[f[2]];
            min_angle = std::min(min_angle, triangle_min_angle_deg(a, b, c));
            edge_sum += (b - a).norm() + (c - b).norm() + (a - c).norm();
            edge_count += 3;
            area += 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
        }
        std::vector<int> loop;
        for (size_t e = 0; e < m.edge_points.size(); ++e)
            for (size_t k = 0; k + 1 < m.edge_points[e].size(); ++k)
                loop.push_back(first[p] + m.edge_points[e][k]);
        g.boundary_loops.push_back(std::move(loop));
    }
    g.cloth = cloth::ClothMesh::from_vertex_pattern(positions, faces, layout);
    const Eigen::Vector2d extent = layout.colwise().maxCoeff().transpose();
    g.uv = layout / std::max(extent.maxCoeff(), 1e-12);

    std::set<std::array<int, 2>> seen;
    for (size_t si = 0; si < pattern.seams.size(); ++si) {
        const Seam& s = pattern.seams[si];
        const auto& fa = samples[s.panel_a][s.edge_a].fractions;
        const auto& pa = meshes[s.panel_a].edge_points[s.edge_a];
        const auto& pb = meshes[s.panel_b].edge_points[s.edge_b];
        const auto& fb = samples[s.panel_b][s.edge_b].fractions;
        for (size_t k = 0; k < fa.size(); ++k) {
            const double target = partner_fraction(s, fa[k]);
            const auto it = std::lower_bound(fb.begin(), fb.end(), target - kFractionTol);
            if (it == fb.end() || std::abs(*it - target) > kFractionTol) continue;
            const int i = pa[k], j = pb[size_t(it - fb.begin())];
            if (i < 0 || j < 0) continue;
            const std::array<int, 2> pair{first[s.panel_a] + i, first[s.panel_b] + j};
            if (pair[0] == pair[1] || !seen.insert(pair).second) continue;
            g.stitches.push_back(pair);
            g.stitch_seam.push_back(int(si));
        }
    }
    out = std::move(g);
    summary.vertices = nv;
    summary.faces = static_cast<int>(nf);
    summary.stitches = static_cast<int>(out.stitches.size());
    summary.min_angle_deg = min_angle;
    summary.mean_edge_cm = edge_count ? edge_sum / edge_count : 0;
    summary.area_cm2 = area;
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return summary;
}

}  // namespace drape::garment
