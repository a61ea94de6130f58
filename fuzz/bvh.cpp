// BVH motion capture: the input is a .bvh file, read through assimp and retargeted by
// body::load_bvh_motion (standard joint map), then resampled to 30 fps as drape animate does.
// The rest skeleton is a hand-made A-pose (metres, +Y up, facing +Z, left at +X): the default
// model's own joints would cost its generation, about a minute under ASan, in every run.
#include "fuzz_common.hpp"

#include <drape/body/motion.hpp>

namespace {

Eigen::Matrix<double, drape::body::kJointCount, 3> rest_joints() {
    Eigen::Matrix<double, drape::body::kJointCount, 3> j;
    j << 0, 0.95, 0,            // pelvis
        0, 1.07, -0.01,         // spine
        0, 1.25, -0.01,         // chest
        0, 1.45, -0.01,         // neck
        0, 1.55, 0,             // head
        0, 1.70, 0,             // head_top
        -0.03, 1.42, 0,         // right_clavicle
        -0.18, 1.40, -0.01,     // right_shoulder
        -0.36, 1.22, -0.02,     // right_elbow
        -0.52, 1.05, 0,         // right_wrist
        0.03, 1.42, 0,          // left_clavicle
        0.18, 1.40, -0.01,      // left_shoulder
        0.36, 1.22, -0.02,      // left_elbow
        0.52, 1.05, 0,          // left_wrist
        -0.09, 0.90, 0,         // right_hip
        -0.10, 0.49, 0.01,      // right_knee
        -0.10, 0.08, -0.02,     // right_ankle
        -0.10, 0.02, 0.11,      // right_toe
        0.09, 0.90, 0,          // left_hip
        0.10, 0.49, 0.01,       // left_knee
        0.10, 0.08, -0.02,      // left_ankle
        0.10, 0.02, 0.11;       // left_toe
    return j;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const auto rest = rest_joints();
    const auto path = drape::fuzz::write_input("motion.bvh", data, size);
    drape::fuzz::expect_clean([&] {
        // Half of the inputs (odd sizes) through the isolated reader (the default: a forked
        // child, its output decoded here), half in this process, where libFuzzer sees the
        // retargeting's coverage (a child's is lost with it).
        drape::body::BvhLoadOptions options;
        options.isolate = size % 2 == 1;
        const drape::body::Motion m =
            drape::body::load_bvh_motion(path, rest, drape::body::BvhJointMap::standard(), nullptr, options);
        (void)drape::body::resample_motion(m, 30, 2);
    });
    return 0;
}
