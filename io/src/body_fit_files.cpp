#include <drape/io/body_fit_files.hpp>

#include <drape/io/body_json.hpp>
#include <drape/io/image_io.hpp>
#include <drape/io/json_io.hpp>

#include "staging.hpp"

#include <drape/body/model_io.hpp>
#include <drape/core/errors.hpp>

#include <vector>

namespace drape::io {

namespace {

void require_size(const body::Mask& m, const cv::Mat& photo, const std::string& what, const std::string& file) {
    if (m.width != photo.cols || m.height != photo.rows)
        throw InvalidInput(what + " '" + file + "' is " + std::to_string(m.width) + " x " + std::to_string(m.height) +
                           " pixels but the photo is " + std::to_string(photo.cols) + " x " +
                           std::to_string(photo.rows));
}

}  // namespace

BodyFitFiles read_body_fit_files(const std::string& image, const std::string& joints, const std::string& silhouette,
                                 const std::string& skin, const std::string& labels) {
    if (labels.empty() && silhouette.empty())
        throw InvalidInput("give a silhouette mask (--silhouette S.png) or a label map (--labels L.png)");
    if (!labels.empty() && (!silhouette.empty() || !skin.empty()))
        throw InvalidInput("a label map replaces the silhouette and skin masks; give one or the other");
    BodyFitFiles f;
    f.photo = read_photo(image);
    const JointsFile joints_file = read_joints_file(joints, f.photo.cols, f.photo.rows);
    f.origin = joints_file.origin;
    f.inputs.joints_px = joints_file.joints_px;
    f.inputs.marks = joints_file.marks;
    if (!labels.empty()) {
        LabelMasks masks = read_label_masks(labels);
        require_size(masks.person, f.photo, "label map", labels);
        f.inputs.person = std::move(masks.person);
        if (masks.skin.count() > 0) f.inputs.skin = std::move(masks.skin);
    } else {
        f.inputs.person = read_mask(silhouette, "silhouette");
        require_size(f.inputs.person, f.photo, "silhouette", silhouette);
        if (!skin.empty()) {
            f.inputs.skin = read_mask(skin, "skin");
            require_size(f.inputs.skin, f.photo, "skin mask", skin);
        }
    }
    return f;
}

const char* termination_name(body::Termination t) {
    switch (t) {
        case body::Termination::converged: return "converged";
        case body::Termination::max_iterations: return "max_iterations";
        case body::Termination::failed: return "failed";
        case body::Termination::cancelled: return "cancelled";
    }
    return "";
}

nlohmann::json body_fit_json(const std::string& image, const BodyFitFiles& files, const body::BodyModel& model,
                             const body::BodyFit& fit, const body::FitSummary& summary,
                             const body::FitQuality& quality) {
    nlohmann::json j;
    j["format"] = "drape.body_fit";
    j["version"] = 1;
    j["image"] = {{"file", image}, {"width", files.photo.cols}, {"height", files.photo.rows}};
    j["pose"] = to_json(fit.pose);
    j["shape"] = to_json(fit.shape);
    j["coefficients"] = std::vector<double>(fit.coefficients.data(), fit.coefficients.data() + fit.coefficients.size());
    j["coefficient_names"] = model.shape_names;
    j["camera"] = to_json(fit.camera);
    const double shift = origin_offset(files.origin);
    nlohmann::json pts = nlohmann::json::array();
    for (int i = 0; i < body::kImageJointCount; ++i) pts.push_back({fit.joints_2d(i, 0) - shift, fit.joints_2d(i, 1) - shift});
    j["joints_2d"] = pts;
    j["joint_names"] = std::vector<std::string>(body::kImageJointNames.begin(), body::kImageJointNames.end());
    j["pixel_origin"] = origin_name(files.origin);
    j["fit"] = {{"termination", termination_name(summary.termination)},
                {"message", summary.message},
                {"iterations", summary.iterations},
                {"seconds", summary.seconds},
                {"mean_joint_error_px", summary.mean_joint_error_px},
                {"person_height_px", quality.person_height_px},
                {"mean_joint_error_percent", quality.mean_joint_error_percent},
                {"person_iou", quality.person_iou},
                {"trunk_out_of_plane_deg", quality.trunk_out_of_plane_deg},
                {"leg_out_of_plane_deg", quality.leg_out_of_plane_deg},
                {"knee_bend_deg", quality.knee_bend_deg}};
    if (quality.skin_coverage >= 0) j["fit"]["skin_coverage"] = quality.skin_coverage;
    return j;
}

nlohmann::json write_body_fit_folder(const std::filesystem::path& out, const std::string& image, const BodyFitFiles& files,
                           const body::BodyModel& model, const body::BodyFit& fit, const body::FitSummary& summary,
                           const body::FitQuality& quality) {
    const body::ShapedBody shaped = body::shape_from_coefficients(model, fit.coefficients);
    nlohmann::json j = body_fit_json(image, files, model, fit, summary, quality);
    detail::Staging staging(out);
    write_json_file(staging / "body.json", j);
    body::export_glb(staging / "body.glb", model, shaped, fit.pose);
    write_png(staging / "overlay.png",
              draw_fit_overlay(files.photo, quality.silhouette, fit.joints_2d, files.inputs.joints_px));
    staging.commit();
    return j;
}

}  // namespace drape::io
