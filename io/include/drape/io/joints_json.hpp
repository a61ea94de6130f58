// The 14-joint file of ../shared/data/photos/joints, read once for every command:
// {"joints": [[x, y] x 14], "joint_names": [...], "image_size": [w, h], "pixel_origin": ...}.
#pragma once

#include <drape/body/skeleton.hpp>
#include <drape/vision/joints.hpp>

#include <Eigen/Core>

#include <filesystem>

namespace drape::io {

/// How the file's pixel coordinates relate to the image frame used by libbody and libvision
/// (origin at the image's top-left corner, pixel centres at +0.5).
enum class PixelOrigin { one_based, zero_based, corner };

/// The offset added to the file's coordinates: −0.5, +0.5 or 0.
double origin_offset(PixelOrigin o);
const char* origin_name(PixelOrigin o);

using JointsPx = Eigen::Matrix<double, body::kImageJointCount, 2>;

struct JointsFile {
    JointsPx joints_px;  ///< image frame, in the Fashionista order (right_ankle ... head)
    PixelOrigin origin = PixelOrigin::one_based;
    vision::JointMarks marks = vision::JointMarks::hand;  ///< the optional "marks" field
};

/// Reads and checks a joints file for a `width` x `height` photo: known keys only, 14
/// finite [x, y] pairs inside the photo, `joint_names` and `image_size` (if present)
/// consistent. \throw drape::InvalidInput naming the file, field and value; IoError.
JointsFile read_joints_file(const std::filesystem::path& path, int width, int height);

}  // namespace drape::io
