#include <drape/body/camera.hpp>

#include <drape/core/errors.hpp>
#include <drape/core/scan_triangle.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace drape::body {

Eigen::Vector2d Camera::project(const Eigen::Vector3d& X) const {
    if (model == CameraModel::weak_perspective)
        return {scale_px_per_m * X.x() + offset_px.x(), -scale_px_per_m * X.y() + offset_px.y()};
    const double zc = distance_m - X.z();
    return {focal_px * X.x() / zc + offset_px.x(), focal_px * -X.y() / zc + offset_px.y()};
}

bool Camera::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    if (!offset_px.allFinite()) return fail("camera offset_px is not finite");
    if (model == CameraModel::weak_perspective) {
        if (!std::isfinite(scale_px_per_m) || scale_px_per_m <= 0) {
            std::ostringstream os;
            os << "camera scale_px_per_m must be a positive number, got " << scale_px_per_m;
            return fail(os.str());
        }
    } else {
        if (!std::isfinite(focal_px) || focal_px <= 0) {
            std::ostringstream os;
            os << "camera focal_px must be a positive number, got " << focal_px;
            return fail(os.str());
        }
        if (!std::isfinite(distance_m) || distance_m <= 0) {
            std::ostringstream os;
            os << "camera distance_m must be a positive number, got " << distance_m;
            return fail(os.str());
        }
    }
    return true;
}

int Mask::count() const {
    return static_cast<int>(std::count_if(pixels.begin(), pixels.end(),
                                          [](std::uint8_t p) { return p != 0; }));
}

Mask render_silhouette(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Camera& camera,
                       int width, int height) {
    require(width >= 0 && height >= 0, "render_silhouette: image size must be non-negative, got ",
            width, " x ", height);
    require(V.cols() == 3, "render_silhouette: V must be #V x 3, got ", V.rows(), " x ", V.cols());
    require(F.cols() == 3 || F.rows() == 0, "render_silhouette: F must be #F x 3, got ", F.rows(),
            " x ", F.cols());
    std::string why;
    require(camera.is_valid(&why), "render_silhouette: ", why);
    Mask mask;
    mask.width = width;
    mask.height = height;
    mask.pixels.assign(static_cast<size_t>(width) * static_cast<size_t>(height), 0);
    if (width == 0 || height == 0) return mask;

    Eigen::MatrixX2d P(V.rows(), 2);
    std::vector<char> in_front(static_cast<size_t>(V.rows()), 1);
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
        const Eigen::Vector3d X = V.row(i).transpose();
        if (camera.model == CameraModel::pinhole && camera.distance_m - X.z() <= 1e-9)
            in_front[static_cast<size_t>(i)] = 0;
        P.row(i) = camera.project(X).transpose();
    }
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
        require(a >= 0 && b >= 0 && c >= 0 && a < V.rows() && b < V.rows() && c < V.rows(),
                "render_silhouette: face ", f, " has a vertex index out of range [0, ", V.rows(),
                ")");
        if (!in_front[static_cast<size_t>(a)] || !in_front[static_cast<size_t>(b)] ||
            !in_front[static_cast<size_t>(c)])
            continue;
        const Eigen::Vector2d pa = P.row(a), pb = P.row(b), pc = P.row(c);
        if (!pa.allFinite() || !pb.allFinite() || !pc.allFinite()) continue;
        // Pixel (x, y) is covered when its centre (x + 0.5, y + 0.5) lies in the triangle;
        // either winding counts (the silhouette does not care which side faces the camera).
        core::scan_triangle(pa, pb, pc, width, height, [&](int x, int y, double, double, double) {
            mask.pixels[static_cast<size_t>(y) * width + x] = 1;
        });
    }
    return mask;
}

}  // namespace drape::body
