// write_garment_obj / write_garment_glb: the glb re-imports through assimp with the mesh's
// vertex and face counts, positions and pattern uv; the OBJ has a group per panel.
#include <drape/core/errors.hpp>
#include <drape/garment/garment_export.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/tshirt.hpp>

#include "test_paths.hpp"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

using namespace drape::garment;

namespace {

struct MeshedTShirt {
    Pattern pattern = make_tshirt(TShirtSizing{});
    GarmentMesh mesh;
    Eigen::MatrixX3d X;
    MeshedTShirt() {
        MeshOptions o;
        o.target_edge_cm = 6.0;
        REQUIRE(mesh_pattern(pattern, o, mesh).usable());
        // A non-planar state: the flat layout bent about the y axis (metres).
        X.resize(mesh.cloth.vertex_count(), 3);
        for (int v = 0; v < mesh.cloth.vertex_count(); ++v) {
            const double u = 0.01 * mesh.cloth.pattern(v, 0), w = 0.01 * mesh.cloth.pattern(v, 1);
            X.row(v) << std::sin(u), w, std::cos(u) - 1;
        }
    }
};

std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("garment glb: re-imports with the same vertices, faces, positions and uv", "[garment][export]") {
    const MeshedTShirt t;
    const auto dir = drape::test::scratch_dir("garment_glb");
    write_garment_glb(dir / "garment.glb", t.mesh, t.X);
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile((dir / "garment.glb").string(), 0);
    REQUIRE(scene != nullptr);
    REQUIRE(scene->mNumMeshes == 1);
    const aiMesh* m = scene->mMeshes[0];
    REQUIRE(m->mNumVertices == unsigned(t.mesh.cloth.vertex_count()));
    REQUIRE(m->mNumFaces == unsigned(t.mesh.cloth.face_count()));
    REQUIRE(m->HasTextureCoords(0));
    double pos_err = 0, uv_err = 0;
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
        for (int k = 0; k < 3; ++k) pos_err = std::max(pos_err, std::abs(m->mVertices[v][unsigned(k)] - t.X(v, k)));
        // assimp's importer turns glTF's downward v back into the pattern's upward v.
        uv_err = std::max({uv_err, std::abs(m->mTextureCoords[0][v].x - t.mesh.uv(v, 0)),
                           std::abs(m->mTextureCoords[0][v].y - t.mesh.uv(v, 1))});
    }
    CHECK(pos_err < 1e-6);
    CHECK(uv_err < 1e-6);
    bool same_faces = true;
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
        REQUIRE(m->mFaces[f].mNumIndices == 3);
        for (unsigned k = 0; k < 3; ++k) same_faces &= int(m->mFaces[f].mIndices[k]) == t.mesh.cloth.faces(f, k);
    }
    CHECK(same_faces);
    CHECK_THROWS_AS(write_garment_glb(dir / "bad.glb", t.mesh, t.X.topRows(3)), drape::InvalidInput);
}

TEST_CASE("garment obj: positions, pattern uv and a group per panel", "[garment][export]") {
    const MeshedTShirt t;
    const auto dir = drape::test::scratch_dir("garment_obj");
    write_garment_obj(dir / "garment.obj", t.pattern, t.mesh, t.X, "test state");
    std::istringstream in(read_text(dir / "garment.obj"));
    std::string line;
    int v = 0, vt = 0, f = 0;
    std::vector<std::string> groups;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) == 0) ++v;
        if (line.rfind("vt ", 0) == 0) ++vt;
        if (line.rfind("f ", 0) == 0) ++f;
        if (line.rfind("g ", 0) == 0) groups.push_back(line.substr(2));
    }
    CHECK(v == t.mesh.cloth.vertex_count());
    CHECK(vt == t.mesh.cloth.vertex_count());
    CHECK(f == t.mesh.cloth.face_count());
    CHECK(groups == std::vector<std::string>{"front", "back", "left_sleeve", "right_sleeve"});
    CHECK_THROWS_AS(write_garment_obj(dir / "bad.obj", t.pattern, t.mesh, t.X.topRows(3), "x"), drape::InvalidInput);
}
