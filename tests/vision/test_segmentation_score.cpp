// Segmentation scoring (drape/vision/segmentation_score.hpp): role masks and IoU with known
// answers.
#include <drape/vision/segmentation_score.hpp>

#include <drape/core/errors.hpp>

#include <catch2/catch.hpp>

using namespace drape::vision;

TEST_CASE("role_mask is the union of a role's classes", "[vision][score]") {
    const LabelTable& t = LabelTable::fashionista();
    // labels.txt: 41 skin, 42 skirt, 51 t-shirt, 31 pants, 0 null.
    cv::Mat labels = (cv::Mat_<std::uint8_t>(2, 3) << 0, 41, 42, 51, 31, 51);
    const cv::Mat lower = role_mask(labels, t, LabelRole::lower_garment);
    const cv::Mat expected = (cv::Mat_<std::uint8_t>(2, 3) << 0, 0, 255, 0, 255, 0);
    CHECK(cv::countNonZero(lower != expected) == 0);
    CHECK(cv::countNonZero(role_mask(labels, t, LabelRole::upper_garment)) == 2);
    CHECK(cv::countNonZero(role_mask(labels, t, LabelRole::full_garment)) == 0);
    // A view into a larger map (not continuous) reads the right pixels.
    cv::Mat big = cv::Mat::zeros(4, 5, CV_8UC1);
    labels.copyTo(big(cv::Rect(1, 1, 3, 2)));
    CHECK(cv::countNonZero(role_mask(big(cv::Rect(1, 1, 3, 2)), t, LabelRole::lower_garment) != expected) == 0);
    CHECK_THROWS_AS(role_mask(cv::Mat::zeros(2, 2, CV_16UC1), t, LabelRole::skin), drape::InvalidInput);
}

TEST_CASE("iou counts non-zero pixels as inside", "[vision][score]") {
    cv::Mat a = cv::Mat::zeros(10, 10, CV_8UC1), b = cv::Mat::zeros(10, 10, CV_8UC1);
    CHECK(iou(a, b) == 1.0);  // both empty
    a(cv::Rect(0, 0, 6, 10)).setTo(255);
    b(cv::Rect(3, 0, 7, 10)).setTo(1);  // any non-zero value is inside
    CHECK(iou(a, b) == Approx(30.0 / 100.0));
    CHECK(iou(a, a) == 1.0);
    CHECK_THROWS_AS(iou(a, cv::Mat::zeros(5, 10, CV_8UC1)), drape::InvalidInput);
    CHECK_THROWS_AS(iou(cv::Mat::zeros(10, 10, CV_8UC3), a), drape::InvalidInput);
}
