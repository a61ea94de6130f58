// write_garment_obj / write_garment_glb. glTF goes through assimp's "glb2" exporter from an
// aiScene built here (as body::export_glb); OBJ is written directly.
#include <drape/garment/garment_export.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <memory>
#include <sstream>

namespace drape::garment {

namespace {

void check_positions(const char* who, const GarmentMesh& mesh, const Eigen::MatrixX3d& positions) {
    require(positions.rows() == mesh.cloth.vertex_count(), who, ": positions have ", positions.rows(),
            " rows, the mesh has ", mesh.cloth.vertex_count(), " vertices");
    require(mesh.uv.rows() >= positions.rows(), who, ": the mesh has ", mesh.uv.rows(), " uv rows for ",
            positions.rows(), " vertices");
    require(positions.allFinite(), who, ": positions are not finite");
}

// One mesh, one default material, one node: what the glb2 exporter needs.
std::unique_ptr<aiScene> garment_scene(const GarmentMesh& m, const Eigen::MatrixX3d& X) {
    auto scene = std::make_unique<aiScene>();
    scene->mNumMaterials = 1;
    scene->mMaterials = new aiMaterial*[1];
    scene->mMaterials[0] = new aiMaterial();
    const aiString material_name("garment");
    scene->mMaterials[0]->AddProperty(&material_name, AI_MATKEY_NAME);

    scene->mNumMeshes = 1;
    scene->mMeshes = new aiMesh*[1];
    aiMesh* mesh = new aiMesh();
    scene->mMeshes[0] = mesh;
    mesh->mName = aiString("garment");
    mesh->mMaterialIndex = 0;
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumVertices = static_cast<unsigned>(X.rows());
    mesh->mVertices = new aiVector3D[mesh->mNumVertices];
    mesh->mTextureCoords[0] = new aiVector3D[mesh->mNumVertices];
    mesh->mNumUVComponents[0] = 2;
    for (Eigen::Index v = 0; v < X.rows(); ++v) {
        mesh->mVertices[v] = aiVector3D(ai_real(X(v, 0)), ai_real(X(v, 1)), ai_real(X(v, 2)));
        // assimp's v runs upwards, as the pattern's; its glTF exporter flips it.
        mesh->mTextureCoords[0][v] = aiVector3D(ai_real(m.uv(v, 0)), ai_real(m.uv(v, 1)), 0);
    }
    const Eigen::MatrixX3i& F = m.cloth.faces;
    mesh->mNumFaces = static_cast<unsigned>(F.rows());
    mesh->mFaces = new aiFace[mesh->mNumFaces];
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        aiFace& face = mesh->mFaces[f];
        face.mNumIndices = 3;
        face.mIndices = new unsigned[3];
        for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(F(f, k));
    }
    scene->mRootNode = new aiNode("garment");
    scene->mRootNode->mNumMeshes = 1;
    scene->mRootNode->mMeshes = new unsigned[1]{0};
    return scene;
}

}  // namespace

void write_garment_obj(const std::filesystem::path& path, const Pattern& pattern, const GarmentMesh& m,
                       const Eigen::MatrixX3d& positions, const std::string& what) {
    check_positions("write_garment_obj", m, positions);
    std::ostringstream os;
    os << "# drape '" << pattern.name << "': " << what << ", metres; vt = pattern uv\n";
    for (Eigen::Index v = 0; v < positions.rows(); ++v)
        os << "v " << positions(v, 0) << " " << positions(v, 1) << " " << positions(v, 2) << "\n";
    for (int v = 0; v < m.cloth.vertex_count(); ++v) os << "vt " << m.uv(v, 0) << " " << m.uv(v, 1) << "\n";
    int group = -1;
    for (int f = 0; f < m.cloth.face_count(); ++f) {
        const int p = m.panel_of_vertex(m.cloth.faces(f, 0));
        if (p != group) os << "g " << pattern.panels[static_cast<std::size_t>(group = p)].name << "\n";
        os << "f";
        for (int k = 0; k < 3; ++k) os << " " << m.cloth.faces(f, k) + 1 << "/" << m.cloth.faces(f, k) + 1;
        os << "\n";
    }
    write_text_atomically(path, os.str());
}

void write_garment_glb(const std::filesystem::path& path, const GarmentMesh& m, const Eigen::MatrixX3d& positions) {
    check_positions("write_garment_glb", m, positions);
    const std::unique_ptr<aiScene> scene = garment_scene(m, positions);
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        Assimp::Exporter exporter;
        if (exporter.Export(scene.get(), "glb2", tmp.string()) != aiReturn_SUCCESS)
            throw IoError("cannot write '" + path.string() + "': " + exporter.GetErrorString());
    });
}

}  // namespace drape::garment
