// label_mask: class ids with occlusion on rectangles whose pixel counts are known.
#include <drape/core/errors.hpp>
#include <drape/recover/label_mask.hpp>

#include "outfit_fixture.hpp"

#include <catch2/catch.hpp>

using namespace drape;

namespace {

long long count_value(const cv::Mat& m, int value) {
    long long n = 0;
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x) n += m.at<std::uint8_t>(y, x) == value;
    return n;
}

recover::LabelMaskOptions options_300(bool coverage = false) {
    recover::LabelMaskOptions o;
    o.width_px = 300;
    o.height_px = 300;
    o.coverage = coverage;
    return o;
}

}  // namespace

TEST_CASE("label mask: class ids with occlusion, per-mesh visible silhouettes", "[recover][mask]") {
    const recover::OutfitMeshes outfit = test::rectangle_outfit();
    recover::LabelMask mask;
    const render::RasterSummary s = recover::label_mask(outfit, test::rectangle_camera(), options_300(true), mask);
    REQUIRE(s.usable());
    REQUIRE(mask.labels.type() == CV_8UC1);
    REQUIRE(mask.labels.rows == 300);
    REQUIRE(mask.labels.cols == 300);
    // Body 40 000 px minus the 10 000 under the skirt; the skirt all 12 000; the t-shirt hidden.
    CHECK(count_value(mask.labels, 41) == 30000);
    CHECK(count_value(mask.labels, 42) == 12000);
    CHECK(count_value(mask.labels, 51) == 0);
    CHECK(count_value(mask.labels, 0) == 300 * 300 - 42000);
    REQUIRE(mask.visible.size() == 3);
    CHECK(mask.visible_pixels == std::vector<long long>{30000, 12000, 0});
    CHECK(s.visible_pixels == mask.visible_pixels);
    CHECK(count_value(mask.visible[0], 255) == 30000);
    CHECK(count_value(mask.visible[1], 255) == 12000);
    CHECK(count_value(mask.visible[2], 255) == 0);
    REQUIRE(mask.coverage.size() == 3);
    CHECK(count_value(mask.coverage[0], 255) == 40000);
    CHECK(count_value(mask.coverage[1], 255) == 12000);
    CHECK(count_value(mask.coverage[2], 255) == 160 * 70);
    // Pixel spot checks: body at (60, 60), skirt at (150, 260) below the body, empty corner.
    CHECK(int(mask.labels.at<std::uint8_t>(60, 60)) == 41);
    CHECK(int(mask.labels.at<std::uint8_t>(260, 150)) == 42);
    CHECK(int(mask.labels.at<std::uint8_t>(5, 5)) == 0);

    // Without coverage the coverage masks stay empty; the labels are the same.
    recover::LabelMask fast;
    recover::label_mask(outfit, test::rectangle_camera(), options_300(false), fast);
    CHECK(fast.coverage[1].empty());
    CHECK(cv::countNonZero(fast.labels != mask.labels) == 0);
}

TEST_CASE("label mask: at equal depth the outer garment shows over the inner one and the body",
          "[recover][mask]") {
    recover::OutfitMeshes outfit = test::rectangle_outfit();
    outfit.garments[0] = test::rectangle(-0.5, 0.5, -0.5, 0.5, 0.0, 42);  // flush with the body
    outfit.garments[1] = test::rectangle(-0.2, 0.2, -0.2, 0.2, 0.0, 51);  // flush, outer
    recover::LabelMask mask;
    recover::label_mask(outfit, test::rectangle_camera(), options_300(), mask);
    CHECK(mask.visible_pixels == std::vector<long long>{40000 - 10000, 10000 - 1600, 1600});
    CHECK(int(mask.labels.at<std::uint8_t>(150, 150)) == 51);
}

TEST_CASE("label mask: pinhole camera, nothing in view, bad input", "[recover][mask]") {
    recover::OutfitMeshes outfit = test::rectangle_outfit();
    body::Camera pin;
    pin.model = body::CameraModel::pinhole;
    pin.focal_px = 500.0;
    pin.distance_m = 5.0;
    pin.offset_px = {150.0, 150.0};
    recover::LabelMask mask;
    REQUIRE(recover::label_mask(outfit, pin, options_300(), mask).usable());
    // The skirt is nearer than the body: under it the skirt shows.
    CHECK(int(mask.labels.at<std::uint8_t>(157, 150)) == 42);
    CHECK(mask.visible_pixels[0] > 0);

    body::Camera away = test::rectangle_camera();
    away.offset_px = {5000.0, 5000.0};
    const render::RasterSummary s = recover::label_mask(outfit, away, options_300(), mask);
    CHECK(s.termination == render::RasterTermination::nothing_in_view);
    CHECK(cv::countNonZero(mask.labels) == 0);

    auto throws_naming = [&](recover::OutfitMeshes o, const std::string& what) {
        try {
            recover::label_mask(o, test::rectangle_camera(), options_300(), mask);
            FAIL("no exception for " << what);
        } catch (const InvalidInput& e) {
            CHECK_THAT(e.what(), Catch::Contains(what));
        }
    };
    recover::OutfitMeshes bad = outfit;
    bad.garments[1].class_id = 0;
    throws_naming(bad, "garment 1 'tshirt': class id 0");
    bad = outfit;
    bad.garments[0].F(0, 0) = 9;
    throws_naming(bad, "garment 0 'skirt': F indexes");
    bad = outfit;
    bad.body_V(0, 0) = std::nan("");
    throws_naming(bad, "body: V has non-finite");
    bad = outfit;
    bad.garments[0].UV.resize(3, 2);
    throws_naming(bad, "UV is 3 x 2");
    recover::LabelMaskOptions zero = options_300();
    zero.width_px = 0;
    CHECK_THROWS_AS(recover::label_mask(outfit, test::rectangle_camera(), zero, mask), InvalidInput);
}
