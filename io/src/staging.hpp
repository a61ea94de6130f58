// Internal to drape::io: an output folder written all at once. Every file goes to a staging
// folder inside DIR first; only a complete set is moved in (each file by an atomic rename),
// so a failed or cancelled run leaves DIR as it was. `drape recover` and `drape tryon` write
// through it.
#pragma once

#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>

namespace drape::io {

class Staging {
  public:
    /// Creates DIR (if needed) and an empty staging folder in it.
    /// \throw drape::IoError naming the folder.
    explicit Staging(const std::filesystem::path& out);
    ~Staging();  ///< removes the staging folder and whatever is left in it
    Staging(const Staging&) = delete;
    Staging& operator=(const Staging&) = delete;

    /// The staged path of a file named `name`.
    std::filesystem::path operator/(const std::string& name) const { return dir_ / name; }
    /// Stages garment `index`'s files: garment_N.glb/.obj (draped, `comment` in the OBJ) and
    /// pattern_N.svg/.dxf/.json. \throw drape::IoError naming the file.
    void write_garment(std::size_t index, const garment::Pattern& pattern, const garment::GarmentMesh& mesh,
                       const Eigen::MatrixX3d& positions, const std::string& comment) const;
    /// Moves every staged file into DIR. \throw drape::IoError naming the file.
    void commit();

  private:
    std::filesystem::path out_, dir_;
};

}  // namespace drape::io
