// drape recover: the body, garments, sewing patterns and fabrics of one photo
// (docs/recovery.md). The pipeline is librecover's; this file parses, reads, writes, prints.
#include "commands.hpp"
#include "interrupt.hpp"
#include "recover_io.hpp"

#include <drape/body/model_io.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/core/errors.hpp>
#include <drape/recover/recover.hpp>

#include <CLI/CLI.hpp>

#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>

namespace drape::app {

using namespace io;

namespace {

struct RecoverArgs {
    std::string image;
    std::string joints;
    std::string strokes;
    std::string palette;
    std::string garment = "auto";
    std::optional<double> height_m;
    std::string gender;
    std::string out;
    std::string model;
    RecoverFlags flags;
};

void run_recover(const RecoverArgs& args) {
    recover::RecoverInputs in = read_recover_inputs(args.image, args.joints, args.strokes, args.palette, args.garment);
    in.height_m = args.height_m;
    if (!args.gender.empty()) in.gender = body::parse_gender(args.gender);
    check_output_folder(args.out);  // an unwritable --out fails now, not after minutes of work
    const recover::RecoverOptions options = recover_options(args.flags, "drape recover");
    const body::BodyModel loaded = args.model.empty() ? body::BodyModel() : body::load_model(args.model);
    const body::BodyModel& model = args.model.empty() ? body::BodyModel::default_model() : loaded;

    recover::RecoveryResult result;
    const recover::RecoverSummary s = recover::recover(model, in, options, result);
    std::cerr << "drape recover: " << s.brief_report() << "\n";
    if (s.termination == recover::RecoverTermination::cancelled)
        throw CommandExit{130, "recover: cancelled; '" + args.out + "' is unchanged"};
    if (s.termination == recover::RecoverTermination::no_garment)
        throw InvalidInput("no garment found in '" + args.image + "': " + s.message);
    if (s.termination != recover::RecoverTermination::recovered) throw std::runtime_error(s.brief_report());
    if (!write_recovery(args.out, args.image, model, in, options, result, s, [] { return !interrupted(); }))
        throw CommandExit{130, "recover: cancelled; '" + args.out + "' is unchanged"};
    std::cout << "drape recover: " << result.garments.size() << " garment(s) in " << args.out << "\n";
    for (const auto& g : result.garments)
        std::cout << "  " << recover::garment_choice_name(g.choice) << ": silhouette " << std::fixed
                  << std::setprecision(1) << g.silhouette_rms_px << " px RMS, bending x" << std::setprecision(2)
                  << g.material.bending_scale << " (nearest " << g.nearest_fabric << "), K " << g.mean_curvature_per_m
                  << " 1/m, drape " << (g.drape.usable ? "usable" : "NOT usable") << "\n";
    if (!s.usable(result)) throw CommandExit{1, "recover: a drape is not usable (see result.json)"};
}

}  // namespace

void add_recover_flags(CLI::App* cmd, RecoverFlags& f) {
    cmd->add_option("--quality", f.quality, "fast|default|fine");
    cmd->add_option("--threads", f.threads, "worker threads (default 2)");
    cmd->add_option("--seed", f.seed, "the particle swarm's seed (default 1)");
    cmd->add_option("--particles", f.particles, "swarm size (overrides --quality)");
    cmd->add_option("--generations", f.generations, "swarm generations per sizing search (overrides --quality)");
    cmd->add_option("--rounds", f.rounds, "sizing/material rounds at most (overrides --quality)");
    cmd->add_flag("--no-material", f.no_material, "keep the base fabric at bending x1 (no material search)");
    cmd->add_option("--material-target", f.material_target,
                    "calibrated (default: K from the calibrated mapping of P) | synthesis (P measured on renders of "
                    "the candidate drapes; docs/material-estimation.md)");
    cmd->add_option("--base-fabric", f.base_fabric,
                    "the measured fabric whose bending the material search scales x1..x100 (default gray-interlock, "
                    "the paper's space; the names are in docs/materials.md)");
    cmd->add_option("--max-arm-elevation", f.max_arm_elevation,
                    "upper arms raised more than this many degrees above hanging are lowered to it before draping "
                    "(default 90; 180 = off; docs/recovery.md)");
    cmd->add_option("--min-ease", f.min_ease,
                    "the least ease (cm of girth over the body) the sizing search lets a garment reach; negative = "
                    "smaller than the body, stretched on it (default 2; -10..10; docs/recovery.md)");
    cmd->add_option("--output-drape", f.output_drape,
                    "output (default: the output drape at the output resolution, usable or not) | auto (the search's "
                    "re-drape where only that one is usable) | search (the search's re-drapes only, quicker; "
                    "docs/recovery.md)");
    cmd->add_flag("--joint-pose", f.joint_pose,
                  "after the sizing/material rounds, search the pose of the joints under each garment together with "
                  "the material (paper Algorithm 2; off by default, docs/recovery.md)");
}

void add_recover_command(CLI::App& app) {
    auto args = std::make_shared<RecoverArgs>();
    CLI::App* cmd = app.add_subcommand(
        "recover", "Recover the body, each garment's sewing pattern, fabric and 3D drape from one photo; writes "
                   "DIR/result.json, garment_N.glb/.obj, pattern_N.svg/.dxf/.json, body.glb, outfit.glb, mask.png, "
                   "overlay.png, segmentation.png, report.html");
    cmd->add_option("image", args->image, "the photo (JPEG/PNG)")->required();
    cmd->add_option("--joints", args->joints, "the 14 joints (JSON, as ../shared/data/photos/joints)")->required();
    cmd->add_option("--strokes", args->strokes, "user strokes (PNG: class ids, or colours with --palette); none = automatic");
    cmd->add_option("--palette", args->palette, "colour -> class table for colour-coded strokes");
    cmd->add_option("--garment", args->garment,
                    "auto, or skirt|pants|shorts|tshirt|tank|longsleeve|dress, or two joined by + (tshirt+pants)");
    cmd->add_option("--height", args->height_m, "the person's stature, metres");
    cmd->add_option("--gender", args->gender, "female|male");
    add_recover_flags(cmd, args->flags);
    cmd->add_option("--model", args->model, "a body model file (default: the built-in model)");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] { run_recover(*args); });
}

}  // namespace drape::app
