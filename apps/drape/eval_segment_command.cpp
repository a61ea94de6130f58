// drape eval-segment DIR [--mode strokes|auto|both] [--split tune|heldout|all]
//                   [--scale-check] [--limit N] --out RESULT.json
//
// Evaluates garment parsing on a folder in the ../shared/data/photos layout
// (images/NAME.jpg, labels/NAME.png, joints/NAME.json, optional index.csv): per photo and
// mean IoU per garment against the hand labels, garment-type accuracy and time
// (docs/vision.md, "Evaluation").
#include "commands.hpp"
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/vision_json.hpp>

#include <drape/core/errors.hpp>
#include <drape/vision/classify_garment.hpp>
#include <drape/vision/garment_result.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/photo_split.hpp>
#include <drape/vision/segmentation.hpp>
#include <drape/vision/segmentation_score.hpp>
#include <drape/vision/strokes.hpp>

#include <CLI/CLI.hpp>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;
using vision::GarmentPart;
using vision::GarmentType;
using vision::LabelRole;
using vision::LabelTable;
using vision::iou;
using vision::role_mask;

struct EvalArgs {
    std::string dir;
    std::string mode = "both";
    std::string out;
    std::string split = "all";
    std::string stroke_style = "medial";
    std::uint64_t stroke_seed = 1;
    int limit = 0;
    bool scale_check = false;
    bool iou_only = false;
    std::string save_dir;
    std::vector<std::string> names;
    vision::SegmentationOptions options;
    vision::GarmentOptions garment;
};

/// Photos of the folder: index.csv rows (name, category) when present, else images/*.jpg.
std::vector<std::pair<std::string, std::string>> list_photos(const fs::path& dir) {
    std::vector<std::pair<std::string, std::string>> out;
    std::ifstream index(dir / "index.csv");
    if (index) {
        std::string line;
        std::getline(index, line);  // header
        while (std::getline(index, line)) {
            if (line.empty()) continue;
            std::stringstream ss(line);
            std::string name, category;
            std::getline(ss, name, ',');
            std::getline(ss, category, ',');
            out.emplace_back(name, category);
        }
        return out;
    }
    std::error_code ec;
    if (!fs::is_directory(dir / "images", ec))
        throw IoError("evaluation folder '" + dir.string() + "' has no images/ subfolder");
    for (const auto& e : fs::directory_iterator(dir / "images"))
        if (e.path().extension() == ".jpg" || e.path().extension() == ".png")
            out.emplace_back(e.path().stem().string(), "");
    std::sort(out.begin(), out.end());
    return out;
}

/// The garments of a parse by part: masks (union of classes of that role) and types.
struct Parse {
    std::map<GarmentPart, cv::Mat> masks;
    std::map<GarmentPart, GarmentType> types;
};

int largest_class(const cv::Mat& labels, const LabelTable& t, LabelRole role) {
    int counts[256] = {};
    for (size_t i = 0; i < labels.total(); ++i) ++counts[labels.data[i]];
    int best = -1;
    for (int id = 0; id < 255; ++id)
        if (t.role(id) == role && counts[id] > 0 && (best < 0 || counts[id] > counts[best])) best = id;
    return best;
}

/// Garments of a label map; types listed in `known` win, else they come from the class.
Parse parse_of(const cv::Mat& labels, const LabelTable& t, const vision::Joints& joints,
               const std::vector<std::pair<int, GarmentType>>& known) {
    Parse p;
    const double min_area = 0.002 * double(labels.total());
    const cv::Mat hiding = vision::sleeve_hiding_mask(labels, t);
    const std::pair<GarmentPart, LabelRole> parts[] = {{GarmentPart::upper, LabelRole::upper_garment},
                                                       {GarmentPart::lower, LabelRole::lower_garment},
                                                       {GarmentPart::full, LabelRole::full_garment}};
    for (const auto& [part, role] : parts) {
        const cv::Mat m = role_mask(labels, t, role);
        if (cv::countNonZero(m) < min_area) continue;
        p.masks[part] = m;
        const int id = largest_class(labels, t, role);
        auto it = std::find_if(known.begin(), known.end(), [id](const auto& k) { return k.first == id; });
        if (it != known.end()) p.types[part] = it->second;
        else if (part == GarmentPart::upper)
            p.types[part] = vision::classify_upper(vision::measure_shape_cues(m, joints, hiding));
        else p.types[part] = vision::garment_type_of_class(m, id, t, joints, hiding);
    }
    return p;
}

struct ModeTotals {
    double iou_sum = 0;
    int garments = 0;
    int types_right = 0;
    double seconds_sum = 0;
    double seconds_max = 0;
    int photos = 0;
    std::map<std::string, std::pair<double, int>> iou_by_type;
};

using Clock = std::chrono::steady_clock;

void add_totals(ModeTotals& sum, const ModeTotals& t) {
    sum.iou_sum += t.iou_sum;
    sum.garments += t.garments;
    sum.types_right += t.types_right;
    sum.seconds_sum += t.seconds_sum;
    sum.seconds_max = std::max(sum.seconds_max, t.seconds_max);
    sum.photos += t.photos;
    for (const auto& [type, v] : t.iou_by_type) {
        sum.iou_by_type[type].first += v.first;
        sum.iou_by_type[type].second += v.second;
    }
}

nlohmann::json totals_json(const ModeTotals& t) {
    nlohmann::json by_type = nlohmann::json::object();
    for (const auto& [type, v] : t.iou_by_type)
        by_type[type] = {{"mean_iou", v.first / v.second}, {"garments", v.second}};
    return {{"photos", t.photos},
            {"garments", t.garments},
            {"mean_garment_iou", t.iou_sum / std::max(1, t.garments)},
            {"type_accuracy", double(t.types_right) / std::max(1, t.garments)},
            {"mean_seconds_per_photo", t.seconds_sum / std::max(1, t.photos)},
            {"max_seconds_per_photo", t.seconds_max},
            {"iou_by_true_type", by_type}};
}

void print_totals(const std::string& label, const ModeTotals& t) {
    std::cout << label << ": mean garment IoU " << std::fixed << std::setprecision(3)
              << t.iou_sum / std::max(1, t.garments) << " over " << t.garments
              << " garments (" << t.photos << " photos), type accuracy " << std::setprecision(1)
              << 100.0 * t.types_right / std::max(1, t.garments) << " %, "
              << std::setprecision(2) << t.seconds_sum / std::max(1, t.photos)
              << " s/photo (max " << t.seconds_max << " s)\n";
}

/// The key of a stroke style in the result: "strokes" for the medial axis (as before the
/// styles existed), "strokes-STYLE" for the others.
std::string strokes_key(vision::StrokeStyle style) {
    return style == vision::StrokeStyle::medial ? "strokes" : std::string("strokes-") + vision::to_string(style);
}

/// The simulated user's seed for one photo: the run's seed mixed with the photo's name
/// (FNV-1a), so every photo gets its own pattern and a run is reproducible.
std::uint64_t photo_seed(std::uint64_t seed, const std::string& name) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : name) h = (h ^ c) * 1099511628211ull;
    return h ^ (seed * 0x9e3779b97f4a7c15ull);
}

nlohmann::json evaluate(const std::string& mode, std::uint64_t seed, const cv::Mat& photo, const cv::Mat& gt,
                        const vision::Joints& joints, const Parse& truth,
                        const vision::SegmentationOptions& options,
                        const vision::GarmentOptions& garment_options, bool iou_only,
                        const std::string& save_prefix, ModeTotals& totals) {
    const LabelTable& table = LabelTable::fashionista();
    vision::Segmentation seg;
    vision::SegmentationSummary summary;
    nlohmann::json j;
    const bool with_strokes = mode.rfind("strokes", 0) == 0;
    cv::Mat strokes;  // the simulated user's strokes: not part of the timed work
    if (with_strokes) {
        const vision::StrokeStyle style =
            mode == "strokes" ? vision::StrokeStyle::medial : vision::parse_stroke_style(mode.substr(8));
        strokes = vision::simulate_strokes(gt, style, seed);
        j["marked_fraction"] = vision::marked_fraction(strokes);
        j["wrong_mark_fraction"] = vision::wrong_mark_fraction(strokes, gt);
    }
    const auto t0 = Clock::now();
    if (with_strokes) {
        summary = vision::segment_with_strokes(photo, strokes, &joints, options, seg);
    } else {
        summary = vision::segment_automatic(photo, joints, options, seg);
    }
    if (!iou_only) vision::describe_garments(photo, seg, joints, table, garment_options);
    if (!save_prefix.empty()) {
        cv::Mat overlay = vision::draw_segmentation(photo, seg.labels);
        if (!strokes.empty()) {
            const cv::Mat c = vision::colour_strokes(strokes, vision::StrokePalette::fashionista_default());
            for (int y = 0; y < c.rows; ++y)
                for (int x = 0; x < c.cols; ++x)
                    if (c.at<cv::Vec4b>(y, x)[3]) {
                        const cv::Vec4b v = c.at<cv::Vec4b>(y, x);
                        overlay.at<cv::Vec3b>(y, x) = cv::Vec3b(v[0], v[1], v[2]);
                    }
        }
        write_png(save_prefix + "_" + mode + ".png", overlay);
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const Parse pred = parse_of(seg.labels, table, joints, seg.garment_types);
    nlohmann::json per = nlohmann::json::array();
    double photo_sum = 0;
    const cv::Mat gt_hiding = vision::sleeve_hiding_mask(gt, table),
                  pred_hiding = vision::sleeve_hiding_mask(seg.labels, table);
    for (const auto& [part, gt_mask] : truth.masks) {
        cv::Mat pm;
        if (part == GarmentPart::full) {
            pm = cv::Mat::zeros(gt.size(), CV_8UC1);
            for (const auto& [pp, m] : pred.masks) pm |= m;
        } else if (pred.masks.count(part)) {
            pm = pred.masks.at(part);
        } else if (pred.masks.count(GarmentPart::full)) {
            pm = pred.masks.at(GarmentPart::full);
        } else {
            pm = cv::Mat::zeros(gt.size(), CV_8UC1);
        }
        const double v = iou(gt_mask, pm);
        const GarmentType tt = truth.types.at(part);
        std::string pt = "none";
        bool right = false;
        if (part == GarmentPart::full) {
            right = pred.types.count(GarmentPart::full) > 0;
            if (right) pt = "dress";
            else if (pred.types.count(GarmentPart::lower))
                pt = std::string(vision::to_string(pred.types.at(GarmentPart::lower)));
        } else if (pred.types.count(part)) {
            pt = std::string(vision::to_string(pred.types.at(part)));
            right = pred.types.at(part) == tt;
        } else if (pred.types.count(GarmentPart::full)) {
            pt = "dress";
        }
        per.push_back({{"true_type", std::string(vision::to_string(tt))},
                       {"predicted_type", pt}, {"type_correct", right}, {"iou", v},
                       {"true_cues", cues_json(vision::measure_shape_cues(gt_mask, joints, gt_hiding))},
                       {"cues", cues_json(vision::measure_shape_cues(pm, joints, pred_hiding))}});
        photo_sum += v;
        totals.iou_sum += v;
        totals.garments += 1;
        totals.types_right += right;
        auto& bt = totals.iou_by_type[std::string(vision::to_string(tt))];
        bt.first += v;
        bt.second += 1;
    }
    totals.seconds_sum += seconds;
    totals.seconds_max = std::max(totals.seconds_max, seconds);
    totals.photos += 1;
    j["garments"] = per;
    j["mean_iou"] = truth.masks.empty() ? 0.0 : photo_sum / double(truth.masks.size());
    j["seconds"] = seconds;
    j["segmentation"] = summary.brief_report();
    return j;
}

/// The wrinkle-density comparisons of the scale check: P(x0.5) and P(x2) against P(x1) for
/// each hand-labelled garment measured at all three scales.
struct ScaleCheckTotals {
    std::vector<double> ratios;  ///< P(xs) / P(x1) where P(x1) > 0
    int comparisons = 0;         ///< ratios + comparisons with P(x1) = 0
    int within = 0;              ///< ratios within +-20 % + both without fold (P = 0 = P)
    int both_without_fold = 0;   ///< P(xs) = P(x1) = 0: no fold at either scale
    int not_measured = 0;        ///< garments too small for P at some scale
};

/// Wrinkle density of each hand-labelled garment at scales 0.5, 1, 2.
nlohmann::json scale_check(const cv::Mat& photo, const cv::Mat& gt, const vision::Joints& joints,
                           const vision::GarmentOptions& garment_options, ScaleCheckTotals& totals) {
    const LabelTable& table = LabelTable::fashionista();
    nlohmann::json j = nlohmann::json::object();
    std::map<int, std::vector<vision::WrinkleSummary>> runs;
    for (double s : {1.0, 0.5, 2.0}) {
        vision::Segmentation seg;
        cv::resize(photo, seg.labels, cv::Size(), s, s, s < 1 ? cv::INTER_AREA : cv::INTER_CUBIC);
        const cv::Mat img = seg.labels;
        cv::resize(gt, seg.labels, img.size(), 0, 0, cv::INTER_NEAREST);
        seg.occlusion = vision::occlusion_mask(seg.labels, table);
        for (const auto& g : vision::describe_garments(img, seg, joints.scaled(s), table, garment_options))
            runs[g.label_id].push_back(g.wrinkles);
    }
    for (const auto& [id, w] : runs) {
        if (w.size() != 3) continue;
        nlohmann::json e = {{"P_x1", w[0].density_per_m2}, {"P_x0.5", w[1].density_per_m2},
                            {"P_x2", w[2].density_per_m2}, {"folds_x1", w[0].fold_count},
                            {"folds_x0.5", w[1].fold_count}, {"folds_x2", w[2].fold_count}};
        if (!w[0].usable() || !w[1].usable() || !w[2].usable()) {
            e["not_measured"] = "garment too small for P at some scale";
            totals.not_measured += 1;
        } else {
            for (int k = 1; k < 3; ++k) {
                const double d0 = w[0].density_per_m2, dk = w[size_t(k)].density_per_m2;
                totals.comparisons += 1;
                if (d0 > 0) {
                    totals.ratios.push_back(dk / d0);
                    totals.within += dk / d0 >= 0.8 && dk / d0 <= 1.2;
                } else if (dk == 0) {
                    totals.within += 1;
                    totals.both_without_fold += 1;
                }
            }
        }
        j[table.name(id)] = e;
    }
    return j;
}

void run_eval(const EvalArgs& args) {
    if (args.stroke_style != "all") vision::parse_stroke_style(args.stroke_style);  // named error early
    if (args.mode != "strokes" && args.mode != "auto" && args.mode != "both" && args.mode != "none")
        throw InvalidInput("--mode '" + args.mode + "' is not one of strokes, auto, both, none");
    const vision::PhotoSplit split = vision::parse_photo_split(args.split);
    const fs::path dir(args.dir);
    auto photos = list_photos(dir);
    // The split's part of every photo, from the sorted names of the whole folder
    // (docs/vision.md, "Evaluation protocol"), before --names or --limit select photos.
    std::map<std::string, vision::PhotoSplit> part_of_photo;
    {
        std::vector<std::string> all_names;
        for (const auto& p : photos) all_names.push_back(p.first);
        const auto parts = vision::photo_split_parts(all_names);
        for (size_t i = 0; i < all_names.size(); ++i) part_of_photo[all_names[i]] = parts[i];
        if (split != vision::PhotoSplit::all) {
            std::vector<std::pair<std::string, std::string>> kept;
            for (const auto& p : photos)
                if (part_of_photo.at(p.first) == split) kept.push_back(p);
            photos = kept;
        }
    }
    if (!args.names.empty()) {
        std::vector<std::pair<std::string, std::string>> kept;
        for (const auto& p : photos)
            if (std::find(args.names.begin(), args.names.end(), p.first) != args.names.end())
                kept.push_back(p);
        photos = kept;
    }
    if (args.limit > 0 && int(photos.size()) > args.limit) photos.resize(size_t(args.limit));
    if (photos.empty()) throw InvalidInput("no photo to evaluate in '" + args.dir + "'");
    std::vector<std::string> modes;
    if (args.mode == "strokes" || args.mode == "both") {
        if (args.stroke_style == "all") {
            for (auto st : {vision::StrokeStyle::medial, vision::StrokeStyle::dashes, vision::StrokeStyle::dots,
                            vision::StrokeStyle::sloppy})
                modes.push_back(strokes_key(st));
        } else {
            modes.push_back(strokes_key(vision::parse_stroke_style(args.stroke_style)));
        }
    }
    if (args.mode == "auto" || args.mode == "both") modes.push_back("auto");
    const LabelTable& table = LabelTable::fashionista();
    // Totals per mode and per part of the split (tune, heldout).
    std::map<std::string, ModeTotals> totals;
    std::map<std::string, std::map<std::string, ModeTotals>> totals_by_part;
    ScaleCheckTotals scale_totals;
    nlohmann::json per_photo = nlohmann::json::array();
    for (const auto& [name, category] : photos) {
        const cv::Mat photo = vision::load_image(dir / "images" / (name + ".jpg"));
        const cv::Mat gt = vision::load_label_map(dir / "labels" / (name + ".png"), "labels");
        const vision::Joints joints =
            read_vision_joints(dir / "joints" / (name + ".json"), photo.cols, photo.rows);
        const Parse truth = parse_of(gt, table, joints, {});
        nlohmann::json pj;
        const std::string part = vision::to_string(part_of_photo.at(name));
        pj["name"] = name;
        pj["category"] = category;
        pj["split"] = part;
        if (!category.empty() && truth.types.count(GarmentPart::lower) &&
            std::string(vision::to_string(truth.types.at(GarmentPart::lower))) != category)
            pj["warning"] = "category in index.csv differs from the labelled lower garment";
        std::cout << name << " (" << category << ", " << part << "):";
        for (const auto& m : modes) {
            ModeTotals one;
            pj[m] = evaluate(m, photo_seed(args.stroke_seed, name), photo, gt, joints, truth, args.options,
                             args.garment, args.iou_only,
                             args.save_dir.empty() ? "" : (fs::path(args.save_dir) / name).string(), one);
            add_totals(totals[m], one);
            add_totals(totals_by_part[m][part], one);
            std::cout << "  " << m << " IoU " << std::fixed << std::setprecision(3)
                      << pj[m]["mean_iou"].get<double>() << " (" << std::setprecision(2)
                      << pj[m]["seconds"].get<double>() << " s)";
            for (const auto& g : pj[m]["garments"])
                std::cout << " " << g["true_type"].get<std::string>() << "->"
                          << g["predicted_type"].get<std::string>();
        }
        if (args.scale_check) pj["wrinkle_scale_check"] = scale_check(photo, gt, joints, args.garment, scale_totals);
        std::cout << "\n";
        per_photo.push_back(pj);
    }
    nlohmann::json result;
    result["format"] = "drape.segment_eval";
    result["version"] = 1;
    result["folder"] = args.dir;
    result["split"] = args.split;
    result["stroke_seed"] = args.stroke_seed;
    result["photos"] = per_photo;
    for (const auto& [m, t] : totals) {
        result["summary"][m] = totals_json(t);
        for (const auto& [part, tp] : totals_by_part[m]) {
            result["summary"][m]["by_split"][part] = totals_json(tp);
            print_totals(m + " [" + part + "]", tp);
        }
        print_totals(m, t);
    }
    if (args.scale_check) {
        const auto& t = scale_totals;
        double worst = 1.0;
        for (double r : t.ratios)
            if (std::abs(std::log(std::max(r, 1e-9))) > std::abs(std::log(std::max(worst, 1e-9)))) worst = r;
        result["summary"]["wrinkle_scale_check"] = {{"comparisons", t.comparisons},
                                                    {"within_20_percent", t.within},
                                                    {"ratios", t.ratios.size()},
                                                    {"both_without_fold", t.both_without_fold},
                                                    {"garments_not_measured", t.not_measured},
                                                    {"worst_ratio", worst}};
        std::cout << "wrinkle density x0.5 / x2 vs x1: " << t.within << " of " << t.comparisons
                  << " comparisons within +-20 % (" << t.ratios.size() << " ratios, worst " << worst << "; "
                  << t.both_without_fold << " with no fold at either scale); " << t.not_measured
                  << " garment(s) too small for P\n";
    }
    write_json_file(args.out, result);
}

/// --NAME options setting an options struct's member `name` (dashes -> underscores).
template <size_t N>
void add_tuning_options(CLI::App& cmd, const std::string& owner,
                        const std::pair<const char*, double*> (&members)[N]) {
    for (const auto& [name, member] : members) {
        std::string member_name = name;
        std::replace(member_name.begin(), member_name.end(), '-', '_');
        cmd.add_option(std::string("--") + name, *member, owner + "::" + member_name + " (for tuning)");
    }
}

}  // namespace

void add_eval_segment_command(CLI::App& app) {
    auto args = std::make_shared<EvalArgs>();
    CLI::App* cmd = app.add_subcommand(
        "eval-segment", "Evaluate garment parsing on a folder in the ../shared/data/photos "
                        "layout: IoU per garment vs the hand labels, type accuracy, time");
    cmd->add_option("dir", args->dir, "folder with images/, labels/, joints/ (and index.csv)")->required();
    cmd->add_option("--mode", args->mode, "strokes | auto | both (default) | none (only with --scale-check)");
    cmd->add_option("--out", args->out, "result JSON to write")->required();
    cmd->add_option("--limit", args->limit, "evaluate only the first N photos");
    cmd->add_option("--names", args->names, "evaluate only these photos (NAME without extension)");
    cmd->add_option("--stroke-style", args->stroke_style,
                    "medial (default) | dashes | dots | sloppy | all: the simulated user's strokes "
                    "(docs/vision.md, \"Simulated strokes\"); summaries strokes, strokes-dashes, ...");
    cmd->add_option("--stroke-seed", args->stroke_seed,
                    "seed of the simulated user (mixed with each photo's name; default 1)");
    cmd->add_option("--split", args->split,
                    "tune | heldout | all (default): the part of the folder's fixed split to evaluate "
                    "(names sorted; even 0-based positions tune, odd held-out; docs/vision.md)");
    cmd->add_flag("--iou-only", args->iou_only,
                  "skip describe_garments (features, wrinkles): for tuning sweeps; the time is then "
                  "the segmentation's alone");
    cmd->add_option("--save-overlays", args->save_dir,
                    "write DIR/NAME_MODE.png: the parse over the photo, with the simulated strokes drawn in");
    cmd->add_flag("--scale-check", args->scale_check,
                  "also measure the wrinkle density of the hand-labelled garments at x0.5 and x2");
    // SegmentationOptions members exposed for tuning (docs/notes/vision.md, "Tuning tried").
    vision::SegmentationOptions& o = args->options;
    const std::pair<const char*, double*> tuning[] = {
        {"smoothness", &o.smoothness},
        {"stroke-distance-weight", &o.stroke_distance_weight},
        {"stroke-colour-weight", &o.stroke_colour_weight},
        {"superpixel-fraction", &o.superpixel_fraction},
        {"background-distance-factor", &o.background_distance_factor},
        {"band-fraction", &o.band_fraction},
        {"band-smoothness", &o.band_smoothness},
        {"mark-outlier-margin", &o.mark_outlier_margin},
        {"mark-edge-px", &o.mark_edge_px},
        {"mark-edge-factor", &o.mark_edge_factor},
        {"soft-mark-weight", &o.soft_mark_weight},
        {"seed-growth-fraction", &o.seed_growth_fraction},
        {"body-prior-weight", &o.body_prior_weight},
        {"body-reach-fraction", &o.body_reach_fraction},
        {"sparse-marks-fraction", &o.sparse_marks_fraction},
        {"compact-marks-factor", &o.compact_marks_factor},
        {"compact-mark-elongation", &o.compact_mark_elongation},
        {"stroke-layout-weight", &o.stroke_layout_weight}};
    add_tuning_options(*cmd, "SegmentationOptions", tuning);
    // WrinkleOptions members exposed for tuning the fold detector with --scale-check.
    vision::WrinkleOptions& w = args->garment.wrinkles;
    cmd->add_option("--wrinkle-scales", w.scale_fractions,
                    "WrinkleOptions::scale_fractions, Hessian scales / body height (for tuning)");
    cmd->add_option("--resolution-ensemble", w.resolution_ensemble,
                    "WrinkleOptions::resolution_ensemble (for tuning)");
    cmd->add_option("--phase-ensemble", w.phase_ensemble, "WrinkleOptions::phase_ensemble (for tuning)");
    cmd->add_option("--wrinkle-threads", w.threads, "WrinkleOptions::threads: threads of the fold detector (0 = all cores)");
    const std::pair<const char*, double*> wrinkle_tuning[] = {
        {"ridge-threshold", &w.ridge_threshold},
        {"working-body-height", &w.working_body_height_px},
        {"min-edge-fraction", &w.min_edge_fraction},
        {"full-fold-fraction", &w.full_fold_fraction},
        {"source-blur", &w.source_blur_px},
        {"min-fold-count", &w.min_fold_count},
        {"min-garment-area-fraction", &w.min_garment_area_fraction}};
    add_tuning_options(*cmd, "WrinkleOptions", wrinkle_tuning);
    cmd->callback([args] {
        std::string why;
        if (!args->garment.is_valid(&why)) throw InvalidInput("wrinkle options: " + why);
        run_eval(*args);
    });
}

}  // namespace drape::app
