// The C facade, part 1: errors, version, memory, cancel flags and monitors; bodies (create,
// shape, pose, measure, fit, export). Every entry point converts exceptions into a
// drape_status and a per-thread message; nothing throws across the boundary.
#include "capi_internal.hpp"

#include <drape/io/body_fit_files.hpp>
#include <drape/io/body_json.hpp>
#include <drape/io/recovery_files.hpp>

#include <drape/body/fit_body.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/model_io.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/body/shape_prior.hpp>
#include <drape/core/errors.hpp>
#include <drape/core/limits.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>

namespace {

namespace db = drape::body;
using namespace drape::capi;

thread_local std::string g_last_error;

// The error function of drape_set_error_function: process-wide, read under the lock and
// called outside it.
struct ErrorFunction {
    std::mutex mutex;
    drape_error_function function = nullptr;
    void* user = nullptr;
};
ErrorFunction& error_function() {
    static ErrorFunction f;
    return f;
}

}  // namespace

namespace drape::capi {

drape_status report_failure(drape_status status, const std::string* message) noexcept {
    try {
        if (message) g_last_error = *message;
        else g_last_error.clear();
    } catch (...) {
        g_last_error.clear();
    }
    drape_error_function function = nullptr;
    void* user = nullptr;
    {
        ErrorFunction& f = error_function();
        std::lock_guard<std::mutex> lock(f.mutex);
        function = f.function;
        user = f.user;
    }
    if (function) function(user, status, g_last_error.c_str());
    return status;
}

char* copy_string(const std::string& s) {
    char* out = static_cast<char*>(std::malloc(s.size() + 1));
    if (!out) throw std::bad_alloc();
    std::memcpy(out, s.c_str(), s.size() + 1);
    return out;
}

namespace {
template <int Cols>
Eigen::Matrix<double, Eigen::Dynamic, Cols> real_rows(const double* values, size_t count, const char* what) {
    if (!values) throw drape::InvalidInput(std::string(what) + " must not be NULL");
    // Refused before anything is copied: a mesh handed over as arrays is bounded as a mesh
    // file is (docs/hardening.md, "Resource limits").
    if (count > static_cast<size_t>(drape::limits::kMaxMeshVertices))
        throw drape::InvalidInput(std::string(what) + ": " + std::to_string(count) +
                                  " vertices, more than the limit of " +
                                  std::to_string(drape::limits::kMaxMeshVertices) + " (docs/hardening.md)");
    Eigen::Matrix<double, Eigen::Dynamic, Cols> M(static_cast<Eigen::Index>(count), Cols);
    for (size_t r = 0; r < count; ++r)
        for (int c = 0; c < Cols; ++c) {
            const double v = values[r * Cols + c];
            if (!std::isfinite(v))
                throw drape::InvalidInput(std::string(what) + "[" + std::to_string(r * Cols + c) + "] = " +
                                          std::to_string(v) + " is not finite");
            M(static_cast<Eigen::Index>(r), c) = v;
        }
    return M;
}
}  // namespace

Eigen::MatrixX3d rows3(const double* values, size_t count, const char* what) { return real_rows<3>(values, count, what); }
Eigen::MatrixX2d rows2(const double* values, size_t count, const char* what) { return real_rows<2>(values, count, what); }

Eigen::MatrixX3i index_rows3(const int32_t* values, size_t count, size_t bound, const char* what) {
    if (!values) throw drape::InvalidInput(std::string(what) + " must not be NULL");
    if (count > static_cast<size_t>(drape::limits::kMaxMeshFaces))
        throw drape::InvalidInput(std::string(what) + ": " + std::to_string(count) +
                                  " triangles, more than the limit of " +
                                  std::to_string(drape::limits::kMaxMeshFaces) + " (docs/hardening.md)");
    Eigen::MatrixX3i M(static_cast<Eigen::Index>(count), 3);
    for (size_t r = 0; r < count; ++r)
        for (int c = 0; c < 3; ++c) {
            const int32_t v = values[r * 3 + c];
            if (v < 0 || static_cast<size_t>(v) >= bound)
                throw drape::InvalidInput(std::string(what) + "[" + std::to_string(r * 3 + c) + "] = " +
                                          std::to_string(v) + " is outside [0, " + std::to_string(bound) + ")");
            M(static_cast<Eigen::Index>(r), c) = v;
        }
    return M;
}

std::shared_ptr<const db::BodyModel> default_model_ptr() {
    // Non-owning alias of the library's cached built-in model.
    return std::shared_ptr<const db::BodyModel>(&db::BodyModel::default_model(), [](const db::BodyModel*) {});
}

std::optional<db::Gender> gender_of(int32_t gender, const char* arg) {
    if (gender == DRAPE_GENDER_FEMALE) return db::Gender::female;
    if (gender == DRAPE_GENDER_MALE) return db::Gender::male;
    if (gender == DRAPE_GENDER_UNSPECIFIED) return std::nullopt;
    throw drape::InvalidInput(std::string(arg) + " = " + std::to_string(gender) + " is not a drape_gender value");
}

Monitor::Monitor(const drape_monitor* monitor, const char* operation)
    : operation_(operation), start_(std::chrono::steady_clock::now()) {
    if (!monitor) return;
    if (!holds(*monitor, &drape_monitor::progress))
        throw drape::InvalidInput("monitor->struct_size is " + std::to_string(monitor->struct_size) +
                                  ": set it to sizeof(drape_monitor) before the call");
    progress_ = monitor->progress;
    if (holds(*monitor, &drape_monitor::user)) user_ = monitor->user;
    if (holds(*monitor, &drape_monitor::cancel)) cancel_ = monitor->cancel;
}

bool Monitor::cancelled() const {
    return stopped_.load(std::memory_order_relaxed) || (cancel_ && cancel_->set.load(std::memory_order_relaxed));
}

double Monitor::seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool Monitor::report(const std::string& stage, int garment, int round, int64_t step, double fraction,
                     double eta_seconds) {
    if (cancelled()) return false;
    if (!progress_) return true;
    drape_progress p;
    p.struct_size = sizeof p;
    p.operation = operation_;
    p.stage = stage.c_str();
    p.garment = garment;
    p.round = round;
    p.step = step;
    p.fraction = fraction;
    p.seconds = seconds();
    p.eta_seconds = eta_seconds;
    if (progress_(user_, &p) == 0) stopped_ = true;
    return !cancelled();
}

drape_status cancelled(const char* function) {
    return fail(DRAPE_ERROR_CANCELLED, [&] { return std::string(function) + ": cancelled"; });
}

std::vector<std::string> strings_of(const char* const* values, size_t count, const char* what) {
    if (count == 0 || !values)
        throw drape::InvalidInput(std::string(what) + ": give at least one result folder (\"DIR\" or \"DIR:N\")");
    std::vector<std::string> out;
    for (size_t k = 0; k < count; ++k) {
        if (!values[k]) throw drape::InvalidInput(std::string(what) + "[" + std::to_string(k) + "] must not be NULL");
        out.emplace_back(values[k]);
    }
    return out;
}

drape_body_s* new_body(std::shared_ptr<const drape::body::BodyModel> model, const drape::body::SemanticShape& shape,
                       const drape::body::ShapedBody& shaped, const drape::body::Pose& pose) {
    auto b = std::make_unique<drape_body_s>();
    b->model = std::move(model);
    b->shape = shape;
    b->shaped = shaped;
    b->pose = pose;
    b->posed = drape::body::pose_body(*b->model, b->shaped, b->pose);
    return b.release();
}

}  // namespace drape::capi

namespace {

double drape_shape_params::*param_field(db::Semantic s) {
    switch (s) {
        case db::Semantic::height_m: return &drape_shape_params::height_m;
        case db::Semantic::weight_kg: return &drape_shape_params::weight_kg;
        case db::Semantic::muscle: return &drape_shape_params::muscle;
        case db::Semantic::chest_girth_m: return &drape_shape_params::chest_girth_m;
        case db::Semantic::waist_girth_m: return &drape_shape_params::waist_girth_m;
        case db::Semantic::hip_girth_m: return &drape_shape_params::hip_girth_m;
        case db::Semantic::thigh_girth_m: return &drape_shape_params::thigh_girth_m;
        case db::Semantic::calf_girth_m: return &drape_shape_params::calf_girth_m;
        case db::Semantic::shoulder_height_m: return &drape_shape_params::shoulder_height_m;
        case db::Semantic::crotch_height_m: return &drape_shape_params::crotch_height_m;
    }
    return nullptr;
}

void repose(drape_body_s& b) { b.posed = db::pose_body(*b.model, b.shaped, b.pose); }

void fill_shape_params(drape_shape_params& p, int32_t gender, const double* values) {
    put(p, &drape_shape_params::gender, gender);
    for (int k = 0; k < db::kSemanticCount; ++k)
        put(p, param_field(static_cast<db::Semantic>(k)), values ? values[k] : kNaN);
}

void fill_measurements(drape_measurements& out, const db::BodyMeasurements& m) {
    put(out, &drape_measurements::height_m, m.height_m);
    put(out, &drape_measurements::weight_kg, m.weight_kg);
    put(out, &drape_measurements::chest_girth_m, m.chest_girth_m);
    put(out, &drape_measurements::waist_girth_m, m.waist_girth_m);
    put(out, &drape_measurements::hip_girth_m, m.hip_girth_m);
    put(out, &drape_measurements::thigh_girth_m, m.thigh_girth_m);
    put(out, &drape_measurements::calf_girth_m, m.calf_girth_m);
    put(out, &drape_measurements::shoulder_height_m, m.shoulder_height_m);
    put(out, &drape_measurements::crotch_height_m, m.crotch_height_m);
}

}  // namespace

namespace drape::capi {

template <>
struct StructTraits<drape_fit_inputs> {
    static constexpr const char* name = "drape_fit_inputs";
    static auto fields() {
        using S = drape_fit_inputs;
        return std::make_tuple(&S::image_path, &S::joints_path, &S::silhouette_path, &S::skin_path, &S::labels_path,
                               &S::height_m, &S::gender);
    }
    static drape_fit_inputs defaults() {
        drape_fit_inputs d{};
        d.struct_size = sizeof d;
        d.height_m = kNaN;
        d.gender = DRAPE_GENDER_UNSPECIFIED;
        return d;
    }
};

template <>
struct StructTraits<drape_fit_options> {
    static constexpr const char* name = "drape_fit_options";
    static auto fields() {
        using S = drape_fit_options;
        return std::make_tuple(&S::focal_px, &S::threads, &S::fit_shape, &S::posture_weight, &S::lean_weight,
                               &S::image_joints, &S::skin_weight);
    }
    static drape_fit_options defaults() {
        drape_fit_options d{};
        d.struct_size = sizeof d;
        d.focal_px = 0;
        d.threads = 2;
        d.fit_shape = 1;
        const drape::body::FitOptions fo;
        d.posture_weight = fo.posture_weight;
        d.lean_weight = fo.lean_weight;
        d.image_joints = DRAPE_IMAGE_JOINTS_FROM_FILE;
        d.skin_weight = fo.skin_weight;
        return d;
    }
};

}  // namespace drape::capi

extern "C" {

// DRAPE_VERSION_STRING is CMake's PROJECT_VERSION (capi/CMakeLists.txt).
const char* drape_version(void) { return DRAPE_VERSION_STRING; }

const char* drape_status_string(drape_status status) {
    // A C caller may pass any int (C enums are ints): read the value as one, since a C++ load
    // of a drape_status outside its enumerators' range is undefined (clang's UBSan "enum"
    // check, the C API's ASan stage).
    static_assert(sizeof(drape_status) == sizeof(std::int32_t));
    std::int32_t code = 0;
    std::memcpy(&code, &status, sizeof code);
    switch (code) {
        case DRAPE_OK: return "ok";
        case DRAPE_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case DRAPE_ERROR_IO: return "input/output error";
        case DRAPE_ERROR_NO_CONVERGENCE: return "no convergence";
        case DRAPE_ERROR_OUT_OF_MEMORY: return "out of memory";
        case DRAPE_ERROR_CANCELLED: return "cancelled";
        case DRAPE_ERROR_INTERNAL: return "internal error";
    }
    return "unknown status";
}

const char* drape_last_error_message(void) { return g_last_error.c_str(); }

void drape_set_error_function(drape_error_function function, void* user) {
    ErrorFunction& f = error_function();
    std::lock_guard<std::mutex> lock(f.mutex);
    f.function = function;
    f.user = user;
}

void drape_free(void* memory) { std::free(memory); }

drape_status drape_cancel_flag_create(drape_cancel_flag* out_flag) {
    DRAPE_REQUIRE_ARG(out_flag, "out_flag must not be NULL");
    *out_flag = nullptr;
    return guarded(__func__, [&] {
        *out_flag = new drape_cancel_flag_s();
        return DRAPE_OK;
    });
}

void drape_cancel_flag_destroy(drape_cancel_flag flag) { delete flag; }

void drape_cancel_flag_set(drape_cancel_flag flag) {
    if (flag) flag->set.store(true, std::memory_order_relaxed);
}

void drape_cancel_flag_reset(drape_cancel_flag flag) {
    if (flag) flag->set.store(false, std::memory_order_relaxed);
}

int32_t drape_cancel_flag_is_set(drape_cancel_flag flag) {
    return flag && flag->set.load(std::memory_order_relaxed) ? 1 : 0;
}

drape_status drape_monitor_init(drape_monitor* m) {
    DRAPE_REQUIRE_ARG(m, "monitor must not be NULL");
    if (const drape_status st = check_struct_size(*m, &drape_monitor::progress, __func__, "monitor", "drape_monitor"))
        return st;
    put(*m, &drape_monitor::progress, static_cast<drape_progress_function>(nullptr));
    put(*m, &drape_monitor::user, static_cast<void*>(nullptr));
    put(*m, &drape_monitor::cancel, static_cast<drape_cancel_flag>(nullptr));
    return DRAPE_OK;
}

drape_status drape_fit_inputs_init(drape_fit_inputs* inputs) { return init_struct(inputs, __func__, "inputs"); }
drape_status drape_fit_options_init(drape_fit_options* options) { return init_struct(options, __func__, "options"); }

drape_status drape_body_model_load(const char* path, drape_body_model* out_model) {
    DRAPE_REQUIRE_ARG(path && out_model, "path and out_model must not be NULL");
    *out_model = nullptr;
    return guarded(__func__, [&] {
        auto handle = std::make_unique<drape_body_model_s>();
        handle->model = std::make_shared<const db::BodyModel>(db::load_model(path));
        *out_model = handle.release();
        return DRAPE_OK;
    });
}

drape_status drape_body_model_save(drape_body_model model, const char* path) {
    DRAPE_REQUIRE_ARG(model && path, "model and path must not be NULL");
    return guarded(__func__, [&] {
        db::save_model(*model->model, path);
        return DRAPE_OK;
    });
}

drape_status drape_body_model_default(drape_body_model* out_model) {
    DRAPE_REQUIRE_ARG(out_model, "out_model must not be NULL");
    *out_model = nullptr;
    return guarded(__func__, [&] {
        auto handle = std::make_unique<drape_body_model_s>();
        handle->model = default_model_ptr();
        *out_model = handle.release();
        return DRAPE_OK;
    });
}

void drape_body_model_destroy(drape_body_model model) { delete model; }

drape_status drape_shape_params_init(drape_shape_params* p) {
    DRAPE_REQUIRE_ARG(p, "params must not be NULL");
    if (const drape_status st = check_struct_size(*p, &drape_shape_params::gender, __func__, "params",
                                                  "drape_shape_params"))
        return st;
    fill_shape_params(*p, DRAPE_GENDER_UNSPECIFIED, nullptr);
    return DRAPE_OK;
}

drape_status drape_measurements_init(drape_measurements* m) {
    DRAPE_REQUIRE_ARG(m, "measurements must not be NULL");
    if (const drape_status st = check_struct_size(*m, &drape_measurements::height_m, __func__, "m",
                                                  "drape_measurements"))
        return st;
    fill_measurements(*m, db::BodyMeasurements{});  // all zero
    return DRAPE_OK;
}

size_t drape_joint_count(void) { return db::kJointCount; }

const char* drape_joint_name(size_t joint) {
    return joint < static_cast<size_t>(db::kJointCount) ? db::kJointNames[joint].data() : nullptr;
}

drape_status drape_body_create(drape_body_model model, drape_body* out_body) {
    DRAPE_REQUIRE_ARG(out_body, "out_body must not be NULL");
    *out_body = nullptr;
    return guarded(__func__, [&] {
        auto body = std::make_unique<drape_body_s>();
        body->model = model ? model->model : default_model_ptr();
        body->shape = body->model->prior.complete(db::SemanticRequest{});
        db::shape_body(*body->model, body->shape, db::ShapeOptions{}, body->shaped);
        repose(*body);
        *out_body = body.release();
        return DRAPE_OK;
    });
}

void drape_body_destroy(drape_body body) { delete body; }

drape_status drape_body_set_shape(drape_body body, const drape_shape_params* params) {
    DRAPE_REQUIRE_ARG(body && params, "body and params must not be NULL");
    if (const drape_status st = check_struct_size(*params, &drape_shape_params::gender, __func__, "params",
                                                  "drape_shape_params"))
        return st;
    return guarded(__func__, [&] {
        db::SemanticRequest request;
        // Fields beyond the caller's struct_size are "not given".
        if (params->gender == DRAPE_GENDER_FEMALE) request.gender = db::Gender::female;
        else if (params->gender == DRAPE_GENDER_MALE) request.gender = db::Gender::male;
        else if (params->gender != DRAPE_GENDER_UNSPECIFIED)
            throw drape::InvalidInput("gender = " + std::to_string(static_cast<int>(params->gender)) +
                                      " is not a drape_gender value");
        for (int k = 0; k < db::kSemanticCount; ++k) {
            const auto field = param_field(static_cast<db::Semantic>(k));
            if (holds(*params, field) && !std::isnan(params->*field)) request.values[k] = params->*field;
        }
        const db::SemanticShape shape = body->model->prior.complete(request);
        db::ShapedBody shaped;
        const db::ShapeSummary summary = db::shape_body(*body->model, shape, db::ShapeOptions{}, shaped);
        body->shape = shape;
        body->shaped = std::move(shaped);
        repose(*body);
        if (summary.termination == db::ShapeTermination::failed ||
            summary.termination == db::ShapeTermination::max_iterations)
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return "drape_body_set_shape: " + summary.brief_report(); });
        return DRAPE_OK;
    });
}

drape_status drape_body_get_shape(drape_body body, drape_shape_params* out) {
    DRAPE_REQUIRE_ARG(body && out, "body and out_params must not be NULL");
    if (const drape_status st = check_struct_size(*out, &drape_shape_params::gender, __func__, "out_params",
                                                  "drape_shape_params"))
        return st;
    fill_shape_params(*out, body->shape.gender == db::Gender::female ? DRAPE_GENDER_FEMALE : DRAPE_GENDER_MALE,
                      body->shape.values.data());
    return DRAPE_OK;
}

drape_status drape_body_set_pose(drape_body body, const double* rotations, size_t rotation_count,
                                 const double* translation) {
    DRAPE_REQUIRE_ARG(body && rotations, "body and rotations must not be NULL");
    DRAPE_REQUIRE_ARG(rotation_count == static_cast<size_t>(db::kJointCount) * 3,
                      "rotation_count is " + std::to_string(rotation_count) + ", expected " +
                          std::to_string(db::kJointCount * 3) + " (joint_count x 3)");
    return guarded(__func__, [&] {
        db::Pose pose;
        for (int j = 0; j < db::kJointCount; ++j)
            for (int k = 0; k < 3; ++k) pose.rotations(j, k) = rotations[3 * j + k];
        if (translation) pose.translation = Eigen::Vector3d(translation[0], translation[1], translation[2]);
        std::string why;
        if (!pose.is_valid(&why)) throw drape::InvalidInput(why);
        body->pose = pose;
        repose(*body);
        return DRAPE_OK;
    });
}

drape_status drape_body_get_counts(drape_body body, size_t* vertex_count, size_t* face_count) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    if (vertex_count) *vertex_count = static_cast<size_t>(body->model->vertex_count());
    if (face_count) *face_count = static_cast<size_t>(body->model->faces.rows());
    return DRAPE_OK;
}

// The buffers are written without temporaries; the barrier still covers all the work.
drape_status drape_body_get_vertices(drape_body body, double* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_rows(body->posed.vertices, out, capacity, required, function); });
}

drape_status drape_body_get_joints(drape_body body, double* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_rows(body->posed.joints, out, capacity, required, function); });
}

drape_status drape_body_get_faces(drape_body body, int32_t* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    return guarded(__func__, [&, function = __func__] { return copy_rows(body->model->faces, out, capacity, required, function); });
}

drape_status drape_body_measure(drape_body body, drape_measurements* out) {
    DRAPE_REQUIRE_ARG(body && out, "body and out must not be NULL");
    if (const drape_status st =
            check_struct_size(*out, &drape_measurements::height_m, __func__, "out", "drape_measurements"))
        return st;
    return guarded(__func__, [&] {
        fill_measurements(*out, db::measure_body(*body->model, body->shaped.vertices));
        return DRAPE_OK;
    });
}

drape_status drape_body_export(drape_body body, const char* path) {
    DRAPE_REQUIRE_ARG(body && path, "body and path must not be NULL");
    return guarded(__func__, [&] {
        const std::filesystem::path p(path);
        const std::string ext = p.extension().string();
        if (ext == ".glb") {
            db::export_glb(p, *body->model, body->shaped, body->pose);
        } else if (ext == ".obj") {
            db::export_obj(p, body->posed.vertices, body->model->faces);
        } else {
            throw drape::InvalidInput("path '" + p.string() + "' must end in .glb or .obj");
        }
        return DRAPE_OK;
    });
}

}  // extern "C"

namespace {

// drape_body_fit and drape_body_fit_to_folder: the fit, then (with a folder) its files.
drape_status fit_body_call(const char* function, drape_body body, const drape_fit_inputs* inputs,
                           const drape_fit_options* options, const drape_monitor* monitor, const char* folder,
                           char** out_json) {
    if (out_json) *out_json = nullptr;
    return guarded(function, [&] {
        const drape_fit_inputs in = read_struct(inputs, "inputs");
        const drape_fit_options opt = read_struct(options, "options");
        if (!in.image_path) throw drape::InvalidInput("inputs->image_path must not be NULL");
        if (!in.joints_path) throw drape::InvalidInput("inputs->joints_path must not be NULL");
        Monitor mon(monitor, "fit_body");
        drape::io::BodyFitFiles files = drape::io::read_body_fit_files(
            in.image_path, in.joints_path, str(in.silhouette_path), str(in.skin_path), str(in.labels_path));
        if (!std::isnan(in.height_m)) files.inputs.height_m = in.height_m;
        files.inputs.gender = gender_of(in.gender, "inputs->gender");
        db::FitOptions fo;
        fo.threads = opt.threads;
        fo.fit_shape = opt.fit_shape != 0;
        fo.posture_weight = opt.posture_weight;
        fo.lean_weight = opt.lean_weight;
        fo.skin_weight = opt.skin_weight;
        if (opt.image_joints == DRAPE_IMAGE_JOINTS_MODEL)
            fo.image_joints = db::ImageJointOffsets::none();
        else if (opt.image_joints == DRAPE_IMAGE_JOINTS_HAND_MARKED)
            fo.image_joints = db::ImageJointOffsets::hand_marked();
        else if (opt.image_joints != DRAPE_IMAGE_JOINTS_FROM_FILE)
            throw drape::InvalidInput("options->image_joints must be DRAPE_IMAGE_JOINTS_FROM_FILE (0), "
                                      "DRAPE_IMAGE_JOINTS_HAND_MARKED (1) or DRAPE_IMAGE_JOINTS_MODEL (2), got " +
                                      std::to_string(opt.image_joints));
        if (opt.focal_px != 0) {
            fo.camera = db::CameraModel::pinhole;
            fo.focal_px = opt.focal_px;
        }
        std::string why;
        if (!fo.is_valid(&why)) throw drape::InvalidInput("options: " + why);
        // An unwritable folder is refused before the fit, not after it.
        if (folder) drape::io::check_output_folder(folder);
        fo.progress = [&](double fraction) { return mon.report("fitting", -1, 0, 0, fraction); };
        if (!mon.report("reading", -1, 0, 0, 0)) return cancelled(function);
        db::BodyFit fit;
        const db::FitSummary summary = db::fit_body(*body->model, files.inputs, fo, fit);
        if (summary.termination == db::Termination::cancelled || mon.cancelled()) return cancelled(function);
        if (!summary.usable())
            return fail(DRAPE_ERROR_NO_CONVERGENCE, [&] { return std::string(function) + ": " + summary.brief_report(); });
        db::ShapedBody shaped = db::shape_from_coefficients(*body->model, fit.coefficients);
        db::PosedBody posed = db::pose_body(*body->model, shaped, fit.pose);
        char* json = nullptr;
        if (out_json || folder) {
            const db::FitQuality quality = db::fit_quality(*body->model, files.inputs, fit, summary);
            nlohmann::json j;
            if (folder) {
                if (!mon.report("writing", -1, 0, 0, 1)) return cancelled(function);
                j = drape::io::write_body_fit_folder(folder, in.image_path, files, *body->model, fit, summary, quality);
            } else {
                j = drape::io::body_fit_json(in.image_path, files, *body->model, fit, summary, quality);
            }
            if (out_json) json = copy_string(j.dump(2));
        }
        // Nothing below throws: the body changes only when the whole call succeeds.
        body->shape = fit.shape;
        body->shaped = std::move(shaped);
        body->pose = fit.pose;
        body->posed = std::move(posed);
        body->camera = fit.camera;
        body->image_width = files.photo.cols;
        body->image_height = files.photo.rows;
        if (out_json) *out_json = json;
        return DRAPE_OK;
    });
}

}  // namespace

extern "C" {

drape_status drape_body_fit(drape_body body, const drape_fit_inputs* inputs, const drape_fit_options* options,
                            const drape_monitor* monitor, char** out_json) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    DRAPE_REQUIRE_ARG(inputs, "inputs must not be NULL");
    return fit_body_call(__func__, body, inputs, options, monitor, nullptr, out_json);
}

drape_status drape_body_fit_to_folder(drape_body body, const drape_fit_inputs* inputs,
                                      const drape_fit_options* options, const drape_monitor* monitor,
                                      const char* folder, char** out_json) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    DRAPE_REQUIRE_ARG(inputs, "inputs must not be NULL");
    DRAPE_REQUIRE_ARG(folder, "folder must not be NULL");
    return fit_body_call(__func__, body, inputs, options, monitor, folder, out_json);
}

drape_status drape_body_to_json(drape_body body, char** out_json) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    DRAPE_REQUIRE_ARG(out_json, "out_json must not be NULL");
    *out_json = nullptr;
    return guarded(__func__, [&] {
        const nlohmann::json j = {{"shape", drape::io::to_json(body->shape)}, {"pose", drape::io::to_json(body->pose)}};
        *out_json = copy_string(j.dump(2));
        return DRAPE_OK;
    });
}

}  // extern "C"
