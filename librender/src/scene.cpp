#include <drape/render/scene.hpp>

#include <drape/core/errors.hpp>
#include <drape/core/vertex_normals.hpp>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "sampling.hpp"

namespace drape::render {

Floor::Floor() { material.colour_srgb = {0.62, 0.58, 0.53}; material.roughness = 1.0; }

Backdrop::Backdrop() { material.colour_srgb = {0.80, 0.80, 0.80}; material.roughness = 1.0; }

void validate_mesh(const Mesh& m, std::size_t index) {
    const std::string who = "render mesh " + std::to_string(index) +
                            (m.name.empty() ? std::string() : " ('" + m.name + "')");
    require(m.V.cols() == 3 && m.V.rows() > 0, who, ": V must be #V x 3 with #V > 0, got ",
            m.V.rows(), " x ", m.V.cols());
    require(m.F.cols() == 3 && m.F.rows() > 0, who, ": F must be #F x 3 with #F > 0 (no triangles), got ",
            m.F.rows(), " x ", m.F.cols());
    for (Eigen::Index i = 0; i < m.V.rows(); ++i)
        require(m.V.row(i).allFinite(), who, ": vertex ", i, " is not finite (", m.V.row(i), ")");
    require(m.F.minCoeff() >= 0 && m.F.maxCoeff() < m.V.rows(), who,
            ": face indices must be in [0, ", m.V.rows() - 1, "], got [", m.F.minCoeff(), ", ",
            m.F.maxCoeff(), "]");
    require(m.N.size() == 0 || (m.N.rows() == m.V.rows() && m.N.cols() == 3 && m.N.allFinite()), who,
            ": N must be empty or #V x 3 finite normals, got ", m.N.rows(), " x ", m.N.cols());
    require(m.UV.size() == 0 || (m.UV.rows() == m.V.rows() && m.UV.cols() == 2 && m.UV.allFinite()),
            who, ": UV must be empty or #V x 2 finite coordinates, got ", m.UV.rows(), " x ",
            m.UV.cols());
    require(m.label >= 0 && m.label <= 255, who, ": label must be in 0..255, got ", m.label);
    require(m.smooth_subdivisions >= 0 && m.smooth_subdivisions <= 4, who,
            ": smooth_subdivisions must be in 0..4, got ", m.smooth_subdivisions);
    std::string why;
    require(m.material.is_valid(&why), who, ": material: ", why);
}

namespace {

/// A strip of quads along a 2D profile (z, y) extruded along x in [-half_width, half_width].
Mesh extrude_profile(const std::vector<Eigen::Vector2d>& profile_zy, double half_width) {
    const int n = static_cast<int>(profile_zy.size());
    Mesh m;
    m.V.resize(2 * n, 3);
    m.UV.resize(2 * n, 2);
    double arc = 0.0;
    for (int i = 0; i < n; ++i) {
        if (i > 0) arc += (profile_zy[i] - profile_zy[i - 1]).norm();
        for (int side = 0; side < 2; ++side) {
            const double x = side == 0 ? -half_width : half_width;
            m.V.row(2 * i + side) << x, profile_zy[i].y(), profile_zy[i].x();
            m.UV.row(2 * i + side) << x, -arc;
        }
    }
    m.F.resize(2 * (n - 1), 3);
    for (int i = 0; i + 1 < n; ++i) {
        const int a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
        m.F.row(2 * i) << a, c, b;
        m.F.row(2 * i + 1) << b, c, d;
    }
    m.N = core::vertex_normals(m.V, m.F);
    return m;
}

}  // namespace

void Scene::validate() const {
    require(!meshes.empty() || floor.enabled || backdrop.enabled,
            "render scene is empty: no meshes, no floor, no backdrop");
    for (size_t i = 0; i < meshes.size(); ++i) validate_mesh(meshes[i], i);
    std::string why;
    if (floor.enabled) {
        require(std::isfinite(floor.height_m), "render floor height_m is not finite");
        require(floor.material.is_valid(&why), "render floor material: ", why);
        require(floor.label >= 0 && floor.label <= 255, "render floor label must be in 0..255, got ",
                floor.label);
    }
    if (backdrop.enabled) {
        require(std::isfinite(backdrop.distance_m) && std::isfinite(backdrop.cove_radius_m) &&
                    std::isfinite(backdrop.height_m) && backdrop.cove_radius_m >= 0 &&
                    backdrop.height_m > backdrop.cove_radius_m,
                "render backdrop: need finite distance_m, cove_radius_m >= 0 and height_m > "
                "cove_radius_m, got ", backdrop.distance_m, ", ", backdrop.cove_radius_m, ", ",
                backdrop.height_m);
        require(backdrop.material.is_valid(&why), "render backdrop material: ", why);
        require(backdrop.label >= 0 && backdrop.label <= 255,
                "render backdrop label must be in 0..255, got ", backdrop.label);
    }
}

Mesh phong_tessellate(const Mesh& mesh, int levels, double alpha) {
    require(levels >= 0, "phong_tessellate: levels must be >= 0, got ", levels);
    require(alpha >= 0 && alpha <= 1, "phong_tessellate: alpha must be in [0, 1], got ", alpha);
    Mesh m = mesh;
    if (m.N.size() == 0) {
        // Normals of the mesh with coincident vertices merged (the two sides of a seam).
        std::map<std::array<double, 3>, int> group_of;
        std::vector<int> group(static_cast<std::size_t>(m.V.rows()));
        for (Eigen::Index i = 0; i < m.V.rows(); ++i)
            group[static_cast<std::size_t>(i)] =
                group_of.emplace(std::array<double, 3>{m.V(i, 0), m.V(i, 1), m.V(i, 2)}, int(group_of.size()))
                    .first->second;
        Eigen::MatrixXi Fg = m.F;
        for (Eigen::Index f = 0; f < Fg.rows(); ++f)
            for (int k = 0; k < 3; ++k) Fg(f, k) = group[static_cast<std::size_t>(m.F(f, k))];
        Eigen::MatrixXd Vg(static_cast<Eigen::Index>(group_of.size()), 3);
        for (Eigen::Index i = 0; i < m.V.rows(); ++i) Vg.row(group[static_cast<std::size_t>(i)]) = m.V.row(i);
        const Eigen::MatrixXd Ng = core::vertex_normals(Vg, Fg);
        m.N.resize(m.V.rows(), 3);
        for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.N.row(i) = Ng.row(group[static_cast<std::size_t>(i)]);
    }
    const bool uv = m.UV.size() != 0;
    for (int level = 0; level < levels; ++level) {
        std::vector<Eigen::Vector3d> V, N;
        std::vector<Eigen::Vector2d> UV;
        for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
            V.push_back(m.V.row(i).transpose());
            N.push_back(m.N.row(i).transpose());
            if (uv) UV.push_back(m.UV.row(i).transpose());
        }
        // A midpoint is a symmetric function of its ends' positions and normals (IEEE sums
        // commute), so coincident edges (the two sides of a seam) get the same point.
        std::map<std::pair<int, int>, int> index_of;
        const auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            if (const auto it = index_of.find(key); it != index_of.end()) return it->second;
            const Eigen::Vector3d pa = V[static_cast<std::size_t>(a)], pb = V[static_cast<std::size_t>(b)];
            const Eigen::Vector3d na = N[static_cast<std::size_t>(a)], nb = N[static_cast<std::size_t>(b)];
            const Eigen::Vector3d p = 0.5 * (pa + pb);
            const Eigen::Vector3d pia = p - (p - pa).dot(na) * na, pib = p - (p - pb).dot(nb) * nb;
            V.push_back((1 - alpha) * p + alpha * 0.5 * (pia + pib));
            const Eigen::Vector3d n = na + nb;
            N.push_back(n.norm() > 1e-12 ? Eigen::Vector3d(n.normalized()) : na);
            if (uv) UV.push_back(0.5 * (UV[static_cast<std::size_t>(a)] + UV[static_cast<std::size_t>(b)]));
            return index_of[key] = static_cast<int>(V.size()) - 1;
        };
        Eigen::MatrixXi F(4 * m.F.rows(), 3);
        for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
            const int i0 = m.F(f, 0), i1 = m.F(f, 1), i2 = m.F(f, 2);
            const int a = midpoint(i0, i1), b = midpoint(i1, i2), c = midpoint(i2, i0);
            F.row(4 * f) << i0, a, c;
            F.row(4 * f + 1) << i1, b, a;
            F.row(4 * f + 2) << i2, c, b;
            F.row(4 * f + 3) << a, b, c;
        }
        m.F = F;
        m.V.resize(static_cast<Eigen::Index>(V.size()), 3);
        m.N.resize(m.V.rows(), 3);
        if (uv) m.UV.resize(m.V.rows(), 2);
        for (std::size_t i = 0; i < V.size(); ++i) {
            m.V.row(static_cast<Eigen::Index>(i)) = V[i].transpose();
            m.N.row(static_cast<Eigen::Index>(i)) = N[i].transpose();
            if (uv) m.UV.row(static_cast<Eigen::Index>(i)) = UV[i].transpose();
        }
    }
    m.smooth_subdivisions = 0;
    return m;
}

std::vector<Mesh> stage_meshes(const Scene& scene) {
    constexpr double kHalfWidth = 20.0, kFront = 20.0;
    std::vector<Mesh> out;
    const double y0 = scene.floor.enabled ? scene.floor.height_m : 0.0;
    if (scene.floor.enabled && scene.backdrop.enabled) {
        // One sweep: floor from the front to the cove, a quarter circle, then the wall.
        const Backdrop& b = scene.backdrop;
        const double r = b.cove_radius_m, zw = -b.distance_m;
        std::vector<Eigen::Vector2d> profile{{kFront, y0}, {zw + r, y0}};
        constexpr int kArc = 24;
        for (int i = 1; i <= kArc; ++i) {
            const double t = 0.5 * detail::kPi * i / kArc;  // 0: floor tangent, pi/2: wall tangent
            profile.emplace_back(zw + r - r * std::sin(t), y0 + r - r * std::cos(t));
        }
        profile.emplace_back(zw, y0 + b.height_m);
        Mesh m = extrude_profile(profile, kHalfWidth);
        m.name = "stage";
        // Floor and wall keep their own materials: split the sweep at the cove's middle.
        Mesh floor = m, wall = m;
        const int quads = static_cast<int>(profile.size()) - 1, split = 1 + kArc / 2;
        floor.F = m.F.topRows(2 * split);
        wall.F = m.F.bottomRows(2 * (quads - split));
        floor.material = scene.floor.material;
        floor.label = scene.floor.label;
        floor.name = "floor";
        wall.material = b.material;
        wall.label = b.label;
        wall.name = "backdrop";
        out.push_back(std::move(floor));
        out.push_back(std::move(wall));
    } else if (scene.floor.enabled) {
        Mesh m = extrude_profile({{kFront, y0}, {-kFront, y0}}, kHalfWidth);
        m.material = scene.floor.material;
        m.label = scene.floor.label;
        m.name = "floor";
        out.push_back(std::move(m));
    } else if (scene.backdrop.enabled) {
        const double zw = -scene.backdrop.distance_m;
        Mesh m = extrude_profile({{zw, -kFront}, {zw, kFront}}, kHalfWidth);
        m.material = scene.backdrop.material;
        m.label = scene.backdrop.label;
        m.name = "backdrop";
        out.push_back(std::move(m));
    }
    return out;
}

}  // namespace drape::render
