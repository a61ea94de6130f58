#include <drape/garment/morph_mesh.hpp>

#include <drape/core/errors.hpp>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace drape::garment {

struct PatternMorph::Data {
    Pattern pattern;
    GarmentMesh mesh;
    std::vector<int> boundary;             // boundary vertices
    std::vector<int> interior;             // interior vertices
    std::vector<int> interior_index;       // per vertex: row in the interior system or -1
    Eigen::SparseMatrix<double> to_interior;  // #interior x #boundary: Σ_j w_ij over boundary j
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;  // the interior Laplacian
};

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Signed area (cm²) of face f at panel coordinates p.
double signed_area(const Eigen::MatrixX2d& p, const Eigen::MatrixX3i& faces, Eigen::Index f) {
    const Eigen::Vector2d a = p.row(faces(f, 0)).transpose(), b = p.row(faces(f, 1)).transpose(),
                          c = p.row(faces(f, 2)).transpose();
    return 0.5 * cross2(b - a, c - a);
}

}  // namespace

bool PatternMorph::same_structure(const Pattern& a, const Pattern& b, std::string* why) {
    const auto fail = [&](const std::string& what) {
        if (why) *why = what;
        return false;
    };
    if (a.panels.size() != b.panels.size())
        return fail(drape::detail::concat("the patterns have ", a.panels.size(), " and ", b.panels.size(), " panels"));
    for (size_t p = 0; p < a.panels.size(); ++p) {
        if (a.panels[p].name != b.panels[p].name)
            return fail(drape::detail::concat("panel ", p, " is \"", a.panels[p].name, "\" in one pattern and \"",
                                       b.panels[p].name, "\" in the other"));
        if (a.panels[p].edges.size() != b.panels[p].edges.size())
            return fail(drape::detail::concat("panel \"", a.panels[p].name, "\" has ", a.panels[p].edges.size(), " and ",
                                       b.panels[p].edges.size(), " edges"));
    }
    if (a.seams.size() != b.seams.size())
        return fail(drape::detail::concat("the patterns have ", a.seams.size(), " and ", b.seams.size(), " seams"));
    for (size_t s = 0; s < a.seams.size(); ++s) {
        const Seam &x = a.seams[s], &y = b.seams[s];
        if (x.panel_a != y.panel_a || x.edge_a != y.edge_a || x.panel_b != y.panel_b || x.edge_b != y.edge_b ||
            x.orientation != y.orientation)
            return fail(drape::detail::concat("seam ", s, " joins other edges"));
    }
    return true;
}

PatternMorph::PatternMorph(const Pattern& pattern, const GarmentMesh& mesh) {
    pattern.validate();
    const int nv = mesh.cloth.vertex_count();
    require(mesh.panel_of_vertex.size() == nv && mesh.panel_point_cm.rows() == nv && mesh.boundary_edge.size() == nv &&
                mesh.boundary_fraction.size() == nv,
            "PatternMorph: the mesh's per-vertex arrays do not all have its ", nv, " rows");
    for (int v = 0; v < nv; ++v) {
        const int p = mesh.panel_of_vertex(v);
        require(p >= 0 && size_t(p) < pattern.panels.size(), "PatternMorph: vertex ", v, " is on panel ", p,
                ", the pattern has ", pattern.panels.size());
        const int e = mesh.boundary_edge(v);
        require(e >= -1 && e < int(pattern.panels[size_t(p)].edges.size()), "PatternMorph: vertex ", v,
                " is on edge ", e, " of panel \"", pattern.panels[size_t(p)].name, "\", which has ",
                pattern.panels[size_t(p)].edges.size());
        if (e < 0) continue;
        const double s = mesh.boundary_fraction(v);
        require(s >= 0 && s <= 1, "PatternMorph: vertex ", v, " has boundary fraction ", s, ", outside [0, 1]");
        // A mesh of this pattern has its boundary vertices on the chords of its edges'
        // discretisation, within a few percent of the edge length of the curve.
        const Edge& edge = pattern.panels[size_t(p)].edges[size_t(e)];
        const double off = (mesh.panel_point_cm.row(v).transpose() - edge.point_at_fraction(s)).norm();
        require(off <= 0.05 * edge.length() + 1e-6, "PatternMorph: vertex ", v, " lies ", off,
                " cm from its place on edge ", e, " of panel \"", pattern.panels[size_t(p)].name,
                "\" (fraction ", s, "): the mesh was not made from this pattern");
    }
    auto d = std::make_shared<Data>();
    d->pattern = pattern;
    d->mesh = mesh;
    d->interior_index.assign(size_t(nv), -1);
    std::vector<int> boundary_index(size_t(nv), -1);
    for (int v = 0; v < nv; ++v) {
        if (mesh.boundary_edge(v) >= 0) {
            boundary_index[size_t(v)] = int(d->boundary.size());
            d->boundary.push_back(v);
        } else {
            d->interior_index[size_t(v)] = int(d->interior.size());
            d->interior.push_back(v);
        }
    }
    // Cotangent weights of the original panel-frame mesh: w_ij = ½ (cot α + cot β) over the
    // angles opposite edge ij. The harmonic extension Σ_j w_ij (d_i − d_j) = 0 at interior
    // vertices reproduces affine displacements exactly on a flat mesh.
    const Eigen::MatrixX3i& faces = mesh.cloth.faces;
    std::map<std::pair<int, int>, double> weight;
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int i = faces(f, (c + 1) % 3), j = faces(f, (c + 2) % 3), k = faces(f, c);
            const Eigen::Vector2d a = (mesh.panel_point_cm.row(i) - mesh.panel_point_cm.row(k)).transpose();
            const Eigen::Vector2d b = (mesh.panel_point_cm.row(j) - mesh.panel_point_cm.row(k)).transpose();
            const double twice_area = cross2(a, b);
            require(twice_area > 0, "PatternMorph: face ", f, " of the mesh is degenerate or clockwise");
            weight[{std::min(i, j), std::max(i, j)}] += 0.5 * a.dot(b) / twice_area;
        }
    const int ni = int(d->interior.size()), nb = int(d->boundary.size());
    std::vector<Eigen::Triplet<double>> laplacian, coupling;
    for (const auto& [edge, w] : weight) {
        const int i = edge.first, j = edge.second;
        const int ii = d->interior_index[size_t(i)], ij = d->interior_index[size_t(j)];
        for (const auto& [row, other, other_interior] :
             {std::make_tuple(ii, j, ij), std::make_tuple(ij, i, ii)}) {
            if (row < 0) continue;
            laplacian.emplace_back(row, row, w);
            if (other_interior >= 0) laplacian.emplace_back(row, other_interior, -w);
            else coupling.emplace_back(row, boundary_index[size_t(other)], w);
        }
    }
    Eigen::SparseMatrix<double> l(ni, ni);
    l.setFromTriplets(laplacian.begin(), laplacian.end());
    d->to_interior.resize(ni, nb);
    d->to_interior.setFromTriplets(coupling.begin(), coupling.end());
    if (ni > 0) {
        d->solver.compute(l);
        require(d->solver.info() == Eigen::Success, "PatternMorph: the interior Laplacian of the mesh is singular");
    }
    data_ = std::move(d);
}

Eigen::MatrixX2d PatternMorph::panel_points_cm(const Pattern& new_pattern) const {
    const Data& d = *data_;
    std::string why;
    require(new_pattern.is_valid(&why), "PatternMorph: the new pattern is invalid: ", why);
    require(same_structure(d.pattern, new_pattern, &why), "PatternMorph: cannot morph \"", d.pattern.name, "\" to \"",
            new_pattern.name, "\": ", why, "; re-mesh the new pattern (mesh_pattern) instead");
    const GarmentMesh& m = d.mesh;
    Eigen::MatrixX2d displacement(m.cloth.vertex_count(), 2);
    Eigen::MatrixX2d boundary(Eigen::Index(d.boundary.size()), 2);
    for (size_t k = 0; k < d.boundary.size(); ++k) {
        const int v = d.boundary[k];
        const size_t p = size_t(m.panel_of_vertex(v)), e = size_t(m.boundary_edge(v));
        const double s = m.boundary_fraction(v);
        boundary.row(Eigen::Index(k)) = (new_pattern.panels[p].edges[e].point_at_fraction(s) -
                                         d.pattern.panels[p].edges[e].point_at_fraction(s))
                                            .transpose();
        displacement.row(v) = boundary.row(Eigen::Index(k));
    }
    if (!d.interior.empty()) {
        const Eigen::MatrixX2d inner = d.solver.solve(Eigen::MatrixX2d(d.to_interior * boundary));
        for (size_t k = 0; k < d.interior.size(); ++k) displacement.row(d.interior[k]) = inner.row(Eigen::Index(k));
    }
    Eigen::MatrixX2d out = m.panel_point_cm + displacement;
    // The simulator's bound on a pattern triangle (1e-12 m²) in cm².
    for (Eigen::Index f = 0; f < m.cloth.faces.rows(); ++f) {
        const double a = signed_area(out, m.cloth.faces, f);
        require(a > 1e-8, "PatternMorph: face ", f, " (panel \"",
                d.pattern.panels[size_t(m.panel_of_vertex(m.cloth.faces(f, 0)))].name,
                "\") inverts or degenerates when morphed to \"", new_pattern.name, "\" (signed area ", a,
                " cm²): the sizing changed too much for this mesh; re-mesh the new pattern (mesh_pattern)");
    }
    return out;
}

GarmentMesh PatternMorph::morph(const Pattern& new_pattern) const {
    const Eigen::MatrixX2d points = panel_points_cm(new_pattern);
    GarmentMesh out = data_->mesh;
    const std::vector<Eigen::Vector2d> offsets = layout_offsets(new_pattern);
    Eigen::MatrixX2d layout(points.rows(), 2);
    for (Eigen::Index v = 0; v < points.rows(); ++v) {
        const size_t p = size_t(out.panel_of_vertex(v));
        const Eigen::Vector2d q = points.row(v).transpose();
        out.cloth.positions.row(v) = new_pattern.placements[p].to_world_m(q).transpose();
        layout.row(v) = 0.01 * (q + offsets[p]).transpose();
    }
    // As mesh_pattern: per-vertex pattern, uv = the layout scaled into [0, 1]².
    out.panel_point_cm = points;
    out.cloth.pattern = layout;
    const Eigen::Vector2d extent = layout.colwise().maxCoeff().transpose();
    out.uv = layout / std::max(extent.maxCoeff(), 1e-12);
    return out;
}

const Pattern& PatternMorph::pattern() const { return data_->pattern; }
const GarmentMesh& PatternMorph::mesh() const { return data_->mesh; }

}  // namespace drape::garment
