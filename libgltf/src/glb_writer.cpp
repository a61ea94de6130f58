// write_glb: an aiScene built from GlbScene, exported by assimp's "glb2" exporter.
#include <drape/gltf/glb_writer.hpp>

#include <drape/core/atomic_file.hpp>
#include <drape/core/errors.hpp>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

namespace drape::gltf {

namespace {

// Animation key times are written in ticks of 1 ms (assimp's exporter divides by this).
constexpr double kTicksPerSecond = 1000.0;

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
    for (std::size_t t = 0; t < m.morph_targets.size(); ++t)
        require(m.morph_targets[t].rows() == m.V.rows() && m.morph_targets[t].cols() == 3 &&
                    m.morph_targets[t].allFinite(),
                who, ": morph target ", t, " is ", m.morph_targets[t].rows(), " x ", m.morph_targets[t].cols(),
                ", expected ", m.V.rows(), " x 3 finite");
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

void check_animation(const GlbScene& scene) {
    if (!scene.animation) return;
    const GlbAnimation& a = *scene.animation;
    const std::size_t K = a.times_s.size();
    require(K >= 1, "write_glb: animation '", a.name, "' has no key time");
    for (std::size_t k = 0; k < K; ++k)
        require(std::isfinite(a.times_s[k]) && a.times_s[k] >= 0 && (k == 0 || a.times_s[k] > a.times_s[k - 1]),
                "write_glb: animation '", a.name, "': key time ", k, " = ", a.times_s[k],
                " must be finite, >= 0 and after the previous one");
    require(a.joint_local.empty() || a.joint_local.size() == scene.skeleton.names.size(), "write_glb: animation '",
            a.name, "' has transforms for ", a.joint_local.size(), " joints, the skeleton has ",
            scene.skeleton.names.size());
    for (std::size_t j = 0; j < a.joint_local.size(); ++j) {
        require(a.joint_local[j].size() == K, "write_glb: animation '", a.name, "': joint ", j, " has ",
                a.joint_local[j].size(), " transforms for ", K, " key times");
        for (const Eigen::Isometry3d& T : a.joint_local[j])
            require(T.matrix().allFinite(), "write_glb: animation '", a.name, "': joint ", j,
                    " has a non-finite transform");
    }
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const GlbMesh& m = scene.meshes[i];
        if (m.morph_targets.empty()) continue;
        require(m.morph_targets.size() == K, "write_glb: mesh ", i, " '", m.mesh_name, "' has ",
                m.morph_targets.size(), " morph targets, the animation ", K, " key times (one target per key)");
        require(!m.node_name.empty(), "write_glb: mesh ", i, " '", m.mesh_name,
                "' is morph-animated, so it needs its own node (node_name)");
    }
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
    if (!m.morph_targets.empty()) {
        const unsigned T = static_cast<unsigned>(m.morph_targets.size());
        mesh->mNumAnimMeshes = T;
        mesh->mAnimMeshes = new aiAnimMesh*[T];
        for (unsigned t = 0; t < T; ++t) {
            auto* target = new aiAnimMesh();
            mesh->mAnimMeshes[t] = target;
            target->mName = aiString("frame_" + std::to_string(t));
            target->mNumVertices = mesh->mNumVertices;
            target->mVertices = new aiVector3D[mesh->mNumVertices];
            target->mWeight = 0;
            const Eigen::MatrixXd& X = m.morph_targets[t];
            for (Eigen::Index v = 0; v < X.rows(); ++v) target->mVertices[v] = to_ai(X(v, 0), X(v, 1), X(v, 2));
        }
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
    // The joints' keys; assimp writes them as translation and rotation channels (the morph
    // weights are added to the file afterwards: its exporter does not write them).
    if (in.animation && !in.animation->joint_local.empty()) {
        const GlbAnimation& a = *in.animation;
        auto* anim = new aiAnimation();
        anim->mName = aiString(a.name);
        anim->mTicksPerSecond = kTicksPerSecond;
        anim->mDuration = a.times_s.back() * kTicksPerSecond;
        const unsigned nj = static_cast<unsigned>(a.joint_local.size());
        const unsigned K = static_cast<unsigned>(a.times_s.size());
        anim->mNumChannels = nj;
        anim->mChannels = new aiNodeAnim*[nj];
        for (unsigned j = 0; j < nj; ++j) {
            auto* ch = new aiNodeAnim();
            anim->mChannels[j] = ch;
            ch->mNodeName = aiString(sk.names[j]);
            ch->mNumPositionKeys = K;
            ch->mPositionKeys = new aiVectorKey[K];
            ch->mNumRotationKeys = K;
            ch->mRotationKeys = new aiQuatKey[K];
            for (unsigned k = 0; k < K; ++k) {
                const Eigen::Isometry3d& T = a.joint_local[j][k];
                const Eigen::Vector3d t = T.translation();
                const Eigen::Quaterniond q(T.linear());
                const double time = a.times_s[k] * kTicksPerSecond;
                ch->mPositionKeys[k] = aiVectorKey(time, to_ai(t.x(), t.y(), t.z()));
                ch->mRotationKeys[k] =
                    aiQuatKey(time, aiQuaternion(static_cast<ai_real>(q.w()), static_cast<ai_real>(q.x()),
                                                 static_cast<ai_real>(q.y()), static_cast<ai_real>(q.z())));
            }
        }
        scene->mNumAnimations = 1;
        scene->mAnimations = new aiAnimation*[1]{anim};
    }
    return scene;
}

// ---- morph weights: added to the exported file ----

std::vector<char> read_all(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read back '" + path.string() + "'");
    return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::uint32_t u32(const std::vector<char>& b, std::size_t at) {
    std::uint32_t x = 0;
    std::memcpy(&x, b.data() + at, 4);
    return x;
}

void put_u32(std::string& out, std::uint32_t x) { out.append(reinterpret_cast<const char*>(&x), 4); }

template <class T>
void append_values(std::vector<char>& bin, const std::vector<T>& values) {
    const char* p = reinterpret_cast<const char*>(values.data());
    bin.insert(bin.end(), p, p + values.size() * sizeof(T));
    while (bin.size() % 4 != 0) bin.push_back(0);
}

/// Adds a "weights" channel per morph-animated mesh node to the animation of the glb at
/// `path` (written by assimp): one shared key-time accessor and one-hot weights (target k
/// at key k), in a new buffer view at the end of the binary chunk.
void add_morph_weights(const std::filesystem::path& path, const GlbScene& scene) {
    const GlbAnimation& a = *scene.animation;
    std::vector<const GlbMesh*> animated;
    for (const GlbMesh& m : scene.meshes)
        if (!m.morph_targets.empty()) animated.push_back(&m);
    if (animated.empty()) return;
    const std::vector<char> file = read_all(path);
    const auto bad = [&](const char* what) {
        return IoError("cannot add morph weights to '" + path.string() + "': " + what);
    };
    if (file.size() < 20 || u32(file, 0) != 0x46546C67u) throw bad("not a glb");
    const std::uint32_t json_length = u32(file, 12);
    if (u32(file, 16) != 0x4E4F534Au || 20 + std::size_t(json_length) > file.size()) throw bad("no JSON chunk");
    nlohmann::json gltf = nlohmann::json::parse(file.begin() + 20, file.begin() + 20 + json_length);
    std::vector<char> bin;
    const std::size_t bin_at = 20 + std::size_t(json_length);
    if (bin_at + 8 <= file.size()) {
        const std::uint32_t bin_length = u32(file, bin_at);
        if (u32(file, bin_at + 4) != 0x004E4942u || bin_at + 8 + bin_length > file.size()) throw bad("bad BIN chunk");
        bin.assign(file.begin() + long(bin_at + 8), file.begin() + long(bin_at + 8 + bin_length));
    }
    if (!gltf.contains("buffers") || gltf["buffers"].empty()) gltf["buffers"] = nlohmann::json::array({{{"byteLength", 0}}});
    const std::size_t K = a.times_s.size();
    std::vector<float> times(K), weights(K * K, 0.0f);
    for (std::size_t k = 0; k < K; ++k) {
        times[k] = static_cast<float>(a.times_s[k]);
        weights[k * K + k] = 1.0f;
    }
    auto add_accessor = [&](const auto& values, std::size_t count, bool with_range) {
        const std::size_t offset = bin.size();
        append_values(bin, values);
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * 4}};
        gltf["bufferViews"].push_back(view);
        nlohmann::json accessor = {{"bufferView", gltf["bufferViews"].size() - 1}, {"byteOffset", 0},
                                   {"componentType", 5126}, {"count", count}, {"type", "SCALAR"}};
        if (with_range) {
            accessor["min"] = {*std::min_element(values.begin(), values.end())};
            accessor["max"] = {*std::max_element(values.begin(), values.end())};
        }
        gltf["accessors"].push_back(accessor);
        return gltf["accessors"].size() - 1;
    };
    const std::size_t input = add_accessor(times, K, true);
    const std::size_t output = add_accessor(weights, K * K, false);
    gltf["buffers"][0]["byteLength"] = bin.size();
    if (!gltf.contains("animations") || gltf["animations"].empty())
        gltf["animations"] = nlohmann::json::array({{{"name", a.name}, {"channels", nlohmann::json::array()},
                                                     {"samplers", nlohmann::json::array()}}});
    nlohmann::json& anim = gltf["animations"][0];
    nlohmann::json targets = nlohmann::json::array();
    for (std::size_t k = 0; k < K; ++k) targets.push_back("frame_" + std::to_string(k));
    for (const GlbMesh* m : animated) {
        int node = -1;
        for (std::size_t n = 0; n < gltf["nodes"].size(); ++n)
            if (gltf["nodes"][n].value("name", std::string()) == m->node_name && gltf["nodes"][n].contains("mesh"))
                node = int(n);
        if (node < 0) throw bad(("no node '" + m->node_name + "' holding a mesh").c_str());
        nlohmann::json& mesh = gltf["meshes"][gltf["nodes"][std::size_t(node)]["mesh"].get<std::size_t>()];
        mesh["extras"]["targetNames"] = targets;
        std::vector<double> initial(K, 0.0);
        initial[0] = 1.0;
        mesh["weights"] = initial;
        anim["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", "LINEAR"}});
        anim["channels"].push_back(
            {{"sampler", anim["samplers"].size() - 1}, {"target", {{"node", node}, {"path", "weights"}}}});
    }
    std::string json = gltf.dump();
    while (json.size() % 4 != 0) json.push_back(' ');
    std::string out;
    put_u32(out, 0x46546C67u);
    put_u32(out, 2);
    put_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    put_u32(out, static_cast<std::uint32_t>(json.size()));
    put_u32(out, 0x4E4F534Au);
    out += json;
    put_u32(out, static_cast<std::uint32_t>(bin.size()));
    put_u32(out, 0x004E4942u);
    out.append(bin.data(), bin.size());
    std::ofstream o(path, std::ios::binary | std::ios::trunc);
    o.write(out.data(), std::streamsize(out.size()));
    if (!o) throw IoError("cannot write '" + path.string() + "'");
}

}  // namespace

void write_glb(const std::filesystem::path& path, const GlbScene& scene) {
    require(!scene.meshes.empty(), "write_glb: the scene has no mesh");
    check_skeleton(scene.skeleton);
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) check_mesh(scene.meshes[i], i, scene.skeleton);
    check_animation(scene);
    const std::unique_ptr<aiScene> ai = make_scene(scene);
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        Assimp::Exporter exporter;
        if (exporter.Export(ai.get(), "glb2", tmp.string()) != aiReturn_SUCCESS)
            throw IoError("cannot write '" + path.string() + "': " + exporter.GetErrorString());
        if (scene.animation) add_morph_weights(tmp, scene);
    });
}

}  // namespace drape::gltf
