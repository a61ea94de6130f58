// ArcSim's material files ({"density", "stretching", "bending"}, `//` comment lines)
// through cloth::load_material, which detects the format from the content.
#include "fuzz_common.hpp"

#include <drape/cloth/material.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("arcsim.json", data, size);
    drape::fuzz::expect_clean([&] { (void)drape::cloth::load_material(path); });
    return 0;
}
