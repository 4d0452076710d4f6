/* Möbius Catmull–Clark on a polygon mesh: reads an OFF file (argv[1]; without an argument a
 * cube inscribed in the unit sphere), subdivides it two levels with the canonical Möbius
 * version of Catmull–Clark (seed 000 §4) in one call, writes out.off and prints the counts.
 * On the built-in cube every output vertex stays on the unit sphere, which the linear
 * Catmull–Clark scheme does not do: both deviations are printed. The passes run on every core
 * through the pool of nlsubdiv_pool.h (the output is the same bits for every thread count).
 *
 * Build (from the repository root, after `cargo build --release -p nlsubdiv-ffi`):
 *   cc -std=c99 -Iinclude c_examples/mesh_subdivide.c target/release/libnlsubdiv.a -lm -pthread -o mesh_subdivide
 *   ./mesh_subdivide [in.off]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "nlsubdiv.h"
#include "nlsubdiv_pool.h"

/* The threads of every call: one pool, started once in main. */
static nls_pool pool;

typedef struct {
    size_t vertex_count, face_count, index_count;
    double *positions;  /* 3 * vertex_count */
    uint32_t *offsets;  /* face_count + 1 */
    uint32_t *indices;  /* index_count */
} mesh;

static void mesh_free(mesh *m) {
    free(m->positions);
    free(m->offsets);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

/* The next non-empty line of `f` without its comment, or NULL at the end of the file. */
static char *next_line(FILE *f, char *buf, int size) {
    while (fgets(buf, size, f) != NULL) {
        char *hash = strchr(buf, '#'), *p = buf;
        if (hash != NULL) *hash = '\0';
        while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') p++;
        if (*p != '\0') return p;
    }
    return NULL;
}

/* Reads an OFF file, one vertex or face per line (extra columns after the coordinates or the
 * face indices, such as COFF colours, are ignored). */
static int read_off(const char *path, mesh *m) {
    char buf[8192], *line, *end;
    unsigned long nv, nf, k, cap = 0;
    FILE *f = fopen(path, "r");
    memset(m, 0, sizeof *m);
    if (f == NULL) {
        fprintf(stderr, "%s: cannot open\n", path);
        return 0;
    }
    line = next_line(f, buf, (int)sizeof buf);
    if (line == NULL) goto bad;
    if (*line == 'C' || *line == 'N') line++; /* COFF, NOFF: extra columns, ignored */
    if (strncmp(line, "OFF", 3) != 0) goto bad;
    line += 3;
    while (*line == ' ' || *line == '\t' || *line == '\r' || *line == '\n') line++;
    if (*line == '\0' && (line = next_line(f, buf, (int)sizeof buf)) == NULL) goto bad;
    if (sscanf(line, "%lu %lu", &nv, &nf) != 2 || nv > 100000000ul || nf > 100000000ul) goto bad;
    m->vertex_count = nv;
    m->face_count = nf;
    m->positions = (double *)malloc(3 * nv * sizeof(double) + 1);
    m->offsets = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
    if (m->positions == NULL || m->offsets == NULL) goto bad;
    for (k = 0; k < nv; k++) {
        double *p = m->positions + 3 * k;
        if ((line = next_line(f, buf, (int)sizeof buf)) == NULL) goto bad;
        if (sscanf(line, "%lf %lf %lf", p, p + 1, p + 2) != 3) goto bad;
    }
    m->offsets[0] = 0;
    for (k = 0; k < nf; k++) {
        unsigned long n, j;
        if ((line = next_line(f, buf, (int)sizeof buf)) == NULL) goto bad;
        n = strtoul(line, &end, 10);
        if (end == line || n > 1024) goto bad;
        if (m->index_count + n > cap) {
            uint32_t *grown;
            cap = 2 * cap + n + 16;
            grown = (uint32_t *)realloc(m->indices, cap * sizeof(uint32_t));
            if (grown == NULL) goto bad;
            m->indices = grown;
        }
        for (j = 0; j < n; j++) {
            line = end;
            m->indices[m->index_count++] = (uint32_t)strtoul(line, &end, 10);
            if (end == line) goto bad;
        }
        m->offsets[k + 1] = (uint32_t)m->index_count;
    }
    fclose(f);
    return 1;
bad:
    fprintf(stderr, "%s: not an OFF file this example can read\n", path);
    fclose(f);
    mesh_free(m);
    return 0;
}

static int write_off(const char *path, const mesh *m) {
    size_t i, f;
    FILE *out = fopen(path, "w");
    if (out == NULL) return 0;
    fprintf(out, "OFF\n%lu %lu 0\n", (unsigned long)m->vertex_count, (unsigned long)m->face_count);
    for (i = 0; i < m->vertex_count; i++)
        fprintf(out, "%.17g %.17g %.17g\n", m->positions[3 * i], m->positions[3 * i + 1], m->positions[3 * i + 2]);
    for (f = 0; f < m->face_count; f++) {
        uint32_t c;
        fprintf(out, "%u", (unsigned)(m->offsets[f + 1] - m->offsets[f]));
        for (c = m->offsets[f]; c < m->offsets[f + 1]; c++) fprintf(out, " %u", (unsigned)m->indices[c]);
        fprintf(out, "\n");
    }
    return fclose(out) == 0;
}

/* A cube with its corners on the unit sphere. */
static void builtin_cube(mesh *m) {
    static const uint32_t faces[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};
    const double s = 1.0 / sqrt(3.0);
    int i;
    m->vertex_count = 8;
    m->face_count = 6;
    m->index_count = 24;
    m->positions = (double *)malloc(24 * sizeof(double));
    m->offsets = (uint32_t *)malloc(7 * sizeof(uint32_t));
    m->indices = (uint32_t *)malloc(sizeof faces);
    for (i = 0; i < 8; i++) {
        m->positions[3 * i] = (i & 1) ? s : -s;
        m->positions[3 * i + 1] = (i & 2) ? s : -s;
        m->positions[3 * i + 2] = (i & 4) ? s : -s;
    }
    for (i = 0; i <= 6; i++) m->offsets[i] = (uint32_t)(4 * i);
    memcpy(m->indices, faces, sizeof faces);
}

/* `levels` levels of `scheme` with `flags` into *out; prints the error and returns 0 on
 * failure. The sizes of the output and of the scratch come from the plan: plan scratch size,
 * plan, subdivide. */
static int subdivide(const mesh *in, uint32_t scheme, uint32_t flags, uint32_t levels, mesh *out,
                     nls_subdivide_report *report) {
    size_t su = 0, sp = 0;
    uint32_t *scratch_u32 = NULL, element = NLS_NO_ELEMENT;
    double *scratch_points = NULL;
    nls_mesh_view view;
    nls_subdivide_options options;
    nls_plan plan;
    nls_status s;
    memset(out, 0, sizeof *out);
    view.positions = in->positions;
    view.vertex_count = in->vertex_count;
    view.positions_stride = 0; /* packed x, y, z */
    view.offsets = in->offsets;
    view.face_count = in->face_count;
    view.indices = in->indices;
    view.index_count = in->index_count;
    nls_subdivide_default_options(&options);
    options.scheme = scheme;
    options.flags = flags;
    options.levels = levels;
    options.executor = nls_pool_executor(&pool); /* NULL with one thread: the calling thread */
    s = nls_mesh_plan_scratch_size(&view, &su);
    if (s == NLS_STATUS_OK) {
        /* the plan needs the input's topology scratch; it gives the scratch of the whole call */
        scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t) + 1);
        s = nls_mesh_plan(&view, &options, scratch_u32, su, &plan, &element);
        free(scratch_u32);
    }
    if (s == NLS_STATUS_OK) {
        su = plan.scratch_u32;
        sp = plan.scratch_points;
        out->vertex_count = plan.output.vertex_count;
        out->face_count = plan.output.face_count;
        out->index_count = plan.output.index_count;
    }
    if (s == NLS_STATUS_OK) {
        scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t) + 1);
        scratch_points = (double *)malloc(3 * sp * sizeof(double) + 1);
        out->positions = (double *)malloc(3 * out->vertex_count * sizeof(double) + 1);
        out->offsets = (uint32_t *)malloc((out->face_count + 1) * sizeof(uint32_t));
        out->indices = (uint32_t *)malloc(out->index_count * sizeof(uint32_t) + 1);
        if (!scratch_u32 || !scratch_points || !out->positions || !out->offsets || !out->indices) {
            fprintf(stderr, "out of memory\n");
            s = NLS_STATUS_BUFFER_TOO_SMALL;
        } else {
            nls_scratch scratch;
            nls_mesh_buffers buffers;
            nls_mesh_sizes written;
            scratch.u32s = scratch_u32;
            scratch.u32_capacity = su;
            scratch.points = scratch_points;
            scratch.point_capacity = sp;
            buffers.positions = out->positions;
            buffers.vertex_capacity = out->vertex_count;
            buffers.offsets = out->offsets;
            buffers.face_capacity = out->face_count;
            buffers.indices = out->indices;
            buffers.index_capacity = out->index_count;
            s = nls_mesh_subdivide(&view, &options, &scratch, &buffers, &written, report, &element);
            out->vertex_count = written.vertex_count;
            out->face_count = written.face_count;
            out->index_count = written.index_count;
        }
        free(scratch_u32);
        free(scratch_points);
    }
    if (s != NLS_STATUS_OK) {
        if (element != NLS_NO_ELEMENT)
            fprintf(stderr, "subdivision failed: %s (element %u)\n", nls_status_str(s), (unsigned)element);
        else
            fprintf(stderr, "subdivision failed: %s\n", nls_status_str(s));
        mesh_free(out);
        return 0;
    }
    return 1;
}

static double sphere_deviation(const mesh *m) {
    size_t i;
    double worst = 0.0;
    for (i = 0; i < m->vertex_count; i++) {
        const double *p = m->positions + 3 * i;
        double d = fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0);
        if (d > worst) worst = d;
    }
    return worst;
}

int main(int argc, char **argv) {
    mesh in, out;
    nls_subdivide_report report;
    const uint32_t levels = 2;
    if (nls_pool_init(&pool, 0) != 0) fprintf(stderr, "no thread pool: one thread\n");
    if (argc > 1) {
        if (!read_off(argv[1], &in)) {
            nls_pool_destroy(&pool);
            return 1;
        }
    } else {
        builtin_cube(&in);
    }
    printf("input:  %lu vertices, %lu faces, %lu corners%s\n", (unsigned long)in.vertex_count,
           (unsigned long)in.face_count, (unsigned long)in.index_count, argc > 1 ? "" : " (cube on the unit sphere)");
    if (!subdivide(&in, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, levels, &out, &report)) {
        mesh_free(&in);
        nls_pool_destroy(&pool);
        return 1;
    }
    printf("output: %lu vertices, %lu faces, %lu corners after %u levels of Möbius Catmull-Clark (%u threads)\n",
           (unsigned long)out.vertex_count, (unsigned long)out.face_count, (unsigned long)out.index_count,
           (unsigned)levels, pool.threads);
    if (report.fallbacks > 0)
        printf("        %u vertices took the linear rule (degenerate stars), the first: vertex %u of level %u\n",
               (unsigned)report.fallbacks, (unsigned)report.first_fallback, (unsigned)report.first_fallback_level);
    if (argc <= 1) {
        mesh lin;
        printf("largest distance from the unit sphere: Möbius %.1e", sphere_deviation(&out));
        if (subdivide(&in, NLS_SCHEME_CATMULL_CLARK, 0, levels, &lin, &report)) {
            printf(", linear %.1e", sphere_deviation(&lin));
            mesh_free(&lin);
        }
        printf("\n");
    }
    if (!write_off("out.off", &out)) {
        fprintf(stderr, "out.off: cannot write\n");
        mesh_free(&in);
        mesh_free(&out);
        nls_pool_destroy(&pool);
        return 1;
    }
    printf("wrote out.off\n");
    mesh_free(&in);
    mesh_free(&out);
    nls_pool_destroy(&pool);
    return 0;
}
