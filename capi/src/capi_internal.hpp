// Private glue of the C facade: the exception barrier, error reporting, versioned structs,
// buffer copies, monitors (progress + cancel) and the handle types shared by the capi/src files.
#pragma once

#include <drape/drape.h>

#include <drape/body/body_model.hpp>
#include <drape/body/camera.hpp>
#include <drape/body/pose.hpp>
#include <drape/body/semantic_shape.hpp>
#include <drape/body/shape_body.hpp>
#include <drape/core/errors.hpp>
#include <drape/garment/garment_mesh.hpp>
#include <drape/garment/garment_sizing.hpp>
#include <drape/garment/pattern.hpp>

#include <Eigen/Core>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

struct drape_body_model_s {
    std::shared_ptr<const drape::body::BodyModel> model;
};

struct drape_body_s {
    std::shared_ptr<const drape::body::BodyModel> model;
    drape::body::SemanticShape shape;
    drape::body::ShapedBody shaped;
    drape::body::Pose pose;
    drape::body::PosedBody posed;
    /// Set by a fit: the photo's camera and size (drape_render's FITTED camera).
    std::optional<drape::body::Camera> camera;
    int image_width = 0, image_height = 0;
};

struct drape_cancel_flag_s {
    std::atomic<bool> set{false};
};

/// A pattern with the sizing it was made from (when it was made from one).
struct drape_pattern_s {
    drape::garment::Pattern pattern;
    std::optional<drape::garment::GarmentSizing> sizing;
};

/// A garment mesh with its pattern and its current vertices (placement, or draped).
struct drape_garment_mesh_s {
    std::shared_ptr<const drape_pattern_s> pattern;
    std::shared_ptr<const drape::garment::GarmentMesh> mesh;
    Eigen::MatrixX3d positions;
};

namespace drape::capi {

/// Records the message of a failure (on this thread, then to the error function) and
/// returns `status`. The message is built inside a try block: building it may itself run
/// out of memory, and nothing may throw across the boundary; it is then left empty.
drape_status report_failure(drape_status status, const std::string* message) noexcept;

template <class MakeMessage>
drape_status fail(drape_status status, MakeMessage&& make_message) noexcept {
    try {
        const std::string message = make_message();
        return report_failure(status, &message);
    } catch (...) {
        return report_failure(status, nullptr);
    }
}

/// The exception barrier: runs `body` and turns every exception into a status and a message
/// prefixed by the function's name.
template <class F>
drape_status guarded(const char* function, F&& body) noexcept {
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
    return ::drape::capi::fail(DRAPE_ERROR_INVALID_ARGUMENT, [&, function = __func__] { return std::string(function) + ": " + (msg); })

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- versioned structs (docs/c-api.md, "Versioned structs") -------------------------------
// struct_size is the size of the struct the caller was compiled with, which may be older
// (smaller) or newer (larger) than ours. A field is read or written only when it lies wholly
// inside struct_size; struct_size itself is never changed by the library.

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

/// The fields (after struct_size) and defaults of an options struct: specialised per type in
/// the files that own it. fields() returns a tuple of member pointers, first field first.
template <class S>
struct StructTraits;

/// *_init(): every field inside s->struct_size gets its default.
template <class S>
drape_status init_struct(S* s, const char* function, const char* arg) {
    using Traits = StructTraits<S>;
    if (!s) return fail(DRAPE_ERROR_INVALID_ARGUMENT, [&] { return std::string(function) + ": " + arg + " must not be NULL"; });
    if (const drape_status st = check_struct_size(*s, std::get<0>(Traits::fields()), function, arg, Traits::name))
        return st;
    const S d = Traits::defaults();
    std::apply([&](auto... f) { (put(*s, f, d.*f), ...); }, Traits::fields());
    return DRAPE_OK;
}

/// The caller's struct as ours: its fields where it holds them, defaults elsewhere; NULL gives
/// the defaults. \throw drape::InvalidInput if struct_size does not cover the first field.
template <class S>
S read_struct(const S* s, const char* arg) {
    using Traits = StructTraits<S>;
    S out = Traits::defaults();
    out.struct_size = sizeof(S);
    if (!s) return out;
    if (!holds(*s, std::get<0>(Traits::fields())))
        throw drape::InvalidInput(std::string(arg) + "->struct_size is " + std::to_string(s->struct_size) +
                                  ": set it to sizeof(" + Traits::name + ") before the call");
    std::apply([&](auto... f) { ((holds(*s, f) ? (void)(out.*f = s->*f) : (void)0), ...); }, Traits::fields());
    return out;
}

/// A C string argument that may be NULL, as std::string ("" for NULL).
inline std::string str(const char* s) { return s ? std::string(s) : std::string(); }

/// `count` C strings as std::strings. \throw drape::InvalidInput naming `what` if there are
/// none (NULL array or count 0) or one is NULL.
std::vector<std::string> strings_of(const char* const* values, size_t count, const char* what);

/// A copy the caller frees with drape_free(). \throw std::bad_alloc.
char* copy_string(const std::string& s);

/// The size-query protocol: report the size, then copy (converting, row-major) if the buffer
/// fits.
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

/// Row-major caller arrays as Eigen matrices. \throw drape::InvalidInput for a non-finite value
/// or an index outside [0, bound).
Eigen::MatrixX3d rows3(const double* values, size_t count, const char* what);
Eigen::MatrixX2d rows2(const double* values, size_t count, const char* what);
Eigen::MatrixX3i index_rows3(const int32_t* values, size_t count, size_t bound, const char* what);

std::shared_ptr<const drape::body::BodyModel> default_model_ptr();

/// A drape_gender value as the library's optional gender. \throw drape::InvalidInput.
std::optional<drape::body::Gender> gender_of(int32_t gender, const char* arg);

/// A monitor for one long call: progress reports and the cancel flag.
class Monitor {
public:
    /// \throw drape::InvalidInput if monitor->struct_size is too small.
    Monitor(const drape_monitor* monitor, const char* operation);
    /// True if the cancel flag is set (or the callback asked to stop before).
    bool cancelled() const;
    /// Reports progress; false: stop (cancel flag set or the callback returned 0).
    bool report(const std::string& stage, int garment = -1, int round = 0, int64_t step = 0, double fraction = -1,
                double eta_seconds = -1);
    double seconds() const;

private:
    drape_progress_function progress_ = nullptr;
    void* user_ = nullptr;
    drape_cancel_flag cancel_ = nullptr;
    const char* operation_;
    std::chrono::steady_clock::time_point start_;
    std::atomic<bool> stopped_{false};  // the callback returned 0 (read by other threads too)
};

/// A new garment mesh handle owning copies of a result's pattern, sizing, mesh and vertices
/// (recoveries and try-ons hand their garments out this way).
drape_garment_mesh_s* new_garment_mesh(const drape::garment::Pattern& pattern,
                                       const drape::garment::GarmentSizing& sizing,
                                       const drape::garment::GarmentMesh& mesh, const Eigen::MatrixX3d& positions);

/// A new body handle of `model` with this shape at rest and in `pose`.
drape_body_s* new_body(std::shared_ptr<const drape::body::BodyModel> model, const drape::body::SemanticShape& shape,
                       const drape::body::ShapedBody& shaped, const drape::body::Pose& pose);

/// DRAPE_ERROR_CANCELLED with a message naming the call.
drape_status cancelled(const char* function);

}  // namespace drape::capi
