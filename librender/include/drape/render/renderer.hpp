// Ray-traced renders of a Scene (Embree for the rays, TBB for parallel tiles): a
// tone-mapped sRGB colour image with soft sun shadows and sky occlusion (so cloth folds
// read), plus per-pixel coverage, label and depth maps.
//
// Determinism: every pixel is computed independently from a hash of (pixel, sample,
// dimension), the BVH is built single-threaded, so the output bytes do not depend on the
// number of threads.
#pragma once

#include <drape/render/camera.hpp>
#include <drape/render/lighting.hpp>
#include <drape/render/scene.hpp>

#include <opencv2/core.hpp>

#include <Eigen/Core>

#include <memory>
#include <string>

namespace drape::render {

struct RenderOptions {
    /// Samples per pixel (anti-aliasing, soft shadows, sky occlusion); 1..4096. 16 gives
    /// clean renders; 4 is a fast preview; 64 for figures.
    int samples_per_pixel = 16;
    int threads = 0;  ///< 0 = all hardware threads
    /// Where a pixel sees no geometry (sRGB in [0, 1]); ignored when a backdrop fills the view.
    Eigen::Vector3d background_srgb{1.0, 1.0, 1.0};
    /// Sky-occlusion rays see occluders up to this far (metres); beyond, the sky is open.
    /// Keeps interiors of loose garments from going black.
    double occlusion_distance_m = 4.0;

    bool is_valid(std::string* why = nullptr) const;
};

/// Images of one render, all width x height.
struct RenderImages {
    cv::Mat colour;      ///< CV_8UC3 BGR, sRGB: the scene over background_srgb
    cv::Mat foreground;  ///< CV_8UC3 BGR, sRGB: colour of the covered part only (for overlays)
    cv::Mat alpha;       ///< CV_8UC1, fraction of samples that hit geometry x 255
    cv::Mat labels;      ///< CV_8UC1, label of the surface at the pixel centre, 0 where none
    cv::Mat mesh_index;  ///< CV_16SC1, index into Scene::meshes at the pixel centre; -1 none/stage
    cv::Mat depth;       ///< CV_32FC1, metres along the centre ray from the eye; +inf where none
};

enum class RenderTermination { rendered, cancelled };

struct RenderSummary {
    RenderTermination termination = RenderTermination::rendered;
    std::string message;
    int width_px = 0;
    int height_px = 0;
    int samples_per_pixel = 0;
    int threads = 0;
    long long triangles = 0;
    long long rays = 0;          ///< primary + shadow + sky rays traced
    double build_seconds = 0.0;  ///< BVH build (once per Renderer)
    double trace_seconds = 0.0;

    bool usable() const { return termination == RenderTermination::rendered; }
    std::string brief_report() const;
};

/// Called between tile rows with the finished fraction in [0, 1]; return false to cancel.
using RenderProgress = bool (*)(double fraction, void* user);

/// A scene prepared for rendering (BVH built once), so that several cameras or lightings
/// (e.g. midday and sunset of one synthetic scene) reuse it. Not copyable; render() may be
/// called from one thread at a time per Renderer.
class Renderer {
public:
    /// Validates and copies the scene, builds the BVH.
    /// \throw drape::InvalidInput (see Scene::validate).
    explicit Renderer(const Scene& scene);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    /// Renders the scene seen by `camera` under `lighting` into `out` (reallocated).
    /// \throw drape::InvalidInput on an invalid camera, lighting or options.
    RenderSummary render(const Camera& camera, const Lighting& lighting,
                         const RenderOptions& options, RenderImages& out,
                         RenderProgress progress = nullptr, void* progress_user = nullptr) const;

    /// Triangles in the BVH (meshes and stage).
    long long triangle_count() const;
    /// Wall-clock seconds spent building the BVH in the constructor.
    double build_seconds() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// One-shot convenience: Renderer(scene).render(...).
RenderSummary render(const Scene& scene, const Camera& camera, const Lighting& lighting,
                     const RenderOptions& options, RenderImages& out);

}  // namespace drape::render
