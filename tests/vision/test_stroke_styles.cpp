// The seeded stroke simulators (dashes, dots, sloppy; strokes.hpp) and stroke-guided
// segmentation that holds with each of them (docs/vision.md, "Simulated strokes").
#include <drape/vision/segmentation.hpp>
#include <drape/vision/segmentation_score.hpp>
#include <drape/vision/strokes.hpp>

#include <drape/core/errors.hpp>

#include "synthetic_figure.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgproc.hpp>

using namespace drape;
using namespace drape::vision;

namespace {

/// Distance (px) of every pixel to the nearest pixel of class `id` (0 on the class).
cv::Mat distance_to_class(const cv::Mat& labels, int id) {
    cv::Mat d;
    cv::distanceTransform(labels != id, d, cv::DIST_L2, 3);
    return d;
}

/// Every class of the figure (each covers > 0.5 % of the image) is marked.
void check_every_region_marked(const cv::Mat& labels, const cv::Mat& strokes) {
    for (int id : {0, 19, 41, 42, 51}) {
        INFO("class " << id);
        REQUIRE(cv::countNonZero(labels == id) > 0.005 * double(labels.total()));
        CHECK(cv::countNonZero(strokes == id) > 0);
    }
}

}  // namespace

TEST_CASE("dashes: short horizontal marks in the region cores, <= 3 %", "[vision][strokes][styles]") {
    const test::SyntheticFigure f = test::make_figure();
    const cv::Mat s = simulate_strokes(f.labels, StrokeStyle::dashes, 11);
    check_every_region_marked(f.labels, s);
    CHECK(marked_fraction(s) <= 0.03);
    CHECK(marked_fraction(s) > 0.005);
    CHECK(wrong_mark_fraction(s, f.labels) == 0);
    // Horizontal dashes: every connected mark is at most 3 px tall and wider than tall.
    cv::Mat comp, stats, cent;
    const int n = cv::connectedComponentsWithStats(s != kUnmarked, comp, stats, cent, 8, CV_32S);
    int wide = 0;
    for (int c = 1; c < n; ++c) {
        CHECK(stats.at<int>(c, cv::CC_STAT_HEIGHT) <= 3);
        wide += stats.at<int>(c, cv::CC_STAT_WIDTH) > stats.at<int>(c, cv::CC_STAT_HEIGHT);
    }
    CHECK(wide > 0.8 * (n - 1));
    // In the cores: the t-shirt's and skirt's marks keep >= 4 px from their borders
    // (core depth 0.8 % of the 721 px diagonal = 5.8 px, pen rows +-1).
    for (int id : {42, 51}) {
        cv::Mat inside;
        cv::distanceTransform(f.labels == id, inside, cv::DIST_L2, 3);
        double lo = 1e9;
        for (int y = 0; y < s.rows; ++y)
            for (int x = 0; x < s.cols; ++x)
                if (s.at<std::uint8_t>(y, x) == id) lo = std::min(lo, double(inside.at<float>(y, x)));
        CHECK(lo >= 4.0);
    }
    // Deterministic by seed; another seed, another pattern.
    CHECK(cv::countNonZero(simulate_strokes(f.labels, StrokeStyle::dashes, 11) != s) == 0);
    CHECK(cv::countNonZero(simulate_strokes(f.labels, StrokeStyle::dashes, 12) != s) > 100);
}

TEST_CASE("dots: a few small disks per region", "[vision][strokes][styles]") {
    const test::SyntheticFigure f = test::make_figure();
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        INFO("seed " << seed);
        const cv::Mat s = simulate_strokes(f.labels, StrokeStyle::dots, seed);
        check_every_region_marked(f.labels, s);
        CHECK(wrong_mark_fraction(s, f.labels) == 0);
        CHECK(marked_fraction(s) < 0.01);
        // Per class: 1 to 4 dots per connected region (the figure's regions: background 1,
        // hair 1, skin (face + neck, arms, legs) several, t-shirt 1, skirt 1), each a disk
        // of radius 2 to 5 px.
        for (int id : {0, 42, 51}) {
            cv::Mat comp, stats, cent;
            const int n = cv::connectedComponentsWithStats(s == id, comp, stats, cent, 8, CV_32S);
            INFO("class " << id << ": " << n - 1 << " dots");
            CHECK(n - 1 >= 1);
            CHECK(n - 1 <= 4);
            for (int c = 1; c < n; ++c) {
                CHECK(stats.at<int>(c, cv::CC_STAT_WIDTH) <= 11);
                CHECK(stats.at<int>(c, cv::CC_STAT_WIDTH) >= 5);
            }
        }
        CHECK(cv::countNonZero(simulate_strokes(f.labels, StrokeStyle::dots, seed) != s) == 0);
    }
    CHECK(cv::countNonZero(simulate_strokes(f.labels, StrokeStyle::dots, 1) !=
                           simulate_strokes(f.labels, StrokeStyle::dots, 2)) > 0);
}

TEST_CASE("sloppy strokes stray a few px over borders, ~1 % of the marks in a wrong class",
          "[vision][strokes][styles]") {
    const test::SyntheticFigure f = test::make_figure();
    for (std::uint64_t seed : {5u, 6u, 7u}) {
        INFO("seed " << seed);
        const cv::Mat s = simulate_strokes(f.labels, StrokeStyle::sloppy, seed);
        check_every_region_marked(f.labels, s);
        CHECK(marked_fraction(s) <= 0.03);
        const double wrong = wrong_mark_fraction(s, f.labels);
        CHECK(wrong >= 0.008);
        CHECK(wrong <= 0.0105);
        // Strays (<= 5 px past a border, <= 0.6 % of the marks) exist; the wrong marks
        // farther than 5 px from their class are the slip of the pen (the rest of the 1 %).
        long long marked = 0, stray = 0, far = 0;
        cv::Mat dist[256];
        for (int y = 0; y < s.rows; ++y)
            for (int x = 0; x < s.cols; ++x) {
                const int v = s.at<std::uint8_t>(y, x);
                if (v == kUnmarked) continue;
                ++marked;
                if (v == f.labels.at<std::uint8_t>(y, x)) continue;
                if (dist[v].empty()) dist[v] = distance_to_class(f.labels, v);
                if (dist[v].at<float>(y, x) <= 5.5f) ++stray;
                else ++far;
            }
        CHECK(stray > 0);
        CHECK(double(far) <= 0.0101 * double(marked));
        CHECK(cv::countNonZero(simulate_strokes(f.labels, StrokeStyle::sloppy, seed) != s) == 0);
    }
}

TEST_CASE("stroke styles parse and reject bad input", "[vision][strokes][styles][errors]") {
    for (StrokeStyle st : {StrokeStyle::medial, StrokeStyle::dashes, StrokeStyle::dots, StrokeStyle::sloppy})
        CHECK(parse_stroke_style(to_string(st)) == st);
    CHECK_THROWS_AS(parse_stroke_style("scribbles"), InvalidInput);
    CHECK_THROWS_AS(simulate_strokes(cv::Mat(), StrokeStyle::dots, 1), InvalidInput);
    CHECK_THROWS_AS(simulate_strokes(cv::Mat(10, 10, CV_8UC3), StrokeStyle::sloppy, 1), InvalidInput);
    // The medial style ignores the seed.
    const test::SyntheticFigure f = test::make_figure();
    CHECK(cv::countNonZero(simulate_strokes(f.labels, StrokeStyle::medial, 9) != simulate_strokes(f.labels)) == 0);
}

TEST_CASE("stroke-guided segmentation holds with dashes, dots and sloppy strokes",
          "[vision][segmentation][styles]") {
    const test::SyntheticFigure f = test::make_figure();
    for (StrokeStyle st : {StrokeStyle::dashes, StrokeStyle::dots, StrokeStyle::sloppy})
        for (std::uint64_t seed : {1u}) {
            const cv::Mat strokes = simulate_strokes(f.labels, st, seed);
            Segmentation seg;
            const SegmentationSummary s = segment_with_strokes(f.photo, strokes, &f.joints, {}, seg);
            INFO(to_string(st) << " seed " << seed << ": " << s.brief_report());
            REQUIRE(s.usable());
            for (int id : {51, 42}) {
                const double v = vision::iou(seg.labels == id, f.labels == id);
                INFO("class " << id << " IoU " << v);
                CHECK(v > 0.95);
            }
        }
}

TEST_CASE("a few clicks: background of a garment's colour far from the person stays background",
          "[vision][segmentation][styles]") {
    // The drawn figure with two patches of the t-shirt's and the skirt's colours in the
    // background, far from the skeleton (a poster, a parked car): the background's few
    // clicks lie far from them, the garments' colour models match them.
    // The figure's 400 x 600 frame widened by 200 px of background on each side.
    test::SyntheticFigure f = test::make_figure();
    cv::copyMakeBorder(f.photo, f.photo, 0, 0, 200, 200, cv::BORDER_REFLECT);
    cv::copyMakeBorder(f.labels, f.labels, 0, 0, 200, 200, cv::BORDER_CONSTANT, cv::Scalar(0));
    for (auto& j : f.joints.px) j.x() += 200;
    cv::rectangle(f.photo, cv::Rect(640, 330, 120, 200), cv::Scalar(60, 50, 170), cv::FILLED);
    cv::rectangle(f.photo, cv::Rect(30, 20, 120, 150), cv::Scalar(190, 120, 60), cv::FILLED);
    SegmentationOptions without = SegmentationOptions{};
    without.body_prior_weight = 0;
    without.sparse_marks_fraction = 0;
    double sum_with = 0, sum_without = 0;
    for (std::uint64_t seed : {1u, 2u}) {
        const cv::Mat dots = simulate_strokes(f.labels, StrokeStyle::dots, seed);
        Segmentation a, b;
        REQUIRE(segment_with_strokes(f.photo, dots, &f.joints, {}, a).usable());
        REQUIRE(segment_with_strokes(f.photo, dots, &f.joints, without, b).usable());
        for (int id : {51, 42}) {
            const double va = vision::iou(a.labels == id, f.labels == id);
            const double vb = vision::iou(b.labels == id, f.labels == id);
            INFO("seed " << seed << " class " << id << ": IoU " << vb << " without the skeleton and sparse-mark priors, "
                         << va << " with");
            CHECK(va > 0.9);
            sum_with += va;
            sum_without += vb;
        }
    }
    INFO("mean IoU without " << sum_without / 4 << ", with " << sum_with / 4);
    CHECK(sum_with >= sum_without - 4 * 0.01);
}

TEST_CASE("compact_mark_share: clicks are compact, strokes are not", "[vision][strokes][styles]") {
    const test::SyntheticFigure f = test::make_figure();
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        INFO("seed " << seed);
        const double dots = compact_mark_share(simulate_strokes(f.labels, StrokeStyle::dots, seed), 2.0);
        const double medial = compact_mark_share(simulate_strokes(f.labels, StrokeStyle::medial, seed), 2.0);
        const double dashes = compact_mark_share(simulate_strokes(f.labels, StrokeStyle::dashes, seed), 2.0);
        const double sloppy = compact_mark_share(simulate_strokes(f.labels, StrokeStyle::sloppy, seed), 2.0);
        INFO("dots " << dots << ", medial " << medial << ", dashes " << dashes << ", sloppy " << sloppy);
        CHECK(dots > 0.8);
        CHECK(medial < 0.05);
        CHECK(dashes < 0.1);
        CHECK(sloppy < 0.1);
    }
    // A hand-made map: one 7 x 7 disk-like square (compact) and one 1 x 40 line.
    cv::Mat s(100, 100, CV_8UC1, cv::Scalar(kUnmarked));
    s(cv::Rect(10, 10, 7, 7)).setTo(0);
    s(cv::Rect(30, 50, 40, 1)).setTo(42);
    CHECK(compact_mark_share(s, 2.0) == Approx(49.0 / 89.0));
    CHECK(compact_mark_share(cv::Mat(10, 10, CV_8UC1, cv::Scalar(kUnmarked)), 2.0) == 0.0);
    CHECK_THROWS_AS(compact_mark_share(cv::Mat(), 2.0), InvalidInput);
}
