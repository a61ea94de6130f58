// The tuning / held-out split of an evaluation folder (docs/vision.md, "Evaluation protocol").
#include <drape/vision/photo_split.hpp>

#include <drape/core/errors.hpp>

#include <algorithm>

namespace drape::vision {

const char* to_string(PhotoSplit split) {
    switch (split) {
        case PhotoSplit::tune: return "tune";
        case PhotoSplit::heldout: return "heldout";
        case PhotoSplit::all: break;
    }
    return "all";
}

PhotoSplit parse_photo_split(const std::string& text) {
    for (PhotoSplit s : {PhotoSplit::all, PhotoSplit::tune, PhotoSplit::heldout})
        if (text == to_string(s)) return s;
    throw InvalidInput("photo split '" + text + "' is not one of tune, heldout, all");
}

std::vector<PhotoSplit> photo_split_parts(const std::vector<std::string>& names) {
    std::vector<std::string> sorted = names;
    std::sort(sorted.begin(), sorted.end());
    for (size_t i = 0; i < sorted.size(); ++i) {
        require(!sorted[i].empty(), "photo split: a photo name is empty");
        require(i == 0 || sorted[i] != sorted[i - 1], "photo split: the name '", sorted[i],
                "' appears twice");
    }
    std::vector<PhotoSplit> parts;
    parts.reserve(names.size());
    for (const std::string& n : names) {
        const size_t pos = size_t(std::lower_bound(sorted.begin(), sorted.end(), n) - sorted.begin());
        parts.push_back(pos % 2 == 0 ? PhotoSplit::tune : PhotoSplit::heldout);
    }
    return parts;
}

std::vector<std::string> select_photo_split(const std::vector<std::string>& names, PhotoSplit split) {
    const std::vector<PhotoSplit> parts = photo_split_parts(names);
    std::vector<std::string> out;
    for (size_t i = 0; i < names.size(); ++i)
        if (split == PhotoSplit::all || parts[i] == split) out.push_back(names[i]);
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace drape::vision
