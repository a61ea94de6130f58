// The files of a try-on (drape::io): the garments read from result folders, tryon.json and the
// output folder (the same files as a recovery's, plus tryon.json and a grading sheet per
// garment), written staged as write_recovery does. Shared by `drape tryon` and `drape eval-tryon`.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/recover/tryon.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace drape::io {

/// The garments of `specs` ("DIR" = every garment of a result folder or synthetic scene,
/// "DIR:N" = garment N), in the order given, each with the body of its folder.
/// \throw drape::InvalidInput if specs is empty, or as read_recovery_folder (naming the folder
///        and field: a folder without a garment, N out of range, bad JSON); drape::IoError.
std::vector<recover::TryOnGarment> read_tryon_garments(const std::vector<std::string>& specs);

/// tryon.json: the target, per garment its source, original and graded G, the grading (rules,
/// clamps, style changes, ease, the size grade against the chart), the drape's checks, and the
/// summary.
nlohmann::json tryon_json(const recover::TryOnInputs& in, const recover::TryOnOptions& options,
                          const recover::TryOnResult& result, const recover::TryOnSummary& summary);

/// Writes the try-on into `out` (docs/tryon.md, "Outputs"): garment_N.glb/.obj,
/// pattern_N.svg/.dxf/.json (graded), grading_N.svg (both sizes nested), body.glb, outfit.glb,
/// report.html, tryon.json, and for a photo target overlay.png, mask.png and
/// own_garment_mask.png. Staged and moved in only once complete (as write_recovery);
/// `keep_going` (if set) is asked before the move: false moves nothing and returns false.
/// \throw drape::IoError naming the file.
bool write_tryon(const std::filesystem::path& out, const body::BodyModel& model, const recover::TryOnInputs& in,
                 const recover::TryOnOptions& options, const recover::TryOnResult& result,
                 const recover::TryOnSummary& summary, const std::function<bool()>& keep_going = {});

}  // namespace drape::io
