// Simulated user strokes: what a user would scribble, derived from a ground-truth label map
// by a deterministic procedure (docs/vision.md, "Simulated strokes"). Used by the
// evaluation and by `drape strokes`; never a copy of the labels.
#pragma once

#include <opencv2/core.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::vision {

struct StrokeOptions {
    /// Regions are eroded by this fraction of the image diagonal (at least 1 px) before
    /// their medial axis is taken, so strokes stay clear of the region boundary.
    double erosion_fraction = 0.008;      ///< >= 0
    /// Connected regions smaller than this fraction of the image get no stroke.
    double min_region_fraction = 0.0004;  ///< >= 0
    int max_strokes_per_region = 3;       ///< >= 1
    /// A stroke shorter than this fraction of the image diagonal is dropped (except the
    /// first stroke of a region, which is always kept).
    double min_stroke_fraction = 0.02;    ///< >= 0
    int stroke_width_px = 1;              ///< >= 1, pen width of the drawn medial path
    /// Hard cap on marked pixels as a fraction of the image (shortest strokes go first).
    double max_marked_fraction = 0.03;    ///< in (0, 1]

    bool is_valid(std::string* why = nullptr) const;
};

/// Strokes for every class of `labels` (8-bit single-channel class ids): per connected
/// region (8-connected) of each class, erode, thin to the medial axis (Zhang-Suen), then
/// take the longest geodesic path through the axis as the first stroke and up to
/// max_strokes_per_region - 1 further longest paths through the axis pixels not yet
/// covered. Marked pixels hold the class id, others kUnmarked (255).
/// \throw drape::InvalidInput for a non-CV_8UC1 or empty map, or invalid options.
cv::Mat simulate_strokes(const cv::Mat& labels, const StrokeOptions& options = {});

/// How a simulated user draws (docs/vision.md, "Simulated strokes").
enum class StrokeStyle {
    medial,  ///< the longest paths through each region's eroded medial axis (above)
    dashes,  ///< short horizontal dashes through the region cores, <= 3 % of the pixels
    dots,    ///< a few click-like small disks per region
    sloppy,  ///< dashes over whole regions that stray a few px over borders; ~1 % wrong class
};

/// "medial", "dashes", "dots", "sloppy".
const char* to_string(StrokeStyle style);
/// Parses a style name. \throw drape::InvalidInput naming the text.
StrokeStyle parse_stroke_style(const std::string& text);

/// Strokes of the given style for every class of `labels` (as above). The dashes, dots and
/// sloppy styles draw their parameters (dash length, spacing, pen width, dot count and
/// radius, stray distance) and positions from `seed`: the same labels and seed give the
/// same strokes, another seed another pattern. `medial` ignores the seed. `options`
/// supplies min_region_fraction, erosion_fraction (the core of a region) and
/// max_marked_fraction (the budget) to every style.
/// \throw drape::InvalidInput as simulate_strokes.
cv::Mat simulate_strokes(const cv::Mat& labels, StrokeStyle style, std::uint64_t seed,
                         const StrokeOptions& options = {});

/// Fraction of the marked pixels of `strokes` whose class differs from `labels`' (0 when
/// nothing is marked). \pre equal sizes, both CV_8UC1.
double wrong_mark_fraction(const cv::Mat& strokes, const cv::Mat& labels);

/// Fraction of pixels of a stroke map that are marked (not 255).
double marked_fraction(const cv::Mat& strokes);

// ---- Colour-coded strokes, for people drawing by hand (docs/vision.md) -----------------

/// The colour of each class in a hand-drawn stroke image. A pixel is marked with a class
/// when it is opaque (alpha >= 128, if the image has alpha) and each of its channels is
/// within `tolerance` of the class's colour; every other pixel (a transparent layer, a
/// white or black canvas, anti-aliased stroke borders, the photo itself) is unmarked. A
/// marked pixel whose colour is another class's colour mixed 20-80 % with black, white or a
/// third palette colour, next to a pixel of that class, is that stroke's anti-aliased rim
/// (or where two strokes cross) and is unmarked too.
struct StrokePalette {
    struct Entry {
        int class_id = 0;     ///< id of the label table, 0..254
        cv::Vec3b rgb;        ///< the colour, (r, g, b)
    };
    std::vector<Entry> entries;
    int tolerance = 40;  ///< 0..63; colours of distinct entries must differ by more than 2x this in some channel

    /// Colours for the classes a user marks (`fashionista_default` ids): background
    /// (null) blue, skin orange, hair maroon, t-shirt red, top (tank top) magenta, shirt
    /// (long-sleeve top) purple, sweater violet, dress green, skirt yellow, pants cyan,
    /// shorts teal, jeans navy, jacket dark green, bag olive, belt pink, shoes lime.
    /// Every channel is 0, 128 or 255, so any two colours differ by >= 127 somewhere.
    static StrokePalette fashionista_default();
    /// "#rrggbb" of an entry's colour.
    static std::string hex(const cv::Vec3b& rgb);
    /// Parses "#rrggbb" (or "rrggbb"). \throw drape::InvalidInput naming the text.
    static cv::Vec3b parse_hex(const std::string& text);

    bool is_valid(std::string* why = nullptr) const;
};

/// What decoding a colour-coded stroke image found.
struct StrokeDecoding {
    long long marked_px = 0;            ///< pixels given a class
    long long unrecognised_px = 0;      ///< opaque pixels of no palette colour (left unmarked)
    std::vector<std::pair<int, long long>> per_class;  ///< (class id, pixels), ascending id
    cv::Vec3b most_common_unrecognised{0, 0, 0};  ///< (r, g, b), ignoring white and black
    long long most_common_unrecognised_px = 0;
};

/// Class-id strokes (CV_8UC1, 255 = unmarked) from a colour-coded image: CV_8UC3 (BGR, as
/// OpenCV reads) or CV_8UC4 (BGRA). \throw drape::InvalidInput for another type, an
/// invalid palette, or an image in which no pixel has a palette colour.
cv::Mat strokes_from_colours(const cv::Mat& image, const StrokePalette& palette,
                             StrokeDecoding* report = nullptr);

/// The colour-coded image (CV_8UC4 BGRA, transparent where unmarked) of class-id strokes.
/// Classes without a palette colour are left out and listed in `missing` (ascending).
cv::Mat colour_strokes(const cv::Mat& strokes, const StrokePalette& palette,
                       std::vector<int>* missing = nullptr);

/// Reads user strokes of either kind: an 8-bit single-channel PNG of class ids (255 =
/// unmarked) as it is, or a colour-coded PNG (RGB or RGBA) decoded with `palette`.
/// \throw drape::IoError (missing/unreadable), drape::InvalidInput (another pixel format,
///        no palette colour found, size limits).
cv::Mat load_strokes(const std::filesystem::path& path, const StrokePalette& palette,
                     StrokeDecoding* report = nullptr);

}  // namespace drape::vision
