// The C facade, part 8: ray-traced renders of bodies and garments (librender).
#include "capi_internal.hpp"

#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/render_camera.hpp>

#include <drape/recover/tryon.hpp>
#include <drape/render/camera.hpp>
#include <drape/render/lighting.hpp>
#include <drape/render/overlay.hpp>
#include <drape/render/preview.hpp>
#include <drape/render/renderer.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::capi {

template <>
struct StructTraits<drape_render_options> {
    static constexpr const char* name = "drape_render_options";
    static auto fields() {
        using S = drape_render_options;
        return std::make_tuple(&S::lighting, &S::width, &S::height, &S::samples, &S::threads, &S::camera,
                               &S::camera_json, &S::photo_path, &S::opacity, &S::labels_path);
    }
    static drape_render_options defaults() {
        drape_render_options d{};
        d.struct_size = sizeof d;
        d.samples = 16;
        d.opacity = 1.0;
        d.camera = DRAPE_RENDER_CAMERA_AUTO;
        return d;
    }
};

}  // namespace drape::capi

namespace {

using namespace drape::capi;
namespace dr = drape::render;

void require_png(const std::string& path, const char* what) {
    if (std::filesystem::path(path).extension() != ".png")
        throw drape::InvalidInput(std::string(what) + " '" + path + "' must end in .png");
}

}  // namespace

extern "C" {

drape_status drape_render_options_init(drape_render_options* options) {
    return init_struct(options, __func__, "options");
}

drape_status drape_render(drape_body body, const drape_garment_mesh* garments, size_t garment_count,
                          const drape_render_options* options, const drape_monitor* monitor, const char* path) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    DRAPE_REQUIRE_ARG(garments || garment_count == 0, "garments must not be NULL when garment_count > 0");
    DRAPE_REQUIRE_ARG(path, "path must not be NULL");
    return guarded(__func__, [&, function = __func__] {
        const drape_render_options opt = read_struct(options, "options");
        require_png(path, "path");
        if (opt.labels_path) require_png(opt.labels_path, "options->labels_path");
        if (!(opt.samples >= 1 && opt.samples <= 4096))
            throw drape::InvalidInput("options->samples = " + std::to_string(opt.samples) + " must be in 1..4096");
        if (opt.threads < 0)
            throw drape::InvalidInput("options->threads = " + std::to_string(opt.threads) + " must be >= 0");
        if (!(opt.opacity >= 0 && opt.opacity <= 1))
            throw drape::InvalidInput("options->opacity = " + std::to_string(opt.opacity) + " must be in [0, 1]");
        if ((opt.width != 0 || opt.height != 0) && (opt.width <= 0 || opt.height <= 0 || opt.width > 12000 ||
                                                     opt.height > 12000))
            throw drape::InvalidInput("options->width x height = " + std::to_string(opt.width) + " x " +
                                      std::to_string(opt.height) + " must both be 0 or both in 1..12000");
        if (opt.camera < DRAPE_RENDER_CAMERA_AUTO || opt.camera > DRAPE_RENDER_CAMERA_FRONT)
            throw drape::InvalidInput("options->camera = " + std::to_string(opt.camera) +
                                      " is not a drape_render_camera value");
        const dr::Lighting lighting = dr::lighting_preset(dr::parse_lighting_preset(opt.lighting ? opt.lighting : "studio"));
        for (size_t i = 0; i < garment_count; ++i)
            if (!garments[i])
                throw drape::InvalidInput("garments[" + std::to_string(i) + "] must not be NULL");
        const nlohmann::json camera_json =
            opt.camera_json ? drape::io::parse_json_text(opt.camera_json, "options->camera_json") : nlohmann::json();
        Monitor mon(monitor, "render");
        const cv::Mat photo = opt.photo_path ? drape::io::read_photo(opt.photo_path) : cv::Mat();

        std::vector<dr::PreviewGarment> pg(garment_count);
        for (size_t i = 0; i < garment_count; ++i) {
            pg[i].V = garments[i]->positions;
            pg[i].F = garments[i]->mesh->cloth.faces;
            if (garments[i]->mesh->cloth.pattern.rows() == pg[i].V.rows())
                pg[i].UV = garments[i]->mesh->cloth.pattern;  // metres of pattern space: prints map on it
        }
        dr::Scene scene = dr::preview_scene(body->posed.vertices, body->model->faces, pg);
        scene.meshes[0].label = 41;  // labels.txt: skin
        for (size_t i = 0; i < garment_count; ++i)
            // The template's labels.txt class (the try-on's classes); 54 "top" for a pattern
            // read from a file without its template.
            scene.meshes[i + 1].label =
                garments[i]->pattern->sizing ? drape::recover::tryon_class_id(garments[i]->pattern->sizing->type) : 54;
        if (!photo.empty()) scene.floor.enabled = false;

        const bool fitted = !opt.camera_json && (opt.camera == DRAPE_RENDER_CAMERA_FITTED ||
                                                 (opt.camera == DRAPE_RENDER_CAMERA_AUTO && body->camera));
        if (fitted && !body->camera)
            throw drape::InvalidInput("options->camera is DRAPE_RENDER_CAMERA_FITTED but the body was not fitted to "
                                      "a photo (drape_body_fit, or a recovery's body)");
        int width = opt.width, height = opt.height;
        if (width == 0 && !photo.empty()) width = photo.cols, height = photo.rows;
        if (width == 0 && fitted && body->image_width > 0) width = body->image_width, height = body->image_height;
        if (width == 0) width = 600, height = 900;
        if (!photo.empty() && (photo.cols != width || photo.rows != height))
            throw drape::InvalidInput("options->photo_path '" + std::string(opt.photo_path) + "' is " +
                                      std::to_string(photo.cols) + " x " + std::to_string(photo.rows) +
                                      " pixels but the render is " + std::to_string(width) + " x " +
                                      std::to_string(height));
        const dr::Camera camera =
            opt.camera_json ? drape::io::render_camera_from_json(camera_json, "options->camera_json", width, height)
            : fitted        ? dr::Camera::from_body(*body->camera, width, height)
            : opt.camera == DRAPE_RENDER_CAMERA_FRONT ? dr::front_camera(scene, width, height)
                                                      : dr::preview_camera(body->posed.vertices, width, height);

        dr::RenderOptions ro;
        ro.samples_per_pixel = opt.samples;
        ro.threads = opt.threads;
        if (!mon.report("tracing", -1, 0, 0, 0)) return cancelled(function);
        const dr::Renderer renderer(scene);
        dr::RenderImages images;
        const dr::RenderSummary summary = renderer.render(
            camera, lighting, ro, images,
            [](double fraction, void* user) { return static_cast<Monitor*>(user)->report("tracing", -1, 0, 0, fraction); },
            &mon);
        if (!summary.usable() || mon.cancelled()) return cancelled(function);
        drape::io::write_png(path, photo.empty() ? images.colour : dr::composite_over(photo, images, opt.opacity));
        if (opt.labels_path) drape::io::write_png(opt.labels_path, images.labels);
        return DRAPE_OK;
    });
}

}  // extern "C"
