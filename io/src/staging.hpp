// A staged output folder (internal to drape::io, not installed): every output file goes to a
// staging folder inside DIR first; only a complete set is moved in (each entry by an atomic
// rename), so a failed or cancelled run leaves DIR as it was. The recovery's, try-on's and
// animation's writers go through it.
#pragma once

#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>

namespace drape::io::detail {

class Staging {
  public:
    /// Creates DIR (if needed) and the empty staging folder DIR/.partial-PID.
    /// \throw drape::IoError naming the folder.
    explicit Staging(const std::filesystem::path& out);
    /// Removes the staging folder and whatever is left in it.
    ~Staging();
    Staging(const Staging&) = delete;
    Staging& operator=(const Staging&) = delete;

    /// The staged path of a file named `name`.
    std::filesystem::path operator/(const std::string& name) const { return dir_ / name; }
    /// Stages garment `index`'s files: garment_N.glb/.obj (draped, `comment` in the OBJ) and
    /// pattern_N.svg/.dxf/.json. \throw drape::IoError naming the file.
    void write_garment(std::size_t index, const garment::Pattern& pattern, const garment::GarmentMesh& mesh,
                       const Eigen::MatrixX3d& positions, const std::string& comment) const;
    /// Moves every staged entry into DIR; a staged folder replaces DIR's folder of that name.
    /// \throw drape::IoError naming the entry.
    void commit();

  private:
    std::filesystem::path out_, dir_;
};

}  // namespace drape::io::detail
