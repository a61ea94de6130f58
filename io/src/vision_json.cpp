#include <drape/io/vision_json.hpp>

#include <drape/io/joints_json.hpp>

#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>

#include "staging.hpp"

#include <drape/core/errors.hpp>
#include <drape/vision/wrinkle_density.hpp>

#include <cmath>

namespace drape::io {

vision::Joints read_vision_joints(const std::filesystem::path& path, int width, int height,
                                  double* shift_out) {
    const JointsFile file = read_joints_file(path, width, height);
    vision::Joints out;
    out.marks = file.marks;
    for (int i = 0; i < vision::kJointCount; ++i)
        out.px[static_cast<std::size_t>(i)] = file.joints_px.row(i).transpose();
    try {
        out.validate(width, height);
    } catch (const InvalidInput& e) {
        throw InvalidInput(path.string() + ": " + e.what());
    }
    if (shift_out) *shift_out = origin_offset(file.origin);
    return out;
}

namespace {

nlohmann::json polygon(const Eigen::Matrix<double, Eigen::Dynamic, 2>& m) {
    nlohmann::json a = nlohmann::json::array();
    for (Eigen::Index i = 0; i < m.rows(); ++i) a.push_back({m(i, 0), m(i, 1)});
    return a;
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

nlohmann::json cues_json(const vision::GarmentShapeCues& c) {
    return {{"sleeve_fraction", c.sleeve_fraction},
            {"hem_fraction", c.hem_fraction},
            {"top_fraction", c.top_fraction},
            {"between_legs_fraction", c.between_legs_fraction},
            {"leg_fraction", c.leg_fraction},
            {"knee_width_ratio", c.knee_width_ratio}};
}

nlohmann::json garments_json(const std::vector<vision::GarmentResult>& garments,
                             const vision::SegmentationSummary& summary,
                             const std::string& image_file, int width, int height,
                             const std::string& mode, double person_height_m) {
    static const char* terminations[] = {"ok", "no_garment_found", "failed"};
    nlohmann::json j;
    j["format"] = "drape.garments";
    j["version"] = 1;
    j["image"] = {{"file", image_file}, {"width", width}, {"height", height}};
    j["frame"] = "image pixels, origin at the top-left corner, pixel centres at +0.5";
    j["segmentation"] = {{"mode", mode},
                         {"termination", terminations[static_cast<int>(summary.termination)]},
                         {"message", summary.message},
                         {"seconds", summary.seconds},
                         {"garments_found", summary.garments_found}};
    j["person_height_m"] = person_height_m;
    nlohmann::json list = nlohmann::json::array();
    for (const auto& g : garments) {
        nlohmann::json e;
        e["type"] = std::string(vision::to_string(g.type));
        e["label_id"] = g.label_id;
        e["class"] = g.class_name;
        e["area_px"] = g.area_px;
        e["occlusion_fraction"] = g.occlusion_fraction;
        nlohmann::json features = nlohmann::json::object();
        features["body_height_px"] = g.features.body_height_px;
        for (const auto& [name, v] : g.features.list())
            features[name] = {{"px", v.first}, {"normalised", v.second}};
        e["features"] = features;
        e["cues"] = cues_json(g.cues);
        // null when P was not measured (garment too small, see the report); 0 when measured
        // and no fold reached the detection limit.
        e["wrinkle_density_per_m2"] =
            g.wrinkles.usable() ? number_or_null(g.wrinkles.density_per_m2) : nlohmann::json();
        e["wrinkles"] = {{"usable", g.wrinkles.usable()},
                         {"folds_detected", g.wrinkles.folds_detected},
                         {"fold_count", g.wrinkles.fold_count},
                         {"folds", g.wrinkles.folds},
                         {"edges", g.wrinkles.edges_merged},
                         {"garment_area_m2", g.wrinkles.garment_area_m2},
                         {"report", g.wrinkles.brief_report()}};
        nlohmann::json pieces = nlohmann::json::array();
        for (const auto& p : g.silhouette) {
            nlohmann::json holes = nlohmann::json::array();
            for (const auto& h : p.holes) holes.push_back(polygon(h));
            pieces.push_back({{"outer", polygon(p.outer)}, {"holes", holes}});
        }
        e["silhouette"] = pieces;
        list.push_back(e);
    }
    j["garments"] = list;
    return j;
}

void make_output_dir(const std::filesystem::path& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    std::error_code ec2;
    if (!std::filesystem::is_directory(dir, ec2))
        throw IoError("cannot create the output folder '" + dir.string() + "'" +
                      (ec ? ": " + ec.message() : std::string()));
}

vision::StrokePalette read_stroke_palette(const std::filesystem::path& file, const vision::LabelTable& table) {
    if (file.empty()) return vision::StrokePalette::fashionista_default();
    const nlohmann::json j = read_json_file(file);
    const std::string f = file.string();
    if (!j.is_object()) throw InvalidInput(f + ": a stroke palette must be a JSON object");
    reject_unknown_keys(j, {"tolerance", "colours"}, f);
    vision::StrokePalette p;
    if (const auto t = optional_number(j, "tolerance", f)) {
        if (*t != std::floor(*t) || *t < 0 || *t > 63)
            throw InvalidInput(f + ": field 'tolerance' must be an integer in 0..63, got " + j["tolerance"].dump());
        p.tolerance = int(*t);
    }
    if (!j.contains("colours") || !j["colours"].is_object() || j["colours"].empty())
        throw InvalidInput(f + ": field 'colours' must be an object {\"<class name>\": \"#rrggbb\", ...}");
    for (const auto& [name, colour] : j["colours"].items()) {
        const int id = table.id(name);
        if (id < 0) throw InvalidInput(f + ": colours: '" + name + "' is not a class of the label table");
        if (!colour.is_string())
            throw InvalidInput(f + ": colours: '" + name + "' must be a \"#rrggbb\" string, got " + colour.dump());
        try {
            p.entries.push_back({id, vision::StrokePalette::parse_hex(colour.get<std::string>())});
        } catch (const InvalidInput& e) {
            throw InvalidInput(f + ": colours: '" + name + "': " + e.what());
        }
    }
    std::string why;
    if (!p.is_valid(&why)) throw InvalidInput(f + ": " + why);
    return p;
}

void write_segmentation_folder(const std::filesystem::path& out, const cv::Mat& photo,
                               const vision::Segmentation& seg, const vision::SegmentationSummary& summary,
                               const std::vector<vision::GarmentResult>& garments, const std::string& image_file,
                               const std::string& mode, double person_height_m) {
    cv::Mat garment_mask = cv::Mat::zeros(photo.size(), CV_8UC1);
    std::vector<vision::Fold> folds;
    for (const auto& g : garments) {
        garment_mask |= seg.labels == g.label_id;
        folds.insert(folds.end(), g.folds.begin(), g.folds.end());
    }
    detail::Staging staging(out);
    write_png(staging / "labels.png", seg.labels);
    write_png(staging / "occlusion.png", seg.occlusion);
    write_png(staging / "overlay.png", vision::draw_segmentation(photo, seg.labels));
    write_png(staging / "folds.png", vision::draw_folds(photo, garment_mask, folds));
    write_json_file(staging / "garments.json",
                    garments_json(garments, summary, image_file, photo.cols, photo.rows, mode, person_height_m));
    staging.commit();
}

}  // namespace drape::io
