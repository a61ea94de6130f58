// The files of a recovery (drape::io): reading a photo's inputs, result.json, writing the
// output folder (staged, then moved in whole), and reading a finished result folder back
// (try-on and animation start from one). Shared by `drape recover`, the evaluations and the
// C API.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/cloth/material.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/garment_type.hpp>
#include <drape/recover/recover.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace drape::io {

/// The photo, its joints and optional strokes (class ids, or colours with a palette), and the
/// garments asked for ("auto" or names joined by '+').
/// \throw drape::InvalidInput naming the file and value; drape::IoError.
recover::RecoverInputs read_recover_inputs(const std::filesystem::path& image, const std::filesystem::path& joints,
                                           const std::string& strokes, const std::string& palette,
                                           const std::string& garments);

/// A drape's state as result.json and tryon.json write it.
nlohmann::json drape_json(const recover::DrapeState& drape);

/// result.json's content (the schema of truth.json plus the recovery's own keys).
nlohmann::json recovery_json(const std::string& image, const recover::RecoverInputs& in,
                             const recover::RecoverOptions& options, const recover::RecoveryResult& result,
                             const recover::RecoverSummary& summary);

/// Writes every output file of a finished recovery into `out` (docs/recovery.md, "Output
/// files"): staged in a folder inside it first and moved in only once all are written, so a
/// failure or a cancel leaves `out` as it was (files of an earlier run are replaced one by one
/// by rename, never truncated). `keep_going` (if set) is asked before the move; when it
/// returns false nothing is moved and the function returns false.
/// \throw drape::IoError naming the file.
bool write_recovery(const std::filesystem::path& out, const std::string& image, const body::BodyModel& model,
                    const recover::RecoverInputs& in, const recover::RecoverOptions& options,
                    const recover::RecoveryResult& result, const recover::RecoverSummary& summary,
                    const std::function<bool()>& keep_going = {});

/// Creates `out` if needed and checks that files can be created in it (a staging folder is
/// made and removed), so that a long recovery refuses an unwritable or read-only output
/// folder before any work rather than after it.
/// \throw drape::IoError naming the folder and the system's reason.
void check_output_folder(const std::filesystem::path& out);

/// One garment of a result folder, as try-on and animation need it.
struct SavedGarment {
    int index = 0;                             ///< N of garment_N.*
    garment::GarmentType type = garment::GarmentType::tshirt;
    std::string garment;                       ///< the recovered choice ("shorts", "tank", ...)
    bool supported = true;
    garment::GarmentSizing sizing;             ///< recovered G
    cloth::Material material;                  ///< recovered fabric (tables × scales)
    std::string base_fabric;
};

/// A result folder of `drape recover` (or a synthetic scene's truth.json, same schema).
struct SavedRecovery {
    std::filesystem::path folder;
    body::SemanticRequest body;                ///< the recovered body's semantic shape
    body::Pose pose;                           ///< the pose it was draped in
    std::vector<SavedGarment> garments;        ///< inner first, as in the file
};

/// Reads `spec` = "DIR" (every garment) or "DIR:N" (garment N only): DIR/result.json, or
/// DIR/truth.json when there is no result.json.
/// \throw drape::IoError (no such folder or file), drape::InvalidInput naming the file and the
/// field (bad JSON, unknown garment type, bad sizing or material, N out of range, no garment).
SavedRecovery read_recovery_folder(const std::string& spec);

}  // namespace drape::io
