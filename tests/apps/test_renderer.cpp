// The renderer (librender, drape::render) against geometry with known answers: projected disks,
// shadow ellipses, ray distances, texture periods, compositing arithmetic, determinism.
#include <catch2/catch.hpp>

#include <drape/core/errors.hpp>
#include <drape/render/camera.hpp>
#include <drape/render/lighting.hpp>
#include <drape/render/overlay.hpp>
#include <drape/render/preview.hpp>
#include <drape/render/renderer.hpp>

#include "render_shapes.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <map>
#include <utility>

using namespace drape::render;
using drape::test::icosphere;
using drape::test::square;

namespace {

/// Distance along the ray to the analytic sphere, or +inf if the ray misses it.
double ray_sphere(const Ray& r, const Eigen::Vector3d& c, double radius) {
    const Eigen::Vector3d oc = c - r.origin;
    const double b = oc.dot(r.direction);
    const double d2 = oc.squaredNorm() - b * b;
    if (b <= 0 || d2 >= radius * radius) return std::numeric_limits<double>::infinity();
    return b - std::sqrt(radius * radius - d2);
}

double luminance(const cv::Vec3b& bgr) { return 0.0722 * bgr[0] + 0.7152 * bgr[1] + 0.2126 * bgr[2]; }

Lighting flat_lighting() {
    Lighting l;
    l.sun_colour.setZero();
    l.sky_zenith = l.sky_horizon = l.ground = l.bounce = Eigen::Vector3d::Constant(0.6);
    return l;
}

}  // namespace

TEST_CASE("render camera matches drape::body::Camera projections", "[render][camera]") {
    drape::body::Camera pin;
    pin.model = drape::body::CameraModel::pinhole;
    pin.focal_px = 1234.0;
    pin.distance_m = 4.5;
    pin.offset_px = {301.5, 455.25};
    drape::body::Camera weak;
    weak.scale_px_per_m = 310.0;
    weak.offset_px = {290.0, 620.0};
    for (const auto& bc : {pin, weak}) {
        const Camera c = Camera::from_body(bc, 600, 900);
        for (const Eigen::Vector3d& X : {Eigen::Vector3d(0.1, 1.2, 0.2), Eigen::Vector3d(-0.3, 0.1, -0.25),
                                        Eigen::Vector3d(0.45, 1.75, 0.05)}) {
            const Eigen::Vector2d p = c.project(X);
            CHECK((p - bc.project(X)).norm() < 1e-9);
            // The ray through that pixel passes through X.
            const Ray r = c.ray(p.x(), p.y());
            const Eigen::Vector3d d = X - r.origin;
            CHECK((d - d.dot(r.direction) * r.direction).norm() < 1e-9);
        }
    }
    CHECK_THROWS_AS(Camera::look_at({0, 1, 3}, {0, 1, 3}, {0, 1, 0}, 500, 10, 10), drape::InvalidInput);
    CHECK_THROWS_AS(Camera::look_at({0, 1, 3}, {0, 1, 0}, {0, 0, 1}, 500, 10, 10), drape::InvalidInput);
}

TEST_CASE("the label map of a sphere is its analytic projected disk", "[render][labels]") {
    const Eigen::Vector3d c(0.2, 1.1, -0.1);
    const double r = 0.3;
    Scene scene;
    scene.meshes.push_back(icosphere(c, r, 5, 7));
    const Camera cam = Camera::look_at({1.0, 1.6, 3.0}, {0, 1, 0}, {0, 1, 0}, 800, 320, 240);
    RenderOptions opt;
    opt.samples_per_pixel = 1;
    RenderImages img;
    const RenderSummary s = render(scene, cam, lighting_preset(LightingPreset::studio), opt, img);
    INFO(s.brief_report());
    REQUIRE(s.usable());
    int inter = 0, uni = 0, analytic = 0;
    for (int y = 0; y < cam.height_px; ++y)
        for (int x = 0; x < cam.width_px; ++x) {
            const bool a = std::isfinite(ray_sphere(cam.ray(x + 0.5, y + 0.5), c, r));
            const bool b = img.labels.at<std::uint8_t>(y, x) == 7;
            CHECK((img.mesh_index.at<std::int16_t>(y, x) == 0) == b);
            analytic += a;
            inter += a && b;
            uni += a || b;
        }
    REQUIRE(analytic > 3000);  // the disk is big enough to measure
    const double iou = static_cast<double>(inter) / uni;
    INFO("IoU " << iou << ", " << analytic << " analytic pixels");
    CHECK(iou >= 0.99);
}

TEST_CASE("depth is the distance along the ray (sphere and floor)", "[render][depth]") {
    const Eigen::Vector3d c(0, 0.8, 0);
    const double r = 0.5;
    Scene scene;
    scene.meshes.push_back(icosphere(c, r, 5, 1));
    scene.floor.enabled = true;
    scene.floor.label = 3;
    const Camera cam = Camera::look_at({0.4, 1.5, 3.5}, {0, 0.5, 0}, {0, 1, 0}, 300, 200, 160);
    RenderOptions opt;
    opt.samples_per_pixel = 1;
    RenderImages img;
    render(scene, cam, lighting_preset(LightingPreset::midday), opt, img);
    // The mesh is inscribed in the sphere: its faces lie up to `sagitta` inside, and a ray
    // meeting the surface at incidence angle i travels up to sagitta / cos(i) further.
    const Mesh& m = scene.meshes[0];
    double sagitta = 0;
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
        const Eigen::Vector3d g = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))).transpose() / 3.0;
        sagitta = std::max(sagitta, r - (g - c).norm());
    }
    double max_sphere = 0, max_floor_rel = 0;
    int n_sphere = 0, n_floor = 0;
    for (int y = 0; y < cam.height_px; ++y)
        for (int x = 0; x < cam.width_px; ++x) {
            const Ray ray = cam.ray(x + 0.5, y + 0.5);
            const double depth = img.depth.at<float>(y, x);
            const double ts = ray_sphere(ray, c, r);
            const int label = img.labels.at<std::uint8_t>(y, x);
            if (label == 1 && std::isfinite(ray_sphere(ray, c, 0.97 * r))) {
                const Eigen::Vector3d n = (ray.origin + ts * ray.direction - c) / r;
                const double cos_i = -n.dot(ray.direction);
                CHECK(depth >= ts - 1e-5);
                CHECK(depth <= ts + sagitta / cos_i + 1e-5);
                max_sphere = std::max(max_sphere, std::abs(depth - ts));
                ++n_sphere;
            } else if (label == 3 && !std::isfinite(ts) && ray.direction.y() < 0) {
                const double tf = -ray.origin.y() / ray.direction.y();
                max_floor_rel = std::max(max_floor_rel, std::abs(depth - tf) / tf);
                ++n_floor;
            } else if (label == 0) {
                CHECK(std::isinf(depth));
            }
        }
    INFO(n_sphere << " sphere pixels, max error " << max_sphere << " m (sagitta " << sagitta << " m); " << n_floor
                  << " floor pixels, max relative error " << max_floor_rel);
    REQUIRE(n_sphere > 1000);
    REQUIRE(n_floor > 1000);
    CHECK(max_sphere < 2e-3 * r);
    CHECK(max_floor_rel < 1e-5);
}

TEST_CASE("a sphere casts its shadow where geometry says", "[render][shadow]") {
    const Eigen::Vector3d c(0, 0.6, 0);
    const double r = 0.25;
    Scene scene;
    scene.meshes.push_back(icosphere(c, r, 4, 1));
    scene.floor.enabled = true;
    scene.floor.label = 3;
    Lighting light = lighting_preset(LightingPreset::midday);
    light.sun_direction = Eigen::Vector3d(0.5, 1.0, 0.3).normalized();
    light.sun_angular_radius_rad = 0.01;
    // A dim sky so that the shadow's contrast measures the sun's occlusion.
    light.sky_zenith = light.sky_horizon = light.ground = Eigen::Vector3d::Constant(0.15);
    light.bounce = Eigen::Vector3d::Constant(0.05);
    const Camera cam = Camera::look_at({0, 2.5, 3.0}, {0.2, 0, 0}, {0, 1, 0}, 260, 240, 200);
    RenderOptions opt;
    opt.samples_per_pixel = 4;
    RenderImages img;
    render(scene, cam, light, opt, img);
    const Eigen::Vector3d L = light.sun_direction.normalized();
    double in_sum = 0, out_sum = 0;
    int in_n = 0, out_n = 0;
    for (int y = 0; y < cam.height_px; ++y)
        for (int x = 0; x < cam.width_px; ++x) {
            if (img.labels.at<std::uint8_t>(y, x) != 3) continue;
            const Ray ray = cam.ray(x + 0.5, y + 0.5);
            if (std::isfinite(ray_sphere(ray, c, 1.2 * r)) || ray.direction.y() >= 0) continue;
            const Eigen::Vector3d P = ray.origin - ray.origin.y() / ray.direction.y() * ray.direction;
            // Distance from the sphere's centre to the ray from P towards the sun.
            const Eigen::Vector3d cp = c - P;
            const double d = (cp - cp.dot(L) * L).norm();
            if ((P - c).norm() > 1.5) continue;  // compare like with like: the neighbourhood
            if (d < 0.85 * r) {
                in_sum += luminance(img.colour.at<cv::Vec3b>(y, x));
                ++in_n;
            } else if (d > 1.2 * r) {
                out_sum += luminance(img.colour.at<cv::Vec3b>(y, x));
                ++out_n;
            }
        }
    REQUIRE(in_n > 300);
    REQUIRE(out_n > 300);
    const double in_mean = in_sum / in_n, out_mean = out_sum / out_n;
    INFO("shadow " << in_mean << " (" << in_n << " px), lit " << out_mean << " (" << out_n << " px)");
    CHECK(in_mean < 0.5 * out_mean);
}

TEST_CASE("renders are byte-identical for 1 and 2 threads", "[render][determinism]") {
    Scene scene;
    Mesh s = icosphere({0, 0.5, 0}, 0.4, 3, 5);
    s.UV = s.V.leftCols(2);
    s.material.print.kind = PrintKind::checks;
    s.material.print.period = 0.1;
    s.material.colour_srgb = {0.7, 0.2, 0.2};
    scene.meshes.push_back(s);
    scene.floor.enabled = true;
    scene.backdrop.enabled = true;
    const Camera cam = Camera::look_at({0.5, 1.2, 3.0}, {0, 0.5, 0}, {0, 1, 0}, 300, 160, 200);
    RenderOptions opt;
    opt.samples_per_pixel = 8;
    const Renderer renderer(scene);
    RenderImages a, b, c;
    opt.threads = 1;
    renderer.render(cam, lighting_preset(LightingPreset::sunset), opt, a);
    opt.threads = 2;
    renderer.render(cam, lighting_preset(LightingPreset::sunset), opt, b);
    render(scene, cam, lighting_preset(LightingPreset::sunset), opt, c);  // a fresh BVH
    for (const RenderImages* other : {&b, &c}) {
        CHECK(cv::norm(a.colour, other->colour, cv::NORM_INF) == 0);
        CHECK(cv::norm(a.alpha, other->alpha, cv::NORM_INF) == 0);
        CHECK(cv::norm(a.labels, other->labels, cv::NORM_INF) == 0);
        CHECK(cv::norm(a.mesh_index, other->mesh_index, cv::NORM_INF) == 0);
        cv::Mat same;
        cv::compare(a.depth, other->depth, same, cv::CMP_EQ);
        CHECK(cv::countNonZero(same) == a.depth.rows * a.depth.cols);
    }
    // And the lightings differ where they should: sunset is warmer than midday.
    RenderImages m;
    renderer.render(cam, lighting_preset(LightingPreset::midday), opt, m);
    const cv::Scalar ms = cv::mean(m.colour), ss = cv::mean(a.colour);
    CHECK(ss[2] / ss[0] > 1.2 * ms[2] / ms[0]);  // red / blue
}

TEST_CASE("a UV-mapped stripe print appears with the right period and phase", "[render][texture]") {
    Scene scene;
    Mesh q = square(1.0, 9);
    q.material.colour_srgb = {0.9, 0.9, 0.9};
    q.material.print.kind = PrintKind::stripes;
    q.material.print.second_colour_srgb = {0.1, 0.1, 0.1};
    q.material.print.period = 0.1;  // 20 px at 200 px/m
    scene.meshes.push_back(q);
    drape::body::Camera weak;
    weak.scale_px_per_m = 200.0;
    weak.offset_px = {160.0, 120.0};
    const Camera cam = Camera::from_body(weak, 320, 240);
    RenderOptions opt;
    opt.samples_per_pixel = 16;
    RenderImages img;
    render(scene, cam, flat_lighting(), opt, img);
    const int row = 100;
    int checked = 0, wrong = 0;
    std::vector<int> rising;
    bool prev_light = false;
    for (int x = 0; x < cam.width_px; ++x) {
        const double lum = luminance(img.colour.at<cv::Vec3b>(row, x));
        const bool light = lum > 128;
        if (x > 0 && light && !prev_light) rising.push_back(x);
        prev_light = light;
        // Pixels whose whole footprint lies in one band: their class is known.
        const double u = (x + 0.5 - 160.0) / 200.0;
        const double phase = u / 0.1 - std::floor(u / 0.1);  // [0, 0.5): colour, [0.5, 1): second
        const double margin = 0.6 / 20.0;
        if (std::abs(phase - 0.5) < margin || phase < margin || phase > 1 - margin) continue;
        ++checked;
        const bool expect_light = phase < 0.5;
        wrong += expect_light != light;
        if (expect_light) CHECK(lum > 200);
        else CHECK(lum < 60);
    }
    CHECK(checked > 250);
    CHECK(wrong == 0);
    // u runs over [-0.8, 0.8): dark-to-light edges at u = -0.7, -0.6, ..., 0.7, 20 px apart.
    REQUIRE(rising.size() == 15);
    CHECK(static_cast<double>(rising.back() - rising.front()) / 14.0 == Approx(20.0).margin(0.1));
    CHECK(rising.front() == 20);  // u = -0.7 at x = 20
}

namespace {

/// A vertical sheet z = amplitude sin(2 pi x / period), x and y in [-1, 1], as a grid.
Mesh corrugated_sheet(double amplitude, double period) {
    const int nx = 401, ny = 11;
    Mesh m;
    m.name = "sheet";
    m.V.resize(nx * ny, 3);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const double x = -1.0 + 2.0 * i / (nx - 1), y = -1.0 + 2.0 * j / (ny - 1);
            m.V.row(j * nx + i) << x, y, amplitude * std::sin(2.0 * 3.14159265358979 * x / period);
        }
    m.F.resize(2 * (nx - 1) * (ny - 1), 3);
    int f = 0;
    for (int j = 0; j + 1 < ny; ++j)
        for (int i = 0; i + 1 < nx; ++i) {
            const int a = j * nx + i;
            m.F.row(f++) << a, a + 1, a + nx;
            m.F.row(f++) << a + 1, a + nx + 1, a + nx;
        }
    m.material.colour_srgb = {0.7, 0.7, 0.7};
    return m;
}

/// Relative amplitude of the luminance's Fourier component of `period_px` along a row.
double modulation(const cv::Mat& colour, int row, double period_px) {
    double re = 0, im = 0, mean = 0;
    const int n = static_cast<int>(std::floor(colour.cols / period_px) * period_px);
    for (int x = 0; x < n; ++x) {
        const double l = luminance(colour.at<cv::Vec3b>(row, x));
        re += l * std::cos(2 * 3.14159265358979 * x / period_px);
        im += l * std::sin(2 * 3.14159265358979 * x / period_px);
        mean += l;
    }
    return 2.0 * std::hypot(re, im) / mean;
}

}  // namespace

TEST_CASE("folds show as shading under every preset", "[render][folds]") {
    // 1 cm deep folds every 10 cm, seen from the front by an orthographic 200 px/m camera.
    drape::body::Camera weak;
    weak.scale_px_per_m = 200.0;
    weak.offset_px = {160.0, 100.0};
    const Camera cam = Camera::from_body(weak, 320, 200);
    RenderOptions opt;
    opt.samples_per_pixel = 8;
    for (const LightingPreset preset : {LightingPreset::midday, LightingPreset::sunset, LightingPreset::studio}) {
        RenderImages folds, flat;
        Scene a, b;
        a.meshes.push_back(corrugated_sheet(0.01, 0.1));
        b.meshes.push_back(corrugated_sheet(0.0, 0.1));
        render(a, cam, lighting_preset(preset), opt, folds);
        render(b, cam, lighting_preset(preset), opt, flat);
        const double m_folds = modulation(folds.colour, 100, 20.0), m_flat = modulation(flat.colour, 100, 20.0);
        INFO(lighting_preset(preset).name << ": fold modulation " << m_folds << ", flat " << m_flat);
        CHECK(m_folds > 0.05);
        CHECK(m_flat < 0.01);
    }
}

TEST_CASE("overlay composites the render over a photo with its alpha", "[render][overlay]") {
    RenderImages r;
    r.foreground = cv::Mat(2, 3, CV_8UC3, cv::Scalar(200, 100, 50));
    r.alpha = (cv::Mat_<std::uint8_t>(2, 3) << 0, 51, 102, 153, 204, 255);
    const cv::Mat photo(2, 3, CV_8UC3, cv::Scalar(10, 20, 30));
    const cv::Mat out = composite_over(photo, r);
    for (int i = 0; i < 6; ++i) {
        const double a = r.alpha.at<std::uint8_t>(i / 3, i % 3) / 255.0;
        const cv::Vec3b o = out.at<cv::Vec3b>(i / 3, i % 3);
        CHECK(o[0] == std::lround(a * 200 + (1 - a) * 10));
        CHECK(o[1] == std::lround(a * 100 + (1 - a) * 20));
        CHECK(o[2] == std::lround(a * 50 + (1 - a) * 30));
    }
    const cv::Mat half = composite_over(photo, r, 0.5);
    CHECK(half.at<cv::Vec3b>(1, 2)[0] == 105);  // 0.5 * 200 + 0.5 * 10
    CHECK_THROWS_AS(composite_over(cv::Mat(3, 3, CV_8UC3), r), drape::InvalidInput);
    CHECK_THROWS_AS(composite_over(photo, r, 1.5), drape::InvalidInput);

    // End to end: uncovered pixels keep the photo, fully covered ones show the render.
    Scene scene;
    scene.meshes.push_back(icosphere({0, 0, 0}, 0.5, 3, 1));
    const Camera cam = Camera::look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 200, 64, 48);
    RenderOptions opt;
    opt.samples_per_pixel = 4;
    RenderImages img;
    render(scene, cam, lighting_preset(LightingPreset::studio), opt, img);
    const cv::Mat bg(48, 64, CV_8UC3, cv::Scalar(0, 255, 0));
    const cv::Mat comp = composite_over(bg, img);
    CHECK(comp.at<cv::Vec3b>(0, 0) == cv::Vec3b(0, 255, 0));
    CHECK(img.alpha.at<std::uint8_t>(24, 32) == 255);
    CHECK(comp.at<cv::Vec3b>(24, 32) == img.foreground.at<cv::Vec3b>(24, 32));
    CHECK(comp.at<cv::Vec3b>(24, 32) == img.colour.at<cv::Vec3b>(24, 32));
}

TEST_CASE("bad render inputs throw InvalidInput with a clear message", "[render][errors]") {
    const Camera cam = Camera::look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 200, 32, 32);
    RenderOptions opt;
    opt.samples_per_pixel = 1;
    RenderImages img;
    const Lighting light = lighting_preset(LightingPreset::studio);

    Scene empty_mesh;
    empty_mesh.meshes.emplace_back();
    empty_mesh.meshes[0].name = "garment.obj";
    CHECK_THROWS_AS(render(empty_mesh, cam, light, opt, img), drape::InvalidInput);
    CHECK_THROWS_WITH(render(empty_mesh, cam, light, opt, img),
                      Catch::Contains("garment.obj") && Catch::Contains("#V > 0"));
    CHECK_THROWS_WITH(render(Scene{}, cam, light, opt, img), Catch::Contains("empty"));

    Scene nan_vertex;
    nan_vertex.meshes.push_back(square(1.0, 1));
    nan_vertex.meshes[0].V(2, 1) = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(render(nan_vertex, cam, light, opt, img), drape::InvalidInput);
    CHECK_THROWS_WITH(render(nan_vertex, cam, light, opt, img), Catch::Contains("vertex 2 is not finite"));

    Scene ok;
    ok.meshes.push_back(square(1.0, 1));
    Camera zero = cam;
    zero.width_px = 0;
    CHECK_THROWS_AS(render(ok, zero, light, opt, img), drape::InvalidInput);
    CHECK_THROWS_WITH(render(ok, zero, light, opt, img), Catch::Contains("image size"));
    CHECK_THROWS_WITH(Camera::look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 200, 0, 10),
                      Catch::Contains("image size must be positive"));

    Scene bad = ok;
    bad.meshes[0].F(1, 2) = 4;
    CHECK_THROWS_WITH(render(bad, cam, light, opt, img), Catch::Contains("face indices"));
    bad = ok;
    bad.meshes[0].label = 300;
    CHECK_THROWS_WITH(render(bad, cam, light, opt, img), Catch::Contains("label"));
    bad = ok;
    bad.meshes[0].material.colour_srgb = {1.5, 0, 0};
    CHECK_THROWS_WITH(render(bad, cam, light, opt, img), Catch::Contains("colour_srgb"));
    RenderOptions bad_opt = opt;
    bad_opt.samples_per_pixel = 0;
    CHECK_THROWS_WITH(render(ok, cam, light, bad_opt, img), Catch::Contains("samples_per_pixel"));
    CHECK_THROWS_WITH(parse_lighting_preset("noon"), Catch::Contains("noon"));
}

TEST_CASE("a progress callback can cancel a render", "[render][progress]") {
    Scene scene;
    scene.meshes.push_back(square(1.0, 1));
    const Camera cam = Camera::look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 200, 64, 200);
    RenderOptions opt;
    opt.samples_per_pixel = 1;
    RenderImages img;
    int calls = 0;
    const RenderSummary s = Renderer(scene).render(
        cam, lighting_preset(LightingPreset::studio), opt, img,
        [](double fraction, void* user) {
            ++*static_cast<int*>(user);
            return fraction < 0.5;
        },
        &calls);
    CHECK(s.termination == RenderTermination::cancelled);
    CHECK_FALSE(s.usable());
    CHECK(calls == 2);  // bands of 64 rows: 64/200 continues, 128/200 cancels
}

TEST_CASE("phong tessellation refines a coarse sphere towards the sphere, seams stay closed",
          "[render][tessellation]") {
    // A level-1 icosphere (edges 32 degrees apart) with its exact normals, tessellated twice:
    // linear midpoints (alpha 0) lie up to 6 % inside the unit sphere, Phong midpoints (alpha
    // 0.75, the second level from averaged normals) within 3 % (slightly outside).
    const Mesh coarse = icosphere(Eigen::Vector3d::Zero(), 1.0, 1, 3);
    const auto worst = [](const Mesh& m) {
        double e = 0;
        for (Eigen::Index i = 0; i < m.V.rows(); ++i) e = std::max(e, std::abs(m.V.row(i).norm() - 1));
        return e;
    };
    const Mesh flat = phong_tessellate(coarse, 2, 0.0), smooth = phong_tessellate(coarse, 2);
    INFO("largest radial error: linear " << worst(flat) << ", Phong " << worst(smooth));
    CHECK(smooth.F.rows() == 16 * coarse.F.rows());
    // Shared edges are split once: V - E + F = 2 for the closed sphere.
    CHECK(smooth.V.rows() == smooth.F.rows() / 2 + 2);
    CHECK(worst(flat) > 0.05);
    CHECK(worst(smooth) < 0.03);
    CHECK(smooth.smooth_subdivisions == 0);
    CHECK_THROWS_AS(phong_tessellate(coarse, -1), drape::InvalidInput);
    CHECK_THROWS_AS(phong_tessellate(coarse, 1, 1.5), drape::InvalidInput);

    // Two triangles of a bent sheet whose shared edge has its own vertices on each side (a
    // seam), no normals given: the midpoints of the seam agree exactly on both sides, and
    // UVs are interpolated.
    Mesh seam;
    seam.V.resize(6, 3);
    seam.V << 0, 0, 0, 1, 0, 0.3, 0, 1, 0,  // triangle 0
        1, 0, 0.3, 1, 1, 0, 0, 1, 0;        // triangle 1: its own copies of (1, 0, .3), (0, 1, 0)
    seam.F.resize(2, 3);
    seam.F << 0, 1, 2, 3, 4, 5;
    seam.UV.resize(6, 2);
    seam.UV << 0, 0, 1, 0, 0, 1, 1, 0, 1, 1, 0, 1;
    const Mesh t = phong_tessellate(seam, 1);
    std::vector<Eigen::Vector3d> mids;
    for (Eigen::Index i = 6; i < t.V.rows(); ++i) {
        const Eigen::Vector2d uv = t.UV.row(i).transpose();
        if (std::abs(uv.x() + uv.y() - 1) < 1e-12) mids.push_back(t.V.row(i).transpose());  // on the diagonal
    }
    REQUIRE(mids.size() == 2);
    CHECK((mids[0] - mids[1]).norm() == 0.0);
}

TEST_CASE("a coarse garment drawn with smooth_subdivisions hides the body under it",
          "[render][tessellation]") {
    // A coarse shell (level-1 icosphere, radius 1) 3 % outside a fine "body" sphere: drawn
    // flat its triangles cut chords into the body, which shows through; Phong-tessellated
    // twice it covers it.
    Scene scene;
    scene.meshes.push_back(icosphere(Eigen::Vector3d::Zero(), 0.97, 5, 41));
    scene.meshes.push_back(icosphere(Eigen::Vector3d::Zero(), 1.0, 1, 51));
    scene.meshes[1].N.resize(0, 3);  // the garment's own area-weighted normals
    const Camera cam = Camera::look_at({0.3, 0.4, 4.0}, {0, 0, 0}, {0, 1, 0}, 300, 200, 200);
    RenderOptions opt;
    opt.samples_per_pixel = 1;
    const auto body_pixels = [&](int levels) {
        scene.meshes[1].smooth_subdivisions = levels;
        RenderImages img;
        REQUIRE(render(scene, cam, flat_lighting(), opt, img).usable());
        int n = 0;
        for (int y = 0; y < img.labels.rows; ++y)
            for (int x = 0; x < img.labels.cols; ++x) n += img.labels.at<std::uint8_t>(y, x) == 41;
        return n;
    };
    const int flat = body_pixels(0), smooth = body_pixels(2);
    INFO("body pixels: flat " << flat << ", tessellated " << smooth);
    CHECK(flat > 500);
    CHECK(smooth == 0);
    scene.meshes[1].smooth_subdivisions = 5;
    CHECK_THROWS_AS(scene.validate(), drape::InvalidInput);
}

TEST_CASE("preview_scene and its cameras frame a dressed body", "[render][preview]") {
    // A 1.7 m tall "body" (a stretched sphere) and a "garment" shell around its middle.
    Mesh body = icosphere(Eigen::Vector3d(0, 0.85, 0), 1.0, 2, 1);
    body.V.col(0) *= 0.2;
    body.V.col(1) = (body.V.col(1).array() - 0.85) * 0.85 + 0.85;
    body.V.col(2) *= 0.15;
    Mesh shell = icosphere(Eigen::Vector3d(0, 1.0, 0), 0.25, 1, 2);
    const Scene scene = preview_scene(body.V, body.F, {{shell.V, shell.F, Eigen::MatrixXd()}, {shell.V, shell.F, {}}});
    REQUIRE(scene.meshes.size() == 3);
    CHECK(scene.meshes[1].material.colour_srgb != scene.meshes[2].material.colour_srgb);
    CHECK(scene.meshes[1].smooth_subdivisions == kSimulatedGarmentSubdivisions);
    CHECK(scene.floor.enabled);
    CHECK(scene.floor.height_m == Approx(body.V.col(1).minCoeff()));
    for (const Camera& cam : {preview_camera(body.V, 300, 450), front_camera(scene, 300, 450)}) {
        double top = 1e9, bottom = -1e9;
        for (Eigen::Index v = 0; v < body.V.rows(); ++v) {
            const Eigen::Vector2d p = cam.project(body.V.row(v).transpose());
            CHECK((p.x() > 0 && p.x() < 300 && p.y() > 0 && p.y() < 450));
            top = std::min(top, p.y());
            bottom = std::max(bottom, p.y());
        }
        // Framed with a margin, but filling most of the height.
        CHECK(bottom - top > 0.75 * 450);
        CHECK(bottom - top < 0.95 * 450);
    }
    CHECK_THROWS_AS(preview_camera(Eigen::MatrixXd(0, 3), 300, 450), drape::InvalidInput);
    CHECK_THROWS_AS(front_camera(Scene{}, 300, 450), drape::InvalidInput);
}
