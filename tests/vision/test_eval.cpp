// Real photos (../shared/data/photos): a few in the default suite; the full 30-photo
// evaluation is `drape eval-segment` (docs/vision.md).
#include <drape/vision/garment_result.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/segmentation.hpp>
#include <drape/vision/segmentation_score.hpp>
#include <drape/vision/strokes.hpp>

#include <drape/core/errors.hpp>

#include "synthetic_figure.hpp"
#include "test_paths.hpp"

#include <catch2/catch.hpp>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include <fstream>

using namespace drape;
using namespace drape::vision;

namespace {

struct Photo {
    cv::Mat image, labels;
    Joints joints;
};

/// Loads NAME from the shared photos (or another folder of ../shared in their layout);
/// joints converted from 1-based to the image frame.
bool load_photo(const std::string& name, Photo& p, const char* folder = "data/photos") {
    const auto dir = test::shared_path(folder);
    if (dir.empty()) return false;
    p.image = load_image(dir / "images" / (name + ".jpg"));
    p.labels = load_label_map(dir / "labels" / (name + ".png"), "labels");
    std::ifstream f(dir / "joints" / (name + ".json"));
    const nlohmann::json j = nlohmann::json::parse(f);
    for (size_t i = 0; i < 14; ++i)
        p.joints.px[i] = {j["joints"][i][0].get<double>() - 0.5, j["joints"][i][1].get<double>() - 0.5};
    return true;
}

cv::Mat role_mask(const cv::Mat& labels, LabelRole role) {
    return vision::role_mask(labels, LabelTable::fashionista(), role);
}

}  // namespace

TEST_CASE("stroke-guided and automatic parsing of real photos", "[vision][photos]") {
    // A skirt + t-shirt photo and a jeans + shirt photo.
    for (const std::string name : {"fashionista_002149", "fashionista_008973"}) {
        Photo p;
        if (!load_photo(name, p)) {
            WARN("skipped: ../shared/data/photos not found (set DRAPE_SHARED_DIR)");
            return;
        }
        INFO(name);
        Segmentation seg;
        const SegmentationSummary s =
            segment_with_strokes(p.image, simulate_strokes(p.labels), &p.joints, {}, seg);
        INFO(s.brief_report());
        REQUIRE(s.usable());
        for (LabelRole r : {LabelRole::upper_garment, LabelRole::lower_garment}) {
            const double v = vision::iou(role_mask(seg.labels, r), role_mask(p.labels, r));
            INFO("strokes, role " << int(r) << " IoU " << v);
            CHECK(v > 0.85);
        }
        Segmentation autoseg;
        const SegmentationSummary a = segment_automatic(p.image, p.joints, {}, autoseg);
        INFO(a.brief_report());
        REQUIRE(a.usable());
        for (LabelRole r : {LabelRole::upper_garment, LabelRole::lower_garment}) {
            const double v = vision::iou(role_mask(autoseg.labels, r), role_mask(p.labels, r));
            INFO("auto, role " << int(r) << " IoU " << v);
            CHECK(v > 0.6);
        }
    }
}

TEST_CASE("a few clicks per region: the learned layout bounds what the clicks do not", "[vision][photos][styles]") {
    // Four photos of the tuning part of photos-dev, dots (seed 1), with and without the
    // learned layout prior (stroke_layout_weight). 047535's clicks alone gave its skirt to
    // the background (IoU 0.00 in the tuning sweep), 006964's and 028113's garments spread
    // over skin and background; 003162 is the photo the prior hurt most in that sweep
    // (0.75 -> 0.55), kept so the test weighs the loss too.
    double with = 0, without = 0;
    int garments = 0;
    for (const char* name : {"fashionista_047535", "fashionista_006964", "fashionista_028113", "fashionista_003162"}) {
        Photo p;
        if (!load_photo(name, p, "data/photos-dev")) {
            WARN("skipped: ../shared/data/photos-dev not found (set DRAPE_SHARED_DIR)");
            return;
        }
        const cv::Mat dots = simulate_strokes(p.labels, StrokeStyle::dots, 1);
        SegmentationOptions off;
        off.stroke_layout_weight = 0;
        Segmentation a, b;
        REQUIRE(segment_with_strokes(p.image, dots, &p.joints, {}, a).usable());
        REQUIRE(segment_with_strokes(p.image, dots, &p.joints, off, b).usable());
        for (LabelRole r : {LabelRole::upper_garment, LabelRole::lower_garment, LabelRole::full_garment}) {
            const cv::Mat truth = role_mask(p.labels, r);
            if (cv::countNonZero(truth) < 0.01 * double(truth.total())) continue;
            const double va = vision::iou(role_mask(a.labels, r), truth), vb = vision::iou(role_mask(b.labels, r), truth);
            INFO(name << " role " << int(r) << ": IoU " << vb << " without the layout prior, " << va << " with");
            CHECK(va > 0.5);
            with += va, without += vb, ++garments;
        }
    }
    REQUIRE(garments >= 6);
    INFO("mean garment IoU over " << garments << ": without " << without / garments << ", with " << with / garments);
    CHECK(with / garments > 0.78);
    CHECK(with / garments > without / garments + 0.2);
}

TEST_CASE("a weaker background distance stops a garment leaking into the background",
          "[vision][photos]") {
    // 093328: a white-and-striped t-shirt in front of parked cars and a grey facade; with
    // the background's stroke distance at full weight (factor 1) the t-shirt takes pieces
    // of the background far from its medial-axis strokes (IoU 0.53 in the 30-photo run).
    Photo p;
    if (!load_photo("fashionista_093328", p)) {
        WARN("skipped: ../shared/data/photos not found (set DRAPE_SHARED_DIR)");
        return;
    }
    const cv::Mat strokes = simulate_strokes(p.labels);
    const cv::Mat truth = role_mask(p.labels, LabelRole::upper_garment);
    // The learned layout prior (stroke_layout_weight) also keeps the parked cars out: the
    // factor's own effect is measured without it, the defaults with both.
    auto upper_iou = [&](double factor, double layout_weight) {
        SegmentationOptions o;
        o.background_distance_factor = factor;
        o.stroke_layout_weight = layout_weight;
        Segmentation seg;
        REQUIRE(segment_with_strokes(p.image, strokes, &p.joints, o, seg).usable());
        return vision::iou(role_mask(seg.labels, LabelRole::upper_garment), truth);
    };
    const SegmentationOptions d;
    const double full = upper_iou(1.0, 0), weak = upper_iou(d.background_distance_factor, 0);
    const double both = upper_iou(d.background_distance_factor, d.stroke_layout_weight);
    INFO("t-shirt IoU without the layout prior: factor 1 " << full << ", default " << weak << "; defaults " << both);
    CHECK(weak > 0.8);
    CHECK(weak > full + 0.15);
    CHECK(both > 0.85);
}

namespace {

/// Wrinkles of the hand-labelled garment `class_name` of `p` on the photo resized by `s`.
WrinkleSummary labelled_wrinkles(const Photo& p, const std::string& class_name, double s,
                                 const WrinkleOptions& options = {}) {
    cv::Mat img, lab;
    cv::resize(p.image, img, cv::Size(), s, s, s < 1 ? cv::INTER_AREA : cv::INTER_CUBIC);
    cv::resize(p.labels, lab, img.size(), 0, 0, cv::INTER_NEAREST);
    const LabelTable& table = LabelTable::fashionista();
    const cv::Mat mask = lab == table.id(class_name);
    return detect_wrinkles(img, mask, occlusion_mask(lab, table), p.joints.scaled(s), options, nullptr);
}

/// Checks that P of the hand-labelled garment `class_name` of photo `name` at x0.5 and x2
/// is within 20 % of P at x1, after `check_x1` on the x1 result. False (and a warning) when
/// the shared photos are absent.
bool check_resized_wrinkles(const char* name, const char* class_name,
                            const std::function<void(const WrinkleSummary&)>& check_x1) {
    Photo p;
    if (!load_photo(name, p)) {
        WARN("skipped: ../shared/data/photos not found (set DRAPE_SHARED_DIR)");
        return false;
    }
    const WrinkleSummary d1 = labelled_wrinkles(p, class_name, 1.0);
    INFO(name << " " << class_name << ": " << d1.brief_report());
    check_x1(d1);
    for (double s : {0.5, 2.0}) {
        const WrinkleSummary ds = labelled_wrinkles(p, class_name, s);
        INFO("scale " << s << ": " << ds.brief_report());
        CHECK(ds.density_per_m2 / d1.density_per_m2 == Approx(1.0).margin(0.2));
    }
    return true;
}

}  // namespace

TEST_CASE("wrinkle density of a real garment is stable under resizing", "[vision][photos][wrinkles]") {
    check_resized_wrinkles("fashionista_002149", "skirt", [](const WrinkleSummary& d1) { REQUIRE(d1.folds >= 3); });
}

TEST_CASE("wrinkle density averaged over working resolutions is stable under resizing",
          "[vision][photos][wrinkles]") {
    // Garments whose P moved by more than 20 % at x0.5 or x2 with a single detection
    // (ratios 0.78 / 0.75, 0.76 / 0.91, 0.75 / 0.79 in the 30-photo run of 2026-11-24).
    const std::pair<const char*, const char*> garments[] = {
        {"fashionista_017182", "dress"}, {"fashionista_003792", "blouse"}, {"fashionista_022589", "top"}};
    for (const auto& [name, class_name] : garments)
        if (!check_resized_wrinkles(name, class_name, [](const WrinkleSummary& d1) { REQUIRE(d1.density_per_m2 > 5); }))
            return;
}

TEST_CASE("garments with about one fold keep their wrinkle density under resizing",
          "[vision][photos][wrinkles]") {
    // 002149's white t-shirt (0.75 full-length folds) and 007094's shorts (1.33): with the
    // earlier ensemble of 5 resolutions x 2 phases their ratios were 0.68 / 0.68 and 0.78 /
    // 0.79 (one detection counts 0.3-1.9 folds on them); 10 x 4 detections average that out.
    const std::pair<const char*, const char*> garments[] = {{"fashionista_002149", "t-shirt"},
                                                            {"fashionista_007094", "shorts"}};
    for (const auto& [name, class_name] : garments)
        if (!check_resized_wrinkles(name, class_name, [](const WrinkleSummary& d1) {
                REQUIRE(d1.folds_detected);
                REQUIRE(d1.fold_count < 2);
            }))
            return;
}

TEST_CASE("a plain garment has no fold at any resolution, a palm-sized patch no P",
          "[vision][photos][wrinkles]") {
    Photo p, q;
    if (!load_photo("fashionista_013932", p) || !load_photo("fashionista_012392", q)) {
        WARN("skipped: ../shared/data/photos not found (set DRAPE_SHARED_DIR)");
        return;
    }
    // 013932's over-exposed white tank top shows no fold; a few grids of the ensemble still
    // pair two short edges (0.03-0.12 full-length folds). Below the detection limit P is 0
    // at every scale; counted, those pairs give ratios of 1.7 and 0.4.
    WrinkleOptions counted;
    counted.min_fold_count = 0;
    std::vector<double> raw;
    for (double s : {1.0, 0.5, 2.0}) {
        const WrinkleSummary w = labelled_wrinkles(p, "top", s);
        INFO("scale " << s << ": " << w.brief_report());
        REQUIRE(w.usable());
        CHECK_FALSE(w.folds_detected);
        CHECK(w.density_per_m2 == 0);
        CHECK(w.folds == 0);
        CHECK(w.fold_count < WrinkleOptions{}.min_fold_count);
        raw.push_back(labelled_wrinkles(p, "top", s, counted).density_per_m2);
    }
    INFO("P without the detection limit: " << raw[0] << ", x0.5 " << raw[1] << ", x2 " << raw[2]);
    REQUIRE(raw[0] > 0);
    CHECK((std::abs(raw[1] / raw[0] - 1) > 0.2 || std::abs(raw[2] / raw[0] - 1) > 0.2));
    // 012392's lace camisole, seen between the flaps of an open shirt, covers 0.46 % of the
    // body height squared, less than one full-length fold's square (1 %): P is not measured.
    // Measured anyway, its one short fold vanishes at x0.5.
    const WrinkleSummary cami = labelled_wrinkles(q, "top", 1.0);
    INFO(cami.brief_report());
    CHECK(cami.termination == WrinkleTermination::garment_too_small);
    CHECK(cami.message.find("% of body height squared") != std::string::npos);
    WrinkleOptions any_size;
    any_size.min_garment_area_fraction = 0;
    any_size.min_fold_count = 0;
    const WrinkleSummary c1 = labelled_wrinkles(q, "top", 1.0, any_size);
    const WrinkleSummary c05 = labelled_wrinkles(q, "top", 0.5, any_size);
    INFO(c1.brief_report() << " / x0.5 " << c05.brief_report());
    REQUIRE(c1.density_per_m2 > 0);
    CHECK(c05.density_per_m2 / c1.density_per_m2 < 0.8);
}

TEST_CASE("automatic garment types of a maxi skirt, a belted dress, a raised-arm t-shirt and a tank top beside a pale arm", "[vision][photos][classify]") {
    // 002149: a yellow maxi skirt reaching the feet (read as pants before the knee-width
    // cue); 001630: a white dress with a gold sash at the waist (two garments before the
    // waist band was left out of the dress test); 008124: a short-sleeved shirt, one arm
    // raised past dark hair, the other hanging beside the torso (long-sleeved while the
    // sleeve cue counted garment touching the arm line from one side only); 013932: a
    // white tank top beside a pale, over-exposed bare arm that the cut gave to the top
    // (long-sleeved before the arm's skin chromaticity sent it back to skin).
    const std::pair<const char*, GarmentType> cases[] = {{"fashionista_002149", GarmentType::skirt},
                                                         {"fashionista_001630", GarmentType::dress},
                                                         {"fashionista_008124", GarmentType::t_shirt},
                                                         {"fashionista_013932", GarmentType::tank_top}};
    for (const auto& [name, expected] : cases) {
        Photo p;
        if (!load_photo(name, p)) {
            WARN("skipped: ../shared/data/photos not found (set DRAPE_SHARED_DIR)");
            return;
        }
        Segmentation seg;
        const SegmentationSummary s = segment_automatic(p.image, p.joints, {}, seg);
        INFO(name << ": " << s.brief_report());
        REQUIRE(s.usable());
        const GarmentPart part = part_of(expected);
        std::vector<GarmentType> types;
        for (const auto& [id, t] : seg.garment_types)
            if (part_of(t) == part || part_of(t) == GarmentPart::full) types.push_back(t);
        REQUIRE(types.size() == 1);
        CHECK(types[0] == expected);
    }
}
