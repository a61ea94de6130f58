// The drape CLI's sub-commands. Each registers itself on the CLI11 app; parsing and JSON
// live here in the app layer, the libraries only see typed options.
#pragma once

#include <drape/body/pose.hpp>

#include <string>

namespace CLI {
class App;
}

namespace drape::app {

/// `drape body --params P.json [--pose POSE.json] --out body.glb [--obj body.obj] [--measure]`
void add_body_command(CLI::App& app);

/// `drape fit-body IMAGE --joints J.json --silhouette S.png [--skin K.png] [--height M]
///  [--gender female|male] [--focal PX] --out DIR`
void add_fit_body_command(CLI::App& app);

/// `drape render [--body body.json] [--mesh M.obj ...] [--lighting midday|sunset|studio]
///  [--camera auto|fitted|front|camera.json] [--photo P.jpg] --out render.png [--labels L.png]`
void add_render_command(CLI::App& app);

/// `drape segment IMAGE --joints J.json [--strokes S.png] [--hint TYPE] [--height M] --out DIR`
void add_segment_command(CLI::App& app);

/// `drape strokes LABELS.png --out S.png` (simulated user strokes)
void add_strokes_command(CLI::App& app);

/// `drape eval-segment DIR [--mode strokes|auto|both] [--scale-check] --out RESULT.json`
void add_eval_segment_command(CLI::App& app);
void add_recover_command(CLI::App& app);
/// `drape tryon --garment RESULT_DIR[:N] ... (--body P.json [--pose POSE] | --photo IMAGE --joints J.json) --out DIR`
/// and `drape eval-tryon SUITE_DIR --out R.json` (docs/tryon.md)
void add_tryon_commands(CLI::App& app);
/// A named pose (a_pose, arms_down, walking, t_pose) or a POSE.json file.
/// \throw drape::InvalidInput naming the value otherwise.
body::Pose resolve_pose(const std::string& name);
void add_eval_recover_commands(CLI::App& app);

/// `drape animate --garment RESULT_DIR[:N] ... [--motion walk|M.bvh] [--wind X,Y,Z] [--seconds S]
///  [--fps F] --out DIR` and `drape eval-animate --out R.json` (docs/animation.md)
void add_animate_command(CLI::App& app);

/// `drape pattern --garment skirt|pants|tshirt|dress --sizing G.json|auto [--body P.json]
///  [--edge CM] --out DIR` (pattern.svg/dxf/json, pattern_mesh.obj, summary.json)
void add_pattern_command(CLI::App& app);

/// `drape dress --garment G --sizing G.json|auto --material NAME|PATH [--body P.json] [--pose NAME] --out DIR`
void add_dress_command(CLI::App& app);

/// `drape eval-dress [--garments LIST] [--poses LIST] [--edge CM] --out DIR` (templates x five
/// ANSUR bodies x poses: table.md, results.json, renders)
void add_eval_dress_command(CLI::App& app);

/// `drape synth --seed N [--garment G] [--pose a|b|c|random] [--material NAME|random] --out DIR`
/// or `drape synth --suite SUITE.json --out DIR` (synthetic ground-truth scenes)
void add_synth_command(CLI::App& app);

/// `drape bench-cloth [--n 32|64] [--seconds S] [--material NAME|PATH] [--threads N] [--out R.json]`
void add_bench_cloth_command(CLI::App& app);
/// drape bench-sizing-drape: the fast re-drape of recovery against the full pipeline.
void add_bench_sizing_drape_command(CLI::App& app);

}  // namespace drape::app
