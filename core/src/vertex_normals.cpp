#include <drape/core/vertex_normals.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace drape::core {

Eigen::MatrixXd vertex_normals(const Eigen::Ref<const Eigen::MatrixXd>& V,
                               const Eigen::Ref<const Eigen::MatrixXi>& F,
                               const VertexNormalOptions& options) {
    Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const Eigen::Vector3d p[3] = {V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(),
                                      V.row(F(f, 2)).transpose()};
        if (options.weighting == NormalWeighting::area) {
            const Eigen::RowVector3d n = (p[1] - p[0]).cross(p[2] - p[0]).transpose();
            for (int c = 0; c < 3; ++c) N.row(F(f, c)) += n;
        } else {
            const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
            for (int c = 0; c < 3; ++c) {
                const Eigen::Vector3d e1 = (p[(c + 1) % 3] - p[c]).normalized();
                const Eigen::Vector3d e2 = (p[(c + 2) % 3] - p[c]).normalized();
                const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
                N.row(F(f, c)) += (angle * n).transpose();
            }
        }
    }
    for (Eigen::Index v = 0; v < N.rows(); ++v) {
        const double length = N.row(v).norm();
        if (length > 0)
            N.row(v) /= length;
        else
            N.row(v) = options.isolated.transpose();
    }
    return N;
}

}  // namespace drape::core
