#include <drape/vision/image_io.hpp>
#include <drape/vision/label_table.hpp>
#include <drape/vision/strokes.hpp>

#include <drape/core/errors.hpp>

#include "synthetic_figure.hpp"
#include "test_paths.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

using namespace drape;
using namespace drape::vision;

namespace {

/// Every marked pixel holds its own ground-truth class; every large class is marked.
void check_strokes(const cv::Mat& labels, const cv::Mat& strokes) {
    REQUIRE(strokes.size() == labels.size());
    REQUIRE(strokes.type() == CV_8UC1);
    int wrong = 0;
    bool marked[256] = {};
    int area[256] = {};
    for (size_t i = 0; i < labels.total(); ++i) {
        ++area[labels.data[i]];
        if (strokes.data[i] == kUnmarked) continue;
        marked[strokes.data[i]] = true;
        wrong += strokes.data[i] != labels.data[i];
    }
    CHECK(wrong == 0);
    for (int id = 0; id < 255; ++id)
        if (area[id] > 0.01 * double(labels.total())) CHECK(marked[id]);
    CHECK(marked_fraction(strokes) <= 0.03);
    CHECK(marked_fraction(strokes) > 0.001);
}

}  // namespace

TEST_CASE("simulated strokes follow the medial axis of every region", "[vision][strokes]") {
    const test::SyntheticFigure f = test::make_figure();
    const cv::Mat s = simulate_strokes(f.labels);
    check_strokes(f.labels, s);
    // Strokes stay away from region borders: each marked pixel is at least the erosion
    // radius (0.8 % of the diagonal = 6 px) inside its region.
    cv::Mat dist;
    for (int id : {42, 51}) {
        cv::distanceTransform(f.labels == id, dist, cv::DIST_L2, 3);
        double min_d = 1e9;
        for (int y = 0; y < s.rows; ++y)
            for (int x = 0; x < s.cols; ++x)
                if (s.at<std::uint8_t>(y, x) == id) min_d = std::min(min_d, double(dist.at<float>(y, x)));
        CHECK(min_d >= 5.0);
    }
    // Deterministic.
    CHECK(cv::countNonZero(simulate_strokes(f.labels) != s) == 0);
}

TEST_CASE("simulated strokes respect the 3 % budget on real label maps", "[vision][strokes][photos]") {
    DRAPE_REQUIRE_SHARED(labels_path, "data/photos/labels/fashionista_002149.png");
    const cv::Mat labels = load_label_map(labels_path, "labels");
    const cv::Mat s = simulate_strokes(labels);
    check_strokes(labels, s);
    StrokeOptions tight;
    tight.max_marked_fraction = 0.005;
    CHECK(marked_fraction(simulate_strokes(labels, tight)) <= 0.005);
}

TEST_CASE("simulate_strokes rejects bad input", "[vision][strokes][errors]") {
    CHECK_THROWS_AS(simulate_strokes(cv::Mat()), InvalidInput);
    CHECK_THROWS_AS(simulate_strokes(cv::Mat(10, 10, CV_8UC3)), InvalidInput);
    StrokeOptions bad;
    bad.max_marked_fraction = 0;
    CHECK_THROWS_AS(simulate_strokes(cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), bad), InvalidInput);
}
