// The files of an animation (drape::io): `drape animate`'s output folder (docs/animation.md,
// "Output files"), staged and moved in whole as a recovery's.
#pragma once

#include <drape/recover/animate_garments.hpp>

#include <drape/body/body_model.hpp>
#include <drape/garment/animate.hpp>
#include <drape/garment/dress_outfit.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace drape::io {

/// Writes into `out`: animation.glb (the skinned body with its motion and each garment as
/// per-frame morph targets, body::export_animated_glb), frames/garment_N_KKKK.obj (garment N
/// at frame K, with its pattern uv) and animation.json (`report`). Staged in a folder inside
/// `out` and moved in only once all are written; `keep_going` (if set) is asked before the
/// move, and when it returns false nothing is moved and the function returns false.
/// \param names one per garment (its glTF node name, e.g. "skirt_0").
/// \throw drape::InvalidInput if the frames do not fit the outfit; drape::IoError naming the file.
bool write_animation(const std::filesystem::path& out, const body::BodyModel& model, const body::ShapedBody& shaped,
                     const garment::DressedOutfit& outfit, const garment::AnimatedOutfit& animation,
                     const std::vector<std::string>& names, const nlohmann::json& report,
                     const std::function<bool()>& keep_going = {});

/// The summary of an animation as JSON (per-frame checks included).
nlohmann::json animation_json(const garment::AnimateSummary& summary);

/// The inputs of an animation from result folders or synthetic scenes (`specs`: "DIR" or
/// "DIR:N", inner first; read_recovery_folder): their garments, the body and pose of the first
/// folder, and `motion`.
/// \throw drape::InvalidInput if specs is empty, a garment was not recovered (unsupported), or
///        as read_recovery_folder (naming the folder and field); drape::IoError.
recover::AnimateGarmentsInputs read_animation_inputs(const std::vector<std::string>& specs, const std::string& motion);

/// animation.json of `drape animate` and drape_animate: animation_json of the animation, the
/// motion, fps, wind, the garments' specs ("DIR[:N]") and the drape's brief report.
nlohmann::json animation_report(const recover::AnimateGarmentsSummary& summary,
                                const recover::AnimateGarmentsOptions& options, const std::string& motion,
                                const std::vector<std::string>& garments);

}  // namespace drape::io
