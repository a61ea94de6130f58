// generate_mannequin / conform_mannequin: implicit body -> marching tetrahedra ->
// isotropic remeshing -> rig. See mannequin.hpp.
#include "mannequin.hpp"

#include <drape/core/errors.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace drape::body::detail {

namespace {
constexpr double kCellSize = 0.012;   // marching-tetrahedra grid, metres
constexpr int kTargetVertices = 12000;
constexpr int kRemeshIterations = 6;
constexpr int kConformRelaxIterations = 6;
long euler_characteristic(const SurfaceMesh& mesh) {
    std::vector<std::pair<int, int>> edges;
    edges.reserve(3 * mesh.faces.size());
    for (const auto& f : mesh.faces)
        for (size_t q = 0; q < 3; ++q) {
            const int a = f[q], b = f[(q + 1) % 3];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    std::sort(edges.begin(), edges.end());
    const long e = static_cast<long>(std::unique(edges.begin(), edges.end()) - edges.begin());
    return static_cast<long>(mesh.vertices.size()) - e + static_cast<long>(mesh.faces.size());
}

}  // namespace

MannequinMesh generate_mannequin(const MannequinDesign& design) {
    std::string why;
    require(design.is_valid(&why), why);
    const MannequinImplicit body(design);
    // The implicit body is genus 0; a coarse grid could still alias a thin gap (thumb,
    // ears) into a handle, so check the Euler characteristic and refine if needed.
    SurfaceMesh mesh;
    double cell = kCellSize;
    for (int attempt = 0; attempt < 3; ++attempt, cell *= 0.8) {
        mesh = polygonize_implicit(body, cell);
        if (euler_characteristic(mesh) == 2) break;
    }
    require(euler_characteristic(mesh) == 2,
            "generate_mannequin: the design's surface is not a sphere (femininity ",
            design.femininity, ", fat ", design.fat, ", muscle ", design.muscle, ")");
    remesh_on_implicit(body, kTargetVertices, kRemeshIterations, mesh);

    MannequinMesh out;
    out.design = design;
    out.V.resize(static_cast<Eigen::Index>(mesh.vertices.size()), 3);
    for (size_t i = 0; i < mesh.vertices.size(); ++i)
        out.V.row(static_cast<Eigen::Index>(i)) = mesh.vertices[i].transpose();
    out.F.resize(static_cast<Eigen::Index>(mesh.faces.size()), 3);
    for (size_t i = 0; i < mesh.faces.size(); ++i)
        for (int q = 0; q < 3; ++q) out.F(static_cast<Eigen::Index>(i), q) = mesh.faces[i][static_cast<size_t>(q)];

    out.landmarks = mannequin_landmarks(body, out.V);
    JointMatrix joints = body.joints();
    joints.row(index(Joint::head_top)) = out.V.row(out.landmarks.head_top);
    out.joint_regressor =
        mannequin_joint_regressor(body, out.V, out.F, joints, out.landmarks.head_top);
    out.joints = out.joint_regressor * out.V;
    out.skin_weights = mannequin_skin_weights(body, out.V, out.F);
    return out;
}

Eigen::MatrixXd conform_mannequin(const MannequinMesh& base, const MannequinDesign& design) {
    std::string why;
    require(design.is_valid(&why), why);
    require(base.V.rows() > 0 && base.F.rows() > 0, "conform_mannequin: empty base mesh");
    require(base.skin_weights.rows() == base.V.rows() && base.skin_weights.cols() == kJointCount,
            "conform_mannequin: base has no skinning weights");
    const MannequinImplicit body(design);
    const int nv = static_cast<int>(base.V.rows());

    // 1. Skeleton-driven pre-warp: each vertex follows the translation of its bones'
    //    joints from the base design to `design` (shoulder width, hip width...).
    const MannequinImplicit base_body(base.design);
    const JointMatrix shift = body.joints() - base_body.joints();
    Eigen::MatrixXd warped = base.V + Eigen::MatrixXd(base.skin_weights * shift);

    // 2. Move each vertex along its (warped) normal onto the new surface.
    const Eigen::MatrixXd N = mannequin_vertex_normals(warped, base.F);
    Eigen::MatrixXd out(nv, 3);
    parallel_for(nv, [&](int i) {
        const Eigen::Vector3d p = warped.row(i).transpose();
        const Eigen::Vector3d n = N.row(i).transpose();
        // Root of g(t) = value(p + t n) by safeguarded Newton from t = 0.
        double t = 0.0;
        double g = body.value(p);
        bool converged = std::abs(g) < 1e-10;
        const double h = 1e-6;
        for (int it = 0; it < 60 && !converged; ++it) {
            const double dg = (body.value(p + (t + h) * n) - body.value(p + (t - h) * n)) / (2 * h);
            if (dg < 0.05) break;  // the normal line grazes the surface: use the fallback
            double step = -g / dg;
            if (std::abs(step) > 0.02) step = std::copysign(0.02, step);
            t += step;
            g = body.value(p + t * n);
            converged = std::abs(g) < 1e-10;
        }
        Eigen::Vector3d q = p + t * n;
        if (!converged) q = project_onto_implicit(body, q, 40, 1e-10);
        out.row(i) = q.transpose();
    });

    // 3. Tangential relaxation towards the base mesh's local layout (its uniform
    //    Laplacian), re-projected onto the surface: undoes the crowding and folding of
    //    normal projection in creases while staying a smooth function of the design.
    std::vector<std::vector<int>> nbr(static_cast<size_t>(nv));
    for (int f = 0; f < base.F.rows(); ++f)
        for (int q = 0; q < 3; ++q) {
            nbr[static_cast<size_t>(base.F(f, q))].push_back(base.F(f, (q + 1) % 3));
            nbr[static_cast<size_t>(base.F(f, (q + 1) % 3))].push_back(base.F(f, q));
        }
    for (auto& n : nbr) {
        std::sort(n.begin(), n.end());
        n.erase(std::unique(n.begin(), n.end()), n.end());
    }
    auto laplacian = [&](const Eigen::MatrixXd& X, int i) {
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (int j : nbr[static_cast<size_t>(i)]) c += X.row(j).transpose();
        return Eigen::Vector3d(c / static_cast<double>(nbr[static_cast<size_t>(i)].size()) -
                               X.row(i).transpose());
    };
    for (int it = 0; it < kConformRelaxIterations; ++it) {
        const Eigen::MatrixXd normals = mannequin_vertex_normals(out, base.F);
        Eigen::MatrixXd next(nv, 3);
        parallel_for(nv, [&](int i) {
            const Eigen::Vector3d n = normals.row(i).transpose();
            Eigen::Vector3d d = laplacian(out, i) - laplacian(warped, i);
            d -= n.dot(d) * n;
            const Eigen::Vector3d q = out.row(i).transpose() + 0.8 * d;
            next.row(i) = project_onto_implicit(body, q, 20, 1e-10).transpose();
        });
        out.swap(next);
    }
    return out;
}

}  // namespace drape::body::detail
