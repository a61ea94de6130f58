// Times the renderer on the default body plus a ~10k-vertex garment (a pleated skirt
// built in code) at 600 x 900 pixels: BVH build, then each lighting preset at several
// sample counts and thread counts. With --figures DIR it also writes the documentation
// images (docs/images/render_*.png). With --raster it times only the rasteriser
// (drape/render/rasterize.hpp) on the same scene and camera, the fast path recovery runs.
// Usage: drape_bench_render [--figures DIR] [--quick] [--raster]
#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/render/rasterize.hpp>
#include <drape/render/renderer.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>
#include <algorithm>

using namespace drape;
using Clock = std::chrono::steady_clock;

namespace {

/// A flared skirt with folds from the waist to below the knees: rings of an ellipse that
/// hugs the body's legs and hips (arms excluded), pushed outwards by pleats that deepen
/// towards the hem. UV = (arc length around the waist, height), metres.
render::Mesh skirt(const Eigen::MatrixXd& body, int rings, int segments) {
    const double height = body.col(1).maxCoeff() - body.col(1).minCoeff();
    const double y_top = 0.60 * height, y_hem = 0.30 * height;
    render::Mesh m;
    m.name = "skirt";
    m.V.resize(rings * segments, 3);
    m.UV.resize(rings * segments, 2);
    for (int r = 0; r < rings; ++r) {
        const double t = static_cast<double>(r) / (rings - 1);  // 0 at the waist
        const double y = y_top + t * (y_hem - y_top);
        double ax = 0.05, bz = 0.05, zc = 0.0;
        int n = 0;
        for (Eigen::Index v = 0; v < body.rows(); ++v)
            if (std::abs(body(v, 1) - y) < 0.03 && std::abs(body(v, 0)) < 0.24) {
                ax = std::max(ax, std::abs(body(v, 0)));
                zc += body(v, 2);
                ++n;
            }
        zc = n > 0 ? zc / n : 0.0;
        for (Eigen::Index v = 0; v < body.rows(); ++v)
            if (std::abs(body(v, 1) - y) < 0.03 && std::abs(body(v, 0)) < 0.24)
                bz = std::max(bz, std::abs(body(v, 2) - zc));
        const double flare = 1.0 + 0.35 * t * t, ease = 0.025;
        for (int s = 0; s < segments; ++s) {
            const double th = 2.0 * 3.14159265358979323846 * s / segments;
            const double pleat = 1.0 + 0.12 * t * (0.5 + 0.5 * std::sin(14.0 * th + 3.0 * t));
            const double x = (ax + ease) * flare * pleat * std::sin(th);
            const double z = zc + (bz + ease) * flare * pleat * std::cos(th);
            m.V.row(r * segments + s) << x, y, z;
            m.UV.row(r * segments + s) << th * 0.45, y;
        }
    }
    m.F.resize(2 * (rings - 1) * segments, 3);
    for (int r = 0; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const int a = r * segments + s, b = r * segments + (s + 1) % segments;
            const int c = a + segments, d = b + segments;
            m.F.row(2 * (r * segments + s)) << a, c, b;
            m.F.row(2 * (r * segments + s) + 1) << b, c, d;
        }
    m.material.colour_srgb = {0.60, 0.12, 0.14};
    m.material.print.kind = render::PrintKind::stripes;
    m.material.print.second_colour_srgb = {0.92, 0.90, 0.84};
    m.material.print.period = 0.06;
    m.material.print.angle_rad = 3.14159265358979323846 / 2;  // horizontal bands
    m.material.roughness = 0.85;
    m.label = 42;  // labels.txt: skirt
    return m;
}

double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Rasterises the scene's meshes `runs` times with and without coverage masks; prints the
/// fastest and the median wall time and the median CPU time (the reliable figure on a
/// loaded machine) of each.
void bench_raster(const std::vector<render::Mesh>& meshes, const body::Camera& camera, int runs) {
    for (const bool coverage : {true, false}) {
        render::RasterOptions options;
        options.coverage = coverage;
        render::RasterImages images;
        std::vector<double> ms, cpu_ms;
        render::RasterSummary s;
        for (int i = 0; i < runs; ++i) {
            const auto t0 = Clock::now();
            const std::clock_t c0 = std::clock();
            s = render::rasterize(meshes, camera, options, images);
            cpu_ms.push_back(1e3 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
            ms.push_back(1e3 * seconds_since(t0));
        }
        std::sort(ms.begin(), ms.end());
        std::sort(cpu_ms.begin(), cpu_ms.end());
        std::printf("rasterize 600x900, coverage %-3s  wall fastest %6.2f ms, median %6.2f ms; cpu median %6.2f ms"
                    "  (%d runs; %s)\n",
                    coverage ? "on" : "off", ms.front(), ms[ms.size() / 2], cpu_ms[cpu_ms.size() / 2], runs,
                    s.brief_report().c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::string figures;
    bool quick = false;
    bool raster_only = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--figures") && i + 1 < argc) figures = argv[++i];
        else if (!std::strcmp(argv[i], "--quick")) quick = true;
        else if (!std::strcmp(argv[i], "--raster")) raster_only = true;
    }
    std::printf("machine: %u hardware threads\n", std::thread::hardware_concurrency());
    const body::BodyModel& model = body::BodyModel::default_model();
    body::ShapedBody shaped;
    body::shape_body(model, model.prior.complete(body::SemanticRequest{}), body::ShapeOptions{}, shaped);
    const Eigen::MatrixXd V = body::pose_body(model, shaped, body::Pose::rest()).vertices;

    render::Scene scene;
    render::Mesh b;
    b.name = "body";
    b.V = V;
    b.F = model.faces;
    b.material.colour_srgb = {0.80, 0.74, 0.67};
    b.material.roughness = 0.55;
    b.label = 41;
    scene.meshes.push_back(b);
    scene.meshes.push_back(skirt(V, 100, 100));
    scene.floor.enabled = true;
    scene.floor.height_m = V.col(1).minCoeff();
    scene.backdrop.enabled = true;
    scene.backdrop.distance_m = 1.4;
    std::printf("scene: body %d vertices, garment %d vertices, %d + %d triangles (+ stage)\n",
                static_cast<int>(V.rows()), static_cast<int>(scene.meshes[1].V.rows()),
                static_cast<int>(model.faces.rows()), static_cast<int>(scene.meshes[1].F.rows()));

    const double cy = 0.52 * (V.col(1).maxCoeff() + V.col(1).minCoeff());
    // A fitted photo's camera (the fit-body convention: centre (0, 0, 5.2)) framing the body
    // as the path tracer's camera below does (its principal point moved down by cy).
    body::Camera fitted;
    fitted.model = body::CameraModel::pinhole;
    fitted.focal_px = 1800.0;
    fitted.distance_m = 5.2;
    fitted.offset_px = {300.0, 450.0 + fitted.focal_px * cy / fitted.distance_m};
    bench_raster(scene.meshes, fitted, quick ? 20 : 100);
    if (raster_only) return 0;

    const auto t0 = Clock::now();
    const render::Renderer renderer(scene);
    std::printf("%-44s %8.1f ms\n", "Renderer (validate + normals + BVH)", 1e3 * seconds_since(t0));

    const render::Camera camera = render::Camera::look_at({0.0, cy, 5.2}, {0.0, cy, 0.0}, {0, 1, 0}, 1800.0, 600, 900);
    render::RenderImages images;
    for (const render::LightingPreset preset :
         {render::LightingPreset::midday, render::LightingPreset::sunset, render::LightingPreset::studio}) {
        const render::Lighting lighting = render::lighting_preset(preset);
        for (const int spp : quick ? std::vector<int>{8} : std::vector<int>{4, 8, 16, 32}) {
            for (const int threads : {1, 2}) {
                if (quick && threads == 1) continue;
                render::RenderOptions opt;
                opt.samples_per_pixel = spp;
                opt.threads = threads;
                const std::clock_t c0 = std::clock();
                const render::RenderSummary s = renderer.render(camera, lighting, opt, images);
                const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
                std::printf("%-7s 600x900 %2d spp %d thread%s  wall %6.2f s  cpu %6.2f s  %5.2f Mrays/cpu-s\n",
                            lighting.name.c_str(), spp, threads, threads > 1 ? "s" : " ", s.trace_seconds, cpu,
                            1e-6 * s.rays / cpu);
            }
        }
    }
    if (!figures.empty()) {
        // Small documentation images: 64 spp at 600 x 900, downsampled to 300 x 450.
        for (const render::LightingPreset preset :
             {render::LightingPreset::midday, render::LightingPreset::sunset, render::LightingPreset::studio}) {
            const render::Lighting lighting = render::lighting_preset(preset);
            render::RenderOptions opt;
            opt.samples_per_pixel = 64;
            renderer.render(camera, lighting, opt, images);
            cv::Mat small;
            cv::resize(images.colour, small, cv::Size(300, 450), 0, 0, cv::INTER_AREA);
            const std::string path = figures + "/render_" + lighting.name + ".png";
            cv::imwrite(path, small);
            std::printf("wrote %s\n", path.c_str());
        }
        // The label map in false colour: 0 black, other ids spread around the hue circle.
        cv::Mat hsv(images.labels.size(), CV_8UC3);
        for (int y = 0; y < hsv.rows; ++y)
            for (int x = 0; x < hsv.cols; ++x) {
                const int id = images.labels.at<std::uint8_t>(y, x);
                hsv.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>((id * 47) % 180), 200,
                                                    static_cast<std::uint8_t>(id == 0 ? 0 : 230));
            }
        cv::Mat labels, small_labels;
        cv::cvtColor(hsv, labels, cv::COLOR_HSV2BGR);
        cv::resize(labels, small_labels, cv::Size(300, 450), 0, 0, cv::INTER_NEAREST);
        cv::imwrite(figures + "/render_labels.png", small_labels);
        std::printf("wrote %s/render_labels.png\n", figures.c_str());
    }
    return 0;
}
