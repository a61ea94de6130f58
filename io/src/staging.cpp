#include "staging.hpp"

#include <drape/core/errors.hpp>
#include <drape/io/vision_json.hpp>

#include <unistd.h>

namespace drape::io::detail {

namespace fs = std::filesystem;

Staging::Staging(const fs::path& out) : out_(out) {
    make_output_dir(out_);
    dir_ = out_ / (".partial-" + std::to_string(::getpid()));
    std::error_code ec;
    fs::remove_all(dir_, ec);
    if (!fs::create_directories(dir_, ec))
        throw IoError("cannot create the staging folder '" + dir_.string() + "': " + ec.message());
}

Staging::~Staging() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
}

void Staging::commit() {
    for (const auto& e : fs::directory_iterator(dir_)) {
        std::error_code ec;
        const fs::path target = out_ / e.path().filename();
        // rename() does not replace a non-empty folder: an earlier run's folder goes first.
        if (e.is_directory() && fs::is_directory(target)) fs::remove_all(target, ec);
        ec.clear();
        fs::rename(e.path(), target, ec);
        if (ec) throw IoError("cannot move '" + e.path().string() + "' into '" + out_.string() + "': " + ec.message());
    }
}

}  // namespace drape::io::detail
