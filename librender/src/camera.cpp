#include <drape/render/camera.hpp>

#include <drape/core/errors.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>

namespace drape::render {

namespace {

void require_size(int width_px, int height_px, const char* who) {
    require(width_px > 0 && height_px > 0, who, ": image size must be positive, got ", width_px,
            " x ", height_px, " pixels");
    require(width_px <= 32768 && height_px <= 32768, who, ": image size above 32768 pixels: ",
            width_px, " x ", height_px);
}

}  // namespace

Camera Camera::look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                       const Eigen::Vector3d& up, double focal_px, int width_px, int height_px) {
    require_size(width_px, height_px, "Camera::look_at");
    require(eye.allFinite() && target.allFinite() && up.allFinite(),
            "Camera::look_at: eye, target and up must be finite");
    require(std::isfinite(focal_px) && focal_px > 0,
            "Camera::look_at: focal_px must be a positive number, got ", focal_px);
    const Eigen::Vector3d view = target - eye;
    require(view.norm() > 1e-12, "Camera::look_at: eye and target coincide at ", eye.transpose());
    const Eigen::Vector3d forward = view.normalized();
    const Eigen::Vector3d right_raw = forward.cross(up);
    require(right_raw.norm() > 1e-9 * std::max(1.0, up.norm()),
            "Camera::look_at: up (", up.transpose(), ") is zero or parallel to the view direction");
    const Eigen::Vector3d right = right_raw.normalized();
    const Eigen::Vector3d down = forward.cross(right);
    Camera c;
    c.projection = Projection::perspective;
    c.width_px = width_px;
    c.height_px = height_px;
    c.focal_px = focal_px;
    c.principal_px = {0.5 * width_px, 0.5 * height_px};
    c.eye = eye;
    c.world_to_camera.row(0) = right.transpose();
    c.world_to_camera.row(1) = down.transpose();
    c.world_to_camera.row(2) = forward.transpose();
    return c;
}

Camera Camera::from_body(const body::Camera& camera, int width_px, int height_px) {
    require_size(width_px, height_px, "Camera::from_body");
    std::string why;
    require(camera.is_valid(&why), "Camera::from_body: ", why);
    Camera c;
    c.width_px = width_px;
    c.height_px = height_px;
    c.principal_px = camera.offset_px;
    c.eye = {0.0, 0.0, camera.distance_m};
    c.world_to_camera << 1, 0, 0, 0, -1, 0, 0, 0, -1;
    if (camera.model == body::CameraModel::pinhole) {
        c.projection = Projection::perspective;
        c.focal_px = camera.focal_px;
    } else {
        c.projection = Projection::orthographic;
        c.scale_px_per_m = camera.scale_px_per_m;
        require(std::isfinite(camera.distance_m) && camera.distance_m > 0,
                "Camera::from_body: distance_m must be a positive number, got ", camera.distance_m);
    }
    return c;
}

Ray Camera::ray(double u_px, double v_px) const {
    const Eigen::Vector2d d = Eigen::Vector2d(u_px, v_px) - principal_px;
    if (projection == Projection::perspective) {
        const Eigen::Vector3d dir_cam(d.x() / focal_px, d.y() / focal_px, 1.0);
        return {eye, (world_to_camera.transpose() * dir_cam).normalized()};
    }
    const Eigen::Vector3d offset_cam(d.x() / scale_px_per_m, d.y() / scale_px_per_m, 0.0);
    return {eye + world_to_camera.transpose() * offset_cam, world_to_camera.row(2).transpose()};
}

Eigen::Vector2d Camera::project(const Eigen::Vector3d& X) const {
    const Eigen::Vector3d Xc = world_to_camera * (X - eye);
    if (projection == Projection::perspective)
        return principal_px + focal_px * Eigen::Vector2d(Xc.x() / Xc.z(), Xc.y() / Xc.z());
    return principal_px + scale_px_per_m * Xc.head<2>();
}

bool Camera::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    std::ostringstream os;
    if (width_px <= 0 || height_px <= 0 || width_px > 32768 || height_px > 32768) {
        os << "camera image size must be positive (at most 32768), got " << width_px << " x "
           << height_px << " pixels";
        return fail(os.str());
    }
    if (projection == Projection::perspective && !(std::isfinite(focal_px) && focal_px > 0)) {
        os << "camera focal_px must be a positive number, got " << focal_px;
        return fail(os.str());
    }
    if (projection == Projection::orthographic &&
        !(std::isfinite(scale_px_per_m) && scale_px_per_m > 0)) {
        os << "camera scale_px_per_m must be a positive number, got " << scale_px_per_m;
        return fail(os.str());
    }
    if (!principal_px.allFinite() || !eye.allFinite() || !world_to_camera.allFinite())
        return fail("camera principal_px, eye and world_to_camera must be finite");
    if ((world_to_camera * world_to_camera.transpose() - Eigen::Matrix3d::Identity()).norm() > 1e-6)
        return fail("camera world_to_camera must be a rotation (orthonormal rows)");
    return true;
}

}  // namespace drape::render
