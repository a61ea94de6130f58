// group_ious: IoU, precision, recall and the row and width errors on rectangles whose pixel
// counts are known.
#include <drape/core/errors.hpp>
#include <drape/recover/metrics.hpp>

#include <catch2/catch.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <string>

using namespace drape;

TEST_CASE("group IoU: precision, recall, rows and width of rectangles", "[recover][metrics]") {
    // 200 x 300 label maps. Truth: a t-shirt (51) on rows 50-149, columns 40-139 (100 x 100)
    // and a skirt (42) on rows 150-249, columns 50-129 (100 rows x 80).
    cv::Mat truth(300, 200, CV_8UC1, cv::Scalar(0));
    cv::rectangle(truth, cv::Rect(40, 50, 100, 100), cv::Scalar(51), cv::FILLED);
    cv::rectangle(truth, cv::Rect(50, 150, 80, 100), cv::Scalar(42), cv::FILLED);
    // Hair (19) above the top on rows 30-39, columns 40-129.
    cv::rectangle(truth, cv::Rect(40, 30, 90, 10), cv::Scalar(19), cv::FILLED);
    // Predicted: the top 20 rows too high and 10 px narrower (rows 30-129, columns 40-129, a
    // blouse id of the same group), the skirt as labelled but 30 rows longer (rows 150-279).
    cv::Mat predicted(300, 200, CV_8UC1, cv::Scalar(0));
    cv::rectangle(predicted, cv::Rect(40, 30, 90, 100), cv::Scalar(5), cv::FILLED);
    cv::rectangle(predicted, cv::Rect(50, 150, 80, 130), cv::Scalar(42), cv::FILLED);
    // The body's arm (41) beside the top: columns 130-139, rows 50-129.
    cv::rectangle(predicted, cv::Rect(130, 50, 10, 80), cv::Scalar(41), cv::FILLED);

    const auto g = recover::group_ious(predicted, truth);
    const recover::GroupIou& upper = g[0];
    const recover::GroupIou& lower = g[1];
    const recover::GroupIou& dress = g[2];
    REQUIRE(upper.group == recover::GarmentGroup::upper);
    REQUIRE(upper.counted);
    // Upper: intersection rows 50-129 x columns 40-129 = 80 x 90 = 7200; predicted 9000,
    // truth 10000, union 11800.
    CHECK(upper.iou == Approx(7200.0 / 11800.0).epsilon(1e-12));
    CHECK(upper.precision == Approx(7200.0 / 9000.0).epsilon(1e-12));
    CHECK(upper.recall == Approx(7200.0 / 10000.0).epsilon(1e-12));
    // Both rectangles are 100 rows tall: the 2nd and 98th percentile rows are the 2nd and
    // 97th rows of each (equal pixels per row), 20 rows apart.
    CHECK(upper.top_row_error_px == Approx(-20.0));
    CHECK(upper.bottom_row_error_px == Approx(-20.0));
    // Rows covered by both (50-129): 90 predicted against 100 labelled pixels.
    CHECK(upper.width_error_px == Approx(-10.0));
    // The 1800 wrongly predicted pixels: 900 on the hair, 900 on the background.
    CHECK(upper.false_positive_shares[1] == Approx(900.0 / 9000.0).epsilon(1e-12));
    CHECK(upper.false_positive_shares[2] == Approx(900.0 / 9000.0).epsilon(1e-12));
    CHECK(upper.false_positive_shares[0] == 0.0);
    CHECK(upper.false_positive_shares[3] == 0.0);
    // The 2800 missed pixels: 800 under the arm, 2000 (rows 130-149) on nothing.
    CHECK(upper.false_negative_shares[0] == Approx(800.0 / 10000.0).epsilon(1e-12));
    CHECK(upper.false_negative_shares[1] == Approx(2000.0 / 10000.0).epsilon(1e-12));
    CHECK(upper.false_negative_shares[2] == 0.0);
    CHECK(std::string(recover::false_positive_names()[1]) == "hair");
    CHECK(std::string(recover::false_negative_names()[0]) == "body");
    // Lower: the prediction holds the truth; 8000 of 10400 predicted pixels are right.
    REQUIRE(lower.counted);
    CHECK(lower.recall == Approx(1.0));
    CHECK(lower.precision == Approx(8000.0 / 10400.0).epsilon(1e-12));
    CHECK(lower.iou == Approx(8000.0 / 10400.0).epsilon(1e-12));
    CHECK(lower.top_row_error_px == Approx(0.0).margin(1.0));
    // 98th percentile rows: 150 + 0.98 * 130 - 1 and 150 + 0.98 * 100 - 1, rounded up to a row.
    CHECK(lower.bottom_row_error_px == Approx(std::ceil(0.98 * 130) - std::ceil(0.98 * 100)).margin(1.0));
    CHECK(lower.width_error_px == Approx(0.0));
    CHECK(lower.false_positive_shares[2] == Approx(2400.0 / 10400.0).epsilon(1e-12));
    // No dress anywhere: not counted, its diagnostics undefined.
    CHECK_FALSE(dress.counted);
    CHECK(dress.iou == 0.0);
    CHECK(std::isnan(dress.precision));
    CHECK(std::isnan(dress.recall));
    CHECK(std::isnan(dress.top_row_error_px));

    SECTION("a missing prediction has recall 0 and no rows") {
        cv::Mat none(300, 200, CV_8UC1, cv::Scalar(0));
        const auto e = recover::group_ious(none, truth);
        CHECK(e[0].iou == 0.0);
        CHECK(e[0].recall == 0.0);
        CHECK(std::isnan(e[0].precision));
        CHECK(std::isnan(e[0].bottom_row_error_px));
    }
    SECTION("maps of different sizes are refused") {
        cv::Mat small(100, 200, CV_8UC1, cv::Scalar(0));
        CHECK_THROWS_AS(recover::group_ious(small, truth), InvalidInput);
    }
}
