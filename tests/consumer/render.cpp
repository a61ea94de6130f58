// drape::render from an installed Drape: a square seen face-on by a fitted (weak
// perspective) camera covers the pixels its projection covers.
#include <drape/render/camera.hpp>
#include <drape/render/renderer.hpp>

#include <opencv2/core.hpp>

#include <cstdio>

int main() {
    namespace dr = drape::render;
    dr::Mesh square;
    square.name = "square";
    square.V.resize(4, 3);
    square.V << -0.1, -0.1, 0, 0.1, -0.1, 0, 0.1, 0.1, 0, -0.1, 0.1, 0;  // 20 cm
    square.F.resize(2, 3);
    square.F << 0, 1, 2, 0, 2, 3;
    square.label = 7;
    dr::Scene scene;
    scene.meshes.push_back(square);

    drape::body::Camera fitted;  // weak perspective, 100 px per metre, origin at (16, 16)
    fitted.scale_px_per_m = 100.0;
    fitted.offset_px = {16.0, 16.0};
    const dr::Camera camera = dr::Camera::from_body(fitted, 32, 32);
    dr::RenderOptions options;
    options.samples_per_pixel = 1;
    options.threads = 1;
    dr::RenderImages images;
    const dr::RenderSummary s = dr::render(scene, camera, dr::lighting_preset(dr::LightingPreset::studio),
                                           options, images);
    const int covered = cv::countNonZero(images.labels == 7);
    std::printf("%s; %d labelled pixels\n", s.brief_report().c_str(), covered);
    return s.usable() && covered == 400 ? 0 : 1;  // 20 x 20 px
}
