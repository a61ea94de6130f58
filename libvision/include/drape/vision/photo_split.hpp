// The fixed split of an evaluation folder into a tuning and a held-out part
// (docs/vision.md, "Evaluation protocol"): the photo names (file stems of images/*.jpg)
// sorted ascending; 0-based even positions are the tuning part, odd positions the
// held-out part. Applies to any folder (`photos`, `photos-dev`); on photos-dev's 109
// names it gives 55 tuning and 54 held-out photos.
#pragma once

#include <string>
#include <vector>

namespace drape::vision {

enum class PhotoSplit { all, tune, heldout };

/// "all", "tune" or "heldout".
const char* to_string(PhotoSplit split);
/// Parses "all", "tune" or "heldout". \throw drape::InvalidInput naming the text.
PhotoSplit parse_photo_split(const std::string& text);

/// The part (tune or heldout) of each of `names`, by its position among the names sorted
/// ascending (byte order). \throw drape::InvalidInput for an empty or repeated name.
std::vector<PhotoSplit> photo_split_parts(const std::vector<std::string>& names);

/// The names of `names` in part `split` (all of them for PhotoSplit::all), sorted ascending.
/// \throw drape::InvalidInput as photo_split_parts.
std::vector<std::string> select_photo_split(const std::vector<std::string>& names, PhotoSplit split);

}  // namespace drape::vision
