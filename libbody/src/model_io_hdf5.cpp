// save_model / load_model: the HDF5 body model file. The layout is specified in
// docs/body-model-format.md; keep the two in step (and bump kFormatVersion on any
// incompatible change).
#include <drape/body/model_io.hpp>

#include "hdf5_file.hpp"

#include <drape/core/atomic_file.hpp>
#include <drape/core/byte_codec.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/isolated.hpp>
#include <drape/core/limits.hpp>

#include <Eigen/SparseCore>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <type_traits>
#include <string>
#include <vector>

namespace drape::body {

namespace {

constexpr const char* kFormatName = "drape-body-model";
constexpr int kFormatVersion = 1;
constexpr const char* kUnits = "metre";
constexpr const char* kUpAxis = "+Y";
constexpr const char* kFront = "+Z";
constexpr double kRowSumTolerance = 1e-6;

struct LandmarkField {
    const char* name;
    int Landmarks::*member;
};
const std::array<LandmarkField, 10> kLandmarkFields = {{
    {"head_top", &Landmarks::head_top},
    {"right_acromion", &Landmarks::right_acromion},
    {"left_acromion", &Landmarks::left_acromion},
    {"crotch", &Landmarks::crotch},
    {"right_bust", &Landmarks::right_bust},
    {"left_bust", &Landmarks::left_bust},
    {"navel", &Landmarks::navel},
    {"buttock", &Landmarks::buttock},
    {"right_thigh", &Landmarks::right_thigh},
    {"right_calf", &Landmarks::right_calf},
}};

/// Reports a problem with the content destined for / read from `dataset`.
using Fail = std::function<void(const std::string& dataset, const std::string& problem)>;

// ---- semantic checks shared by save (in-memory model) and load (file content) --------

void check_row_sums(const Eigen::SparseMatrix<double>& m, const std::string& dataset,
                    bool non_negative, const Fail& fail) {
    Eigen::VectorXd sums = Eigen::VectorXd::Zero(m.rows());
    for (int k = 0; k < m.outerSize(); ++k) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it) {
            if (!std::isfinite(it.value()))
                fail(dataset, "non-finite value at row " + std::to_string(it.row()) + ", column " +
                                  std::to_string(it.col()));
            if (non_negative && it.value() < 0)
                fail(dataset, "negative weight " + std::to_string(it.value()) + " at row " +
                                  std::to_string(it.row()) + ", column " + std::to_string(it.col()));
            sums[it.row()] += it.value();
        }
    }
    for (Eigen::Index r = 0; r < sums.size(); ++r) {
        if (std::abs(sums[r] - 1.0) > kRowSumTolerance)
            fail(dataset, "row " + std::to_string(r) + " sums to " + std::to_string(sums[r]) +
                              ", expected 1 (within 1e-6)");
    }
}

void check_gaussian(const GaussianPrior& g, const std::string& group, const Fail& fail) {
    if (!g.mean.allFinite()) fail(group + "/mean", "non-finite value");
    if (!g.covariance.allFinite()) fail(group + "/covariance", "non-finite value");
    if (!g.min.allFinite()) fail(group + "/min", "non-finite value");
    if (!g.max.allFinite()) fail(group + "/max", "non-finite value");
    const double scale = std::max(1.0, g.covariance.cwiseAbs().maxCoeff());
    if ((g.covariance - g.covariance.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
        fail(group + "/covariance", "not symmetric");
    for (int i = 0; i < kSemanticCount; ++i) {
        if (!(g.covariance(i, i) > 0))
            fail(group + "/covariance", "diagonal entry " + std::to_string(i) + " is " +
                                            std::to_string(g.covariance(i, i)) + ", expected > 0");
        if (g.min[i] > g.max[i])
            fail(group + "/min", "entry " + std::to_string(i) + " (" + std::to_string(g.min[i]) +
                                     ") exceeds /max (" + std::to_string(g.max[i]) + ")");
    }
    if (g.sample_count < 0)
        fail(group + "/sample_count", "is " + std::to_string(g.sample_count) + ", expected >= 0");
}

/// Every invariant the file format promises, named by the dataset that carries it.
void check_model(const BodyModel& m, const Fail& fail) {
    const Eigen::Index V = m.template_vertices.rows();
    if (m.template_vertices.cols() != 3 || V < 3)
        fail("/mesh/template_vertices", "has shape " + std::to_string(V) + " x " +
                                            std::to_string(m.template_vertices.cols()) +
                                            ", expected #V x 3 with #V >= 3");
    if (!m.template_vertices.allFinite()) fail("/mesh/template_vertices", "non-finite value");
    if (m.faces.cols() != 3 || m.faces.rows() < 1)
        fail("/mesh/faces", "has shape " + std::to_string(m.faces.rows()) + " x " +
                                std::to_string(m.faces.cols()) + ", expected #F x 3 with #F >= 1");
    for (Eigen::Index f = 0; f < m.faces.rows(); ++f) {
        for (int c = 0; c < 3; ++c) {
            const int v = m.faces(f, c);
            if (v < 0 || v >= V)
                fail("/mesh/faces", "face " + std::to_string(f) + " refers to vertex " +
                                        std::to_string(v) + ", outside [0, " + std::to_string(V) + ")");
        }
        if (m.faces(f, 0) == m.faces(f, 1) || m.faces(f, 1) == m.faces(f, 2) ||
            m.faces(f, 0) == m.faces(f, 2))
            fail("/mesh/faces", "face " + std::to_string(f) + " repeats a vertex");
    }
    const Eigen::Index K = m.shape_basis.cols();
    if (m.shape_basis.rows() != 3 * V)
        fail("/shape/basis", "has " + std::to_string(m.shape_basis.rows()) + " rows, expected 3 #V = " +
                                 std::to_string(3 * V));
    if (!m.shape_basis.allFinite()) fail("/shape/basis", "non-finite value");
    if (static_cast<Eigen::Index>(m.shape_names.size()) != K)
        fail("/shape/names", "has " + std::to_string(m.shape_names.size()) +
                                 " names, expected one per basis column (" + std::to_string(K) + ")");
    if (!m.template_joints.allFinite()) fail("/skeleton/rest_joints", "non-finite value");
    if (m.joint_regressor.rows() != kJointCount || m.joint_regressor.cols() != V)
        fail("/skeleton/joint_regressor", "has shape " + std::to_string(m.joint_regressor.rows()) +
                                              " x " + std::to_string(m.joint_regressor.cols()) +
                                              ", expected 22 x #V = 22 x " + std::to_string(V));
    check_row_sums(m.joint_regressor, "/skeleton/joint_regressor", false, fail);
    if (m.skin_weights.rows() != V || m.skin_weights.cols() != kJointCount)
        fail("/skinning/weights", "has shape " + std::to_string(m.skin_weights.rows()) + " x " +
                                      std::to_string(m.skin_weights.cols()) + ", expected #V x 22 = " +
                                      std::to_string(V) + " x 22");
    check_row_sums(m.skin_weights, "/skinning/weights", true, fail);
    for (const LandmarkField& lf : kLandmarkFields) {
        const int v = m.landmarks.*lf.member;
        if (v < -1 || v >= V)
            fail(std::string("/landmarks/") + lf.name,
                 "vertex " + std::to_string(v) + " outside [0, " + std::to_string(V) + ") (or -1 = absent)");
    }
    const SemanticMap& sm = m.semantic_map;
    if (sm.A.rows() != K || sm.A.cols() != 1 + kSemanticCount)
        fail("/semantic_map/A", "has shape " + std::to_string(sm.A.rows()) + " x " +
                                    std::to_string(sm.A.cols()) + ", expected K x 11 = " +
                                    std::to_string(K) + " x 11");
    if (!sm.A.allFinite()) fail("/semantic_map/A", "non-finite value");
    if (sm.b.size() != K)
        fail("/semantic_map/b", "has length " + std::to_string(sm.b.size()) + ", expected K = " +
                                    std::to_string(K));
    if (!sm.b.allFinite()) fail("/semantic_map/b", "non-finite value");
    if (!sm.reference.allFinite()) fail("/semantic_map/reference", "non-finite value");
    if (sm.refinable.size() != K)
        fail("/semantic_map/refinable", "has length " + std::to_string(sm.refinable.size()) +
                                            ", expected K = " + std::to_string(K));
    if (!sm.refinable.allFinite()) fail("/semantic_map/refinable", "non-finite value");
    check_gaussian(m.prior.female, "/prior/female", fail);
    check_gaussian(m.prior.male, "/prior/male", fail);
    if (!std::isfinite(m.density_kg_m3) || m.density_kg_m3 <= 0)
        fail("/physical/density_kg_m3", "is " + std::to_string(m.density_kg_m3) + ", expected > 0");
}

// ---- sparse matrices as CSR groups ---------------------------------------------------

void write_csr(h5::File& f, const std::string& group, const Eigen::SparseMatrix<double>& m) {
    Eigen::SparseMatrix<double, Eigen::RowMajor> r = m;
    r.makeCompressed();
    const Eigen::Index nnz = r.nonZeros();
    f.write_vector(group + "/data", Eigen::Map<const Eigen::VectorXd>(r.valuePtr(), nnz));
    f.write_int_vector(group + "/indices",
                       std::vector<std::int64_t>(r.innerIndexPtr(), r.innerIndexPtr() + nnz));
    f.write_int_vector(group + "/indptr",
                       std::vector<std::int64_t>(r.outerIndexPtr(), r.outerIndexPtr() + r.rows() + 1));
    f.write_int_vector(group + "/shape", {r.rows(), r.cols()}, /*wide=*/true);
}

Eigen::SparseMatrix<double> read_csr(const h5::File& f, const std::string& group, long rows,
                                     long cols) {
    const std::vector<std::int64_t> shape = f.read_int_vector(group + "/shape", 2);
    if (shape[0] != rows || shape[1] != cols)
        f.fail(group + "/shape", "is [" + std::to_string(shape[0]) + ", " + std::to_string(shape[1]) +
                                     "], expected [" + std::to_string(rows) + ", " +
                                     std::to_string(cols) + "]");
    const Eigen::VectorXd data = f.read_vector(group + "/data", -1);
    const long nnz = static_cast<long>(data.size());
    const std::vector<std::int64_t> indices = f.read_int_vector(group + "/indices", nnz);
    const std::vector<std::int64_t> indptr = f.read_int_vector(group + "/indptr", rows + 1);
    if (indptr[0] != 0) f.fail(group + "/indptr", "must start at 0");
    if (indptr[static_cast<std::size_t>(rows)] != nnz)
        f.fail(group + "/indptr", "ends at " + std::to_string(indptr.back()) +
                                      ", expected the length of data (" + std::to_string(nnz) + ")");
    std::vector<long> last_row_of_column(static_cast<std::size_t>(cols), -1);
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(nnz));
    for (long r = 0; r < rows; ++r) {
        const std::int64_t begin = indptr[static_cast<std::size_t>(r)];
        const std::int64_t end = indptr[static_cast<std::size_t>(r) + 1];
        if (end < begin)
            f.fail(group + "/indptr", "decreases at row " + std::to_string(r));
        if (end > nnz)  // found by fuzz/body_model: a middle entry past the data read out of bounds
            f.fail(group + "/indptr", "entry " + std::to_string(r + 1) + " is " + std::to_string(end) +
                                          ", past the length of data (" + std::to_string(nnz) + ")");
        for (std::int64_t k = begin; k < end; ++k) {
            const std::int64_t c = indices[static_cast<std::size_t>(k)];
            if (c < 0 || c >= cols)
                f.fail(group + "/indices", "entry " + std::to_string(k) + " is column " +
                                               std::to_string(c) + ", outside [0, " +
                                               std::to_string(cols) + ")");
            if (last_row_of_column[static_cast<std::size_t>(c)] == r)
                f.fail(group + "/indices", "row " + std::to_string(r) + " lists column " +
                                               std::to_string(c) + " twice");
            last_row_of_column[static_cast<std::size_t>(c)] = r;
            triplets.emplace_back(static_cast<int>(r), static_cast<int>(c),
                                  data[static_cast<Eigen::Index>(k)]);
        }
    }
    Eigen::SparseMatrix<double> m(rows, cols);
    m.setFromTriplets(triplets.begin(), triplets.end());
    m.makeCompressed();
    return m;
}

void write_gaussian(h5::File& f, const std::string& group, const GaussianPrior& g) {
    f.write_vector(group + "/mean", g.mean);
    f.write_matrix(group + "/covariance", g.covariance);
    f.write_vector(group + "/min", g.min);
    f.write_vector(group + "/max", g.max);
    f.write_int_scalar(group + "/sample_count", g.sample_count);
}

GaussianPrior read_gaussian(const h5::File& f, const std::string& group) {
    GaussianPrior g;
    g.mean = f.read_vector(group + "/mean", kSemanticCount);
    g.covariance = f.read_matrix(group + "/covariance", kSemanticCount, kSemanticCount);
    g.min = f.read_vector(group + "/min", kSemanticCount);
    g.max = f.read_vector(group + "/max", kSemanticCount);
    const std::int64_t n = f.read_int_scalar(group + "/sample_count");
    if (n < 0 || n > INT32_MAX)
        f.fail(group + "/sample_count", "is " + std::to_string(n) + ", expected 0 .. 2^31-1");
    g.sample_count = static_cast<int>(n);
    return g;
}

void expect_attribute(const h5::File& f, const std::string& name, const std::string& expected,
                      const std::string& hint) {
    const std::string value = f.read_string_attribute("/", name);
    if (value != expected)
        f.fail("/@" + name, "is \"" + value + "\", expected \"" + expected + "\"" + hint);
}

}  // namespace

void save_model(const BodyModel& model, const std::filesystem::path& path) {
    check_model(model, [&](const std::string& dataset, const std::string& problem) {
        throw InvalidInput("save_model: model '" + model.name + "' is inconsistent, so '" +
                           path.string() + "' was not written: " + dataset + ": " + problem);
    });
    std::string why;
    if (!model.is_valid(&why))
        throw InvalidInput("save_model: model '" + model.name + "' is inconsistent, so '" +
                           path.string() + "' was not written: " + why);
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        h5::File f(tmp, h5::Mode::create);
        f.write_string_attribute("/", "format_name", kFormatName);
        f.write_int_attribute("/", "format_version", kFormatVersion);
        f.write_string_attribute("/", "units", kUnits);
        f.write_string_attribute("/", "up_axis", kUpAxis);
        f.write_string_attribute("/", "front", kFront);
        f.write_string_attribute("/", "name", model.name);

        f.write_matrix("/mesh/template_vertices", model.template_vertices);
        f.write_int_matrix("/mesh/faces", model.faces);
        f.write_matrix("/shape/basis", model.shape_basis);
        f.write_strings("/shape/names", model.shape_names);

        std::vector<std::string> joint_names(kJointNames.begin(), kJointNames.end());
        f.write_strings("/skeleton/joint_names", joint_names);
        f.write_int_vector("/skeleton/parents",
                           std::vector<std::int64_t>(kJointParents.begin(), kJointParents.end()));
        f.write_matrix("/skeleton/rest_joints", model.template_joints);
        write_csr(f, "/skeleton/joint_regressor", model.joint_regressor);
        write_csr(f, "/skinning/weights", model.skin_weights);

        for (const LandmarkField& lf : kLandmarkFields)
            f.write_int_scalar(std::string("/landmarks/") + lf.name, model.landmarks.*lf.member);

        f.write_matrix("/semantic_map/A", model.semantic_map.A);
        f.write_vector("/semantic_map/b", model.semantic_map.b);
        f.write_vector("/semantic_map/reference", model.semantic_map.reference);
        f.write_vector("/semantic_map/refinable", model.semantic_map.refinable);
        write_gaussian(f, "/prior/female", model.prior.female);
        write_gaussian(f, "/prior/male", model.prior.male);
        f.write_double_scalar("/physical/density_kg_m3", model.density_kg_m3);
        f.close();
    });
}

namespace {

BodyModel parse_model(h5::File& f, const std::filesystem::path& path, const ModelLoadOptions& options) {
    f.allow_variable_length_strings(options.allow_variable_length_strings);

    if (!f.has_attribute("/", "format_name"))
        f.fail("/@format_name", "missing attribute; this HDF5 file is not a Drape body model");
    expect_attribute(f, "format_name", kFormatName, "; this HDF5 file is not a Drape body model");
    const std::int64_t version = f.read_int_attribute("/", "format_version");
    if (version != kFormatVersion)
        f.fail("/@format_version", "is " + std::to_string(version) + "; this build reads version " +
                                       std::to_string(kFormatVersion));
    expect_attribute(f, "units", kUnits, " (convert lengths to metres)");
    expect_attribute(f, "up_axis", kUpAxis, " (rotate the model so that +Y is up)");
    expect_attribute(f, "front", kFront, " (rotate the model so that it faces +Z)");

    BodyModel m;
    m.name = f.read_string_attribute("/", "name");
    m.template_vertices = f.read_matrix("/mesh/template_vertices", -1, 3);
    const long V = static_cast<long>(m.template_vertices.rows());
    if (V > limits::kMaxMeshVertices)
        f.fail("/mesh/template_vertices", "has " + std::to_string(V) + " vertices, more than the limit of " +
                                              std::to_string(limits::kMaxMeshVertices) + " (docs/hardening.md)");
    m.faces = f.read_int_matrix("/mesh/faces", -1, 3);
    m.shape_basis = f.read_matrix("/shape/basis", 3 * V, -1);
    const long K = static_cast<long>(m.shape_basis.cols());
    m.shape_names = f.read_strings("/shape/names", K);

    const std::vector<std::string> joint_names = f.read_strings("/skeleton/joint_names", kJointCount);
    for (int j = 0; j < kJointCount; ++j) {
        if (joint_names[static_cast<std::size_t>(j)] != kJointNames[static_cast<std::size_t>(j)])
            f.fail("/skeleton/joint_names",
                   "entry " + std::to_string(j) + " is \"" + joint_names[static_cast<std::size_t>(j)] +
                       "\", expected \"" + std::string(kJointNames[static_cast<std::size_t>(j)]) +
                       "\" (the skeleton is fixed; see docs/body-model-format.md)");
    }
    const std::vector<std::int64_t> parents = f.read_int_vector("/skeleton/parents", kJointCount);
    for (int j = 0; j < kJointCount; ++j) {
        if (parents[static_cast<std::size_t>(j)] != kJointParents[static_cast<std::size_t>(j)])
            f.fail("/skeleton/parents",
                   "entry " + std::to_string(j) + " (" + std::string(kJointNames[static_cast<std::size_t>(j)]) +
                       ") is " + std::to_string(parents[static_cast<std::size_t>(j)]) + ", expected " +
                       std::to_string(kJointParents[static_cast<std::size_t>(j)]));
    }
    m.template_joints = f.read_matrix("/skeleton/rest_joints", kJointCount, 3);
    m.joint_regressor = read_csr(f, "/skeleton/joint_regressor", kJointCount, V);
    m.skin_weights = read_csr(f, "/skinning/weights", V, kJointCount);

    for (const LandmarkField& lf : kLandmarkFields) {
        const std::string dataset = std::string("/landmarks/") + lf.name;
        if (!f.exists(dataset)) continue;  // absent, like -1
        const std::int64_t v = f.read_int_scalar(dataset);
        if (v < -1 || v >= V)
            f.fail(dataset, "vertex " + std::to_string(v) + " outside [0, " + std::to_string(V) +
                                ") (or -1 = absent)");
        m.landmarks.*lf.member = static_cast<int>(v);
    }

    m.semantic_map.A = f.read_matrix("/semantic_map/A", K, 1 + kSemanticCount);
    m.semantic_map.b = f.read_vector("/semantic_map/b", K);
    m.semantic_map.reference = f.read_vector("/semantic_map/reference", 1 + kSemanticCount);
    // Optional: a converted model without it lets shape_body() refine every coefficient.
    m.semantic_map.refinable = f.exists("/semantic_map/refinable")
                                   ? f.read_vector("/semantic_map/refinable", K)
                                   : Eigen::VectorXd::Ones(K);
    m.prior.female = read_gaussian(f, "/prior/female");
    m.prior.male = read_gaussian(f, "/prior/male");
    m.density_kg_m3 = f.read_double_scalar("/physical/density_kg_m3");

    check_model(m, [&](const std::string& dataset, const std::string& problem) { f.fail(dataset, problem); });
    // The remaining invariants (closed, consistently oriented surface, ...) have no single
    // dataset to blame.
    std::string why;
    if (!m.is_valid(&why))
        throw InvalidInput("file '" + path.string() + "': the model is inconsistent: " + why);
    return m;
}

// The isolated reader's output: the parsed model as plain bytes (core::ByteEncoder), decoded
// here as untrusted input (every size bounded, every index checked by check_model after).
using Encoder = core::ByteEncoder;
using Decoder = core::ByteDecoder;

void encode(Encoder& e, const GaussianPrior& g) {
    e.matrix(g.mean);
    e.matrix(g.covariance);
    e.matrix(g.min);
    e.matrix(g.max);
    e.i64(g.sample_count);
}

void decode(Decoder& d, GaussianPrior& g) {
    d.matrix(g.mean);
    d.matrix(g.covariance);
    d.matrix(g.min);
    d.matrix(g.max);
    const std::int64_t n = d.i64();
    g.sample_count = static_cast<int>(std::clamp<std::int64_t>(n, -1, std::numeric_limits<int>::max()));
}

std::string encode_model(const BodyModel& m) {
    Encoder e;
    e.str(m.name);
    e.matrix(m.template_vertices);
    e.matrix(m.faces);
    e.matrix(m.shape_basis);
    e.u64(m.shape_names.size());
    for (const std::string& n : m.shape_names) e.str(n);
    e.matrix(m.template_joints);
    e.sparse(m.joint_regressor);
    e.sparse(m.skin_weights);
    for (const LandmarkField& lf : kLandmarkFields) e.i64(m.landmarks.*lf.member);
    e.matrix(m.semantic_map.A);
    e.matrix(m.semantic_map.b);
    e.matrix(m.semantic_map.reference);
    e.matrix(m.semantic_map.refinable);
    encode(e, m.prior.female);
    encode(e, m.prior.male);
    e.f64(m.density_kg_m3);
    return e.take();
}

BodyModel decode_model(const std::string& bytes, const std::filesystem::path& path) {
    Decoder d(bytes, "cannot read '" + path.string() + "': the isolated reader's output is damaged (docs/hardening.md)",
              std::uint64_t(limits::kMaxModelDatasetElements));
    BodyModel m;
    m.name = d.str();
    d.matrix(m.template_vertices);
    d.matrix(m.faces);
    d.matrix(m.shape_basis);
    const std::uint64_t k = d.u64();
    if (k > std::uint64_t(m.shape_basis.cols())) d.fail();  // more names than columns
    m.shape_names.resize(k);
    for (std::string& n : m.shape_names) n = d.str();
    d.matrix(m.template_joints);
    m.joint_regressor = d.sparse();
    m.skin_weights = d.sparse();
    for (const LandmarkField& lf : kLandmarkFields) {
        const std::int64_t v = d.i64();
        m.landmarks.*lf.member = static_cast<int>(std::clamp<std::int64_t>(v, -2, std::numeric_limits<int>::max()));
    }
    d.matrix(m.semantic_map.A);
    d.matrix(m.semantic_map.b);
    d.matrix(m.semantic_map.reference);
    d.matrix(m.semantic_map.refinable);
    decode(d, m.prior.female);
    decode(d, m.prior.male);
    m.density_kg_m3 = d.f64();
    d.finish();
    return m;
}

}  // namespace

BodyModel load_model(const std::filesystem::path& path, const ModelLoadOptions& options) {
    const std::string bytes = limits::read_file_capped(path, limits::kMaxModelFileBytes, "body model file");
    if (!options.isolate) {
        h5::File f(path, bytes);
        return parse_model(f, path, options);
    }
    const core::IsolatedOutcome o = core::run_isolated(
        [&] {
            h5::File f(path, bytes);
            return encode_model(parse_model(f, path, options));
        },
        options.isolation_timeout_s, std::size_t(2 * limits::kMaxModelFileBytes));
    const std::string p = path.string();
    core::throw_unless_finished(o, "cannot read '" + p + "'", "the HDF5 library", options.isolation_timeout_s);
    // Decoded as untrusted bytes, then the same checks as a parse here.
    BodyModel m = decode_model(o.output, path);
    check_model(m, [&](const std::string& dataset, const std::string& problem) {
        throw InvalidInput("file '" + p + "', dataset '" + dataset + "': " + problem);
    });
    std::string why;
    if (!m.is_valid(&why)) throw InvalidInput("file '" + p + "': the model is inconsistent: " + why);
    return m;
}

}  // namespace drape::body
