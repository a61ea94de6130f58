// Times the output pieces of recovery (drape/recover/) on the default body (rest pose)
// and a 2 000-vertex garment (a tube around the hips, built here) at 600 x 900 pixels,
// seen by a fitted-photo pinhole camera: the label mask (mask.png and the per-mesh visible
// silhouettes that the recovery scores candidates with), with and without coverage masks,
// and the overlay (overlay.png, ray traced) over a plain photo. Prints the fastest and
// median wall time and the median CPU time (the reliable figure on a loaded machine).
// Usage: drape_bench_recover [--runs N] [--overlay-png FILE]
#include <drape/body/body_model.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/recover/label_mask.hpp>
#include <drape/recover/overlay.hpp>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <string>
#include <thread>
#include <vector>

using namespace drape;
using Clock = std::chrono::steady_clock;

namespace {

/// `rings` x `segments` vertices on an elliptic tube around the body's hips, 4 cm outside
/// its widest extent in the band from 45 % to 60 % of the height.
recover::OutfitGarment hip_tube(const Eigen::MatrixXd& body, int rings, int segments) {
    const double y0 = body.col(1).minCoeff(), h = body.col(1).maxCoeff() - y0;
    const double lo = y0 + 0.45 * h, hi = y0 + 0.60 * h;
    double ax = 0.0, az = 0.0;
    for (Eigen::Index v = 0; v < body.rows(); ++v)
        if (body(v, 1) >= lo && body(v, 1) <= hi && std::abs(body(v, 0)) < 0.25) {
            ax = std::max(ax, std::abs(body(v, 0)));
            az = std::max(az, std::abs(body(v, 2)));
        }
    recover::OutfitGarment g;
    g.name = "tube";
    g.class_id = 42;
    g.V.resize(rings * segments, 3);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double a = 2.0 * 3.14159265358979323846 * s / segments;
            g.V.row(r * segments + s) << (ax + 0.04) * std::cos(a), hi - (hi - lo) * r / (rings - 1),
                (az + 0.04) * std::sin(a);
        }
    g.F.resize(2 * (rings - 1) * segments, 3);
    for (int r = 0; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const int p = r * segments + s, q = r * segments + (s + 1) % segments;
            g.F.row(2 * (r * segments + s)) << p, q, p + segments;
            g.F.row(2 * (r * segments + s) + 1) << q, q + segments, p + segments;
        }
    return g;
}

/// Runs `step` `runs` times; prints its fastest and median wall and median CPU milliseconds.
void time_it(const char* what, int runs, const std::function<std::string()>& step) {
    std::vector<double> wall, cpu;
    std::string last;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = Clock::now();
        const std::clock_t c0 = std::clock();
        last = step();
        cpu.push_back(1e3 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
        wall.push_back(1e3 * std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::sort(wall.begin(), wall.end());
    std::sort(cpu.begin(), cpu.end());
    std::printf("%-40s wall fastest %7.2f ms, median %7.2f ms; cpu median %7.2f ms  (%d runs; %s)\n", what,
                wall.front(), wall[wall.size() / 2], cpu[cpu.size() / 2], runs, last.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 50;
    std::string overlay_png;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
        else if (!std::strcmp(argv[i], "--overlay-png") && i + 1 < argc) overlay_png = argv[++i];
    }
    std::printf("machine: %u hardware threads\n", std::thread::hardware_concurrency());
    const body::BodyModel& model = body::BodyModel::default_model();
    body::ShapedBody shaped;
    body::shape_body(model, model.prior.complete(body::SemanticRequest{}), body::ShapeOptions{}, shaped);

    recover::OutfitMeshes outfit;
    outfit.body_V = body::pose_body(model, shaped, body::Pose::rest()).vertices;
    outfit.body_F = model.faces;
    outfit.garments.push_back(hip_tube(outfit.body_V, 20, 100));
    std::printf("outfit: body %d vertices / %d triangles, garment %d vertices / %d triangles\n",
                static_cast<int>(outfit.body_V.rows()), static_cast<int>(outfit.body_F.rows()),
                static_cast<int>(outfit.garments[0].V.rows()), static_cast<int>(outfit.garments[0].F.rows()));

    // A fitted photo's camera (the fit-body convention: centre at (0, 0, 5.2)) framing the body.
    const double cy = 0.5 * (outfit.body_V.col(1).maxCoeff() + outfit.body_V.col(1).minCoeff());
    body::Camera camera;
    camera.model = body::CameraModel::pinhole;
    camera.focal_px = 1800.0;
    camera.distance_m = 5.2;
    camera.offset_px = {300.0, 450.0 + camera.focal_px * cy / camera.distance_m};

    for (const bool coverage : {false, true}) {
        recover::LabelMaskOptions options;
        options.width_px = 600;
        options.height_px = 900;
        options.coverage = coverage;
        recover::LabelMask mask;
        time_it(coverage ? "label_mask 600x900, coverage on" : "label_mask 600x900, coverage off", runs, [&] {
            const render::RasterSummary s = recover::label_mask(outfit, camera, options, mask);
            return "body " + std::to_string(s.visible_pixels[0]) + " px, garment " +
                   std::to_string(s.visible_pixels[1]) + " px visible";
        });
    }
    const cv::Mat photo(900, 600, CV_8UC3, cv::Scalar(170, 180, 190));
    cv::Mat overlay;
    time_it("render_overlay 600x900, 8 spp", std::max(1, runs / 10), [&] {
        overlay = recover::render_overlay(photo, outfit, camera);
        return std::string("default options");
    });
    if (!overlay_png.empty() && !cv::imwrite(overlay_png, overlay))
        std::fprintf(stderr, "cannot write '%s'\n", overlay_png.c_str());
    return 0;
}
