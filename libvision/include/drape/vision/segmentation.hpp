// Garment parsing (paper section 4.2, "Garment Parsing"): labels {background, skin, hair,
// each garment, occluders} for every pixel, either guided by user strokes or seeded
// automatically from the 14 joints.
//
// Both modes share two stages: (1) a multi-label graph cut (alpha-expansion with
// contrast-sensitive Potts smoothness, colour histogram models re-estimated GrabCut-style)
// at a working resolution, then (2) boundary refinement at full resolution: an edge-aware
// re-clustering into SLIC superpixels, each taking the majority label of its pixels, so
// that region borders follow the image's colour edges, then a pixel-level graph cut at
// full resolution in a narrow band around the class borders.
#pragma once

#include <drape/vision/garment_type.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/label_table.hpp>

#include <opencv2/core.hpp>

#include <optional>
#include <string>
#include <vector>

namespace drape::vision {

struct SegmentationOptions {
    /// Stage 1 runs on the photo shrunk so that its longer side is at most this.
    int working_max_side_px = 300;          ///< >= 32
    /// Weight of the contrast-sensitive Potts term (GrabCut's gamma, per unit edge).
    double smoothness = 12.0;               ///< >= 0
    int histogram_bins = 24;                ///< per channel, in [4, 64]
    /// Outer rounds of (graph cut, re-estimate colour models); alpha-expansion cycles per round.
    int rounds = 3;                         ///< >= 1
    int expansion_cycles = 2;               ///< >= 1
    /// Strokes mode: cost per body height of distance from the label's nearest stroke
    /// (a spatial prior that separates classes of similar colour).
    double stroke_distance_weight = 20.0;   ///< >= 0
    /// Strokes mode: the distance to a stroke is geodesic; a step across a colour
    /// difference |dc| costs (1 + stroke_colour_weight |dc| / <|dc|>) times its length,
    /// <|dc|> being the photo's mean neighbour difference (0 = plain distance).
    double stroke_colour_weight = 0.5;      ///< >= 0
    /// Strokes mode: the background's distance cost is scaled by this. The background
    /// surrounds the person and fills the frame, so most of its pixels lie far from its
    /// strokes (drawn along its medial axis) however surely they are background; a
    /// compact garment region has no such far pixels.
    double background_distance_factor = 0.625;  ///< >= 0
    /// Strokes mode, marks as evidence rather than law (docs/vision.md, "Segmentation"):
    /// a mark whose colour costs more than this (nats, -log p) under its class's colour
    /// model (from the marks) than under another marked class's is dropped as a slip or a
    /// stroke past a border. 0 keeps every mark.
    double mark_outlier_margin = 0.0;       ///< >= 0
    /// Strokes mode: marks within this distance (working px) of a strong colour edge (an
    /// RGB step to a 4-neighbour above `mark_edge_factor` x the photo's mean step) are soft
    /// evidence (`soft_mark_weight` per other label) instead of hard. 0 = all hard.
    double mark_edge_px = 0.0;              ///< >= 0
    double mark_edge_factor = 3.0;          ///< > 0
    double soft_mark_weight = 4.0;          ///< >= 0
    /// Strokes mode: the first colour model of a class takes the pixels within this
    /// geodesic distance (fraction of the body height) of its marks, not the marks alone,
    /// so that a few clicks sample their region. 0 = the marks.
    double seed_growth_fraction = 0.0;      ///< >= 0
    /// Strokes mode with joints: every class but the background costs up to this much more
    /// beyond `body_reach_fraction` x body height from the skeleton (ramping up over one
    /// more such distance). 0 = off.
    double body_prior_weight = 10.0;        ///< >= 0
    /// Strokes mode: when fewer than this fraction of the pixels are marked, the stroke
    /// distance weight is scaled by (marked fraction / this), down to a quarter. 0 = off.
    double sparse_marks_fraction = 0.01;    ///< in [0, 1]
    /// Strokes mode: marks drawn as clicks (compact blobs: a connected mark whose bounding
    /// box's longer side squared is below `compact_mark_elongation` x its area; a disk
    /// gives 4/pi, a stroke its length / width) say where a region is, not how far it
    /// reaches. The stroke distance weight is scaled by 1 - b (1 - this), b being the
    /// share of the marked pixels in such blobs, and the skeleton prior (body_prior_weight)
    /// divided by that scale (docs/notes/vision.md, 2026-11-26 b). 1 = off.
    double compact_marks_factor = 0.25;     ///< in (0, 1]
    double compact_mark_elongation = 2.0;   ///< > 0
    double body_reach_fraction = 0.12;      ///< > 0
    /// Strokes mode with joints: the automatic mode's learned spatial prior as soft
    /// evidence for the marked classes, each through its role (background, skin, hair,
    /// upper, lower; a dress: upper or lower; anything else: "other"), this weight x
    /// -ln p(role | body-frame cell) added to its cost. The marks say which classes are
    /// worn and their colours; where people wear them bounds what sparse or sloppy marks do
    /// not (docs/vision.md, "Segmentation"; tuned on the tuning part of photos-dev). 0 = off.
    double stroke_layout_weight = 0.5;      ///< >= 0
    /// Automatic mode: weight of the learned spatial prior, layout_weight x -ln p(label |
    /// body-frame cell) added to each label's colour cost (docs/vision.md, "Segmentation").
    double layout_weight = 0.5;             ///< >= 0
    bool refine_boundaries = true;
    /// SLIC superpixel size for the refinement, as a fraction of the body height (or of
    /// the image height in strokes mode without joints).
    double superpixel_fraction = 0.016;     ///< > 0
    /// Stage 2b: pixel-level graph cut at full resolution in a band of this half-width
    /// (fraction of the body height) around the class borders left by the superpixel
    /// vote; colour models re-estimated at full resolution, contrast-sensitive Potts term
    /// of weight `band_smoothness`. 0 turns the stage off.
    double band_fraction = 0.004;           ///< in [0, 0.2]
    double band_smoothness = 12.0;          ///< >= 0
    /// Connected pieces of a class smaller than this fraction of the image are merged into
    /// their surroundings.
    double min_piece_fraction = 0.0005;     ///< >= 0
    /// Automatic mode: a garment-type hint (e.g. skirt, dress) overrides the classifier
    /// for garments of its part (GarmentPart).
    std::optional<GarmentType> hint;
    /// Class table of the stroke/label ids.
    LabelTable table = LabelTable::fashionista();

    bool is_valid(std::string* why = nullptr) const;
};

enum class SegmentationTermination { ok, no_garment_found, failed };

struct SegmentationSummary {
    SegmentationTermination termination = SegmentationTermination::failed;
    std::string message;
    int labels_used = 0;            ///< distinct classes in the result
    int garments_found = 0;
    double seconds_graph_cut = 0;
    double seconds_refinement = 0;
    double seconds = 0;

    /// True when at least one garment was found.
    bool usable() const { return termination == SegmentationTermination::ok; }
    std::string brief_report() const;
};

/// A parse of one photo.
struct Segmentation {
    cv::Mat labels;     ///< CV_8UC1, photo size, class ids of the options' LabelTable
    /// CV_8UC1, 255 where something (hair, arms, bag, belt, ...) lies in front of a
    /// garment: non-garment pixels inside a garment's outline, and occluder/skin/hair
    /// pixels touching a garment. Later stages must not read these borders as garment edges.
    cv::Mat occlusion;
    /// Automatic mode: the type found for each garment id present in `labels`.
    std::vector<std::pair<int, GarmentType>> garment_types;
};

/// User-assisted parsing: `strokes` (CV_8UC1, photo size) holds class ids where marked and
/// kUnmarked (255) elsewhere; every class to appear in the result needs a stroke, and the
/// background (id 0) must be marked. Stroked pixels keep their class.
/// \param joints optional; sets the superpixel scale from the body height when given.
/// \throw drape::InvalidInput for a non-BGR image, strokes of another size/type, no
///        background or no stroke at all, ids unknown to the table, invalid options.
SegmentationSummary segment_with_strokes(const cv::Mat& image_bgr, const cv::Mat& strokes,
                                         const Joints* joints,
                                         const SegmentationOptions& options,
                                         Segmentation& result);

/// Automatic parsing seeded from the joints: body-part regions give the initial colour
/// models of upper garment, lower garment, skin, hair and background; rounds of graph
/// cuts refine them; upper-garment pixels along an arm that have the skin's chromaticity
/// rather than the garment's go back to skin (bare_arms.hpp); each garment is then
/// classified from its mask geometry relative to the joints (classify_garment.hpp) and
/// written with label_id_of(type). A photo where the
/// upper and lower regions share one colour model and meet at the waist is a dress.
/// \throw drape::InvalidInput for a non-BGR image, joints off the image, invalid options.
SegmentationSummary segment_automatic(const cv::Mat& image_bgr, const Joints& joints,
                                      const SegmentationOptions& options,
                                      Segmentation& result);

/// The share of the marked pixels of `strokes` (class ids, 255 = unmarked) that lie in
/// compact blobs: 8-connected marks whose bounding box's longer side squared is below
/// `max_elongation` x their area (clicks; a stroke's is its length / width). 0 if no mark.
double compact_mark_share(const cv::Mat& strokes, double max_elongation);

/// The occlusion mask of a label map (see Segmentation::occlusion).
cv::Mat occlusion_mask(const cv::Mat& labels, const LabelTable& table);

/// The photo with every class tinted in a fixed colour per id (background left as is) and
/// class borders outlined; for overlay.png.
cv::Mat draw_segmentation(const cv::Mat& image_bgr, const cv::Mat& labels);

}  // namespace drape::vision
