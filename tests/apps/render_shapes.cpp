#include "render_shapes.hpp"

#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace drape::test {

render::Mesh icosphere(const Eigen::Vector3d& centre, double radius, int level, int label) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (auto& p : v) p.normalize();
    for (int l = 0; l < level; ++l) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            const auto key = std::minmax(a, b);
            const auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back((v[a] + v[b]).normalized());
            return mid[key] = static_cast<int>(v.size()) - 1;
        };
        std::vector<Eigen::Vector3i> next;
        for (const auto& tri : f) {
            const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
            next.insert(next.end(), {{tri[0], a, c}, {tri[1], b, a}, {tri[2], c, b}, {a, b, c}});
        }
        f = std::move(next);
    }
    render::Mesh m;
    m.name = "sphere";
    m.V.resize(static_cast<Eigen::Index>(v.size()), 3);
    m.N.resize(m.V.rows(), 3);
    for (size_t i = 0; i < v.size(); ++i) {
        m.N.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
        m.V.row(static_cast<Eigen::Index>(i)) = (centre + radius * v[i]).transpose();
    }
    m.F.resize(static_cast<Eigen::Index>(f.size()), 3);
    for (size_t i = 0; i < f.size(); ++i) m.F.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
    m.label = label;
    return m;
}

render::Mesh square(double half, int label) {
    render::Mesh m;
    m.name = "square";
    m.V.resize(4, 3);
    m.V << -half, -half, 0, half, -half, 0, half, half, 0, -half, half, 0;
    m.F.resize(2, 3);
    m.F << 0, 1, 2, 0, 2, 3;
    m.UV = m.V.leftCols(2);
    m.label = label;
    return m;
}

}  // namespace drape::test
