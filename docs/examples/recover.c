/* Recover the garments of one photo through the C API: print each garment's sizing G and
 * material, export the outfit as a glTF binary and write the result folder.
 *
 *   recover PHOTO JOINTS.json OUT_DIR [STROKES.png] [GARMENTS]
 *
 * GARMENTS is "auto" (default) or names joined by '+' (skirt, tshirt+pants, ...). The
 * recovery runs at fast quality with a small swarm (8 particles, 2 generations), about a
 * minute for one garment; drop those settings for the paper's quality (docs/recovery.md).
 * Built and run as the test "capi: docs/examples/recover.c" on a synthetic scene rendered
 * by `drape synth` (docs/c-api.md, "The example"). */
#include <drape/drape.h>

#include <stdio.h>
#include <string.h>

/* Progress on stderr, once per stage. */
static int32_t print_progress(void* user, const drape_progress* p) {
    char* last_stage = (char*)user;
    if (strcmp(last_stage, p->stage) != 0) {
        fprintf(stderr, "recover: [%.1f s] %s\n", p->seconds, p->stage);
        strncpy(last_stage, p->stage, 63);
        last_stage[63] = '\0';
    }
    return 1; /* go on */
}

/* Every failure also reaches this function (as Embree's error callback). */
static void print_error(void* user, drape_status status, const char* message) {
    (void)user;
    fprintf(stderr, "drape error (%s): %s\n", drape_status_string(status), message);
}

int main(int argc, char** argv) {
    drape_recover_inputs inputs;
    drape_recover_options options;
    drape_monitor monitor;
    drape_recovery recovery = NULL;
    drape_status status;
    char last_stage[64] = "";
    char glb_path[4096];
    size_t count = 0, i;
    FILE* glb;
    long glb_bytes = 0;

    if (argc < 4) {
        fprintf(stderr, "usage: %s PHOTO JOINTS.json OUT_DIR [STROKES.png] [GARMENTS]\n", argv[0]);
        return 2;
    }
    drape_set_error_function(print_error, NULL);
    printf("Drape %s\n", drape_version());

    inputs.struct_size = sizeof inputs;
    drape_recover_inputs_init(&inputs);
    inputs.image_path = argv[1];
    inputs.joints_path = argv[2];
    if (argc > 4 && argv[4][0] != '\0') inputs.strokes_path = argv[4];
    if (argc > 5) inputs.garments = argv[5];

    options.struct_size = sizeof options;
    drape_recover_options_init(&options);
    options.quality = "fast";
    options.particles = 8;
    options.generations = 2;

    monitor.struct_size = sizeof monitor;
    drape_monitor_init(&monitor);
    monitor.progress = print_progress;
    monitor.user = last_stage;

    status = drape_recover(NULL, &inputs, &options, &monitor, &recovery);
    if (status != DRAPE_OK && !(status == DRAPE_ERROR_NO_CONVERGENCE && recovery)) {
        fprintf(stderr, "recover failed: %s\n", drape_last_error_message());
        return 1;
    }
    if (status == DRAPE_ERROR_NO_CONVERGENCE) printf("note: %s\n", drape_last_error_message());

    drape_recovery_get_garment_count(recovery, &count);
    printf("%u garment(s)\n", (unsigned)count);
    for (i = 0; i < count; ++i) {
        char* sizing = NULL;
        char* material = NULL;
        if (drape_recovery_garment_sizing_json(recovery, i, &sizing) != DRAPE_OK ||
            drape_recovery_garment_material_json(recovery, i, &material) != DRAPE_OK) {
            drape_free(sizing);
            drape_recovery_destroy(recovery);
            return 1;
        }
        printf("garment %u\n  G (cm, degrees): %s\n  material: %s\n", (unsigned)i, sizing, material);
        drape_free(sizing);
        drape_free(material);
    }

    snprintf(glb_path, sizeof glb_path, "%s/outfit_capi.glb", argv[3]);
    if (drape_recovery_write_folder(recovery, argv[3], NULL) != DRAPE_OK ||
        drape_recovery_export(recovery, glb_path) != DRAPE_OK) {
        drape_recovery_destroy(recovery);
        return 1;
    }
    drape_recovery_destroy(recovery);
    glb = fopen(glb_path, "rb");
    if (glb) {
        fseek(glb, 0, SEEK_END);
        glb_bytes = ftell(glb);
        fclose(glb);
    }
    if (glb_bytes < 1000) {
        fprintf(stderr, "%s is missing or too small (%ld bytes)\n", glb_path, glb_bytes);
        return 1;
    }
    printf("wrote %s (%ld bytes) and the result folder %s\n", glb_path, glb_bytes, argv[3]);
    return 0;
}
