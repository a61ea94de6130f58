/* Two threads use distinct handles at once: each shapes and poses its own body, makes a
 * skirt pattern sized for it, meshes it, simulates it on its body for a few steps and reads
 * the vertices back, and provokes an error whose per-thread message must name its own
 * argument. Run in the default suite and under ThreadSanitizer (scripts/test_tsan.sh). */
#define _POSIX_C_SOURCE 200809L
#include <drape/drape.h>

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct job {
    double height_m;        /* in: the body's stature */
    int ok;                 /* out: every check passed */
    char why[512];          /* out: the first failed check */
    double top_y;           /* out: the highest cloth vertex (the waist) after the steps */
    size_t cloth_vertices;  /* out */
} job;

static pthread_mutex_t g_errors_mutex = PTHREAD_MUTEX_INITIALIZER;
static int g_errors = 0;

static void count_error(void* user, drape_status status, const char* message) {
    (void)user;
    (void)status;
    (void)message;
    pthread_mutex_lock(&g_errors_mutex);
    ++g_errors;
    pthread_mutex_unlock(&g_errors_mutex);
}

#define EXPECT(cond)                                                                                        \
    do {                                                                                                    \
        if (!(cond)) {                                                                                      \
            snprintf(j->why, sizeof j->why, "line %d: %s (last error: %s)", __LINE__, #cond,               \
                     drape_last_error_message());                                                           \
            goto done;                                                                                      \
        }                                                                                                   \
    } while (0)

static void* run(void* arg) {
    job* j = (job*)arg;
    drape_body body = NULL;
    drape_pattern pattern = NULL;
    drape_garment_mesh mesh = NULL;
    drape_simulator sim = NULL;
    drape_shape_params p;
    double rotations[22 * 3];
    double* x = NULL;
    size_t n = 0, k;
    const char* name = j->height_m < 1.7 ? "first_thread_argument" : "second_thread_argument";

    j->ok = 0;
    EXPECT(drape_body_create(NULL, &body) == DRAPE_OK);
    p.struct_size = sizeof p;
    EXPECT(drape_shape_params_init(&p) == DRAPE_OK);
    p.gender = DRAPE_GENDER_FEMALE;
    p.height_m = j->height_m;
    EXPECT(drape_body_set_shape(body, &p) == DRAPE_OK);
    memset(rotations, 0, sizeof rotations);
    rotations[3 * 1 + 0] = -0.2; /* a little flexion at the left hip */
    EXPECT(drape_body_set_pose(body, rotations, 22 * 3, NULL) == DRAPE_OK);

    /* A failure on this thread: its message names this thread's value, whatever the other
     * thread does meanwhile. */
    EXPECT(drape_pattern_create(name, NULL, &pattern) == DRAPE_ERROR_INVALID_ARGUMENT);
    EXPECT(strstr(drape_last_error_message(), name) != NULL);

    EXPECT(drape_pattern_create_for_body("skirt", body, &pattern) == DRAPE_OK);
    EXPECT(drape_garment_mesh_create(pattern, 6.0, &mesh) == DRAPE_OK);
    EXPECT(drape_simulator_create_from_garment(mesh, "gray-interlock", NULL, &sim) == DRAPE_OK);
    EXPECT(drape_simulator_set_obstacle_body(sim, body) == DRAPE_OK);
    EXPECT(drape_simulator_step(sim, 3, NULL) == DRAPE_OK);
    EXPECT(drape_simulator_get_vertices(sim, NULL, 0, &n) == DRAPE_OK);
    EXPECT(n > 300 && n % 3 == 0);
    x = (double*)malloc(n * sizeof *x);
    EXPECT(x != NULL);
    EXPECT(drape_simulator_get_vertices(sim, x, n, NULL) == DRAPE_OK);
    j->top_y = -1e9;
    for (k = 0; k < n; ++k) EXPECT(isfinite(x[k]));
    for (k = 1; k < n; k += 3)
        if (x[k] > j->top_y) j->top_y = x[k];
    j->cloth_vertices = n / 3;
    j->ok = 1;
done:
    free(x);
    drape_simulator_destroy(sim);
    drape_garment_mesh_destroy(mesh);
    drape_pattern_destroy(pattern);
    drape_body_destroy(body);
    return NULL;
}

int main(void) {
    job jobs[2];
    pthread_t threads[2];
    int t, failures = 0;
    memset(jobs, 0, sizeof jobs);
    jobs[0].height_m = 1.55;
    jobs[1].height_m = 1.85;
    drape_set_error_function(count_error, NULL);
    for (t = 0; t < 2; ++t)
        if (pthread_create(&threads[t], NULL, run, &jobs[t]) != 0) return 1;
    for (t = 0; t < 2; ++t) pthread_join(threads[t], NULL);
    drape_set_error_function(NULL, NULL);
    for (t = 0; t < 2; ++t) {
        if (!jobs[t].ok) {
            fprintf(stderr, "thread %d failed: %s\n", t, jobs[t].why);
            ++failures;
        } else {
            printf("thread %d: body %.2f m, %u cloth vertices, waist at y = %.3f m\n", t, jobs[t].height_m,
                   (unsigned)jobs[t].cloth_vertices, jobs[t].top_y);
        }
    }
    /* One provoked error per thread reached the error function. */
    if (g_errors != 2) {
        fprintf(stderr, "the error function was called %d times, expected 2\n", g_errors);
        ++failures;
    }
    /* Distinct bodies give distinct skirts: sized for the taller body, the skirt is longer and
     * wider, so its mesh at the same edge length has more vertices. */
    if (!failures && !(jobs[1].cloth_vertices > jobs[0].cloth_vertices + 20)) {
        fprintf(stderr, "the skirts have %u and %u vertices: expected more on the taller body's\n",
                (unsigned)jobs[0].cloth_vertices, (unsigned)jobs[1].cloth_vertices);
        ++failures;
    }
    return failures ? 1 : 0;
}
