#pragma once
// Shared by the tools that read a photo folder in the ../shared/data/photos layout
// (images/, labels/, joints/): the joints file and the fixed photo split of docs/vision.md.
#include <drape/vision/photo_split.hpp>
#include <drape/vision/joints.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace drape::tools {

inline drape::vision::Joints read_joints(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) throw std::runtime_error("cannot read " + file.string());
    const nlohmann::json j = nlohmann::json::parse(in);
    double shift = -0.5;  // one_based, the default of the folder format
    if (j.contains("pixel_origin")) {
        const std::string o = j["pixel_origin"].get<std::string>();
        shift = o == "zero_based" ? 0.5 : o == "corner" ? 0.0 : -0.5;
    }
    drape::vision::Joints out;
    for (int i = 0; i < drape::vision::kJointCount; ++i)
        out.px[size_t(i)] = {j["joints"][size_t(i)][0].get<double>() + shift,
                             j["joints"][size_t(i)][1].get<double>() + shift};
    return out;
}

/// The photo names (stems of images/*.jpg) sorted ascending; with tuning_only, the
/// tuning part of the fixed split (`vision::select_photo_split`, docs/vision.md).
inline std::vector<std::string> photo_names(const std::filesystem::path& dir, bool tuning_only) {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir / "images"))
        if (e.path().extension() == ".jpg") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    return drape::vision::select_photo_split(
        names, tuning_only ? drape::vision::PhotoSplit::tune : drape::vision::PhotoSplit::all);
}

}  // namespace drape::tools
