// Drape's own material files (format "drape-material") through cloth::load_material, and
// the material object of truth.json / result.json through io::material_from_json.
#include "fuzz_common.hpp"

#include <drape/cloth/material.hpp>
#include <drape/io/garment_json.hpp>
#include <drape/io/json_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto path = drape::fuzz::write_input("material.json", data, size);
    drape::fuzz::expect_clean([&] {
        drape::cloth::MaterialInfo info;
        (void)drape::cloth::load_material(path, &info);
    });
    drape::fuzz::expect_clean([&] {
        std::string base;
        (void)drape::io::material_from_json(drape::io::read_json_file(path), "material.json", &base);
    });
    return 0;
}
