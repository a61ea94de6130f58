#include <drape/cloth/local_curvature.hpp>

#include <drape/cloth/energies.hpp>
#include <drape/core/errors.hpp>

#include <Eigen/Geometry>

#include <cmath>

namespace drape::cloth {

Eigen::Vector4d hinge_local_curvature(const Eigen::Matrix<double, 3, 4>& x) {
    const Eigen::Vector3d e = x.col(1) - x.col(0);
    const double len = e.norm();
    const double area2_0 = e.cross(x.col(2) - x.col(0)).norm();  // |N1| = 2 A1 = |e| h1
    const double area2_1 = (x.col(3) - x.col(0)).cross(e).norm();
    if (!(len > 0 && area2_0 > 0 && area2_1 > 0)) return Eigen::Vector4d::Zero();
    const double heights = (area2_0 + area2_1) / len;
    const double factor = std::abs(std::sin(0.5 * dihedral_angle(x))) * len / heights;
    const Vector12d modes = dihedral_angle_gradient(x);
    Eigen::Vector4d kappa;
    for (int i = 0; i < 4; ++i) kappa(i) = factor * modes.segment<3>(3 * i).norm();
    return kappa;
}

Eigen::VectorXd vertex_local_curvature(const ClothMesh& mesh, const std::vector<Hinge>& hinges,
                                       const Eigen::MatrixX3d& positions) {
    require(positions.rows() == mesh.vertex_count(), "vertex_local_curvature: positions has ",
            positions.rows(), " rows, the mesh ", mesh.vertex_count(), " vertices");
    require(positions.allFinite(), "vertex_local_curvature: positions are not finite");
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(positions.rows());
    Eigen::VectorXd count = Eigen::VectorXd::Zero(positions.rows());
    for (const Hinge& h : hinges) {
        Eigen::Matrix<double, 3, 4> x;
        for (int c = 0; c < 4; ++c) {
            const int v = h.v[static_cast<std::size_t>(c)];
            require(v >= 0 && v < positions.rows(), "vertex_local_curvature: hinge vertex ", v,
                    " is out of range");
            x.col(c) = positions.row(v).transpose();
        }
        const Eigen::Vector4d k = hinge_local_curvature(x);
        for (int c = 0; c < 4; ++c) {
            sum(h.v[static_cast<std::size_t>(c)]) += k(c);
            count(h.v[static_cast<std::size_t>(c)]) += 1;
        }
    }
    return (count.array() > 0).select(sum.array() / count.array().max(1.0), 0.0).matrix();
}

double mean_local_curvature(const Eigen::VectorXd& kappa, const std::vector<int>& vertices) {
    require(!vertices.empty(), "mean_local_curvature: vertices is empty");
    double sum = 0;
    for (int v : vertices) {
        require(v >= 0 && v < kappa.size(), "mean_local_curvature: vertex ", v,
                " is out of range [0, ", kappa.size(), ")");
        sum += kappa(v);
    }
    return sum / static_cast<double>(vertices.size());
}

}  // namespace drape::cloth
