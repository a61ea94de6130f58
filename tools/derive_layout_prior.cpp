// drape_derive_layout_prior: prints libvision/src/layout_prior_data.cpp, the class counts
// per cell of the joint-normalised body frame (libvision/src/layout_frame.hpp) that the
// automatic segmentation turns into spatial costs (docs/vision.md, "Segmentation").
//
//   drape_derive_layout_prior DIR[:tune|:all] ... > libvision/src/layout_prior_data.cpp
//
// Each DIR is a folder in the ../shared/data/photos layout (images/, labels/, joints/).
// ":tune" keeps only the tuning part of the fixed split of docs/vision.md (the photo
// names sorted ascending, 0-based even positions); ":all" (default) every photo. Only
// statistics leave the labels: counts of six classes (background, skin, hair, upper
// garment, lower garment, other: occluders such as bags, belts and outerwear, shoes,
// tights, accessories; a dress counts as upper above the natural waist, 62 % shoulder ->
// hip, and as lower below) per frame cell, every photo
// also counted mirrored (left and right joints swapped), every second pixel in x and y.
#include "layout_frame.hpp"
#include "photo_folder.hpp"

#include <drape/vision/image_io.hpp>
#include <drape/vision/joints.hpp>
#include <drape/vision/label_table.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace drape::vision;

namespace {

/// The joints of the horizontally mirrored photo: x -> width - x, left and right swapped.
Joints mirrored(const Joints& j, int width) {
    const int swap[kJointCount] = {5, 4, 3, 2, 1, 0, 11, 10, 9, 8, 7, 6, 12, 13};
    Joints out;
    for (int i = 0; i < kJointCount; ++i) {
        const Eigen::Vector2d p = j.px[size_t(swap[i])];
        out.px[size_t(i)] = {width - p.x(), p.y()};
    }
    return out;
}

int auto_class(LabelRole r, bool below_waist) {
    switch (r) {
        case LabelRole::skin: return 1;
        case LabelRole::hair: return 2;
        case LabelRole::upper_garment: return 3;
        case LabelRole::lower_garment: return 4;
        case LabelRole::full_garment: return below_waist ? 4 : 3;
        case LabelRole::background: return 0;
        default: return 5;  // occluders (bags, belts, outerwear, ...) and the rest (shoes, tights, ...)
    }
}

void count(const cv::Mat& labels, const Joints& j, const LabelTable& table,
           std::vector<std::array<std::uint64_t, 6>>& counts) {
    const auto seg = drape::vision::detail::frame_segments(j);
    const double H = j.body_height_px();
    const Eigen::Vector2d wr = j[Joint::right_shoulder] + 0.62 * (j[Joint::right_hip] - j[Joint::right_shoulder]);
    const Eigen::Vector2d wl = j[Joint::left_shoulder] + 0.62 * (j[Joint::left_hip] - j[Joint::left_shoulder]);
    // Normal of the waist line (wr -> wl) pointing down the image.
    Eigen::Vector2d down(-(wl - wr).y(), (wl - wr).x());
    if (down.y() < 0) down = -down;
    for (int y = 0; y < labels.rows; y += 2)
        for (int x = 0; x < labels.cols; x += 2) {
            const Eigen::Vector2d p(x + 0.5, y + 0.5);
            const bool below = down.dot(p - wr) > 0;
            const int c = auto_class(table.role(labels.at<std::uint8_t>(y, x)), below);
            ++counts[size_t(drape::vision::detail::frame_cell(seg, H, p))][size_t(c)];
        }
}

}  // namespace

int main(int argc, char** argv) {
    using drape::vision::detail::kFrameCells;
    if (argc < 2) {
        std::cerr << "usage: drape_derive_layout_prior DIR[:tune|:all] ... > layout_prior_data.cpp\n";
        return 2;
    }
    try {
        std::vector<std::array<std::uint64_t, 6>> counts(size_t(kFrameCells), {0, 0, 0, 0, 0, 0});
        std::vector<std::string> sources;
        int photos = 0;
        for (int a = 1; a < argc; ++a) {
            std::string arg = argv[a], part = "all";
            if (const auto colon = arg.rfind(':'); colon != std::string::npos && colon > 1) {
                part = arg.substr(colon + 1);
                arg = arg.substr(0, colon);
            }
            if (part != "tune" && part != "all") throw std::runtime_error("part must be tune or all: " + part);
            const fs::path dir(arg);
            const LabelTable table = LabelTable::fashionista();
            const size_t total = drape::tools::photo_names(dir, false).size();
            const std::vector<std::string> names = drape::tools::photo_names(dir, part == "tune");
            int used = 0;
            for (size_t i = 0; i < names.size(); ++i) {
                const cv::Mat labels = load_label_map(dir / "labels" / (names[i] + ".png"), "labels");
                const Joints j = drape::tools::read_joints(dir / "joints" / (names[i] + ".json"));
                count(labels, j, table, counts);
                cv::Mat flipped;
                cv::flip(labels, flipped, 1);
                count(flipped, mirrored(j, labels.cols), table, counts);
                ++used;
            }
            photos += used;
            sources.push_back(dir.filename().string() + " (" + part + ": " + std::to_string(used) +
                              " of " + std::to_string(total) + " photos)");
        }
        std::cout << "// Generated by tools/derive_layout_prior.cpp (drape_derive_layout_prior); do not edit.\n"
                     "// Class counts (background, skin, hair, upper, lower, other) per cell of the body frame of\n"
                     "// layout_frame.hpp, from the hand labels of:\n";
        for (const auto& s : sources) std::cout << "//   " << s << "\n";
        std::cout << "// " << photos << " photos, each also mirrored; every second pixel in x and y.\n"
                     "// Regenerate: docs/vision.md, \"Segmentation\" (automatic).\n"
                     "#include \"layout_prior_data.hpp\"\n\n"
                     "namespace drape::vision::detail {\n\n"
                     "const std::uint32_t kLayoutPriorCounts[kFrameCells][kLayoutPriorClasses] = {\n";
        for (int c = 0; c < kFrameCells; ++c) {
            std::cout << "    {";
            for (int k = 0; k < 6; ++k) std::cout << counts[size_t(c)][size_t(k)] << (k < 5 ? ", " : "");
            std::cout << "},\n";
        }
        std::cout << "};\n\n}  // namespace drape::vision::detail\n";
    } catch (const std::exception& e) {
        std::cerr << "drape_derive_layout_prior: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
