#include <drape/vision/segmentation.hpp>
#include <drape/vision/segmentation_score.hpp>
#include <drape/vision/strokes.hpp>

#include <drape/core/errors.hpp>

#include "synthetic_figure.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

using namespace drape;
using namespace drape::vision;

TEST_CASE("stroke-guided segmentation recovers a drawn figure", "[vision][segmentation]") {
    const test::SyntheticFigure f = test::make_figure();
    const cv::Mat strokes = simulate_strokes(f.labels);
    Segmentation seg;
    const SegmentationSummary s = segment_with_strokes(f.photo, strokes, &f.joints, {}, seg);
    INFO(s.brief_report());
    REQUIRE(s.usable());
    CHECK(s.garments_found == 2);
    for (int id : {51, 42, 41}) {
        INFO("class " << id);
        CHECK(vision::iou(seg.labels == id, f.labels == id) > 0.93);
    }
    // Stroked pixels keep their class.
    CHECK(cv::countNonZero((strokes != kUnmarked) & (seg.labels != strokes)) == 0);
    // The plain (colour-blind) stroke distance works too on flat colours.
    SegmentationOptions plain;
    plain.stroke_colour_weight = 0;
    Segmentation seg_plain;
    REQUIRE(segment_with_strokes(f.photo, strokes, &f.joints, plain, seg_plain).usable());
    for (int id : {51, 42}) CHECK(vision::iou(seg_plain.labels == id, f.labels == id) > 0.93);
    // Arms over the t-shirt's side and the face above the collar are occlusion borders.
    CHECK(cv::countNonZero(seg.occlusion) > 0);
}

TEST_CASE("the full-resolution band graph cut moves blocky borders onto the image edges",
          "[vision][segmentation][band]") {
    const test::SyntheticFigure f = test::make_figure();
    const cv::Mat strokes = simulate_strokes(f.labels);
    // Stage 1 on a 60 px grid and no superpixel vote: borders are ~7 px blocks.
    SegmentationOptions coarse;
    coarse.working_max_side_px = 60;
    coarse.refine_boundaries = false;
    coarse.band_fraction = 0;
    SegmentationOptions band = coarse;
    band.band_fraction = 0.012;
    Segmentation a, b;
    REQUIRE(segment_with_strokes(f.photo, strokes, &f.joints, coarse, a).usable());
    REQUIRE(segment_with_strokes(f.photo, strokes, &f.joints, band, b).usable());
    for (int id : {51, 42}) {
        const double before = vision::iou(a.labels == id, f.labels == id);
        const double after = vision::iou(b.labels == id, f.labels == id);
        INFO("class " << id << ": IoU " << before << " -> " << after);
        CHECK(after > before + 0.01);
        CHECK(after > 0.95);
    }
    // Border pixels only: away from the band nothing changes.
    const cv::Mat changed = a.labels != b.labels;
    cv::Mat hi, lo, border;
    cv::dilate(a.labels, hi, cv::Mat());
    cv::erode(a.labels, lo, cv::Mat());
    const int r = int(std::lround(band.band_fraction * f.joints.body_height_px()));
    cv::dilate(hi != lo, border, cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1}));
    CHECK(cv::countNonZero(changed & ~border) == 0);
    SegmentationOptions bad;
    bad.band_fraction = -0.1;
    CHECK_THROWS_WITH(segment_with_strokes(f.photo, strokes, &f.joints, bad, a),
                      Catch::Contains("band_fraction"));
    bad = SegmentationOptions{};
    bad.background_distance_factor = -1;
    CHECK_THROWS_WITH(segment_with_strokes(f.photo, strokes, &f.joints, bad, a),
                      Catch::Contains("background_distance_factor"));
}

TEST_CASE("automatic segmentation finds and classifies the drawn garments", "[vision][segmentation]") {
    for (auto bottom : {test::Bottom::skirt, test::Bottom::pants}) {
        const test::SyntheticFigure f = test::make_figure(bottom);
        Segmentation seg;
        const SegmentationSummary s = segment_automatic(f.photo, f.joints, {}, seg);
        INFO(s.brief_report());
        REQUIRE(s.usable());
        const int lower_id = bottom == test::Bottom::skirt ? 42 : 31;
        CHECK(vision::iou(seg.labels == 51, f.labels == 51) > 0.85);
        CHECK(vision::iou(seg.labels == lower_id, f.labels == lower_id) > 0.85);
        bool has_tshirt = false, has_lower = false;
        for (const auto& [id, type] : seg.garment_types) {
            has_tshirt |= type == GarmentType::t_shirt && id == 51;
            has_lower |= id == lower_id;
        }
        CHECK(has_tshirt);
        CHECK(has_lower);
    }
}

TEST_CASE("a hint overrides the lower garment type", "[vision][segmentation]") {
    const test::SyntheticFigure f = test::make_figure();
    SegmentationOptions o;
    o.hint = GarmentType::shorts;
    Segmentation seg;
    REQUIRE(segment_automatic(f.photo, f.joints, o, seg).usable());
    CHECK(cv::countNonZero(seg.labels == label_id_of(GarmentType::shorts)) > 0);
    CHECK(cv::countNonZero(seg.labels == 42) == 0);
}

TEST_CASE("segmentation rejects bad input and reports a garment-free photo", "[vision][segmentation][errors]") {
    const test::SyntheticFigure f = test::make_figure();
    const cv::Mat strokes = simulate_strokes(f.labels);
    Segmentation seg;
    cv::Mat small;
    cv::resize(strokes, small, cv::Size(200, 300), 0, 0, cv::INTER_NEAREST);
    CHECK_THROWS_WITH(segment_with_strokes(f.photo, small, nullptr, {}, seg),
                      Catch::Contains("200 x 300"));
    CHECK_THROWS_WITH(segment_with_strokes(f.photo, cv::Mat(600, 400, CV_8UC1, cv::Scalar(255)),
                                           nullptr, {}, seg),
                      Catch::Contains("mark no pixel"));
    cv::Mat no_bg = strokes.clone();
    no_bg.setTo(kUnmarked, strokes == 0);
    CHECK_THROWS_WITH(segment_with_strokes(f.photo, no_bg, nullptr, {}, seg),
                      Catch::Contains("background"));
    Joints off = f.joints;
    off[Joint::head] = {500, -20};
    CHECK_THROWS_WITH(segment_automatic(f.photo, off, {}, seg), Catch::Contains("head"));
    SegmentationOptions bad;
    bad.rounds = 0;
    CHECK_THROWS_AS(segment_automatic(f.photo, f.joints, bad, seg), InvalidInput);
    SegmentationOptions bad_colour;
    bad_colour.stroke_colour_weight = -1;
    CHECK_THROWS_WITH(segment_with_strokes(f.photo, strokes, &f.joints, bad_colour, seg),
                      Catch::Contains("stroke_colour_weight"));
    // Strokes with only background and skin: a clear "no garment" result, not an error.
    cv::Mat bare = strokes.clone();
    bare.setTo(kUnmarked, (strokes != 0) & (strokes != 41) & (strokes != kUnmarked));
    const SegmentationSummary s = segment_with_strokes(f.photo, bare, nullptr, {}, seg);
    CHECK(s.termination == SegmentationTermination::no_garment_found);
    CHECK_FALSE(s.usable());
}
