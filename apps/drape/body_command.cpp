// drape body --params P.json [--pose POSE.json] --out body.glb [--obj body.obj] [--measure]
#include <drape/io/body_json.hpp>
#include "commands.hpp"
#include <drape/io/json_io.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/model_io.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>

#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

namespace drape::app {

using namespace io;

namespace {

struct BodyArgs {
    std::string params;
    std::string pose;
    std::string out;
    std::string obj;
    std::string model;
    bool measure = false;
};

void run_body(const BodyArgs& args) {
    const body::BodyModel loaded =
        args.model.empty() ? body::BodyModel() : body::load_model(args.model);
    const body::BodyModel& model = args.model.empty() ? body::BodyModel::default_model() : loaded;

    const body::SemanticRequest request =
        args.params.empty() ? body::SemanticRequest{}
                            : semantic_request_from_json(read_json_file(args.params), args.params);
    const body::SemanticShape shape = model.prior.complete(request);
    body::ShapedBody shaped;
    const body::ShapeSummary summary = body::shape_body(model, shape, body::ShapeOptions{}, shaped);
    if (!summary.usable()) throw std::runtime_error(summary.brief_report());
    if (summary.termination != body::ShapeTermination::converged)
        std::cerr << "drape body: warning: " << summary.brief_report() << "\n";

    const body::Pose pose =
        args.pose.empty() ? body::Pose::rest() : pose_from_json(read_json_file(args.pose), args.pose);
    if (!args.out.empty()) body::export_glb(args.out, model, shaped, pose);
    if (!args.obj.empty())
        body::export_obj(args.obj, body::pose_body(model, shaped, pose).vertices, model.faces);
    if (args.measure) {
        nlohmann::json j = to_json(summary.measured, shape.gender);
        j["muscle"] = shape[body::Semantic::muscle];
        std::cout << j.dump(2) << std::endl;
    }
}

}  // namespace

void add_body_command(CLI::App& app) {
    auto args = std::make_shared<BodyArgs>();
    CLI::App* cmd = app.add_subcommand(
        "body", "Make a body from semantic measurements (missing ones predicted from ANSUR II), "
                "pose it and export it");
    cmd->add_option("--params", args->params,
                    "JSON with any subset of gender, height_m, weight_kg, muscle, chest_girth_m, "
                    "waist_girth_m, hip_girth_m, thigh_girth_m, calf_girth_m, shoulder_height_m, "
                    "crotch_height_m (default: the mean female)");
    cmd->add_option("--pose", args->pose,
                    "JSON {preset, translation, rotations{joint: [axis-angle]}} (default: A-pose)");
    cmd->add_option("--out", args->out, "rigged glTF binary to write (.glb)");
    cmd->add_option("--obj", args->obj, "also write the posed mesh as OBJ");
    cmd->add_option("--model", args->model, "body model HDF5 file (default: built-in mannequin)");
    cmd->add_flag("--measure", args->measure,
                  "print the measurements taken on the generated mesh as one JSON object");
    cmd->callback([args] {
        if (args->out.empty() && args->obj.empty() && !args->measure)
            throw InvalidInput("drape body: nothing to do: give --out, --obj or --measure");
        run_body(*args);
    });
}

}  // namespace drape::app
