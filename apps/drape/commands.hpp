// The drape CLI's sub-commands. Each registers itself on the CLI11 app; parsing and JSON
// live here in the app layer, the libraries only see typed options.
#pragma once

namespace CLI {
class App;
}

namespace drape::app {

/// `drape body --params P.json [--pose POSE.json] --out body.glb [--obj body.obj] [--measure]`
void add_body_command(CLI::App& app);

/// `drape fit-body IMAGE --joints J.json --silhouette S.png [--skin K.png] [--height M]
///  [--gender female|male] [--focal PX] --out DIR`
void add_fit_body_command(CLI::App& app);

}  // namespace drape::app
