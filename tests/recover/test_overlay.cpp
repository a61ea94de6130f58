// render_overlay: where nothing is drawn the photo is unchanged; the body blends with its
// opacity, garments show in their preview colours; side by side keeps the photo on the left.
#include <drape/core/errors.hpp>
#include <drape/recover/overlay.hpp>

#include "outfit_fixture.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>

using namespace drape;

namespace {

/// A 300 x 300 photo with a gradient, so that unchanged pixels are told apart.
cv::Mat gradient_photo() {
    cv::Mat p(300, 300, CV_8UC3);
    for (int y = 0; y < p.rows; ++y)
        for (int x = 0; x < p.cols; ++x)
            p.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>(60 + x / 3), 120, static_cast<std::uint8_t>(60 + y / 3));
    return p;
}

recover::OverlayOptions fast(double body_opacity, double garment_opacity) {
    recover::OverlayOptions o;
    o.body_opacity = body_opacity;
    o.garment_opacity = garment_opacity;
    o.samples_per_pixel = 4;
    return o;
}

}  // namespace

TEST_CASE("overlay: photo outside the meshes, body blended by its opacity, garments in colour",
          "[recover][overlay]") {
    const cv::Mat photo = gradient_photo();
    const recover::OutfitMeshes outfit = test::rectangle_outfit();
    const body::Camera camera = test::rectangle_camera();
    const cv::Mat full = recover::render_overlay(photo, outfit, camera, fast(1.0, 1.0));
    const cv::Mat half = recover::render_overlay(photo, outfit, camera, fast(0.5, 1.0));
    const cv::Mat none = recover::render_overlay(photo, outfit, camera, fast(0.0, 1.0));
    REQUIRE(full.type() == CV_8UC3);
    REQUIRE(full.size() == photo.size());

    // Outside every mesh (the body is pixels 50..249, the skirt reaches row 269): the photo.
    for (const cv::Point p : {cv::Point(10, 10), cv::Point(280, 150), cv::Point(60, 290)})
        CHECK(full.at<cv::Vec3b>(p) == photo.at<cv::Vec3b>(p));
    // Body only (not under the skirt): opacity 0 leaves the photo, 0.5 is the mean of the
    // photo and the opaque render, and the opaque render is not the photo.
    int changed = 0, off_mean = 0;
    for (int y = 60; y < 140; y += 7)
        for (int x = 60; x < 240; x += 7) {
            const cv::Vec3b p = photo.at<cv::Vec3b>(y, x), f = full.at<cv::Vec3b>(y, x), h = half.at<cv::Vec3b>(y, x);
            CHECK(none.at<cv::Vec3b>(y, x) == p);
            for (int k = 0; k < 3; ++k) {
                changed += std::abs(f[k] - p[k]) > 20;
                off_mean += std::abs(2 * h[k] - (f[k] + p[k])) > 2;
            }
        }
    CHECK(changed > 100);
    CHECK(off_mean == 0);
    // The skirt (garment 0) is opaque and in the preview's first garment colour, blue.
    const cv::Vec3b skirt = none.at<cv::Vec3b>(200, 150);
    CHECK(int(skirt[0]) > int(skirt[2]) + 40);
    CHECK(skirt == full.at<cv::Vec3b>(200, 150));
}

TEST_CASE("overlay: side by side, bad input", "[recover][overlay]") {
    const cv::Mat photo = gradient_photo();
    const recover::OutfitMeshes outfit = test::rectangle_outfit();
    const body::Camera camera = test::rectangle_camera();
    recover::OverlayOptions o = fast(0.45, 0.85);
    const cv::Mat blended = recover::render_overlay(photo, outfit, camera, o);
    o.layout = recover::OverlayLayout::side_by_side;
    const cv::Mat side = recover::render_overlay(photo, outfit, camera, o);
    REQUIRE(side.cols == 600);
    REQUIRE(side.rows == 300);
    CHECK(cv::norm(side.colRange(0, 300), photo, cv::NORM_INF) == 0);
    CHECK(cv::norm(side.colRange(300, 600), blended, cv::NORM_INF) == 0);

    o = fast(1.5, 0.85);
    CHECK_THROWS_AS(recover::render_overlay(photo, outfit, camera, o), InvalidInput);
    o = fast(0.5, 0.5);
    o.samples_per_pixel = 0;
    CHECK_THROWS_AS(recover::render_overlay(photo, outfit, camera, o), InvalidInput);
    cv::Mat gray(300, 300, CV_8UC1, cv::Scalar(128));
    CHECK_THROWS_WITH(recover::render_overlay(gray, outfit, camera, fast(0.5, 0.5)),
                      Catch::Contains("8-bit BGR"));
    recover::OutfitMeshes bad = outfit;
    bad.garments[0].V.resize(0, 3);
    CHECK_THROWS_WITH(recover::render_overlay(photo, bad, camera, fast(0.5, 0.5)),
                      Catch::Contains("garment 0 'skirt'"));
}
