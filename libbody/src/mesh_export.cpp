// export_glb / export_obj / import_mesh. glTF is written by drape::gltf (write_glb) from the
// scene built here; OBJ is written directly (exact round trip of doubles); import_mesh reads
// any format through assimp.
#include <drape/body/model_io.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>
#include <drape/core/vertex_normals.hpp>
#include <drape/gltf/glb_writer.hpp>

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

/// The rigged body as a glTF scene: root "drape_body" holding the mesh node "body_mesh"
/// (rest vertices, skinned) and the skeleton (joint nodes posed by their local transforms).
gltf::GlbScene build_scene(const BodyModel& model, const ShapedBody& shaped, const Pose& pose) {
    const PosedSkeleton sk = forward_kinematics(shaped.joints, pose);
    const auto local = local_transforms(sk);
    gltf::GlbScene scene;
    scene.root_name = "drape_body";
    gltf::GlbMesh mesh;
    mesh.mesh_name = model.name.empty() ? std::string("body") : model.name;
    mesh.node_name = "body_mesh";
    mesh.material_name = "body";
    mesh.V = shaped.vertices;
    mesh.F = model.faces;
    mesh.N = vertex_normals(mesh.V, mesh.F);
    mesh.skin = top4_weights(model.skin_weights);
    scene.meshes.push_back(std::move(mesh));
    // Joint frames are axis-aligned at rest, so the inverse bind matrix of joint j is a
    // pure translation by -rest_j.
    gltf::GlbSkeleton& skeleton = scene.skeleton;
    for (int j = 0; j < kJointCount; ++j) {
        const auto k = static_cast<std::size_t>(j);
        skeleton.names.emplace_back(kJointNames[k]);
        skeleton.parents.push_back(kJointParents[k]);
        skeleton.local.push_back(local[k]);
        Eigen::Isometry3d inverse_bind = Eigen::Isometry3d::Identity();
        inverse_bind.translation() = -shaped.joints.row(j).transpose();
        skeleton.inverse_bind.push_back(inverse_bind);
    }
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
    gltf::write_glb(path, build_scene(model, shaped, pose));
}

void export_animated_glb(const std::filesystem::path& path, const BodyModel& model, const ShapedBody& shaped,
                         const Motion& motion, const std::vector<FrameMesh>& meshes) {
    std::string why;
    require(motion.is_valid(&why), "export_animated_glb: motion: ", why);
    const Eigen::Index nv = model.template_vertices.rows();
    require(shaped.vertices.rows() == nv && shaped.vertices.cols() == 3, "export_animated_glb: shaped.vertices is ",
            shaped.vertices.rows(), " x ", shaped.vertices.cols(), ", expected ", nv, " x 3");
    check_triangle_mesh("export_animated_glb", shaped.vertices, model.faces);
    gltf::GlbScene scene = build_scene(model, shaped, motion.frames.front());
    gltf::GlbAnimation animation;
    animation.name = "motion";
    animation.joint_local.assign(kJointCount, {});
    for (std::size_t k = 0; k < motion.frames.size(); ++k) {
        animation.times_s.push_back(double(k) / motion.fps);
        const auto local = local_transforms(forward_kinematics(shaped.joints, motion.frames[k]));
        for (int j = 0; j < kJointCount; ++j)
            animation.joint_local[std::size_t(j)].push_back(local[std::size_t(j)]);
    }
    for (const FrameMesh& m : meshes) {
        require(m.frames.size() == motion.frames.size(), "export_animated_glb: mesh '", m.name, "' has ",
                m.frames.size(), " frames, the motion ", motion.frames.size());
        gltf::GlbMesh g;
        g.mesh_name = m.name;
        g.node_name = m.name;
        g.material_name = m.name;
        g.V = m.frames.front();
        g.F = m.F;
        g.N = vertex_normals(g.V, g.F);
        g.UV = m.UV;
        g.base_colour_linear = m.colour_linear;
        g.morph_targets = m.frames;
        scene.meshes.push_back(std::move(g));
    }
    scene.animation = std::move(animation);
    gltf::write_glb(path, scene);
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
    const auto bytes = std::filesystem::file_size(path, ec);
    if (ec) throw IoError("cannot read mesh '" + path.string() + "': " + ec.message());
    require(static_cast<std::int64_t>(bytes) <= limits::kMaxMeshFileBytes, "mesh '", path.string(),
            "' is too large: ", bytes, " bytes (limit ", limits::kMaxMeshFileBytes, ", docs/hardening.md)");
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_Triangulate |
                                                                aiProcess_JoinIdenticalVertices);
    if (!scene)
        throw IoError("cannot read mesh '" + path.string() + "': " + importer.GetErrorString());
    std::int64_t vertex_total = 0;
    for (unsigned k = 0; k < scene->mNumMeshes; ++k) vertex_total += scene->mMeshes[k]->mNumVertices;
    require(vertex_total <= limits::kMaxMeshVertices, "mesh '", path.string(), "' has ", vertex_total,
            " vertices, more than the limit of ", limits::kMaxMeshVertices, " (docs/hardening.md)");

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
