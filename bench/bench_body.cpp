// Prints timings of the body pipeline: model generation, shaping, posing, measuring, export.
// Usage: drape_bench_body [repetitions]   (see docs/benchmarks.md)
#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/model_io.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <thread>

using namespace drape::body;
using Clock = std::chrono::steady_clock;

namespace {

double time_ms(int reps, const std::function<void()>& f) {
    const auto t0 = Clock::now();
    for (int i = 0; i < reps; ++i) f();
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / reps;
}

}  // namespace

int main(int argc, char** argv) {
    const int reps = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
    std::printf("machine: %u hardware threads\n", std::thread::hardware_concurrency());
    const auto t0 = Clock::now();
    const BodyModel& model = BodyModel::default_model();
    std::printf("%-40s %10.1f ms (once)\n", "build default model (mesh+rig+basis)",
                std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    std::printf("model: %d vertices, %d faces, %d shape columns\n", model.vertex_count(),
                static_cast<int>(model.faces.rows()), model.shape_count());

    SemanticRequest req;
    req.gender = Gender::male;
    req[Semantic::height_m] = 1.80;
    req[Semantic::weight_kg] = 80;
    const SemanticShape shape = model.prior.complete(req);
    ShapedBody body;
    ShapeOptions linear;
    linear.match_measurements = false;
    std::printf("%-40s %10.3f ms\n", "prior.complete", time_ms(reps * 100, [&] { (void)model.prior.complete(req); }));
    std::printf("%-40s %10.2f ms\n", "shape_body (linear map only)",
                time_ms(reps, [&] { shape_body(model, shape, linear, body); }));
    std::printf("%-40s %10.2f ms\n", "shape_body (measurements matched)",
                time_ms(reps, [&] { shape_body(model, shape, ShapeOptions{}, body); }));
    std::printf("%-40s %10.2f ms\n", "measure_body", time_ms(reps, [&] { (void)measure_body(model, body.vertices); }));
    const Pose pose = named_pose(NamedPose::walking);
    std::printf("%-40s %10.2f ms\n", "pose_body (FK + LBS)", time_ms(reps, [&] { (void)pose_body(model, body, pose); }));
    const auto dir = std::filesystem::temp_directory_path();
    std::printf("%-40s %10.2f ms\n", "export_glb",
                time_ms(std::max(1, reps / 4), [&] { export_glb(dir / "drape_bench.glb", model, body, pose); }));
    std::printf("%-40s %10.2f ms\n", "save_model (HDF5)",
                time_ms(std::max(1, reps / 4), [&] { save_model(model, dir / "drape_bench.h5"); }));
    std::printf("%-40s %10.2f ms\n", "load_model (HDF5, isolated reader)",
                time_ms(std::max(1, reps / 4), [&] { (void)load_model(dir / "drape_bench.h5"); }));
    ModelLoadOptions in_process;
    in_process.isolate = false;
    std::printf("%-40s %10.2f ms\n", "load_model (HDF5, in process)",
                time_ms(std::max(1, reps / 4), [&] { (void)load_model(dir / "drape_bench.h5", in_process); }));
    return 0;
}
