// What the 14 image joints of a photo mark: shared by libvision (vision::Joints carries it
// with the points) and libbody (the photo fit chooses its image-joint offsets by it).
#pragma once

namespace drape::core {

/// `hand`: where people mark joints on a photo (the hips' and shoulders' outline, the hand,
/// the top of the hair: body::ImageJointOffsets::hand_marked()); `model`: the body model's
/// joints themselves (synthetic scenes project them). docs/body-fitting.md, "Image joints".
enum class JointMarks { hand, model };

}  // namespace drape::core
