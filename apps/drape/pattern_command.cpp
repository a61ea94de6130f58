// drape pattern --garment skirt|pants|tshirt|dress --sizing G.json|auto [--body P.json]
//               [--edge CM] --out DIR
#include <drape/io/body_json.hpp>
#include "commands.hpp"
#include <drape/io/garment_json.hpp>
#include <drape/io/json_io.hpp>

#include <drape/body/body_model.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_export.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern_dxf.hpp>
#include <drape/garment/pattern_json.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

namespace drape::app {

using namespace io;

namespace {

struct PatternArgs {
    std::string garment;
    std::string sizing;
    std::string body;
    std::string out;
    double edge_cm = 1.5;
};

// G from the body's measurements (the mean female when no P.json is given).
GarmentSizing auto_sizing(GarmentType type, const std::string& body_file) {
    const body::BodyModel& model = body::BodyModel::default_model();
    const body::SemanticRequest request =
        body_file.empty() ? body::SemanticRequest{}
                          : semantic_request_from_json(read_json_file(body_file), body_file);
    body::ShapedBody shaped;
    const body::ShapeSummary s =
        body::shape_body(model, model.prior.complete(request), body::ShapeOptions{}, shaped);
    if (!s.usable()) throw std::runtime_error("drape pattern: body shaping failed: " + s.brief_report());
    return proposed_sizing(type, model, shaped, s.measured);
}

void run_pattern(const PatternArgs& args) {
    const GarmentType type = garment_type_from_name(args.garment);
    if (!args.body.empty() && args.sizing != "auto")
        throw InvalidInput("drape pattern: --body is used only with --sizing auto");
    const GarmentSizing sizing =
        args.sizing == "auto" ? auto_sizing(type, args.body)
                              : sizing_from_json(type, read_json_file(args.sizing), args.sizing);
    const garment::Pattern pattern = make_pattern(sizing);
    const std::filesystem::path dir(args.out);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw IoError("cannot create output folder '" + args.out + "': " + ec.message());
    garment::write_pattern_svg(dir / "pattern.svg", pattern);
    garment::write_pattern_dxf(dir / "pattern.dxf", pattern);
    garment::write_pattern_json(dir / "pattern.json", pattern);
    garment::MeshOptions options;
    options.target_edge_cm = args.edge_cm;
    garment::GarmentMesh mesh;
    const garment::MeshSummary summary = garment::mesh_pattern(pattern, options, mesh);
    garment::write_garment_obj(dir / "pattern_mesh.obj", pattern, mesh, garment::flat_layout(mesh), "flat layout");
    nlohmann::json report = {{"garment", garment_type_name(type)},
                             {"sizing", to_json(sizing)},
                             {"panels", pattern.panels.size()},
                             {"seams", pattern.seams.size()},
                             {"area_cm2", pattern.total_area()},
                             {"vertices", summary.vertices},
                             {"faces", summary.faces},
                             {"stitches", summary.stitches},
                             {"min_angle_deg", summary.min_angle_deg},
                             {"mean_edge_cm", summary.mean_edge_cm},
                             {"mesh_usable", summary.usable()},
                             {"seconds", summary.seconds}};
    write_json_file(dir / "summary.json", report);
    std::cout << "drape pattern: " << pattern.name << ", " << summary.brief_report() << "\n";
    if (!summary.usable()) throw std::runtime_error("drape pattern: " + summary.message);
}

}  // namespace

void add_pattern_command(CLI::App& app) {
    auto args = std::make_shared<PatternArgs>();
    CLI::App* cmd = app.add_subcommand(
        "pattern", "Make a sewing pattern from sizing parameters G and export it (SVG at true "
                   "scale, AAMA DXF, GarmentCode JSON, flat mesh OBJ)");
    cmd->add_option("--garment", args->garment, "skirt, pants, tshirt or dress")->required();
    cmd->add_option("--sizing", args->sizing,
                    "G.json with the paper's parameter names (cm, degrees), or 'auto' to "
                    "derive G from the body's measurements")
        ->required();
    cmd->add_option("--body", args->body,
                    "with --sizing auto: body P.json (semantic measurements, as `drape body "
                    "--params`); default: the mean female");
    cmd->add_option("--edge", args->edge_cm, "mesh target edge length, cm (default 1.5)");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] { run_pattern(*args); });
}

}  // namespace drape::app
