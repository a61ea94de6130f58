/* Proves that drape.h compiles as C99 and round-trips real calls through the C API. */
#include <drape/drape.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "c_check.h"

int main(int argc, char** argv) {
    drape_body body = NULL;
    drape_shape_params params;
    drape_measurements m;
    size_t nv = 0, nf = 0, required = 0, j;
    double* vertices;
    double rotations[22 * 3];
    double ymax = -1e9, ymin = 1e9;
    const char* out_dir = argc > 1 ? argv[1] : ".";
    char path[1024];

    CHECK(strlen(drape_version()) > 0);
    CHECK(strcmp(drape_status_string(DRAPE_ERROR_IO), "input/output error") == 0);
    CHECK(drape_joint_count() == 22);
    CHECK(strcmp(drape_joint_name(9), "right_wrist") == 0);

    /* Errors are reported, never crash. */
    CHECK(drape_body_create(NULL, NULL) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(strlen(drape_last_error_message()) > 0);
    drape_body_destroy(NULL);

    CHECK(drape_body_create(NULL, &body) == DRAPE_OK);
    CHECK(body != NULL);
    if (!body) return 1;

    params.struct_size = sizeof params;
    CHECK(drape_shape_params_init(&params) == DRAPE_OK);
    params.gender = DRAPE_GENDER_MALE;
    params.height_m = 1.80;
    params.weight_kg = 80.0;
    CHECK(drape_body_set_shape(body, &params) == DRAPE_OK);
    CHECK(drape_body_get_shape(body, &params) == DRAPE_OK);
    CHECK(params.gender == DRAPE_GENDER_MALE);
    CHECK(fabs(params.height_m - 1.80) < 1e-12);
    CHECK(params.chest_girth_m > 0.8 && params.chest_girth_m < 1.3); /* predicted */

    m.struct_size = sizeof m;
    CHECK(drape_measurements_init(&m) == DRAPE_OK);
    CHECK(drape_body_measure(body, &m) == DRAPE_OK);
    CHECK(fabs(m.height_m - 1.80) < 0.005);
    CHECK(fabs(m.chest_girth_m - params.chest_girth_m) < 0.01);

    CHECK(drape_body_get_counts(body, &nv, &nf) == DRAPE_OK);
    CHECK(nv >= 8000 && nv <= 20000);
    CHECK(drape_body_get_vertices(body, NULL, 0, &required) == DRAPE_OK);
    CHECK(required == 3 * nv);
    vertices = (double*)malloc(required * sizeof(double));
    CHECK(drape_body_get_vertices(body, vertices, required - 1, NULL) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(drape_body_get_vertices(body, vertices, required, &required) == DRAPE_OK);
    for (j = 0; j < nv; ++j) {
        if (vertices[3 * j + 1] > ymax) ymax = vertices[3 * j + 1];
        if (vertices[3 * j + 1] < ymin) ymin = vertices[3 * j + 1];
    }
    CHECK(fabs((ymax - ymin) - 1.80) < 0.005);
    {
        /* The faces: 3 x nf indices, each a vertex of the body, every vertex used. */
        size_t nidx = 0, k;
        int32_t* faces;
        unsigned char* used;
        size_t unused = 0;
        CHECK(drape_body_get_faces(body, NULL, 0, &nidx) == DRAPE_OK);
        CHECK(nidx == 3 * nf);
        faces = (int32_t*)malloc(nidx * sizeof(int32_t));
        used = (unsigned char*)calloc(nv, 1);
        CHECK(drape_body_get_faces(body, faces, nidx - 1, NULL) == DRAPE_ERROR_INVALID_ARGUMENT);
        CHECK(drape_body_get_faces(body, faces, nidx, NULL) == DRAPE_OK);
        for (k = 0; k < nidx; ++k) {
            CHECK(faces[k] >= 0 && (size_t)faces[k] < nv);
            if (faces[k] >= 0 && (size_t)faces[k] < nv) used[faces[k]] = 1;
        }
        for (k = 0; k < nv; ++k) unused += !used[k];
        CHECK(unused == 0);
        free(used);
        free(faces);
    }

    /* Raise the right arm: the right wrist must go up. */
    memset(rotations, 0, sizeof rotations);
    rotations[3 * 7 + 2] = -1.2; /* right_shoulder about +Z */
    CHECK(drape_body_set_pose(body, rotations, 22 * 3, NULL) == DRAPE_OK);
    {
        double joints[22 * 3];
        CHECK(drape_body_get_joints(body, joints, 22 * 3, NULL) == DRAPE_OK);
        CHECK(joints[3 * 9 + 1] > joints[3 * 7 + 1]); /* wrist above shoulder */
    }
    rotations[0] = NAN;
    CHECK(drape_body_set_pose(body, rotations, 22 * 3, NULL) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(drape_body_set_pose(body, rotations, 5, NULL) == DRAPE_ERROR_INVALID_ARGUMENT);

    snprintf(path, sizeof path, "%s/c_api_body.obj", out_dir);
    CHECK(drape_body_export(body, path) == DRAPE_OK);
    snprintf(path, sizeof path, "%s/c_api_body.txt", out_dir);
    CHECK(drape_body_export(body, path) == DRAPE_ERROR_INVALID_ARGUMENT);
    CHECK(drape_body_export(body, "/nonexistent-folder/x.obj") == DRAPE_ERROR_IO);

    free(vertices);
    drape_body_destroy(body);
    if (failures) {
        fprintf(stderr, "%d C API checks failed\n", failures);
        return 1;
    }
    printf("C API: all checks passed\n");
    return 0;
}
