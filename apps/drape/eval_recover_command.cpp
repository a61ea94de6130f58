// drape eval-synthetic / drape eval-photos: recovery measured against known answers
// (docs/recovery.md, "Accuracy"), with the metrics of librecover/metrics.hpp.
#include "commands.hpp"
#include <drape/io/garment_json.hpp>
#include "interrupt.hpp"
#include <drape/io/json_io.hpp>
#include "recover_io.hpp"

#include <drape/core/errors.hpp>
#include <drape/recover/metrics.hpp>
#include <drape/recover/recover.hpp>
#include <drape/vision/image_io.hpp>
#include <drape/vision/photo_split.hpp>
#include <drape/vision/strokes.hpp>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;

std::string fixed(double v, int d) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(d) << v;
    return s.str();
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct EvalSynthArgs {
    std::string dir;
    std::string out;
    std::string lighting = "both";
    std::vector<std::string> only;
    std::string save_dir;
    RecoverFlags flags;
};

void run_eval_synthetic(const EvalSynthArgs& args) {
    std::vector<fs::path> scenes;
    if (fs::exists(fs::path(args.dir) / "truth.json")) {
        scenes.push_back(args.dir);
    } else {
        for (const auto& e : fs::directory_iterator(args.dir))
            if (fs::exists(e.path() / "truth.json")) scenes.push_back(e.path());
    }
    std::sort(scenes.begin(), scenes.end());
    if (!args.only.empty())
        scenes.erase(std::remove_if(scenes.begin(), scenes.end(),
                                    [&](const fs::path& p) {
                                        return std::find(args.only.begin(), args.only.end(), p.filename().string()) ==
                                               args.only.end();
                                    }),
                     scenes.end());
    if (scenes.empty()) throw InvalidInput("eval-synthetic: no scene (a folder with truth.json) in '" + args.dir + "'");
    std::vector<std::string> lightings;
    if (args.lighting == "both" || args.lighting == "midday") lightings.push_back("midday");
    if (args.lighting == "both" || args.lighting == "sunset") lightings.push_back("sunset");
    if (lightings.empty()) throw InvalidInput("--lighting '" + args.lighting + "' is not midday, sunset or both");

    const body::BodyModel& model = body::BodyModel::default_model();
    const recover::RecoverOptions options = recover_options(args.flags, "drape eval-synthetic");
    nlohmann::json rows = nlohmann::json::array();
    std::vector<double> sizing, material, curvature, bend_err, seconds;
    int runs = 0, usable = 0;
    std::cout << "| scene | light | garment | sizing % | material % | log10 s_b error | curvature % | drape | s |\n"
                 "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const fs::path& scene : scenes) {
        const nlohmann::json truth = read_json_file(scene / "truth.json");
        std::string garments;
        for (const auto& g : truth.at("garments")) garments += (garments.empty() ? "" : "+") + g.at("type").get<std::string>();
        for (const std::string& light : lightings) {
            if (interrupted()) throw CommandExit{130, "eval-synthetic: cancelled"};
            const auto t0 = std::chrono::steady_clock::now();
            recover::RecoverInputs in = read_recover_inputs(scene / ("image_" + light + ".png"), scene / "joints.json",
                                                            (scene / "strokes.png").string(), "", garments);
            recover::RecoveryResult result;
            const recover::RecoverSummary s = recover::recover(model, in, options, result);
            const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            ++runs;
            nlohmann::json row = {{"scene", scene.filename().string()}, {"lighting", light}, {"seconds", secs},
                                  {"termination", s.brief_report()}};
            if (s.termination != recover::RecoverTermination::recovered) {
                std::cout << "| " << scene.filename().string() << " | " << light << " | failed: " << s.message
                          << " | | | | | | " << fixed(secs, 0) << " |\n";
                rows.push_back(row);
                continue;
            }
            if (s.usable(result)) ++usable;
            seconds.push_back(secs);
            if (!args.save_dir.empty())
                write_recovery(fs::path(args.save_dir) / (scene.filename().string() + "_" + light),
                               (scene / ("image_" + light + ".png")).string(), model, in, options, result, s,
                               [] { return !interrupted(); });
            nlohmann::json gs = nlohmann::json::array();
            for (const auto& tg : truth.at("garments")) {
                const garment::GarmentType type = garment::garment_type_from_name(tg.at("type").get<std::string>());
                const auto it = std::find_if(result.garments.begin(), result.garments.end(),
                                             [&](const recover::RecoveredGarment& g) { return g.type == type; });
                if (it == result.garments.end()) continue;
                const std::string file = (scene / "truth.json").string();
                const garment::GarmentSizing gt = sizing_from_json(type, tg.at("sizing"), file);
                const cloth::Material gm = material_from_json(tg.at("material"), file);
                const recover::GarmentScore sc =
                    recover::score_garment(it->sizing, it->initial_sizing, it->material, it->mean_curvature_per_m, gt, gm,
                                           tg.at("mean_curvature_per_m").get<double>());
                const double sa = sc.sizing, ma = sc.material, be = sc.bending_log10, ca = sc.curvature;
                sizing.push_back(sa);
                material.push_back(ma);
                bend_err.push_back(be);
                curvature.push_back(ca);
                gs.push_back({{"type", garment::garment_type_name(type)},
                              {"sizing_accuracy", sa},
                              {"initial_sizing_accuracy", sc.initial_sizing},
                              {"material_accuracy", ma},
                              {"bending_log10_error", be},
                              {"curvature_accuracy", ca},
                              {"estimate", {{"sizing", to_json(it->sizing)},
                                            {"bending_scale", it->material.bending_scale},
                                            {"mean_curvature_per_m", it->mean_curvature_per_m},
                                            {"wrinkle_density_per_m2", it->wrinkle_density_per_m2}}},
                              {"truth", {{"sizing", tg.at("sizing")},
                                         {"bending_scale", gm.bending_scale},
                                         {"base_fabric", tg.at("material").value("base_fabric", "")},
                                         {"mean_curvature_per_m", tg.at("mean_curvature_per_m")},
                                         {"wrinkle_density_per_m2", tg.at("wrinkle_density_per_m2")}}},
                              {"usable", it->drape.usable}});
                std::cout << "| " << scene.filename().string() << " | " << light << " | "
                          << garment::garment_type_name(type) << " | " << fixed(100 * sa, 1) << " | "
                          << fixed(100 * ma, 1) << " | " << fixed(be, 2) << " | " << fixed(100 * ca, 1) << " | "
                          << (it->drape.usable ? "usable" : "NOT usable") << " | " << fixed(secs, 0) << " |\n"
                          << std::flush;
            }
            row["garments"] = gs;
            rows.push_back(row);
        }
    }
    auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? 0.0 : s / static_cast<double>(v.size());
    };
    std::cout << "\n" << runs << " recoveries (" << scenes.size() << " scenes x " << lightings.size() << " lightings), "
              << usable << " with every drape usable; mean sizing accuracy " << fixed(100 * mean(sizing), 1)
              << " %, material " << fixed(100 * mean(material), 1) << " %, curvature " << fixed(100 * mean(curvature), 1)
              << " %, mean |log10 s_b error| " << fixed(mean(bend_err), 2) << "; median " << fixed(median(seconds), 0)
              << " s per recovery\n";
    write_json_file(args.out, {{"format", "drape.eval_synthetic"},
                               {"quality", args.flags.quality},
                               {"recoveries", runs},
                               {"usable", usable},
                               {"mean_sizing_accuracy", mean(sizing)},
                               {"mean_material_accuracy", mean(material)},
                               {"mean_curvature_accuracy", mean(curvature)},
                               {"mean_bending_log10_error", mean(bend_err)},
                               {"median_seconds", median(seconds)},
                               {"runs", rows}});
}

// A GroupIou's account of where its IoU is lost, for R.json (NaN is written as null).
nlohmann::json where_lost_json(const recover::GroupIou& g) {
    nlohmann::json j = {{"precision", g.precision},
                        {"recall", g.recall},
                        {"top_row_error_px", g.top_row_error_px},
                        {"bottom_row_error_px", g.bottom_row_error_px},
                        {"width_error_px", g.width_error_px}};
    for (size_t k = 0; k < g.false_positive_shares.size(); ++k)
        j["false_positive_shares"][recover::false_positive_names()[k]] = g.false_positive_shares[k];
    for (size_t k = 0; k < g.false_negative_shares.size(); ++k)
        j["false_negative_shares"][recover::false_negative_names()[k]] = g.false_negative_shares[k];
    return j;
}

struct EvalPhotosArgs {
    std::string dir;
    std::string out;
    std::string mode = "strokes";
    std::string split = "all";
    std::string stroke_style = "medial";
    int limit = 0;
    std::vector<std::string> names;
    std::string save_dir;
    std::string rescore_dir;
    RecoverFlags flags;
};

void run_eval_photos(const EvalPhotosArgs& args) {
    const fs::path dir(args.dir);
    if (!fs::is_directory(dir / "images"))
        throw InvalidInput("eval-photos: '" + args.dir + "' has no images/ folder (the layout of ../shared/data/photos)");
    if (args.mode != "strokes" && args.mode != "auto")
        throw InvalidInput("--mode '" + args.mode + "' is not strokes or auto");
    std::vector<std::string> all;
    for (const auto& e : fs::directory_iterator(dir / "images"))
        if (e.path().extension() == ".jpg") all.push_back(e.path().stem().string());
    std::sort(all.begin(), all.end());
    std::vector<std::string> names =
        args.names.empty() ? vision::select_photo_split(all, vision::parse_photo_split(args.split)) : args.names;
    if (args.limit > 0 && static_cast<int>(names.size()) > args.limit) names.resize(static_cast<size_t>(args.limit));
    const vision::StrokeStyle style = vision::parse_stroke_style(args.stroke_style);
    const body::BodyModel& model = body::BodyModel::default_model();
    const recover::RecoverOptions options = recover_options(args.flags, "drape eval-photos");
    nlohmann::json rows = nlohmann::json::array();
    std::vector<double> ious, seconds, joint_err;
    int runs = 0, recovered = 0, usable = 0;
    std::array<std::vector<recover::GroupIou>, 3> counted;  // per group, the photos where it counts
    std::cout << "| photo | upper IoU | lower IoU | dress IoU | joint error % | drapes usable | s |\n"
                 "| --- | --- | --- | --- | --- | --- | --- |\n";
    for (const std::string& name : names) {
        if (interrupted()) throw CommandExit{130, "eval-photos: cancelled"};
        const auto t0 = std::chrono::steady_clock::now();
        const cv::Mat truth = vision::load_label_map(dir / "labels" / (name + ".png"), "labels");
        ++runs;
        nlohmann::json row = {{"photo", name}};
        cv::Mat mask;
        std::string tail = " | | | |\n";  // joint error, usable, seconds: none when rescoring
        if (!args.rescore_dir.empty()) {
            // Score an earlier --save run's mask.png instead of recovering.
            const fs::path saved = fs::path(args.rescore_dir) / name / "mask.png";
            if (!fs::exists(saved)) {
                row["error"] = "no " + saved.string();
                std::cout << "| " << name << " | not saved: " << saved.string() << " | | | | | |\n";
                rows.push_back(row);
                continue;
            }
            mask = vision::load_label_map(saved, "mask");
            if (mask.size() != truth.size()) {
                row["error"] = saved.string() + " is " + std::to_string(mask.cols) + " x " + std::to_string(mask.rows) +
                               ", the photo's labels " + std::to_string(truth.cols) + " x " +
                               std::to_string(truth.rows) + ": not a recovery of this photo";
                std::cout << "| " << name << " | not scored: " << row["error"].get<std::string>() << " | | | | | |\n";
                rows.push_back(row);
                continue;
            }
            ++recovered;
        } else {
            recover::RecoverInputs in = read_recover_inputs(dir / "images" / (name + ".jpg"),
                                                            dir / "joints" / (name + ".json"), "", "", "auto");
            if (args.mode == "strokes") in.strokes = vision::simulate_strokes(truth, style, 1);
            recover::RecoveryResult result;
            recover::RecoverSummary s;
            std::string error;
            try {
                s = recover::recover(model, in, options, result);
            } catch (const InvalidInput& e) {
                error = e.what();
            }
            const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            row["seconds"] = secs;
            if (!error.empty() || s.termination != recover::RecoverTermination::recovered) {
                row["error"] = error.empty() ? s.brief_report() : error;
                std::cout << "| " << name << " | failed: " << row["error"].get<std::string>() << " | | | | | "
                          << fixed(secs, 0) << " |\n";
                rows.push_back(row);
                continue;
            }
            ++recovered;
            const bool ok = s.usable(result);
            usable += ok ? 1 : 0;
            seconds.push_back(secs);
            if (!args.save_dir.empty())
                write_recovery(fs::path(args.save_dir) / name, (dir / "images" / (name + ".jpg")).string(), model, in,
                               options, result, s, [] { return !interrupted(); });
            mask = result.mask;
            const double err = result.joint_error_percent;
            joint_err.push_back(err);
            row["joint_error_percent"] = err;
            row["usable"] = ok;
            tail = " | " + fixed(err, 2) + " | " + (ok ? "yes" : "no") + " | " + fixed(secs, 0) + " |\n";
        }
        const auto groups = recover::group_ious(mask, truth);
        std::cout << "| " << name;
        nlohmann::json gj = nlohmann::json::object(), dj = nlohmann::json::object();
        for (const auto& g : groups) {
            if (g.counted) ious.push_back(g.iou);
            std::cout << " | " << (g.counted ? fixed(g.iou, 3) : std::string("–"));
            if (!g.counted) continue;
            gj[recover::group_name(g.group)] = g.iou;
            dj[recover::group_name(g.group)] = where_lost_json(g);
            counted[static_cast<size_t>(g.group)].push_back(g);
        }
        std::cout << tail << std::flush;
        row["iou"] = gj;
        row["where_lost"] = dj;
        rows.push_back(row);
    }
    auto mean = [](const std::vector<double>& v) {
        double s = 0;
        for (double x : v) s += x;
        return v.empty() ? 0.0 : s / static_cast<double>(v.size());
    };
    if (!args.rescore_dir.empty()) {
        std::cout << "\n" << runs << " photos rescored from " << args.rescore_dir << ", " << recovered
                  << " with a mask.png; mean garment IoU " << fixed(mean(ious), 3) << " over " << ious.size()
                  << " garment groups\n";
    } else {
        std::cout << "\n" << runs << " photos (" << args.mode << "), " << recovered << " recovered, " << usable
                  << " with every drape usable; mean garment IoU " << fixed(mean(ious), 3) << " over " << ious.size()
                  << " garment groups; mean joint error " << fixed(mean(joint_err), 2) << " %; median "
                  << fixed(median(seconds), 0) << " s per photo\n";
    }
    // Where the IoU is lost, per group: means over the photos (medians for the rows and
    // widths, whose errors have either sign); NaN fields (an empty group) left out.
    nlohmann::json lost_json = nlohmann::json::object();
    std::cout << "\nWhere the IoU is lost (means over the garments; rows and widths: medians, px, > 0 lower or "
                 "wider than labelled; wrong = shares of the predicted pixels on what the labels hold there; "
                 "missed = shares of the labelled pixels on what the prediction holds there):\n\n"
                 "| group | garments | precision | recall | top row | bottom row | width | wrong: skin / hair / "
                 "background / garment / other | missed: body / background / garment |\n"
                 "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const auto& gs : counted) {
        if (gs.empty()) continue;
        const auto over = [&](const auto& field) {
            std::vector<double> v;
            for (const recover::GroupIou& g : gs)
                if (std::isfinite(field(g))) v.push_back(field(g));
            return v;
        };
        recover::GroupIou m;  // the summary, in GroupIou's fields
        m.precision = mean(over([](const auto& g) { return g.precision; }));
        m.recall = mean(over([](const auto& g) { return g.recall; }));
        m.top_row_error_px = median(over([](const auto& g) { return g.top_row_error_px; }));
        m.bottom_row_error_px = median(over([](const auto& g) { return g.bottom_row_error_px; }));
        m.width_error_px = median(over([](const auto& g) { return g.width_error_px; }));
        for (size_t k = 0; k < m.false_positive_shares.size(); ++k)
            m.false_positive_shares[k] = mean(over([k](const auto& g) { return g.false_positive_shares[k]; }));
        for (size_t k = 0; k < m.false_negative_shares.size(); ++k)
            m.false_negative_shares[k] = mean(over([k](const auto& g) { return g.false_negative_shares[k]; }));
        const std::string gname = recover::group_name(gs.front().group);
        std::cout << "| " << gname << " | " << gs.size() << " | " << fixed(m.precision, 3) << " | "
                  << fixed(m.recall, 3) << " | " << fixed(m.top_row_error_px, 1) << " | "
                  << fixed(m.bottom_row_error_px, 1) << " | " << fixed(m.width_error_px, 1) << " |";
        for (size_t k = 0; k < m.false_positive_shares.size(); ++k)
            std::cout << (k ? " / " : " ") << fixed(m.false_positive_shares[k], 3);
        std::cout << " |";
        for (size_t k = 0; k < m.false_negative_shares.size(); ++k)
            std::cout << (k ? " / " : " ") << fixed(m.false_negative_shares[k], 3);
        std::cout << " |\n";
        lost_json[gname] = where_lost_json(m);
        lost_json[gname]["garments"] = gs.size();
    }
    write_json_file(args.out, {{"format", "drape.eval_photos"},
                               {"rescored_from",
                                args.rescore_dir.empty() ? nlohmann::json() : nlohmann::json(args.rescore_dir)},
                               {"where_lost", lost_json},
                               {"mode", args.mode},
                               {"split", args.split},
                               {"photos", runs},
                               {"recovered", recovered},
                               {"usable", usable},
                               {"mean_garment_iou", mean(ious)},
                               {"mean_joint_error_percent", mean(joint_err)},
                               {"median_seconds", median(seconds)},
                               {"runs", rows}});
}

}  // namespace

void add_eval_recover_commands(CLI::App& app) {
    auto sa = std::make_shared<EvalSynthArgs>();
    CLI::App* s = app.add_subcommand("eval-synthetic",
                                     "Recover every scene written by drape synth (each lighting) and compare result "
                                     "with truth.json: sizing, material and curvature accuracy, time");
    s->add_option("dir", sa->dir, "a scene folder, or a folder of scene folders")->required();
    s->add_option("--out", sa->out, "result JSON to write")->required();
    s->add_option("--lighting", sa->lighting, "midday|sunset|both (default)");
    s->add_option("--only", sa->only, "only these scene folders (names)");
    s->add_option("--save", sa->save_dir, "also write each recovery's files into this folder");
    add_recover_flags(s, sa->flags);
    s->callback([sa] { run_eval_synthetic(*sa); });

    auto pa = std::make_shared<EvalPhotosArgs>();
    CLI::App* p = app.add_subcommand("eval-photos",
                                     "Recover every photo of a folder in the layout of ../shared/data/photos and "
                                     "score mask.png against the hand labels (IoU per garment group), joints, time");
    p->add_option("dir", pa->dir, "folder with images/, labels/, joints/")->required();
    p->add_option("--out", pa->out, "result JSON to write")->required();
    p->add_option("--mode", pa->mode, "strokes (simulated from the labels, default) | auto");
    p->add_option("--split", pa->split, "all (default) | tune | heldout (docs/vision.md)");
    p->add_option("--stroke-style", pa->stroke_style, "medial (default) | dashes | dots | sloppy");
    p->add_option("--limit", pa->limit, "only the first N photos");
    p->add_option("--names", pa->names, "only these photos (NAME without extension)");
    p->add_option("--save", pa->save_dir, "also write each recovery's files into this folder");
    p->add_option("--rescore", pa->rescore_dir,
                  "do not recover: score the mask.png files an earlier --save run wrote into this folder");
    add_recover_flags(p, pa->flags);
    p->callback([pa] { run_eval_photos(*pa); });
}

}  // namespace drape::app
