// Write-to-temporary-then-rename, so that a failed or interrupted write never leaves a
// half-written file where a good one stood.
#pragma once

#include <drape/core/errors.hpp>

#include <atomic>
#include <cstdio>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <system_error>

namespace drape {

/// Calls `write(tmp_path)` to produce the file under a temporary name in the same folder,
/// then renames it onto `path`. On any failure the temporary is removed, `path` is left as
/// it was, and IoError (or the writer's own exception) propagates.
inline void write_atomically(const std::filesystem::path& path,
                             const std::function<void(const std::filesystem::path&)>& write) {
    namespace fs = std::filesystem;
    if (path.empty()) throw InvalidInput("output path is empty");
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw IoError("cannot write '" + path.string() + "': folder '" + dir.string() +
                      "' does not exist");
    static std::atomic<unsigned> counter{0};
    const fs::path tmp = dir / ("." + path.filename().string() + ".tmp" +
                                std::to_string(::getpid()) + "_" + std::to_string(counter++));
    try {
        write(tmp);
    } catch (...) {
        fs::remove(tmp, ec);
        throw;
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw IoError("cannot move finished file into place at '" + path.string() + "': " +
                      ec.message());
    }
}

/// Writes a text string atomically.
inline void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw IoError("cannot open '" + tmp.string() + "' for writing");
        out << text;
        out.flush();
        if (!out) throw IoError("failed while writing '" + path.string() + "' (disk full?)");
    });
}

}  // namespace drape
