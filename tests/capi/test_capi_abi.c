/* ABI checks, compiled as C11 and linked against the shared library (libdrape.so):
 *  - the layout of the versioned structs of this version (v1) is pinned, so a change that
 *    moves a field fails to compile (append new fields at the end instead);
 *  - a caller compiled against v1, whose options structs are smaller than a later version's,
 *    works: *_init fills only its fields, calls read only its fields (a later field's default
 *    is used), and nothing beyond its struct_size is touched;
 *  - struct_size 0 (never set) is refused with a message naming it.
 * drape.h is also compiled as C99 (test_capi.c, test_capi_threads.c) and as C++
 * (test_capi_errors.cpp, test_capi_api.cpp). */
#include <drape/drape.h>

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#if !defined(__STDC_VERSION__) || __STDC_VERSION__ < 201112L
#error "compile this test as C11"
#endif

/* v1 layouts (LP64 / ILP32 alike for these: doubles and pointers at natural alignment). */
_Static_assert(offsetof(drape_shape_params, gender) == 4, "drape_shape_params layout changed");
_Static_assert(offsetof(drape_shape_params, height_m) == 8, "drape_shape_params layout changed");
_Static_assert(offsetof(drape_monitor, progress) == sizeof(void*), "drape_monitor layout changed");
_Static_assert(offsetof(drape_monitor, cancel) == 3 * sizeof(void*), "drape_monitor layout changed");
_Static_assert(offsetof(drape_recover_options, quality) == sizeof(void*), "drape_recover_options layout changed");
_Static_assert(offsetof(drape_recover_options, threads) == 2 * sizeof(void*), "drape_recover_options layout changed");
_Static_assert(offsetof(drape_simulator_options, time_step_s) == 8, "drape_simulator_options layout changed");
_Static_assert(offsetof(drape_simulator_options, gravity_x) == 16, "drape_simulator_options layout changed");
_Static_assert(offsetof(drape_dress_options, edge_cm) == 8, "drape_dress_options layout changed");
_Static_assert(offsetof(drape_progress, operation) == sizeof(void*), "drape_progress layout changed");
_Static_assert(sizeof(drape_status) == sizeof(int), "drape_status is an int-sized enum");

#include "c_check.h"

/* What a caller of an older drape.h would have had: the options ending earlier. The guard
 * bytes follow the struct in the caller's memory and must stay untouched. */
typedef struct recover_options_v0 {
    uint32_t struct_size;
    const char* quality;
    int32_t threads;
} recover_options_v0;

typedef struct simulator_options_v0 {
    uint32_t struct_size;
    double time_step_s;
} simulator_options_v0;

typedef struct dress_options_v0 {
    uint32_t struct_size;
    double edge_cm;
} dress_options_v0;

#define GUARD 0x5a

static int untouched(const unsigned char* bytes, size_t n) {
    size_t i;
    for (i = 0; i < n; ++i)
        if (bytes[i] != GUARD) return 0;
    return 1;
}

int main(void) {
    struct {
        recover_options_v0 o;
        unsigned char guard[64];
    } rec;
    struct {
        simulator_options_v0 o;
        unsigned char guard[64];
    } sim_opt;
    struct {
        dress_options_v0 o;
        unsigned char guard[64];
    } dress;
    drape_monitor full_monitor;
    drape_simulator sim = NULL;
    const double v[9] = {0, 0, 0, 0.1, 0, 0, 0, 0, 0.1};
    const double uv[6] = {0, 0, 0.1, 0, 0, 0.1};
    const int32_t f[3] = {0, 1, 2};
    double x[9];

    CHECK(strcmp(drape_version(), DRAPE_VERSION_STRING) == 0);

    /* init fills only the old fields. */
    memset(&rec, GUARD, sizeof rec);
    rec.o.struct_size = sizeof rec.o;
    CHECK(drape_recover_options_init((drape_recover_options*)&rec.o) == DRAPE_OK);
    CHECK(rec.o.struct_size == sizeof rec.o);
    CHECK(rec.o.quality == NULL);
    CHECK(rec.o.threads == 2);
    CHECK(untouched(rec.guard, sizeof rec.guard));

    memset(&dress, GUARD, sizeof dress);
    dress.o.struct_size = sizeof dress.o;
    CHECK(drape_dress_options_init((drape_dress_options*)&dress.o) == DRAPE_OK);
    CHECK(dress.o.edge_cm == 0);
    CHECK(untouched(dress.guard, sizeof dress.guard));

    /* A call reads only the old fields: read as gravity, the guard bytes after time_step_s
     * would be 1.2e127 m/s^2 along every axis; the default gravity pulls along -Y only. */
    memset(&sim_opt, GUARD, sizeof sim_opt);
    sim_opt.o.struct_size = sizeof sim_opt.o;
    CHECK(drape_simulator_options_init((drape_simulator_options*)&sim_opt.o) == DRAPE_OK);
    CHECK(fabs(sim_opt.o.time_step_s - 0.01) < 1e-12);
    CHECK(untouched(sim_opt.guard, sizeof sim_opt.guard));
    sim_opt.o.time_step_s = 0.005;
    CHECK(drape_simulator_create(v, 3, f, 1, uv, NULL, (const drape_simulator_options*)&sim_opt.o, &sim) == DRAPE_OK);
    if (sim) {
        CHECK(drape_simulator_step(sim, 4, NULL) == DRAPE_OK);
        CHECK(drape_simulator_get_vertices(sim, x, 9, NULL) == DRAPE_OK);
        /* 4 backward-Euler steps of 5 ms at 9.8 m/s^2: 2.45 mm down without air drag
         * (g dt^2 n (n + 1) / 2), a little less with it; x and z kept. */
        CHECK(x[1] < -0.001 && x[1] > -0.0025);
        CHECK(fabs(x[0]) < 1e-9 && fabs(x[2]) < 1e-9);
    }
    drape_simulator_destroy(sim);
    CHECK(untouched(sim_opt.guard, sizeof sim_opt.guard));

    /* A newer caller's larger struct: the library keeps its struct_size. */
    full_monitor.struct_size = sizeof full_monitor + 16;
    CHECK(drape_monitor_init(&full_monitor) == DRAPE_OK);
    CHECK(full_monitor.struct_size == sizeof full_monitor + 16);
    CHECK(full_monitor.progress == NULL && full_monitor.cancel == NULL);

    /* struct_size never set. */
    rec.o.struct_size = 0;
    CHECK(drape_recover_options_init((drape_recover_options*)&rec.o) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(strstr(drape_last_error_message(), "struct_size is 0") != NULL);
    sim_opt.o.struct_size = 0;
    CHECK(drape_simulator_create(v, 3, f, 1, uv, NULL, (const drape_simulator_options*)&sim_opt.o, &sim) ==
          DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(sim == NULL);
    CHECK(strstr(drape_last_error_message(), "options->struct_size is 0") != NULL);

    if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
    return failures ? 1 : 0;
}
