// A try-on source as `drape synth` and `drape recover` leave one (truth.json's schema): a median
// woman of ANSUR II (1.626 m, 66.8 kg) and a knee-length skirt of gray interlock made for her,
// or no garment. Shared by the try-on tests of the CLI and of the C API.
#pragma once

#include <drape/cloth/material.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/io/garment_json.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace drape::test {

inline std::filesystem::path write_skirt_scene(const std::filesystem::path& dir, bool with_garment = true) {
    std::filesystem::create_directories(dir);
    garment::GarmentSizing g;
    g.type = garment::GarmentType::skirt;
    g.skirt = {40.0, 40.0 / (3.14159265358979 / 2), 50.0, 90.0};
    nlohmann::json garments = nlohmann::json::array();
    if (with_garment)
        garments.push_back({{"type", "skirt"},
                            {"sizing", io::to_json(g)},
                            {"material", io::material_to_json(cloth::builtin_material("gray-interlock"), "gray-interlock")}});
    const nlohmann::json truth = {
        {"body", {{"params", {{"gender", "female"}, {"height_m", 1.626}, {"weight_kg", 66.8}}}}},
        {"garments", garments}};
    std::ofstream(dir / "truth.json") << truth.dump();
    return dir;
}

}  // namespace drape::test
