// write_outfit_glb: re-imports through assimp with each mesh's vertex and face counts,
// positions, uv, node names and distinct colours; the Khronos glTF-Validator (when
// installed) reports no error.
#include <drape/core/errors.hpp>
#include <drape/recover/outfit_glb.hpp>

#include "outfit_fixture.hpp"
#include "run_command.hpp"
#include "test_paths.hpp"

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/scene.h>
#include <catch2/catch.hpp>

#include <map>

using namespace drape;

namespace {

/// The rectangle outfit with the garments subdivided into a grid (more than 4 vertices),
/// so that counts are not trivially equal.
recover::OutfitMeshes grid_outfit() {
    recover::OutfitMeshes o = test::rectangle_outfit();
    recover::OutfitGarment& g = o.garments[1];
    const int n = 9;
    g.V.resize(n * n, 3);
    g.UV.resize(n * n, 2);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            g.V.row(i * n + j) << -0.8 + 1.6 * j / (n - 1), 0.2 + 0.7 * i / (n - 1), -0.1 + 0.01 * ((i + j) % 3);
            g.UV.row(i * n + j) << 0.05 * j, 0.04 * i;
        }
    g.F.resize(2 * (n - 1) * (n - 1), 3);
    int f = 0;
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const int a = i * n + j;
            g.F.row(f++) << a, a + 1, a + n + 1;
            g.F.row(f++) << a, a + n + 1, a + n;
        }
    return o;
}

struct Imported {
    const aiMesh* mesh = nullptr;
    aiColor4D colour;
};

/// Node name -> its mesh (and material colour), for the nodes directly under the root.
std::map<std::string, Imported> meshes_by_node(const aiScene* scene) {
    std::map<std::string, Imported> out;
    for (unsigned c = 0; c < scene->mRootNode->mNumChildren; ++c) {
        const aiNode* node = scene->mRootNode->mChildren[c];
        REQUIRE(node->mNumMeshes == 1);
        Imported im;
        im.mesh = scene->mMeshes[node->mMeshes[0]];
        scene->mMaterials[im.mesh->mMaterialIndex]->Get(AI_MATKEY_BASE_COLOR, im.colour);
        out[node->mName.C_Str()] = im;
    }
    return out;
}

}  // namespace

TEST_CASE("outfit glb: body and garments re-import with their counts, positions, uv, names and colours",
          "[recover][glb]") {
    const recover::OutfitMeshes outfit = grid_outfit();
    const auto dir = test::scratch_dir("recover_outfit_glb");
    const auto path = dir / "outfit.glb";
    recover::write_outfit_glb(path, outfit);

    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), 0);
    REQUIRE(scene != nullptr);
    CHECK(std::string(scene->mRootNode->mName.C_Str()) == "outfit");
    const auto by_node = meshes_by_node(scene);
    REQUIRE(by_node.size() == 3);
    REQUIRE(by_node.count("body") == 1);
    REQUIRE(by_node.count("garment_0") == 1);
    REQUIRE(by_node.count("garment_1") == 1);
    const std::array<std::pair<const char*, const Eigen::MatrixXd*>, 3> expect = {
        {{"body", &outfit.body_V}, {"garment_0", &outfit.garments[0].V}, {"garment_1", &outfit.garments[1].V}}};
    const std::array<const Eigen::MatrixXi*, 3> faces = {&outfit.body_F, &outfit.garments[0].F, &outfit.garments[1].F};
    for (std::size_t i = 0; i < 3; ++i) {
        const aiMesh* m = by_node.at(expect[i].first).mesh;
        const Eigen::MatrixXd& V = *expect[i].second;
        INFO(expect[i].first);
        REQUIRE(m->mNumVertices == unsigned(V.rows()));
        REQUIRE(m->mNumFaces == unsigned(faces[i]->rows()));
        CHECK(m->HasNormals());
        double err = 0;
        for (unsigned v = 0; v < m->mNumVertices; ++v)
            for (unsigned k = 0; k < 3; ++k) err = std::max(err, std::abs(m->mVertices[v][k] - V(v, k)));
        CHECK(err < 1e-6);
        bool same_faces = true;
        for (unsigned f = 0; f < m->mNumFaces; ++f)
            for (unsigned k = 0; k < 3; ++k) same_faces &= int(m->mFaces[f].mIndices[k]) == (*faces[i])(f, k);
        CHECK(same_faces);
    }
    CHECK(std::string(by_node.at("garment_0").mesh->mName.C_Str()) == "skirt");
    CHECK_FALSE(by_node.at("body").mesh->HasTextureCoords(0));
    const aiMesh* tshirt = by_node.at("garment_1").mesh;
    REQUIRE(tshirt->HasTextureCoords(0));
    double uv_err = 0;
    for (unsigned v = 0; v < tshirt->mNumVertices; ++v)
        uv_err = std::max({uv_err, std::abs(tshirt->mTextureCoords[0][v].x - outfit.garments[1].UV(v, 0)),
                           std::abs(tshirt->mTextureCoords[0][v].y - outfit.garments[1].UV(v, 1))});
    CHECK(uv_err < 1e-6);
    // Three different colours: a skin tone (red > blue), then the preview's blue garment.
    const aiColor4D body = by_node.at("body").colour, skirt = by_node.at("garment_0").colour,
                    shirt = by_node.at("garment_1").colour;
    CHECK(body.r > body.b);
    CHECK(skirt.b > skirt.r);
    CHECK_FALSE((skirt.r == shirt.r && skirt.g == shirt.g && skirt.b == shirt.b));

    recover::OutfitMeshes bad = outfit;
    bad.garments[1].class_id = 300;
    CHECK_THROWS_AS(recover::write_outfit_glb(dir / "bad.glb", bad), InvalidInput);
    CHECK_FALSE(std::filesystem::exists(dir / "bad.glb"));
    CHECK_THROWS_AS(recover::write_outfit_glb(dir / "no_such_dir" / "x.glb", outfit), IoError);
}

TEST_CASE("outfit glb: the Khronos glTF-Validator reports no error", "[recover][glb]") {
    const auto dir = test::scratch_dir("recover_outfit_glb_validator");
    const auto path = dir / "outfit.glb";
    recover::write_outfit_glb(path, grid_outfit());
    if (test::run_command("command -v node").exit_code != 0) {
        WARN("skipped: node is not installed (the glTF-Validator runs on node)");
        return;
    }
    const auto script = test::source_dir() / "tests" / "recover" / "validate_gltf.js";
    const test::CommandResult r =
        test::run_command("NODE_PATH=\"$(npm root -g 2>/dev/null)\" node \"" + script.string() + "\" \"" +
                          path.string() + "\"");
    if (r.exit_code == 77) {
        WARN("skipped: the npm package gltf-validator is not installed (npm install -g gltf-validator)");
        return;
    }
    INFO(r.out);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains("\"numErrors\": 0"));
}
