/* Drape C API: bodies (and, as later issues land, garments) behind opaque handles.
 *
 * Rules (see docs/c-api.md):
 *  - Every function returns drape_status; on failure drape_last_error_message() (per
 *    thread) says what went wrong. No exception or abort crosses this boundary.
 *  - Inputs are borrowed for the duration of the call. Outputs go to caller buffers after
 *    a size query (pass NULL to learn the size) or to handles the caller destroys.
 *  - *_destroy(NULL) is a no-op. Distinct handles may be used from distinct threads at
 *    once; one handle must not be used from two threads at the same time.
 *  - Options/parameter structs start with uint32_t struct_size. The caller sets it to
 *    sizeof the struct it was compiled with, then calls the *_init() function. The library
 *    never changes struct_size and reads or writes only the fields that lie wholly inside
 *    it, so fields can be appended without breaking callers built against older headers.
 *  - Units: metres, kilograms, radians. Frame: +Y up, the body faces +Z, its left is +X.
 */
#ifndef DRAPE_DRAPE_H
#define DRAPE_DRAPE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum drape_status {
    DRAPE_OK = 0,
    DRAPE_ERROR_INVALID_ARGUMENT = 1,
    DRAPE_ERROR_IO = 2,
    DRAPE_ERROR_NO_CONVERGENCE = 3,
    DRAPE_ERROR_OUT_OF_MEMORY = 4,
    DRAPE_ERROR_CANCELLED = 5, /* a long call's progress callback asked to stop */
    DRAPE_ERROR_INTERNAL = 6
} drape_status;

/** Library version, "MAJOR.MINOR.PATCH" (the CMake project version). Never NULL. */
const char* drape_version(void);
/** A fixed English description of a status code. Never NULL. */
const char* drape_status_string(drape_status status);
/** The message of the last failed call on this thread ("" if none). Valid until the next
 *  failing call on this thread. */
const char* drape_last_error_message(void);

/* ---- body model ------------------------------------------------------------------- */

typedef struct drape_body_model_s* drape_body_model;

/** Loads a body model file (HDF5, docs/body-model-format.md). */
drape_status drape_body_model_load(const char* path, drape_body_model* out_model);
/** Writes a model to an HDF5 file (atomically). */
drape_status drape_body_model_save(drape_body_model model, const char* path);
/** A handle on the built-in mannequin model (generated on first use, then shared). */
drape_status drape_body_model_default(drape_body_model* out_model);
void drape_body_model_destroy(drape_body_model model);

/* ---- body: shape, pose, geometry ---------------------------------------------------- */

typedef struct drape_body_s* drape_body;

typedef enum drape_gender {
    DRAPE_GENDER_UNSPECIFIED = 0,
    DRAPE_GENDER_FEMALE = 1,
    DRAPE_GENDER_MALE = 2
} drape_gender;

/** Semantic shape parameters. A NaN value means "not given": it is predicted from the
 *  ANSUR II prior given the others. */
typedef struct drape_shape_params {
    uint32_t struct_size;
    int32_t gender; /* a drape_gender value */
    double height_m;
    double weight_kg;
    double muscle; /* 0..1 */
    double chest_girth_m;
    double waist_girth_m;
    double hip_girth_m;
    double thigh_girth_m;
    double calf_girth_m;
    double shoulder_height_m;
    double crotch_height_m;
} drape_shape_params;

/** Sets every value (that fits in params->struct_size) to "not given" and gender to
 *  DRAPE_GENDER_UNSPECIFIED. Set params->struct_size = sizeof(drape_shape_params) first. */
drape_status drape_shape_params_init(drape_shape_params* params);

/** Measurements taken on the body mesh at rest, like a tailor's tape. */
typedef struct drape_measurements {
    uint32_t struct_size;
    double height_m;
    double weight_kg;
    double chest_girth_m;
    double waist_girth_m;
    double hip_girth_m;
    double thigh_girth_m;
    double calf_girth_m;
    double shoulder_height_m;
    double crotch_height_m;
} drape_measurements;
/** Zeroes every value (that fits in m->struct_size). Set m->struct_size first. */
drape_status drape_measurements_init(drape_measurements* m);

/** Number of skeleton joints (22) and their names (index order of the pose arrays). */
size_t drape_joint_count(void);
const char* drape_joint_name(size_t joint);

/** Creates a body of `model` (NULL = the built-in model) with the prior's mean female
 *  shape in the rest A-pose. The body keeps its own reference to the model. */
drape_status drape_body_create(drape_body_model model, drape_body* out_body);
void drape_body_destroy(drape_body body);

/** Shapes the body: completes the parameters from the prior, then matches every given
 *  girth and height on the mesh. DRAPE_ERROR_NO_CONVERGENCE if the measurements could not
 *  be matched (the body is still shaped as closely as possible). */
drape_status drape_body_set_shape(drape_body body, const drape_shape_params* params);
/** The complete parameters in use (given + predicted), as far as out_params->struct_size
 *  holds them. */
drape_status drape_body_get_shape(drape_body body, drape_shape_params* out_params);

/** Poses the body. rotations: joint_count x 3 axis-angle vectors (radians, parent frame,
 *  relative to the rest pose), row-major; translation: 3 values (root, metres) or NULL. */
drape_status drape_body_set_pose(drape_body body, const double* rotations, size_t rotation_count,
                                 const double* translation);

/** Vertex and face counts of the body mesh. */
drape_status drape_body_get_counts(drape_body body, size_t* vertex_count, size_t* face_count);
/** Posed vertices, xyz interleaved. With out == NULL only *required (3 x vertex count) is
 *  set; otherwise capacity (in doubles) must be >= *required. required may be NULL. */
drape_status drape_body_get_vertices(drape_body body, double* out, size_t capacity, size_t* required);
/** Triangle indices (0-based, counter-clockwise from outside), same size-query protocol. */
drape_status drape_body_get_faces(drape_body body, int32_t* out, size_t capacity, size_t* required);
/** Posed joint positions, joint_count x 3, same size-query protocol. */
drape_status drape_body_get_joints(drape_body body, double* out, size_t capacity, size_t* required);
/** Measures the shaped body at rest. */
drape_status drape_body_measure(drape_body body, drape_measurements* out);
/** Writes the posed body: ".glb" (rigged glTF binary) or ".obj", chosen by extension. */
drape_status drape_body_export(drape_body body, const char* path);

#ifdef __cplusplus
}
#endif

#endif /* DRAPE_DRAPE_H */
