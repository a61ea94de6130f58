#include <drape/garment/mesh_inside.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>

namespace drape::garment {

struct MeshInsideTest::Grid {
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    double x0 = 0, z0 = 0, x1 = 0, z1 = 0, cell = 1;
    int nx = 1, nz = 1;
    std::vector<std::vector<int>> faces;  // per cell

    int cell_of(double x, double z, int* ix, int* iz) const {
        *ix = std::clamp(int(std::floor((x - x0) / cell)), 0, nx - 1);
        *iz = std::clamp(int(std::floor((z - z0) / cell)), 0, nz - 1);
        return *iz * nx + *ix;
    }
};

MeshInsideTest::MeshInsideTest(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F)
    : grid_(std::make_unique<Grid>()) {
    require(F.rows() > 0 && V.cols() == 3 && F.cols() == 3, "MeshInsideTest: empty mesh or wrong shape");
    require(F.minCoeff() >= 0 && F.maxCoeff() < V.rows(), "MeshInsideTest: face index out of range");
    Grid& g = *grid_;
    g.V = V;
    g.F = F;
    const Eigen::Vector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
    const double area = std::max(1e-12, (hi.x() - lo.x()) * (hi.z() - lo.z()));
    g.cell = std::max(1e-6, std::sqrt(area / std::max<double>(1.0, double(F.rows()) / 4.0)));
    g.x0 = lo.x();
    g.z0 = lo.z();
    g.x1 = hi.x();
    g.z1 = hi.z();
    g.nx = std::max(1, int(std::ceil((hi.x() - lo.x()) / g.cell)) + 1);
    g.nz = std::max(1, int(std::ceil((hi.z() - lo.z()) / g.cell)) + 1);
    g.faces.assign(size_t(g.nx) * size_t(g.nz), {});
    for (int f = 0; f < F.rows(); ++f) {
        double ax = 1e300, az = 1e300, bx = -1e300, bz = -1e300;
        for (int k = 0; k < 3; ++k) {
            ax = std::min(ax, V(F(f, k), 0));
            bx = std::max(bx, V(F(f, k), 0));
            az = std::min(az, V(F(f, k), 2));
            bz = std::max(bz, V(F(f, k), 2));
        }
        int ix0, iz0, ix1, iz1;
        g.cell_of(ax, az, &ix0, &iz0);
        g.cell_of(bx, bz, &ix1, &iz1);
        for (int iz = iz0; iz <= iz1; ++iz)
            for (int ix = ix0; ix <= ix1; ++ix) g.faces[size_t(iz) * g.nx + ix].push_back(f);
    }
}

MeshInsideTest::~MeshInsideTest() = default;
MeshInsideTest::MeshInsideTest(MeshInsideTest&&) noexcept = default;
MeshInsideTest& MeshInsideTest::operator=(MeshInsideTest&&) noexcept = default;

bool MeshInsideTest::inside(const Eigen::Vector3d& point) const {
    const Grid& g = *grid_;
    // A tiny irrational offset keeps the vertical ray off mesh edges and vertices.
    const double px = point.x() + 1.3e-9 * std::sqrt(2.0), pz = point.z() + 0.7e-9 * std::sqrt(3.0);
    if (px < g.x0 || pz < g.z0 || px > g.x1 || pz > g.z1) return false;
    int ix, iz;
    const int c = g.cell_of(px, pz, &ix, &iz);
    int crossings = 0;
    for (int f : g.faces[size_t(c)]) {
        const Eigen::Vector3d a = g.V.row(g.F(f, 0)), b = g.V.row(g.F(f, 1)), d = g.V.row(g.F(f, 2));
        // Barycentric coordinates of (px, pz) in the triangle's (x, z) projection.
        const double det = (b.x() - a.x()) * (d.z() - a.z()) - (d.x() - a.x()) * (b.z() - a.z());
        if (std::abs(det) < 1e-18) continue;
        const double u = ((px - a.x()) * (d.z() - a.z()) - (d.x() - a.x()) * (pz - a.z())) / det;
        const double v = ((b.x() - a.x()) * (pz - a.z()) - (px - a.x()) * (b.z() - a.z())) / det;
        if (u < 0 || v < 0 || u + v > 1) continue;
        const double y = a.y() + u * (b.y() - a.y()) + v * (d.y() - a.y());
        if (y > point.y()) ++crossings;
    }
    return (crossings % 2) == 1;
}

std::vector<bool> MeshInsideTest::inside(const Eigen::MatrixX3d& points) const {
    std::vector<bool> out(size_t(points.rows()));
    for (Eigen::Index i = 0; i < points.rows(); ++i) out[size_t(i)] = inside(Eigen::Vector3d(points.row(i)));
    return out;
}

}  // namespace drape::garment
