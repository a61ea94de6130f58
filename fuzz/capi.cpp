// The C API (capi/include/drape/drape.h) with random arguments: the input is decoded into a
// sequence of calls (at most kMaxCalls) on a few live handles. Arguments: NULL or valid
// handles (never dangling ones: those are the caller's bug), NULL / empty / random / too long
// strings as names, paths and JSON texts, files written from the input (joints, sizing,
// material and pattern JSON) and a tiny valid PNG, numbers out of range (NaN, +-inf,
// negative, huge), versioned structs whose struct_size is 0, too small or larger than ours
// (the buffer is exactly struct_size bytes, so a read past it is an ASan report), pose arrays
// of the wrong length, and output buffers of every capacity around the required one.
//
// The contract checked, besides ASan/UBSan/LSan: every call returns DRAPE_OK or a
// DRAPE_ERROR_* code other than INTERNAL ("a bug") and OUT_OF_MEMORY; a failure sets a
// non-empty last-error message and calls the error function with the same status; an
// output handle is set on success and NULL on failure (except NO_CONVERGENCE, which may
// return one). The long calls (fit, segment, dress, recover, try-on, animate) get a monitor
// whose cancel flag is set, or inputs that cannot be valid, so they only run their
// validation and reading: the time limit per input is a few seconds.
//
// Bodies are made of the built-in model, passed as a handle loaded once per process from
// capi_default_model.h5 next to the harness (written there by the first run: generating the
// model takes about a minute under ASan, longer than a unit may run). model NULL and
// drape_body_model_default are therefore not called (the capi tests cover them); the
// 4-vertex model of fuzz/corpus/body_model (DRAPE_FUZZ_MODEL) is loaded as a second, odd model.
#include "fuzz_common.hpp"

#include <drape/drape.h>

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace {

constexpr int kMaxCalls = 24;

// An 8 x 8 RGB PNG: a photo that decodes, so the readers after the image (joints, strokes,
// palette) are reached.
const unsigned char kTinyPng[] = {
    137, 80,  78,  71,  13,  10,  26,  10,  0,   0,   0,   13,  73,  72,  68,  82,  0,   0,   0,   8,   0,
    0,   0,   8,   8,   2,   0,   0,   0,   75,  109, 41,  220, 0,   0,   0,   108, 73,  68,  65,  84,  120,
    156, 21,  205, 65,  21,  0,   81,  8,   66,  81,  163, 24,  133, 40,  70,  121, 81,  136, 66,  20,  162,
    204, 31,  151, 92,  14,  206, 12,  59,  104, 184, 129, 193, 67,  134, 14,  51,  203, 46,  90,  110, 97,
    241, 146, 165, 251, 64,  172, 144, 56,  129, 176, 136, 168, 30,  28,  123, 232, 184, 131, 195, 71,  142,
    222, 131, 127, 224, 85,  95,  248, 159, 33,  208, 247, 110, 204, 26,  153, 243, 31,  219, 196, 212, 15,
    194, 6,   133, 203, 95,  118, 72,  104, 30,  148, 45,  42,  215, 127, 194, 37,  165, 229, 3,   198, 123,
    88,  1,   159, 87,  222, 116, 0,   0,   0,   0,   73,  69,  78,  68,  174, 66,  96,  130};

[[noreturn]] void finding(const char* call, const std::string& what) {
    std::fprintf(stderr, "fuzz capi: %s: %s\n", call, what.c_str());
    std::abort();
}

drape_body_model g_default_model = nullptr;  // the built-in model, shared by every input, never destroyed
int g_error_calls = 0;
drape_status g_error_status = DRAPE_OK;
void on_error(void*, drape_status status, const char* message) {
    ++g_error_calls;
    g_error_status = status;
    if (!message || !*message) finding("error function", "called with an empty message");
}

/// Checks one call's status against the contract.
drape_status checked(const char* call, drape_status st, int calls_before) {
    static const bool trace = std::getenv("DRAPE_FUZZ_TRACE") != nullptr;  // to read what an input does
    if (trace) std::fprintf(stderr, "%s -> %d %s\n", call, int(st), st ? drape_last_error_message() : "");
    if (st == DRAPE_OK) return st;
    if (st < DRAPE_ERROR_INVALID_ARGUMENT || st > DRAPE_ERROR_INTERNAL)
        finding(call, "status " + std::to_string(int(st)) + " is not a drape_status");
    const char* msg = drape_last_error_message();
    if (!msg || !*msg) finding(call, "failed with status " + std::to_string(int(st)) + " and no message");
    if (st == DRAPE_ERROR_INTERNAL || st == DRAPE_ERROR_OUT_OF_MEMORY)
        finding(call, std::string(drape_status_string(st)) + ": " + msg);
    if (g_error_calls != calls_before + 1 || g_error_status != st)
        finding(call, "the error function was not called once with the status");
    return st;
}

#define CALL(expr)                                   \
    [&] {                                            \
        const int before_ = g_error_calls;           \
        const drape_status st_ = (expr);             \
        return checked(#expr, st_, before_);         \
    }()

struct Fuzz {
    FuzzedDataProvider& in;
    std::filesystem::path dir;
    std::deque<std::string> strings;  // keeps every string handed to the library alive
    std::vector<std::unique_ptr<unsigned char[]>> blocks;

    drape_body_model model = nullptr;
    drape_body body = nullptr;
    drape_pattern pattern = nullptr;
    drape_garment_mesh mesh = nullptr;
    drape_simulator sim = nullptr;
    bool sim_small = false;
    int shapings = 0;  // calls that shape or measure a body: 0.5-2 s each under ASan
    /// Whether one more such call fits in the input's budget (else it gets a NULL body).
    bool shaping() { return shapings++ < 3; }  // a raw mesh of a few vertices: stepping it is cheap
    drape_cancel_flag cancel = nullptr;

    Fuzz(FuzzedDataProvider& input, std::filesystem::path scratch) : in(input), dir(std::move(scratch)) {}
    Fuzz(const Fuzz&) = delete;
    Fuzz& operator=(const Fuzz&) = delete;
    ~Fuzz() {
        drape_simulator_destroy(sim);
        drape_garment_mesh_destroy(mesh);
        drape_pattern_destroy(pattern);
        drape_body_destroy(body);
        if (model != g_default_model) drape_body_model_destroy(model);
        drape_cancel_flag_destroy(cancel);
    }

    const char* keep(std::string s) {
        strings.push_back(std::move(s));
        return strings.back().c_str();
    }
    std::string path(const char* name) const { return (dir / name).string(); }

    double number() {
        switch (in.ConsumeIntegralInRange(0, 9)) {
            case 0: return std::numeric_limits<double>::quiet_NaN();
            case 1: return std::numeric_limits<double>::infinity();
            case 2: return -std::numeric_limits<double>::infinity();
            case 3: return -1;
            case 4: return 0;
            case 5: return 1e300;
            case 6: return -1e-300;
            case 7: return in.ConsumeFloatingPoint<double>();
            default: return in.ConsumeFloatingPointInRange<double>(-3, 3);
        }
    }
    /// A number near `typical` (a valid value, usually) or an out-of-range one.
    double number_near(double typical) {
        return in.ConsumeBool() ? typical * in.ConsumeFloatingPointInRange<double>(0.5, 1.5) : number();
    }
    int32_t int_arg() {
        switch (in.ConsumeIntegralInRange(0, 4)) {
            case 0: return std::numeric_limits<int32_t>::min();
            case 1: return -1;
            case 2: return 0;
            case 3: return std::numeric_limits<int32_t>::max();
            default: return in.ConsumeIntegralInRange<int32_t>(-3, 8);
        }
    }
    size_t size_arg(size_t typical) {
        switch (in.ConsumeIntegralInRange(0, 4)) {
            case 0: return 0;
            case 1: return std::numeric_limits<size_t>::max();
            case 2: return typical ? typical - 1 : 0;
            case 3: return typical + 1;
            default: return typical;
        }
    }

    /// NULL, "", random text, one of `names`, a file written from the input, a missing file,
    /// the scratch folder or the tiny PNG.
    const char* text(std::initializer_list<const char*> names = {}) {
        switch (in.ConsumeIntegralInRange(0, 9)) {
            case 0: return nullptr;
            case 1: return "";
            case 2: return keep(in.ConsumeRandomLengthString(64));
            case 3: return keep(std::string(5000, 'x'));
            case 4: return keep(path(in.PickValueInArray({"joints.json", "sizing.json", "material.json",
                                                           "pattern.json", "arcsim.json"})));
            case 5: return keep(path("missing/file.json"));
            case 6: return keep(dir.string());
            case 7: return keep(path("tiny.png"));
            default:
                if (names.size() == 0) return keep(in.ConsumeRandomLengthString(16));
                return *(names.begin() + in.ConsumeIntegralInRange<size_t>(0, names.size() - 1));
        }
    }
    /// A JSON text: NULL, random bytes, or one written as a file.
    const char* json_text() {
        switch (in.ConsumeIntegralInRange(0, 3)) {
            case 0: return nullptr;
            case 1: return "{}";
            case 2: return keep(std::string(200, '[') + std::string(200, ']'));
            default: return keep(in.ConsumeRandomLengthString(512));
        }
    }
    /// An output path: a file in the scratch folder with one of the export extensions (or a
    /// bad one), a missing folder, the folder itself, NULL.
    const char* out_path() {
        switch (in.ConsumeIntegralInRange(0, 4)) {
            case 0: return nullptr;
            case 1: return keep(path("missing/out.glb"));
            case 2: return keep(dir.string());
            case 3: return keep(path("out") + in.ConsumeRandomLengthString(8));
            default:
                return keep(path("out") +
                            in.PickValueInArray({".glb", ".obj", ".svg", ".dxf", ".json", ".png", ".txt", ""}));
        }
    }

    /// A versioned struct: NULL (the defaults, where allowed) or `s` in a buffer of exactly
    /// struct_size bytes (at least 4, at most ours + 64) with a random struct_size.
    template <class S>
    const S* versioned(const S& s) {
        uint32_t size = sizeof(S);
        switch (in.ConsumeIntegralInRange(0, 9)) {
            case 0: return nullptr;
            case 1: size = 0; break;
            case 2: size = in.ConsumeIntegralInRange<uint32_t>(1, sizeof(S) - 1); break;
            case 3: size = sizeof(S) + in.ConsumeIntegralInRange<uint32_t>(1, 64); break;
            case 4: size = std::numeric_limits<uint32_t>::max(); break;
            default: break;
        }
        const size_t bytes = std::max<size_t>(4, std::min<size_t>(size, sizeof(S) + 64));
        blocks.push_back(std::make_unique<unsigned char[]>(bytes));
        unsigned char* b = blocks.back().get();
        std::memset(b, 0xA5, bytes);
        std::memcpy(b, &s, std::min(bytes, sizeof(S)));
        std::memcpy(b, &size, 4);
        return reinterpret_cast<const S*>(b);
    }
    template <class S>
    S initialised(drape_status (*init)(S*)) {
        S s{};
        s.struct_size = sizeof(S);
        if (CALL(init(&s)) != DRAPE_OK) finding("init", "a struct of our size was refused");
        return s;
    }
    /// A monitor whose cancel flag is set (or a progress function that cancels).
    const drape_monitor* cancelling_monitor() {
        drape_monitor m = initialised(drape_monitor_init);
        if (in.ConsumeBool()) {
            drape_cancel_flag_set(cancel);
            m.cancel = cancel;
        } else {
            m.progress = [](void*, const drape_progress*) -> int32_t { return 0; };
        }
        blocks.push_back(std::make_unique<unsigned char[]>(sizeof m));
        std::memcpy(blocks.back().get(), &m, sizeof m);
        return reinterpret_cast<const drape_monitor*>(blocks.back().get());
    }

    /// A caller buffer of `capacity` values around `required` (exactly that size), or NULL.
    template <class T, class Get>
    void size_query(const char* call, Get get) {
        size_t required = 0;
        if (CALL(get(nullptr, 0, &required)) != DRAPE_OK) return;
        if (required > (size_t(1) << 26)) finding(call, "required " + std::to_string(required));
        const size_t capacity = std::min(size_arg(required), required + 1);
        std::vector<T> buf(capacity);
        size_t again = 0;
        const drape_status st = CALL(get(capacity ? buf.data() : nullptr, capacity, in.ConsumeBool() ? &again : nullptr));
        if (st == DRAPE_OK && capacity >= required && required && !buf.data()) finding(call, "no buffer");
    }

    template <class H>
    void expect_handle(const char* call, drape_status st, H h) {
        if (st == DRAPE_OK && !h) finding(call, "DRAPE_OK without a handle");
        if (st != DRAPE_OK && st != DRAPE_ERROR_NO_CONVERGENCE && h) finding(call, "failed but returned a handle");
    }

    void write_file(const char* name, const std::string& bytes) {
        std::ofstream(dir / name, std::ios::binary | std::ios::trunc) << bytes;
    }

    void step();
};

void Fuzz::step() {
    switch (in.ConsumeIntegralInRange(0, 35)) {
        case 0: {  // a file the calls read
            const char* name = in.PickValueInArray({"joints.json", "sizing.json", "material.json", "pattern.json",
                                                    "arcsim.json"});
            write_file(name, in.ConsumeRandomLengthString(2048));
            break;
        }
        case 1: {  // body model files: the small model, or paths that are no HDF5 file
            drape_body_model m = nullptr;
            const char* p = in.PickValueInArray<const char*>(
                {nullptr, "", "/nonexistent/model.h5", DRAPE_FUZZ_MODEL, "/", "/dev/null"});
            const std::string png = path("tiny.png");
            expect_handle("drape_body_model_load", CALL(drape_body_model_load(in.ConsumeBool() ? p : png.c_str(), &m)),
                          m);
            CALL(drape_body_model_load(DRAPE_FUZZ_MODEL, nullptr));
            if (m && in.ConsumeBool()) CALL(drape_body_model_save(m, out_path()));
            if (m && in.ConsumeBool()) {
                if (model != g_default_model) drape_body_model_destroy(model);
                model = m;
            } else {
                drape_body_model_destroy(m);
                if (model != g_default_model && in.ConsumeBool()) {
                    drape_body_model_destroy(model);
                    model = g_default_model;
                }
            }
            break;
        }
        case 2: {
            CALL(drape_body_create(model, nullptr));
            if (!shaping()) break;
            drape_body_destroy(body);
            body = nullptr;
            expect_handle("drape_body_create", CALL(drape_body_create(model, &body)), body);
            break;
        }
        case 3: {  // shape parameters with NaN, inf, negative, huge values and any struct_size
            drape_shape_params p = initialised(drape_shape_params_init);
            p.gender = in.ConsumeBool() ? int_arg() : in.ConsumeIntegralInRange(0, 2);
            for (double* v : {&p.height_m, &p.weight_kg, &p.muscle, &p.chest_girth_m, &p.waist_girth_m, &p.hip_girth_m,
                              &p.thigh_girth_m, &p.calf_girth_m, &p.shoulder_height_m, &p.crotch_height_m})
                if (in.ConsumeBool()) *v = number();
            const drape_shape_params* arg = versioned(p);
            CALL(drape_body_set_shape(in.ConsumeBool() && shaping() ? body : nullptr, arg));
            break;
        }
        case 4: {
            drape_shape_params p = initialised(drape_shape_params_init);
            drape_shape_params* out = const_cast<drape_shape_params*>(versioned(p));
            CALL(drape_body_get_shape(body, out));
            break;
        }
        case 5: {  // a pose array of any length, any values
            const size_t n = in.ConsumeBool() ? 66 : in.ConsumeIntegralInRange<size_t>(0, 70);
            std::vector<double> r(n);
            for (double& v : r) v = in.ConsumeBool() ? number() : in.ConsumeFloatingPointInRange(-0.5, 0.5);
            double t[3] = {number(), number(), number()};
            CALL(drape_body_set_pose(body, n ? r.data() : nullptr, in.ConsumeBool() ? n : size_arg(n),
                                     in.ConsumeBool() ? t : nullptr));
            break;
        }
        case 6: {
            size_t v = 0, f = 0;
            CALL(drape_body_get_counts(body, in.ConsumeBool() ? &v : nullptr, in.ConsumeBool() ? &f : nullptr));
            break;
        }
        case 7:
            size_query<double>("drape_body_get_vertices",
                               [&](double* o, size_t c, size_t* r) { return drape_body_get_vertices(body, o, c, r); });
            break;
        case 8:
            size_query<int32_t>("drape_body_get_faces",
                                [&](int32_t* o, size_t c, size_t* r) { return drape_body_get_faces(body, o, c, r); });
            break;
        case 9:
            size_query<double>("drape_body_get_joints",
                               [&](double* o, size_t c, size_t* r) { return drape_body_get_joints(body, o, c, r); });
            break;
        case 10: {
            drape_measurements m = initialised(drape_measurements_init);
            drape_measurements* out = const_cast<drape_measurements*>(versioned(m));
            CALL(drape_body_measure(shaping() ? body : nullptr, out));
            break;
        }
        case 11: CALL(drape_body_export(body, out_path())); break;
        case 12: {
            char* json = nullptr;
            CALL(drape_body_to_json(body, in.ConsumeBool() ? &json : nullptr));
            drape_free(json);
            break;
        }
        case 13: {  // joint names, status strings, struct inits with any struct_size
            (void)drape_joint_name(size_arg(drape_joint_count()));
            (void)drape_status_string(static_cast<drape_status>(in.ConsumeIntegralInRange(0, 7)));
            drape_shape_params p{};
            p.struct_size = in.ConsumeIntegralInRange<uint32_t>(0, sizeof p + 8);
            if (p.struct_size > sizeof p) p.struct_size = sizeof p;
            CALL(drape_shape_params_init(in.ConsumeBool() ? &p : nullptr));
            drape_monitor m{};
            m.struct_size = in.ConsumeIntegralInRange<uint32_t>(0, sizeof m);
            CALL(drape_monitor_init(&m));
            break;
        }
        case 14: {  // a pattern from a garment name and a sizing JSON text
            drape_pattern p = nullptr;
            const char* g = text({"skirt", "pants", "tshirt", "dress", "shorts", "Skirt"});
            expect_handle("drape_pattern_create", CALL(drape_pattern_create(g, json_text(), &p)), p);
            if (p) {
                drape_pattern_destroy(pattern);
                pattern = p;
            }
            break;
        }
        case 15: {
            drape_pattern p = nullptr;
            const char* g = text({"skirt", "pants", "tshirt", "dress"});
            expect_handle("drape_pattern_create_for_body",
                          CALL(drape_pattern_create_for_body(g, shaping() ? body : nullptr, &p)), p);
            drape_pattern_destroy(p);
            break;
        }
        case 16: {
            char* json = nullptr;
            CALL(drape_pattern_to_json(pattern, in.ConsumeBool() ? &json : nullptr));
            drape_free(json);
            break;
        }
        case 17: CALL(drape_pattern_export(pattern, out_path())); break;
        case 18: {  // meshing: a coarse edge, or one out of range
            drape_garment_mesh m = nullptr;
            const double edge = in.ConsumeBool() ? in.ConsumeFloatingPointInRange(4.0, 20.0) : number();
            const drape_status st = CALL(drape_garment_mesh_create(pattern, edge, &m));
            expect_handle("drape_garment_mesh_create", st, m);
            if (m) {
                drape_garment_mesh_destroy(mesh);
                mesh = m;
            }
            break;
        }
        case 19: {
            size_t v = 0, f = 0, s = 0;
            CALL(drape_garment_mesh_get_counts(mesh, in.ConsumeBool() ? &v : nullptr, &f, in.ConsumeBool() ? &s : nullptr));
            switch (in.ConsumeIntegralInRange(0, 3)) {
                case 0:
                    size_query<double>("drape_garment_mesh_get_vertices", [&](double* o, size_t c, size_t* r) {
                        return drape_garment_mesh_get_vertices(mesh, o, c, r);
                    });
                    break;
                case 1:
                    size_query<int32_t>("drape_garment_mesh_get_faces", [&](int32_t* o, size_t c, size_t* r) {
                        return drape_garment_mesh_get_faces(mesh, o, c, r);
                    });
                    break;
                case 2:
                    size_query<double>("drape_garment_mesh_get_pattern_coords", [&](double* o, size_t c, size_t* r) {
                        return drape_garment_mesh_get_pattern_coords(mesh, o, c, r);
                    });
                    break;
                default:
                    size_query<int32_t>("drape_garment_mesh_get_stitches", [&](int32_t* o, size_t c, size_t* r) {
                        return drape_garment_mesh_get_stitches(mesh, o, c, r);
                    });
            }
            break;
        }
        case 20: {
            drape_pattern p = nullptr;
            expect_handle("drape_garment_mesh_get_pattern", CALL(drape_garment_mesh_get_pattern(mesh, &p)), p);
            drape_pattern_destroy(p);
            CALL(drape_garment_mesh_export(mesh, out_path()));
            CALL(drape_garment_mesh_export_flat(mesh, out_path()));
            break;
        }
        case 21: {  // a raw simulator of a few vertices: any indices, any values, any material
            const size_t nv = in.ConsumeIntegralInRange<size_t>(0, 8), nf = in.ConsumeIntegralInRange<size_t>(0, 6);
            std::vector<double> v(3 * nv), uv(2 * nv);
            for (size_t i = 0; i < v.size(); ++i) v[i] = in.ConsumeBool() ? number() : double(i % 5) * 0.1;
            for (size_t i = 0; i < uv.size(); ++i) uv[i] = in.ConsumeBool() ? number() : double(i % 3) * 0.1;
            std::vector<int32_t> f(3 * nf);
            for (int32_t& x : f) x = in.ConsumeBool() ? int_arg() : in.ConsumeIntegralInRange<int32_t>(0, int32_t(nv));
            drape_simulator_options o = initialised(drape_simulator_options_init);
            for (double* x : {&o.time_step_s, &o.gravity_y, &o.air_drag_n_s_per_m3, &o.contact_thickness_m,
                              &o.obstacle_friction})
                if (in.ConsumeBool()) *x = number();
            if (in.ConsumeBool()) o.max_newton_iterations = in.ConsumeIntegralInRange(-2, 20);
            if (in.ConsumeBool()) o.self_contact = int_arg();
            drape_simulator s = nullptr;
            const drape_status st = CALL(drape_simulator_create(
                nv ? v.data() : nullptr, nv, nf ? f.data() : nullptr, nf, in.ConsumeBool() && nv ? uv.data() : nullptr,
                text({"gray-interlock", "denim", "nonsense"}), versioned(o), &s));
            expect_handle("drape_simulator_create", st, s);
            if (s) {
                drape_simulator_destroy(sim);
                sim = s;
                sim_small = true;
            }
            break;
        }
        case 22: {
            drape_simulator_options o = initialised(drape_simulator_options_init);
            if (in.ConsumeBool()) o.time_step_s = number();
            drape_simulator s = nullptr;
            const drape_status st = CALL(drape_simulator_create_from_garment(
                mesh, text({"gray-interlock", "nonsense"}), versioned(o), &s));
            expect_handle("drape_simulator_create_from_garment", st, s);
            if (s) {
                drape_simulator_destroy(sim);
                sim = s;
                sim_small = false;
            }
            break;
        }
        case 23: {  // obstacles: raw arrays, the body, none
            const size_t nv = in.ConsumeIntegralInRange<size_t>(0, 6), nf = in.ConsumeIntegralInRange<size_t>(0, 4);
            std::vector<double> v(3 * nv);
            for (double& x : v) x = in.ConsumeBool() ? number() : in.ConsumeFloatingPointInRange(-1.0, 1.0);
            std::vector<int32_t> f(3 * nf);
            for (int32_t& x : f) x = in.ConsumeBool() ? int_arg() : in.ConsumeIntegralInRange<int32_t>(0, int32_t(nv));
            switch (in.ConsumeIntegralInRange(0, 2)) {
                case 0:
                    CALL(drape_simulator_set_obstacle(sim, nv ? v.data() : nullptr, nv, nf ? f.data() : nullptr, nf));
                    break;
                case 1: CALL(drape_simulator_set_obstacle_body(sim, body)); break;
                default: CALL(drape_simulator_clear_obstacle(sim));
            }
            break;
        }
        case 24: {  // pin, step, solve: cheap on a raw mesh; cancelled at once on a garment's
            CALL(drape_simulator_pin(sim, size_arg(3)));
            const drape_monitor* mon = sim_small && in.ConsumeBool() ? nullptr : cancelling_monitor();
            if (in.ConsumeBool())
                CALL(drape_simulator_step(sim, in.ConsumeBool() ? in.ConsumeIntegralInRange(-2, 3) : int_arg() % 4, mon));
            else
                CALL(drape_simulator_solve_static(sim, mon));
            drape_cancel_flag_reset(cancel);
            break;
        }
        case 25: {
            size_t v = 0, f = 0;
            CALL(drape_simulator_get_counts(sim, &v, in.ConsumeBool() ? &f : nullptr));
            size_query<double>("drape_simulator_get_vertices", [&](double* o, size_t c, size_t* r) {
                return drape_simulator_get_vertices(sim, o, c, r);
            });
            std::vector<double> x(in.ConsumeIntegralInRange<size_t>(0, 30));
            for (double& y : x) y = in.ConsumeBool() ? number() : 0.1;
            CALL(drape_simulator_set_vertices(sim, x.empty() ? nullptr : x.data(), x.size() / 3));
            char* json = nullptr;
            if (sim_small) CALL(drape_simulator_report_json(sim, &json));
            drape_free(json);
            break;
        }
        case 26: {  // segmentation: the tiny PNG or a bad file, joints from the input
            drape_segment_options o = initialised(drape_segment_options_init);
            o.strokes_path = in.ConsumeBool() ? nullptr : text();
            o.palette_path = in.ConsumeBool() ? nullptr : text();
            o.hint = in.ConsumeBool() ? nullptr : text({"skirt", "t-shirt", "dress", "pants"});
            if (in.ConsumeBool()) o.height_m = number();
            drape_segmentation s = nullptr;
            const drape_status st = CALL(drape_segment(text(), text(), versioned(o), &s));
            expect_handle("drape_segment", st, s);
            if (s) {
                int32_t w = 0, h = 0;
                CALL(drape_segmentation_get_size(s, &w, in.ConsumeBool() ? &h : nullptr));
                size_query<uint8_t>("drape_segmentation_get_labels", [&](uint8_t* o2, size_t c, size_t* r) {
                    return drape_segmentation_get_labels(s, o2, c, r);
                });
                char* json = nullptr;
                CALL(drape_segmentation_garments_json(s, &json));
                drape_free(json);
                CALL(drape_segmentation_export_labels(s, out_path()));
                size_query<uint8_t>("drape_segmentation_get_occlusion", [&](uint8_t* o2, size_t c, size_t* r) {
                    return drape_segmentation_get_occlusion(s, o2, c, r);
                });
                CALL(drape_segmentation_write_folder(s, out_path()));
            }
            drape_segmentation_destroy(s);
            break;
        }
        case 27: {  // body fit: validation and reading only (cancelled)
            drape_fit_inputs fi = initialised(drape_fit_inputs_init);
            fi.image_path = text();
            fi.joints_path = text();
            fi.silhouette_path = in.ConsumeBool() ? nullptr : text();
            fi.labels_path = in.ConsumeBool() ? nullptr : text();
            fi.height_m = number();
            fi.gender = int_arg();
            drape_fit_options fo = initialised(drape_fit_options_init);
            if (in.ConsumeBool()) fo.focal_px = number();
            if (in.ConsumeBool()) fo.threads = int_arg();
            if (in.ConsumeBool()) fo.skin_weight = number();
            char* json = nullptr;
            if (in.ConsumeBool())
                CALL(drape_body_fit(body, versioned(fi), versioned(fo), cancelling_monitor(), in.ConsumeBool() ? &json : nullptr));
            else
                CALL(drape_body_fit_to_folder(body, versioned(fi), versioned(fo), cancelling_monitor(), out_path(),
                                              in.ConsumeBool() ? &json : nullptr));
            drape_free(json);
            drape_cancel_flag_reset(cancel);
            break;
        }
        case 28: {  // dressing: validation only (cancelled), specs of any struct_size
            const size_t n = in.ConsumeIntegralInRange<size_t>(0, 3);
            drape_garment_spec spec = initialised(drape_garment_spec_init);
            uint32_t stride = sizeof spec;
            switch (in.ConsumeIntegralInRange(0, 4)) {
                case 0: stride = 0; break;  // refused
                case 1: stride = offsetof(drape_garment_spec, garment) + sizeof(const char*); break;
                case 2: stride = sizeof spec + 16; break;
                default: break;
            }
            const size_t bytes = std::max<size_t>(sizeof spec, n * std::max<size_t>(stride, 4));
            blocks.push_back(std::make_unique<unsigned char[]>(bytes));
            unsigned char* b = blocks.back().get();
            std::memset(b, 0, bytes);
            for (size_t g = 0; g < std::max<size_t>(n, 1); ++g) {
                spec.struct_size = stride;
                spec.garment = text({"skirt", "pants", "tshirt", "dress"});
                spec.sizing_json = in.ConsumeBool() ? nullptr : json_text();
                spec.material = text({"gray-interlock", "denim"});
                std::memcpy(b + g * stride, &spec, std::min<size_t>(std::max<uint32_t>(stride, 4), sizeof spec));
                if (stride == 0) break;
            }
            drape_dress_options o = initialised(drape_dress_options_init);
            if (in.ConsumeBool()) o.edge_cm = number();
            if (in.ConsumeBool()) o.body_motion_s = number();
            if (in.ConsumeBool()) o.max_steps = int_arg();
            drape_outfit out = nullptr;
            const drape_status st = CALL(drape_dress(body, in.ConsumeBool() ? reinterpret_cast<drape_garment_spec*>(b) : nullptr,
                                                     n, versioned(o), cancelling_monitor(), &out));
            if (st == DRAPE_OK || out) finding("drape_dress", "a cancelled call returned an outfit");
            drape_cancel_flag_reset(cancel);
            break;
        }
        case 29: {  // recover: validation and reading only (cancelled)
            drape_recover_inputs ri = initialised(drape_recover_inputs_init);
            ri.image_path = text();
            ri.joints_path = text();
            ri.strokes_path = in.ConsumeBool() ? nullptr : text();
            ri.palette_path = in.ConsumeBool() ? nullptr : text();
            ri.garments = text({"auto", "skirt", "pants+tshirt", "dress+", "+"});
            ri.height_m = number();
            ri.gender = int_arg();
            drape_recover_options ro = initialised(drape_recover_options_init);
            ro.quality = in.ConsumeBool() ? nullptr : text({"fast", "default", "fine"});
            if (in.ConsumeBool()) ro.threads = int_arg();
            if (in.ConsumeBool()) ro.particles = int_arg();
            if (in.ConsumeBool()) ro.generations = int_arg();
            if (in.ConsumeBool()) ro.rounds = int_arg();
            drape_recovery r = nullptr;
            const drape_status st = CALL(drape_recover(model, versioned(ri), versioned(ro), cancelling_monitor(), &r));
            if (st == DRAPE_OK || r) finding("drape_recover", "a cancelled call returned a recovery");
            drape_cancel_flag_reset(cancel);
            break;
        }
        case 30: {  // try-on: garment folders without result.json, body or photo target
            const size_t n = in.ConsumeIntegralInRange<size_t>(0, 3);
            std::vector<const char*> specs(std::max<size_t>(n, 1));
            for (const char*& s : specs)
                s = in.PickValueInArray<const char*>({nullptr, "", keep(dir.string()), keep(dir.string() + ":0"),
                                                      keep(dir.string() + ":-1"), keep(path("missing") + ":9")});
            drape_tryon_inputs ti = initialised(drape_tryon_inputs_init);
            ti.garments = in.ConsumeBool() ? specs.data() : nullptr;
            ti.garment_count = in.ConsumeBool() ? n : size_arg(n);
            if (ti.garment_count > specs.size()) ti.garment_count = specs.size();
            ti.body = in.ConsumeBool() ? body : nullptr;
            ti.image_path = in.ConsumeBool() ? nullptr : text();
            ti.joints_path = in.ConsumeBool() ? nullptr : text();
            ti.height_m = number();
            ti.gender = int_arg();
            drape_tryon_options to = initialised(drape_tryon_options_init);
            if (in.ConsumeBool()) to.edge_cm = number();
            if (in.ConsumeBool()) to.max_drape_steps = int_arg();
            if (in.ConsumeBool()) to.threads = int_arg();
            drape_tryon_result r = nullptr;
            const drape_monitor* mon = in.ConsumeBool() ? nullptr : cancelling_monitor();
            const drape_status st = CALL(drape_tryon(model, versioned(ti), versioned(to), mon, &r));
            if (st == DRAPE_OK || r) finding("drape_tryon", "returned a result without a garment folder");
            drape_cancel_flag_reset(cancel);
            break;
        }
        case 31: {  // animation: folders without result.json
            const size_t n = in.ConsumeIntegralInRange<size_t>(0, 2);
            std::vector<const char*> specs(std::max<size_t>(n, 1));
            for (const char*& s : specs)
                s = in.PickValueInArray<const char*>({nullptr, "", keep(dir.string()), keep(dir.string() + ":1")});
            drape_animate_inputs ai = initialised(drape_animate_inputs_init);
            ai.garments = in.ConsumeBool() ? specs.data() : nullptr;
            ai.garment_count = std::min(size_arg(n), specs.size());
            ai.motion = in.ConsumeBool() ? nullptr : text({"walk", "run"});
            drape_animate_options ao = initialised(drape_animate_options_init);
            for (double* x : {&ao.seconds, &ao.fps, &ao.edge_cm, &ao.wind_x})
                if (in.ConsumeBool()) *x = number();
            drape_animation a = nullptr;
            const drape_monitor* mon = in.ConsumeBool() ? nullptr : cancelling_monitor();
            const drape_status st = CALL(drape_animate(model, versioned(ai), versioned(ao), mon, &a));
            if (st == DRAPE_OK || a) finding("drape_animate", "returned an animation without a garment folder");
            drape_cancel_flag_reset(cancel);
            break;
        }
        case 32: {  // NULL handles and NULL outputs everywhere
            size_t n = 0;
            CALL(drape_outfit_get_garment_count(nullptr, &n));
            CALL(drape_recovery_get_garment_count(nullptr, &n));
            CALL(drape_tryon_get_garment_count(nullptr, &n));
            CALL(drape_animation_get_counts(nullptr, &n, &n));
            char* json = nullptr;
            CALL(drape_recovery_json(nullptr, &json));
            CALL(drape_recovery_write_folder(nullptr, text(), nullptr));
            CALL(drape_tryon_write_folder(nullptr, text(), nullptr));
            CALL(drape_animation_write_folder(nullptr, text(), nullptr));
            CALL(drape_segmentation_get_size(nullptr, nullptr, nullptr));
            CALL(drape_cancel_flag_create(nullptr));
            CALL(drape_body_measure(body, nullptr));
            CALL(drape_pattern_create("skirt", nullptr, nullptr));
            CALL(drape_garment_mesh_create(pattern, 5, nullptr));
            // The accessors of result handles (a live outfit: case 34; recoveries, try-ons and
            // animations take too long for a unit, so only their validation runs here).
            drape_garment_mesh gm = nullptr;
            drape_body b = nullptr;
            size_t req = 0;
            CALL(drape_outfit_summary_json(nullptr, &json));
            CALL(drape_outfit_get_body_vertices(nullptr, nullptr, 0, &req));
            CALL(drape_outfit_get_garment_mesh(nullptr, size_arg(1), &gm));
            CALL(drape_recovery_garment_json(nullptr, size_arg(1), &json));
            CALL(drape_recovery_garment_sizing_json(nullptr, size_arg(1), &json));
            CALL(drape_recovery_garment_material_json(nullptr, size_arg(1), &json));
            CALL(drape_recovery_get_garment_mesh(nullptr, size_arg(1), &gm));
            CALL(drape_recovery_get_body(nullptr, &b));
            CALL(drape_recovery_export(nullptr, out_path()));
            CALL(drape_tryon_json(nullptr, &json));
            CALL(drape_tryon_get_garment_mesh(nullptr, size_arg(1), &gm));
            CALL(drape_tryon_get_body(nullptr, &b));
            CALL(drape_animation_json(nullptr, &json));
            CALL(drape_animation_get_frame_vertices(nullptr, size_arg(1), size_arg(1), nullptr, 0, &req));
            CALL(drape_animation_get_garment_mesh(nullptr, size_arg(1), &gm));
            CALL(drape_segmentation_get_occlusion(nullptr, nullptr, 0, &req));
            CALL(drape_segmentation_write_folder(nullptr, out_path()));
            CALL(drape_garment_mesh_export_flat(nullptr, out_path()));
            CALL(drape_render(nullptr, nullptr, 0, nullptr, nullptr, out_path()));
            CALL(drape_body_fit_to_folder(nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
            if (gm || b || json) finding("accessors", "a NULL handle gave an output");
            break;
        }
        case 33: {  // render: validation always; a tiny render when the size and samples are small
            drape_render_options o = initialised(drape_render_options_init);
            o.lighting = in.ConsumeBool() ? nullptr : text({"studio", "midday", "sunset", "noon"});
            if (in.ConsumeBool()) {
                o.width = in.ConsumeBool() ? in.ConsumeIntegralInRange(1, 24) : int_arg();
                o.height = in.ConsumeBool() ? in.ConsumeIntegralInRange(1, 24) : int_arg();
            }
            o.samples = in.ConsumeBool() ? in.ConsumeIntegralInRange(1, 2) : int_arg();
            if (in.ConsumeBool()) o.threads = int_arg();
            o.camera = in.ConsumeBool() ? in.ConsumeIntegralInRange(0, 3) : int_arg();
            o.camera_json = in.ConsumeBool() ? nullptr : json_text();
            o.photo_path = in.ConsumeBool() ? nullptr : text();
            if (in.ConsumeBool()) o.opacity = number();
            o.labels_path = in.ConsumeBool() ? nullptr : out_path();
            const size_t n = in.ConsumeIntegralInRange<size_t>(0, 2);
            std::vector<drape_garment_mesh> meshes(std::max<size_t>(n, 1), in.ConsumeBool() ? mesh : nullptr);
            // A unit must stay well under the time limit: small images render, others are
            // cancelled at the first report (their validation and the photo's reading ran).
            const bool small = o.width > 0 && o.width <= 24 && o.height > 0 && o.height <= 24 && o.samples <= 2;
            const drape_monitor* mon = small && in.ConsumeBool() ? nullptr : cancelling_monitor();
            CALL(drape_render(shaping() ? body : nullptr, in.ConsumeBool() ? meshes.data() : nullptr,
                              in.ConsumeBool() ? n : size_arg(n), versioned(o), mon, out_path()));
            drape_cancel_flag_reset(cancel);
            break;
        }
        case 34: {  // a live outfit: a coarse skirt dressed and draped for one step, its accessors
            if (!body || in.ConsumeIntegralInRange(0, 7) != 0) break;  // rare: a dressing costs seconds
            drape_garment_spec spec = initialised(drape_garment_spec_init);
            spec.garment = "skirt";
            drape_dress_options o = initialised(drape_dress_options_init);
            o.edge_cm = 10;
            o.max_steps = 1;
            drape_outfit out = nullptr;
            const drape_status st = CALL(drape_dress(body, &spec, 1, &o, nullptr, &out));
            expect_handle("drape_dress", st, out);
            if (out) {
                size_t n = 0;
                CALL(drape_outfit_get_garment_count(out, &n));
                char* json = nullptr;
                CALL(drape_outfit_summary_json(out, in.ConsumeBool() ? &json : nullptr));
                drape_free(json);
                size_query<double>("drape_outfit_get_body_vertices", [&](double* o2, size_t c, size_t* r) {
                    return drape_outfit_get_body_vertices(out, o2, c, r);
                });
                drape_garment_mesh gm = nullptr;
                expect_handle("drape_outfit_get_garment_mesh", CALL(drape_outfit_get_garment_mesh(out, size_arg(n), &gm)), gm);
                if (gm) {
                    drape_render_options ro = initialised(drape_render_options_init);
                    ro.width = 8;
                    ro.height = 12;
                    ro.samples = 1;
                    CALL(drape_render(body, &gm, 1, &ro, nullptr, out_path()));
                }
                drape_garment_mesh_destroy(gm);
                drape_outfit_destroy(out);
            }
            break;
        }
        default: {  // the cancel flag
            const bool set = in.ConsumeBool();
            drape_cancel_flag_set(set ? cancel : nullptr);
            if (drape_cancel_flag_is_set(cancel) != int32_t(set)) finding("drape_cancel_flag_is_set", "wrong state");
            drape_cancel_flag_reset(cancel);
            if (drape_cancel_flag_is_set(nullptr) != 0) finding("drape_cancel_flag_is_set", "NULL is set");
        }
    }
}

}  // namespace

// Outside the units' time limit: the built-in model, from the cache file or generated.
// DRAPE_FUZZ_CAPI_SMALL_MODEL=1 (CI's short regression stage, scripts/test.sh): the 4-vertex
// model instead, which makes no body (every body call then sees NULL) but costs no generation.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    if (const char* small = std::getenv("DRAPE_FUZZ_CAPI_SMALL_MODEL"); small && *small == '1') {
        if (drape_body_model_load(DRAPE_FUZZ_MODEL, &g_default_model) != DRAPE_OK)
            finding("drape_body_model_load", drape_last_error_message());
        return 0;
    }
    const std::filesystem::path cache = std::filesystem::read_symlink("/proc/self/exe").parent_path() /
                                        "capi_default_model.h5";
    if (drape_body_model_load(cache.c_str(), &g_default_model) != DRAPE_OK) {
        if (drape_body_model_default(&g_default_model) != DRAPE_OK)
            finding("drape_body_model_default", drape_last_error_message());
        (void)drape_body_model_save(g_default_model, cache.c_str());  // best effort
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool once = [] {
        drape_set_error_function(on_error, nullptr);
        std::ofstream(drape::fuzz::scratch_dir() / "tiny.png", std::ios::binary)
            .write(reinterpret_cast<const char*>(kTinyPng), sizeof kTinyPng);
        return true;
    }();
    (void)once;
    FuzzedDataProvider in(data, size);
    Fuzz f{in, drape::fuzz::scratch_dir()};
    if (CALL(drape_cancel_flag_create(&f.cancel)) != DRAPE_OK) finding("drape_cancel_flag_create", "failed");
    f.model = g_default_model;
    for (const char* name : {"joints.json", "sizing.json", "material.json", "pattern.json", "arcsim.json"})
        std::filesystem::remove(f.dir / name);
    for (int i = 0; i < kMaxCalls && in.remaining_bytes() > 0; ++i) f.step();
    return 0;
}
