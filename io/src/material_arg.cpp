#include <drape/io/material_arg.hpp>

#include <drape/core/errors.hpp>

#include <filesystem>

namespace drape::io {

cloth::Material load_material_arg(const std::string& name_or_path, const std::string& materials_dir,
                                  std::string* source) {
    namespace fs = std::filesystem;
    const fs::path given(name_or_path);
    std::error_code ec;
    if (given.has_extension() || given.has_parent_path()) {
        if (!fs::is_regular_file(given, ec))
            throw IoError("--material: file '" + name_or_path + "' not found");
        if (source) *source = given.string();
        return cloth::load_material(given);
    }
    if (!materials_dir.empty()) {
        const fs::path file = fs::path(materials_dir) / (name_or_path + ".json");
        if (fs::is_regular_file(file, ec)) {
            if (source) *source = file.string();
            return cloth::load_material(file);
        }
    }
    if (source) *source = "built-in " + name_or_path;
    return cloth::builtin_material(name_or_path);
}

}  // namespace drape::io
