// drape segment IMAGE --joints J.json [--strokes S.png] [--palette P.json] [--hint TYPE] [--height M] --out DIR
// drape strokes LABELS.png --out S.png [--style medial|dashes|dots|sloppy] [--seed N] [--colour] [--palette P.json]
#include "commands.hpp"
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/vision_json.hpp>

#include <drape/core/errors.hpp>
#include <drape/vision/garment_result.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/segmentation.hpp>
#include <drape/vision/strokes.hpp>

#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <optional>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;

/// What a colour-coded stroke image was read as, for the user who drew it.
void report_decoding(const vision::StrokeDecoding& d, const vision::LabelTable& table) {
    std::cerr << "drape segment: colour-coded strokes: " << d.marked_px << " px marked (";
    for (size_t i = 0; i < d.per_class.size(); ++i)
        std::cerr << (i ? ", " : "") << table.name(d.per_class[i].first) << " " << d.per_class[i].second;
    std::cerr << "); " << d.unrecognised_px << " opaque px of no palette colour left unmarked";
    if (d.most_common_unrecognised_px > 0)
        std::cerr << " (most often " << vision::StrokePalette::hex(d.most_common_unrecognised) << ", "
                  << d.most_common_unrecognised_px << " px)";
    std::cerr << "\n";
}

struct SegmentArgs {
    std::string image;
    std::string joints;
    std::string strokes;
    std::string palette;
    std::string hint;
    double height_m = 1.70;
    std::string out;
};

void run_segment(const SegmentArgs& args) {
    const cv::Mat photo = vision::load_image(args.image);
    const vision::Joints joints = read_vision_joints(args.joints, photo.cols, photo.rows);
    vision::SegmentationOptions options;
    if (!args.hint.empty()) {
        options.hint = vision::parse_garment_type(args.hint);
        if (!options.hint)
            throw InvalidInput("--hint '" + args.hint + "' is not one of t-shirt, tank-top, "
                               "long-sleeve-top, dress, skirt, pants, shorts");
    }
    if (!(args.height_m > 0.5 && args.height_m < 2.6))
        throw InvalidInput("--height " + std::to_string(args.height_m) +
                           " m is outside 0.5 .. 2.6 m");
    make_output_dir(args.out);

    vision::Segmentation seg;
    vision::SegmentationSummary summary;
    std::string mode;
    if (!args.palette.empty() && args.strokes.empty())
        throw InvalidInput("--palette is for colour-coded --strokes; no --strokes given");
    if (!args.strokes.empty()) {
        const vision::StrokePalette palette = read_stroke_palette(args.palette, options.table);
        vision::StrokeDecoding decoding;
        const cv::Mat strokes = vision::load_strokes(args.strokes, palette, &decoding);
        if (decoding.marked_px > 0) report_decoding(decoding, options.table);
        summary = vision::segment_with_strokes(photo, strokes, &joints, options, seg);
        mode = "strokes";
    } else {
        summary = vision::segment_automatic(photo, joints, options, seg);
        mode = "auto";
    }
    std::cerr << "drape segment: " << summary.brief_report() << "\n";
    vision::GarmentOptions gopt;
    gopt.wrinkles.person_height_m = args.height_m;
    const std::vector<vision::GarmentResult> garments =
        vision::describe_garments(photo, seg, joints, options.table, gopt, options.hint);
    for (const auto& g : garments)
        std::cerr << "  " << vision::to_string(g.type) << " (class " << g.label_id << " "
                  << g.class_name << "): " << g.area_px << " px, occluded "
                  << g.occlusion_fraction << ", " << g.wrinkles.brief_report() << "\n";
    if (garments.empty()) std::cerr << "drape segment: no garment found\n";
    write_segmentation_folder(args.out, photo, seg, summary, garments, args.image, mode, args.height_m);
}

}  // namespace

void add_segment_command(CLI::App& app) {
    auto args = std::make_shared<SegmentArgs>();
    CLI::App* cmd = app.add_subcommand(
        "segment", "Parse the garments of a photo (labels.png, garments.json, overlay.png, "
                   "folds.png, occlusion.png in DIR): automatic from the joints, or guided by "
                   "user strokes");
    cmd->add_option("image", args->image, "the photo (JPEG/PNG; EXIF orientation is applied)")->required();
    cmd->add_option("--joints", args->joints,
                    "JSON {\"joints\": 14 [x, y] pixels (right_ankle ... head), optional "
                    "\"pixel_origin\": one_based (default) | zero_based | corner}")
        ->required();
    cmd->add_option("--strokes", args->strokes,
                    "PNG of the photo's size: 8-bit gray with class ids of labels.txt where marked, 255 "
                    "elsewhere (see `drape strokes`), or colour-coded RGB/RGBA drawn by hand (docs/vision.md)");
    cmd->add_option("--palette", args->palette,
                    "JSON {\"tolerance\": 40, \"colours\": {\"skirt\": \"#ffff00\", ...}} for colour-coded "
                    "strokes (default: docs/vision.md, \"Colour-coded strokes\")");
    cmd->add_option("--hint", args->hint,
                    "garment type hint: t-shirt, tank-top, long-sleeve-top, dress, skirt, pants, shorts");
    cmd->add_option("--height", args->height_m, "the person's stature in metres (default 1.70)");
    cmd->add_option("--out", args->out, "output folder (created if absent)")->required();
    cmd->callback([args] { run_segment(*args); });
}

void add_strokes_command(CLI::App& app) {
    struct StrokesArgs {
        std::string labels, out, palette, style = "medial";
        std::uint64_t seed = 1;
        bool colour = false;
    };
    auto args = std::make_shared<StrokesArgs>();
    CLI::App* cmd = app.add_subcommand(
        "strokes", "Simulate user strokes from a ground-truth label map (docs/vision.md): a few "
                   "medial-axis strokes per region, at most 3 % of the pixels");
    cmd->add_option("labels", args->labels, "8-bit class-id PNG (labels.txt ids)")->required();
    cmd->add_option("--out", args->out, "the strokes PNG to write (255 = unmarked)")->required();
    cmd->add_flag("--colour", args->colour,
                  "write colour-coded strokes (RGBA, transparent where unmarked) as a person would draw them");
    cmd->add_option("--palette", args->palette, "palette JSON for --colour (default: the built-in palette)");
    cmd->add_option("--style", args->style,
                    "medial (default) | dashes | dots | sloppy: how the simulated user draws (docs/vision.md)");
    cmd->add_option("--seed", args->seed, "seed of the dashes, dots and sloppy styles (default 1)");
    cmd->callback([args] {
        const vision::StrokeStyle style = vision::parse_stroke_style(args->style);
        if (!args->palette.empty() && !args->colour)
            throw InvalidInput("--palette is for --colour; add --colour or drop --palette");
        const vision::LabelTable& table = vision::LabelTable::fashionista();
        const vision::StrokePalette palette = read_stroke_palette(args->palette, table);
        const cv::Mat gt = vision::load_label_map(args->labels, "labels");
        const cv::Mat strokes = vision::simulate_strokes(gt, style, args->seed);
        if (args->colour) {
            std::vector<int> missing;
            write_png(args->out, vision::colour_strokes(strokes, palette, &missing));
            if (!missing.empty()) {
                std::cerr << "drape strokes: classes without a palette colour left out:";
                for (int id : missing) std::cerr << " " << table.name(id);
                std::cerr << "\n";
            }
        } else {
            write_png(args->out, strokes);
        }
        std::cerr << "drape strokes: marked " << 100.0 * vision::marked_fraction(strokes)
                  << " % of the pixels\n";
    });
}

}  // namespace drape::app
