#include <drape/body/body_model.hpp>

#include <drape/core/errors.hpp>

#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace drape::body {

namespace {

bool fail(std::string* why, const std::string& message) {
    if (why) *why = message;
    return false;
}

}  // namespace

bool BodyModel::is_valid(std::string* why) const {
    const Eigen::Index nv = template_vertices.rows();
    if (nv < 4 || template_vertices.cols() != 3)
        return fail(why, "template_vertices must be #V x 3 with #V >= 4, got " +
                             std::to_string(nv) + " x " + std::to_string(template_vertices.cols()));
    if (!template_vertices.allFinite()) return fail(why, "template_vertices has non-finite values");
    if (faces.rows() < 4 || faces.cols() != 3) return fail(why, "faces must be #F x 3 with #F >= 4");
    if (faces.minCoeff() < 0 || faces.maxCoeff() >= nv)
        return fail(why, "faces index a vertex outside [0, " + std::to_string(nv - 1) + "]");
    // Closed 2-manifold: every directed edge appears once and its twin once.
    std::map<std::pair<int, int>, int> directed;
    for (Eigen::Index f = 0; f < faces.rows(); ++f)
        for (int e = 0; e < 3; ++e) {
            const int a = faces(f, e), b = faces(f, (e + 1) % 3);
            if (a == b) return fail(why, "face " + std::to_string(f) + " is degenerate");
            if (++directed[{a, b}] > 1)
                return fail(why, "edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                     ") is used twice in the same direction: the mesh is not a "
                                     "consistently oriented manifold");
        }
    for (const auto& [edge, count] : directed)
        if (!directed.count({edge.second, edge.first}))
            return fail(why, "edge (" + std::to_string(edge.first) + ", " +
                                 std::to_string(edge.second) + ") has no twin: the mesh is not closed");
    if (shape_basis.rows() != 3 * nv)
        return fail(why, "shape_basis must have 3#V = " + std::to_string(3 * nv) + " rows, got " +
                             std::to_string(shape_basis.rows()));
    if (!shape_basis.allFinite()) return fail(why, "shape_basis has non-finite values");
    if (static_cast<Eigen::Index>(shape_names.size()) != shape_basis.cols())
        return fail(why, "shape_names has " + std::to_string(shape_names.size()) +
                             " entries for " + std::to_string(shape_basis.cols()) + " basis columns");
    if (!template_joints.allFinite()) return fail(why, "template_joints has non-finite values");
    if (joint_regressor.rows() != kJointCount || joint_regressor.cols() != nv)
        return fail(why, "joint_regressor must be " + std::to_string(kJointCount) + " x #V");
    const Eigen::VectorXd reg_sums = joint_regressor * Eigen::VectorXd::Ones(nv);
    for (int j = 0; j < kJointCount; ++j)
        if (std::abs(reg_sums[j] - 1.0) > 1e-6)
            return fail(why, "joint_regressor row of joint '" + std::string(kJointNames[j]) +
                                 "' sums to " + std::to_string(reg_sums[j]) + ", not 1");
    if (skin_weights.rows() != nv || skin_weights.cols() != kJointCount)
        return fail(why, "skin_weights must be #V x " + std::to_string(kJointCount));
    const Eigen::VectorXd w_sums = skin_weights * Eigen::VectorXd::Ones(kJointCount);
    for (Eigen::Index v = 0; v < nv; ++v)
        if (std::abs(w_sums[v] - 1.0) > 1e-6)
            return fail(why, "skin weights of vertex " + std::to_string(v) + " sum to " +
                                 std::to_string(w_sums[v]) + ", not 1");
    for (int k = 0; k < skin_weights.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(skin_weights, k); it; ++it)
            if (!(it.value() >= 0)) return fail(why, "skin weights must be non-negative");
    const int K = static_cast<int>(shape_basis.cols());
    if (semantic_map.A.rows() != K || semantic_map.A.cols() != 1 + kSemanticCount ||
        semantic_map.b.size() != K || semantic_map.refinable.size() != K)
        return fail(why, "semantic_map must be A: K x " + std::to_string(1 + kSemanticCount) +
                             ", b: K and refinable: K with K = " + std::to_string(K));
    if (!semantic_map.A.allFinite() || !semantic_map.b.allFinite())
        return fail(why, "semantic_map has non-finite values");
    if (!(density_kg_m3 > 0) || !std::isfinite(density_kg_m3))
        return fail(why, "density_kg_m3 must be positive");
    return true;
}

ShapedBody shape_from_coefficients(const BodyModel& model, const Eigen::VectorXd& c) {
    require(c.size() == model.shape_count(), "shape coefficients: expected ", model.shape_count(),
            " values, got ", c.size());
    require(c.allFinite(), "shape coefficients are not finite");
    ShapedBody out;
    out.coefficients = c;
    const Eigen::VectorXd flat = model.shape_basis * c;
    out.vertices = model.template_vertices +
                   Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
                       flat.data(), model.vertex_count(), 3);
    out.joints = model.joint_regressor * out.vertices;
    return out;
}

std::vector<int> dominant_joints(const BodyModel& model) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> W = model.skin_weights;
    std::vector<int> dominant(static_cast<std::size_t>(W.rows()), -1);
    for (Eigen::Index v = 0; v < W.rows(); ++v) {
        double w = 0;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(W, v); it; ++it)
            if (it.value() > w) w = it.value(), dominant[static_cast<std::size_t>(v)] = static_cast<int>(it.col());
    }
    return dominant;
}

}  // namespace drape::body
