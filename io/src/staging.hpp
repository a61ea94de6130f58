// A staged output folder (not installed): every output file goes to a staging folder inside
// DIR first; only a complete set is moved in (each entry by an atomic rename), so a failed or
// cancelled run leaves DIR as it was. Shared by the recovery's and the animation's writers.
#pragma once

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

    std::filesystem::path operator/(const std::string& name) const { return dir_ / name; }
    /// Moves every staged entry into DIR; a staged folder replaces DIR's folder of that name.
    /// \throw drape::IoError naming the entry.
    void commit();

  private:
    std::filesystem::path out_, dir_;
};

}  // namespace drape::io::detail
