// Where tests find ../shared (photos, anthropometry) and a scratch folder.
#pragma once

#include <filesystem>
#include <string>

namespace drape::test {

/// The shared data folder: $DRAPE_SHARED_DIR if set, else the one configured by CMake
/// (../shared beside the source tree). May not exist: use shared_path_or_skip.
std::filesystem::path shared_dir();

/// shared_dir()/relative if it exists, else an empty path (the caller SKIPs with a message).
std::filesystem::path shared_path(const std::string& relative);

/// A fresh, empty scratch folder for one test, under the build's temp folder.
std::filesystem::path scratch_dir(const std::string& name);

/// The project's source tree.
std::filesystem::path source_dir();

}  // namespace drape::test

/// Skips the current test with a clear message when a shared data file is absent.
#define DRAPE_REQUIRE_SHARED(var, relative)                                              \
    const std::filesystem::path var = ::drape::test::shared_path(relative);              \
    if (var.empty()) {                                                                   \
        WARN("skipped: shared data '" << (relative) << "' not found under "              \
             << ::drape::test::shared_dir() << " (set DRAPE_SHARED_DIR)");               \
        return;                                                                          \
    }
