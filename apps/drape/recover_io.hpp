// The files of a recovery (app layer): reading a photo's inputs, the options from flags, the
// progress line, and writing the output folder (staged, then moved in whole). Shared by
// `drape recover` and the evaluations `drape eval-synthetic` / `drape eval-photos`.
#pragma once

#include <drape/body/body_model.hpp>
#include <drape/recover/recover.hpp>

#include <nlohmann/json.hpp>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace drape::app {

/// The flags every recovery command shares.
struct RecoverFlags {
    std::string quality = "default";
    int threads = 2;
    unsigned seed = 1;
    std::optional<int> particles, generations, rounds;
    bool no_material = false;
};

/// Adds the shared flags to a command.
void add_recover_flags(CLI::App* cmd, RecoverFlags& flags);

/// Options from the flags (quality preset, then the overrides), with a progress callback
/// that prints a line on stderr per stage and every 2 s (prefix, e.g. "drape recover") and
/// stops on Ctrl-C / SIGTERM.
recover::RecoverOptions recover_options(const RecoverFlags& flags, const std::string& prefix);

/// The photo, its joints and optional strokes (class ids, or colours with a palette), and the
/// garments asked for ("auto" or names joined by '+').
/// \throw drape::InvalidInput naming the file and value; drape::IoError.
recover::RecoverInputs read_recover_inputs(const std::filesystem::path& image, const std::filesystem::path& joints,
                                           const std::string& strokes, const std::string& palette,
                                           const std::string& garments);

/// result.json's content (the schema of truth.json plus the recovery's own keys).
nlohmann::json recovery_json(const std::string& image, const recover::RecoverInputs& in,
                             const recover::RecoverOptions& options, const recover::RecoveryResult& result,
                             const recover::RecoverSummary& summary);

/// Writes every output file of a finished recovery into `out`: staged in a folder inside it
/// first and moved in only once all are written, so a failure or a cancel leaves `out` as it
/// was. \throw drape::IoError; CommandExit(130) if interrupted before the move.
void write_recovery(const std::filesystem::path& out, const std::string& image, const body::BodyModel& model,
                    const recover::RecoverInputs& in, const recover::RecoverOptions& options,
                    const recover::RecoveryResult& result, const recover::RecoverSummary& summary);

}  // namespace drape::app
