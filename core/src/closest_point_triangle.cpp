#include <drape/core/closest_point_triangle.hpp>

namespace drape::core {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                          TriangleFeature* feature, Eigen::Vector3d* weights) {
    // Records the feature and the weights of b and c (a's is the rest).
    const auto found = [feature, weights](TriangleFeature f, double wb, double wc) {
        if (feature) *feature = f;
        if (weights) *weights << 1 - wb - wc, wb, wc;
    };
    const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) {
        found(TriangleFeature::vertex_a, 0, 0);
        return a;
    }
    const Eigen::Vector3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) {
        found(TriangleFeature::vertex_b, 1, 0);
        return b;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double t = d1 / (d1 - d3);
        found(TriangleFeature::edge_ab, t, 0);
        return a + t * ab;
    }
    const Eigen::Vector3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) {
        found(TriangleFeature::vertex_c, 0, 1);
        return c;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double t = d2 / (d2 - d6);
        found(TriangleFeature::edge_ca, 0, t);
        return a + t * ac;
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        found(TriangleFeature::edge_bc, 1 - t, t);
        return b + t * (c - b);
    }
    const double denom = 1 / (va + vb + vc);
    found(TriangleFeature::interior, vb * denom, vc * denom);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace drape::core
