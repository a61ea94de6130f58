#include "fit_kinematics.hpp"

#include <drape/core/errors.hpp>

namespace drape::body::detail {

Eigen::VectorXd semantic_to_coefficients(const BodyModel& model, Gender gender,
                                         const Eigen::Matrix<double, kSemanticCount, 1>& z) {
    const SemanticMap& map = model.semantic_map;
    Eigen::Matrix<double, 1 + kSemanticCount, 1> v;
    v[0] = gender == Gender::female ? 1.0 : 0.0;
    v.tail<kSemanticCount>() = z;
    return map.A * (v - map.reference) + map.b;
}

LinearRest make_linear_rest(const BodyModel& model, Gender gender,
                            const std::vector<int>& vertex_ids) {
    const SemanticMap& map = model.semantic_map;
    const int K = model.shape_count();
    require(map.A.rows() == K && map.A.cols() == 1 + kSemanticCount && map.b.size() == K,
            "fit_body: the model's semantic map must be ", K, " x ", 1 + kSemanticCount,
            " with a bias of ", K, ", got ", map.A.rows(), " x ", map.A.cols(), " and ",
            map.b.size());
    // c = Cz z + c0
    const Eigen::MatrixXd Cz = map.A.rightCols(kSemanticCount);
    const Eigen::VectorXd c0 =
        semantic_to_coefficients(model, gender, Eigen::Matrix<double, kSemanticCount, 1>::Zero());

    LinearRest out;
    const int V = model.vertex_count();
    for (int d = 0; d < 3; ++d) {
        Eigen::MatrixXd Zd(V, K);  // coordinate d of every vertex
        for (int v = 0; v < V; ++v) Zd.row(v) = model.shape_basis.row(3 * v + d);
        const Eigen::VectorXd base = model.template_vertices.col(d) + Zd * c0;
        const Eigen::VectorXd jb = model.joint_regressor * base;
        const Eigen::MatrixXd jz = (model.joint_regressor * Zd) * Cz;
        for (int j = 0; j < kJointCount; ++j) {
            out.joint_offset[3 * j + d] = jb[j];
            out.joint_jacobian.row(3 * j + d) = jz.row(j);
        }
    }
    out.vertex_ids = vertex_ids;
    const int n = static_cast<int>(vertex_ids.size());
    out.vertex_offset.resize(3 * n);
    out.vertex_jacobian.resize(3 * n, kSemanticCount);
    const Eigen::SparseMatrix<double, Eigen::RowMajor> W = model.skin_weights;
    out.weight_start.push_back(0);
    for (int k = 0; k < n; ++k) {
        const int v = vertex_ids[static_cast<size_t>(k)];
        require(v >= 0 && v < V, "fit_body: vertex id ", v, " out of range");
        for (int d = 0; d < 3; ++d) {
            const Eigen::RowVectorXd zrow = model.shape_basis.row(3 * v + d);
            out.vertex_offset[3 * k + d] = model.template_vertices(v, d) + zrow.dot(c0);
            out.vertex_jacobian.row(3 * k + d) = zrow * Cz;
        }
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(W, v); it; ++it) {
            if (it.value() == 0) continue;
            out.weight_joint.push_back(static_cast<int>(it.col()));
            out.weight_value.push_back(it.value());
        }
        out.weight_start.push_back(static_cast<int>(out.weight_joint.size()));
    }
    return out;
}

}  // namespace drape::body::detail
