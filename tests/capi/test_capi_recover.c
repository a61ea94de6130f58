/* Recovery through the C API on a synthetic scene (C99):
 *  1. the cancel flag, set by another thread (as a UI would) when a stage is first reported
 *     (the callback itself says "go on"), stops drape_recover at a later progress check:
 *     DRAPE_ERROR_CANCELLED, no recovery; the time from the set to the return is printed and
 *     bounded (what runs between two checks: docs/c-api.md, "Progress and cancellation");
 *  2. a finished recovery's result folder, cancelled before the move, leaves the folder as it
 *     was (an earlier run's result.json stays); written without a cancel, it is replaced whole;
 *  3. written onto a full disk (a 64 KB tmpfs; skipped with a message where mounting is not
 *     permitted), it fails with DRAPE_ERROR_IO naming the folder and leaves it as it was;
 *  4. the recovery's body and garment mesh handles.
 *   test_capi_recover PHOTO JOINTS STROKES OUT_DIR */
#define _POSIX_C_SOURCE 200809L
#include <drape/drape.h>

#include <dirent.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "c_check.h"

static double now_s(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

typedef struct canceller {
    const char* at_stage;  /* set the flag when this stage is first reported */
    drape_cancel_flag flag;
    double set_at;         /* now_s() when set, 0 before (guarded by mutex) */
    int armed;             /* the stage was reported (guarded by mutex) */
    int done;              /* the call returned (guarded by mutex) */
    pthread_mutex_t mutex;
    pthread_cond_t wake;
    char stages[512];      /* the stages reported, in order */
} canceller;

static int32_t cancel_at_stage(void* user, const drape_progress* p) {
    canceller* c = (canceller*)user;
    if (strstr(c->stages, p->stage) == NULL && strlen(c->stages) + strlen(p->stage) + 2 < sizeof c->stages) {
        strcat(c->stages, p->stage);
        strcat(c->stages, " ");
    }
    if (strcmp(p->stage, c->at_stage) == 0) {
        pthread_mutex_lock(&c->mutex);
        c->armed = 1;
        pthread_cond_signal(&c->wake);
        pthread_mutex_unlock(&c->mutex);
    }
    return 1; /* go on: the flag alone must stop the call */
}

/* The other thread: sets the flag once the stage was reported. */
static void* set_flag_when_armed(void* user) {
    canceller* c = (canceller*)user;
    pthread_mutex_lock(&c->mutex);
    while (!c->armed && !c->done) pthread_cond_wait(&c->wake, &c->mutex);
    if (c->armed && !c->done) {
        c->set_at = now_s();
        drape_cancel_flag_set(c->flag);
    }
    pthread_mutex_unlock(&c->mutex);
    return NULL;
}

/* Stops the folder's write when every file is staged, before the move. */
static int32_t stop_at_moving(void* user, const drape_progress* p) {
    (void)user;
    return strcmp(p->stage, "moving") != 0;
}

/* The first byte of DIR/NAME, or -1. */
static int first_byte(const char* dir, const char* name) {
    char path[8192]; /* folder (< 4096) + name */
    FILE* f;
    int c;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    f = fopen(path, "rb");
    if (!f) return -1;
    c = fgetc(f);
    fclose(f);
    return c;
}

static void write_text(const char* dir, const char* name, const char* text) {
    char path[8192]; /* folder (< 4096) + name */
    FILE* f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    f = fopen(path, "wb");
    if (!f) return;
    fputs(text, f);
    fclose(f);
}

static int file_exists(const char* dir, const char* name) {
    char path[8192]; /* folder (< 4096) + name */
    FILE* f;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    f = fopen(path, "rb");
    if (f) fclose(f);
    return f != NULL;
}

/* A recovery cancelled at the first report of `stage`; returns the seconds from the set to the
 * return (-1 if the stage was never reported). */
static double cancelled_recovery(const drape_recover_inputs* in, const drape_recover_options* o, const char* stage) {
    canceller c;
    drape_monitor m;
    drape_recovery r = NULL;
    drape_status st;
    pthread_t thread;
    double latency, returned;
    memset(&c, 0, sizeof c);
    c.at_stage = stage;
    pthread_mutex_init(&c.mutex, NULL);
    pthread_cond_init(&c.wake, NULL);
    CHECK(drape_cancel_flag_create(&c.flag) == DRAPE_OK);
    m.struct_size = sizeof m;
    drape_monitor_init(&m);
    m.progress = cancel_at_stage;
    m.user = &c;
    m.cancel = c.flag;
    if (pthread_create(&thread, NULL, set_flag_when_armed, &c) != 0) return -1;
    st = drape_recover(NULL, in, o, &m, &r);
    returned = now_s();
    pthread_mutex_lock(&c.mutex);
    c.done = 1;
    pthread_cond_signal(&c.wake);
    pthread_mutex_unlock(&c.mutex);
    pthread_join(thread, NULL);
    latency = c.set_at > 0 ? returned - c.set_at : -1;
    CHECK(st == DRAPE_ERROR_CANCELLED);
    CHECK(r == NULL);
    CHECK(strcmp(drape_last_error_message(), "drape_recover: cancelled") == 0);
    printf("cancel at '%s': returned %.2f s after the flag was set (stages reported: %s)\n", stage, latency, c.stages);
    drape_recovery_destroy(r);
    drape_cancel_flag_destroy(c.flag);
    pthread_cond_destroy(&c.wake);
    pthread_mutex_destroy(&c.mutex);
    return latency;
}

int main(int argc, char** argv) {
    drape_recover_inputs in;
    drape_recover_options o;
    drape_recovery r = NULL;
    drape_monitor m;
    char folder[4096];
    double latency;
    drape_status st;
    if (argc < 5) {
        fprintf(stderr, "usage: %s PHOTO JOINTS STROKES OUT_DIR\n", argv[0]);
        return 2;
    }
    in.struct_size = sizeof in;
    drape_recover_inputs_init(&in);
    in.image_path = argv[1];
    in.joints_path = argv[2];
    in.strokes_path = argv[3];
    in.garments = "skirt";
    o.struct_size = sizeof o;
    drape_recover_options_init(&o);
    o.quality = "fast";
    o.particles = 8;
    o.generations = 2;
    o.rounds = 1;

    /* 1. Cancel bounds: the segmentation (one check after it), and the search (the flag is
     *    set at its first report, after the dressing; the next check follows one swarm
     *    generation of 8 particles). */
    latency = cancelled_recovery(&in, &o, "segmenting");
    CHECK(latency >= 0 && latency < 20.0);
    latency = cancelled_recovery(&in, &o, "sizing");
    CHECK(latency >= 0 && latency < 60.0);

    /* 2. A finished recovery (the smallest search, and the search's re-drape as the result:
     *    this part tests the files, not the estimate), its folder cancelled before the move,
     *    then written whole. */
    o.estimate_material = 0;
    o.particles = 4;
    o.generations = 1;
    o.output_drape = "best";
    CHECK(drape_recover(NULL, &in, &o, NULL, &r) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(r == NULL);
    CHECK(strstr(drape_last_error_message(), "unknown output drape 'best'") != NULL);
    o.output_drape = "search";
    /* The options added after output_drape: their defaults, then each bad value named. */
    CHECK(o.material_target == NULL && o.base_fabric == NULL && o.joint_pose == 0);
    CHECK(o.max_arm_elevation_degrees == 90.0 && o.min_ease_cm == 2.0);
    o.base_fabric = "velvet";
    CHECK(drape_recover(NULL, &in, &o, NULL, &r) == DRAPE_ERROR_INVALID_ARGUMENT && r == NULL);
    CHECK(strstr(drape_last_error_message(), "base_fabric 'velvet' is not a measured fabric") != NULL);
    o.base_fabric = "gray-interlock";
    o.min_ease_cm = 12;
    CHECK(drape_recover(NULL, &in, &o, NULL, &r) == DRAPE_ERROR_INVALID_ARGUMENT && r == NULL);
    CHECK(strstr(drape_last_error_message(), "min_ease_cm must be in [-10, 10]") != NULL);
    o.min_ease_cm = -3;
    o.max_arm_elevation_degrees = -1;
    CHECK(drape_recover(NULL, &in, &o, NULL, &r) == DRAPE_ERROR_INVALID_ARGUMENT && r == NULL);
    CHECK(strstr(drape_last_error_message(), "max_arm_elevation_degrees must be in [0, 180]") != NULL);
    o.max_arm_elevation_degrees = 120;
    o.material_target = "guess";
    CHECK(drape_recover(NULL, &in, &o, NULL, &r) == DRAPE_ERROR_INVALID_ARGUMENT && r == NULL);
    o.material_target = "calibrated";
    st = drape_recover(NULL, &in, &o, NULL, &r);
    CHECK(st == DRAPE_OK || (st == DRAPE_ERROR_NO_CONVERGENCE && r != NULL));
    if (!r) return 1;
    {
        char* g = NULL;
        CHECK(drape_recovery_garment_json(r, 0, &g) == DRAPE_OK);
        CHECK(g && strstr(g, "\"mesh\": \"search\"") != NULL);  /* dump(2): "key": value */
        drape_free(g);
        g = NULL;
        CHECK(drape_recovery_json(r, &g) == DRAPE_OK);  /* the options the recovery ran with */
        CHECK(g && strstr(g, "\"min_ease_cm\": -3.0") != NULL);
        CHECK(g && strstr(g, "\"max_arm_elevation_degrees\": 120.0") != NULL);
        CHECK(g && strstr(g, "\"base_fabric\": \"gray-interlock\"") != NULL);
        drape_free(g);
    }
    snprintf(folder, sizeof folder, "%s/result", argv[4]);
    CHECK(drape_recovery_write_folder(r, folder, NULL) == DRAPE_OK);  /* an earlier run's folder */
    CHECK(first_byte(folder, "result.json") == '{');
    write_text(folder, "result.json", "an earlier run");
    m.struct_size = sizeof m;
    drape_monitor_init(&m);
    m.progress = stop_at_moving;
    CHECK(drape_recovery_write_folder(r, folder, &m) == DRAPE_ERROR_CANCELLED);
    CHECK(first_byte(folder, "result.json") == 'a'); /* the folder as it was */
    CHECK(drape_recovery_write_folder(r, folder, NULL) == DRAPE_OK);
    CHECK(first_byte(folder, "result.json") == '{'); /* replaced whole */
    CHECK(file_exists(folder, "result.json"));
    CHECK(file_exists(folder, "outfit.glb"));
    CHECK(file_exists(folder, "garment_0.glb"));
    CHECK(file_exists(folder, "pattern_0.svg"));

    /* 3. A full disk: 64 KB hold the earlier run's file but not the glb files. */
    {
        char cmd[9000];
        snprintf(folder, sizeof folder, "%s/full", argv[4]);
        snprintf(cmd, sizeof cmd, "mkdir -p '%s' && mount -t tmpfs -o size=64k tmpfs '%s' 2>/dev/null", folder, folder);
        if (system(cmd) != 0) {
            printf("full disk: skipped, mounting a tmpfs is not permitted here\n");
        } else {
            DIR* d;
            struct dirent* e;
            int leftovers = 0, entries = 0;
            write_text(folder, "result.json", "an earlier run");
            CHECK(drape_recovery_write_folder(r, folder, NULL) == DRAPE_ERROR_IO);
            CHECK(strstr(drape_last_error_message(), folder) != NULL);
            printf("full disk: %s\n", drape_last_error_message());
            CHECK(first_byte(folder, "result.json") == 'a'); /* the folder as it was */
            d = opendir(folder);
            CHECK(d != NULL);
            while (d && (e = readdir(d)) != NULL) {
                if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
                ++entries;
                if (e->d_name[0] == '.') ++leftovers; /* a staging folder or temporary file */
            }
            if (d) closedir(d);
            CHECK(entries == 1);
            CHECK(leftovers == 0);
            snprintf(cmd, sizeof cmd, "umount '%s'", folder);
            CHECK(system(cmd) == 0);
        }
    }

    /* 4. The recovered body and garment as handles. */
    {
        drape_body b = NULL;
        drape_garment_mesh gm = NULL;
        size_t nv = 0, nf = 0, ns = 0;
        CHECK(drape_recovery_get_body(r, &b) == DRAPE_OK && b != NULL);
        CHECK(drape_body_get_counts(b, &nv, &nf) == DRAPE_OK);
        CHECK(nv > 1000 && nf > 2000);
        drape_body_destroy(b);
        CHECK(drape_recovery_get_garment_mesh(r, 0, &gm) == DRAPE_OK && gm != NULL);
        CHECK(drape_garment_mesh_get_counts(gm, &nv, &nf, &ns) == DRAPE_OK);
        CHECK(nv > 10 && nf > 10);
        drape_garment_mesh_destroy(gm);
        gm = NULL;
        CHECK(drape_recovery_get_garment_mesh(r, 1, &gm) == DRAPE_ERROR_INVALID_ARGUMENT && gm == NULL);
    }
    drape_recovery_destroy(r);
    if (failures) fprintf(stderr, "%d check(s) failed\n", failures);
    return failures ? 1 : 0;
}
