// ImageJointOffsets::hand_marked(): where hand-marked fashion photos put their 14 joints
// relative to the model's joints. Printed by `drape_calibrate_image_joints` (tools/) from
// the tuning part of ../shared/data/photos-dev, 55 photos, 4 rounds, posture weight 100
// (docs/body-fitting.md, "Image joints").
#include <drape/body/fit_body.hpp>

namespace drape::body {

ImageJointOffsets ImageJointOffsets::hand_marked() {
    ImageJointOffsets o;
    // kImageJoints order, metres, in the rest frame of the bone that ends at the joint.
    o.offset_m <<
        0.0100, 0.0128, 0.0000,  // right_ankle
        -0.0019, 0.0044, 0.0000,  // right_knee
        -0.0296, -0.0020, 0.0000,  // right_hip
        0.0296, -0.0020, 0.0000,  // left_hip
        0.0019, 0.0044, 0.0000,  // left_knee
        -0.0100, 0.0128, 0.0000,  // left_ankle
        -0.0299, -0.0319, 0.0000,  // right_hand
        0.0049, 0.0087, 0.0000,  // right_elbow
        -0.0187, 0.0218, 0.0000,  // right_shoulder
        0.0187, 0.0218, 0.0000,  // left_shoulder
        -0.0049, 0.0087, 0.0000,  // left_elbow
        0.0299, -0.0319, 0.0000,  // left_hand
        0.0000, -0.0177, 0.0000,  // neck
        0.0000, 0.0328, 0.0000;  // head
    return o;
}

}  // namespace drape::body
