// drape render [--body body.json] [--pose POSE.json] [--mesh M.obj|.glb ...] [--color R,G,B ...]
//              [--label ID ...] [--print KIND[:PERIOD_M] ...] [--lighting midday|sunset|studio]
//              [--camera auto|fitted|front|camera.json] [--photo P.jpg] [--width W --height H]
//              [--samples N] [--threads N] [--stage auto|none|floor|cove] --out render.png
//              [--labels labels.png]
#include <drape/io/body_json.hpp>
#include <drape/io/render_camera.hpp>
#include "commands.hpp"
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/model_io.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>
#include <drape/render/overlay.hpp>
#include <drape/render/preview.hpp>
#include <drape/render/renderer.hpp>

#include <CLI/CLI.hpp>

#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;

struct RenderArgs {
    std::string body;
    std::string pose;
    bool no_body = false;
    std::vector<std::string> meshes;
    std::vector<std::string> colours;
    std::vector<int> labels;
    std::vector<std::string> prints;
    int smooth = 0;
    std::string lighting = "studio";
    std::string camera = "auto";
    std::string photo;
    int width = 0;
    int height = 0;
    int samples = 16;
    int threads = 0;
    std::string stage = "auto";
    double opacity = 1.0;
    std::string out;
    std::string labels_out;
    std::string model;
};

/// What body.json holds: a `drape fit-body` result (shape coefficients, pose, camera and
/// the photo's size) or a `drape body --params` request.
struct BodyInput {
    Eigen::MatrixXd vertices;
    Eigen::MatrixXi faces;
    std::optional<body::Camera> camera;
    int image_width = 0;
    int image_height = 0;
};

BodyInput load_body(const RenderArgs& args) {
    const body::BodyModel loaded = args.model.empty() ? body::BodyModel() : body::load_model(args.model);
    const body::BodyModel& model = args.model.empty() ? body::BodyModel::default_model() : loaded;
    BodyInput in;
    body::ShapedBody shaped;
    body::Pose pose = body::Pose::rest();
    const nlohmann::json j = args.body.empty() ? nlohmann::json::object() : read_json_file(args.body);
    if (j.is_object() && j.value("format", "") == "drape.body_fit") {
        if (!j.contains("coefficients") || !j["coefficients"].is_array())
            throw InvalidInput(args.body + ": field 'coefficients' must be an array of numbers");
        Eigen::VectorXd coeff(static_cast<Eigen::Index>(j["coefficients"].size()));
        for (size_t k = 0; k < j["coefficients"].size(); ++k) {
            const auto& v = j["coefficients"][k];
            if (!v.is_number()) throw InvalidInput(args.body + ": coefficient " + std::to_string(k) + " is not a number");
            coeff[static_cast<Eigen::Index>(k)] = v.get<double>();
        }
        if (coeff.size() != model.shape_count())
            throw InvalidInput(args.body + ": field 'coefficients' has " + std::to_string(coeff.size()) +
                               " values but the body model has " + std::to_string(model.shape_count()));
        shaped = body::shape_from_coefficients(model, coeff);
        if (j.contains("pose")) pose = pose_from_json(j["pose"], args.body);
        if (j.contains("camera")) in.camera = camera_from_json(j["camera"], args.body);
        if (j.contains("image") && j["image"].is_object()) {
            in.image_width = static_cast<int>(j["image"].value("width", 0.0));
            in.image_height = static_cast<int>(j["image"].value("height", 0.0));
        }
    } else {
        const body::SemanticShape shape = model.prior.complete(semantic_request_from_json(j, args.body));
        const body::ShapeSummary summary = body::shape_body(model, shape, body::ShapeOptions{}, shaped);
        if (!summary.usable()) throw std::runtime_error(summary.brief_report());
    }
    if (!args.pose.empty()) pose = pose_from_json(read_json_file(args.pose), args.pose);
    in.vertices = body::pose_body(model, shaped, pose).vertices;
    in.faces = model.faces;
    return in;
}

Eigen::Vector3d parse_colour(const std::string& s) {
    std::stringstream ss(s);
    std::string item;
    std::vector<double> v;
    while (std::getline(ss, item, ',')) {
        try {
            size_t used = 0;
            v.push_back(std::stod(item, &used));
            if (used != item.size()) v.push_back(-1);
        } catch (const std::exception&) {
            v.push_back(-1);
        }
    }
    if (v.size() != 3 || *std::min_element(v.begin(), v.end()) < 0 || *std::max_element(v.begin(), v.end()) > 255)
        throw InvalidInput("--color '" + s + "' must be R,G,B with each in 0..255 (e.g. 200,30,40)");
    return Eigen::Vector3d(v[0], v[1], v[2]) / 255.0;
}

render::Print parse_print(const std::string& s) {
    render::Print p;
    const auto colon = s.find(':');
    const std::string kind = s.substr(0, colon);
    if (kind == "solid") p.kind = render::PrintKind::solid;
    else if (kind == "stripes") p.kind = render::PrintKind::stripes;
    else if (kind == "checks") p.kind = render::PrintKind::checks;
    else if (kind == "dots") p.kind = render::PrintKind::dots;
    else throw InvalidInput("--print '" + s + "': kind must be solid, stripes, checks or dots");
    if (colon != std::string::npos) {
        try {
            size_t used = 0;
            const std::string period = s.substr(colon + 1);
            p.period = std::stod(period, &used);
            if (used != period.size()) throw std::invalid_argument(period);
        } catch (const std::exception&) {
            throw InvalidInput("--print '" + s + "': the period after ':' must be a number of metres");
        }
        if (!(p.period > 0)) throw InvalidInput("--print '" + s + "': the period must be positive");
    }
    return p;
}

/// Default label of a garment file, from the labels.txt ids of ../shared/data/photos.
int label_from_name(const std::string& path) {
    const std::string n = fs::path(path).stem().string();
    auto has = [&](const char* k) { return n.find(k) != std::string::npos; };
    if (has("tshirt") || has("t-shirt") || has("t_shirt")) return 51;
    if (has("dress")) return 14;
    if (has("skirt")) return 42;
    if (has("shorts")) return 40;
    if (has("pants") || has("trousers")) return 31;
    return 54;  // "top": the generic garment class
}

render::Camera camera_from_file(const std::string& file, int width, int height) {
    return render_camera_from_json(read_json_file(file), file, width, height);
}

void run_render(const RenderArgs& args) {
    if (args.no_body && args.meshes.empty())
        throw InvalidInput("drape render: nothing to draw: --no-body and no --mesh");
    if (!args.colours.empty() && args.colours.size() != args.meshes.size() + (args.no_body ? 0 : 1))
        throw InvalidInput("drape render: give one --color per drawn mesh (" +
                           std::string(args.no_body ? "" : "the body, then ") + "each --mesh in order); got " +
                           std::to_string(args.colours.size()) + " for " +
                           std::to_string(args.meshes.size() + (args.no_body ? 0 : 1)) + " meshes");
    if (!args.labels.empty() && args.labels.size() != args.meshes.size())
        throw InvalidInput("drape render: give one --label per --mesh, got " + std::to_string(args.labels.size()) +
                           " for " + std::to_string(args.meshes.size()));
    if (!args.prints.empty() && args.prints.size() != args.meshes.size())
        throw InvalidInput("drape render: give one --print per --mesh, got " + std::to_string(args.prints.size()) +
                           " for " + std::to_string(args.meshes.size()));
    if (args.stage != "auto" && args.stage != "none" && args.stage != "floor" && args.stage != "cove")
        throw InvalidInput("drape render: --stage '" + args.stage + "' is not one of auto, none, floor, cove");
    const render::Lighting lighting = render::lighting_preset(render::parse_lighting_preset(args.lighting));
    for (const std::string& path : {args.out, args.labels_out}) {
        const fs::path dir = fs::path(path).parent_path();
        std::error_code ec;
        if (!path.empty() && !dir.empty() && !fs::is_directory(dir, ec))
            throw IoError("cannot write '" + path + "': folder '" + dir.string() + "' does not exist");
    }

    // Read every input before the (slow) render, so that errors come first.
    const cv::Mat photo = args.photo.empty() ? cv::Mat() : read_photo(args.photo);
    render::Scene scene;
    BodyInput body;
    const std::vector<Eigen::Vector3d> palette = {
        {0.20, 0.33, 0.62}, {0.72, 0.18, 0.16}, {0.85, 0.80, 0.68}, {0.15, 0.45, 0.30}};
    size_t colour_index = 0;
    if (!args.no_body) {
        body = load_body(args);
        render::Mesh m;
        m.name = "body";
        m.V = body.vertices;
        m.F = body.faces;
        m.material.colour_srgb = {0.80, 0.74, 0.67};  // a light mannequin finish
        m.material.roughness = 0.55;
        m.label = 41;  // labels.txt: skin
        if (!args.colours.empty()) m.material.colour_srgb = parse_colour(args.colours[colour_index++]);
        scene.meshes.push_back(std::move(m));
    }
    for (size_t i = 0; i < args.meshes.size(); ++i) {
        const body::TriangleMesh tm = body::import_mesh(args.meshes[i]);
        render::Mesh m;
        m.name = args.meshes[i];
        m.V = tm.V;
        m.F = tm.F;
        m.material.colour_srgb = args.colours.empty() ? palette[i % palette.size()] : parse_colour(args.colours[colour_index++]);
        m.material.roughness = 0.85;
        if (!args.prints.empty()) m.material.print = parse_print(args.prints[i]);
        m.smooth_subdivisions = args.smooth;
        m.label = args.labels.empty() ? label_from_name(args.meshes[i]) : args.labels[i];
        scene.meshes.push_back(std::move(m));
    }

    if ((args.width != 0 || args.height != 0) && (args.width <= 0 || args.height <= 0))
        throw InvalidInput("drape render: --width and --height must both be positive, got " +
                           std::to_string(args.width) + " x " + std::to_string(args.height));
    const bool fitted = args.camera == "fitted" || (args.camera == "auto" && body.camera);
    if (fitted && !body.camera)
        throw InvalidInput("drape render: --camera fitted needs a body.json written by `drape fit-body`");
    int width = args.width, height = args.height;
    if (width <= 0 && !photo.empty()) width = photo.cols, height = photo.rows;
    if (width <= 0 && fitted && body.image_width > 0) width = body.image_width, height = body.image_height;
    if (width <= 0) width = 600, height = 900;
    if (!photo.empty() && (photo.cols != width || photo.rows != height))
        throw InvalidInput("drape render: the photo '" + args.photo + "' is " + std::to_string(photo.cols) + " x " +
                           std::to_string(photo.rows) + " pixels but the render is " + std::to_string(width) +
                           " x " + std::to_string(height));

    const std::string stage = args.stage == "auto" ? (photo.empty() ? "cove" : "none") : args.stage;
    scene.floor.enabled = stage == "floor" || stage == "cove";
    scene.backdrop.enabled = stage == "cove";
    if (scene.floor.enabled) {
        double min_y = 1e300;
        for (const render::Mesh& m : scene.meshes) min_y = std::min(min_y, m.V.col(1).minCoeff());
        scene.floor.height_m = min_y;  // the feet (or the lowest garment) stand on it
    }

    const render::Camera camera = fitted ? render::Camera::from_body(*body.camera, width, height)
                                  : args.camera == "front" || args.camera == "auto"
                                      ? render::front_camera(scene, width, height)
                                      : camera_from_file(args.camera, width, height);
    if (scene.backdrop.enabled) {
        double min_z = 1e300;
        for (const render::Mesh& m : scene.meshes) min_z = std::min(min_z, m.V.col(2).minCoeff());
        scene.backdrop.distance_m = -(min_z - 1.2);
    }

    render::RenderOptions options;
    options.samples_per_pixel = args.samples;
    options.threads = args.threads;
    render::RenderImages images;
    const render::RenderSummary summary = render::render(scene, camera, lighting, options, images);
    std::cerr << "drape render: " << summary.brief_report() << "\n";
    write_png(args.out, photo.empty() ? images.colour : render::composite_over(photo, images, args.opacity));
    if (!args.labels_out.empty()) write_png(args.labels_out, images.labels);
}

}  // namespace

void add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* cmd = app.add_subcommand(
        "render", "Ray-trace the body and garments (soft sun shadows, sky light) to a PNG, "
                  "optionally over the photo they were fitted to; also a label map");
    cmd->add_option("--body", args->body,
                    "body.json from `drape fit-body` (shape, pose and camera) or a `drape body "
                    "--params` JSON (default: the mean female)");
    cmd->add_option("--pose", args->pose, "POSE.json (as for `drape body`), replacing the body's pose");
    cmd->add_flag("--no-body", args->no_body, "draw the --mesh files only");
    cmd->add_option("--mesh", args->meshes, "garment or other mesh (.obj, .glb, .gltf), world metres; repeatable");
    cmd->add_option("--color", args->colours,
                    "R,G,B (0..255) per drawn mesh in order: the body first (unless --no-body), then each --mesh");
    cmd->add_option("--label", args->labels,
                    "label-map id per --mesh (labels.txt; default from the file name: tshirt 51, "
                    "pants 31, skirt 42, dress 14, shorts 40, else 54 top); the body is 41 skin");
    cmd->add_option("--print", args->prints,
                    "KIND[:PERIOD_M] per --mesh: solid, stripes, checks, dots (white on the colour; "
                    "mapped by world x, y since mesh files carry no pattern UVs)");
    cmd->add_option("--smooth", args->smooth,
                    "levels of Phong tessellation of every --mesh before drawing, 0..4 (default 0; 2 "
                    "turns a 6 cm simulated garment into 1.5 cm triangles on its smooth surface)")
        ->check(CLI::Range(0, 4));
    cmd->add_option("--lighting", args->lighting, "midday | sunset | studio (default studio)");
    cmd->add_option("--camera", args->camera,
                    "auto (default: fitted if body.json has a camera, else front) | fitted (body.json's "
                    "camera and image size) | front (framing everything from +Z) | a JSON file: a fit-body camera {model, focal_px|scale_px_per_m, distance_m, "
                    "offset_px}, a body.json, or a look-at {eye, target, up, focal_px}");
    cmd->add_option("--photo", args->photo, "composite the render over this photo (sets the image size)");
    cmd->add_option("--opacity", args->opacity, "overlay opacity in [0, 1] (default 1)");
    cmd->add_option("--width", args->width, "image width, pixels (default: the photo's, else 600)");
    cmd->add_option("--height", args->height, "image height, pixels (default: the photo's, else 900)");
    cmd->add_option("--samples", args->samples, "samples per pixel, 1..4096 (default 16)");
    cmd->add_option("--threads", args->threads, "threads (default 0 = all)");
    cmd->add_option("--stage", args->stage,
                    "auto (cove without --photo, none with it) | none | floor | cove (floor + backdrop)");
    cmd->add_option("--model", args->model, "body model HDF5 file (default: built-in mannequin)");
    cmd->add_option("--out", args->out, "PNG to write")->required();
    cmd->add_option("--labels", args->labels_out, "also write the label map (8-bit PNG of label ids)");
    cmd->callback([args] { run_render(*args); });
}

}  // namespace drape::app
