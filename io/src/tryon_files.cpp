#include <drape/io/tryon_files.hpp>

#include <drape/io/body_json.hpp>
#include <drape/io/garment_json.hpp>
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/recovery_files.hpp>

#include "staging.hpp"

#include <drape/body/model_io.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/pattern_svg.hpp>
#include <drape/recover/outfit_glb.hpp>
#include <drape/recover/report.hpp>
#include <drape/vision/segmentation.hpp>

#include <cstdio>

namespace drape::io {

namespace fs = std::filesystem;

namespace {

nlohmann::json grading_json(const garment::GradingSummary& s) {
    static const char* names[] = {"graded", "clamped", "invalid_pattern"};
    nlohmann::json parameters = nlohmann::json::array(), style = nlohmann::json::array(), ease = nlohmann::json::array();
    for (const auto& p : s.parameters)
        parameters.push_back({{"name", p.name}, {"unit", p.unit}, {"original", p.original}, {"graded", p.graded},
                              {"unclamped", p.unclamped}, {"clamped", p.clamped}, {"rule", p.rule}});
    for (const auto& p : s.style)
        style.push_back({{"name", p.name}, {"original", p.original}, {"graded", p.graded},
                         {"relative_change", p.relative_change}});
    for (const auto& e : s.ease) ease.push_back({{"name", e.name}, {"original_cm", e.original_cm}, {"graded_cm", e.graded_cm}});
    return {{"termination", names[static_cast<int>(s.termination)]},
            {"message", s.message},
            {"usable", s.usable()},
            {"grade", {{"chart", s.grade.chart}, {"dimension", s.grade.dimension}, {"from_cm", s.grade.from_cm},
                       {"to_cm", s.grade.to_cm}, {"sizes", s.grade.sizes}, {"text", s.grade.text}}},
            {"parameters", parameters},
            {"style", style},
            {"max_style_change", s.max_style_change},
            {"ease", ease}};
}

std::string num(double v, int digits) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", digits, v);
    return buf;
}

std::string grading_label(const recover::TriedOnGarment& g) {
    return "graded: " + g.grading.grade.text + " (" + g.grading.grade.chart + ", " + g.grading.grade.dimension + " " +
           num(g.grading.grade.from_cm, 1) + " -> " + num(g.grading.grade.to_cm, 1) + " cm)";
}

recover::ReportContent tryon_report(const recover::TryOnInputs& in, const recover::TryOnResult& r,
                                    const recover::TryOnSummary& s) {
    recover::ReportContent c;
    c.title = "Drape try-on";
    const bool photo = !in.target.body.has_value();
    if (photo) {
        c.images.push_back(recover::report_image("The target photo", in.target.photo_bgr, "image/jpeg"));
        if (!r.overlay.empty())
            c.images.push_back(recover::report_image("The garments tried on (arms, head and hair in front)", r.overlay, "image/jpeg"));
        if (!r.own_garment_mask.empty())
            c.images.push_back(recover::report_image("Where the person's own garment still shows (" +
                                                         num(100 * r.own_garment_fraction, 1) + " % of it)",
                                                     r.own_garment_mask));
    }
    for (size_t i = 0; i < r.garments.size(); ++i) {
        const auto& g = r.garments[i];
        c.svgs.push_back({"Grading sheet of garment " + std::to_string(i) + " (" + g.source.name + "): original solid, " +
                              grading_label(g) + " dashed",
                          garment::grading_sheet_to_svg({{&g.original_pattern, "original"}, {&g.pattern, grading_label(g)}})});
    }
    recover::ReportTable garments;
    garments.caption = "Garments";
    garments.header = {"garment", "from", "grade", "style change max", "clamped", "drape", "penetration mm", "seam gap mm"};
    for (const auto& g : r.garments)
        garments.rows.push_back({g.source.name, g.source.source, g.grading.grade.text,
                                 num(100 * g.grading.max_style_change, 2) + " %", std::to_string(g.grading.clamped),
                                 g.drape.usable ? "usable" : "not usable", num(1000 * g.drape.penetration_max_m, 2),
                                 num(1000 * g.drape.seam_gap_max_m, 2)});
    c.tables.push_back(garments);
    for (size_t i = 0; i < r.garments.size(); ++i) {
        recover::ReportTable t;
        t.caption = "Grading of garment " + std::to_string(i) + " (" + r.garments[i].source.name + ")";
        t.header = {"parameter", "original", "graded", "rule"};
        for (const auto& p : r.garments[i].grading.parameters)
            t.rows.push_back({p.name + " (" + p.unit + ")", num(p.original, 2),
                              num(p.graded, 2) + (p.clamped ? " (clamped from " + num(p.unclamped, 2) + ")" : ""), p.rule});
        c.tables.push_back(t);
    }
    c.notes.push_back(s.brief_report());
    return c;
}

}  // namespace

std::vector<recover::TryOnGarment> read_tryon_garments(const std::vector<std::string>& specs) {
    if (specs.empty()) throw InvalidInput("no --garment given: name a result folder (DIR or DIR:N)");
    std::vector<recover::TryOnGarment> out;
    for (const std::string& spec : specs) {
        const SavedRecovery saved = read_recovery_folder(spec);
        for (const SavedGarment& g : saved.garments)
            out.push_back(recover::TryOnGarment{g.type, g.garment, g.sizing, g.material, g.base_fabric, saved.body,
                                                saved.folder.string() + ":" + std::to_string(g.index)});
    }
    return out;
}

nlohmann::json tryon_json(const recover::TryOnInputs& in, const recover::TryOnOptions& options,
                          const recover::TryOnResult& r, const recover::TryOnSummary& s) {
    static const char* terminations[] = {"draped", "graded", "body_fit_failed", "drape_failed", "cancelled"};
    nlohmann::json garments = nlohmann::json::array();
    for (const auto& g : r.garments)
        garments.push_back({{"garment", g.source.name},
                            {"type", garment::garment_type_name(g.source.type)},
                            {"source", g.source.source},
                            {"class_id", g.class_id},
                            {"original_sizing", to_json(g.source.sizing)},
                            {"sizing", to_json(g.sizing)},
                            {"material", material_to_json(g.source.material, g.source.base_fabric)},
                            {"grading", grading_json(g.grading)},
                            {"drape", drape_json(g.drape)}});
    nlohmann::json target;
    if (in.target.body) {
        target = {{"kind", "body"}, {"params", to_json(r.shape)}, {"pose", to_json(r.pose)}};
    } else {
        target = {{"kind", "photo"},
                  {"width", in.target.photo_bgr.cols},
                  {"height", in.target.photo_bgr.rows},
                  {"mode", in.target.strokes.empty() ? "auto" : "strokes"},
                  {"params", to_json(r.shape)},
                  {"pose", to_json(r.pose)},
                  {"camera", to_json(r.fit.camera)},
                  {"own_garment_fraction", r.own_garment_fraction}};
    }
    return {{"format", "drape.tryon"},
            {"version", 1},
            {"target", target},
            {"edge_cm", options.edge_cm},
            {"size_chart", {{"name", options.grading.chart.name}, {"girth_step_cm", options.grading.chart.girth_step_cm}}},
            {"garments", garments},
            {"summary",
             {{"termination", terminations[static_cast<int>(s.termination)]},
              {"message", s.message},
              {"usable", s.usable(r)},
              {"drape", s.drape.brief_report()},
              {"seconds", {{"fit", s.seconds_fit}, {"grade", s.seconds_grade}, {"drape", s.seconds_drape},
                           {"render", s.seconds_render}, {"total", s.seconds}}}}}};
}

bool write_tryon(const fs::path& out, const body::BodyModel& model, const recover::TryOnInputs& in,
                 const recover::TryOnOptions& options, const recover::TryOnResult& result,
                 const recover::TryOnSummary& s, const std::function<bool()>& keep_going) {
    detail::Staging staging(out);
    for (size_t i = 0; i < result.garments.size(); ++i) {
        const recover::TriedOnGarment& g = result.garments[i];
        staging.write_garment(i, g.pattern, g.mesh, g.positions, "drape tryon: " + g.source.name + " from " + g.source.source);
        garment::write_grading_sheet_svg(staging / ("grading_" + std::to_string(i) + ".svg"),
                                         {{&g.original_pattern, "original"}, {&g.pattern, grading_label(g)}});
    }
    body::export_glb(staging / "body.glb", model, result.shaped, result.pose);
    recover::write_outfit_glb(staging / "outfit.glb", recover::tryon_outfit_meshes(model, result));
    if (!result.overlay.empty()) write_png(staging / "overlay.png", result.overlay);
    if (!result.mask.empty()) write_png(staging / "mask.png", result.mask);
    if (!result.own_garment_mask.empty()) write_png(staging / "own_garment_mask.png", result.own_garment_mask);
    recover::write_report_html(staging / "report.html", tryon_report(in, result, s));
    write_json_file(staging / "tryon.json", tryon_json(in, options, result, s));
    if (keep_going && !keep_going()) return false;
    staging.commit();
    return true;
}

}  // namespace drape::io
