// POSE.json (preset, translation, axis-angle rotations per joint).
#include "fuzz_common.hpp"

#include <drape/io/body_json.hpp>
#include <drape/io/json_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("pose.json", data, size);
    drape::fuzz::expect_clean([&] {
        (void)drape::io::pose_from_json(drape::io::read_json_file(path), "pose.json");
    });
    return 0;
}
