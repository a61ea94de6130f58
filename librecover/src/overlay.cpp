#include <drape/recover/overlay.hpp>

#include <drape/core/errors.hpp>
#include <drape/render/camera.hpp>
#include <drape/render/overlay.hpp>
#include <drape/render/preview.hpp>
#include <drape/render/renderer.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace drape::recover {

namespace {

/// The opacity of pixel (x, y): the body's where its centre sees the body (mesh 0), the
/// garments' where it sees a garment; an anti-aliased rim pixel (centre sees nothing) takes
/// the opacity of the mesh most of its 8 neighbours see.
double pixel_opacity(const cv::Mat& mesh_index, int x, int y, double body, double garment) {
    const std::int16_t m = mesh_index.at<std::int16_t>(y, x);
    if (m == 0) return body;
    if (m > 0) return garment;
    int bodies = 0, garments = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            if (u < 0 || v < 0 || u >= mesh_index.cols || v >= mesh_index.rows) continue;
            const std::int16_t n = mesh_index.at<std::int16_t>(v, u);
            bodies += n == 0;
            garments += n > 0;
        }
    return bodies > garments ? body : garment;
}

}  // namespace

bool OverlayOptions::is_valid(std::string* why) const {
    std::ostringstream s;
    if (!(body_opacity >= 0.0 && body_opacity <= 1.0)) s << "body_opacity must be in [0, 1], got " << body_opacity;
    else if (!(garment_opacity >= 0.0 && garment_opacity <= 1.0))
        s << "garment_opacity must be in [0, 1], got " << garment_opacity;
    else if (samples_per_pixel < 1 || samples_per_pixel > 4096)
        s << "samples_per_pixel must be in 1..4096, got " << samples_per_pixel;
    else if (threads < 0) s << "threads must be >= 0, got " << threads;
    if (why) *why = s.str();
    return s.str().empty();
}

cv::Mat render_overlay(const cv::Mat& photo, const OutfitMeshes& outfit, const body::Camera& camera,
                       const OverlayOptions& options) {
    std::string why;
    require(options.is_valid(&why), "render_overlay: ", why);
    require(!photo.empty() && photo.type() == CV_8UC3, "render_overlay: the photo must be a non-empty 8-bit BGR "
            "image (CV_8UC3), got ", photo.cols, " x ", photo.rows, " of type ", photo.type());
    outfit.validate();
    std::vector<render::PreviewGarment> garments;
    garments.reserve(outfit.garments.size());
    for (const OutfitGarment& g : outfit.garments) garments.push_back({g.V, g.F, g.UV});
    render::Scene scene = render::preview_scene(outfit.body_V, outfit.body_F, garments);
    scene.floor.enabled = false;  // the photo is the background

    render::RenderOptions ro;
    ro.samples_per_pixel = options.samples_per_pixel;
    ro.threads = options.threads;
    render::RenderImages images;
    render::render(scene, render::Camera::from_body(camera, photo.cols, photo.rows),
                   render::lighting_preset(options.lighting), ro, images);

    // Per-pixel opacity folded into the render's alpha, then one composite.
    for (int y = 0; y < images.alpha.rows; ++y) {
        auto* a = images.alpha.ptr<std::uint8_t>(y);
        for (int x = 0; x < images.alpha.cols; ++x) {
            if (a[x] == 0) continue;
            const double o = pixel_opacity(images.mesh_index, x, y, options.body_opacity, options.garment_opacity);
            a[x] = static_cast<std::uint8_t>(std::lround(o * a[x]));
        }
    }
    cv::Mat blended = render::composite_over(photo, images, 1.0);
    if (options.layout == OverlayLayout::blended) return blended;
    cv::Mat side;
    cv::hconcat(photo, blended, side);
    return side;
}

}  // namespace drape::recover
