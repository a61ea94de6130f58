// The recovery commands' flags (app layer): the options from flags and the progress line,
// shared by `drape recover` and the evaluations `drape eval-synthetic` / `drape eval-photos`.
// The files (inputs, result.json, the output folder) are drape::io's (recovery_files.hpp).
#pragma once

#include <drape/io/recovery_files.hpp>
#include <drape/recover/recover.hpp>

#include <nlohmann/json.hpp>

#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <string>

namespace drape::app {

using namespace io;

/// The flags every recovery command shares.
struct RecoverFlags {
    std::string quality = "default";
    int threads = 2;
    unsigned seed = 1;
    std::optional<int> particles, generations, rounds;
    bool no_material = false;
    bool joint_pose = false;
    std::string material_target = "calibrated";
    std::string output_drape = "output";  // output | auto | search
    std::optional<double> max_arm_elevation;
    std::optional<double> min_ease;
    std::optional<std::string> base_fabric;
};

/// Adds the shared flags to a command.
void add_recover_flags(CLI::App* cmd, RecoverFlags& flags);

/// Options from the flags (quality preset, then the overrides), with a progress callback
/// that prints a line on stderr per stage and every 2 s (prefix, e.g. "drape recover") and
/// stops on Ctrl-C / SIGTERM.
recover::RecoverOptions recover_options(const RecoverFlags& flags, const std::string& prefix);

}  // namespace drape::app
