// drape_fit_curvature_calibration: the calibrated mapping from the wrinkle density P to the
// target mean curvature K and to the bending scale s_b (issue 21, material C;
// docs/material-estimation.md).
//
//   drape_fit_curvature_calibration fit [--fabric NAME] [--cache FILE] DIR... > libgarment/src/curvature_calibration_data.cpp
//   drape_fit_curvature_calibration evaluate [--cache FILE] DIR...
//
// --cache FILE keeps the measurements per scene folder (JSON), so that a scene is measured
// once (P on two renders: seconds each) across runs.
//
// Both read the scene folders `drape synth` writes (any folder under DIR holding summary.json,
// written last, truth.json,
// summary.json, labels.png, joints.json and the two images). Per garment they take the type,
// fabric, bending scale, K (truth.json mean_curvature_per_m) and P at mid-day (truth.json),
// and measure P on image_sunset.png with the same detector, mask and joints as drape synth
// does at mid-day (libsynth measure_wrinkles: vision::detect_wrinkles, label mask, person
// height); mid-day P is measured again and must equal truth.json's. Garments whose drape is
// not usable are left out.
//
// `fit` takes single-garment scenes only, chooses the model forms and the lighting by
// leave-one-garment-out error on `--fabric` (default gray-interlock) among the forms whose
// slopes have the physical sign (more folds: more curvature, softer), prints the comparison
// on stderr and the generated source on stdout. It does not use the embedded calibration.
// `evaluate` prints, per garment and lighting, the embedded calibration's K and s_b and the
// paper's interpolation against the truth, then the means (never fit on these scenes).
#include "photo_folder.hpp"

#include <drape/core/errors.hpp>
#include <drape/garment/curvature_calibration.hpp>
#include <drape/vision/wrinkle_density.hpp>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using drape::garment::GarmentType;
using drape::garment::WrinkleCalibration;
using drape::garment::WrinkleCalibrationSample;
using drape::garment::WrinkleLighting;
using drape::garment::WrinkleModelForm;

namespace {

struct SceneGarment {
    WrinkleCalibrationSample sample;
    int garments_in_scene = 1;
    bool usable = false;
};

nlohmann::json read_json(const fs::path& file) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file.string());
    return nlohmann::json::parse(in);
}

cv::Mat read_image(const fs::path& file, int flags) {
    cv::Mat m = cv::imread(file.string(), flags);
    if (m.empty()) throw std::runtime_error("cannot read " + file.string());
    return m;
}

// P of one garment on one render, as libsynth's measure_wrinkles (0 when not visible or
// refused by the detector).
double measure_p(const cv::Mat& colour, const cv::Mat& labels, int label, const drape::vision::Joints& joints,
                 double height_m) {
    cv::Mat mask;
    cv::compare(labels, label, mask, cv::CMP_EQ);
    if (cv::countNonZero(mask) == 0) return 0;
    drape::vision::WrinkleOptions wo;
    wo.person_height_m = height_m;
    try {
        return drape::vision::detect_wrinkles(colour, mask, cv::Mat(), joints, wo, nullptr).density_per_m2;
    } catch (const drape::InvalidInput&) {
        return 0;
    }
}

std::vector<fs::path> scene_folders(const std::vector<std::string>& roots) {
    std::vector<fs::path> out;
    for (const std::string& r : roots) {
        if (!fs::is_directory(r)) throw std::runtime_error("not a folder: " + r);
        if (fs::exists(fs::path(r) / "summary.json")) out.emplace_back(r);
        for (const auto& e : fs::recursive_directory_iterator(r))
            if (e.is_directory() && fs::exists(e.path() / "summary.json")) out.push_back(e.path());
    }
    std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
        return a.filename().string() < b.filename().string();
    });
    return out;
}

std::vector<SceneGarment> read_scene(const fs::path& dir) {
    const nlohmann::json truth = read_json(dir / "truth.json");
    const nlohmann::json summary = read_json(dir / "summary.json");
    const cv::Mat labels = read_image(dir / "labels.png", cv::IMREAD_UNCHANGED);
    const cv::Mat midday = read_image(dir / "image_midday.png", cv::IMREAD_COLOR);
    const cv::Mat sunset = read_image(dir / "image_sunset.png", cv::IMREAD_COLOR);
    const drape::vision::Joints joints = drape::tools::read_joints(dir / "joints.json");
    const double height_m = truth["body"]["params"]["height_m"].get<double>();
    std::vector<SceneGarment> out;
    const auto& garments = truth["garments"];
    for (size_t i = 0; i < garments.size(); ++i) {
        const auto& g = garments[i];
        const auto& report = summary["drapes"][i];
        SceneGarment s;
        s.garments_in_scene = int(garments.size());
        s.usable = report["usable"].get<bool>();
        s.sample.scene = dir.filename().string();
        s.sample.type = drape::garment::garment_type_from_name(g["type"].get<std::string>());
        s.sample.fabric = g["material"]["base_fabric"].get<std::string>();
        s.sample.bending_scale = g["material"]["bending_scale"].get<double>();
        s.sample.k_per_m = g["mean_curvature_per_m"].get<double>();
        s.sample.p_midday_per_m2 = g["wrinkle_density_per_m2"].get<double>();
        const int label = report["label"].get<int>();
        const double p_mid = measure_p(midday, labels, label, joints, height_m);
        if (std::abs(p_mid - s.sample.p_midday_per_m2) > 1e-9 * std::max(1.0, p_mid))
            throw std::runtime_error(dir.string() + ": P measured again on image_midday.png (" + std::to_string(p_mid) +
                                     ") differs from truth.json's (" +
                                     std::to_string(s.sample.p_midday_per_m2) + ")");
        s.sample.p_sunset_per_m2 = measure_p(sunset, labels, label, joints, height_m);
        out.push_back(s);
    }
    return out;
}

// The measured garments of the scenes under `roots`. With a cache file, the garments of a
// scene folder already in it (same path, same truth.json size and time) are not measured
// again, and the cache is rewritten with every folder read.
std::vector<SceneGarment> read_scenes(const std::vector<std::string>& roots, const std::string& cache_file) {
    nlohmann::json cache = nlohmann::json::object();
    if (!cache_file.empty() && fs::exists(cache_file)) cache = read_json(cache_file);
    std::vector<SceneGarment> out;
    for (const fs::path& dir : scene_folders(roots)) {
        const std::string key = fs::absolute(dir).lexically_normal().string();
        const std::string stamp = std::to_string(fs::file_size(dir / "truth.json")) + ":" +
                                  std::to_string(fs::last_write_time(dir / "truth.json").time_since_epoch().count());
        if (cache.contains(key) && cache[key]["stamp"] == stamp) {
            for (const auto& j : cache[key]["garments"]) {
                SceneGarment g;
                g.garments_in_scene = j["garments_in_scene"].get<int>();
                g.usable = j["usable"].get<bool>();
                g.sample.scene = j["scene"].get<std::string>();
                g.sample.type = drape::garment::garment_type_from_name(j["type"].get<std::string>());
                g.sample.fabric = j["fabric"].get<std::string>();
                g.sample.bending_scale = j["bending_scale"].get<double>();
                g.sample.p_midday_per_m2 = j["p_midday_per_m2"].get<double>();
                g.sample.p_sunset_per_m2 = j["p_sunset_per_m2"].get<double>();
                g.sample.k_per_m = j["k_per_m"].get<double>();
                out.push_back(g);
            }
            continue;
        }
        nlohmann::json entry = {{"stamp", stamp}, {"garments", nlohmann::json::array()}};
        for (const SceneGarment& g : read_scene(dir)) {
            out.push_back(g);
            entry["garments"].push_back({{"garments_in_scene", g.garments_in_scene},
                                         {"usable", g.usable},
                                         {"scene", g.sample.scene},
                                         {"type", drape::garment::garment_type_name(g.sample.type)},
                                         {"fabric", g.sample.fabric},
                                         {"bending_scale", g.sample.bending_scale},
                                         {"p_midday_per_m2", g.sample.p_midday_per_m2},
                                         {"p_sunset_per_m2", g.sample.p_sunset_per_m2},
                                         {"k_per_m", g.sample.k_per_m}});
        }
        cache[key] = entry;
        std::cerr << "measured " << dir.filename().string() << "\n";
        if (!cache_file.empty()) std::ofstream(cache_file) << cache.dump(1) << "\n";
    }
    return out;
}

std::string num(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

std::string fixed(double v, int digits) {
    std::ostringstream os;
    os.setf(std::ios::fixed);
    os.precision(digits);
    os << v;
    return os.str();
}

std::string form_enum(WrinkleModelForm f) { return "WrinkleModelForm::" + drape::garment::wrinkle_model_form_name(f); }

std::string model_source(const std::string& name, const drape::garment::WrinkleModel& m) {
    std::ostringstream os;
    os << "    c." << name << ".form = " << form_enum(m.form) << ";\n";
    os << "    c." << name << ".offset = {{" << num(m.offset[0]) << ", " << num(m.offset[1]) << ", " << num(m.offset[2])
       << ", " << num(m.offset[3]) << "}};\n";
    os << "    c." << name << ".slope = {{" << num(m.slope[0]) << ", " << num(m.slope[1]) << ", " << num(m.slope[2])
       << ", " << num(m.slope[3]) << "}};\n";
    os << "    c." << name << ".censored_offset = " << num(m.censored_offset) << ";\n";
    os << "    c." << name << ".residual_low = " << num(m.residual_low) << ";\n";
    os << "    c." << name << ".residual_high = " << num(m.residual_high) << ";\n";
    os << "    c." << name << ".censored_residual_low = " << num(m.censored_residual_low) << ";\n";
    os << "    c." << name << ".censored_residual_high = " << num(m.censored_residual_high) << ";\n";
    return os.str();
}

const char* lighting_name(WrinkleLighting l) { return l == WrinkleLighting::midday ? "midday" : "both"; }

int fit(const std::string& fabric, const std::vector<std::string>& roots, const std::string& cache) {
    std::vector<WrinkleCalibrationSample> samples;
    int skipped_unusable = 0, skipped_outfit = 0;
    for (const SceneGarment& g : read_scenes(roots, cache)) {
        if (g.garments_in_scene != 1) {
            ++skipped_outfit;
            continue;
        }
        if (!g.usable) {
            ++skipped_unusable;
            continue;
        }
        samples.push_back(g.sample);
    }
    int of_fabric = 0;
    for (const auto& s : samples) of_fabric += s.fabric == fabric ? 1 : 0;
    std::cerr << samples.size() << " garments (" << of_fabric << " of " << fabric << "), left out " << skipped_unusable
              << " not usable, " << skipped_outfit << " of outfits\n";

    // Every form and lighting, scored by leave-one-garment-out on both lightings. A form is
    // admissible when its fit on all the data has the physical sign for every type: more
    // folds, more curvature (K slopes >= 0) and a softer fabric (s_b slopes <= 0). A slope of
    // the other sign fits the detector's noise (prints, light), and the optimiser needs a
    // monotone target. The constant per type is always admissible.
    const WrinkleModelForm forms[] = {WrinkleModelForm::type_constant, WrinkleModelForm::shared_line,
                                      WrinkleModelForm::type_offset_line, WrinkleModelForm::type_line};
    const WrinkleLighting lightings[] = {WrinkleLighting::midday, WrinkleLighting::both};
    const auto sign_ok = [](const drape::garment::WrinkleModel& m, double sign) {
        for (const double b : m.slope)
            if (sign * b < 0) return false;
        return true;
    };
    std::ostringstream table;
    table << "| fitted on P at | form | K accuracy | mean abs log10(K^/K) | K slopes >= 0 | mean abs dlog10 s_b | "
             "s_b slopes <= 0 |\n| --- | --- | --- | --- | --- | --- | --- |\n";
    double best_k = -1, best_b = 1e9;
    WrinkleModelForm k_form = WrinkleModelForm::type_constant, b_form = WrinkleModelForm::type_constant;
    WrinkleLighting lighting = WrinkleLighting::both;
    std::map<int, std::pair<bool, double>> b_scores;  // per (lighting, form): (admissible, s_b error)
    for (const WrinkleLighting l : lightings)
        for (const WrinkleModelForm f : forms) {
            const WrinkleCalibration c = drape::garment::fit_wrinkle_calibration(samples, fabric, f, f, l);
            const bool k_ok = sign_ok(c.curvature, 1), b_ok = sign_ok(c.bending, -1);
            table << "| " << lighting_name(l) << " | " << drape::garment::wrinkle_model_form_name(f) << " | "
                  << fixed(100 * c.errors.curvature_accuracy, 1) << " % | " << fixed(c.errors.curvature_abs_log10, 3)
                  << " | " << (k_ok ? "yes" : "no") << " | " << fixed(c.errors.bending_abs_log10, 3) << " | "
                  << (b_ok ? "yes" : "no") << " |\n";
            b_scores[int(l) * 10 + int(f)] = {b_ok, c.errors.bending_abs_log10};
            if (k_ok && c.errors.curvature_accuracy > best_k) {
                best_k = c.errors.curvature_accuracy;
                k_form = f;
                lighting = l;
            }
        }
    for (const WrinkleModelForm f : forms) {
        const auto [ok, e] = b_scores[int(lighting) * 10 + int(f)];
        if (ok && e < best_b) best_b = e, b_form = f;
    }
    const WrinkleCalibration c = drape::garment::fit_wrinkle_calibration(samples, fabric, k_form, b_form, lighting);
    // What P adds to s_b: the error of always answering the middle of the calibrated range.
    double centre_error = 0;
    int centre_n = 0;
    for (const auto& o : drape::garment::wrinkle_observations(samples, fabric, true, WrinkleLighting::both))
        centre_error += std::abs(o.y - 0.5 * (c.log10_bending_min + c.log10_bending_max)), ++centre_n;
    table << "\nBaseline without P: log10 s_b = the middle of the range, mean abs dlog10 s_b "
          << fixed(centre_error / std::max(1, centre_n), 3) << ".\n";
    std::cerr << table.str();
    std::cerr << "chosen: K " << drape::garment::wrinkle_model_form_name(k_form) << ", s_b "
              << drape::garment::wrinkle_model_form_name(b_form) << ", fitted on P at " << lighting_name(lighting)
              << "; leave-one-garment-out over both lightings: K accuracy " << fixed(100 * c.errors.curvature_accuracy, 1)
              << " % (paper's interpolation " << fixed(100 * c.errors.paper_curvature_accuracy, 1)
              << " %), mean abs log10(K^/K) " << fixed(c.errors.curvature_abs_log10, 3) << " (paper "
              << fixed(c.errors.paper_curvature_abs_log10, 3) << "), mean abs dlog10 s_b "
              << fixed(c.errors.bending_abs_log10, 3) << "\n";

    std::ostringstream out;
    out << "// Generated by drape_fit_curvature_calibration (tools/fit_curvature_calibration.cpp); do not edit.\n"
        << "// Regenerate (docs/material-estimation.md):\n"
        << "//   drape_fit_curvature_calibration fit --fabric " << fabric << " DIR > libgarment/src/curvature_calibration_data.cpp\n"
        << "// with DIR the scenes of data/synth/curvature_calibration.json made by `drape synth --suite`.\n"
        << "// " << c.errors.garments << " garments of " << fabric << " fitted on, " << samples.size()
        << " garments in the table.\n"
        << "// Leave-one-garment-out errors of every form (predicting P at mid-day and at sunset):\n";
    std::istringstream lines(table.str());
    for (std::string line; std::getline(lines, line);) out << "//   " << line << "\n";
    out << "// Chosen: K " << drape::garment::wrinkle_model_form_name(k_form) << ", s_b "
        << drape::garment::wrinkle_model_form_name(b_form) << ", fitted on P at " << lighting_name(lighting) << ".\n"
        << "#include <drape/garment/curvature_calibration.hpp>\n\n"
        << "namespace drape::garment {\n\nnamespace {\n\n"
        << "WrinkleCalibration make_calibration() {\n"
        << "    WrinkleCalibration c;\n"
        << "    c.fabric = \"" << fabric << "\";\n"
        << "    c.log10_bending_min = " << num(c.log10_bending_min) << ";\n"
        << "    c.log10_bending_max = " << num(c.log10_bending_max) << ";\n"
        << "    c.lighting = WrinkleLighting::" << lighting_name(lighting) << ";\n"
        << model_source("curvature", c.curvature) << model_source("bending", c.bending)
        << "    c.errors.garments = " << c.errors.garments << ";\n"
        << "    c.errors.curvature_accuracy = " << num(c.errors.curvature_accuracy) << ";\n"
        << "    c.errors.curvature_abs_log10 = " << num(c.errors.curvature_abs_log10) << ";\n"
        << "    c.errors.bending_abs_log10 = " << num(c.errors.bending_abs_log10) << ";\n"
        << "    c.errors.paper_curvature_accuracy = " << num(c.errors.paper_curvature_accuracy) << ";\n"
        << "    c.errors.paper_curvature_abs_log10 = " << num(c.errors.paper_curvature_abs_log10) << ";\n"
        << "    // scene, type, fabric, bending scale, P mid-day (1/m^2), P sunset (1/m^2), K (1/m)\n"
        << "    c.samples = {\n";
    for (const auto& s : samples)
        out << "        {\"" << s.scene << "\", GarmentType::" << drape::garment::garment_type_name(s.type) << ", \""
            << s.fabric << "\", " << num(s.bending_scale) << ", " << num(s.p_midday_per_m2) << ", "
            << num(s.p_sunset_per_m2) << ", " << num(s.k_per_m) << "},\n";
    out << "    };\n    return c;\n}\n\n}  // namespace\n\n"
        << "const WrinkleCalibration& embedded_wrinkle_calibration() {\n"
        << "    static const WrinkleCalibration c = make_calibration();\n"
        << "    return c;\n}\n\n}  // namespace drape::garment\n";
    std::cout << out.str();
    return 0;
}

// The paper's end points read as a geometric interpolation (log10 K linear in P), for
// comparison with the literal linear one.
double paper_log_linear(double p) {
    const double q = std::clamp(p, 1.0, 50.0);
    return std::pow(10.0, -4 + 9 * (q - 1) / 49);
}

struct Means {
    int n = 0;
    double k_acc = 0, k_log = 0, b_log = 0, paper_acc = 0, paper_log = 0, paper_loglin_acc = 0, paper_loglin_log = 0;
    void add(double k, const drape::garment::CurvatureTarget& t, double log10_sb, double k_paper, double k_loglin) {
        ++n;
        k_acc += std::max(0.0, 1 - std::abs(t.k_per_m - k) / k);
        k_log += std::abs(std::log10(t.k_per_m / k));
        b_log += std::abs(t.log10_bending_scale - log10_sb);
        paper_acc += std::max(0.0, 1 - std::abs(k_paper - k) / k);
        paper_log += std::abs(std::log10(k_paper / k));
        paper_loglin_acc += std::max(0.0, 1 - std::abs(k_loglin - k) / k);
        paper_loglin_log += std::abs(std::log10(k_loglin / k));
    }
    std::string row(const std::string& what) const {
        const double d = std::max(1, n);
        return "| " + what + " | " + std::to_string(n) + " | " + fixed(100 * k_acc / d, 1) + " % | " +
               fixed(k_log / d, 3) + " | " + fixed(b_log / d, 3) + " | " + fixed(100 * paper_acc / d, 1) + " % | " +
               fixed(paper_log / d, 2) + " | " + fixed(100 * paper_loglin_acc / d, 1) + " % | " +
               fixed(paper_loglin_log / d, 2) + " |";
    }
};

int evaluate(const std::vector<std::string>& roots, const std::string& cache) {
    const WrinkleCalibration& cal = drape::garment::embedded_wrinkle_calibration();
    std::cout << "calibration: " << cal.fabric << ", " << cal.errors.garments << " garments, K "
              << drape::garment::wrinkle_model_form_name(cal.curvature.form) << ", s_b "
              << drape::garment::wrinkle_model_form_name(cal.bending.form) << "\n\n";
    std::cout << "| scene | garment | fabric | s_b | K (1/m) | light | P (1/m^2) | K^ [interval] | s_b^ [interval] | "
                 "paper K |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    std::map<std::string, Means> means;
    for (const SceneGarment& g : read_scenes(roots, cache)) {
        if (!g.usable) {
            std::cout << "| " << g.sample.scene << " | " << drape::garment::garment_type_name(g.sample.type)
                      << " | drape not usable: left out | | | | | | | |\n";
            continue;
        }
        const auto& s = g.sample;
        const std::string space = s.fabric == cal.fabric ? cal.fabric : "other fabrics";
        for (int light = 0; light < 2; ++light) {
            const double p = light == 0 ? s.p_midday_per_m2 : s.p_sunset_per_m2;
            const auto t = drape::garment::curvature_from_wrinkle_density(s.type, p);
            const double kp = drape::garment::paper_curvature_from_wrinkle_density(p);
            std::cout << "| " << s.scene << " | " << drape::garment::garment_type_name(s.type) << " | " << s.fabric
                      << " | " << fixed(s.bending_scale, 1) << " | " << fixed(s.k_per_m, 3) << " | "
                      << (light == 0 ? "midday" : "sunset") << " | " << fixed(p, 2) << (t.censored ? " (none)" : "")
                      << " | " << fixed(t.k_per_m, 3) << " [" << fixed(t.k_low_per_m, 3) << ", "
                      << fixed(t.k_high_per_m, 3) << "] | " << fixed(std::pow(10, t.log10_bending_scale), 1) << " ["
                      << fixed(std::pow(10, t.log10_bending_low), 1) << ", " << fixed(std::pow(10, t.log10_bending_high), 1)
                      << "] | " << fixed(kp, 1) << " |\n";
            const double lsb = std::log10(s.bending_scale);
            const std::string lname = light == 0 ? "midday" : "sunset";
            means[space + ", " + lname].add(s.k_per_m, t, lsb, kp, paper_log_linear(p));
            means[space + ", both lightings"].add(s.k_per_m, t, lsb, kp, paper_log_linear(p));
        }
    }
    std::cout << "\n| fabric space, lighting | garment-lightings | calibrated K accuracy | mean abs log10(K^/K) | "
                 "mean abs dlog10 s_b | paper K accuracy | paper mean abs log10 | paper (log-linear reading) accuracy "
                 "| its mean abs log10 |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    for (const auto& [name, m] : means) std::cout << m.row(name) << "\n";
    return 0;
}

int usage() {
    std::cerr << "usage: drape_fit_curvature_calibration fit [--fabric NAME] [--cache FILE] DIR... > curvature_calibration_data.cpp\n"
                 "       drape_fit_curvature_calibration evaluate [--cache FILE] DIR...\n";
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) return usage();
    const std::string mode = argv[1];
    std::string fabric = "gray-interlock";
    std::string cache;
    std::vector<std::string> roots;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--fabric" && i + 1 < argc)
            fabric = argv[++i];
        else if (a == "--cache" && i + 1 < argc)
            cache = argv[++i];
        else
            roots.push_back(a);
    }
    if (roots.empty()) return usage();
    try {
        if (mode == "fit") return fit(fabric, roots, cache);
        if (mode == "evaluate") return evaluate(roots, cache);
        return usage();
    } catch (const std::exception& e) {
        std::cerr << "drape_fit_curvature_calibration: " << e.what() << "\n";
        return 1;
    }
}
