#include "staging.hpp"

#include <drape/core/errors.hpp>
#include <drape/garment/garment_export.hpp>
#include <drape/garment/pattern_dxf.hpp>
#include <drape/garment/pattern_json.hpp>
#include <drape/garment/pattern_svg.hpp>
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

void Staging::write_garment(std::size_t index, const garment::Pattern& pattern, const garment::GarmentMesh& mesh,
                            const Eigen::MatrixX3d& positions, const std::string& comment) const {
    const std::string n = std::to_string(index);
    garment::write_garment_glb(dir_ / ("garment_" + n + ".glb"), mesh, positions);
    garment::write_garment_obj(dir_ / ("garment_" + n + ".obj"), pattern, mesh, positions, comment);
    garment::write_pattern_svg(dir_ / ("pattern_" + n + ".svg"), pattern);
    garment::write_pattern_dxf(dir_ / ("pattern_" + n + ".dxf"), pattern);
    garment::write_pattern_json(dir_ / ("pattern_" + n + ".json"), pattern);
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
