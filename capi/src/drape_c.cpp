// The C facade: every entry point converts exceptions into a drape_status and a per-thread
// message; nothing throws across the boundary.
#include <drape/drape.h>

#include <drape/body/body_model.hpp>
#include <drape/body/measurements.hpp>
#include <drape/body/model_io.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/body/shape_prior.hpp>
#include <drape/core/errors.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <string>

struct drape_body_model_s {
    std::shared_ptr<const drape::body::BodyModel> model;
};

struct drape_body_s {
    std::shared_ptr<const drape::body::BodyModel> model;
    drape::body::SemanticShape shape;
    drape::body::ShapedBody shaped;
    drape::body::Pose pose;
    drape::body::PosedBody posed;
};

namespace {

namespace db = drape::body;

thread_local std::string g_last_error;

// Records the message of a failure and returns `status`. The message is built here, inside
// a try block: building it may itself run out of memory (also while handling bad_alloc), and
// nothing may throw across the boundary. Then the message is left empty.
template <class MakeMessage>
drape_status fail(drape_status status, MakeMessage&& make_message) noexcept {
    try {
        g_last_error = make_message();
    } catch (...) {
        g_last_error.clear();
    }
    return status;
}

template <class F>
drape_status guarded(const char* function, F&& body) {
    try {
        return body();
    } catch (const drape::InvalidInput& e) {
        return fail(DRAPE_ERROR_INVALID_ARGUMENT, [&] { return std::string(function) + ": " + e.what(); });
    } catch (const drape::IoError& e) {
        return fail(DRAPE_ERROR_IO, [&] { return std::string(function) + ": " + e.what(); });
    } catch (const std::bad_alloc&) {
        return fail(DRAPE_ERROR_OUT_OF_MEMORY, [&] { return std::string(function) + ": out of memory"; });
    } catch (const std::exception& e) {
        return fail(DRAPE_ERROR_INTERNAL, [&] { return std::string(function) + ": internal error: " + e.what(); });
    } catch (...) {
        return fail(DRAPE_ERROR_INTERNAL, [&] { return std::string(function) + ": unknown internal error"; });
    }
}

#define DRAPE_REQUIRE_ARG(cond, msg) \
    if (!(cond))                     \
    return fail(DRAPE_ERROR_INVALID_ARGUMENT, [&, function = __func__] { return std::string(function) + ": " + (msg); })

std::shared_ptr<const db::BodyModel> default_model_ptr() {
    // Non-owning alias of the library's cached built-in model.
    return std::shared_ptr<const db::BodyModel>(&db::BodyModel::default_model(),
                                                [](const db::BodyModel*) {});
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

// Versioned structs (docs/c-api.md, "Versioned structs"): struct_size is the size of the
// struct the caller was compiled with, which may be older (smaller) or newer (larger) than
// ours. A field is read or written only when it lies wholly inside struct_size; struct_size
// itself is never changed by the library.
template <class S, class T>
size_t end_of(T S::*field) {
    static const S probe{};
    return static_cast<size_t>(reinterpret_cast<const char*>(&(probe.*field)) -
                               reinterpret_cast<const char*>(&probe)) +
           sizeof(T);
}

template <class S, class T>
bool holds(const S& s, T S::*field) {
    return end_of(field) <= s.struct_size;
}

template <class S, class T>
void put(S& s, T S::*field, const T& value) {
    if (holds(s, field)) s.*field = value;
}

// A struct must at least hold its first field after struct_size; a smaller struct_size
// means the caller did not set it.
template <class S, class T>
drape_status check_struct_size(const S& s, T S::*first_field, const char* function, const char* arg,
                               const char* type) {
    if (holds(s, first_field)) return DRAPE_OK;
    return fail(DRAPE_ERROR_INVALID_ARGUMENT, [&] {
        return std::string(function) + ": " + arg + "->struct_size is " + std::to_string(s.struct_size) +
               ": set it to sizeof(" + type + ") before the call";
    });
}

void repose(drape_body_s& b) { b.posed = db::pose_body(*b.model, b.shaped, b.pose); }

// The size-query protocol: report the size, then copy (converting, row-major) if the buffer
// fits. M is #rows x 3.
template <class Out, class Matrix>
drape_status copy_rows(const Matrix& M, Out* out, size_t capacity, size_t* required, const char* what) {
    const size_t n = static_cast<size_t>(M.size());
    if (required) *required = n;
    if (!out) return DRAPE_OK;
    if (capacity < n)
        return fail(DRAPE_ERROR_INVALID_ARGUMENT, [&] {
            return std::string(what) + ": buffer holds " + std::to_string(capacity) + " values, " +
                   std::to_string(n) + " needed";
        });
    const Eigen::Index cols = M.cols();
    for (Eigen::Index r = 0; r < M.rows(); ++r)
        for (Eigen::Index c = 0; c < cols; ++c) out[r * cols + c] = static_cast<Out>(M(r, c));
    return DRAPE_OK;
}

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

extern "C" {

// DRAPE_VERSION_STRING is CMake's PROJECT_VERSION (capi/CMakeLists.txt).
const char* drape_version(void) { return DRAPE_VERSION_STRING; }

const char* drape_status_string(drape_status status) {
    switch (status) {
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
    return guarded(__func__, [&] { return copy_rows(body->posed.vertices, out, capacity, required, __func__); });
}

drape_status drape_body_get_joints(drape_body body, double* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    return guarded(__func__, [&] { return copy_rows(body->posed.joints, out, capacity, required, __func__); });
}

drape_status drape_body_get_faces(drape_body body, int32_t* out, size_t capacity, size_t* required) {
    DRAPE_REQUIRE_ARG(body, "body must not be NULL");
    return guarded(__func__, [&] { return copy_rows(body->model->faces, out, capacity, required, __func__); });
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
