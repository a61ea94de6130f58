// drape fit-body IMAGE --joints J.json (--silhouette S.png [--skin K.png] | --labels L.png)
//                [--height M] [--gender female|male] [--focal PX] --out DIR
#include <drape/io/body_fit_files.hpp>
#include "commands.hpp"
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>

#include <drape/body/fit_body.hpp>
#include <drape/body/model_io.hpp>
#include <drape/core/errors.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;

struct FitArgs {
    std::string image;
    std::string joints;
    std::string silhouette;
    std::string skin;
    std::string labels;
    std::optional<double> height_m;
    std::string gender;
    std::optional<double> focal_px;
    std::string out;
    std::string model;
    int threads = 2;
    bool no_shape = false;
    std::optional<double> posture_weight;
    std::optional<double> lean_weight;
    std::optional<double> skin_weight;
    std::string image_joints;  // empty: as the joints file says (its "marks")
};

void run_fit_body(const FitArgs& args) {
    BodyFitFiles files = read_body_fit_files(args.image, args.joints, args.silhouette, args.skin, args.labels);
    body::FitInputs& in = files.inputs;
    in.height_m = args.height_m;
    if (!args.gender.empty()) in.gender = body::parse_gender(args.gender);

    body::FitOptions options;
    options.threads = args.threads;
    options.fit_shape = !args.no_shape;
    if (args.posture_weight) options.posture_weight = *args.posture_weight;
    if (args.lean_weight) options.lean_weight = *args.lean_weight;
    if (args.skin_weight) options.skin_weight = *args.skin_weight;
    if (args.image_joints == "model")
        options.image_joints = body::ImageJointOffsets::none();
    else if (args.image_joints == "hand-marked")
        options.image_joints = body::ImageJointOffsets::hand_marked();
    else if (!args.image_joints.empty())
        throw InvalidInput("--image-joints must be hand-marked or model, got '" + args.image_joints + "'");
    if (args.focal_px) {
        options.camera = body::CameraModel::pinhole;
        options.focal_px = *args.focal_px;
    }

    const body::BodyModel loaded = args.model.empty() ? body::BodyModel() : body::load_model(args.model);
    const body::BodyModel& model = args.model.empty() ? body::BodyModel::default_model() : loaded;

    // Fail before the fit, not after it.
    std::error_code ec;
    fs::create_directories(args.out, ec);
    std::error_code ec_dir;
    if (!fs::is_directory(args.out, ec_dir))
        throw IoError("cannot create the output folder '" + args.out + "'" +
                      (ec ? ": " + ec.message() : std::string()));

    body::BodyFit fit;
    const body::FitSummary summary = body::fit_body(model, in, options, fit);
    std::cerr << "drape fit-body: " << summary.brief_report() << "\n";
    if (!summary.usable()) throw std::runtime_error(summary.brief_report());

    const body::FitQuality quality = body::fit_quality(model, in, fit, summary);
    write_body_fit_folder(args.out, args.image, files, model, fit, summary, quality);
}

}  // namespace

void add_fit_body_command(CLI::App& app) {
    auto args = std::make_shared<FitArgs>();
    CLI::App* cmd = app.add_subcommand(
        "fit-body", "Fit the body model (pose, semantic shape, camera) to a photo from its 14 "
                    "joints and the person's silhouette; writes DIR/body.json, body.glb, overlay.png");
    cmd->add_option("image", args->image, "the photo (JPEG/PNG; EXIF orientation is applied)")->required();
    cmd->add_option("--joints", args->joints,
                    "JSON {\"joints\": 14 [x, y] pixels (right_ankle ... head), optional "
                    "\"pixel_origin\": one_based (default, MATLAB) | zero_based | corner, optional "
                    "\"marks\": hand (default) | model}")
        ->required();
    cmd->add_option("--silhouette", args->silhouette,
                    "PNG mask of the person, garments included (non-zero = person)");
    cmd->add_option("--skin", args->skin, "PNG mask of the visible skin (non-zero = skin)");
    cmd->add_option("--labels", args->labels,
                    "instead of --silhouette/--skin: a Fashionista/CCP class-id label map (8-bit "
                    "PNG); person = all classes but null, accessories, bag, hair, hat, purse, "
                    "wallet; skin = class 41");
    cmd->add_option("--height", args->height_m, "the person's stature, metres");
    cmd->add_option("--gender", args->gender, "female | male (default: chosen by the prior)");
    cmd->add_option("--focal", args->focal_px,
                    "focal length in pixels: use a pinhole camera (default: weak perspective)");
    cmd->add_option("--out", args->out, "output folder (created if absent)")->required();
    cmd->add_option("--model", args->model, "body model HDF5 file (default: built-in mannequin)");
    cmd->add_option("--threads", args->threads, "solver threads (default 2)");
    cmd->add_option("--posture-weight", args->posture_weight,
                    "weight of the posture prior that keeps the trunk and legs from bending "
                    "towards or away from the camera (default 100; 0 = off)");
    cmd->add_option("--lean-weight", args->lean_weight,
                    "weight of the prior that keeps the whole body from leaning forwards, backwards "
                    "or sideways (default 1000; 0 = off)");
    cmd->add_option("--skin-weight", args->skin_weight, "weight of the skin term (default 2)");
    cmd->add_option("--image-joints", args->image_joints,
                    "which body points the joints mark: hand-marked (the convention of hand-marked "
                    "fashion photos, docs/body-fitting.md) | model (the model's joints); default: the "
                    "joints file's \"marks\" (hand or model), hand-marked when it has none");
    cmd->add_flag("--no-shape", args->no_shape, "keep the prior's shape, fit pose and camera only");
    cmd->callback([args] { run_fit_body(*args); });
}

}  // namespace drape::app
