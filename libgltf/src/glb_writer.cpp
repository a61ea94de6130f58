// write_glb: an aiScene built from GlbScene, exported by assimp's "glb2" exporter.
#include <drape/gltf/glb_writer.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace drape::gltf {

namespace {

aiMatrix4x4 to_ai(const Eigen::Isometry3d& T) {
    const Eigen::Matrix4d M = T.matrix();
    aiMatrix4x4 m;  // aiMatrix4x4 is row-major: a1..a4 is the first row
    for (unsigned r = 0; r < 4; ++r)
        for (unsigned c = 0; c < 4; ++c) m[r][c] = static_cast<ai_real>(M(r, c));
    return m;
}

aiVector3D to_ai(double x, double y, double z) {
    return aiVector3D(static_cast<ai_real>(x), static_cast<ai_real>(y), static_cast<ai_real>(z));
}

void check_skeleton(const GlbSkeleton& s) {
    const std::size_t n = s.names.size();
    require(s.parents.size() == n && s.local.size() == n && s.inverse_bind.size() == n, "write_glb: the skeleton has ",
            n, " names but ", s.parents.size(), " parents, ", s.local.size(), " local and ", s.inverse_bind.size(),
            " inverse bind transforms");
    for (std::size_t j = 0; j < n; ++j) {
        require(s.parents[j] >= -1 && s.parents[j] < static_cast<int>(j), "write_glb: skeleton joint ", j, " '",
                s.names[j], "' has parent ", s.parents[j], ", expected -1 or an earlier joint");
        require(s.local[j].matrix().allFinite() && s.inverse_bind[j].matrix().allFinite(), "write_glb: skeleton joint ",
                j, " '", s.names[j], "' has non-finite transforms");
    }
}

void check_mesh(const GlbMesh& m, std::size_t index, const GlbSkeleton& skeleton) {
    const std::string who = "write_glb: mesh " + std::to_string(index) + " '" + m.mesh_name + "'";
    require(m.V.cols() == 3 && m.V.rows() >= 1, who, ": V is ", m.V.rows(), " x ", m.V.cols(), ", expected #V x 3");
    require(m.V.allFinite(), who, ": V has non-finite positions");
    require(m.F.cols() == 3 && m.F.rows() >= 1, who, ": F is ", m.F.rows(), " x ", m.F.cols(), ", expected #F x 3");
    require(m.F.minCoeff() >= 0 && m.F.maxCoeff() < m.V.rows(), who, ": F indexes vertices in [", m.F.minCoeff(),
            ", ", m.F.maxCoeff(), "], outside [0, ", m.V.rows(), ")");
    require(m.N.size() == 0 || (m.N.rows() == m.V.rows() && m.N.cols() == 3 && m.N.allFinite()), who, ": N is ",
            m.N.rows(), " x ", m.N.cols(), ", expected empty or ", m.V.rows(), " x 3 finite");
    require(m.UV.size() == 0 || (m.UV.rows() == m.V.rows() && m.UV.cols() == 2 && m.UV.allFinite()), who,
            ": UV is ", m.UV.rows(), " x ", m.UV.cols(), ", expected empty or ", m.V.rows(), " x 2 finite");
    require(!m.base_colour_linear || (m.base_colour_linear->allFinite() && m.base_colour_linear->minCoeff() >= 0.0 &&
                                      m.base_colour_linear->maxCoeff() <= 1.0),
            who, ": the base colour must be in [0, 1]");
    if (m.skin.empty()) return;
    require(!skeleton.empty(), who, ": skinned, but the scene has no skeleton");
    require(m.skin.size() == static_cast<std::size_t>(m.V.rows()), who, ": skin has ", m.skin.size(),
            " vertices, V has ", m.V.rows());
    const int joints = static_cast<int>(skeleton.names.size());
    for (std::size_t v = 0; v < m.skin.size(); ++v)
        for (const auto& [j, w] : m.skin[v])
            require(j >= 0 && j < joints && w >= 0.0 && w <= 1.0, who, ": vertex ", v, " has skin weight ", w,
                    " on joint ", j, ", expected a joint in [0, ", joints, ") and a weight in [0, 1]");
}

aiMaterial* make_material(const GlbMesh& m) {
    auto* material = new aiMaterial();
    const aiString name(m.material_name);
    material->AddProperty(&name, AI_MATKEY_NAME);
    if (m.base_colour_linear) {
        const Eigen::Vector3d& c = *m.base_colour_linear;
        const aiColor4D colour(static_cast<ai_real>(c.x()), static_cast<ai_real>(c.y()), static_cast<ai_real>(c.z()), 1);
        material->AddProperty(&colour, 1, AI_MATKEY_BASE_COLOR);
        material->AddProperty(&colour, 1, AI_MATKEY_COLOR_DIFFUSE);
    }
    return material;
}

aiMesh* make_mesh(const GlbMesh& m, unsigned material, const GlbSkeleton& skeleton) {
    auto* mesh = new aiMesh();
    mesh->mName = aiString(m.mesh_name);
    mesh->mMaterialIndex = material;
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumVertices = static_cast<unsigned>(m.V.rows());
    mesh->mVertices = new aiVector3D[mesh->mNumVertices];
    if (m.N.size() > 0) mesh->mNormals = new aiVector3D[mesh->mNumVertices];
    if (m.UV.size() > 0) {
        mesh->mTextureCoords[0] = new aiVector3D[mesh->mNumVertices];
        mesh->mNumUVComponents[0] = 2;
    }
    for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
        mesh->mVertices[v] = to_ai(m.V(v, 0), m.V(v, 1), m.V(v, 2));
        if (m.N.size() > 0) mesh->mNormals[v] = to_ai(m.N(v, 0), m.N(v, 1), m.N(v, 2));
        // assimp's v runs upwards, as the pattern's; its glTF exporter flips it.
        if (m.UV.size() > 0) mesh->mTextureCoords[0][v] = to_ai(m.UV(v, 0), m.UV(v, 1), 0.0);
    }
    mesh->mNumFaces = static_cast<unsigned>(m.F.rows());
    mesh->mFaces = new aiFace[mesh->mNumFaces];
    for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
        aiFace& face = mesh->mFaces[f];
        face.mNumIndices = 3;
        face.mIndices = new unsigned[3];
        for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(m.F(f, k));
    }
    if (m.skin.empty()) return mesh;
    // One bone per joint (also those without weights), named as the joint's node.
    const std::size_t joints = skeleton.names.size();
    std::vector<std::vector<aiVertexWeight>> bone_weights(joints);
    for (std::size_t v = 0; v < m.skin.size(); ++v)
        for (const auto& [j, w] : m.skin[v])
            bone_weights[static_cast<std::size_t>(j)].emplace_back(static_cast<unsigned>(v), static_cast<ai_real>(w));
    mesh->mNumBones = static_cast<unsigned>(joints);
    mesh->mBones = new aiBone*[joints];
    for (std::size_t j = 0; j < joints; ++j) {
        auto* bone = new aiBone();
        mesh->mBones[j] = bone;
        bone->mName = aiString(skeleton.names[j]);
        bone->mOffsetMatrix = to_ai(skeleton.inverse_bind[j]);
        const auto& bw = bone_weights[j];
        bone->mNumWeights = static_cast<unsigned>(bw.size());
        if (!bw.empty()) {
            bone->mWeights = new aiVertexWeight[bw.size()];
            std::copy(bw.begin(), bw.end(), bone->mWeights);
        }
    }
    return mesh;
}

std::unique_ptr<aiScene> make_scene(const GlbScene& in) {
    auto scene = std::make_unique<aiScene>();
    const unsigned n = static_cast<unsigned>(in.meshes.size());
    scene->mNumMaterials = n;
    scene->mMaterials = new aiMaterial*[n];
    scene->mNumMeshes = n;
    scene->mMeshes = new aiMesh*[n];
    for (unsigned i = 0; i < n; ++i) {
        scene->mMaterials[i] = make_material(in.meshes[i]);
        scene->mMeshes[i] = make_mesh(in.meshes[i], i, in.skeleton);
    }
    auto* root = new aiNode(in.root_name);
    scene->mRootNode = root;
    std::vector<unsigned> at_root;
    std::vector<aiNode*> children;
    for (unsigned i = 0; i < n; ++i) {
        if (in.meshes[i].node_name.empty()) {
            at_root.push_back(i);
            continue;
        }
        auto* node = new aiNode(in.meshes[i].node_name);
        node->mNumMeshes = 1;
        node->mMeshes = new unsigned[1]{i};
        children.push_back(node);
    }
    if (!at_root.empty()) {
        root->mNumMeshes = static_cast<unsigned>(at_root.size());
        root->mMeshes = new unsigned[at_root.size()];
        std::copy(at_root.begin(), at_root.end(), root->mMeshes);
    }
    const GlbSkeleton& sk = in.skeleton;
    std::vector<aiNode*> joints(sk.names.size());
    for (std::size_t j = 0; j < joints.size(); ++j) {
        joints[j] = new aiNode(sk.names[j]);
        joints[j]->mTransformation = to_ai(sk.local[j]);
    }
    for (std::size_t j = 0; j < joints.size(); ++j)
        if (sk.parents[j] < 0) children.push_back(joints[j]);
    for (std::size_t p = 0; p < joints.size(); ++p) {
        std::vector<aiNode*> under;  // joint p's children, in joint order
        for (std::size_t j = p + 1; j < joints.size(); ++j)
            if (sk.parents[j] == static_cast<int>(p)) under.push_back(joints[j]);
        if (!under.empty()) joints[p]->addChildren(static_cast<unsigned>(under.size()), under.data());
    }
    if (!children.empty()) root->addChildren(static_cast<unsigned>(children.size()), children.data());
    return scene;
}

}  // namespace

void write_glb(const std::filesystem::path& path, const GlbScene& scene) {
    require(!scene.meshes.empty(), "write_glb: the scene has no mesh");
    check_skeleton(scene.skeleton);
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) check_mesh(scene.meshes[i], i, scene.skeleton);
    const std::unique_ptr<aiScene> ai = make_scene(scene);
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        Assimp::Exporter exporter;
        if (exporter.Export(ai.get(), "glb2", tmp.string()) != aiReturn_SUCCESS)
            throw IoError("cannot write '" + path.string() + "': " + exporter.GetErrorString());
    });
}

}  // namespace drape::gltf
