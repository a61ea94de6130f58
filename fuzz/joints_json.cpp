// Joints files (../shared/data/photos/joints format) through both readers: drape::io's
// (body fit, recovery) and the vision one (segmentation), for a 640 x 480 photo.
#include "fuzz_common.hpp"

#include <drape/io/joints_json.hpp>
#include <drape/io/vision_json.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("joints.json", data, size);
    drape::fuzz::expect_clean([&] { (void)drape::io::read_joints_file(path, 640, 480); });
    drape::fuzz::expect_clean([&] {
        double shift = 0;
        (void)drape::io::read_vision_joints(path, 640, 480, &shift);
    });
    return 0;
}
