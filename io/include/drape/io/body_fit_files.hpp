// The files of a body fit (drape::io, shared by `drape fit-body` and the C API): reading the
// photo, its joints and the person's masks into body::FitInputs, and body.json.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/fit_body.hpp>
#include <drape/io/joints_json.hpp>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include <filesystem>
#include <string>

namespace drape::io {

/// What a fit reads: the photo, its joints file's pixel convention and the fit's inputs.
struct BodyFitFiles {
    cv::Mat photo;                    ///< 8-bit BGR, EXIF orientation applied
    PixelOrigin origin = PixelOrigin::one_based;
    body::FitInputs inputs;           ///< joints (and their "marks"), person mask, skin mask (height, gender unset)
};

/// Reads the photo, its 14 joints and either a silhouette (with an optional skin mask) or a
/// Fashionista class-id label map (person = every class but kNotPersonLabels, skin = 41).
/// Empty strings mean "not given".
/// \throw drape::InvalidInput (neither or both of silhouette and labels, a mask of another
///        size than the photo, naming the file), drape::IoError.
BodyFitFiles read_body_fit_files(const std::string& image, const std::string& joints, const std::string& silhouette,
                                 const std::string& skin, const std::string& labels);

/// "converged", "max_iterations", "failed", "cancelled".
const char* termination_name(body::Termination t);

/// body.json of a fit: {"format": "drape.body_fit", "version": 1, "image", "pose", "shape",
/// "coefficients", "coefficient_names", "camera", "joints_2d" (in the joints file's pixel
/// convention), "joint_names", "pixel_origin", "fit": {termination, figures}}.
nlohmann::json body_fit_json(const std::string& image, const BodyFitFiles& files, const body::BodyModel& model,
                             const body::BodyFit& fit, const body::FitSummary& summary,
                             const body::FitQuality& quality);

/// Writes the folder of `drape fit-body`: body.json (body_fit_json), body.glb (the fitted
/// body, rigged, in the fitted pose) and overlay.png (draw_fit_overlay of the fitted body's
/// silhouette and joints over the photo), staged inside `out` and moved in only once all are
/// written, so a failure leaves `out` as it was. Shared by the CLI and the C API.
/// \return the body.json written (the C API hands it out too).
/// \throw drape::IoError naming the file or folder.
nlohmann::json write_body_fit_folder(const std::filesystem::path& out, const std::string& image, const BodyFitFiles& files,
                           const body::BodyModel& model, const body::BodyFit& fit, const body::FitSummary& summary,
                           const body::FitQuality& quality);

}  // namespace drape::io
