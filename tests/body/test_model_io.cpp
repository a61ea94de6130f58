// Body model files (HDF5) and mesh files (glb, OBJ): round trips, validation, errors.
#include <drape/body/model_io.hpp>
#include <drape/body/pose.hpp>
#include <drape/core/errors.hpp>

#include "hdf5_file.hpp"
#include "test_paths.hpp"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <functional>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <unistd.h>
#include <vector>

using namespace drape::body;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A closed, outward-oriented capped cylinder standing on Y = 0 (rings x segments + 2 caps),
/// with a 2-column shape basis, a ring-averaging joint regressor and height-blended skin
/// weights (at most 4 joints per vertex).
BodyModel synthetic_model() {
    const int rings = 18, segments = 16;
    const double height = 1.7, radius = 0.15;
    const int nv = rings * segments + 2;
    BodyModel m;
    m.name = "synthetic-cylinder";
    m.template_vertices.resize(nv, 3);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double a = 2 * kPi * s / segments;
            m.template_vertices.row(r * segments + s) << radius * std::cos(a),
                height * r / (rings - 1), radius * std::sin(a);
        }
    const int bottom = rings * segments, top = bottom + 1;
    m.template_vertices.row(bottom) << 0, 0, 0;
    m.template_vertices.row(top) << 0, height, 0;
    std::vector<Eigen::Vector3i> faces;
    for (int r = 0; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const int a = r * segments + s, b = r * segments + (s + 1) % segments;
            const int c = a + segments, d = b + segments;
            faces.emplace_back(a, c, b);
            faces.emplace_back(b, c, d);
        }
    for (int s = 0; s < segments; ++s) {
        faces.emplace_back(bottom, s, (s + 1) % segments);
        const int o = (rings - 1) * segments;
        faces.emplace_back(top, o + (s + 1) % segments, o + s);
    }
    m.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f) m.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();

    m.shape_basis = Eigen::MatrixXd::Zero(3 * nv, 2);
    for (int v = 0; v < nv; ++v) {
        m.shape_basis(3 * v + 0, 0) = 0.1 * m.template_vertices(v, 0);  // girth
        m.shape_basis(3 * v + 2, 0) = 0.1 * m.template_vertices(v, 2);
        m.shape_basis(3 * v + 1, 1) = 0.05 * m.template_vertices(v, 1);  // height
    }
    m.shape_names = {"girth", "height"};

    // Joint j sits at ring ring_of[j]; side joints average the ring's +X or -X half.
    const std::array<int, kJointCount> ring_of = {7, 9, 11, 14, 15, 17, 13, 13, 12, 11,
                                                  13, 13, 12, 11, 6, 3, 1, 0, 6, 3, 1, 0};
    std::vector<Eigen::Triplet<double>> reg;
    for (int j = 0; j < kJointCount; ++j) {
        const std::string_view name = kJointNames[static_cast<std::size_t>(j)];
        const int side = name.rfind("left", 0) == 0 ? 1 : name.rfind("right", 0) == 0 ? -1 : 0;
        std::vector<int> picked;
        for (int s = 0; s < segments; ++s) {
            const double x = m.template_vertices(ring_of[static_cast<std::size_t>(j)] * segments + s, 0);
            if (side == 0 || side * x > 0.05) picked.push_back(ring_of[static_cast<std::size_t>(j)] * segments + s);
        }
        for (int v : picked) reg.emplace_back(j, v, 1.0 / static_cast<double>(picked.size()));
    }
    m.joint_regressor.resize(kJointCount, nv);
    m.joint_regressor.setFromTriplets(reg.begin(), reg.end());
    m.template_joints = m.joint_regressor * m.template_vertices;

    // Weights: blend between the two chain joints nearest in height, plus an arm joint pair
    // for vertices off to one side near the top.
    const std::vector<int> centre = {index(Joint::pelvis), index(Joint::spine), index(Joint::chest),
                                     index(Joint::neck), index(Joint::head), index(Joint::head_top)};
    std::vector<Eigen::Triplet<double>> w;
    for (int v = 0; v < nv; ++v) {
        const double y = m.template_vertices(v, 1), x = m.template_vertices(v, 0);
        std::map<int, double> wv;
        if (y < m.template_joints(index(Joint::pelvis), 1)) {
            const bool left = x >= 0;
            const int hip = index(left ? Joint::left_hip : Joint::right_hip);
            const int knee = index(left ? Joint::left_knee : Joint::right_knee);
            const double t = std::clamp(y / m.template_joints(hip, 1), 0.0, 1.0);
            wv[knee] += 1 - t;
            wv[hip] += 0.7 * t;
            wv[index(Joint::pelvis)] += 0.3 * t;
        } else {
            std::size_t k = 0;
            while (k + 2 < centre.size() && m.template_joints(centre[k + 1], 1) < y) ++k;
            const double y0 = m.template_joints(centre[k], 1), y1 = m.template_joints(centre[k + 1], 1);
            const double t = std::clamp((y - y0) / (y1 - y0), 0.0, 1.0);
            double arm = 0;
            if (std::abs(x) > 0.1 && y > 1.1 && y < 1.4) arm = 0.4;
            wv[centre[k]] += (1 - t) * (1 - arm);
            wv[centre[k + 1]] += t * (1 - arm);
            if (arm > 0) {
                wv[index(x > 0 ? Joint::left_shoulder : Joint::right_shoulder)] += 0.6 * arm;
                wv[index(x > 0 ? Joint::left_elbow : Joint::right_elbow)] += 0.4 * arm;
            }
        }
        for (const auto& [j, x_w] : wv)
            if (x_w > 0) w.emplace_back(v, j, x_w);
    }
    m.skin_weights.resize(nv, kJointCount);
    m.skin_weights.setFromTriplets(w.begin(), w.end());

    m.landmarks.head_top = top;
    m.landmarks.crotch = 5 * segments;
    m.landmarks.navel = 10 * segments + 4;

    m.semantic_map.A = Eigen::MatrixXd::Zero(2, 1 + kSemanticCount);
    m.semantic_map.A(0, 1 + static_cast<int>(Semantic::waist_girth_m)) = 2.0;
    m.semantic_map.A(1, 1 + static_cast<int>(Semantic::height_m)) = 1.0 / 0.085;
    m.semantic_map.b = Eigen::Vector2d(0.25, -0.5);
    m.semantic_map.reference.setConstant(0.5);
    m.semantic_map.refinable = Eigen::Vector2d(1.0, 0.0);

    for (GaussianPrior* g : {&m.prior.female, &m.prior.male}) {
        g->mean.setLinSpaced(0.5, 1.5);
        Eigen::Matrix<double, kSemanticCount, kSemanticCount> L =
            Eigen::Matrix<double, kSemanticCount, kSemanticCount>::Identity() * 0.1;
        L(3, 1) = 0.05;
        g->covariance = L * L.transpose();
        g->min = g->mean.array() - 0.4;
        g->max = g->mean.array() + 0.4;
        g->sample_count = g == &m.prior.female ? 1986 : 4082;
    }
    m.density_kg_m3 = 1012.5;
    return m;
}

void require_identical(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
    REQUIRE(a.rows() == b.rows());
    REQUIRE(a.cols() == b.cols());
    REQUIRE(a.nonZeros() == b.nonZeros());
    const Eigen::MatrixXd da = a, db = b;
    REQUIRE((da.array() == db.array()).all());
}

void require_identical(const BodyModel& a, const BodyModel& b) {
    REQUIRE(a.name == b.name);
    REQUIRE(a.template_vertices.rows() == b.template_vertices.rows());
    REQUIRE((a.template_vertices.array() == b.template_vertices.array()).all());
    REQUIRE(a.faces.rows() == b.faces.rows());
    REQUIRE((a.faces.array() == b.faces.array()).all());
    REQUIRE(a.shape_basis.cols() == b.shape_basis.cols());
    REQUIRE((a.shape_basis.array() == b.shape_basis.array()).all());
    REQUIRE(a.shape_names == b.shape_names);
    REQUIRE((a.template_joints.array() == b.template_joints.array()).all());
    require_identical(a.joint_regressor, b.joint_regressor);
    require_identical(a.skin_weights, b.skin_weights);
    REQUIRE(a.landmarks.head_top == b.landmarks.head_top);
    REQUIRE(a.landmarks.right_acromion == b.landmarks.right_acromion);
    REQUIRE(a.landmarks.left_acromion == b.landmarks.left_acromion);
    REQUIRE(a.landmarks.crotch == b.landmarks.crotch);
    REQUIRE(a.landmarks.right_bust == b.landmarks.right_bust);
    REQUIRE(a.landmarks.left_bust == b.landmarks.left_bust);
    REQUIRE(a.landmarks.navel == b.landmarks.navel);
    REQUIRE(a.landmarks.buttock == b.landmarks.buttock);
    REQUIRE(a.landmarks.right_thigh == b.landmarks.right_thigh);
    REQUIRE(a.landmarks.right_calf == b.landmarks.right_calf);
    REQUIRE(a.semantic_map.A.rows() == b.semantic_map.A.rows());
    REQUIRE((a.semantic_map.A.array() == b.semantic_map.A.array()).all());
    REQUIRE((a.semantic_map.b.array() == b.semantic_map.b.array()).all());
    REQUIRE((a.semantic_map.reference.array() == b.semantic_map.reference.array()).all());
    REQUIRE(a.semantic_map.refinable.size() == b.semantic_map.refinable.size());
    REQUIRE((a.semantic_map.refinable.array() == b.semantic_map.refinable.array()).all());
    for (Gender g : {Gender::female, Gender::male}) {
        const GaussianPrior &pa = a.prior.of(g), &pb = b.prior.of(g);
        REQUIRE((pa.mean.array() == pb.mean.array()).all());
        REQUIRE((pa.covariance.array() == pb.covariance.array()).all());
        REQUIRE((pa.min.array() == pb.min.array()).all());
        REQUIRE((pa.max.array() == pb.max.array()).all());
        REQUIRE(pa.sample_count == pb.sample_count);
    }
    REQUIRE(a.density_kg_m3 == b.density_kg_m3);
}

/// Runs `fn` with stderr redirected to a file; returns what was printed there.
template <class Fn>
std::string captured_stderr(const fs::path& dir, Fn fn) {
    const fs::path log = dir / "stderr.txt";
    std::fflush(stderr);
    const int saved = ::dup(2);
    FILE* f = std::fopen(log.string().c_str(), "w");
    ::dup2(::fileno(f), 2);
    try {
        fn();
    } catch (...) {
    }
    std::fflush(stderr);
    ::dup2(saved, 2);
    ::close(saved);
    std::fclose(f);
    std::ifstream in(log);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Saves the synthetic model, lets `edit` damage the file, and returns load_model's complaint.
template <class Edit>
std::string load_error_after(const std::string& name, Edit edit) {
    const fs::path dir = drape::test::scratch_dir("model_io_" + name);
    const fs::path p = dir / "model.h5";
    save_model(synthetic_model(), p);
    {
        h5::File f(p, h5::Mode::read_write);
        edit(f);
        f.close();
    }
    try {
        load_model(p);
    } catch (const drape::InvalidInput& e) {
        return e.what();
    }
    FAIL("load_model accepted a damaged file (" << name << ")");
    return "";
}

// ---- a minimal glTF 2.0 binary reader for checking export_glb ---------------------------

struct Glb {
    nlohmann::json json;
    std::vector<std::uint8_t> bin;

    /// Accessor `i` as doubles, `components` per element (normalised integers scaled).
    std::vector<double> accessor(int i, int* components = nullptr) const {
        const auto& acc = json.at("accessors").at(static_cast<std::size_t>(i));
        const auto& view = json.at("bufferViews").at(acc.at("bufferView").get<std::size_t>());
        static const std::map<std::string, int> kComponents = {
            {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT4", 16}};
        const int n = kComponents.at(acc.at("type").get<std::string>());
        if (components) *components = n;
        const int type = acc.at("componentType").get<int>();
        const std::size_t size = type == 5126 || type == 5125 ? 4 : type == 5123 || type == 5122 ? 2 : 1;
        const std::size_t stride = view.value("byteStride", static_cast<std::size_t>(n) * size);
        const std::size_t base = view.value("byteOffset", std::size_t{0}) + acc.value("byteOffset", std::size_t{0});
        const std::size_t count = acc.at("count").get<std::size_t>();
        REQUIRE(base % size == 0);
        REQUIRE(base + (count - 1) * stride + static_cast<std::size_t>(n) * size <= bin.size());
        REQUIRE(base + (count - 1) * stride + static_cast<std::size_t>(n) * size <=
                view.value("byteOffset", std::size_t{0}) + view.at("byteLength").get<std::size_t>());
        const bool normalized = acc.value("normalized", false);
        std::vector<double> out;
        for (std::size_t e = 0; e < count; ++e)
            for (int c = 0; c < n; ++c) {
                const std::uint8_t* p = bin.data() + base + e * stride + static_cast<std::size_t>(c) * size;
                double x = 0;
                if (type == 5126) {
                    float f;
                    std::memcpy(&f, p, 4);
                    x = f;
                } else if (type == 5125) {
                    std::uint32_t u;
                    std::memcpy(&u, p, 4);
                    x = u;
                } else if (type == 5123) {
                    std::uint16_t u;
                    std::memcpy(&u, p, 2);
                    x = normalized ? u / 65535.0 : u;
                } else if (type == 5121) {
                    x = normalized ? *p / 255.0 : *p;
                } else {
                    FAIL("unexpected componentType " << type);
                }
                out.push_back(x);
            }
        return out;
    }
};

std::uint32_t u32(const std::vector<std::uint8_t>& b, std::size_t at) {
    std::uint32_t x;
    std::memcpy(&x, b.data() + at, 4);
    return x;
}

Glb read_glb(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    const std::vector<std::uint8_t> b((std::istreambuf_iterator<char>(in)), {});
    REQUIRE(b.size() >= 28);
    REQUIRE(std::memcmp(b.data(), "glTF", 4) == 0);
    REQUIRE(u32(b, 4) == 2);
    REQUIRE(u32(b, 8) == b.size());
    const std::uint32_t json_length = u32(b, 12);
    REQUIRE(u32(b, 16) == 0x4E4F534Au);  // "JSON"
    REQUIRE(json_length % 4 == 0);
    Glb g;
    g.json = nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + json_length);
    const std::size_t bin_at = 20 + json_length;
    REQUIRE(bin_at + 8 <= b.size());
    const std::uint32_t bin_length = u32(b, bin_at);
    REQUIRE(u32(b, bin_at + 4) == 0x004E4942u);  // "BIN\0"
    REQUIRE(bin_length % 4 == 0);
    REQUIRE(bin_at + 8 + bin_length == b.size());
    g.bin.assign(b.begin() + static_cast<long>(bin_at) + 8, b.end());
    REQUIRE(g.json.at("buffers").at(0).at("byteLength").get<std::size_t>() <= bin_length);
    return g;
}

Eigen::Matrix4d node_local(const nlohmann::json& node) {
    Eigen::Matrix4d M = Eigen::Matrix4d::Identity();
    if (node.contains("matrix")) {
        const auto& m = node.at("matrix");
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) M(r, c) = m.at(static_cast<std::size_t>(4 * c + r)).get<double>();
        return M;
    }
    Eigen::Affine3d T = Eigen::Affine3d::Identity();
    if (node.contains("translation")) {
        const auto& t = node.at("translation");
        T.translate(Eigen::Vector3d(t[0].get<double>(), t[1].get<double>(), t[2].get<double>()));
    }
    if (node.contains("rotation")) {
        const auto& q = node.at("rotation");  // x, y, z, w
        T.rotate(Eigen::Quaterniond(q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>()));
    }
    if (node.contains("scale")) {
        const auto& s = node.at("scale");
        T.scale(Eigen::Vector3d(s[0].get<double>(), s[1].get<double>(), s[2].get<double>()));
    }
    return T.matrix();
}

Pose test_pose() {
    Pose pose = named_pose(NamedPose::walking);
    pose.translation = Eigen::Vector3d(0.1, -0.05, 0.3);
    for (int j = 0; j < kJointCount; ++j)
        pose.rotations.row(j) += Eigen::RowVector3d(0.1 * std::sin(j), 0.15 * std::cos(2.0 * j), 0.05 * j / kJointCount);
    return pose;
}

}  // namespace

TEST_CASE("synthetic model is valid", "[body][io]") {
    std::string why;
    const bool ok = synthetic_model().is_valid(&why);
    INFO(why);
    REQUIRE(ok);
}

TEST_CASE("save_model / load_model round-trip bit-exactly", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_roundtrip");
    const BodyModel m = synthetic_model();
    save_model(m, dir / "model.h5");
    const BodyModel back = load_model(dir / "model.h5");
    require_identical(m, back);

    SECTION("the layout and attributes are as documented") {
        h5::File f(dir / "model.h5", h5::Mode::read_only);
        CHECK(f.read_string_attribute("/", "format_name") == "drape-body-model");
        CHECK(f.read_int_attribute("/", "format_version") == 1);
        CHECK(f.read_string_attribute("/", "units") == "metre");
        CHECK(f.read_string_attribute("/", "up_axis") == "+Y");
        CHECK(f.read_string_attribute("/", "front") == "+Z");
        CHECK(f.read_string_attribute("/", "name") == "synthetic-cylinder");
        const auto nv = static_cast<std::size_t>(m.vertex_count());
        CHECK(f.dims("/mesh/template_vertices") == h5::Dims{nv, 3});
        CHECK(f.dims("/mesh/faces") == h5::Dims{static_cast<std::size_t>(m.faces.rows()), 3});
        CHECK(f.dims("/shape/basis") == h5::Dims{3 * nv, 2});
        CHECK(f.dims("/skeleton/rest_joints") == h5::Dims{22, 3});
        CHECK(f.read_int_vector("/skeleton/joint_regressor/shape", 2) == std::vector<std::int64_t>{22, static_cast<std::int64_t>(nv)});
        CHECK(f.read_int_vector("/skinning/weights/indptr", -1).size() == nv + 1);
        CHECK(f.read_int_scalar("/landmarks/navel") == m.landmarks.navel);
        CHECK(f.read_int_scalar("/landmarks/buttock") == -1);
        CHECK(f.read_double_scalar("/physical/density_kg_m3") == 1012.5);
        CHECK(f.read_int_scalar("/prior/male/sample_count") == 4082);
        // Row 3v+d of the basis is coordinate d of vertex v.
        const Eigen::MatrixXd basis = f.read_matrix("/shape/basis", -1, -1);
        CHECK(basis(3 * 5 + 2, 0) == m.shape_basis(3 * 5 + 2, 0));
    }
    SECTION("overwriting an existing file works") {
        BodyModel m2 = m;
        m2.name = "second";
        save_model(m2, dir / "model.h5");
        CHECK(load_model(dir / "model.h5").name == "second");
    }
}

TEST_CASE("the default model round-trips bit-exactly", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_default");
    const BodyModel& m = BodyModel::default_model();
    save_model(m, dir / "default.h5");
    require_identical(m, load_model(dir / "default.h5"));
}

TEST_CASE("load_model reads files written the way h5py converters write them", "[body][io]") {
    // Variable-length string attributes (only when allowed), fixed-length name arrays,
    // float32 geometry, int64 indices and no optional datasets (landmarks, refinable).
    const fs::path dir = drape::test::scratch_dir("model_io_converter");
    const BodyModel m = synthetic_model();
    save_model(m, dir / "model.h5");
    {
        h5::File f(dir / "model.h5", h5::Mode::read_write);
        for (const char* a : {"format_name", "units", "up_axis", "front", "name"}) {
            const std::string v = f.read_string_attribute("/", a);
            f.remove_attribute("/", a);
            f.write_string_attribute("/", a, v, /*variable_length=*/true);
        }
        f.remove("/shape/names");
        f.write_strings("/shape/names", m.shape_names, 16);
        f.remove("/skeleton/joint_names");
        f.write_strings("/skeleton/joint_names", std::vector<std::string>(kJointNames.begin(), kJointNames.end()), 20);
        f.remove("/mesh/template_vertices");
        f.write_matrix("/mesh/template_vertices", m.template_vertices, /*single=*/true);
        f.remove("/skinning/weights/indices");
        std::vector<std::int64_t> idx;
        const Eigen::SparseMatrix<double, Eigen::RowMajor> W = m.skin_weights;
        for (Eigen::Index k = 0; k < W.nonZeros(); ++k) idx.push_back(W.innerIndexPtr()[k]);
        f.write_int_vector("/skinning/weights/indices", idx, /*wide=*/true);
        f.remove("/landmarks");
        f.remove("/semantic_map/refinable");
        f.close();
    }
    // Variable-length strings are refused by default (libhdf5 reads their global heap
    // unchecked: docs/hardening.md), naming the attribute and the way out.
    CHECK_THROWS_WITH(load_model(dir / "model.h5"), Catch::Contains("/@format_name") &&
                                                        Catch::Contains("variable-length strings") &&
                                                        Catch::Contains("allow_variable_length_strings"));
    ModelLoadOptions trusted;
    trusted.allow_variable_length_strings = true;
    const BodyModel back = load_model(dir / "model.h5", trusted);
    CHECK(back.name == m.name);
    CHECK(back.shape_names == m.shape_names);
    CHECK((back.template_vertices - m.template_vertices).cwiseAbs().maxCoeff() < 1e-6);
    CHECK(back.landmarks.navel == -1);
    CHECK(back.landmarks.head_top == -1);
    CHECK(back.semantic_map.refinable == Eigen::VectorXd::Ones(2));
    require_identical(back.skin_weights, m.skin_weights);
}

TEST_CASE("load_model: missing and non-HDF5 files are IoErrors naming the path", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_badfiles");
    const fs::path missing = dir / "nope.h5";
    REQUIRE_THROWS_AS(load_model(missing), drape::IoError);
    REQUIRE_THROWS_WITH(load_model(missing), Catch::Contains(missing.string()));
    const fs::path text = dir / "text.h5";
    std::ofstream(text) << "this is not an HDF5 file\n";
    REQUIRE_THROWS_AS(load_model(text), drape::IoError);
    REQUIRE_THROWS_WITH(load_model(text), Catch::Contains(text.string()) && Catch::Contains("not an HDF5"));
    // An HDF5 file that is not a body model.
    const fs::path other = dir / "other.h5";
    {
        h5::File f(other, h5::Mode::create);
        f.write_double_scalar("/x", 1.0);
        f.close();
    }
    REQUIRE_THROWS_AS(load_model(other), drape::InvalidInput);
    REQUIRE_THROWS_WITH(load_model(other), Catch::Contains("format_name"));
}

TEST_CASE("load_model: HDF5 prints nothing to stderr on failure", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_stderr");
    std::ofstream(dir / "text.h5") << "garbage";
    save_model(synthetic_model(), dir / "model.h5");
    {
        // A group where a dataset belongs: H5Dopen fails inside HDF5 (which would print).
        h5::File f(dir / "model.h5", h5::Mode::read_write);
        f.remove("/mesh/faces");
        f.write_double_scalar("/mesh/faces/oops", 1.0);
        f.close();
    }
    const std::string printed = captured_stderr(dir, [&] {
        try {
            load_model(dir / "text.h5");
        } catch (const drape::IoError&) {
        }
        load_model(dir / "model.h5");
    });
    CHECK(printed.empty());
    REQUIRE_THROWS_WITH(load_model(dir / "model.h5"),
                        Catch::Contains("/mesh/faces") && Catch::Contains("not a dataset"));
}

TEST_CASE("load_model: inconsistent content is InvalidInput naming the dataset", "[body][io]") {
    const BodyModel m = synthetic_model();
    const int nv = m.vertex_count();

    SECTION("faces with the wrong shape") {
        const std::string e = load_error_after("faces_shape", [&](h5::File& f) {
            f.remove("/mesh/faces");
            f.write_int_matrix("/mesh/faces", Eigen::MatrixXi::Zero(10, 4));
        });
        CHECK_THAT(e, Catch::Contains("/mesh/faces") && Catch::Contains("10 x 4"));
    }
    SECTION("shape basis with the wrong row count") {
        const std::string e = load_error_after("basis_shape", [&](h5::File& f) {
            f.remove("/shape/basis");
            f.write_matrix("/shape/basis", Eigen::MatrixXd::Zero(3 * nv - 3, 2));
        });
        CHECK_THAT(e, Catch::Contains("/shape/basis"));
    }
    SECTION("face index out of range") {
        const std::string e = load_error_after("face_range", [&](h5::File& f) {
            Eigen::MatrixXi F = m.faces;
            F(7, 1) = nv;
            f.remove("/mesh/faces");
            f.write_int_matrix("/mesh/faces", F);
        });
        CHECK_THAT(e, Catch::Contains("/mesh/faces") && Catch::Contains("face 7") &&
                          Catch::Contains(std::to_string(nv)));
    }
    SECTION("NaN in the template") {
        const std::string e = load_error_after("nan", [&](h5::File& f) {
            Eigen::MatrixXd V = m.template_vertices;
            V(3, 2) = std::nan("");
            f.remove("/mesh/template_vertices");
            f.write_matrix("/mesh/template_vertices", V);
        });
        CHECK_THAT(e, Catch::Contains("/mesh/template_vertices") && Catch::Contains("row 3, column 2"));
    }
    SECTION("skin weights not summing to one") {
        const std::string e = load_error_after("weights", [&](h5::File& f) {
            Eigen::VectorXd data = f.read_vector("/skinning/weights/data", -1);
            data[0] += 1e-3;
            f.remove("/skinning/weights/data");
            f.write_vector("/skinning/weights/data", data);
        });
        CHECK_THAT(e, Catch::Contains("/skinning/weights") && Catch::Contains("sums to"));
    }
    SECTION("sparse column index out of range") {
        const std::string e = load_error_after("csr_indices", [&](h5::File& f) {
            std::vector<std::int64_t> idx = f.read_int_vector("/skinning/weights/indices", -1);
            idx[2] = 22;
            f.remove("/skinning/weights/indices");
            f.write_int_vector("/skinning/weights/indices", idx);
        });
        CHECK_THAT(e, Catch::Contains("/skinning/weights/indices") && Catch::Contains("column 22"));
    }
    SECTION("a different skeleton") {
        const std::string e = load_error_after("joint_names", [&](h5::File& f) {
            std::vector<std::string> names(kJointNames.begin(), kJointNames.end());
            names[3] = "neck_base";
            f.remove("/skeleton/joint_names");
            f.write_strings("/skeleton/joint_names", names);
        });
        CHECK_THAT(e, Catch::Contains("/skeleton/joint_names") && Catch::Contains("neck_base"));
        const std::string e2 = load_error_after("parents", [&](h5::File& f) {
            std::vector<std::int64_t> parents(kJointParents.begin(), kJointParents.end());
            parents[7] = 2;
            f.remove("/skeleton/parents");
            f.write_int_vector("/skeleton/parents", parents);
        });
        CHECK_THAT(e2, Catch::Contains("/skeleton/parents") && Catch::Contains("right_shoulder"));
    }
    SECTION("landmark out of range, wrong units, newer version") {
        CHECK_THAT(load_error_after("landmark", [&](h5::File& f) {
                       f.remove("/landmarks/navel");
                       f.write_int_scalar("/landmarks/navel", nv + 5);
                   }),
                   Catch::Contains("/landmarks/navel"));
        CHECK_THAT(load_error_after("units", [&](h5::File& f) {
                       f.remove_attribute("/", "units");
                       f.write_string_attribute("/", "units", "millimetre");
                   }),
                   Catch::Contains("units") && Catch::Contains("millimetre"));
        CHECK_THAT(load_error_after("version", [&](h5::File& f) {
                       f.remove_attribute("/", "format_version");
                       f.write_int_attribute("/", "format_version", 2);
                   }),
                   Catch::Contains("format_version") && Catch::Contains("2"));
        CHECK_THAT(load_error_after("missing_group", [&](h5::File& f) { f.remove("/mesh"); }),
                   Catch::Contains("/mesh/template_vertices") && Catch::Contains("missing"));
    }
    SECTION("a non-symmetric prior covariance") {
        const std::string e = load_error_after("prior", [&](h5::File& f) {
            Eigen::MatrixXd C = f.read_matrix("/prior/male/covariance", 10, 10);
            C(0, 1) += 0.5;
            f.remove("/prior/male/covariance");
            f.write_matrix("/prior/male/covariance", C);
        });
        CHECK_THAT(e, Catch::Contains("/prior/male/covariance") && Catch::Contains("symmetric"));
    }
}

TEST_CASE("save_model: invalid models and failed writes", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_save_errors");
    const BodyModel m = synthetic_model();

    REQUIRE_THROWS_AS(save_model(m, dir / "no_such_folder" / "model.h5"), drape::IoError);

    BodyModel bad = m;
    bad.faces(0, 0) = m.vertex_count();
    REQUIRE_THROWS_AS(save_model(bad, dir / "bad.h5"), drape::InvalidInput);
    REQUIRE_THROWS_WITH(save_model(bad, dir / "bad.h5"), Catch::Contains("/mesh/faces"));
    CHECK_FALSE(fs::exists(dir / "bad.h5"));

    SECTION("a failed write leaves the existing file untouched") {
        // The temporary's name (".<name>.tmp<pid>_<n>") exceeds NAME_MAX while <name>
        // itself does not, so creating the HDF5 file fails after the checks passed.
        const fs::path p = dir / (std::string(250, 'm') + ".h5");
        std::ofstream(p) << "precious";
        REQUIRE_THROWS_AS(save_model(m, p), drape::IoError);
        std::ifstream in(p);
        CHECK(std::string(std::istreambuf_iterator<char>(in), {}) == "precious");
        for (const auto& entry : fs::directory_iterator(dir))
            CHECK(entry.path().filename().string().find(".tmp") == std::string::npos);
    }
    SECTION("an invalid model leaves the existing file untouched") {
        save_model(m, dir / "model.h5");
        REQUIRE_THROWS_AS(save_model(bad, dir / "model.h5"), drape::InvalidInput);
        require_identical(m, load_model(dir / "model.h5"));
    }
}

TEST_CASE("export_obj / import_mesh round trip", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_obj");
    const BodyModel m = synthetic_model();
    export_obj(dir / "body.obj", m.template_vertices, m.faces);
    const TriangleMesh back = import_mesh(dir / "body.obj");
    REQUIRE(back.V.rows() == m.template_vertices.rows());
    REQUIRE(back.F.rows() == m.faces.rows());
    // Vertex order may change; compare the triangles as sets of positions (assimp reads
    // single precision).
    auto key = [](const Eigen::RowVector3d& p) {
        return std::array<long, 3>{std::lround(p[0] * 1e5), std::lround(p[1] * 1e5), std::lround(p[2] * 1e5)};
    };
    std::set<std::array<std::array<long, 3>, 3>> expected, found;
    auto insert = [&](auto& set, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
        for (Eigen::Index f = 0; f < F.rows(); ++f) {
            std::array<std::array<long, 3>, 3> t = {key(V.row(F(f, 0))), key(V.row(F(f, 1))), key(V.row(F(f, 2)))};
            std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());  // keeps orientation
            set.insert(t);
        }
    };
    insert(expected, m.template_vertices, m.faces);
    insert(found, back.V, back.F);
    CHECK(expected == found);

    // The text itself: v, vn, f with 1-based v//vn indices and exact doubles.
    std::ifstream in(dir / "body.obj");
    const std::string text(std::istreambuf_iterator<char>(in), {});
    CHECK(text.find("\nvn ") != std::string::npos);
    CHECK(text.find("\nf 1") != std::string::npos);  // some face uses vertex 1 ... as v//vn
    CHECK(text.find("//") != std::string::npos);

    REQUIRE_THROWS_AS(export_obj(dir / "missing" / "x.obj", m.template_vertices, m.faces), drape::IoError);
    Eigen::MatrixXi badF = m.faces;
    badF(0, 0) = -1;
    REQUIRE_THROWS_AS(export_obj(dir / "bad.obj", m.template_vertices, badF), drape::InvalidInput);
}

TEST_CASE("import_mesh errors", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_import_errors");
    REQUIRE_THROWS_AS(import_mesh(dir / "missing.obj"), drape::IoError);
    std::ofstream(dir / "garbage.glb") << "not a mesh at all";
    REQUIRE_THROWS_AS(import_mesh(dir / "garbage.glb"), drape::IoError);
    std::ofstream(dir / "lines.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n";
    CHECK_THROWS_AS(import_mesh(dir / "lines.obj"), drape::InvalidInput);
}

TEST_CASE("export_glb writes a rigged glTF that reproduces pose_body", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_glb");
    const BodyModel m = synthetic_model();
    const ShapedBody shaped = shape_from_coefficients(m, Eigen::Vector2d(0.3, -0.2));
    const Pose pose = test_pose();
    const fs::path p = dir / "body.glb";
    export_glb(p, m, shaped, pose);
    const Glb g = read_glb(p);
    const auto& J = g.json;

    REQUIRE(J.at("asset").at("version") == "2.0");
    REQUIRE(J.at("skins").size() == 1);
    const auto& skin = J.at("skins").at(0);
    REQUIRE(skin.at("joints").size() == kJointCount);
    const auto& nodes = J.at("nodes");

    // Which node is joint j, by name.
    std::array<int, kJointCount> node_of{};
    std::vector<int> joint_of_skin_slot;
    for (const auto& n : skin.at("joints")) {
        const std::string name = nodes.at(n.get<std::size_t>()).at("name");
        int j = -1;
        for (int k = 0; k < kJointCount; ++k)
            if (kJointNames[static_cast<std::size_t>(k)] == name) j = k;
        REQUIRE(j >= 0);
        node_of[static_cast<std::size_t>(j)] = n.get<int>();
        joint_of_skin_slot.push_back(j);
    }

    // Exactly one mesh node, and it references the skin.
    int mesh_node = -1;
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].contains("mesh")) {
            REQUIRE(mesh_node < 0);
            mesh_node = static_cast<int>(i);
        }
    REQUIRE(mesh_node >= 0);
    REQUIRE(nodes.at(static_cast<std::size_t>(mesh_node)).at("skin") == 0);

    // World transforms of every node (from the scene roots).
    std::vector<Eigen::Matrix4d> world(nodes.size(), Eigen::Matrix4d::Identity());
    std::vector<int> parent(nodes.size(), -1);
    for (std::size_t i = 0; i < nodes.size(); ++i)
        for (const auto& c : nodes[i].value("children", nlohmann::json::array())) parent[c.get<std::size_t>()] = static_cast<int>(i);
    std::function<Eigen::Matrix4d(int)> world_of = [&](int i) -> Eigen::Matrix4d {
        const Eigen::Matrix4d L = node_local(nodes.at(static_cast<std::size_t>(i)));
        return parent[static_cast<std::size_t>(i)] < 0 ? L : Eigen::Matrix4d(world_of(parent[static_cast<std::size_t>(i)]) * L);
    };
    for (std::size_t i = 0; i < nodes.size(); ++i) world[i] = world_of(static_cast<int>(i));

    // The node hierarchy mirrors the skeleton.
    for (int j = 1; j < kJointCount; ++j)
        CHECK(parent[static_cast<std::size_t>(node_of[static_cast<std::size_t>(j)])] ==
              node_of[static_cast<std::size_t>(kJointParents[static_cast<std::size_t>(j)])]);

    // Inverse bind matrices invert the rest joint transforms [I | rest_j].
    int comps = 0;
    const std::vector<double> ibm = g.accessor(skin.at("inverseBindMatrices").get<int>(), &comps);
    REQUIRE(comps == 16);
    REQUIRE(ibm.size() == 16 * kJointCount);
    std::vector<Eigen::Matrix4d> IBM;
    for (int s = 0; s < kJointCount; ++s) {
        Eigen::Matrix4d M;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) M(r, c) = ibm[static_cast<std::size_t>(16 * s + 4 * c + r)];
        Eigen::Matrix4d rest = Eigen::Matrix4d::Identity();
        rest.block<3, 1>(0, 3) = shaped.joints.row(joint_of_skin_slot[static_cast<std::size_t>(s)]).transpose();
        CHECK((M * rest - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff() < 1e-6);
        IBM.push_back(M);
    }

    // Mesh attributes.
    const auto& prim = J.at("meshes").at(0).at("primitives").at(0);
    const auto& attr = prim.at("attributes");
    REQUIRE(attr.contains("POSITION"));
    REQUIRE(attr.contains("NORMAL"));
    REQUIRE(attr.contains("JOINTS_0"));
    REQUIRE(attr.contains("WEIGHTS_0"));
    const auto& pos_acc = J.at("accessors").at(attr.at("POSITION").get<std::size_t>());
    REQUIRE(pos_acc.contains("min"));
    REQUIRE(pos_acc.contains("max"));
    const int joints_type = J.at("accessors").at(attr.at("JOINTS_0").get<std::size_t>()).at("componentType");
    CHECK((joints_type == 5121 || joints_type == 5123));
    const std::vector<double> P = g.accessor(attr.at("POSITION").get<int>());
    const std::vector<double> JW = g.accessor(attr.at("JOINTS_0").get<int>());
    const std::vector<double> W = g.accessor(attr.at("WEIGHTS_0").get<int>());
    const auto nv = static_cast<std::size_t>(m.vertex_count());
    REQUIRE(P.size() == 3 * nv);
    REQUIRE(JW.size() == 4 * nv);
    REQUIRE(W.size() == 4 * nv);
    for (std::size_t d = 0; d < 3; ++d) {
        double lo = 1e30, hi = -1e30;
        for (std::size_t v = 0; v < nv; ++v) {
            lo = std::min(lo, P[3 * v + d]);
            hi = std::max(hi, P[3 * v + d]);
        }
        CHECK(pos_acc.at("min").at(d).get<double>() == Approx(lo).margin(1e-6));
        CHECK(pos_acc.at("max").at(d).get<double>() == Approx(hi).margin(1e-6));
    }
    const std::vector<double> indices = g.accessor(prim.at("indices").get<int>());
    REQUIRE(indices.size() == 3 * static_cast<std::size_t>(m.faces.rows()));
    for (std::size_t i = 0; i < indices.size(); ++i)
        REQUIRE(indices[i] == m.faces(static_cast<Eigen::Index>(i / 3), static_cast<Eigen::Index>(i % 3)));

    // The rest vertices are the shaped vertices; skinning with the exported node
    // transforms reproduces pose_body.
    const PosedBody posed = pose_body(m, shaped, pose);
    double worst = 0, worst_rest = 0;
    for (std::size_t v = 0; v < nv; ++v) {
        const Eigen::Vector4d rest(P[3 * v], P[3 * v + 1], P[3 * v + 2], 1.0);
        worst_rest = std::max(worst_rest, (rest.head<3>() - shaped.vertices.row(static_cast<Eigen::Index>(v)).transpose()).norm());
        double sum = 0;
        Eigen::Vector4d out = Eigen::Vector4d::Zero();
        for (std::size_t k = 0; k < 4; ++k) {
            const double w = W[4 * v + k];
            sum += w;
            if (w == 0) continue;
            const auto slot = static_cast<std::size_t>(JW[4 * v + k]);
            REQUIRE(slot < kJointCount);
            const int jn = node_of[static_cast<std::size_t>(joint_of_skin_slot[slot])];
            out += w * (world[static_cast<std::size_t>(jn)] * IBM[slot] * rest);
        }
        REQUIRE(sum == Approx(1.0).margin(1e-6));
        worst = std::max(worst, (out.head<3>() - posed.vertices.row(static_cast<Eigen::Index>(v)).transpose()).norm());
    }
    CHECK(worst_rest < 1e-6);
    CHECK(worst < 1e-5);
    // The posed joints are where the joint nodes are.
    for (int j = 0; j < kJointCount; ++j)
        CHECK((world[static_cast<std::size_t>(node_of[static_cast<std::size_t>(j)])].block<3, 1>(0, 3) -
               posed.joints.row(j).transpose()).norm() < 1e-5);

    SECTION("assimp re-imports the skin") {
        Assimp::Importer importer;
        const aiScene* s = importer.ReadFile(p.string(), 0);
        REQUIRE(s != nullptr);
        REQUIRE(s->mNumMeshes == 1);
        CHECK(s->mMeshes[0]->mNumBones == static_cast<unsigned>(kJointCount));
        CHECK(s->mMeshes[0]->mNumVertices == nv);
    }
    SECTION("import_mesh reads the rest mesh back") {
        const TriangleMesh back = import_mesh(p);
        CHECK(back.V.rows() == static_cast<Eigen::Index>(nv));
        CHECK(back.F.rows() == m.faces.rows());
    }
    SECTION("errors") {
        REQUIRE_THROWS_AS(export_glb(dir / "missing" / "x.glb", m, shaped, pose), drape::IoError);
        ShapedBody wrong = shaped;
        wrong.vertices.conservativeResize(wrong.vertices.rows() - 1, 3);
        REQUIRE_THROWS_AS(export_glb(dir / "x.glb", m, wrong, pose), drape::InvalidInput);
    }
}

TEST_CASE("export_glb keeps at most 4 renormalised weights per vertex", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_glb_weights");
    BodyModel m = synthetic_model();
    // Give vertex 0 six influences.
    Eigen::MatrixXd W = m.skin_weights;
    W.row(0).setZero();
    const double w[6] = {0.3, 0.25, 0.2, 0.15, 0.06, 0.04};
    for (int k = 0; k < 6; ++k) W(0, k) = w[k];
    m.skin_weights = W.sparseView();
    const ShapedBody shaped = shape_from_coefficients(m, Eigen::Vector2d::Zero());
    export_glb(dir / "body.glb", m, shaped, Pose::rest());
    const Glb g = read_glb(dir / "body.glb");
    const auto& attr = g.json.at("meshes").at(0).at("primitives").at(0).at("attributes");
    const std::vector<double> Wg = g.accessor(attr.at("WEIGHTS_0").get<int>());
    double sum = 0;
    for (int k = 0; k < 4; ++k) {
        sum += Wg[static_cast<std::size_t>(k)];
        CHECK(Wg[static_cast<std::size_t>(k)] > 0);
    }
    CHECK(sum == Approx(1.0).margin(1e-6));
    CHECK(Wg[0] == Approx(0.3 / 0.9).margin(1e-6));
}

// The body model fuzzer's findings (fuzz/regressions/body_model): damaged files that crashed,
// hung or leaked in libhdf5. Each is an error naming the file; the heap overflow inside
// libhdf5's object-header parser (open upstream in 1.10.8) is contained by the isolated
// reader: this process survives it and gets an IoError.
TEST_CASE("load_model: the fuzzer's damaged files are errors, libhdf5's crash contained", "[body][io]") {
    const fs::path dir = drape::test::source_dir() / "fuzz" / "regressions" / "body_model";
    REQUIRE(fs::is_directory(dir));
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        ++files;
        INFO(entry.path().filename().string());
        try {
            (void)load_model(entry.path());
            FAIL("loaded a damaged file");
        } catch (const drape::IoError& e) {
            CHECK_THAT(e.what(), Catch::Contains(entry.path().string()));
        } catch (const drape::InvalidInput& e) {
            CHECK_THAT(e.what(), Catch::Contains(entry.path().string()));
        }
    }
    CHECK(files >= 4);
    // The overflow: the isolated child crashes (or, without a sanitizer, may read past the
    // header silently and refuse the result); never this process.
    const fs::path overflow = dir / "hdf5_object_header_overflow.h5";
    CHECK_THROWS_WITH(load_model(overflow), Catch::Contains(overflow.string()));
}

TEST_CASE("load_model: isolated and in-process reads give the same model", "[body][io]") {
    const fs::path dir = drape::test::scratch_dir("model_io_isolated");
    const BodyModel m = synthetic_model();
    save_model(m, dir / "model.h5");
    ModelLoadOptions here;
    here.isolate = false;
    require_identical(m, load_model(dir / "model.h5"));
    require_identical(m, load_model(dir / "model.h5", here));
}
