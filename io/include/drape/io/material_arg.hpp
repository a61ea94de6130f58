// The `--material NAME|PATH` argument of the CLI commands that simulate cloth.
#pragma once

#include <drape/cloth/material.hpp>

#include <string>

namespace drape::io {

/// A path (it has an extension or a folder) is loaded as a material file (ours or
/// ArcSim's); a NAME is looked up as NAME.json in `materials_dir` when that is given and
/// holds it, else among the built-in measured fabrics (cloth::builtin_material).
/// `source` (if not null) receives the file used or "built-in NAME".
/// \throw drape::IoError for a missing file, drape::InvalidInput for an unknown name
///        (the message lists the known ones) or a malformed file.
cloth::Material load_material_arg(const std::string& name_or_path, const std::string& materials_dir,
                                  std::string* source = nullptr);

}  // namespace drape::io
