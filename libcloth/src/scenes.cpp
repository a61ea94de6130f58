#include <drape/cloth/scenes.hpp>

#include <drape/core/errors.hpp>

#include <map>
#include <utility>
#include <vector>

namespace drape::cloth {

TriangleMesh make_icosphere(int subdivisions, double radius_m, const Eigen::Vector3d& centre_m) {
    require(subdivisions >= 0 && subdivisions <= 7, "make_icosphere: subdivisions = ", subdivisions,
            " must be in [0, 7]");
    require(std::isfinite(radius_m) && radius_m > 0, "make_icosphere: radius_m = ", radius_m,
            " must be > 0");
    require(centre_m.allFinite(), "make_icosphere: centre is not finite");
    const double t = (1 + std::sqrt(5.0)) / 2;
    std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                                      {0, -1, t}, {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                                      {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v) p.normalize();
    std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
            const int index = static_cast<int>(v.size()) - 1;
            mid.emplace(key, index);
            return index;
        };
        std::vector<std::array<int, 3>> next;
        next.reserve(4 * f.size());
        for (const auto& tri : f) {
            const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
            next.push_back({tri[0], a, c});
            next.push_back({tri[1], b, a});
            next.push_back({tri[2], c, b});
            next.push_back({a, b, c});
        }
        f = std::move(next);
    }
    TriangleMesh m;
    m.positions.resize(static_cast<Eigen::Index>(v.size()), 3);
    for (std::size_t i = 0; i < v.size(); ++i)
        m.positions.row(static_cast<Eigen::Index>(i)) = (centre_m + radius_m * v[i]).transpose();
    m.faces.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (std::size_t i = 0; i < f.size(); ++i)
        m.faces.row(static_cast<Eigen::Index>(i)) << f[i][0], f[i][1], f[i][2];
    return m;
}

AnchorScene make_anchor_scene(int n) {
    require(n >= 2 && n % 2 == 0, "make_anchor_scene: n = ", n, " must be even and >= 2");
    AnchorScene s;
    // Pattern u along world x, v along world y: the grid lies in z = 0.6, centred on the axis.
    s.cloth = make_square_grid(n, 1.0, Eigen::Vector3d(-0.5, -0.5, 0.6), Eigen::Vector3d::UnitX(),
                               Eigen::Vector3d::UnitY());
    s.sphere = make_icosphere(3, 0.5);
    s.options.time_step_s = 5e-3;
    s.options.gravity_m_per_s2 = Eigen::Vector3d(0, 0, -9.8);
    s.options.cloth_friction = 0.6;
    s.options.obstacle_friction = 0.3;
    s.options.contact_thickness_m = 5e-3;
    s.centre_vertex = (n / 2) * (n + 1) + n / 2;
    return s;
}

}  // namespace drape::cloth
