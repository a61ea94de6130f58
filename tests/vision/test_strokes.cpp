#include <drape/vision/image_io.hpp>
#include <drape/vision/label_table.hpp>
#include <drape/vision/strokes.hpp>

#include <drape/core/errors.hpp>

#include "synthetic_figure.hpp"
#include "test_paths.hpp"

#include <catch2/catch.hpp>
#include <opencv2/imgcodecs.hpp>
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

TEST_CASE("colour-coded strokes decode to the class ids they were drawn from", "[vision][strokes]") {
    const StrokePalette palette = StrokePalette::fashionista_default();
    std::string why;
    REQUIRE(palette.is_valid(&why));
    // Every two default colours differ by >= 127 in some channel.
    for (size_t i = 0; i < palette.entries.size(); ++i)
        for (size_t k = 0; k < i; ++k) {
            int d = 0;
            for (int c = 0; c < 3; ++c)
                d = std::max(d, std::abs(int(palette.entries[i].rgb[c]) - int(palette.entries[k].rgb[c])));
            CHECK(d >= 127);
        }
    // The drawn figure's strokes (background, skin, hair, t-shirt, skirt) round-trip.
    const test::SyntheticFigure f = test::make_figure();
    const cv::Mat ids = simulate_strokes(f.labels);
    std::vector<int> missing;
    const cv::Mat colours = colour_strokes(ids, palette, &missing);
    REQUIRE(colours.type() == CV_8UC4);
    CHECK(missing.empty());
    StrokeDecoding d;
    const cv::Mat back = strokes_from_colours(colours, palette, &d);
    CHECK(cv::countNonZero(back != ids) == 0);
    CHECK(d.marked_px == cv::countNonZero(ids != kUnmarked));
    CHECK(d.unrecognised_px == 0);
    // Channel order: OpenCV images are BGR; the skirt's yellow is (r, g, b) = (255, 255, 0).
    cv::Mat one(20, 20, CV_8UC3, cv::Scalar(255, 255, 255));
    one.at<cv::Vec3b>(3, 4) = cv::Vec3b(0, 255, 255);   // yellow in BGR
    one.at<cv::Vec3b>(5, 6) = cv::Vec3b(255, 0, 0);     // blue in BGR: background
    const cv::Mat decoded = strokes_from_colours(one, palette);
    const LabelTable& t = LabelTable::fashionista();
    CHECK(int(decoded.at<std::uint8_t>(3, 4)) == t.id("skirt"));
    CHECK(int(decoded.at<std::uint8_t>(5, 6)) == t.id("null"));
    CHECK(cv::countNonZero(decoded != kUnmarked) == 2);
    // A class the palette has no colour for is left out and named.
    cv::Mat with_necklace = ids.clone();
    with_necklace.at<std::uint8_t>(0, 0) = std::uint8_t(t.id("necklace"));
    colour_strokes(with_necklace, palette, &missing);
    CHECK(missing == std::vector<int>{t.id("necklace")});
}

TEST_CASE("hand-drawn anti-aliased strokes mark their cores and leave blends unmarked", "[vision][strokes]") {
    const StrokePalette palette = StrokePalette::fashionista_default();
    const LabelTable& t = LabelTable::fashionista();
    // A transparent layer: the brush's anti-aliasing fades alpha; a white canvas: it blends
    // the colour towards white. Either way the blends must not become another class.
    for (const bool layer : {true, false}) {
        cv::Mat canvas = layer ? cv::Mat(200, 200, CV_8UC4, cv::Scalar(0, 0, 0, 0))
                               : cv::Mat(200, 200, CV_8UC3, cv::Scalar(255, 255, 255));
        const cv::Scalar yellow = layer ? cv::Scalar(0, 255, 255, 255) : cv::Scalar(0, 255, 255);
        const cv::Scalar red = layer ? cv::Scalar(0, 0, 255, 255) : cv::Scalar(0, 0, 255);
        cv::line(canvas, {20, 30}, {180, 150}, yellow, 7, cv::LINE_AA);
        cv::line(canvas, {20, 170}, {170, 20}, red, 5, cv::LINE_AA);
        StrokeDecoding d;
        const cv::Mat ids = strokes_from_colours(canvas, palette, &d);
        INFO((layer ? "RGBA layer" : "white canvas") << ": " << d.marked_px << " marked, "
                                                     << d.unrecognised_px << " unrecognised");
        int skirt = 0, tshirt = 0, other = 0;
        for (size_t i = 0; i < ids.total(); ++i) {
            const int v = ids.data[i];
            if (v == kUnmarked) continue;
            if (v == t.id("skirt")) ++skirt;
            else if (v == t.id("t-shirt")) ++tshirt;
            else ++other;
        }
        CHECK(other == 0);
        CHECK(skirt > 5 * 190);   // at least 5 px of the 7 px wide, ~200 px long line
        CHECK(tshirt > 3 * 200);
        // Where the two strokes cross (x 100, y 90) the later, red one wins.
        CHECK(int(ids.at<std::uint8_t>(90, 100)) == t.id("t-shirt"));
    }
}

TEST_CASE("stroke palettes and colour-coded strokes reject bad input", "[vision][strokes][errors]") {
    StrokePalette p = StrokePalette::fashionista_default();
    std::string why;
    p.entries.push_back({LabelTable::fashionista().id("coat"), cv::Vec3b(250, 250, 10)});  // ~ skirt yellow
    CHECK_FALSE(p.is_valid(&why));
    CHECK(why.find("#fafa0a") != std::string::npos);
    p = StrokePalette::fashionista_default();
    p.entries.push_back({p.entries[0].class_id, cv::Vec3b(10, 10, 10)});
    CHECK_FALSE(p.is_valid(&why));
    CHECK(why.find("two colours") != std::string::npos);
    p = StrokePalette::fashionista_default();
    p.tolerance = 64;
    CHECK_FALSE(p.is_valid());
    CHECK_THROWS_AS(StrokePalette::parse_hex("#12345"), InvalidInput);
    CHECK_THROWS_AS(StrokePalette::parse_hex("#12345g"), InvalidInput);
    CHECK(StrokePalette::parse_hex("#FFa000") == cv::Vec3b(255, 160, 0));
    CHECK(StrokePalette::hex(cv::Vec3b(255, 160, 0)) == "#ffa000");
    const StrokePalette d = StrokePalette::fashionista_default();
    // A drawing in colours of no palette entry is an error naming the colour it found.
    cv::Mat grey(50, 50, CV_8UC3, cv::Scalar(255, 255, 255));
    cv::rectangle(grey, cv::Rect(10, 10, 20, 20), cv::Scalar(60, 200, 90), cv::FILLED);
    try {
        strokes_from_colours(grey, d);
        FAIL("no error");
    } catch (const InvalidInput& e) {
        CHECK(std::string(e.what()).find("#5ac83c") != std::string::npos);
    }
    CHECK_THROWS_AS(strokes_from_colours(cv::Mat(10, 10, CV_16UC3, cv::Scalar(0)), d), InvalidInput);
    CHECK_THROWS_AS(strokes_from_colours(cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)), d), InvalidInput);
    CHECK_THROWS_AS(colour_strokes(cv::Mat(10, 10, CV_8UC3), d), InvalidInput);
}

TEST_CASE("load_strokes reads class-id and colour-coded PNGs alike", "[vision][strokes]") {
    const test::SyntheticFigure f = test::make_figure();
    const cv::Mat ids = simulate_strokes(f.labels);
    const StrokePalette palette = StrokePalette::fashionista_default();
    const auto dir = test::scratch_dir("load_strokes");
    cv::imwrite((dir / "ids.png").string(), ids);
    cv::imwrite((dir / "rgba.png").string(), colour_strokes(ids, palette));
    cv::Mat rgb;
    cv::cvtColor(colour_strokes(ids, palette), rgb, cv::COLOR_BGRA2BGR);  // black where unmarked
    cv::imwrite((dir / "rgb.png").string(), rgb);
    for (const char* name : {"ids.png", "rgba.png", "rgb.png"}) {
        INFO(name);
        CHECK(cv::countNonZero(load_strokes(dir / name, palette) != ids) == 0);
    }
    cv::Mat deep(40, 40, CV_16UC1, cv::Scalar(1000));
    cv::imwrite((dir / "deep.png").string(), deep);
    CHECK_THROWS_AS(load_strokes(dir / "deep.png", palette), InvalidInput);
    CHECK_THROWS_AS(load_strokes(dir / "absent.png", palette), IoError);
}
