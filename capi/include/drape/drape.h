/* Drape C API: bodies, photos, sewing patterns, garment meshes, dressing and draping, the
 * cloth simulator and garment recovery behind opaque handles (docs/c-api.md).
 *
 * Rules:
 *  - Every function that can fail returns drape_status; on failure drape_last_error_message()
 *    (per thread) says what went wrong, naming the argument, value or file, and the error
 *    function set by drape_set_error_function() (if any) is called. No exception or abort
 *    crosses this boundary.
 *  - Inputs are borrowed for the duration of the call. Outputs go to caller buffers after a
 *    size query (pass NULL to learn the size), to handles the caller destroys, or to JSON
 *    strings (UTF-8, NUL-terminated) the caller releases with drape_free().
 *  - *_destroy(NULL) is a no-op. A failed call leaves its output handle NULL and the handles
 *    it was given as they were (except where a function says otherwise).
 *  - Threads: no global initialisation. Distinct handles may be used from distinct threads
 *    at once; one handle must not be used from two threads at the same time.
 *  - Versioned structs (options, parameters, progress) start with uint32_t struct_size. The
 *    caller sets it to sizeof the struct it was compiled with, then calls the *_init()
 *    function. The library never changes struct_size and reads or writes only the fields
 *    that lie wholly inside it, so fields can be appended without breaking callers built
 *    against older headers.
 *  - Long calls (fit, dress, simulate, render, recover, try-on, animate, write a result
 *    folder) take a drape_monitor: a progress callback and a cancel flag; cancelled, they
 *    return DRAPE_ERROR_CANCELLED promptly and leave no partial output. Calls without one are
 *    bounded: segmentation (<= 3 s per photo), meshing, the built-in model's first build
 *    (about 1 s, once per process), file reads and writes, accessors.
 *  - Units: metres, kilograms, seconds, radians; pattern sizing G in centimetres and
 *    degrees (the paper's names); image coordinates in pixels. World frame: +Y up, the body
 *    faces +Z, its left is +X, feet on Y = 0. Arrays are row-major: an "#V x 3" array holds
 *    x0 y0 z0 x1 y1 z1 ...
 */
#ifndef DRAPE_DRAPE_H
#define DRAPE_DRAPE_H

#include <stddef.h>
#include <stdint.h>

#include <drape/drape_version.h>

/* DRAPE_API marks the functions a shared build of the library exports. On Windows define
 * DRAPE_CAPI_DLL when using the DLL (the build defines DRAPE_CAPI_BUILD); elsewhere the
 * functions get default visibility and the library is built with hidden visibility. */
#if defined(_WIN32) || defined(__CYGWIN__)
#  if defined(DRAPE_CAPI_BUILD)
#    define DRAPE_API __declspec(dllexport)
#  elif defined(DRAPE_CAPI_DLL)
#    define DRAPE_API __declspec(dllimport)
#  else
#    define DRAPE_API
#  endif
#elif defined(__GNUC__) || defined(__clang__)
#  define DRAPE_API __attribute__((visibility("default")))
#else
#  define DRAPE_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef enum drape_status {
    DRAPE_OK = 0,
    DRAPE_ERROR_INVALID_ARGUMENT = 1, /* a NULL pointer, wrong size, bad value or bad file content */
    DRAPE_ERROR_IO = 2,               /* a file could not be read or written */
    DRAPE_ERROR_NO_CONVERGENCE = 3,   /* a numerical method fell short; see the function */
    DRAPE_ERROR_OUT_OF_MEMORY = 4,
    DRAPE_ERROR_CANCELLED = 5,        /* the monitor's cancel flag or progress callback stopped the call */
    DRAPE_ERROR_INTERNAL = 6          /* a bug: please report the message */
} drape_status;

/** Library version, "MAJOR.MINOR.PATCH" (the CMake project version, also DRAPE_VERSION_STRING
 *  of the header the caller compiled against). Never NULL. */
DRAPE_API const char* drape_version(void);
/** A fixed English description of a status code. Never NULL. */
DRAPE_API const char* drape_status_string(drape_status status);
/** The message of the last failed call on this thread ("" if none). Valid until the next
 *  failing call on this thread. */
DRAPE_API const char* drape_last_error_message(void);

/** Called on the failing thread, after the per-thread message is set, for every failed call
 *  (as Embree's rtcSetDeviceErrorFunction). `message` is valid during the call only. The
 *  function must not call drape functions that could fail re-entrantly on the same thread
 *  with the same handles, and must not throw or longjmp. */
typedef void (*drape_error_function)(void* user, drape_status status, const char* message);
/** Sets the process-wide error function (NULL removes it); `user` is passed back to it.
 *  Safe to call from any thread; calls already in flight may still use the previous one. */
DRAPE_API void drape_set_error_function(drape_error_function function, void* user);

/** Releases memory the library returned (JSON strings). drape_free(NULL) is a no-op. */
DRAPE_API void drape_free(void* memory);

/* ---- progress and cancellation ---------------------------------------------------- */

/** A cancel flag: set from any thread (a UI, a signal-handling thread) to stop every long
 *  call whose monitor holds it. Setting it is atomic and lock-free. */
typedef struct drape_cancel_flag_s* drape_cancel_flag;
/** A new flag, not set. */
DRAPE_API drape_status drape_cancel_flag_create(drape_cancel_flag* out_flag);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_cancel_flag_destroy(drape_cancel_flag flag);
/** Requests cancellation (a NULL flag is ignored). */
DRAPE_API void drape_cancel_flag_set(drape_cancel_flag flag);
/** Clears the request, so the flag can be reused for another call. */
DRAPE_API void drape_cancel_flag_reset(drape_cancel_flag flag);
/** 1 if set, 0 if not (or flag is NULL). */
DRAPE_API int32_t drape_cancel_flag_is_set(drape_cancel_flag flag);

/** What a long call is doing, passed to the progress callback. */
typedef struct drape_progress {
    uint32_t struct_size;
    const char* operation;   /* "fit_body", "dress", "simulate", "render", "recover", "write_recovery",
                                "tryon", "write_tryon", "animate", "write_animation" */
    const char* stage;       /* e.g. "segmenting", "sizing", "closing_seams", "step" */
    int32_t garment;         /* garment index, -1 = all / none */
    int32_t round;           /* recover: sizing/material round (1-based), 0 outside them */
    int64_t step;            /* simulation steps or drape evaluations so far */
    double fraction;         /* 0..1 when known, -1 otherwise */
    double seconds;          /* since the call began */
    double eta_seconds;      /* estimated seconds left, -1 unknown */
} drape_progress;

/** Return nonzero to go on, 0 to cancel. Called on the thread of the long call (recover's
 *  searches call it between generations, from that thread); it must be quick and must not
 *  use the handle of the call it monitors. `progress` is valid during the call only. */
typedef int32_t (*drape_progress_function)(void* user, const drape_progress* progress);

/** How a long call reports progress and is cancelled. Every field may be NULL. */
typedef struct drape_monitor {
    uint32_t struct_size;
    drape_progress_function progress;
    void* user;                 /* passed to progress */
    drape_cancel_flag cancel;   /* checked at least at every progress report */
} drape_monitor;
/** Sets progress, user and cancel to NULL. Set monitor->struct_size first. */
DRAPE_API drape_status drape_monitor_init(drape_monitor* monitor);

/* ---- body model ------------------------------------------------------------------- */

typedef struct drape_body_model_s* drape_body_model;

/** Loads a body model file (HDF5, docs/body-model-format.md). Variable-length strings
 *  (h5py's default) are refused with DRAPE_ERROR_INVALID_ARGUMENT naming the dataset: libhdf5
 *  reads them from the file's global heap unchecked (docs/hardening.md); store fixed-length
 *  strings, as drape_body_model_save does. libhdf5 parses the file in a forked child
 *  process (the isolated reader): a damaged file that crashes or hangs libhdf5 returns
 *  DRAPE_ERROR_IO naming it, and the calling process is unharmed. */
DRAPE_API drape_status drape_body_model_load(const char* path, drape_body_model* out_model);
/** Writes a model to an HDF5 file (atomically). */
DRAPE_API drape_status drape_body_model_save(drape_body_model model, const char* path);
/** A handle on the built-in mannequin model (generated on first use, then shared). */
DRAPE_API drape_status drape_body_model_default(drape_body_model* out_model);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_body_model_destroy(drape_body_model model);

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
DRAPE_API drape_status drape_shape_params_init(drape_shape_params* params);

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
DRAPE_API drape_status drape_measurements_init(drape_measurements* m);

/** Number of skeleton joints (22) and their names (index order of the pose arrays). */
DRAPE_API size_t drape_joint_count(void);
DRAPE_API const char* drape_joint_name(size_t joint);

/** Creates a body of `model` (NULL = the built-in model) with the prior's mean female
 *  shape in the rest A-pose. The body keeps its own reference to the model. */
DRAPE_API drape_status drape_body_create(drape_body_model model, drape_body* out_body);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_body_destroy(drape_body body);

/** Shapes the body: completes the parameters from the prior, then matches every given
 *  girth and height on the mesh. DRAPE_ERROR_NO_CONVERGENCE if the measurements could not
 *  be matched (the body is still shaped as closely as possible). */
DRAPE_API drape_status drape_body_set_shape(drape_body body, const drape_shape_params* params);
/** The complete parameters in use (given + predicted), as far as out_params->struct_size
 *  holds them. */
DRAPE_API drape_status drape_body_get_shape(drape_body body, drape_shape_params* out_params);

/** Poses the body. rotations: joint_count x 3 axis-angle vectors (radians, parent frame,
 *  relative to the rest pose), row-major; translation: 3 values (root, metres) or NULL. */
DRAPE_API drape_status drape_body_set_pose(drape_body body, const double* rotations, size_t rotation_count,
                                 const double* translation);

/** Vertex and face counts of the body mesh. */
DRAPE_API drape_status drape_body_get_counts(drape_body body, size_t* vertex_count, size_t* face_count);
/** Posed vertices, xyz interleaved. With out == NULL only *required (3 x vertex count) is
 *  set; otherwise capacity (in doubles) must be >= *required. required may be NULL. */
DRAPE_API drape_status drape_body_get_vertices(drape_body body, double* out, size_t capacity, size_t* required);
/** Triangle indices (0-based, counter-clockwise from outside), same size-query protocol. */
DRAPE_API drape_status drape_body_get_faces(drape_body body, int32_t* out, size_t capacity, size_t* required);
/** Posed joint positions, joint_count x 3, same size-query protocol. */
DRAPE_API drape_status drape_body_get_joints(drape_body body, double* out, size_t capacity, size_t* required);
/** Measures the shaped body at rest. */
DRAPE_API drape_status drape_body_measure(drape_body body, drape_measurements* out);
/** Writes the posed body: ".glb" (rigged glTF binary) or ".obj", chosen by extension. */
DRAPE_API drape_status drape_body_export(drape_body body, const char* path);

/* ---- body: fit to a photo's joints and silhouette ----------------------------------- */

/** The files of a body fit, as `drape fit-body` reads them. Paths are UTF-8. */
typedef struct drape_fit_inputs {
    uint32_t struct_size;
    const char* image_path;      /* the photo (JPEG/PNG; EXIF orientation applied), required */
    const char* joints_path;     /* 14-joint JSON (../shared/data/photos/joints format), required */
    const char* silhouette_path; /* PNG mask of the person, garments included (non-zero = person) */
    const char* skin_path;       /* optional PNG mask of the visible skin, with silhouette_path */
    const char* labels_path;     /* instead of silhouette/skin: a Fashionista class-id label map */
    double height_m;             /* the person's stature, NaN = unknown */
    int32_t gender;              /* a drape_gender value; UNSPECIFIED = chosen by the prior */
} drape_fit_inputs;
/** Sets the paths to NULL, height_m to NaN, gender to unspecified. */
DRAPE_API drape_status drape_fit_inputs_init(drape_fit_inputs* inputs);

/** Which points of the body a joints file marks (docs/body-fitting.md, "Image joints"). */
typedef enum drape_image_joints {
    DRAPE_IMAGE_JOINTS_FROM_FILE = 0,   /* as the joints file's "marks" says; hand-marked if it has none (default) */
    DRAPE_IMAGE_JOINTS_HAND_MARKED = 1, /* hand-marked photos' convention (Fashionista) */
    DRAPE_IMAGE_JOINTS_MODEL = 2        /* the body model's joints themselves (synthetic scenes) */
} drape_image_joints;

typedef struct drape_fit_options {
    uint32_t struct_size;
    double focal_px;    /* > 0: pinhole camera of this focal length (pixels); 0 = weak perspective */
    int32_t threads;    /* solver threads, >= 1 (default 2) */
    int32_t fit_shape;  /* 1 (default): fit the semantic shape; 0: pose and camera only */
    /* Added after the first release (a smaller struct_size leaves them at their defaults): */
    double posture_weight; /* >= 0 (default 100): keeps trunk and legs from bending towards the camera */
    double lean_weight;    /* >= 0 (default 1000): keeps the whole body from leaning */
    int32_t image_joints;  /* a drape_image_joints value (default DRAPE_IMAGE_JOINTS_FROM_FILE) */
    double skin_weight;    /* >= 0 (default as `drape fit-body --skin-weight`): weight of the skin mask term */
} drape_fit_options;
/** Sets every field of *options to its default (given beside each field above). Set
 *  options->struct_size = sizeof *options first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_fit_options_init(drape_fit_options* options);

/** Fits pose, shape and camera of `body` (its model) to a photo (docs/body-fitting.md) and
 *  sets the body to the fitted shape and pose. options and monitor may be NULL (defaults).
 *  \param out_json if not NULL, receives body.json of `drape fit-body` (pose, shape,
 *         coefficients, camera, projected joints, fit figures); free it with drape_free().
 *  \return DRAPE_ERROR_NO_CONVERGENCE if the fit is not usable (the body is unchanged),
 *          DRAPE_ERROR_CANCELLED if the monitor stopped it (the body is unchanged). */
DRAPE_API drape_status drape_body_fit(drape_body body, const drape_fit_inputs* inputs, const drape_fit_options* options,
                                      const drape_monitor* monitor, char** out_json);
/** As drape_body_fit, then writes the folder of `drape fit-body` into `folder` (created if
 *  needed): body.json, body.glb (rigged, fitted pose) and overlay.png (the fitted silhouette
 *  and joints over the photo). The folder is checked for writing before the fit; the files
 *  are staged inside it and moved in only once all are written, so a failure or a cancel
 *  leaves it as it was (DRAPE_ERROR_IO names the file or folder). The body changes only
 *  when the whole call succeeds. options, monitor and out_json may be NULL. */
DRAPE_API drape_status drape_body_fit_to_folder(drape_body body, const drape_fit_inputs* inputs,
                                                const drape_fit_options* options, const drape_monitor* monitor,
                                                const char* folder, char** out_json);
/** The body's semantic shape and pose as JSON: {"shape": {...}, "pose": {...}} in the forms of
 *  `drape body` (P.json keys, POSE.json). Free with drape_free(). */
DRAPE_API drape_status drape_body_to_json(drape_body body, char** out_json);

/* ---- vision: segmentation and garment features -------------------------------------- */

typedef struct drape_segmentation_s* drape_segmentation;

typedef struct drape_segment_options {
    uint32_t struct_size;
    const char* strokes_path;  /* user strokes PNG (class ids, or colours with palette_path); NULL = automatic */
    const char* palette_path;  /* colour -> class JSON for colour-coded strokes; NULL = built-in palette */
    const char* hint;          /* garment type hint (t-shirt, tank-top, long-sleeve-top, dress, skirt,
                                  pants, shorts) or NULL */
    double height_m;           /* the person's stature for the wrinkle scale (default 1.70) */
} drape_segment_options;
/** Sets every field of *options to its default (given beside each field above). Set
 *  options->struct_size = sizeof *options first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_segment_options_init(drape_segment_options* options);

/** Parses the garments of a photo (docs/vision.md): automatic from the joints, or guided by
 *  strokes; then describes each garment (type, silhouette, occlusion, folds, wrinkle density).
 *  options may be NULL. A photo where no garment is found still gives a segmentation (its
 *  garments JSON lists none). */
DRAPE_API drape_status drape_segment(const char* image_path, const char* joints_path,
                                     const drape_segment_options* options, drape_segmentation* out_segmentation);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_segmentation_destroy(drape_segmentation segmentation);
/** The photo's size in pixels. */
DRAPE_API drape_status drape_segmentation_get_size(drape_segmentation segmentation, int32_t* width, int32_t* height);
/** The label map: width x height class ids (labels.txt of Fashionista), row-major from the
 *  top-left pixel; size-query protocol (capacity in bytes). */
DRAPE_API drape_status drape_segmentation_get_labels(drape_segmentation segmentation, uint8_t* out, size_t capacity,
                                                     size_t* required);
/** The occlusion mask (255 where something lies in front of a garment), as the labels. */
DRAPE_API drape_status drape_segmentation_get_occlusion(drape_segmentation segmentation, uint8_t* out,
                                                        size_t capacity, size_t* required);
/** garments.json of `drape segment` (format "drape.garments", version 1): every garment's
 *  type, class, area, occlusion, silhouette polygons (pixels, image frame), folds, wrinkle
 *  density and shape cues. Free with drape_free(). */
DRAPE_API drape_status drape_segmentation_garments_json(drape_segmentation segmentation, char** out_json);
/** Writes the label map as an 8-bit PNG (".png" only), atomically. */
DRAPE_API drape_status drape_segmentation_export_labels(drape_segmentation segmentation, const char* path);
/** Writes the folder of `drape segment` into `folder` (created if needed): labels.png,
 *  occlusion.png, overlay.png (the labels over the photo), folds.png (the folds found) and
 *  garments.json; staged inside it and moved in only once all are written, so a failure
 *  leaves the folder as it was (DRAPE_ERROR_IO names the file or folder). */
DRAPE_API drape_status drape_segmentation_write_folder(drape_segmentation segmentation, const char* folder);

/* ---- sewing patterns ---------------------------------------------------------------- */

typedef struct drape_pattern_s* drape_pattern;

/** A pattern of template `garment` ("skirt", "pants", "tshirt", "dress") from sizing
 *  parameters G as JSON text with the paper's names (cm, degrees; docs/patterns.md): absent
 *  keys keep the template defaults; sizing_json NULL = all defaults. */
DRAPE_API drape_status drape_pattern_create(const char* garment, const char* sizing_json, drape_pattern* out_pattern);
/** A pattern sized for a body: G proposed from its measurements (a top fitted to its arms and
 *  neck), as `drape pattern --sizing auto`. */
DRAPE_API drape_status drape_pattern_create_for_body(const char* garment, drape_body body, drape_pattern* out_pattern);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_pattern_destroy(drape_pattern pattern);
/** {"garment": NAME, "sizing": {G}, "panels": n, "seams": n, "area_cm2": A}. Free with drape_free(). */
DRAPE_API drape_status drape_pattern_to_json(drape_pattern pattern, char** out_json);
/** Writes the pattern: ".svg" (true scale), ".dxf" (AAMA) or ".json" (GarmentCode), by
 *  extension, atomically. */
DRAPE_API drape_status drape_pattern_export(drape_pattern pattern, const char* path);

/* ---- garment meshes ----------------------------------------------------------------- */

typedef struct drape_garment_mesh_s* drape_garment_mesh;

/** Meshes a pattern (constrained Delaunay, CGAL) at a target edge length in cm (<= 0: 1.5).
 *  Each panel is a separate piece placed around the body; seams are stitches (vertex pairs).
 *  \return DRAPE_ERROR_NO_CONVERGENCE if the seams' discretisations did not agree (the mesh
 *          is still returned). */
DRAPE_API drape_status drape_garment_mesh_create(drape_pattern pattern, double edge_cm, drape_garment_mesh* out_mesh);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_garment_mesh_destroy(drape_garment_mesh mesh);
/** Vertex, face and stitch counts (any pointer may be NULL). */
DRAPE_API drape_status drape_garment_mesh_get_counts(drape_garment_mesh mesh, size_t* vertex_count, size_t* face_count,
                                                     size_t* stitch_count);
/** Vertex positions, #V x 3, world, metres (a fresh mesh: the panels' placement around the
 *  body; from a drape or recovery: draped). Size-query protocol (capacity in doubles). */
DRAPE_API drape_status drape_garment_mesh_get_vertices(drape_garment_mesh mesh, double* out, size_t capacity,
                                                       size_t* required);
/** Faces, #F x 3 vertex indices (0-based, counter-clockwise in the pattern). */
DRAPE_API drape_status drape_garment_mesh_get_faces(drape_garment_mesh mesh, int32_t* out, size_t capacity,
                                                    size_t* required);
/** Pattern coordinates, #V x 2, metres, the flat layout (u = weft). */
DRAPE_API drape_status drape_garment_mesh_get_pattern_coords(drape_garment_mesh mesh, double* out, size_t capacity,
                                                             size_t* required);
/** Stitches, #S x 2 vertex indices sewn together. */
DRAPE_API drape_status drape_garment_mesh_get_stitches(drape_garment_mesh mesh, int32_t* out, size_t capacity,
                                                       size_t* required);
/** The pattern the mesh was made from (a new handle the caller destroys). */
DRAPE_API drape_status drape_garment_mesh_get_pattern(drape_garment_mesh mesh, drape_pattern* out_pattern);
/** Writes the mesh at its current vertices: ".obj" (with pattern uv and panel groups) or
 *  ".glb" (glTF binary), by extension, atomically. */
DRAPE_API drape_status drape_garment_mesh_export(drape_garment_mesh mesh, const char* path);
/** Writes the flat layout of the mesh (the panels in pattern coordinates, metres, z = 0; as
 *  `drape pattern` writes pattern_mesh.obj): ".obj" or ".glb", by extension, atomically. */
DRAPE_API drape_status drape_garment_mesh_export_flat(drape_garment_mesh mesh, const char* path);

/* ---- rendering ---------------------------------------------------------------------- */

/** Which camera drape_render looks through. */
typedef enum drape_render_camera {
    DRAPE_RENDER_CAMERA_AUTO = 0,    /* FITTED for a body fitted to a photo, else PREVIEW (default) */
    DRAPE_RENDER_CAMERA_FITTED = 1,  /* the camera drape_body_fit found, at its photo's size */
    DRAPE_RENDER_CAMERA_PREVIEW = 2, /* the view of `drape dress`'s render.png: front-left, slightly above */
    DRAPE_RENDER_CAMERA_FRONT = 3    /* from +Z, framing everything (`drape render --camera front`) */
} drape_render_camera;

typedef struct drape_render_options {
    uint32_t struct_size;
    const char* lighting;    /* "studio" (default), "midday" or "sunset" (docs/rendering.md) */
    int32_t width;           /* pixels; width and height both 0 (default): the photo's, else the */
    int32_t height;          /*   fitted photo's (FITTED camera), else 600 x 900 */
    int32_t samples;         /* samples per pixel, 1..4096 (default 16) */
    int32_t threads;         /* >= 0; 0 (default) = all cores */
    int32_t camera;          /* a drape_render_camera value */
    const char* camera_json; /* if not NULL, replaces `camera`: the JSON text `drape render --camera FILE`
                                reads (a fit-body camera, a body.json, or a look-at {eye, target, up, focal_px}) */
    const char* photo_path;  /* if not NULL, the render is composited over this photo (its size must be the
                                render's; no floor is drawn) */
    double opacity;          /* of the render over the photo, in [0, 1] (default 1) */
    const char* labels_path; /* if not NULL, also writes the label map there (8-bit PNG of labels.txt class
                                ids: 41 the body, each garment its template's class: 42 skirt, 31 pants,
                                51 t-shirt, 14 dress, or 54 top for a pattern without a template; 0
                                elsewhere) */
} drape_render_options;
/** Sets lighting and the paths to NULL, width = height = 0, samples 16, threads 0, camera AUTO,
 *  opacity 1. Set options->struct_size first. */
DRAPE_API drape_status drape_render_options_init(drape_render_options* options);

/** Ray traces the posed body and the garment meshes (their current vertices: placed, or
 *  draped by drape_dress, a recovery or a try-on) in the preview look of `drape dress` and
 *  `drape recover` (docs/rendering.md: the body in a neutral skin tone, garments blue,
 *  terracotta, olive, ...; soft sun shadows and sky light; a floor under the lowest point
 *  unless over a photo) and writes a PNG to `path` (".png", atomically). garments may be
 *  NULL when garment_count is 0. options and monitor may be NULL (defaults). The monitor
 *  is asked between tile rows (operation "render", stage "tracing").
 *  \return DRAPE_ERROR_INVALID_ARGUMENT for a FITTED camera on a body that was never fitted,
 *          a photo of another size than the render, or a bad option (named). */
DRAPE_API drape_status drape_render(drape_body body, const drape_garment_mesh* garments, size_t garment_count,
                                    const drape_render_options* options, const drape_monitor* monitor,
                                    const char* path);

/* ---- dressing and draping ----------------------------------------------------------- */

/** One garment of an outfit. */
typedef struct drape_garment_spec {
    uint32_t struct_size;
    const char* garment;      /* "skirt", "pants", "tshirt", "dress"; required */
    const char* sizing_json;  /* G as JSON text; NULL = proposed from the body */
    const char* material;     /* a built-in fabric name or a material file (ours or ArcSim's);
                                 NULL = "gray-interlock" */
} drape_garment_spec;
/** Sets every field of *spec to its default (given beside each field above). Set
 *  spec->struct_size = sizeof *spec first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_garment_spec_init(drape_garment_spec* spec);

typedef struct drape_dress_options {
    uint32_t struct_size;
    double edge_cm;          /* mesh edge, cm; 0 (default) = 1.5, or 2.5 with pants */
    int32_t clear_arms;      /* 1 (default): raise arms just clear of the trunk before draping */
    double body_motion_s;    /* time the body takes to move from the A-pose to its pose (0.6 s) */
    int32_t max_steps;       /* dynamic steps at most (600) */
} drape_dress_options;
/** Sets every field of *options to its default (given beside each field above). Set
 *  options->struct_size = sizeof *options first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_dress_options_init(drape_dress_options* options);

typedef struct drape_outfit_s* drape_outfit;

/** Dresses `body` (its shape, in its current pose) in one garment or an outfit (inner
 *  first, e.g. pants then a t-shirt) and drapes it (docs/dressing.md): sizing, pattern,
 *  mesh, dressing in the A-pose, sewing and settling in a cloth simulation, checks; as
 *  `drape dress`. options and monitor may be NULL. The monitor is called after every
 *  simulation step (operation "dress").
 *  \return DRAPE_OK with a usable drape; DRAPE_ERROR_NO_CONVERGENCE if the drape ran but is
 *          not usable (the outfit is still returned: see its summary JSON) or a pattern could
 *          not be meshed (no outfit); DRAPE_ERROR_CANCELLED (no outfit). */
DRAPE_API drape_status drape_dress(drape_body body, const drape_garment_spec* garments, size_t garment_count,
                                   const drape_dress_options* options, const drape_monitor* monitor,
                                   drape_outfit* out_outfit);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_outfit_destroy(drape_outfit outfit);
/** The number of garments, inner first (the index of the accessors below). */
DRAPE_API drape_status drape_outfit_get_garment_count(drape_outfit outfit, size_t* count);
/** The draped garment `index` (inner first) as a new mesh handle (draped vertices, world),
 *  independent of the outfit. */
DRAPE_API drape_status drape_outfit_get_garment_mesh(drape_outfit outfit, size_t index, drape_garment_mesh* out_mesh);
/** summary.json of `drape dress`: drape figures (steps, seam gap, penetration, usable, ...)
 *  and per garment its sizing and checks. Free with drape_free(). */
DRAPE_API drape_status drape_outfit_summary_json(drape_outfit outfit, char** out_json);
/** Body vertices in the pose draped in (#B x 3, world; arms cleared if asked), size query. */
DRAPE_API drape_status drape_outfit_get_body_vertices(drape_outfit outfit, double* out, size_t capacity,
                                                      size_t* required);

/* ---- the cloth simulator ------------------------------------------------------------ */

typedef struct drape_simulator_s* drape_simulator;

typedef struct drape_simulator_options {
    uint32_t struct_size;
    double time_step_s;           /* backward-Euler step (10 ms) */
    double gravity_x, gravity_y, gravity_z; /* m/s^2, world frame (0, -9.8, 0) */
    double air_drag_n_s_per_m3;   /* linear air drag per unit area (2) */
    double contact_thickness_m;   /* cloth-obstacle and cloth-cloth contact thickness (5 mm) */
    double obstacle_friction;     /* Coulomb mu against the obstacle (0.3) */
    int32_t self_contact;         /* 1 (default): cloth-cloth repulsion */
    int32_t max_newton_iterations;/* per step (3) and per static solve (100 at least) */
} drape_simulator_options;
/** The defaults of draping (garment::DrapeOptions' simulator settings, docs/cloth.md). */
DRAPE_API drape_status drape_simulator_options_init(drape_simulator_options* options);

/** A simulator of a raw cloth mesh. vertices: vertex_count x 3 (world, metres); faces:
 *  face_count x 3 (0-based); pattern_coords: vertex_count x 2 rest coordinates (pattern
 *  frame, metres; u = weft), faces counter-clockwise in them. material: a built-in fabric
 *  name or a material file; NULL = "gray-interlock". options may be NULL. */
DRAPE_API drape_status drape_simulator_create(const double* vertices, size_t vertex_count, const int32_t* faces,
                                              size_t face_count, const double* pattern_coords, const char* material,
                                              const drape_simulator_options* options, drape_simulator* out_simulator);
/** A simulator of a garment mesh at its current vertices, with its seams as stitches that
 *  close during steps. */
DRAPE_API drape_status drape_simulator_create_from_garment(drape_garment_mesh mesh, const char* material,
                                                           const drape_simulator_options* options,
                                                           drape_simulator* out_simulator);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_simulator_destroy(drape_simulator simulator);
/** Sets the obstacle (a closed triangle mesh, outward counter-clockwise faces) the cloth
 *  collides with, replacing any previous one. vertices #O x 3 world metres, faces #G x 3. */
DRAPE_API drape_status drape_simulator_set_obstacle(drape_simulator simulator, const double* vertices,
                                                    size_t vertex_count, const int32_t* faces, size_t face_count);
/** Sets the posed body as the obstacle. */
DRAPE_API drape_status drape_simulator_set_obstacle_body(drape_simulator simulator, drape_body body);
/** Removes the obstacle. */
DRAPE_API drape_status drape_simulator_clear_obstacle(drape_simulator simulator);
/** Holds a vertex at its current position. */
DRAPE_API drape_status drape_simulator_pin(drape_simulator simulator, size_t vertex);
/** Takes `steps` backward-Euler time steps, calling the monitor after each (operation
 *  "simulate", stage "step"). monitor may be NULL.
 *  \return DRAPE_ERROR_NO_CONVERGENCE if a step failed even when halved (state as before
 *          that step), DRAPE_ERROR_CANCELLED (the steps done so far are kept). */
DRAPE_API drape_status drape_simulator_step(drape_simulator simulator, int32_t steps, const drape_monitor* monitor);
/** Minimises the potential energy from the current state (static equilibrium; velocities
 *  become zero). The cancel flag is checked after every Newton iteration.
 *  \return DRAPE_ERROR_NO_CONVERGENCE if Newton did not reach its tolerance (the state is
 *          the last iterate), DRAPE_ERROR_CANCELLED. */
DRAPE_API drape_status drape_simulator_solve_static(drape_simulator simulator, const drape_monitor* monitor);
/** Vertex and face counts of the simulated cloth (a garment's welded seams are not merged:
 *  the count is the mesh's). */
DRAPE_API drape_status drape_simulator_get_counts(drape_simulator simulator, size_t* vertex_count, size_t* face_count);
/** Current positions, #V x 3, world, metres; size-query protocol. */
DRAPE_API drape_status drape_simulator_get_vertices(drape_simulator simulator, double* out, size_t capacity,
                                                    size_t* required);
/** Replaces the positions (#V x 3 values) and zeroes the velocities. */
DRAPE_API drape_status drape_simulator_set_vertices(drape_simulator simulator, const double* vertices, size_t count);
/** Penetration, seam gaps and self-intersections of the current state:
 *  {"max_penetration_m", "vertices_inside", "max_stitch_gap_m", "self_intersections"}. */
DRAPE_API drape_status drape_simulator_report_json(drape_simulator simulator, char** out_json);

/* ---- recovery from a photo ---------------------------------------------------------- */

typedef struct drape_recover_inputs {
    uint32_t struct_size;
    const char* image_path;    /* the photo (JPEG/PNG), required */
    const char* joints_path;   /* its 14 joints (JSON), required */
    const char* strokes_path;  /* user strokes PNG, NULL = automatic segmentation */
    const char* palette_path;  /* colour -> class JSON for colour-coded strokes, or NULL */
    const char* garments;      /* "auto" (NULL) or names joined by '+': skirt, pants, shorts,
                                  tshirt, tank, longsleeve, dress */
    double height_m;           /* known stature, NaN = unknown */
    int32_t gender;            /* a drape_gender value */
} drape_recover_inputs;
/** Sets every field of *inputs to its default (given beside each field above). Set
 *  inputs->struct_size = sizeof *inputs first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_recover_inputs_init(drape_recover_inputs* inputs);

typedef struct drape_recover_options {
    uint32_t struct_size;
    const char* quality;        /* "fast", "default" (NULL) or "fine" (docs/recovery.md) */
    int32_t threads;            /* workers, >= 1 (2) */
    uint32_t seed;              /* the particle swarm's seed (1) */
    int32_t particles;          /* swarm size; 0 = by quality */
    int32_t generations;        /* per sizing search; 0 = by quality */
    int32_t rounds;             /* sizing/material rounds at most; 0 = by quality */
    int32_t estimate_material;  /* 1 (default); 0 keeps the base fabric at bending x1 */
    const char* output_drape;   /* which drape the garments are: "output" (NULL: the output
                                   drape, usable or not), "auto" (the search's re-drape where
                                   only that one is usable) or "search" (docs/recovery.md, step 7); a caller
                                   whose struct_size ends before it gets NULL */
    /* Added after output_drape; a caller whose struct_size ends before a field gets its default. */
    const char* material_target;       /* "calibrated" (NULL: K from the calibrated mapping of P) or
                                          "synthesis" (P measured on renders of the candidate drapes;
                                          docs/material-estimation.md) */
    const char* base_fabric;           /* the base fabric of the material space, bending x1..x100: a
                                          measured fabric's name (docs/materials.md); NULL = "gray-interlock" */
    double max_arm_elevation_degrees;  /* upper arms raised more than this above hanging are lowered to
                                          it before draping; [0, 180], 180 = off (90) */
    double min_ease_cm;                /* the least ease, cm of girth over the fitted body, the sizing
                                          search lets a garment reach; negative = smaller than the body,
                                          stretched on it; [-10, 10] (2) */
    int32_t joint_pose;                /* 1: search the pose of the joints under each garment together
                                          with the material (paper Algorithm 2); 0 (default) */
} drape_recover_options;
/** Sets every field of *options to its default (given beside each field above). Set
 *  options->struct_size = sizeof *options first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_recover_options_init(drape_recover_options* options);

typedef struct drape_recovery_s* drape_recovery;

/** Recovers the body, each garment's sewing pattern, fabric and drape from one photo
 *  (docs/recovery.md), as `drape recover`. model NULL = the built-in model; options and
 *  monitor may be NULL. The monitor is called between stages and after every search
 *  generation and material iterate (operation "recover").
 *  \return DRAPE_OK (every drape usable); DRAPE_ERROR_NO_CONVERGENCE with a recovery when a
 *          final drape is not usable (see its JSON), without one when the body could not be
 *          fitted or a drape made; DRAPE_ERROR_INVALID_ARGUMENT when no garment is found;
 *          DRAPE_ERROR_CANCELLED (no recovery). */
DRAPE_API drape_status drape_recover(drape_body_model model, const drape_recover_inputs* inputs,
                                     const drape_recover_options* options, const drape_monitor* monitor,
                                     drape_recovery* out_recovery);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_recovery_destroy(drape_recovery recovery);
/** result.json of `drape recover`: image, body (shape, pose, camera), per garment its type,
 *  sizing G, material (scales, tables, nearest fabric), drape state and figures; timings.
 *  Free with drape_free(). */
DRAPE_API drape_status drape_recovery_json(drape_recovery recovery, char** out_json);
/** The number of garments, inner first (the index of the accessors below). */
DRAPE_API drape_status drape_recovery_get_garment_count(drape_recovery recovery, size_t* count);
/** Garment `index`'s entry of result.json ("garments"[index]). Free with drape_free(). */
DRAPE_API drape_status drape_recovery_garment_json(drape_recovery recovery, size_t index, char** out_json);
/** Garment `index`'s recovered sizing G (the paper's parameter names, cm and degrees, as
 *  G.json; the template is the entry's "type") and material ({"bending_scale",
 *  "stretching_scale", "base_fabric", "stretching", "bending" (SI tables, ArcSim layout),
 *  "density" (kg/m^2), "nearest_fabric", "bending_scale_range"}): the "sizing" and "material"
 *  members of its result.json entry. Free with drape_free(). */
DRAPE_API drape_status drape_recovery_garment_sizing_json(drape_recovery recovery, size_t index, char** out_json);
DRAPE_API drape_status drape_recovery_garment_material_json(drape_recovery recovery, size_t index, char** out_json);
/** Garment `index` as a new mesh handle (draped vertices, world; its pattern through
 *  drape_garment_mesh_get_pattern), independent of the recovery. */
DRAPE_API drape_status drape_recovery_get_garment_mesh(drape_recovery recovery, size_t index,
                                                       drape_garment_mesh* out_mesh);
/** The recovered body (fitted shape, the pose draped in) as a new body handle. */
DRAPE_API drape_status drape_recovery_get_body(drape_recovery recovery, drape_body* out_body);
/** Writes the recovery: ".glb" = the outfit (body and garments, outfit.glb), by extension. */
DRAPE_API drape_status drape_recovery_export(drape_recovery recovery, const char* path);
/** Writes the result folder of `drape recover` (result.json, garment_N.glb/.obj,
 *  pattern_N.svg/.dxf/.json, body.glb, outfit.glb, masks, overlay, report.html; the folder
 *  is created): staged, then moved in whole, so a failure or a cancel (checked before the
 *  move; operation "write_recovery") leaves `folder` as it was. monitor may be NULL. */
DRAPE_API drape_status drape_recovery_write_folder(drape_recovery recovery, const char* folder,
                                                   const drape_monitor* monitor);

/* ---- virtual try-on ------------------------------------------------------------------ */

typedef struct drape_tryon_inputs {
    uint32_t struct_size;
    const char* const* garments; /* garment_count specs, inner garment first: "DIR" (every garment
                                    of a result folder, as drape_recovery_write_folder or `drape
                                    recover` writes it, or of a `drape synth` scene) or "DIR:N"
                                    (garment N); required */
    size_t garment_count;        /* >= 1 */
    drape_body body;             /* a body target: its shape and pose (not consumed); NULL for a
                                    photo target. Exactly one of body and image_path is set. */
    const char* image_path;      /* a photo target: the photo (JPEG/PNG) */
    const char* joints_path;     /*   its 14 joints (JSON), required with image_path */
    const char* strokes_path;    /*   user strokes PNG, NULL = automatic segmentation */
    const char* palette_path;    /*   colour -> class JSON for colour-coded strokes, or NULL */
    double height_m;             /*   the person's known stature, NaN = unknown */
    int32_t gender;              /*   a drape_gender value */
} drape_tryon_inputs;
/** Sets every field of *inputs to its default (given beside each field above). Set
 *  inputs->struct_size = sizeof *inputs first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_tryon_inputs_init(drape_tryon_inputs* inputs);

typedef struct drape_tryon_options {
    uint32_t struct_size;
    double edge_cm;              /* mesh edge of the drape, (0.5, 20] cm (3) */
    int32_t max_drape_steps;     /* dynamic steps of the drape, >= 1 (400) */
    int32_t threads;             /* body fit and overlay workers, >= 1 (2) */
} drape_tryon_options;
/** Sets every field of *options to its default (given beside each field above). Set
 *  options->struct_size = sizeof *options first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_tryon_options_init(drape_tryon_options* options);

typedef struct drape_tryon_s* drape_tryon_result;

/** Puts recovered garments on another body or into another photo, as `drape tryon`
 *  (docs/tryon.md): each garment keeps its fabric, its sizing G is graded to the new body
 *  (ease over each girth kept, lengths by the body's proportions, style parameters fixed),
 *  and the outfit is dressed and draped; a photo target's body is fitted from the photo first
 *  and the garments are rendered over it. model NULL = the body target's model, else the
 *  built-in model. options and monitor may be NULL; the monitor is called between stages and
 *  after every simulation step (operation "tryon", stages "fitting_body", "grading",
 *  "draping", "rendering").
 *  \return DRAPE_OK (every drape and grading usable); DRAPE_ERROR_NO_CONVERGENCE with a
 *          result when one is not (see its JSON), without one when the photo's body could not
 *          be fitted or a pattern meshed; DRAPE_ERROR_INVALID_ARGUMENT (a folder without a
 *          garment, N out of range, both or neither target, bad joints; the message names the
 *          file and field); DRAPE_ERROR_IO; DRAPE_ERROR_CANCELLED (no result). */
DRAPE_API drape_status drape_tryon(drape_body_model model, const drape_tryon_inputs* inputs,
                                   const drape_tryon_options* options, const drape_monitor* monitor,
                                   drape_tryon_result* out_result);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_tryon_destroy(drape_tryon_result result);
/** tryon.json of `drape tryon`: the target, per garment its source, original and graded G,
 *  the grading (rules, clamps, style changes, ease, the size grade against the chart), the
 *  drape's checks, and the summary. Free with drape_free(). */
DRAPE_API drape_status drape_tryon_json(drape_tryon_result result, char** out_json);
/** The number of garments, inner first (the index of the accessors below). */
DRAPE_API drape_status drape_tryon_get_garment_count(drape_tryon_result result, size_t* count);
/** Garment `index` (inner first) as a new mesh handle: its graded pattern and the draped
 *  vertices (world, metres), independent of the result. */
DRAPE_API drape_status drape_tryon_get_garment_mesh(drape_tryon_result result, size_t index,
                                                    drape_garment_mesh* out_mesh);
/** The target body (its shape, the pose draped in) as a new body handle. */
DRAPE_API drape_status drape_tryon_get_body(drape_tryon_result result, drape_body* out_body);
/** Writes the folder of `drape tryon` (tryon.json, garment_N.glb/.obj, pattern_N.svg/.dxf/
 *  .json, grading_N.svg, body.glb, outfit.glb, report.html; for a photo target overlay.png,
 *  mask.png, own_garment_mask.png): staged, then moved in whole, so a failure or a cancel
 *  (checked before the move; operation "write_tryon") leaves `folder` as it was. */
DRAPE_API drape_status drape_tryon_write_folder(drape_tryon_result result, const char* folder,
                                                const drape_monitor* monitor);

/* ---- animation ----------------------------------------------------------------------- */

typedef struct drape_animate_inputs {
    uint32_t struct_size;
    const char* const* garments; /* garment_count specs, inner first: "DIR" or "DIR:N" as for
                                    drape_tryon; the first folder's body (and the pose it was
                                    draped in) is the body animated; required */
    size_t garment_count;        /* >= 1 */
    const char* motion;          /* "walk" (NULL: the built-in walk cycle) or a .bvh file,
                                    retargeted with the standard joint map (docs/animation.md) */
} drape_animate_inputs;
/** Sets every field of *inputs to its default (given beside each field above). Set
 *  inputs->struct_size = sizeof *inputs first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_animate_inputs_init(drape_animate_inputs* inputs);

typedef struct drape_animate_options {
    uint32_t struct_size;
    double seconds;              /* length, (0, 120] s (5); a shorter BVH holds its last pose */
    double fps;                  /* frame rate, (0, 240] (30) */
    double edge_cm;              /* mesh edge of the garments, (0, 20] cm (3) */
    double wind_x, wind_y, wind_z; /* wind, world frame, m/s (0, 0, 0) */
} drape_animate_options;
/** Sets every field of *options to its default (given beside each field above). Set
 *  options->struct_size = sizeof *options first (docs/c-api.md, "Versioned structs"). */
DRAPE_API drape_status drape_animate_options_init(drape_animate_options* options);

typedef struct drape_animation_s* drape_animation;

/** Dresses recovered garments on their body and animates them along the motion, as `drape
 *  animate` (docs/animation.md): the body moves (walk or BVH), the garments are simulated on
 *  it with optional wind, every frame is checked. model NULL = the built-in model. options
 *  and monitor may be NULL; the monitor is called after every drape step (stage "draping")
 *  and every frame ("blending", "animating"; step = frames done, fraction = of the phase).
 *  \return DRAPE_OK (every frame made, no frame deeper than 2 mm in the body, no crossing, no
 *          garment sunk 5 cm down the body);
 *          DRAPE_ERROR_NO_CONVERGENCE with an animation when it stopped early or is not
 *          usable (the frames made are kept; see its JSON), without one when the outfit could
 *          not be draped; DRAPE_ERROR_INVALID_ARGUMENT (bad folders, options, a BVH that does
 *          not parse or does not fit, naming the file); DRAPE_ERROR_IO; DRAPE_ERROR_CANCELLED
 *          (no animation). */
DRAPE_API drape_status drape_animate(drape_body_model model, const drape_animate_inputs* inputs,
                                     const drape_animate_options* options, const drape_monitor* monitor,
                                     drape_animation* out_animation);
/** Releases the handle and what it owns; NULL is a no-op. */
DRAPE_API void drape_animation_destroy(drape_animation animation);
/** animation.json of `drape animate`: frames, vertices, per-frame checks (penetration,
 *  crossings, speed), the maxima, seconds per frame, the motion, fps, wind and the drape.
 *  Free with drape_free(). */
DRAPE_API drape_status drape_animation_json(drape_animation animation, char** out_json);
/** Output frames and garments of the animation. */
DRAPE_API drape_status drape_animation_get_counts(drape_animation animation, size_t* frame_count,
                                                  size_t* garment_count);
/** Garment `garment`'s vertices at output frame `frame` (#V x 3, world, metres; the vertex
 *  order of its mesh, drape_animation_get_garment_mesh); size-query protocol. */
DRAPE_API drape_status drape_animation_get_frame_vertices(drape_animation animation, size_t garment, size_t frame,
                                                          double* out, size_t capacity, size_t* required);
/** Garment `garment` as a new mesh handle (pattern, faces, stitches), its vertices as draped
 *  before the motion. */
DRAPE_API drape_status drape_animation_get_garment_mesh(drape_animation animation, size_t garment,
                                                        drape_garment_mesh* out_mesh);
/** Writes the folder of `drape animate` (animation.glb: the skinned body with its motion and
 *  each garment as per-frame morph targets; frames/garment_N_KKKK.obj; animation.json):
 *  staged, then moved in whole; a failure or a cancel (checked before the move; operation
 *  "write_animation") leaves `folder` as it was. monitor may be NULL. */
DRAPE_API drape_status drape_animation_write_folder(drape_animation animation, const char* folder,
                                                    const drape_monitor* monitor);

#ifdef __cplusplus
}
#endif

#endif /* DRAPE_DRAPE_H */
