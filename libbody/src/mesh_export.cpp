// export_glb / export_obj / import_mesh. glTF goes through assimp's "glb2" exporter from an
// aiScene built here; OBJ is written directly (exact round trip of doubles).
#include <drape/body/model_io.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/vertex_normals.hpp>

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

namespace drape::body {

namespace {

void check_triangle_mesh(const char* fn, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    require(V.cols() == 3 && V.rows() >= 3, fn, ": V is ", V.rows(), " x ", V.cols(),
            ", expected #V x 3 with #V >= 3");
    require(V.allFinite(), fn, ": V has non-finite coordinates");
    require(F.cols() == 3 && F.rows() >= 1, fn, ": F is ", F.rows(), " x ", F.cols(),
            ", expected #F x 3 with #F >= 1");
    require(F.minCoeff() >= 0 && F.maxCoeff() < V.rows(), fn, ": F indexes vertices in [",
            F.minCoeff(), ", ", F.maxCoeff(), "], outside [0, ", V.rows(), ")");
}

/// Area-weighted vertex normals (unit; +Y for isolated vertices).
Eigen::MatrixXd vertex_normals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    core::VertexNormalOptions options;
    options.isolated = Eigen::Vector3d::UnitY();
    return core::vertex_normals(V, F, options);
}

aiMatrix4x4 to_ai(const Eigen::Isometry3d& T) {
    const Eigen::Matrix4d M = T.matrix();
    aiMatrix4x4 m;  // aiMatrix4x4 is row-major: a1..a4 is the first row
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m[static_cast<unsigned>(r)][static_cast<unsigned>(c)] = static_cast<ai_real>(M(r, c));
    return m;
}

aiVector3D to_ai(const Eigen::RowVector3d& p) {
    return aiVector3D(static_cast<ai_real>(p[0]), static_cast<ai_real>(p[1]), static_cast<ai_real>(p[2]));
}

/// Per vertex, the (at most) 4 largest skin weights, renormalised to sum to 1.
std::vector<std::vector<std::pair<int, double>>> top4_weights(const Eigen::SparseMatrix<double>& W) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> R = W;
    std::vector<std::vector<std::pair<int, double>>> out(static_cast<std::size_t>(R.rows()));
    for (Eigen::Index v = 0; v < R.rows(); ++v) {
        auto& w = out[static_cast<std::size_t>(v)];
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(R, v); it; ++it)
            if (it.value() > 0) w.emplace_back(static_cast<int>(it.col()), it.value());
        std::sort(w.begin(), w.end(), [](const auto& a, const auto& b) {
            return a.second != b.second ? a.second > b.second : a.first < b.first;
        });
        if (w.size() > 4) w.resize(4);
        double sum = 0;
        for (const auto& [j, x] : w) sum += x;
        require(sum > 0, "export_glb: vertex ", v, " has no positive skin weight");
        for (auto& jw : w) jw.second /= sum;
    }
    return out;
}

/// Node-local transforms reproducing forward_kinematics(): root local = root global,
/// child local = global(parent)^-1 * global(child).
std::array<Eigen::Isometry3d, kJointCount> local_transforms(const PosedSkeleton& sk) {
    std::array<Eigen::Isometry3d, kJointCount> local;
    for (int j = 0; j < kJointCount; ++j) {
        const int p = kJointParents[static_cast<std::size_t>(j)];
        local[static_cast<std::size_t>(j)] =
            p < 0 ? sk.global[static_cast<std::size_t>(j)]
                  : sk.global[static_cast<std::size_t>(p)].inverse() * sk.global[static_cast<std::size_t>(j)];
    }
    return local;
}

std::unique_ptr<aiScene> build_scene(const BodyModel& model, const ShapedBody& shaped,
                                     const Pose& pose) {
    const Eigen::MatrixXd& V = shaped.vertices;
    const Eigen::MatrixXi& F = model.faces;
    const PosedSkeleton sk = forward_kinematics(shaped.joints, pose);
    const auto local = local_transforms(sk);
    const auto weights = top4_weights(model.skin_weights);
    const Eigen::MatrixXd N = vertex_normals(V, F);

    auto scene = std::make_unique<aiScene>();
    scene->mNumMaterials = 1;
    scene->mMaterials = new aiMaterial*[1];
    scene->mMaterials[0] = new aiMaterial();
    const aiString material_name("body");
    scene->mMaterials[0]->AddProperty(&material_name, AI_MATKEY_NAME);

    scene->mNumMeshes = 1;
    scene->mMeshes = new aiMesh*[1];
    aiMesh* mesh = new aiMesh();
    scene->mMeshes[0] = mesh;
    mesh->mName = aiString(model.name.empty() ? std::string("body") : model.name);
    mesh->mMaterialIndex = 0;
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mNumVertices = static_cast<unsigned>(V.rows());
    mesh->mVertices = new aiVector3D[mesh->mNumVertices];
    mesh->mNormals = new aiVector3D[mesh->mNumVertices];
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
        mesh->mVertices[v] = to_ai(V.row(v));
        mesh->mNormals[v] = to_ai(N.row(v));
    }
    mesh->mNumFaces = static_cast<unsigned>(F.rows());
    mesh->mFaces = new aiFace[mesh->mNumFaces];
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        aiFace& face = mesh->mFaces[f];
        face.mNumIndices = 3;
        face.mIndices = new unsigned[3];
        for (int k = 0; k < 3; ++k) face.mIndices[k] = static_cast<unsigned>(F(f, k));
    }

    // Bones: joint frames are axis-aligned at rest, so the inverse bind matrix of joint j
    // is a pure translation by -rest_j.
    std::array<std::vector<aiVertexWeight>, kJointCount> bone_weights;
    for (std::size_t v = 0; v < weights.size(); ++v)
        for (const auto& [j, w] : weights[v])
            bone_weights[static_cast<std::size_t>(j)].emplace_back(static_cast<unsigned>(v), static_cast<ai_real>(w));
    mesh->mNumBones = kJointCount;
    mesh->mBones = new aiBone*[kJointCount];
    for (int j = 0; j < kJointCount; ++j) {
        aiBone* bone = new aiBone();
        mesh->mBones[j] = bone;
        bone->mName = aiString(std::string(kJointNames[static_cast<std::size_t>(j)]));
        Eigen::Isometry3d inverse_bind = Eigen::Isometry3d::Identity();
        inverse_bind.translation() = -shaped.joints.row(j).transpose();
        bone->mOffsetMatrix = to_ai(inverse_bind);
        const auto& bw = bone_weights[static_cast<std::size_t>(j)];
        bone->mNumWeights = static_cast<unsigned>(bw.size());
        if (!bw.empty()) {
            bone->mWeights = new aiVertexWeight[bw.size()];
            std::copy(bw.begin(), bw.end(), bone->mWeights);
        }
    }

    // Nodes: root "drape_body" holds the mesh node and the skeleton.
    aiNode* root = new aiNode("drape_body");
    scene->mRootNode = root;
    std::array<aiNode*, kJointCount> joint_nodes{};
    for (int j = 0; j < kJointCount; ++j) {
        joint_nodes[static_cast<std::size_t>(j)] = new aiNode(std::string(kJointNames[static_cast<std::size_t>(j)]));
        joint_nodes[static_cast<std::size_t>(j)]->mTransformation = to_ai(local[static_cast<std::size_t>(j)]);
    }
    std::array<std::vector<aiNode*>, kJointCount> children;
    for (int j = 1; j < kJointCount; ++j)
        children[static_cast<std::size_t>(kJointParents[static_cast<std::size_t>(j)])].push_back(
            joint_nodes[static_cast<std::size_t>(j)]);
    for (int j = 0; j < kJointCount; ++j) {
        auto& c = children[static_cast<std::size_t>(j)];
        if (c.empty()) continue;
        joint_nodes[static_cast<std::size_t>(j)]->addChildren(static_cast<unsigned>(c.size()), c.data());
    }
    aiNode* mesh_node = new aiNode("body_mesh");
    mesh_node->mNumMeshes = 1;
    mesh_node->mMeshes = new unsigned[1]{0};
    std::array<aiNode*, 2> top = {mesh_node, joint_nodes[0]};
    root->addChildren(2, top.data());
    return scene;
}

}  // namespace

void export_glb(const std::filesystem::path& path, const BodyModel& model,
                const ShapedBody& shaped, const Pose& pose) {
    const Eigen::Index nv = model.template_vertices.rows();
    require(shaped.vertices.rows() == nv && shaped.vertices.cols() == 3, "export_glb: shaped.vertices is ",
            shaped.vertices.rows(), " x ", shaped.vertices.cols(), ", expected ", nv,
            " x 3 (the model's vertex count)");
    require(model.skin_weights.rows() == nv && model.skin_weights.cols() == kJointCount,
            "export_glb: model.skin_weights is ", model.skin_weights.rows(), " x ",
            model.skin_weights.cols(), ", expected #V x 22");
    require(shaped.joints.allFinite(), "export_glb: shaped.joints has non-finite values");
    check_triangle_mesh("export_glb", shaped.vertices, model.faces);
    std::unique_ptr<aiScene> scene = build_scene(model, shaped, pose);
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        Assimp::Exporter exporter;
        if (exporter.Export(scene.get(), "glb2", tmp.string()) != aiReturn_SUCCESS)
            throw IoError("cannot write '" + path.string() + "': " + exporter.GetErrorString());
    });
}

void export_obj(const std::filesystem::path& path, const Eigen::MatrixXd& V,
                const Eigen::MatrixXi& F) {
    check_triangle_mesh("export_obj", V, F);
    const Eigen::MatrixXd N = vertex_normals(V, F);
    std::string text = "# drape mesh: " + std::to_string(V.rows()) + " vertices, " +
                       std::to_string(F.rows()) + " triangles (metres)\n";
    text.reserve(static_cast<std::size_t>(V.rows()) * 120 + static_cast<std::size_t>(F.rows()) * 40);
    char buf[32];
    // to_chars: shortest exact representation, independent of the C locale.
    auto put_row = [&](const char* tag, const Eigen::RowVector3d& p) {
        text += tag;
        for (int d = 0; d < 3; ++d) {
            text += ' ';
            const auto r = std::to_chars(buf, buf + sizeof(buf), p[d]);
            text.append(buf, r.ptr);
        }
        text += '\n';
    };
    for (Eigen::Index v = 0; v < V.rows(); ++v) put_row("v", V.row(v));
    for (Eigen::Index v = 0; v < V.rows(); ++v) put_row("vn", N.row(v));
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
        text += 'f';
        for (int k = 0; k < 3; ++k) {
            const std::string i = std::to_string(F(f, k) + 1);
            text += ' ' + i + "//" + i;
        }
        text += '\n';
    }
    write_text_atomically(path, text);
}

TriangleMesh import_mesh(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw IoError("cannot read mesh '" + path.string() + "': no such file");
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate |
                                                                aiProcess_JoinIdenticalVertices);
    if (!scene)
        throw IoError("cannot read mesh '" + path.string() + "': " + importer.GetErrorString());

    // Merge every mesh instance in world coordinates, welding exactly equal positions.
    std::map<std::array<double, 3>, int> index_of;
    std::vector<std::array<double, 3>> vertices;
    std::vector<std::array<int, 3>> faces;
    struct Item {
        const aiNode* node;
        aiMatrix4x4 parent;
    };
    std::vector<Item> stack;
    if (scene->mRootNode) stack.push_back({scene->mRootNode, aiMatrix4x4()});
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        const aiMatrix4x4 world = item.parent * item.node->mTransformation;
        for (unsigned c = 0; c < item.node->mNumChildren; ++c) stack.push_back({item.node->mChildren[c], world});
        for (unsigned k = 0; k < item.node->mNumMeshes; ++k) {
            if (item.node->mMeshes[k] >= scene->mNumMeshes) continue;
            const aiMesh* mesh = scene->mMeshes[item.node->mMeshes[k]];
            std::vector<int> remap(mesh->mNumVertices);
            for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
                const aiVector3D p = world * mesh->mVertices[v];
                const std::array<double, 3> key = {p.x, p.y, p.z};
                auto [it, inserted] = index_of.emplace(key, static_cast<int>(vertices.size()));
                if (inserted) vertices.push_back(key);
                remap[v] = it->second;
            }
            for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
                const aiFace& face = mesh->mFaces[f];
                if (face.mNumIndices != 3) continue;  // points and lines
                const std::array<int, 3> t = {remap[face.mIndices[0]], remap[face.mIndices[1]],
                                              remap[face.mIndices[2]]};
                if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // degenerate
                faces.push_back(t);
            }
        }
    }
    if (faces.empty())
        throw InvalidInput("import_mesh: '" + path.string() + "' holds no triangles");
    TriangleMesh out;
    out.V.resize(static_cast<Eigen::Index>(vertices.size()), 3);
    for (std::size_t v = 0; v < vertices.size(); ++v)
        for (int d = 0; d < 3; ++d) out.V(static_cast<Eigen::Index>(v), d) = vertices[v][static_cast<std::size_t>(d)];
    out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f)
        for (int k = 0; k < 3; ++k) out.F(static_cast<Eigen::Index>(f), k) = faces[f][static_cast<std::size_t>(k)];
    return out;
}

}  // namespace drape::body
