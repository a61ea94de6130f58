#include <drape/render/overlay.hpp>

#include <drape/core/errors.hpp>

#include <cmath>

namespace drape::render {

cv::Mat composite_over(const cv::Mat& photo, const RenderImages& render, double opacity) {
    require(opacity >= 0.0 && opacity <= 1.0, "composite_over: opacity must be in [0, 1], got ", opacity);
    require(photo.type() == CV_8UC3, "composite_over: the photo must be 8-bit BGR (CV_8UC3)");
    require(render.foreground.type() == CV_8UC3 && render.alpha.type() == CV_8UC1 &&
                render.foreground.size() == render.alpha.size(),
            "composite_over: the render has no foreground/alpha images of matching size");
    require(photo.size() == render.alpha.size(), "composite_over: the photo is ", photo.cols, " x ",
            photo.rows, " pixels but the render is ", render.alpha.cols, " x ", render.alpha.rows);
    cv::Mat out(photo.size(), CV_8UC3);
    for (int y = 0; y < photo.rows; ++y) {
        const auto* p = photo.ptr<cv::Vec3b>(y);
        const auto* f = render.foreground.ptr<cv::Vec3b>(y);
        const auto* a = render.alpha.ptr<std::uint8_t>(y);
        auto* o = out.ptr<cv::Vec3b>(y);
        for (int x = 0; x < photo.cols; ++x) {
            const double w = opacity * a[x] / 255.0;
            for (int k = 0; k < 3; ++k)
                o[x][k] = static_cast<std::uint8_t>(std::lround(w * f[x][k] + (1.0 - w) * p[x][k]));
        }
    }
    return out;
}

}  // namespace drape::render
