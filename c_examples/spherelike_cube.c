/* Spherelike interpolating subdivision (seed 003 §3) of a cube cage: four levels in one
 * call of nls_mesh_subdivide with NLS_SCHEME_SPHERELIKE. The cube's corners are kept
 * bit for bit and the surface comes out close to the cube's circumsphere; the same four
 * levels of linear Kobbelt (interpolating too) and Catmull–Clark are printed for comparison.
 * Writes spherelike_cube.off in the current directory and nothing else.
 *
 * Build (from the repository root, after `cargo build --release -p nlsubdiv-ffi`):
 *   gcc -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude c_examples/spherelike_cube.c \
 *       target/release/libnlsubdiv.a -lm -o spherelike_cube
 *   ./spherelike_cube
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nlsubdiv.h"

#define LEVELS 4

static const double CUBE_P[24] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                  -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
static const uint32_t CUBE_OFF[7] = {0, 4, 8, 12, 16, 20, 24};
static const uint32_t CUBE_IDX[24] = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};

typedef struct {
    size_t vertex_count, face_count, index_count;
    double *positions;
    uint32_t *offsets;
    uint32_t *indices;
} mesh;

static void mesh_free(mesh *m) {
    free(m->positions);
    free(m->offsets);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

/* LEVELS levels of `scheme` on the cube, sized by the plan. */
static nls_status run(uint32_t scheme, mesh *out) {
    size_t su0 = 0, su = 0, sp = 0, nv = 0, nf = 0, ni = 0;
    uint32_t *scratch_u32 = NULL, element = NLS_NO_ELEMENT;
    double *scratch_points = NULL;
    nls_mesh_view cube = {CUBE_P, 8, 0, CUBE_OFF, 6, CUBE_IDX, 24};
    nls_subdivide_options options;
    nls_plan plan;
    nls_status s;
    memset(out, 0, sizeof *out);
    nls_subdivide_default_options(&options);
    options.scheme = scheme;
    options.levels = LEVELS;
    s = nls_mesh_plan_scratch_size(&cube, &su0);
    if (s != NLS_STATUS_OK) return s;
    scratch_u32 = (uint32_t *)malloc(su0 * sizeof(uint32_t));
    if (scratch_u32 == NULL) return NLS_STATUS_SIZE_OVERFLOW;
    s = nls_mesh_plan(&cube, &options, scratch_u32, su0, &plan, &element);
    free(scratch_u32);
    if (s != NLS_STATUS_OK) return s;
    nv = plan.output.vertex_count;
    nf = plan.output.face_count;
    ni = plan.output.index_count;
    su = plan.scratch_u32;
    sp = plan.scratch_points;
    scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t));
    scratch_points = (double *)malloc((3 * sp + 1) * sizeof(double));
    out->positions = (double *)malloc(3 * nv * sizeof(double));
    out->offsets = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
    out->indices = (uint32_t *)malloc(ni * sizeof(uint32_t));
    if (!scratch_u32 || !scratch_points || !out->positions || !out->offsets || !out->indices) {
        s = NLS_STATUS_SIZE_OVERFLOW;
    } else {
        nls_scratch scratch = {scratch_u32, su, scratch_points, sp};
        nls_mesh_buffers buffers = {out->positions, nv, out->offsets, nf, out->indices, ni};
        nls_mesh_sizes written = {0, 0, 0};
        s = nls_mesh_subdivide(&cube, &options, &scratch, &buffers, &written, NULL, &element);
        out->vertex_count = written.vertex_count;
        out->face_count = written.face_count;
        out->index_count = written.index_count;
    }
    free(scratch_u32);
    free(scratch_points);
    if (s != NLS_STATUS_OK) {
        fprintf(stderr, "scheme %u: %s (element %u)\n", (unsigned)scheme, nls_status_str(s), (unsigned)element);
        mesh_free(out);
    }
    return s;
}

/* Largest |‖p‖ − r| / r over the vertices, about the cube's centre (the origin), r the
 * mean distance. */
static double roundness(const mesh *m) {
    double mean = 0.0, worst = 0.0;
    size_t k;
    for (k = 0; k < m->vertex_count; k++) {
        const double *p = m->positions + 3 * k;
        mean += sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    }
    mean /= (double)m->vertex_count;
    for (k = 0; k < m->vertex_count; k++) {
        const double *p = m->positions + 3 * k;
        double d = fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - mean) / mean;
        if (d > worst) worst = d;
    }
    return worst;
}

static int write_off(const char *path, const mesh *m) {
    size_t k, c;
    FILE *f = fopen(path, "w");
    if (f == NULL) return 1;
    fprintf(f, "OFF\n%zu %zu 0\n", m->vertex_count, m->face_count);
    for (k = 0; k < m->vertex_count; k++)
        fprintf(f, "%.17g %.17g %.17g\n", m->positions[3 * k], m->positions[3 * k + 1], m->positions[3 * k + 2]);
    for (k = 0; k < m->face_count; k++) {
        fprintf(f, "%u", (unsigned)(m->offsets[k + 1] - m->offsets[k]));
        for (c = m->offsets[k]; c < m->offsets[k + 1]; c++) fprintf(f, " %u", (unsigned)m->indices[c]);
        fprintf(f, "\n");
    }
    return fclose(f) != 0;
}

int main(void) {
    static const uint32_t schemes[3] = {NLS_SCHEME_SPHERELIKE, NLS_SCHEME_KOBBELT, NLS_SCHEME_CATMULL_CLARK};
    static const char *const names[3] = {"spherelike", "kobbelt", "catmull-clark"};
    mesh m;
    int k, rc = 0;
    for (k = 0; k < 3; k++) {
        if (run(schemes[k], &m) != NLS_STATUS_OK) return 1;
        printf("%-14s %d levels: %zu vertices, %zu quads, max relative deviation from a sphere %.2e, corners %s\n",
               names[k], LEVELS, m.vertex_count, m.face_count, roundness(&m),
               memcmp(m.positions, CUBE_P, sizeof CUBE_P) == 0 ? "kept bit for bit" : "moved");
        if (k == 0 && write_off("spherelike_cube.off", &m) != 0) {
            fprintf(stderr, "cannot write spherelike_cube.off\n");
            rc = 1;
        }
        mesh_free(&m);
    }
    if (rc == 0) printf("wrote spherelike_cube.off\n");
    return rc;
}
