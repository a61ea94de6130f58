#include <drape/render/rasterize.hpp>

#include <drape/core/errors.hpp>
#include <drape/core/scan_triangle.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace drape::render {

namespace {

/// Vertices in the image: pixel position and a "nearness" that is affine in image space
/// and grows towards the camera, so the z-buffer interpolates it linearly between the
/// corners: 1 / z_c for a pinhole (perspective-correct), world Z for weak perspective.
struct Projected {
    std::vector<Eigen::Vector2d> px;
    std::vector<float> nearness;
    std::vector<char> drawable;  ///< pinhole: in front of the near plane
};

Projected project_mesh(const Mesh& mesh, const body::Camera& camera, double near_m) {
    const Eigen::Index n = mesh.V.rows();
    Projected p;
    p.px.resize(static_cast<size_t>(n));
    p.nearness.resize(static_cast<size_t>(n));
    p.drawable.assign(static_cast<size_t>(n), 1);
    const bool pinhole = camera.model == body::CameraModel::pinhole;
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Vector3d X = mesh.V.row(i).transpose();
        const size_t k = static_cast<size_t>(i);
        p.px[k] = camera.project(X);
        if (pinhole) {
            const double zc = camera.distance_m - X.z();
            p.drawable[k] = zc > near_m;
            p.nearness[k] = static_cast<float>(zc > near_m ? 1.0 / zc : 0.0);
        } else {
            p.nearness[k] = static_cast<float>(X.z());
        }
    }
    return p;
}

/// What a triangle's pixels write: the z-buffer test, then the mesh index (and coverage).
struct Target {
    int width = 0;
    int height = 0;
    float* zbuffer;  ///< nearness of the surface drawn so far, -inf where none
    std::int16_t* mesh_index;
    std::uint8_t* coverage;  ///< this mesh's mask, or null
};

// The pixels of a triangle (core::scan_triangle: pixel centres inside or on an edge, either
// winding), z-buffered on the interpolated nearness.
void draw_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   float qa, float qb, float qc, std::int16_t index, Target& t) {
    core::scan_triangle(a, b, c, t.width, t.height, [&](int x, int y, double wa, double wb, double wc) {
        const size_t k = static_cast<size_t>(y) * static_cast<size_t>(t.width) + static_cast<size_t>(x);
        if (t.coverage) t.coverage[k] = 255;
        const float q = static_cast<float>(wa * qa + wb * qb + wc * qc);
        if (q > t.zbuffer[k]) {
            t.zbuffer[k] = q;
            t.mesh_index[k] = index;
        }
    });
}

}  // namespace

bool RasterOptions::is_valid(std::string* why) const {
    auto fail = [&](const std::string& m) {
        if (why) *why = m;
        return false;
    };
    std::ostringstream os;
    if (width_px <= 0 || height_px <= 0 || width_px > 32768 || height_px > 32768) {
        os << "raster image size must be positive (at most 32768), got " << width_px << " x " << height_px
           << " pixels";
        return fail(os.str());
    }
    if (!(std::isfinite(near_m) && near_m > 0)) {
        os << "raster near_m must be a positive number, got " << near_m;
        return fail(os.str());
    }
    return true;
}

std::string RasterSummary::brief_report() const {
    std::ostringstream os;
    os << (termination == RasterTermination::rasterised ? "rasterised" : "nothing in view") << " " << width_px
       << "x" << height_px << " px, " << triangles << " triangles";
    if (triangles_behind > 0) os << " (" << triangles_behind << " behind the camera)";
    os << ", " << pixels_covered << " pixels covered, " << seconds * 1e3 << " ms";
    if (!message.empty()) os << ": " << message;
    return os.str();
}

RasterSummary rasterize(const std::vector<Mesh>& meshes, const body::Camera& camera,
                        const RasterOptions& options, RasterImages& out) {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why;
    require(options.is_valid(&why), "rasterize: ", why);
    require(camera.is_valid(&why), "rasterize: ", why);
    require(meshes.size() <= 32767, "rasterize: at most 32767 meshes (CV_16S mesh_index), got ", meshes.size());
    for (size_t i = 0; i < meshes.size(); ++i) validate_mesh(meshes[i], i);

    const int W = options.width_px, H = options.height_px;
    const size_t pixels = static_cast<size_t>(W) * static_cast<size_t>(H);
    const size_t n = meshes.size();
    // Buffers of a previous call of the same size are reused (cv::Mat::create), which
    // saves the page faults of fresh allocations in a loop. depth_m holds the z-buffer's
    // nearness until the end.
    out.mesh_index.create(H, W, CV_16SC1);
    out.mesh_index.setTo(cv::Scalar(-1));
    out.depth_m.create(H, W, CV_32FC1);
    out.depth_m.setTo(cv::Scalar(-std::numeric_limits<float>::infinity()));
    out.coverage.resize(options.coverage ? n : 0);
    float* zbuffer = out.depth_m.ptr<float>();
    Target target{W, H, zbuffer, out.mesh_index.ptr<std::int16_t>(), nullptr};

    RasterSummary summary;
    summary.width_px = W;
    summary.height_px = H;
    for (size_t i = 0; i < n; ++i) {
        const Mesh& m = meshes[i];
        const Projected p = project_mesh(m, camera, options.near_m);
        if (options.coverage) {
            out.coverage[i].create(H, W, CV_8UC1);
            out.coverage[i].setTo(cv::Scalar(0));
            target.coverage = out.coverage[i].ptr<std::uint8_t>();
        }
        summary.triangles += m.F.rows();
        for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
            const size_t a = static_cast<size_t>(m.F(f, 0)), b = static_cast<size_t>(m.F(f, 1)),
                         c = static_cast<size_t>(m.F(f, 2));
            if (!p.drawable[a] || !p.drawable[b] || !p.drawable[c]) {
                ++summary.triangles_behind;
                continue;
            }
            draw_triangle(p.px[a], p.px[b], p.px[c], p.nearness[a], p.nearness[b], p.nearness[c],
                          static_cast<std::int16_t>(i), target);
        }
    }

    // Labels, depth and visible silhouettes from the winning mesh of each pixel.
    out.labels.create(H, W, CV_8UC1);
    out.visible.resize(n);
    for (cv::Mat& v : out.visible) {
        v.create(H, W, CV_8UC1);
        v.setTo(cv::Scalar(0));
    }
    summary.visible_pixels.assign(n, 0);
    const std::int16_t* index = out.mesh_index.ptr<std::int16_t>();
    std::uint8_t* labels = out.labels.ptr<std::uint8_t>();
    float* depth = out.depth_m.ptr<float>();
    const bool pinhole = camera.model == body::CameraModel::pinhole;
    for (size_t k = 0; k < pixels; ++k) {
        const int i = index[k];
        if (i < 0) {
            labels[k] = 0;
            depth[k] = std::numeric_limits<float>::infinity();
            continue;
        }
        labels[k] = static_cast<std::uint8_t>(meshes[static_cast<size_t>(i)].label);
        depth[k] = pinhole ? 1.0f / depth[k] : static_cast<float>(camera.distance_m - depth[k]);
        out.visible[static_cast<size_t>(i)].data[k] = 255;
        ++summary.visible_pixels[static_cast<size_t>(i)];
        ++summary.pixels_covered;
    }
    if (summary.pixels_covered == 0) {
        summary.termination = RasterTermination::nothing_in_view;
        summary.message = "no triangle covers a pixel centre of the image";
    }
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return summary;
}

}  // namespace drape::render
