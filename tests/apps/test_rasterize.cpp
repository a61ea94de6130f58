// The rasteriser (drape/render/rasterize.hpp) against projections with known answers (a
// box, a sphere, weak perspective and pinhole), occlusion order, the path tracer's label
// map on a body + garment scene, and invalid input.
#include <catch2/catch.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/vertex_normals.hpp>
#include <drape/render/rasterize.hpp>
#include <drape/render/renderer.hpp>
#include <drape/vision/segmentation_score.hpp>

#include <cmath>
#include <cstdint>
#include <limits>

#include "render_shapes.hpp"

using namespace drape::render;
using BodyCamera = drape::body::Camera;
using drape::body::CameraModel;
using drape::test::icosphere;
using drape::test::square;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Pixel centres k + 0.5 (k in [0, n)) inside [lo, hi].
int centres_in(double lo, double hi, int n) {
    int count = 0;
    for (int k = 0; k < n; ++k) count += lo <= k + 0.5 && k + 0.5 <= hi;
    return count;
}

/// An axis-aligned box, half-extents h, centred at c (12 triangles).
Mesh box(const Eigen::Vector3d& c, const Eigen::Vector3d& h, int label) {
    Mesh m;
    m.name = "box";
    m.V.resize(8, 3);
    for (int i = 0; i < 8; ++i)
        m.V.row(i) << c.x() + ((i & 1) ? h.x() : -h.x()), c.y() + ((i & 2) ? h.y() : -h.y()),
            c.z() + ((i & 4) ? h.z() : -h.z());
    m.F.resize(12, 3);
    m.F << 0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 3, 7,
        1, 7, 5;
    m.label = label;
    return m;
}

BodyCamera weak_camera(double scale, const Eigen::Vector2d& offset) {
    BodyCamera c;
    c.model = CameraModel::weak_perspective;
    c.scale_px_per_m = scale;
    c.offset_px = offset;
    return c;
}

BodyCamera pinhole_camera(double focal, double distance, const Eigen::Vector2d& offset) {
    BodyCamera c;
    c.model = CameraModel::pinhole;
    c.focal_px = focal;
    c.distance_m = distance;
    c.offset_px = offset;
    return c;
}

RasterOptions size(int w, int h) {
    RasterOptions o;
    o.width_px = w;
    o.height_px = h;
    return o;
}

}  // namespace

TEST_CASE("a box projects to its analytic rectangle (weak perspective and pinhole)", "[render][rasterize]") {
    // A box centred on the optical axis: its silhouette is the projection of its front face,
    // for weak perspective (u = s x + tx) and for a pinhole (u = f x / (d - z_front) + tx).
    // Corners are placed off pixel centres, so the covered pixels are exactly the centres
    // inside the rectangle: the count is exact, no tolerance.
    const Eigen::Vector3d h(0.21, 0.33, 0.1);
    const std::vector<Mesh> meshes = {box({0, 0, 0}, h, 5)};
    const int W = 200, H = 260;
    const Eigen::Vector2d o(100.3, 130.2);
    for (const BodyCamera& cam : {weak_camera(250.0, o), pinhole_camera(1000.0, 4.0, o)}) {
        const double s = cam.model == CameraModel::pinhole ? cam.focal_px / (cam.distance_m - h.z())
                                                           : cam.scale_px_per_m;
        const int expected = centres_in(o.x() - s * h.x(), o.x() + s * h.x(), W) *
                             centres_in(o.y() - s * h.y(), o.y() + s * h.y(), H);
        RasterImages img;
        const RasterSummary sum = rasterize(meshes, cam, size(W, H), img);
        INFO(sum.brief_report());
        REQUIRE(sum.usable());
        CHECK(sum.pixels_covered == expected);
        CHECK(cv::countNonZero(img.labels == 5) == expected);
        CHECK(cv::countNonZero(img.visible[0]) == expected);
        CHECK(cv::countNonZero(img.coverage[0]) == expected);
        // Depth at the centre pixel: the front face, z_c = d - z_front (weak: from z = d).
        const int cx = int(o.x()), cy = int(o.y());
        CHECK(img.depth_m.at<float>(cy, cx) == Approx(cam.distance_m - h.z()).epsilon(1e-6));
        CHECK(std::isinf(img.depth_m.at<float>(0, 0)));
        CHECK(img.mesh_index.at<std::int16_t>(0, 0) == -1);
    }
}

TEST_CASE("a sphere projects to its analytic disk, larger with a pinhole than with weak perspective",
          "[render][rasterize]") {
    // Sphere of radius r at distance d on the optical axis: weak perspective with s = f / d
    // gives a disk of radius s r; the pinhole's tangent cone gives f r / sqrt(d^2 - r^2).
    // The level-5 icosphere's rim lies within r (1 - cos 1 deg) = 0.015 px of the sphere's
    // at this size, so every pixel centre farther than 0.05 px from the analytic circle is
    // decided as the circle decides it; the count then differs from the area pi R^2 only by
    // the sampling of the rim (Gauss circle problem: O(R^(2/3)), here checked against half a
    // pixel row around the rim, pi R).
    const double r = 0.3, d = 4.0, f = 1200.0;
    const std::vector<Mesh> meshes = {icosphere({0, 0, 0}, r, 5, 9)};
    const int W = 240, H = 240;
    const Eigen::Vector2d o(120.25, 119.6);
    long long counts[2] = {0, 0};
    int k = 0;
    for (const BodyCamera& cam : {weak_camera(f / d, o), pinhole_camera(f, d, o)}) {
        const double R = cam.model == CameraModel::pinhole ? f * r / std::sqrt(d * d - r * r) : f / d * r;
        RasterImages img;
        const RasterSummary sum = rasterize(meshes, cam, size(W, H), img);
        INFO(sum.brief_report() << "; R = " << R << " px");
        int disagree = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const double rho = (Eigen::Vector2d(x + 0.5, y + 0.5) - o).norm();
                if (std::abs(rho - R) < 0.05) continue;
                disagree += (rho < R) != (img.labels.at<std::uint8_t>(y, x) == 9);
            }
        CHECK(disagree == 0);
        CHECK(std::abs(double(sum.pixels_covered) - kPi * R * R) <= kPi * R);
        counts[k++] = sum.pixels_covered;
    }
    CHECK(counts[1] > counts[0]);
}

TEST_CASE("a mesh in front hides the one behind, in either order", "[render][rasterize]") {
    // Two 0.4 m squares, overlapping by half, one 0.2 m nearer to the camera. Whichever is
    // nearer (and whichever comes first in the list) shows in the overlap; the one behind
    // keeps its full coverage but loses the overlap from its visible silhouette.
    for (const BodyCamera& cam : {weak_camera(200.0, {100.2, 80.3}), pinhole_camera(800.0, 4.0, {100.2, 80.3})})
        for (const bool first_in_front : {true, false})
            for (const bool swap_list : {false, true}) {
                Mesh front = square(0.2, 1), back = square(0.2, 2);
                front.V.col(2).array() += 0.2;
                front.V.col(0).array() += 0.1;
                back.V.col(0).array() -= 0.1;
                if (!first_in_front) std::swap(front.label, back.label);
                std::vector<Mesh> meshes = {front, back};
                if (swap_list) std::swap(meshes[0], meshes[1]);
                const int i_front = swap_list ? 1 : 0, i_back = 1 - i_front;
                RasterImages img;
                REQUIRE(rasterize(meshes, cam, size(200, 160), img).usable());
                const cv::Mat overlap = img.coverage[0] & img.coverage[1];
                REQUIRE(cv::countNonZero(overlap) > 500);
                CHECK(cv::countNonZero(overlap & ~img.visible[i_front]) == 0);
                CHECK(cv::countNonZero(overlap & img.visible[i_back]) == 0);
                CHECK(cv::countNonZero(img.visible[i_back] != (img.coverage[i_back] & ~overlap)) == 0);
                CHECK(cv::countNonZero((img.labels == meshes[size_t(i_front)].label) != img.visible[i_front]) == 0);
            }
}

TEST_CASE("the rasteriser's labels agree with the path tracer's on a body + garment scene",
          "[render][rasterize]") {
    // The default body in its rest pose and a tight "garment": the torso's faces pushed
    // 1.5 cm out along the vertex normals, framed by a pinhole camera as `drape synth` frames
    // its scenes. Both sample the pixel centres; they could differ only where a centre is
    // within float rounding of an edge (measured: identical, IoU 1 for every label).
    const drape::body::BodyModel& model = drape::body::BodyModel::default_model();
    drape::body::ShapedBody shaped;
    drape::body::shape_body(model, model.prior.complete(drape::body::SemanticRequest{}),
                            drape::body::ShapeOptions{}, shaped);
    const Eigen::MatrixXd V = drape::body::pose_body(model, shaped, drape::body::Pose::rest()).vertices;
    const Eigen::MatrixXi F = model.faces;
    const double y_min = V.col(1).minCoeff(), h = V.col(1).maxCoeff() - y_min;
    const Eigen::MatrixXd N = drape::core::vertex_normals(V, F);
    std::vector<Eigen::Vector3i> shell;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        bool torso = true;
        for (int k = 0; k < 3; ++k) {
            const double y = V(F(f, k), 1) - y_min;
            torso = torso && y > 0.45 * h && y < 0.75 * h;
        }
        if (torso) shell.emplace_back(F.row(f).transpose());
    }
    REQUIRE(shell.size() > 1000);
    Mesh body, garment;
    body.name = "body";
    body.V = V;
    body.F = F;
    body.label = 41;
    garment.name = "garment";
    garment.V = V + 0.015 * N;
    garment.F.resize(Eigen::Index(shell.size()), 3);
    for (size_t i = 0; i < shell.size(); ++i) garment.F.row(Eigen::Index(i)) = shell[i].transpose();
    garment.label = 51;

    const int W = 600, H = 900;
    BodyCamera cam = pinhole_camera(0.5 * H / std::tan(14.0 * kPi / 180.0), 0.0, {0.5 * W, 0.0});
    cam.distance_m = cam.focal_px * 1.25 * h / H;
    cam.offset_px.y() = 0.5 * H + cam.focal_px * (y_min + 0.5 * h) / cam.distance_m;
    RasterImages raster;
    const RasterSummary rs = rasterize({body, garment}, cam, size(W, H), raster);
    Scene scene;
    scene.meshes = {body, garment};
    RenderOptions ro;
    ro.samples_per_pixel = 1;
    RenderImages traced;
    render(scene, drape::render::Camera::from_body(cam, W, H), lighting_preset(LightingPreset::studio), ro, traced);
    INFO(rs.brief_report());
    REQUIRE(rs.visible_pixels[1] > 20000);
    REQUIRE(rs.visible_pixels[0] > 40000);
    for (const int label : {0, 41, 51}) {
        const double v = drape::vision::iou(raster.labels == label, traced.labels == label);
        INFO("label " << label << ": IoU " << v << ", rasterised " << cv::countNonZero(raster.labels == label)
                      << " px, traced " << cv::countNonZero(traced.labels == label) << " px");
        CHECK(v >= 0.98);
    }
    // The garment hides the body over most of its silhouette (the rest is its 1.5 cm rim
    // beyond the body's outline): measured 83 %.
    CHECK(cv::countNonZero(raster.coverage[0] & raster.visible[1]) > 0.75 * rs.visible_pixels[1]);
}

TEST_CASE("rasterize: invalid input throws InvalidInput, nothing in view is a result", "[render][rasterize]") {
    const std::vector<Mesh> ok = {square(0.2, 1)};
    const BodyCamera cam = weak_camera(100.0, {50, 50});
    RasterImages img;
    CHECK_THROWS_AS(rasterize(ok, cam, size(0, 10), img), drape::InvalidInput);
    RasterOptions near;
    near.near_m = 0.0;
    CHECK_THROWS_AS(rasterize(ok, cam, near, img), drape::InvalidInput);
    CHECK_THROWS_AS(rasterize(ok, weak_camera(-1.0, {0, 0}), size(10, 10), img), drape::InvalidInput);
    CHECK_THROWS_AS(rasterize(ok, pinhole_camera(500.0, 0.0, {0, 0}), size(10, 10), img), drape::InvalidInput);
    std::vector<Mesh> bad = ok;
    bad[0].F(1, 2) = 4;
    CHECK_THROWS_WITH(rasterize(bad, cam, size(10, 10), img), Catch::Contains("face indices"));
    bad = ok;
    bad[0].label = 300;
    CHECK_THROWS_AS(rasterize(bad, cam, size(10, 10), img), drape::InvalidInput);
    bad = ok;
    bad[0].V(2, 1) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(rasterize(bad, cam, size(10, 10), img), Catch::Contains("not finite"));

    // Outside the image, or behind a pinhole camera: a summary that says so.
    RasterSummary s = rasterize(ok, weak_camera(100.0, {-500, -500}), size(20, 20), img);
    CHECK(s.termination == RasterTermination::nothing_in_view);
    CHECK_FALSE(s.usable());
    CHECK(cv::countNonZero(img.labels) == 0);
    std::vector<Mesh> behind = ok;
    behind[0].V.col(2).array() += 5.0;  // at z = 5 > distance_m = 4
    s = rasterize(behind, pinhole_camera(500.0, 4.0, {10, 10}), size(20, 20), img);
    CHECK(s.triangles_behind == 2);
    CHECK(s.termination == RasterTermination::nothing_in_view);
}
