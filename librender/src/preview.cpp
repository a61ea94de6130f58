#include <drape/render/preview.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace drape::render {

namespace {

constexpr double kPi = 3.14159265358979323846;

void require_points(const Eigen::MatrixXd& V, const char* who) {
    require(V.rows() > 0 && V.cols() == 3, who, ": the body must be #B x 3 with B > 0, got ", V.rows(), " x ",
            V.cols());
}

}  // namespace

Scene preview_scene(const Eigen::MatrixXd& body_V, const Eigen::MatrixXi& body_F,
                    const std::vector<PreviewGarment>& garments) {
    require_points(body_V, "preview_scene");
    Scene scene;
    Mesh b;
    b.name = "body";
    b.V = body_V;
    b.F = body_F;
    b.material.colour_srgb = {0.80, 0.74, 0.67};
    b.material.roughness = 0.55;
    scene.meshes.push_back(std::move(b));
    const std::array<Eigen::Vector3d, 3> colours = {Eigen::Vector3d(0.20, 0.33, 0.62), Eigen::Vector3d(0.66, 0.33, 0.22),
                                                    Eigen::Vector3d(0.42, 0.47, 0.25)};
    double floor_y = body_V.col(1).minCoeff();
    for (size_t k = 0; k < garments.size(); ++k) {
        Mesh g;
        g.name = "garment" + std::to_string(k);
        g.V = garments[k].V;
        g.F = garments[k].F;
        g.UV = garments[k].UV;
        g.material.colour_srgb = colours[k % colours.size()];
        g.material.roughness = 0.85;
        g.smooth_subdivisions = kSimulatedGarmentSubdivisions;
        if (g.V.rows() > 0) floor_y = std::min(floor_y, g.V.col(1).minCoeff());
        scene.meshes.push_back(std::move(g));
    }
    scene.floor.enabled = true;
    scene.floor.height_m = floor_y;
    return scene;
}

Camera preview_camera(const Eigen::MatrixXd& body_V, int width_px, int height_px) {
    require_points(body_V, "preview_camera");
    require(width_px > 0 && height_px > 0, "preview_camera: image size must be positive, got ", width_px, " x ",
            height_px);
    const Eigen::Vector3d lo = body_V.colwise().minCoeff(), hi = body_V.colwise().maxCoeff();
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    const double focal = 0.5 * height_px / std::tan(15.0 * kPi / 180.0);  // 30° vertical view
    const double dist = 1.15 * (hi.y() - lo.y()) * focal / height_px;
    const Eigen::Vector3d eye = centre + dist * Eigen::Vector3d(0.35, 0.05, 1.0).normalized();
    return Camera::look_at(eye, centre, {0, 1, 0}, focal, width_px, height_px);
}

Camera front_camera(const Scene& scene, int width_px, int height_px) {
    require(!scene.meshes.empty(), "front_camera: the scene has no mesh");
    require(width_px > 0 && height_px > 0, "front_camera: image size must be positive, got ", width_px, " x ",
            height_px);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
    for (const Mesh& m : scene.meshes) {
        lo = lo.cwiseMin(m.V.colwise().minCoeff().transpose());
        hi = hi.cwiseMax(m.V.colwise().maxCoeff().transpose());
    }
    const double tan_half = std::tan(15.0 * kPi / 180.0);
    const double focal = 0.5 * height_px / tan_half;
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    const double need_h = 1.12 * (hi.y() - lo.y()), need_w = 1.12 * (hi.x() - lo.x());
    const double dist =
        std::max(need_h * focal / height_px, need_w * focal / width_px) + 0.5 * (hi.z() - lo.z());
    return Camera::look_at({centre.x(), centre.y(), hi.z() + dist}, centre, {0, 1, 0}, focal, width_px, height_px);
}

}  // namespace drape::render
