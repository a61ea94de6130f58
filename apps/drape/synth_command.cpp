// drape synth --seed N [--garment G|random] [--pose a|b|c|random] [--material NAME|random]
//             [--bending-scale S] [--print none|stripes|checks|dots] [--edge CM] [--max-steps N]
//             [--samples N] [--print-check] --out DIR
// drape synth --suite SUITE.json [--only NAME,...] [--skip-existing] [--print-check] --out DIR
#include "commands.hpp"
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>
#include "synth_scene.hpp"

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <CLI/CLI.hpp>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <iomanip>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>

namespace drape::app {

using namespace io;

namespace {

namespace fs = std::filesystem;

using synth::SynthOptions;
using synth::SynthSummary;

struct SynthArgs {
    SynthOptions options;
    SynthChoices choices;
    long long seed = -1;
    std::string suite;
    std::string only;
    bool skip_existing = false;
    bool print_check = false;
    std::string print_shading = "luminance";
    std::string out;
};

// One scene of a suite file: {"name", "seed", and any of "garment", "pose", "material",
// "bending_scale", "edge_cm", "max_steps", "samples"}; "defaults" holds the same optional keys.
void apply_scene_keys(const nlohmann::json& j, const std::string& where, SynthOptions& o, SynthChoices& c) {
    auto text = [&](const char* key, std::string& field) {
        if (!j.contains(key)) return;
        if (!j[key].is_string()) throw InvalidInput(where + ": field '" + key + "' must be a string, got " + j[key].dump());
        field = j[key].get<std::string>();
    };
    text("garment", c.garment);
    text("pose", c.pose);
    text("material", c.material);
    if (const auto v = optional_number(j, "bending_scale", where)) o.bending_scale = *v;
    if (const auto v = optional_number(j, "edge_cm", where)) o.edge_cm = *v;
    if (const auto v = optional_number(j, "max_steps", where)) o.max_steps = int(*v);
    if (const auto v = optional_number(j, "samples", where)) o.samples_per_pixel = int(*v);
    if (const auto v = optional_number(j, "seed", where)) {
        if (*v < 0 || *v != std::floor(*v)) throw InvalidInput(where + ": field 'seed' must be a whole number >= 0");
        o.seed = std::uint64_t(*v);
    }
}

struct SuiteScene {
    std::string name;
    SynthOptions options;
    SynthChoices choices;
};

std::vector<SuiteScene> read_suite(const std::string& file, const SynthOptions& base, const SynthChoices& base_choices) {
    const nlohmann::json j = read_json_file(file);
    reject_unknown_keys(j, {"format", "version", "description", "defaults", "scenes"}, file);
    if (!j.contains("scenes") || !j["scenes"].is_array() || j["scenes"].empty())
        throw InvalidInput(file + ": field 'scenes' must be a non-empty array");
    SynthOptions defaults = base;
    SynthChoices default_choices = base_choices;
    if (j.contains("defaults")) {
        reject_unknown_keys(j["defaults"], {"garment", "pose", "material", "bending_scale", "edge_cm", "max_steps",
                                            "samples"}, file + " defaults");
        apply_scene_keys(j["defaults"], file + ": defaults", defaults, default_choices);
    }
    std::vector<SuiteScene> scenes;
    for (std::size_t i = 0; i < j["scenes"].size(); ++i) {
        const nlohmann::json& s = j["scenes"][i];
        const std::string where = file + ": scenes[" + std::to_string(i) + "]";
        reject_unknown_keys(s, {"name", "group", "seed", "garment", "pose", "material", "bending_scale", "edge_cm",
                                "max_steps", "samples"}, where);
        if (!s.contains("name") || !s["name"].is_string() || s["name"].get<std::string>().empty())
            throw InvalidInput(where + ": field 'name' must be a non-empty string");
        if (!s.contains("seed")) throw InvalidInput(where + ": field 'seed' is missing");
        SuiteScene scene{s["name"].get<std::string>(), defaults, default_choices};
        apply_scene_keys(s, where, scene.options, scene.choices);
        std::string why;
        if (!scene.options.is_valid(&why)) throw InvalidInput(where + ": " + why);
        scenes.push_back(scene);
    }
    return scenes;
}

// A grid of the suite's images: per scene the mid-day and sunset renders side by side
// with the scene name underneath.
cv::Mat contact_sheet(const std::vector<std::pair<std::string, fs::path>>& scenes, int cell_height) {
    const int columns = 4, image_h = cell_height, image_w = cell_height * 2 / 3, caption = 22;
    const int cell_w = 2 * image_w + 8, cell_h = image_h + caption;
    const int rows = (int(scenes.size()) + columns - 1) / columns;
    cv::Mat sheet(std::max(1, rows) * cell_h, columns * cell_w, CV_8UC3, cv::Scalar(255, 255, 255));
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const int x0 = int(i % columns) * cell_w, y0 = int(i / columns) * cell_h;
        int k = 0;
        for (const char* file : {"image_midday.png", "image_sunset.png"}) {
            const cv::Mat im = cv::imread((scenes[i].second / file).string(), cv::IMREAD_COLOR);
            if (!im.empty()) {
                cv::Mat small;
                cv::resize(im, small, cv::Size(image_w, image_h), 0, 0, cv::INTER_AREA);
                small.copyTo(sheet(cv::Rect(x0 + k * image_w, y0, image_w, image_h)));
            }
            ++k;
        }
        cv::putText(sheet, scenes[i].first, cv::Point(x0 + 4, y0 + image_h + 16), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                    cv::Scalar(30, 30, 30), 1, cv::LINE_AA);
    }
    return sheet;
}

// --print-shading: the fold detector's options for the print check.
vision::WrinkleOptions print_check_detector(const std::string& shading) {
    vision::WrinkleOptions o;
    if (shading == "luminance") return o;
    o.suppress_prints = true;
    if (shading == "gradient-fill") o.print_method = vision::WrinkleOptions::PrintMethod::gradient_fill;
    else if (shading == "albedo-classes") o.print_method = vision::WrinkleOptions::PrintMethod::albedo_classes;
    else throw InvalidInput("drape synth --print-shading '" + shading + "': must be luminance, gradient-fill or albedo-classes");
    return o;
}

// One line per garment of a print check: P plain, P per print and the ratios to plain.
void print_check_lines(const std::string& name, const nlohmann::json& check) {
    for (const auto& g : check["garments"]) {
        std::cout << "print check: " << name << " " << g["type"].get<std::string>() << " (sampled "
                  << g["sampled_print"].get<std::string>() << ", bending x" << std::setprecision(3)
                  << g["bending_scale"].get<double>() << "): P";
        for (const char* k : {"none", "stripes", "checks", "dots"})
            std::cout << " " << k << " " << std::fixed << std::setprecision(2) << g["prints"][k]["P_per_m2"].get<double>()
                      << std::defaultfloat;
        std::cout << "; ratio";
        for (const char* k : {"stripes", "checks", "dots"})
            std::cout << " " << std::fixed << std::setprecision(3) << g["ratio_to_plain"][k].get<double>()
                      << std::defaultfloat;
        std::cout << "\n";
    }
}

void run_single(const SynthArgs& args) {
    if (args.seed < 0) throw InvalidInput("drape synth: give --seed N (N >= 0) or --suite FILE");
    SynthOptions options = with_choices(args.options, args.choices);
    options.seed = std::uint64_t(args.seed);
    if (args.print_check) {
        SynthSummary s;
        const nlohmann::json check = make_and_write_print_check(options, args.out, args.skip_existing, &s,
                                                                  print_check_detector(args.print_shading));
        print_check_lines("seed " + std::to_string(options.seed), check);
        return;
    }
    const SynthSummary s = make_and_write_synth_scene(options, args.out);
    std::cout << "drape synth: seed " << options.seed << ", " << s.brief_report() << "\n";
    if (!s.usable())
        throw std::runtime_error("drape synth: a drape is not usable (files written; see summary.json)");
}

void run_suite(const SynthArgs& args) {
    std::vector<SuiteScene> scenes = read_suite(args.suite, args.options, args.choices);
    if (!args.only.empty()) {
        std::vector<SuiteScene> kept;
        for (const SuiteScene& s : scenes)
            if (("," + args.only + ",").find("," + s.name + ",") != std::string::npos) kept.push_back(s);
        if (kept.empty()) throw InvalidInput("drape synth: --only '" + args.only + "' names no scene of " + args.suite);
        scenes = kept;
    }
    const fs::path out(args.out);
    // A resumed run keeps the entries (status, seconds) of the scenes it skips.
    nlohmann::json previous = nlohmann::json::array();
    if (args.skip_existing && fs::exists(out / "suite_report.json")) previous = read_json_file(out / "suite_report.json");
    nlohmann::json report = nlohmann::json::array();
    std::vector<std::pair<std::string, fs::path>> done;
    int failed = 0;
    if (args.print_check) {
        // The plain / printed comparison of every scene: a drape each (unless --skip-existing
        // finds its renders), four mid-day renders, P on each.
        nlohmann::json checks = nlohmann::json::object();
        for (const SuiteScene& s : scenes) {
            try {
                checks[s.name] = make_and_write_print_check(with_choices(s.options, s.choices), out / s.name,
                                                            args.skip_existing, nullptr,
                                                            print_check_detector(args.print_shading));
                print_check_lines(s.name, checks[s.name]);
            } catch (const std::exception& e) {
                ++failed;
                checks[s.name] = {{"failed", e.what()}};
                std::cout << "print check: " << s.name << ": failed, " << e.what() << std::endl;
            }
        }
        write_json_file(out / "print_check.json", checks);
        if (failed > 0) throw std::runtime_error("drape synth: " + std::to_string(failed) + " scene(s) failed");
        return;
    }
    for (const SuiteScene& s : scenes) {
        const fs::path dir = out / s.name;
        nlohmann::json r = {{"name", s.name}, {"seed", s.options.seed}, {"garment", s.choices.garment},
                            {"pose", s.choices.pose}, {"material", s.choices.material}};
        if (args.skip_existing && fs::exists(dir / "truth.json")) {
            r["status"] = "skipped (exists)";
            for (const auto& p : previous)
                if (p.is_object() && p.value("name", "") == s.name) r = p;
        } else {
            const auto t0 = std::chrono::steady_clock::now();
            try {
                const SynthSummary summary = make_and_write_synth_scene(with_choices(s.options, s.choices), dir);
                r["status"] = summary.usable() ? "usable" : "not usable";
                r["report"] = summary.brief_report();
                r["seconds"] = summary.seconds;
            } catch (const std::exception& e) {
                ++failed;
                r["status"] = "failed";
                r["report"] = e.what();
                r["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            }
            std::cout << "drape synth: " << s.name << ": " << r["status"].get<std::string>() << ", "
                      << r["report"].get<std::string>() << std::endl;
        }
        if (fs::exists(dir / "image_midday.png")) done.emplace_back(s.name, dir);
        report.push_back(r);
    }
    write_json_file(out / "suite_report.json", report);
    const cv::Mat sheet = contact_sheet(done, 240);
    write_png(out / "contact_sheet.png", sheet);
    std::vector<unsigned char> jpeg;
    cv::imencode(".jpg", sheet, jpeg, {cv::IMWRITE_JPEG_QUALITY, 80});
    write_text_atomically(out / "contact_sheet.jpg", std::string(jpeg.begin(), jpeg.end()));
    if (failed > 0) throw std::runtime_error("drape synth: " + std::to_string(failed) + " scene(s) failed (suite_report.json)");
}

}  // namespace

void add_synth_command(CLI::App& app) {
    auto args = std::make_shared<SynthArgs>();
    CLI::App* cmd = app.add_subcommand(
        "synth", "Synthetic ground-truth scene: a sampled body in a standing pose, dressed, draped and rendered "
                 "under mid-day and sunset light (image_*.png, labels.png, strokes.png, joints.json, truth.json, "
                 "summary.json); or a whole suite with a contact sheet");
    cmd->add_option("--seed", args->seed, "scene seed (every random choice derives from it)");
    cmd->add_option("--garment", args->choices.garment,
                    "skirt, pants, tshirt, dress, tshirt+pants, tshirt+skirt or random (default)");
    cmd->add_option("--pose", args->choices.pose, "a (A-pose), b (arms down), c (walking) or random (default)");
    cmd->add_option("--material", args->choices.material,
                    "a built-in measured fabric (e.g. gray-interlock) or random (default: a measured fabric "
                    "with bending scale log-uniform in [1, 100])");
    cmd->add_option("--bending-scale", args->options.bending_scale, "fix the bending scale s_b (> 0)");
    cmd->add_option("--print", args->choices.print,
                    "none (plain), stripes, checks, dots, or sampled (default: drawn with the look); the same seed "
                    "gives the same drape and labels whatever the print");
    cmd->add_flag("--print-check", args->print_check,
                  "render each drape plain and with each print (mid-day) and compare P: print_*.png, "
                  "print_check.json (an evaluation; with --skip-existing re-measures existing renders)");
    cmd->add_option("--print-shading", args->print_shading,
                    "with --print-check, what the fold detector runs on: luminance (default, as truth.json), "
                    "gradient-fill or albedo-classes (WrinkleOptions::suppress_prints and print_method)");
    cmd->add_option("--edge", args->options.edge_cm, "mesh target edge length, cm (default 4)");
    cmd->add_option("--max-steps", args->options.max_steps, "dynamic steps per drape at most (default 600)");
    cmd->add_option("--width", args->options.width_px, "image width, px (default 600)");
    cmd->add_option("--height", args->options.height_px, "image height, px (>= 600, default 900)");
    cmd->add_option("--samples", args->options.samples_per_pixel, "render samples per pixel (default 16)");
    cmd->add_option("--threads", args->options.threads, "render threads (0 = all; output does not depend on it)");
    cmd->add_option("--suite", args->suite, "suite JSON (data/synth/suite.json): run every scene into OUT/NAME");
    cmd->add_option("--only", args->only, "with --suite: comma-separated scene names to run");
    cmd->add_flag("--skip-existing", args->skip_existing, "with --suite: keep scenes whose truth.json exists");
    cmd->add_option("--out", args->out, "output folder")->required();
    cmd->callback([args] {
        std::string why;
        if (!args->options.is_valid(&why)) throw InvalidInput("drape synth: " + why);
        print_check_detector(args->print_shading);  // a bad --print-shading is refused before any drape
        if (args->suite.empty()) run_single(*args);
        else run_suite(*args);
    });
}

}  // namespace drape::app
