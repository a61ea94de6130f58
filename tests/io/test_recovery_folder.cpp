// Reading a result folder back (try-on and animation start from one): every field round-trips
// through the writers' JSON, and bad folders get errors naming the file and the field.
#include <drape/io/body_json.hpp>
#include <drape/io/garment_json.hpp>
#include <drape/io/json_io.hpp>
#include <drape/io/recovery_files.hpp>

#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/sizing_proposal.hpp>

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace drape;

namespace {

struct Folder {
    fs::path dir = fs::temp_directory_path() / ("drape_io_test_" + std::to_string(::getpid()));
    Folder() {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Folder() { fs::remove_all(dir); }
};

garment::GarmentSizing sizing_of(garment::GarmentType type) {
    garment::GarmentSizing g;
    g.type = type;
    return g;
}

cloth::Material test_material() {
    cloth::Material m = cloth::builtin_material("gray-interlock");
    m.bending_scale = 7.5;
    m.stretching_scale = 1.25;
    return m;
}

nlohmann::json result_with(const nlohmann::json& garments) {
    body::SemanticShape shape;
    shape.gender = body::Gender::female;
    for (int k = 0; k < body::kSemanticCount; ++k) shape.values[k] = 0.5 + 0.01 * k;
    const body::Pose pose = body::named_pose(body::NamedPose::walking);
    return {{"format", "drape.recovery"},
            {"body", {{"params", io::to_json(shape)}, {"pose", io::to_json(pose)}}},
            {"garments", garments}};
}

}  // namespace

TEST_CASE("a result folder reads back the garments' type, sizing and material", "[io][recovery]") {
    Folder f;
    garment::GarmentSizing skirt = sizing_of(garment::GarmentType::skirt);
    skirt.skirt.l1 = 61.5;
    garment::GarmentSizing pants = sizing_of(garment::GarmentType::pants);
    pants.pants.h1 = 93.25;
    const cloth::Material m = test_material();
    nlohmann::json gs = nlohmann::json::array();
    gs.push_back({{"type", "skirt"}, {"garment", "skirt"}, {"supported", true}, {"sizing", io::to_json(skirt)},
                  {"material", io::material_to_json(m, "gray-interlock")}});
    gs.push_back({{"type", "pants"}, {"garment", "shorts"}, {"supported", false}, {"sizing", io::to_json(pants)},
                  {"material", io::material_to_json(m, "gray-interlock")}});
    io::write_json_file(f.dir / "result.json", result_with(gs));

    const io::SavedRecovery all = io::read_recovery_folder(f.dir.string());
    REQUIRE(all.garments.size() == 2);
    CHECK(all.body.gender == body::Gender::female);
    REQUIRE(all.body.values[0].has_value());
    CHECK(*all.body.values[0] == Approx(0.5));
    CHECK(all.pose.rotations.isApprox(body::named_pose(body::NamedPose::walking).rotations, 1e-12));
    CHECK(all.garments[0].type == garment::GarmentType::skirt);
    CHECK(all.garments[0].sizing.skirt.l1 == Approx(61.5));
    CHECK(all.garments[0].material.bending_scale == Approx(7.5));
    CHECK(all.garments[0].material.stretching_scale == Approx(1.25));
    CHECK(all.garments[0].material.bending_n_m[1][2] == Approx(m.bending_n_m[1][2]));
    CHECK(all.garments[0].material.density_kg_per_m2 == Approx(m.density_kg_per_m2));
    CHECK(all.garments[0].base_fabric == "gray-interlock");
    CHECK(all.garments[1].garment == "shorts");
    CHECK_FALSE(all.garments[1].supported);
    CHECK(all.garments[1].sizing.pants.h1 == Approx(93.25));

    const io::SavedRecovery one = io::read_recovery_folder(f.dir.string() + ":1");
    REQUIRE(one.garments.size() == 1);
    CHECK(one.garments[0].index == 1);
    CHECK(one.garments[0].type == garment::GarmentType::pants);
}

TEST_CASE("bad result folders are refused with the file and the field", "[io][recovery]") {
    Folder f;
    auto message = [](const std::string& spec) {
        try {
            io::read_recovery_folder(spec);
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THROWS_AS(io::read_recovery_folder((f.dir / "absent").string()), IoError);
    CHECK(message(f.dir.string()).find("neither result.json nor truth.json") != std::string::npos);

    const cloth::Material m = test_material();
    nlohmann::json g = {{"type", "skirt"},
                        {"sizing", io::to_json(sizing_of(garment::GarmentType::skirt))},
                        {"material", io::material_to_json(m, "gray-interlock")}};
    io::write_json_file(f.dir / "result.json", result_with(nlohmann::json::array({g})));
    CHECK(message(f.dir.string() + ":3").find("holds 1 garment(s)") != std::string::npos);

    nlohmann::json bad = g;
    bad["type"] = "cape";
    io::write_json_file(f.dir / "result.json", result_with(nlohmann::json::array({bad})));
    CHECK(message(f.dir.string()).find("field 'type'") != std::string::npos);

    bad = g;
    bad["material"]["bending_scale"] = -2;
    io::write_json_file(f.dir / "result.json", result_with(nlohmann::json::array({bad})));
    CHECK(message(f.dir.string()).find("'bending_scale' must be positive") != std::string::npos);

    bad = g;
    bad["material"]["bending"] = nlohmann::json::array({1, 2});
    io::write_json_file(f.dir / "result.json", result_with(nlohmann::json::array({bad})));
    CHECK(message(f.dir.string()).find("'bending' must be 3 rows") != std::string::npos);

    bad = g;
    bad["sizing"]["l1"] = "long";
    io::write_json_file(f.dir / "result.json", result_with(nlohmann::json::array({bad})));
    CHECK(message(f.dir.string()).find("l1") != std::string::npos);

    io::write_json_file(f.dir / "result.json", result_with(nlohmann::json::array()));
    CHECK(message(f.dir.string()).find("holds no garment") != std::string::npos);
}
