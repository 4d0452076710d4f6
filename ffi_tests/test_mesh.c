/* C99 tests of the mesh exports of nlsubdiv.h: every scheme, linear and Möbius, on small
 * generated meshes with sizes from the size queries; output validity; sphere preservation;
 * interpolation; one call of several levels against repeated single levels; the tier-1 star
 * rules against the whole-mesh driver, bit for bit; every bad-input class with its status and
 * element; the strict flag; a MemorySafe sweep over every output and scratch buffer (every
 * short capacity in a fresh heap block that ends where the buffer ends, so ASan and valgrind
 * see any overrun); the floating-point-environment guard. Run under ASan+UBSan and valgrind. */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "nlsubdiv.h"
#include "check.h"
#include "flat_args.h"

#define NSCHEMES 9
static const uint32_t SCHEMES[NSCHEMES] = {
    NLS_SCHEME_LOOP,    NLS_SCHEME_CATMULL_CLARK, NLS_SCHEME_MODIFIED_BUTTERFLY,
    NLS_SCHEME_KOBBELT, NLS_SCHEME_DOO_SABIN,     NLS_SCHEME_SIMPLEST,
    NLS_SCHEME_DUAL,    NLS_SCHEME_VERTEX_INSERTION, NLS_SCHEME_DUAL_TRUNCATION};
static const char *const NAMES[NSCHEMES] = {"loop",     "catmull-clark", "butterfly",        "kobbelt",        "doo-sabin",
                                            "simplest", "dual",          "vertex-insertion", "dual-truncation"};

/* ------------------------------------------------------------------------------ meshes */

typedef struct {
    size_t nv, nf, ni;
    double *p;
    uint32_t *off;
    uint32_t *idx;
} mesh;

static void mesh_free(mesh *m) {
    free(m->p);
    free(m->off);
    free(m->idx);
    m->p = NULL;
    m->off = NULL;
    m->idx = NULL;
}

/* A mesh from positions and faces given as a -1-terminated list of -1-terminated faces. */
static mesh mesh_make(const double *p, size_t nv, const int *faces) {
    mesh m;
    size_t k, nf = 0, ni = 0;
    for (k = 0; faces[k] != -2; k++) {
        if (faces[k] == -1)
            nf++;
        else
            ni++;
    }
    m.nv = nv;
    m.nf = nf;
    m.ni = ni;
    m.p = (double *)malloc(3 * nv * sizeof(double) + 1);
    m.off = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
    m.idx = (uint32_t *)malloc(ni * sizeof(uint32_t) + 1);
    memcpy(m.p, p, 3 * nv * sizeof(double));
    m.off[0] = 0;
    nf = 0;
    ni = 0;
    for (k = 0; faces[k] != -2; k++) {
        if (faces[k] == -1)
            m.off[++nf] = (uint32_t)ni;
        else
            m.idx[ni++] = (uint32_t)faces[k];
    }
    return m;
}

static mesh tetrahedron(void) {
    static const double p[] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
    static const int f[] = {0, 1, 2, -1, 0, 3, 1, -1, 0, 2, 3, -1, 1, 3, 2, -1, -2};
    return mesh_make(p, 4, f);
}

static mesh cube(void) {
    double p[24];
    int i;
    static const int f[] = {0, 2, 3, 1, -1, 4, 5, 7, 6, -1, 0, 1, 5, 4, -1, 2, 6, 7, 3, -1, 0, 4, 6, 2, -1, 1, 3, 7, 5, -1, -2};
    for (i = 0; i < 8; i++) {
        p[3 * i] = (i & 1) * 2.0 - 1.0;
        p[3 * i + 1] = ((i >> 1) & 1) * 2.0 - 1.0;
        p[3 * i + 2] = ((i >> 2) & 1) * 2.0 - 1.0;
    }
    return mesh_make(p, 8, f);
}

static mesh octahedron(void) {
    static const double p[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const int f[] = {0, 2, 4, -1, 2, 1, 4, -1, 1, 3, 4, -1, 3, 0, 4, -1, 2, 0, 5, -1,
                            1, 2, 5, -1, 3, 1, 5, -1, 0, 3, 5, -1, -2};
    return mesh_make(p, 6, f);
}

/* An m x n grid of quads (tri = 0) or of triangles (tri = 1) on z = 0, slightly bent. */
static mesh grid(int m, int n, int tri) {
    double p[3 * 64];
    int f[8 * 64];
    int i, j, k = 0;
    for (j = 0; j <= n; j++)
        for (i = 0; i <= m; i++) {
            double *q = p + 3 * (j * (m + 1) + i);
            q[0] = i + 0.1 * sin(1.7 * j + i);
            q[1] = j + 0.1 * cos(2.3 * i - j);
            q[2] = 0.05 * (i * i - j);
        }
    for (j = 0; j < n; j++)
        for (i = 0; i < m; i++) {
            int a = j * (m + 1) + i, b = a + 1, c = a + m + 2, d = a + m + 1;
            if (tri) {
                f[k++] = a; f[k++] = b; f[k++] = c; f[k++] = -1;
                f[k++] = a; f[k++] = c; f[k++] = d; f[k++] = -1;
            } else {
                f[k++] = a; f[k++] = b; f[k++] = c; f[k++] = d; f[k++] = -1;
            }
        }
    f[k] = -2;
    return mesh_make(p, (size_t)((m + 1) * (n + 1)), f);
}

/* A pyramid over a pentagon: one pentagon, five triangles, closed. */
static mesh pyramid(void) {
    double p[18];
    int k;
    static const int f[] = {4, 3, 2, 1, 0, -1, 0, 1, 5, -1, 1, 2, 5, -1, 2, 3, 5, -1, 3, 4, 5, -1, 4, 0, 5, -1, -2};
    for (k = 0; k < 5; k++) {
        p[3 * k] = cos(2.0 * 3.14159265358979323846 * k / 5.0);
        p[3 * k + 1] = sin(2.0 * 3.14159265358979323846 * k / 5.0);
        p[3 * k + 2] = 0.0;
    }
    p[15] = 0.1;
    p[16] = -0.05;
    p[17] = 1.2;
    return mesh_make(p, 6, f);
}

static void onto_unit_sphere(mesh *m) {
    size_t i;
    for (i = 0; i < m->nv; i++) {
        double *q = m->p + 3 * i;
        double r = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        q[0] /= r;
        q[1] /= r;
        q[2] /= r;
    }
}

/* Which meshes a scheme accepts: Loop/Butterfly triangles, Kobbelt quads, the others all. */
static int accepts(uint32_t scheme, int has_tri, int has_quad, int has_other) {
    if (scheme == NLS_SCHEME_LOOP || scheme == NLS_SCHEME_MODIFIED_BUTTERFLY) return !has_quad && !has_other;
    if (scheme == NLS_SCHEME_KOBBELT) return !has_tri && !has_other;
    return 1;
}

static int mesh_accepts(uint32_t scheme, const mesh *m) {
    int t = 0, q = 0, o = 0;
    size_t f;
    for (f = 0; f < m->nf; f++) {
        uint32_t d = m->off[f + 1] - m->off[f];
        if (d == 3)
            t = 1;
        else if (d == 4)
            q = 1;
        else
            o = 1;
    }
    return accepts(scheme, t, q, o);
}

static int is_interpolating(uint32_t s) {
    return s == NLS_SCHEME_MODIFIED_BUTTERFLY || s == NLS_SCHEME_KOBBELT || s == NLS_SCHEME_VERTEX_INSERTION;
}

/* ------------------------------------------------------------------------------ calls */

/* levels levels with exactly sized heap buffers (nls_mesh_plan_scratch_size, nls_plan,
 * nls_mesh_subdivide); the result in *out (freed by the caller). */
static nls_status subdivide_levels_el(uint32_t scheme, uint32_t flags, const mesh *m, uint32_t levels, mesh *out,
                                      nls_subdivide_report *rep, uint32_t *element) {
    size_t su0 = 0, su, sp, nv, nf, ni;
    uint32_t *scratch_u32;
    double *scratch_points;
    nls_plan plan;
    nls_mesh_sizes w = {777, 777, 777};
    nls_status s = flat_plan_scratch_size(m->nv, m->ni, &su0);
    out->p = NULL;
    out->off = NULL;
    out->idx = NULL;
    if (s != NLS_STATUS_OK) return s;
    scratch_u32 = (uint32_t *)malloc(su0 * sizeof(uint32_t) + 1);
    s = flat_plan(scheme, flags, levels, m->p, m->nv, m->off, m->nf, m->idx, m->ni, scratch_u32, su0, &plan, element);
    free(scratch_u32);
    if (s != NLS_STATUS_OK) return s;
    su = plan.scratch_u32;
    sp = plan.scratch_points;
    nv = plan.output.vertex_count;
    nf = plan.output.face_count;
    ni = plan.output.index_count;
    CHECK(su >= su0);
    scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t) + 1);
    scratch_points = sp ? (double *)malloc(3 * sp * sizeof(double)) : NULL;
    out->p = (double *)malloc(3 * nv * sizeof(double) + 1);
    out->off = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
    out->idx = (uint32_t *)malloc(ni * sizeof(uint32_t) + 1);
    s = flat_subdivide(scheme, flags, levels, m->p, m->nv, m->off, m->nf, m->idx, m->ni, scratch_u32, su,
                       scratch_points, sp, out->p, nv, out->off, nf, out->idx, ni, &w, rep, element);
    if (s == NLS_STATUS_OK) CHECK(w.vertex_count == nv && w.face_count == nf && w.index_count == ni);
    out->nv = w.vertex_count;
    out->nf = w.face_count;
    out->ni = w.index_count;
    free(scratch_u32);
    free(scratch_points);
    return s;
}

/* One level with exactly sized heap buffers; the result in *out (freed by the caller). */
static nls_status subdivide(uint32_t scheme, uint32_t flags, const mesh *m, mesh *out, nls_subdivide_report *rep,
                            uint32_t *element) {
    return subdivide_levels_el(scheme, flags, m, 1, out, rep, element);
}

/* Several levels in one call, exactly sized. */
static nls_status subdivide_levels(uint32_t scheme, uint32_t flags, const mesh *m, uint32_t levels, mesh *out,
                                   nls_subdivide_report *rep) {
    return subdivide_levels_el(scheme, flags, m, levels, out, rep, NULL);
}

/* Finite positions, monotonic offsets, indices in range; and the output passes the
 * library's own validation (a valid manifold polygon mesh). */
static int valid_output(const mesh *o) {
    size_t i, f;
    int ok = o->off[0] == 0 && o->off[o->nf] == o->ni;
    for (i = 0; i < 3 * o->nv; i++) ok = ok && isfinite(o->p[i]);
    for (f = 0; f < o->nf; f++) ok = ok && o->off[f + 1] >= o->off[f] + 3;
    for (i = 0; i < o->ni; i++) ok = ok && o->idx[i] < o->nv;
    if (ok) {
        size_t su = 0;
        uint32_t *scratch;
        nls_plan plan;
        ok = flat_plan_scratch_size(o->nv, o->ni, &su) == NLS_STATUS_OK;
        scratch = (uint32_t *)malloc(su * sizeof(uint32_t) + 1);
        ok = ok && flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, o->p, o->nv, o->off, o->nf, o->idx, o->ni, scratch, su,
                             &plan, NULL) == NLS_STATUS_OK;
        free(scratch);
    }
    return ok;
}

static double sphere_deviation(const mesh *o) {
    size_t i;
    double worst = 0.0;
    for (i = 0; i < o->nv; i++) {
        const double *q = o->p + 3 * i;
        double d = fabs(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - 1.0);
        if (!(d <= worst)) worst = d;
    }
    return worst;
}

/* ------------------------------------------------------------------------------ tests */

static void test_constants(void) {
    CHECK(NLS_SCHEME_LOOP == 0 && NLS_SCHEME_DUAL_TRUNCATION == 8);
    CHECK(NLS_SUBDIVIDE_MOBIUS == 1u && NLS_SUBDIVIDE_STRICT == 2u && NLS_SUBDIVIDE_LITERAL == 4u);
    CHECK(NLS_NO_ELEMENT == UINT32_MAX);
    {
        nls_subdivide_report r;
        nls_subdivide_options o = {777, 777, 777, 777.0, NULL, NULL};
        CHECK(sizeof r == 6 * sizeof(uint32_t));
        CHECK_STATUS(nls_subdivide_default_options(&o), NLS_STATUS_OK);
        CHECK(o.scheme == NLS_SCHEME_LOOP && o.flags == 0 && o.levels == 1 && o.linear_weight == 0.0);
        CHECK_STATUS(nls_subdivide_default_options(NULL), NLS_STATUS_NULL_PARAMETER);
    }
}

static void test_every_scheme(void) {
    mesh meshes[5];
    const char *names[5] = {"tetrahedron", "cube", "quad grid", "triangle grid", "pentagon pyramid"};
    int mi, si, mob, runs = 0;
    meshes[0] = tetrahedron();
    meshes[1] = cube();
    meshes[2] = grid(3, 2, 0);
    meshes[3] = grid(3, 2, 1);
    meshes[4] = pyramid();
    for (mi = 0; mi < 5; mi++) {
        const mesh *m = &meshes[mi];
        for (si = 0; si < NSCHEMES; si++) {
            for (mob = 0; mob <= 1; mob++) {
                const uint32_t flags = mob ? NLS_SUBDIVIDE_MOBIUS : 0u;
                mesh o;
                nls_subdivide_report rep = {777, 777, 777, 777, 777, 777};
                uint32_t element = 12345;
                nls_status s = subdivide(SCHEMES[si], flags, m, &o, &rep, &element);
                if (mesh_accepts(SCHEMES[si], m)) {
                    if (s != NLS_STATUS_OK)
                        fprintf(stderr, "%s %s%s: %s (element %u)\n", names[mi], mob ? "mobius-" : "", NAMES[si],
                                nls_status_str(s), element);
                    CHECK(s == NLS_STATUS_OK);
                    CHECK(element == 12345); /* written on failure only */
                    if (s == NLS_STATUS_OK) {
                        runs++;
                        CHECK(valid_output(&o));
                        CHECK(rep.fallbacks == 0 && rep.first_fallback == NLS_NO_ELEMENT &&
                              rep.first_fallback_level == 0);
                        if (is_interpolating(SCHEMES[si])) {
                            CHECK(memcmp(o.p, m->p, 3 * m->nv * sizeof(double)) == 0);
                        }
                    }
                } else {
                    CHECK(s == NLS_STATUS_UNSUPPORTED_FACE_TYPE);
                    CHECK(element < m->nf);
                    CHECK(rep.fallbacks == 777);
                }
                mesh_free(&o);
            }
        }
    }
    printf("test_mesh: %d scheme runs on the five meshes\n", runs);
    CHECK(runs >= 70);
    for (mi = 0; mi < 5; mi++) mesh_free(&meshes[mi]);
}

static void test_spheres(void) {
    mesh c = cube(), oct = octahedron();
    int si;
    double worst = 0.0;
    onto_unit_sphere(&c);
    for (si = 0; si < NSCHEMES; si++) {
        const mesh *m = mesh_accepts(SCHEMES[si], &c) ? &c : &oct;
        mesh o, o2;
        nls_subdivide_report rep;
        double d;
        CHECK_STATUS(subdivide(SCHEMES[si], NLS_SUBDIVIDE_MOBIUS, m, &o, &rep, NULL), NLS_STATUS_OK);
        d = sphere_deviation(&o);
        if (d > worst) worst = d;
        CHECK(d < 1e-12);
        /* two levels in one call equal two single levels, bit for bit */
        CHECK_STATUS(subdivide_levels(SCHEMES[si], NLS_SUBDIVIDE_MOBIUS, m, 2, &o2, &rep), NLS_STATUS_OK);
        {
            mesh o1b;
            nls_subdivide_report rep1;
            CHECK_STATUS(subdivide(SCHEMES[si], NLS_SUBDIVIDE_MOBIUS, &o, &o1b, &rep1, NULL), NLS_STATUS_OK);
            CHECK(o1b.nv == o2.nv && o1b.nf == o2.nf && o1b.ni == o2.ni);
            CHECK(memcmp(o1b.p, o2.p, 3 * o2.nv * sizeof(double)) == 0);
            CHECK(memcmp(o1b.off, o2.off, (o2.nf + 1) * sizeof(uint32_t)) == 0);
            CHECK(memcmp(o1b.idx, o2.idx, o2.ni * sizeof(uint32_t)) == 0);
            mesh_free(&o1b);
        }
        d = sphere_deviation(&o2);
        if (d > worst) worst = d;
        CHECK(d < 1e-12);
        CHECK(rep.fallbacks == 0 && rep.first_fallback_level == 0);
        mesh_free(&o);
        mesh_free(&o2);
    }
    printf("test_mesh: worst distance from the unit sphere (Möbius, 1 and 2 levels) %.2e\n", worst);
    /* the linear schemes leave the sphere */
    {
        mesh o;
        CHECK_STATUS(subdivide(NLS_SCHEME_CATMULL_CLARK, 0, &c, &o, NULL, NULL), NLS_STATUS_OK);
        CHECK(sphere_deviation(&o) > 1e-3);
        mesh_free(&o);
    }
    /* zero levels copy the mesh */
    {
        mesh o;
        CHECK_STATUS(subdivide_levels(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, &oct, 0, &o, NULL), NLS_STATUS_OK);
        CHECK(o.nv == oct.nv && memcmp(o.p, oct.p, 3 * oct.nv * sizeof(double)) == 0);
        CHECK(o.ni == oct.ni && memcmp(o.idx, oct.idx, oct.ni * sizeof(uint32_t)) == 0);
        mesh_free(&o);
    }
    mesh_free(&c);
    mesh_free(&oct);
}

static void test_levels_linear(void) {
    mesh g = grid(3, 2, 1), o1, o2, o3;
    CHECK_STATUS(subdivide(NLS_SCHEME_LOOP, 0, &g, &o1, NULL, NULL), NLS_STATUS_OK);
    CHECK_STATUS(subdivide(NLS_SCHEME_LOOP, 0, &o1, &o2, NULL, NULL), NLS_STATUS_OK);
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_LOOP, 0, &g, 2, &o3, NULL), NLS_STATUS_OK);
    CHECK(o2.nv == o3.nv && memcmp(o2.p, o3.p, 3 * o2.nv * sizeof(double)) == 0);
    CHECK(o2.ni == o3.ni && memcmp(o2.idx, o3.idx, o2.ni * sizeof(uint32_t)) == 0);
    CHECK(valid_output(&o3));
    mesh_free(&o1);
    mesh_free(&o2);
    mesh_free(&o3);
    {
        nls_plan plan = {{777, 777, 777}, 777, 777};
        uint32_t scratch[256], element = 0;
        CHECK_STATUS(flat_plan(NLS_SCHEME_LOOP, 0, NLS_MAX_LEVELS + 1, g.p, g.nv, g.off, g.nf, g.idx, g.ni, scratch, 256,
                               &plan, &element),
                     NLS_STATUS_INVALID_ARGUMENT);
        CHECK_STATUS(flat_plan(NLS_SCHEME_LOOP, 0, NLS_MAX_LEVELS, g.p, g.nv, g.off, g.nf, g.idx, g.ni, scratch, 256,
                               &plan, &element),
                     NLS_STATUS_SIZE_OVERFLOW);
        CHECK(plan.output.vertex_count == 777 && plan.scratch_u32 == 777);
        CHECK_STATUS(flat_plan(NLS_SCHEME_LOOP, 0, 3, g.p, g.nv, g.off, g.nf, g.idx, g.ni, scratch, 256, &plan, &element),
                     NLS_STATUS_OK);
        CHECK(plan.output.face_count == g.nf * 64 && plan.output.index_count == 3 * plan.output.face_count &&
              plan.scratch_points > 0 && plan.scratch_u32 > 0);
    }
    mesh_free(&g);
}

/* ------------------------------------------------------------------------------ bad input */

/* Runs nls_plan (one level) on a mesh given by arrays; returns the status, *element. */
static nls_status size_of(const double *p, size_t nv, const uint32_t *off, size_t nf, const uint32_t *idx, size_t ni,
                          uint32_t scheme, uint32_t *element) {
    uint32_t scratch[512];
    nls_plan plan = {{777, 777, 777}, 777, 777};
    nls_status s;
    *element = 12345;
    s = flat_plan(scheme, 0, 1, p, nv, off, nf, idx, ni, scratch, 512, &plan, element);
    if (s != NLS_STATUS_OK) CHECK(plan.output.vertex_count == 777 && plan.output.face_count == 777 && plan.scratch_u32 == 777);
    return s;
}

/* The build's capacities (nls_max_valence, nls_max_face_size; 128 unless the library was
   built with NLSUBDIV_MAX_VALENCE / NLSUBDIV_MAX_FACE_SIZE): one polygon of exactly the face
   cap validates, one more corner is VALENCE_TOO_HIGH naming the face; a Catmull-Clark level
   of it makes a face point of that valence, refused by the plan (no element) when it is
   above the valence cap. */
static void test_capacities(void) {
    uint32_t vcap = nls_max_valence(), fcap = nls_max_face_size(), e, n;
    CHECK(vcap >= 8 && vcap <= 4096 && fcap >= 8 && fcap <= 4096);
    for (n = fcap; n <= fcap + 1; n++) {
        double *p = malloc(3 * (size_t)n * sizeof(double));
        uint32_t *idx = malloc((size_t)n * sizeof(uint32_t)), off[2] = {0, 0};
        size_t need = 0;
        uint32_t *su;
        uint32_t k;
        nls_plan plan;
        nls_status s;
        CHECK(p != NULL && idx != NULL);
        if (p == NULL || idx == NULL) return;
        for (k = 0; k < n; k++) {
            double t = 2.0 * 3.141592653589793 * k / n;
            p[3 * k] = cos(t);
            p[3 * k + 1] = sin(t);
            p[3 * k + 2] = 0.0;
            idx[k] = k;
        }
        off[1] = n;
        CHECK_STATUS(flat_plan_scratch_size(n, n, &need), NLS_STATUS_OK);
        su = malloc(need * sizeof(uint32_t));
        CHECK(su != NULL);
        if (su == NULL) return;
        e = 12345;
        s = flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 0, p, n, off, 1, idx, n, su, need, &plan, &e);
        if (n == fcap) {
            CHECK_STATUS(s, NLS_STATUS_OK);
            e = 12345;
            s = flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, p, n, off, 1, idx, n, su, need, &plan, &e);
            if (n <= vcap) {
                CHECK_STATUS(s, NLS_STATUS_OK);
            } else {
                CHECK_STATUS(s, NLS_STATUS_VALENCE_TOO_HIGH);
                CHECK(e == NLS_NO_ELEMENT);
            }
        } else {
            CHECK_STATUS(s, NLS_STATUS_VALENCE_TOO_HIGH);
            CHECK(e == 0);
        }
        free(su);
        free(idx);
        free(p);
    }
}

static void test_bad_meshes(void) {
    double p[3 * 6];
    uint32_t e;
    int k;
    for (k = 0; k < 18; k++) p[k] = sin(1.3 * k) + 0.1 * k;
    {   /* out-of-range index */
        const uint32_t off[] = {0, 3, 6}, idx[] = {0, 1, 2, 2, 1, 6};
        CHECK_STATUS(size_of(p, 6, off, 2, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_INDEX_OUT_OF_RANGE);
        CHECK(e == 1);
    }
    {   /* face with two vertices */
        const uint32_t off[] = {0, 3, 5}, idx[] = {0, 1, 2, 2, 1};
        CHECK_STATUS(size_of(p, 6, off, 2, idx, 5, NLS_SCHEME_CATMULL_CLARK, &e), NLS_STATUS_FACE_TOO_SMALL);
        CHECK(e == 1);
    }
    {   /* repeated vertex */
        const uint32_t off[] = {0, 3, 7}, idx[] = {0, 1, 2, 2, 1, 3, 1};
        CHECK_STATUS(size_of(p, 6, off, 2, idx, 7, NLS_SCHEME_CATMULL_CLARK, &e), NLS_STATUS_REPEATED_VERTEX);
        CHECK(e == 1);
    }
    {   /* non-manifold edge: three triangles on the edge 0-1 */
        const uint32_t off[] = {0, 3, 6, 9}, idx[] = {0, 1, 2, 1, 0, 3, 1, 0, 4};
        CHECK_STATUS(size_of(p, 6, off, 3, idx, 9, NLS_SCHEME_LOOP, &e), NLS_STATUS_NON_MANIFOLD_EDGE);
        CHECK(e == 2);
    }
    {   /* bow-tie: two triangles sharing only vertex 0 */
        const uint32_t off[] = {0, 3, 6}, idx[] = {0, 1, 2, 0, 3, 4};
        CHECK_STATUS(size_of(p, 6, off, 2, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_NON_MANIFOLD_VERTEX);
        CHECK(e == 0);
    }
    {   /* inconsistent orientation: both triangles run 0 -> 1 */
        const uint32_t off[] = {0, 3, 6}, idx[] = {0, 1, 2, 0, 1, 3};
        CHECK_STATUS(size_of(p, 6, off, 2, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_INCONSISTENT_ORIENTATION);
        CHECK(e == 1);
    }
    {   /* duplicate face (the same triangle in both orientations) */
        const uint32_t off[] = {0, 3, 6, 9}, idx[] = {0, 1, 2, 2, 1, 0, 1, 3, 2};
        CHECK_STATUS(size_of(p, 6, off, 3, idx, 9, NLS_SCHEME_LOOP, &e), NLS_STATUS_DUPLICATE_FACE);
    }
    {   /* NaN and infinite coordinates name the vertex */
        const uint32_t off[] = {0, 3, 6}, idx[] = {0, 1, 2, 2, 1, 3};
        double q[3 * 6];
        memcpy(q, p, sizeof q);
        q[3 * 3 + 2] = NAN;
        CHECK_STATUS(size_of(q, 6, off, 2, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_NON_FINITE_INPUT);
        CHECK(e == 3);
        q[3 * 3 + 2] = 0.0;
        q[3 * 5] = -INFINITY; /* unreferenced vertices are checked too */
        CHECK_STATUS(size_of(q, 6, off, 2, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_NON_FINITE_INPUT);
        CHECK(e == 5);
    }
    {   /* bad offsets: not starting at 0, decreasing, not ending at the index count */
        const uint32_t idx[] = {0, 1, 2, 2, 1, 3};
        const uint32_t o1[] = {1, 3, 6}, o2[] = {0, 4, 3, 6}, o3[] = {0, 3, 5};
        CHECK_STATUS(size_of(p, 6, o1, 2, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_BAD_OFFSETS);
        CHECK_STATUS(size_of(p, 6, o2, 3, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_BAD_OFFSETS);
        CHECK(e == 1);
        CHECK_STATUS(size_of(p, 6, o3, 2, idx, 6, NLS_SCHEME_LOOP, &e), NLS_STATUS_BAD_OFFSETS);
    }
    {   /* a quad for Loop, a triangle for Kobbelt */
        const uint32_t off[] = {0, 3, 7}, idx[] = {0, 1, 2, 2, 1, 3, 4};
        CHECK_STATUS(size_of(p, 6, off, 2, idx, 7, NLS_SCHEME_LOOP, &e), NLS_STATUS_UNSUPPORTED_FACE_TYPE);
        CHECK(e == 1);
        CHECK_STATUS(size_of(p, 6, off, 2, idx, 7, NLS_SCHEME_KOBBELT, &e), NLS_STATUS_UNSUPPORTED_FACE_TYPE);
        CHECK(e == 0);
    }
    {   /* the empty mesh is valid: vertices carried through, no faces */
        const uint32_t off[] = {0};
        nls_plan plan = {{0, 7, 7}, 7, 7};
        uint32_t scratch[32];
        CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, p, 2, off, 0, NULL, 0, scratch, 32, &plan, NULL),
                     NLS_STATUS_OK);
        CHECK(plan.output.vertex_count == 2 && plan.output.face_count == 0 && plan.output.index_count == 0);
        CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, NULL, 0, off, 0, NULL, 0, NULL, 0, &plan, NULL),
                     NLS_STATUS_OK);
        CHECK(plan.output.vertex_count == 0 && plan.output.face_count == 0 && plan.output.index_count == 0);
    }
}

/* Fixture for the pointer tests: the pyramid and buffers big enough for one level. */
typedef struct {
    mesh m;
    uint32_t su[512];
    double sp[3 * 128];
    double op[3 * 128];
    uint32_t oo[128];
    uint32_t oi[512];
    nls_mesh_sizes sz;
    nls_subdivide_report rep;
    uint32_t element;
} fixture;

static nls_status call(fixture *x, uint32_t scheme, uint32_t flags) {
    x->element = 12345;
    return flat_subdivide(scheme, flags, 1, x->m.p, x->m.nv, x->m.off, x->m.nf, x->m.idx, x->m.ni, x->su, 512, x->sp, 128,
                          x->op, 128, x->oo, 127, x->oi, 512, &x->sz, &x->rep, &x->element);
}

static void test_bad_arguments(void) {
    static fixture x;
    x.m = pyramid();
    x.sz.vertex_count = x.sz.face_count = x.sz.index_count = 777;
    x.rep.fallbacks = 777;
#define CALL(...) flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, 1, __VA_ARGS__, &x.rep, &x.element)
#define MESH x.m.p, x.m.nv, x.m.off, x.m.nf, x.m.idx, x.m.ni
#define SCR x.su, 512, x.sp, 128
#define OUT x.op, 128, x.oo, 127, x.oi, 512
#define CNT &x.sz
    /* unknown scheme codes and flag bits, too many levels */
    CHECK_STATUS(call(&x, NLS_SCHEME_SPHERELIKE + 1u, 0), NLS_STATUS_INVALID_ARGUMENT);
    CHECK(x.element == NLS_NO_ELEMENT);
    CHECK_STATUS(call(&x, UINT32_MAX, 0), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(call(&x, NLS_SCHEME_CATMULL_CLARK, 1u << 3), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(call(&x, NLS_SCHEME_CATMULL_CLARK, 0x80000000u | NLS_SUBDIVIDE_MOBIUS), NLS_STATUS_INVALID_ARGUMENT);
    {
        size_t su = 777;
        nls_plan plan = {{777, 777, 777}, 777, 777};
        nls_mesh_view v = flat_view(x.m.p, x.m.nv, x.m.off, x.m.nf, x.m.idx, x.m.ni);
        CHECK_STATUS(flat_plan(NLS_SCHEME_SPHERELIKE + 1u, 0, 1, MESH, x.su, 512, &plan, NULL),
                     NLS_STATUS_INVALID_ARGUMENT);
        CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 8u, 1, MESH, x.su, 512, &plan, NULL),
                     NLS_STATUS_INVALID_ARGUMENT);
        CHECK_STATUS(flat_plan(NLS_SCHEME_SPHERELIKE, NLS_SUBDIVIDE_MOBIUS, 1, MESH, x.su, 512, &plan, NULL),
                     NLS_STATUS_INVALID_ARGUMENT);
        CHECK(plan.scratch_u32 == 777 && plan.scratch_points == 777);
        /* the pyramid: 6 vertices, 20 corners; Möbius: two candidates per corner, per
         * vertex the kept canonical form's centre (6 points), then the fold guard's trust
         * and the form's radius per vertex, the candidates' slot per corner and the guard's
         * F4-angle term per edge (room for one per corner), three values to a point
         * (ceil(52 / 3) = 18 points); the star workspace: four arrays of
         * the largest valence (the apex's, 5) for each chunk, at most one per vertex (6);
         * u32: the topology (su) and the spoke workspace, four entries per spoke of the
         * largest valence for each chunk */
        CHECK_STATUS(nls_mesh_plan_scratch_size(&v, &su), NLS_STATUS_OK);
        CHECK(su == 4 * 20 + 3 * 6);
        CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 1, MESH, x.su, su, &plan, NULL),
                     NLS_STATUS_OK);
        CHECK(plan.scratch_u32 == su + 4 * 5 * 6 && plan.scratch_points == 40 + 6 + 18 + 4 * 5 * 6);
        CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_STRICT, 1, MESH, x.su, su, &plan, NULL),
                     NLS_STATUS_OK);
        CHECK(plan.scratch_points == 0);
        CHECK_STATUS(flat_plan_scratch_size(SIZE_MAX / 2, 20, &su), NLS_STATUS_SIZE_OVERFLOW);
        CHECK_STATUS(flat_plan_scratch_size(6, SIZE_MAX / 2, &su), NLS_STATUS_SIZE_OVERFLOW);
        CHECK_STATUS(flat_plan_scratch_size((size_t)UINT32_MAX, 3, &su), NLS_STATUS_SIZE_OVERFLOW);
        CHECK_STATUS(nls_mesh_plan_scratch_size(&v, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_plan_scratch_size(NULL, &su), NLS_STATUS_NULL_PARAMETER);
        v.positions_stride = 20;
        CHECK_STATUS(nls_mesh_plan_scratch_size(&v, &su), NLS_STATUS_INVALID_ARGUMENT);
    }
    /* the strict flag is accepted by the linear schemes (which never fall back) */
    CHECK_STATUS(call(&x, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_STRICT), NLS_STATUS_OK);
    CHECK(x.sz.vertex_count == 6 + 10 + 6 && x.sz.face_count == 20 && x.sz.index_count == 80);
    CHECK(x.rep.fallbacks == 0 && x.rep.first_fallback == NLS_NO_ELEMENT && x.element == 12345);
    x.sz.vertex_count = x.sz.face_count = x.sz.index_count = 777;
    x.rep.fallbacks = 777;
    CHECK_STATUS(flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, NLS_MAX_LEVELS + 1, MESH, SCR, OUT, CNT, &x.rep,
                                &x.element),
                 NLS_STATUS_INVALID_ARGUMENT);
    CHECK(x.element == NLS_NO_ELEMENT);
    /* NULL structs */
    {
        nls_mesh_view v = flat_view(MESH);
        nls_subdivide_options o = flat_options(NLS_SCHEME_CATMULL_CLARK, 0, 1);
        nls_scratch sc = flat_scratch(SCR);
        nls_mesh_buffers b = flat_buffers(OUT);
        nls_plan plan;
        CHECK_STATUS(nls_mesh_subdivide(NULL, &o, &sc, &b, &x.sz, NULL, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_subdivide(&v, NULL, &sc, &b, &x.sz, NULL, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_subdivide(&v, &o, NULL, &b, &x.sz, NULL, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_subdivide(&v, &o, &sc, NULL, &x.sz, NULL, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_plan(NULL, &o, x.su, 512, &plan, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_plan(&v, NULL, x.su, 512, &plan, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_plan(&v, &o, x.su, 512, NULL, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_mesh_plan(&v, &o, NULL, 512, &plan, NULL), NLS_STATUS_NULL_PARAMETER);
        CHECK(x.sz.vertex_count == 777);
    }
    /* NULL with a non-zero count */
    CHECK_STATUS(CALL(NULL, 6, x.m.off, 6, x.m.idx, 20, SCR, OUT, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(x.m.p, 6, NULL, 6, x.m.idx, 20, SCR, OUT, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(x.m.p, 6, NULL, 0, x.m.idx, 0, SCR, OUT, CNT), NLS_STATUS_NULL_PARAMETER); /* offsets[1] */
    CHECK_STATUS(CALL(x.m.p, 6, x.m.off, 6, NULL, 20, SCR, OUT, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(MESH, NULL, 512, x.sp, 128, OUT, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(MESH, x.su, 512, NULL, 128, OUT, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(MESH, SCR, NULL, 128, x.oo, 127, x.oi, 512, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(MESH, SCR, x.op, 128, NULL, 0, x.oi, 512, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(MESH, SCR, x.op, 128, x.oo, 127, NULL, 512, CNT), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(CALL(MESH, SCR, OUT, NULL), NLS_STATUS_NULL_PARAMETER);
    /* NULL point scratch with capacity 0 is fine for a linear scheme */
    CHECK_STATUS(CALL(MESH, x.su, 512, NULL, 0, OUT, CNT), NLS_STATUS_OK);
    x.sz.vertex_count = x.sz.face_count = x.sz.index_count = 777;
    /* misaligned pointers */
    {
        union {
            double d[3 * 8];
            unsigned char c[sizeof(double) * 3 * 8];
        } raw; /* aligned for double, so c + 1 is aligned for neither double nor uint32_t */
        double *mis = (double *)(void *)(raw.c + 1);
        uint32_t *mis32 = (uint32_t *)(void *)(raw.c + 1);
        nls_mesh_sizes *miss = (nls_mesh_sizes *)(void *)(raw.c + 1);
        CHECK_STATUS(CALL(mis, 6, x.m.off, 6, x.m.idx, 20, SCR, OUT, CNT), NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(CALL(x.m.p, 6, mis32, 6, x.m.idx, 20, SCR, OUT, CNT), NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(CALL(x.m.p, 6, x.m.off, 6, mis32, 20, SCR, OUT, CNT), NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(CALL(MESH, mis32, 16, x.sp, 128, OUT, CNT), NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(CALL(MESH, x.su, 512, mis, 1, OUT, CNT), NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(CALL(MESH, SCR, mis, 1, x.oo, 127, x.oi, 512, CNT), NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(CALL(MESH, SCR, OUT, miss), NLS_STATUS_MISALIGNED_POINTER);
        x.element = 12345;
        CHECK_STATUS(flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, 1, MESH, SCR, OUT, CNT,
                                    (nls_subdivide_report *)(void *)(raw.c + 1), &x.element),
                     NLS_STATUS_MISALIGNED_POINTER);
        CHECK(x.element == NLS_NO_ELEMENT);
        CHECK_STATUS(flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, 1, MESH, SCR, OUT, CNT, &x.rep, mis32),
                     NLS_STATUS_MISALIGNED_POINTER);
    }
    /* SIZE_MAX/2 counts and capacities */
    CHECK_STATUS(CALL(x.m.p, SIZE_MAX / 2, x.m.off, 6, x.m.idx, 20, SCR, OUT, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(x.m.p, 6, x.m.off, SIZE_MAX / 2, x.m.idx, 20, SCR, OUT, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(x.m.p, 6, x.m.off, SIZE_MAX, x.m.idx, 20, SCR, OUT, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(x.m.p, 6, x.m.off, 6, x.m.idx, SIZE_MAX / 2, SCR, OUT, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(MESH, x.su, SIZE_MAX / 2, x.sp, 128, OUT, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(MESH, x.su, 512, x.sp, SIZE_MAX / 2, OUT, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(MESH, SCR, x.op, SIZE_MAX / 2, x.oo, 127, x.oi, 512, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(MESH, SCR, x.op, 128, x.oo, SIZE_MAX / 2, x.oi, 512, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(MESH, SCR, x.op, 128, x.oo, SIZE_MAX, x.oi, 512, CNT), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(CALL(MESH, SCR, x.op, 128, x.oo, 127, x.oi, SIZE_MAX / 2, CNT), NLS_STATUS_SIZE_OVERFLOW);
    {
        nls_plan plan = {{777, 777, 777}, 777, 777};
        CHECK_STATUS(flat_plan(NLS_SCHEME_LOOP, 0, 1, x.m.p, SIZE_MAX / 2, x.m.off, 6, x.m.idx, 20, x.su, 512, &plan,
                               NULL),
                     NLS_STATUS_SIZE_OVERFLOW);
        CHECK(plan.output.vertex_count == 777);
    }
    /* aliasing: every output and scratch against the inputs and each other */
    {
        double *pbuf = (double *)malloc(3 * 200 * sizeof(double));
        uint32_t *ubuf = (uint32_t *)malloc(2000 * sizeof(uint32_t));
        double *pin = pbuf + 3 * 150;
        uint32_t *oin = ubuf + 1000, *iin = ubuf + 1100;
        memcpy(pin, x.m.p, 3 * 6 * sizeof(double));
        memcpy(oin, x.m.off, 7 * sizeof(uint32_t));
        memcpy(iin, x.m.idx, 20 * sizeof(uint32_t));
#define AMESH pin, 6, oin, 6, iin, 20
        /* out_positions over the input positions (first and last point) */
        CHECK_STATUS(CALL(AMESH, SCR, pin + 3 * 5, 22, x.oo, 127, x.oi, 512, CNT), NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(CALL(AMESH, SCR, pbuf + 3 * 129, 22, x.oo, 127, x.oi, 512, CNT), NLS_STATUS_ALIASING_BUFFERS);
        /* out_indices over the input indices, out_offsets over the input offsets */
        CHECK_STATUS(CALL(AMESH, SCR, x.op, 128, x.oo, 127, ubuf + 1110, 80, CNT), NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(CALL(AMESH, SCR, x.op, 128, ubuf + 990, 20, x.oi, 512, CNT), NLS_STATUS_ALIASING_BUFFERS);
        /* scratch over an input, scratch over an output, two outputs */
        CHECK_STATUS(CALL(AMESH, ubuf + 1090, 200, x.sp, 128, OUT, CNT), NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(CALL(AMESH, x.su, 512, pin - 3 * 10, 11, OUT, CNT), NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(CALL(AMESH, ubuf, 200, x.sp, 128, x.op, 128, ubuf + 199, 20, x.oi, 512, CNT),
                     NLS_STATUS_ALIASING_BUFFERS);
        /* out_offsets holds out_face_capacity + 1 = 21 entries: adjacent is fine, one less is not */
        CHECK_STATUS(CALL(AMESH, SCR, x.op, 128, ubuf, 20, ubuf + 21, 80, CNT), NLS_STATUS_OK);
        CHECK(x.sz.vertex_count == 22 && x.sz.face_count == 20 && x.sz.index_count == 80);
        CHECK_STATUS(CALL(AMESH, SCR, x.op, 128, ubuf, 20, ubuf + 20, 80, CNT), NLS_STATUS_ALIASING_BUFFERS);
        /* the input mesh right after the outputs */
        CHECK_STATUS(CALL(AMESH, SCR, pin - 3 * 22, 22, x.oo, 127, x.oi, 512, CNT), NLS_STATUS_OK);
        {   /* the size query's scratch over the mesh */
            nls_plan plan;
            CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, ubuf + 1106, 200, &plan, NULL),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, ubuf, 200, &plan, NULL), NLS_STATUS_OK);
            /* the plan itself, or out_element, inside the mesh or the scratch */
            CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, ubuf, 200, (nls_plan *)(void *)(pin + 3),
                                   NULL),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, ubuf, 200, (nls_plan *)(void *)(ubuf + 8),
                                   NULL),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK_STATUS(flat_plan(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, ubuf, 200, &plan, iin + 4),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK(iin[4] == x.m.idx[4]); /* not written */
        }
        /* every out-pointer into every buffer of the call: refused before anything is written */
        {
            double *op = (double *)malloc(3 * 128 * sizeof(double));
            uint32_t *sc = ubuf + 1200, *oo = ubuf + 1400, *oi = ubuf + 1600;
            size_t k;
            int which;
            for (which = 0; which < 3; which++) {
                void *into[6];
                into[0] = pin + 3;     /* input positions */
                into[1] = iin + 2;     /* input indices */
                into[2] = sc + 2;      /* u32 scratch */
                into[3] = op + 6;      /* output positions: the case that used to corrupt the output */
                into[4] = oo + 2;      /* output offsets */
                into[5] = oi + 10;     /* output indices */
                for (k = 0; k < 6; k++) {
                    nls_mesh_sizes *sz = which == 0 ? (nls_mesh_sizes *)into[k] : &x.sz;
                    nls_subdivide_report *r = which == 1 ? (nls_subdivide_report *)into[k] : &x.rep;
                    uint32_t *el = which == 2 ? (uint32_t *)into[k] : &x.element;
                    uint32_t saved_in = iin[2];
                    size_t q;
                    for (q = 0; q < 3 * 128; q++) op[q] = 0.25;
                    x.element = 12345;
                    CHECK_STATUS(flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, sc, 200, NULL, 0, op, 128, oo, 21,
                                                oi, 80, sz, r, el),
                                 NLS_STATUS_ALIASING_BUFFERS);
                    CHECK(op[6] == 0.25 && op[7] == 0.25 && iin[2] == saved_in);
                    if (which != 2) CHECK(x.element == NLS_NO_ELEMENT);
                }
            }
            /* two out-pointers on each other */
            CHECK_STATUS(flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, sc, 200, NULL, 0, op, 128, oo, 21, oi, 80,
                                        &x.sz, (nls_subdivide_report *)(void *)&x.sz, &x.element),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK_STATUS(flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, sc, 200, NULL, 0, op, 128, oo, 21, oi, 80,
                                        &x.sz, &x.rep, (uint32_t *)(void *)&x.rep),
                         NLS_STATUS_ALIASING_BUFFERS);
            /* and the same buffers with out-pointers of their own: fine */
            CHECK_STATUS(flat_subdivide(NLS_SCHEME_CATMULL_CLARK, 0, 1, AMESH, sc, 200, NULL, 0, op, 128, oo, 21, oi, 80,
                                        &x.sz, &x.rep, &x.element),
                         NLS_STATUS_OK);
            CHECK(x.sz.vertex_count == 22);
            free(op);
        }
        free(pbuf);
        free(ubuf);
#undef AMESH
    }
    x.sz.vertex_count = x.sz.face_count = x.sz.index_count = 777;
    CHECK_STATUS(CALL(MESH, SCR, x.op, 128, x.oo, 127, x.oi, 512, CNT), NLS_STATUS_OK);
    CHECK(x.sz.face_count == 20);
#undef CALL
#undef MESH
#undef SCR
#undef OUT
#undef CNT
    mesh_free(&x.m);
}

/* out_element on failures found before the out-pointer check (a NULL or misaligned argument
 * struct, a bad stride). It is written (NLS_NO_ELEMENT) only when the call can name every
 * caller buffer and out_element lies in none of them; otherwise it keeps the caller's value,
 * and no caller buffer is ever written. */
static void test_early_failure_element(void) {
    static fixture x;
    union {
        double d[16];
        unsigned char c[sizeof(double) * 16];
    } raw;
    nls_mesh_view v, *misview = (nls_mesh_view *)(void *)(raw.c + 1);
    nls_subdivide_options o = flat_options(NLS_SCHEME_CATMULL_CLARK, 0, 1);
    nls_scratch s;
    nls_mesh_buffers b;
    nls_plan plan;
    uint32_t *into_out = (uint32_t *)(void *)(x.op + 6); /* inside the output positions */
    size_t q;
    x.m = pyramid();
    v = flat_view(x.m.p, x.m.nv, x.m.off, x.m.nf, x.m.idx, x.m.ni);
    s = flat_scratch(x.su, 512, x.sp, 128);
    b = flat_buffers(x.op, 128, x.oo, 127, x.oi, 512);
#define RESET()                                                \
    do {                                                       \
        for (q = 0; q < 3 * 128; q++) x.op[q] = 0.25;          \
        x.element = 12345;                                     \
    } while (0)
#define UNTOUCHED() CHECK(x.op[6] == 0.25 && x.op[7] == 0.25 && x.element == 12345)
    /* NULL view: no input buffer, so the call knows every buffer and a separate out_element
     * receives NLS_NO_ELEMENT; one inside the output positions is not written */
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(NULL, &o, &s, &b, &x.sz, &x.rep, &x.element), NLS_STATUS_NULL_PARAMETER);
    CHECK(x.element == NLS_NO_ELEMENT);
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(NULL, &o, &s, &b, &x.sz, &x.rep, into_out), NLS_STATUS_NULL_PARAMETER);
    UNTOUCHED();
    /* NULL options, NULL scratch struct, NULL output struct: out_element into the input
     * indices, the output indices, the u32 scratch */
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(&v, NULL, &s, &b, &x.sz, &x.rep, into_out), NLS_STATUS_NULL_PARAMETER);
    UNTOUCHED();
    {
        uint32_t saved = x.m.idx[3];
        RESET();
        CHECK_STATUS(nls_mesh_subdivide(&v, &o, NULL, &b, &x.sz, &x.rep, (uint32_t *)&x.m.idx[3]),
                     NLS_STATUS_NULL_PARAMETER);
        CHECK(x.m.idx[3] == saved);
    }
    x.su[7] = 4242;
    CHECK_STATUS(nls_mesh_subdivide(&v, &o, &s, NULL, &x.sz, &x.rep, &x.su[7]), NLS_STATUS_NULL_PARAMETER);
    CHECK(x.su[7] == 4242);
    /* a misaligned view: its buffers cannot be named, so out_element keeps its value */
    memcpy(raw.c + 1, &v, sizeof v);
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(misview, &o, &s, &b, &x.sz, &x.rep, &x.element), NLS_STATUS_MISALIGNED_POINTER);
    UNTOUCHED();
    /* a bad stride: the extent of the positions is unknown, so the same */
    v.positions_stride = 7;
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(&v, &o, &s, &b, &x.sz, &x.rep, &x.element), NLS_STATUS_INVALID_ARGUMENT);
    UNTOUCHED();
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(&v, &o, &s, &b, &x.sz, &x.rep, into_out), NLS_STATUS_INVALID_ARGUMENT);
    UNTOUCHED();
    v.positions_stride = 0;
    /* a misaligned out_sizes: every buffer is known, NLS_NO_ELEMENT is written */
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(&v, &o, &s, &b, (nls_mesh_sizes *)(void *)(raw.c + 1), &x.rep, &x.element),
                 NLS_STATUS_MISALIGNED_POINTER);
    CHECK(x.element == NLS_NO_ELEMENT);
    RESET();
    CHECK_STATUS(nls_mesh_subdivide(&v, &o, &s, &b, (nls_mesh_sizes *)(void *)(raw.c + 1), &x.rep, into_out),
                 NLS_STATUS_MISALIGNED_POINTER);
    UNTOUCHED();
    /* the plan: NULL view with out_element into the scratch; misaligned view */
    x.su[9] = 4242;
    CHECK_STATUS(nls_mesh_plan(NULL, &o, x.su, 512, &plan, &x.su[9]), NLS_STATUS_NULL_PARAMETER);
    CHECK(x.su[9] == 4242);
    x.element = 12345;
    CHECK_STATUS(nls_mesh_plan(misview, &o, x.su, 512, &plan, &x.element), NLS_STATUS_MISALIGNED_POINTER);
    CHECK(x.element == 12345);
    x.element = 12345;
    CHECK_STATUS(nls_mesh_plan(NULL, &o, x.su, 512, &plan, &x.element), NLS_STATUS_NULL_PARAMETER);
    CHECK(x.element == NLS_NO_ELEMENT);
    /* the differential calls */
    {
        nls_differential_options d;
        nls_differential_report dr;
        CHECK_STATUS(nls_differential_default_options(&d), NLS_STATUS_OK);
        RESET();
        CHECK_STATUS(nls_differential_subdivide(NULL, &d, &s, &b, &x.sz, &dr, into_out), NLS_STATUS_NULL_PARAMETER);
        UNTOUCHED();
        RESET();
        CHECK_STATUS(nls_differential_subdivide(misview, &d, &s, &b, &x.sz, &dr, &x.element),
                     NLS_STATUS_MISALIGNED_POINTER);
        UNTOUCHED();
        /* an edit array cannot be named without the view (its length is the vertex count) */
        d.curvature_scale = x.sp;
        RESET();
        CHECK_STATUS(nls_differential_subdivide(misview, &d, &s, &b, &x.sz, &dr, &x.element),
                     NLS_STATUS_MISALIGNED_POINTER);
        UNTOUCHED();
        d.curvature_scale = NULL;
        RESET();
        CHECK_STATUS(nls_differential_subdivide(NULL, &d, &s, &b, &x.sz, &dr, &x.element), NLS_STATUS_NULL_PARAMETER);
        CHECK(x.element == NLS_NO_ELEMENT);
        x.su[9] = 4242;
        CHECK_STATUS(nls_differential_plan(NULL, &d, x.su, 512, &plan, &x.su[9]), NLS_STATUS_NULL_PARAMETER);
        CHECK(x.su[9] == 4242);
    }
    /* the curve call: NULL view with out_element into the output; misaligned view */
    {
        nls_curve_view *miscurve = (nls_curve_view *)(void *)(raw.c + 1);
        size_t cnt = 0;
        RESET();
        CHECK_STATUS(nls_curve_subdivide(NLS_CURVE_FOUR_POINT, NULL, 1, x.op, 128, x.sp, 128, &cnt,
                                         into_out),
                     NLS_STATUS_NULL_PARAMETER);
        UNTOUCHED();
        RESET();
        CHECK_STATUS(nls_curve_subdivide(NLS_CURVE_FOUR_POINT, miscurve, 1, x.op, 128, x.sp, 128,
                                         &cnt, &x.element),
                     NLS_STATUS_MISALIGNED_POINTER);
        UNTOUCHED();
        RESET();
        CHECK_STATUS(nls_curve_subdivide(NLS_CURVE_FOUR_POINT, NULL, 1, x.op, 128, x.sp, 128, &cnt,
                                         &x.element),
                     NLS_STATUS_NULL_PARAMETER);
        CHECK(x.element == NLS_NO_ELEMENT);
    }
#undef RESET
#undef UNTOUCHED
    mesh_free(&x.m);
}

static void test_strict(void) {
    mesh c = cube(), o;
    nls_subdivide_report rep = {777, 777, 777, 777, 777, 777};
    uint32_t element = 12345;
    onto_unit_sphere(&c);
    memcpy(c.p + 3, c.p, 3 * sizeof(double)); /* vertex 1 on vertex 0 */
    CHECK_STATUS(subdivide(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &c, &o, &rep, &element), NLS_STATUS_OK);
    CHECK(rep.fallbacks > 0 && rep.first_fallback < o.nv && rep.first_fallback_level == 1);
    CHECK(element == 12345);
    CHECK(valid_output(&o));
    mesh_free(&o);
    {
        nls_subdivide_report r2 = {777, 777, 777, 777, 777, 777};
        CHECK_STATUS(subdivide(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_STRICT, &c, &o, &r2,
                               &element),
                     NLS_STATUS_FALLBACK_IN_STRICT_MODE);
        /* strict refuses the first element the call would change: a fallback, or one the
         * fold guard changes (the same vertex pass finds both) */
        CHECK(element == rep.first_fallback || (rep.guarded > 0 && element == rep.first_guarded));
        CHECK(r2.fallbacks == 777);
        mesh_free(&o);
    }
    /* several levels: the report counts every level, the first fallback is in level 1 */
    {
        nls_subdivide_report r3 = {777, 777, 777, 777, 777, 777};
        CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &c, 2, &o, &r3), NLS_STATUS_OK);
        CHECK(r3.fallbacks >= rep.fallbacks && r3.first_fallback == rep.first_fallback && r3.first_fallback_level == 1);
        mesh_free(&o);
        CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_STRICT, &c, 2, &o,
                                      &r3),
                     NLS_STATUS_FALLBACK_IN_STRICT_MODE);
        mesh_free(&o);
    }
    /* the linear scheme has nothing to fall back from */
    CHECK_STATUS(subdivide(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_STRICT, &c, &o, &rep, NULL), NLS_STATUS_OK);
    CHECK(rep.fallbacks == 0);
    mesh_free(&o);
    mesh_free(&c);
}

static int same_mesh_bits(const mesh *a, const mesh *b) {
    return a->nv == b->nv && a->ni == b->ni && memcmp(a->p, b->p, 3 * a->nv * sizeof(double)) == 0;
}

/* The fold guard and the Möbius–linear spectrum through the C options: linear_weight 1 is
 * the linear result and 0 (the default) the Möbius result, bit for bit; a weight in between
 * is neither; NaN or outside [0, 1] is refused; NLS_SUBDIVIDE_LITERAL is accepted, changes
 * nothing where the guard has nothing to do (a mesh on a sphere), and reports no guarded
 * element; an unknown flag bit is refused. */
static void test_spectrum_and_literal(void) {
    mesh g = grid(4, 4, 0), lin, mob, mid, lit, c = cube(), cm, cl;
    nls_subdivide_report rep = {777, 777, 777, 777, 777, 777};
    size_t i;
    for (i = 0; i < g.nv; i++) g.p[3 * i + 2] = 0.3 * sin(1.7 * g.p[3 * i]) * cos(1.1 * g.p[3 * i + 1]);
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, 0, &g, 2, &lin, &rep), NLS_STATUS_OK);
    CHECK(rep.guarded == 0 && rep.first_guarded == NLS_NO_ELEMENT && rep.first_guarded_level == 0);
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &g, 2, &mob, &rep), NLS_STATUS_OK);
    flat_linear_weight = 1.0;
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &g, 2, &mid, &rep), NLS_STATUS_OK);
    CHECK(same_mesh_bits(&mid, &lin));
    mesh_free(&mid);
    flat_linear_weight = 0.5;
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &g, 2, &mid, &rep), NLS_STATUS_OK);
    CHECK(!same_mesh_bits(&mid, &lin) && !same_mesh_bits(&mid, &mob) && valid_output(&mid));
    mesh_free(&mid);
    {
        const double bad[3] = {NAN, -0.25, 1.5};
        int k;
        for (k = 0; k < 3; k++) {
            uint32_t element = 5;
            flat_linear_weight = bad[k];
            CHECK_STATUS(subdivide_levels_el(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &g, 2, &mid, &rep,
                                             &element),
                         NLS_STATUS_INVALID_ARGUMENT);
            mesh_free(&mid);
        }
    }
    flat_linear_weight = 0.0;
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_LITERAL, &g, 2, &lit,
                                  &rep),
                 NLS_STATUS_OK);
    CHECK(rep.guarded == 0 && rep.first_guarded == NLS_NO_ELEMENT && valid_output(&lit));
    onto_unit_sphere(&c);
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &c, 2, &cm, &rep), NLS_STATUS_OK);
    CHECK(rep.guarded == 0);
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_LITERAL, &c, 2, &cl,
                                  &rep),
                 NLS_STATUS_OK);
    CHECK(same_mesh_bits(&cm, &cl));
    CHECK(sphere_deviation(&cm) < 1e-12);
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS | (1u << 3), &c, 1, &mid, &rep),
                 NLS_STATUS_INVALID_ARGUMENT);
    mesh_free(&mid);
    mesh_free(&cm);
    mesh_free(&cl);
    mesh_free(&lit);
    mesh_free(&mob);
    mesh_free(&lin);
    mesh_free(&g);
    mesh_free(&c);
}

/* Positions with a byte stride (x, y, z then other attributes) give the bits of packed ones;
 * a stride that is not 0, or is not a multiple of 8, or is below 24 is refused. */
static void test_stride(void) {
    mesh c = cube(), o;
    nls_plan plan;
    size_t su = 0, v;
    const size_t stride = 7; /* doubles per vertex: x y z and four other attributes */
    double *wide = (double *)malloc(stride * c.nv * sizeof(double));
    uint32_t *scratch, *oo, *oi, *soo, *soi;
    double *sp, *op, *sop;
    nls_mesh_view view = flat_view(wide, c.nv, c.off, c.nf, c.idx, c.ni);
    nls_subdivide_options opts = flat_options(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2);
    nls_scratch sc;
    nls_mesh_buffers b, sb;
    nls_mesh_sizes sz = {0, 0, 0};
    onto_unit_sphere(&c);
    c.p[3 * 2] += 0.01;
    for (v = 0; v < c.nv; v++) {
        size_t k;
        memcpy(wide + stride * v, c.p + 3 * v, 3 * sizeof(double));
        for (k = 3; k < stride; k++) wide[stride * v + k] = k == 3 ? NAN : -1.0 * (double)k;
    }
    view.positions_stride = stride * sizeof(double);
    CHECK_STATUS(subdivide_levels(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &c, 2, &o, NULL), NLS_STATUS_OK);
    CHECK_STATUS(nls_mesh_plan_scratch_size(&view, &su), NLS_STATUS_OK);
    scratch = (uint32_t *)malloc(su * sizeof(uint32_t));
    CHECK_STATUS(nls_mesh_plan(&view, &opts, scratch, su, &plan, NULL), NLS_STATUS_OK);
    CHECK(plan.output.vertex_count == o.nv && plan.output.face_count == o.nf && plan.output.index_count == o.ni);
    free(scratch);
    scratch = (uint32_t *)malloc(plan.scratch_u32 * sizeof(uint32_t));
    sp = (double *)malloc(3 * plan.scratch_points * sizeof(double));
    op = (double *)malloc(3 * o.nv * sizeof(double));
    oo = (uint32_t *)malloc((o.nf + 1) * sizeof(uint32_t));
    oi = (uint32_t *)malloc(o.ni * sizeof(uint32_t));
    sc = flat_scratch(scratch, plan.scratch_u32, sp, plan.scratch_points);
    b = flat_buffers(op, o.nv, oo, o.nf, oi, o.ni);
    CHECK_STATUS(nls_mesh_subdivide(&view, &opts, &sc, &b, &sz, NULL, NULL), NLS_STATUS_OK);
    CHECK(sz.vertex_count == o.nv && memcmp(op, o.p, 3 * o.nv * sizeof(double)) == 0);
    CHECK(memcmp(oi, o.idx, o.ni * sizeof(uint32_t)) == 0);
    /* 24 is packed too */
    view.positions = c.p;
    view.positions_stride = 24;
    memset(op, 0, 3 * o.nv * sizeof(double));
    CHECK_STATUS(nls_mesh_subdivide(&view, &opts, &sc, &b, &sz, NULL, NULL), NLS_STATUS_OK);
    CHECK(memcmp(op, o.p, 3 * o.nv * sizeof(double)) == 0);
    /* bad strides */
    {
        const size_t bad[4] = {8, 16, 25, 60};
        size_t k;
        for (k = 0; k < 4; k++) {
            view.positions_stride = bad[k];
            CHECK_STATUS(nls_mesh_subdivide(&view, &opts, &sc, &b, &sz, NULL, NULL), NLS_STATUS_INVALID_ARGUMENT);
            CHECK_STATUS(nls_mesh_plan(&view, &opts, sc.u32s, su, &plan, NULL), NLS_STATUS_INVALID_ARGUMENT);
        }
    }
    /* the strided input's extent counts for the overlap rule: an output inside the attributes
     * of the last vertex but one is refused */
    view.positions = wide;
    view.positions_stride = stride * sizeof(double);
    sop = wide + stride * (c.nv - 2) + 3;
    soo = oo;
    soi = oi;
    sb = flat_buffers(sop, 1, soo, o.nf, soi, o.ni);
    CHECK_STATUS(nls_mesh_subdivide(&view, &opts, &sc, &sb, &sz, NULL, NULL), NLS_STATUS_ALIASING_BUFFERS);
    free(wide);
    free(scratch);
    free(sp);
    free(op);
    free(oo);
    free(oi);
    mesh_free(&o);
    mesh_free(&c);
}

/* ------------------------------------------------------------------------------ MemorySafe */

/* A block of exactly `n` elements of `size` bytes (NULL for 0), filled with 0xAB. */
static void *block(size_t n, size_t size) {
    void *b;
    if (n == 0) return NULL;
    b = malloc(n * size);
    memset(b, 0xAB, n * size);
    return b;
}

static int untouched(const void *b, size_t bytes) {
    const unsigned char *c = (const unsigned char *)b;
    size_t i;
    for (i = 0; i < bytes; i++)
        if (c[i] != 0xAB) return 0;
    return 1;
}

/* Every too-small capacity of every buffer of one call of `levels` levels (the plan's own
 * scratch too), then the exact sizes. Returns the number of calls made. */
static int sweep(uint32_t scheme, uint32_t flags, const mesh *m, uint32_t levels) {
    size_t need[5], nv = 0, nf = 0, ni = 0, su = 0, sp = 0, su0 = 0;
    size_t elem[5];
    int b, calls = 0;
    elem[0] = sizeof(uint32_t);
    elem[1] = elem[2] = 3 * sizeof(double);
    elem[3] = elem[4] = sizeof(uint32_t);
    {
        uint32_t *s;
        nls_plan plan = {{0, 0, 0}, 0, 0};
        CHECK_STATUS(flat_plan_scratch_size(m->nv, m->ni, &su0), NLS_STATUS_OK);
        s = (uint32_t *)block(su0, sizeof(uint32_t));
        CHECK_STATUS(flat_plan(scheme, flags, levels, m->p, m->nv, m->off, m->nf, m->idx, m->ni, s, su0, &plan, NULL),
                     NLS_STATUS_OK);
        nv = plan.output.vertex_count;
        nf = plan.output.face_count;
        ni = plan.output.index_count;
        su = plan.scratch_u32;
        sp = plan.scratch_points;
        /* the plan's own scratch, every short size */
        {
            size_t cap;
            for (cap = 0; cap < su0; cap++) {
                uint32_t *t = (uint32_t *)block(cap, sizeof(uint32_t)), element = 0;
                nls_plan p2 = {{777, 777, 777}, 777, 777};
                CHECK_STATUS(flat_plan(scheme, flags, levels, m->p, m->nv, m->off, m->nf, m->idx, m->ni, t, cap, &p2,
                                       &element),
                             NLS_STATUS_BUFFER_TOO_SMALL);
                CHECK(element == NLS_MESH_BUFFER_SCRATCH_U32 && p2.output.vertex_count == 777 && p2.scratch_u32 == 777);
                free(t);
                calls++;
            }
        }
        free(s);
    }
    need[0] = su;
    need[1] = sp;
    need[2] = nv;
    need[3] = nf; /* capacity in faces: the block holds one more entry */
    need[4] = ni;
    for (b = 0; b <= 5; b++) {
        size_t cap, last = b == 5 ? 1 : need[b];
        for (cap = 0; cap < last; cap++) {
            void *buf[5];
            size_t capn[5];
            int k;
            nls_mesh_sizes cs = {777, 777, 777};
            uint32_t element = 12345;
            nls_subdivide_report rep = {777, 777, 777, 777, 777, 777};
            nls_status s;
            for (k = 0; k < 5; k++) {
                capn[k] = k == b ? cap : need[k];
                buf[k] = block(k == 3 ? capn[k] + 1 : capn[k], elem[k]);
            }
            s = flat_subdivide(scheme, flags, levels, m->p, m->nv, m->off, m->nf, m->idx, m->ni, (uint32_t *)buf[0],
                               capn[0], (double *)buf[1], capn[1], (double *)buf[2], capn[2], (uint32_t *)buf[3],
                               capn[3], (uint32_t *)buf[4], capn[4], &cs, &rep, &element);
            calls++;
            if (b < 5) {
                CHECK(s == NLS_STATUS_BUFFER_TOO_SMALL);
                CHECK(element == (uint32_t)b);
                CHECK(rep.fallbacks == 777);
                if (b >= 2)
                    CHECK(cs.vertex_count == nv && cs.face_count == nf && cs.index_count == ni);
                else
                    CHECK(cs.vertex_count == 777 && cs.face_count == 777 && cs.index_count == 777);
                /* no output buffer was written */
                CHECK(capn[2] == 0 || untouched(buf[2], capn[2] * elem[2]));
                CHECK(untouched(buf[3], (capn[3] + 1) * elem[3]));
                CHECK(capn[4] == 0 || untouched(buf[4], capn[4] * elem[4]));
            } else {
                CHECK(s == NLS_STATUS_OK);
                CHECK(cs.vertex_count == nv && cs.face_count == nf && cs.index_count == ni && element == 12345 &&
                      rep.fallbacks == 0);
            }
            for (k = 0; k < 5; k++) free(buf[k]);
        }
    }
    return calls;
}

static void test_memory_safe_sweep(void) {
    mesh meshes[3];
    int si, mob, calls = 0;
    meshes[0] = pyramid();
    meshes[1] = tetrahedron();
    meshes[2] = cube();
    for (si = 0; si < NSCHEMES; si++) {
        const mesh *m = mesh_accepts(SCHEMES[si], &meshes[0]) ? &meshes[0]
                        : mesh_accepts(SCHEMES[si], &meshes[1]) ? &meshes[1]
                                                                 : &meshes[2];
        for (mob = 0; mob <= 1; mob++) calls += sweep(SCHEMES[si], mob ? NLS_SUBDIVIDE_MOBIUS : 0u, m, 1);
    }
    calls += sweep(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, &meshes[0], 2);
    calls += sweep(NLS_SCHEME_LOOP, 0, &meshes[1], 2);
    calls += sweep(NLS_SCHEME_DOO_SABIN, NLS_SUBDIVIDE_MOBIUS, &meshes[2], 1);
    printf("test_mesh: MemorySafe sweep, %d calls\n", calls);
    mesh_free(&meshes[0]);
    mesh_free(&meshes[1]);
    mesh_free(&meshes[2]);
}

/* ------------------------------------------------------------------------------ star rules */

/* The corner after / before corner c in its face. */
static uint32_t face_of(const mesh *m, uint32_t c) {
    uint32_t f = 0;
    while (m->off[f + 1] <= c) f++;
    return f;
}
static uint32_t next_corner(const mesh *m, uint32_t c) {
    uint32_t f = face_of(m, c);
    return c + 1 == m->off[f + 1] ? m->off[f] : c + 1;
}
static uint32_t prev_corner(const mesh *m, uint32_t c) {
    uint32_t f = face_of(m, c);
    return c == m->off[f] ? m->off[f + 1] - 1 : c - 1;
}
/* The corner of the half-edge a -> b, or UINT32_MAX. */
static uint32_t half_edge(const mesh *m, uint32_t a, uint32_t b) {
    uint32_t c;
    for (c = 0; c < m->ni; c++)
        if (m->idx[c] == a && m->idx[next_corner(m, c)] == b) return c;
    return UINT32_MAX;
}

/* The star of an interior vertex in the driver's order: spokes from the lowest outgoing
 * corner, counter-clockwise. Writes the spoke corners; returns the valence. */
static size_t star_spokes(const mesh *m, uint32_t v, uint32_t *spokes) {
    uint32_t c, h;
    size_t n = 0;
    for (c = 0; m->idx[c] != v; c++) {
    }
    h = c;
    do {
        spokes[n++] = h;
        h = half_edge(m, v, m->idx[prev_corner(m, h)]);
    } while (h != c && n < 64);
    return n;
}

/* The edge id of {a, b}: its rank among all edges sorted by (min, max). */
static size_t edge_id(const mesh *m, uint32_t a, uint32_t b) {
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a, c;
    size_t id = 0;
    for (c = 0; c < m->ni; c++) {
        uint32_t x = m->idx[c], y = m->idx[next_corner(m, c)];
        uint32_t l = x < y ? x : y, h = x < y ? y : x;
        /* count each edge once: from its min -> max half-edge (closed meshes have both) */
        if (x < y && (l < lo || (l == lo && h < hi))) id++;
    }
    return id;
}

typedef struct {
    double vertex[3];
    double edges[3 * 64];
    double faces[3 * 64];
    uint32_t spokes[64];
    size_t n;
} star_rules;

static nls_status rules_of(const mesh *m, uint32_t v, int cc, star_rules *r) {
    double ring[3 * 64], corners[3 * 512];
    uint32_t offs[65];
    size_t j, nc = 0;
    r->n = star_spokes(m, v, r->spokes);
    offs[0] = 0;
    for (j = 0; j < r->n; j++) {
        uint32_t h = r->spokes[j], f = face_of(m, h), k;
        memcpy(ring + 3 * j, m->p + 3 * m->idx[next_corner(m, h)], 3 * sizeof(double));
        for (k = m->off[f]; k < m->off[f + 1]; k++) memcpy(corners + 3 * nc++, m->p + 3 * m->idx[k], 3 * sizeof(double));
        offs[j + 1] = (uint32_t)nc;
    }
    {
        nls_star_view star;
        star.v = m->p + 3 * v;
        star.ring = ring;
        star.ring_count = r->n;
        star.closed = 1;
        star.face_offsets = offs;
        star.face_count = r->n;
        star.face_corners = corners;
        star.corner_count = nc;
        if (!cc) return nls_mobius_loop_star(&star, r->vertex, r->edges);
        return nls_mobius_catmull_clark_star(&star, r->vertex, r->edges, r->faces);
    }
}

/* The candidate of edge v -> u from v's rules. */
static const double *cand(const mesh *m, const star_rules *r, uint32_t u) {
    size_t j;
    for (j = 0; j < r->n; j++)
        if (m->idx[next_corner(m, r->spokes[j])] == u) return r->edges + 3 * j;
    return NULL;
}

static void test_star_rules_match_the_driver(int cc) {
    mesh m = cc ? cube() : octahedron(), o;
    star_rules *rules = (star_rules *)malloc(8 * sizeof(star_rules));
    uint32_t v, c;
    size_t ne = m.ni / 2, nsame = 0;
    if (cc) {
        onto_unit_sphere(&m);
        m.p[3 * 6] += 0.03; /* off the symmetric case, still exact to compare */
    } else {
        m.p[3 * 4 + 1] += 0.05;
    }
    CHECK_STATUS(subdivide(cc ? NLS_SCHEME_CATMULL_CLARK : NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, &m, &o, NULL, NULL),
                 NLS_STATUS_OK);
    for (v = 0; v < m.nv; v++) {
        CHECK_STATUS(rules_of(&m, v, cc, &rules[v]), NLS_STATUS_OK);
        CHECK(memcmp(rules[v].vertex, o.p + 3 * v, 3 * sizeof(double)) == 0);
        nsame++;
    }
    for (c = 0; c < m.ni; c++) {
        uint32_t a = m.idx[c], b = m.idx[next_corner(&m, c)];
        double e[3];
        if (a > b) continue;
        CHECK_STATUS(nls_f4_hinted(m.p + 3 * a, cand(&m, &rules[a], b), cand(&m, &rules[b], a), m.p + 3 * b,
                                   m.p + 3 * m.idx[next_corner(&m, next_corner(&m, c))], e),
                     NLS_STATUS_OK);
        CHECK(memcmp(e, o.p + 3 * (m.nv + edge_id(&m, a, b)), sizeof e) == 0);
        nsame++;
    }
    if (cc) {
        uint32_t f;
        for (f = 0; f < m.nf; f++) {
            double verts[3 * 8], cands[3 * 8], fp[3];
            uint32_t k, d = m.off[f + 1] - m.off[f];
            for (k = 0; k < d; k++) {
                uint32_t u = m.idx[m.off[f] + k];
                size_t j;
                memcpy(verts + 3 * k, m.p + 3 * u, 3 * sizeof(double));
                for (j = 0; j < rules[u].n; j++)
                    if (face_of(&m, rules[u].spokes[j]) == f) memcpy(cands + 3 * k, rules[u].faces + 3 * j, 3 * sizeof(double));
            }
            CHECK_STATUS(nls_face_point_with_ids(verts, cands, m.idx + m.off[f], d, fp), NLS_STATUS_OK);
            CHECK(memcmp(fp, o.p + 3 * (m.nv + ne + f), sizeof fp) == 0);
            nsame++;
        }
    }
    printf("test_mesh: %s star rules = driver on %zu points, bit for bit\n", cc ? "Catmull-Clark" : "Loop", nsame);
    free(rules);
    mesh_free(&o);
    mesh_free(&m);
}

/* The star rules with flat arguments (the fields of nls_star_view in order). */
static nls_status cc_star(const double *v, const double *ring, size_t n, uint32_t closed, const uint32_t *offs,
                          size_t nf, const double *corners, size_t nc, double *vp, double *e, double *f) {
    nls_star_view star;
    star.v = v;
    star.ring = ring;
    star.ring_count = n;
    star.closed = closed;
    star.face_offsets = offs;
    star.face_count = nf;
    star.face_corners = corners;
    star.corner_count = nc;
    return nls_mobius_catmull_clark_star(&star, vp, e, f);
}

static nls_status loop_star(const double *v, const double *ring, size_t n, uint32_t closed, double *vp, double *e) {
    nls_star_view star;
    star.v = v;
    star.ring = ring;
    star.ring_count = n;
    star.closed = closed;
    star.face_offsets = NULL;
    star.face_count = 0;
    star.face_corners = NULL;
    star.corner_count = 0;
    return nls_mobius_loop_star(&star, vp, e);
}

static void fill(double *p, size_t n, double value) {
    size_t i;
    for (i = 0; i < n; i++) p[i] = value;
}

static int all_equal(const double *p, size_t n, double value) {
    size_t i;
    for (i = 0; i < n; i++)
        if (p[i] != value) return 0;
    return 1;
}

static void test_star_rules_edge_cases(void) {
    static const double v[3] = {0, 0, 0};
    static const double ring[3 * 4] = {1, 0, 0.1, 0, 1, -0.1, -1, 0, 0.1, 0, -1, -0.1};
    double vp[3], e[3 * 4], f[3 * 4];
    double sentinel = 777.0;
    /* a boundary star: no vertex point, no candidates on the two boundary edges */
    CHECK_STATUS(loop_star(v, ring, 4, 0, vp, e), NLS_STATUS_OK);
    CHECK(isnan(vp[0]) && isnan(e[0]) && isnan(e[9]) && isfinite(e[3]) && isfinite(e[6]));
    CHECK_STATUS(loop_star(v, ring, 4, 1, vp, e), NLS_STATUS_OK);
    CHECK(isfinite(vp[0]) && isfinite(e[0]) && isfinite(e[9]));
    /* bad arguments: nothing written (the rules write the caller's buffers directly, only
     * once they cannot fail) */
    fill(vp, 3, sentinel);
    fill(e, 3 * 4, sentinel);
    CHECK_STATUS(loop_star(v, ring, 4, 2, vp, e), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(loop_star(v, ring, 1, 1, vp, e), NLS_STATUS_TOO_FEW_POINTS);
    CHECK_STATUS(loop_star(v, NULL, 4, 1, vp, e), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(loop_star(v, ring, 4, 1, NULL, e), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(loop_star(v, ring, 200, 1, vp, e), NLS_STATUS_VALENCE_TOO_HIGH);
    CHECK_STATUS(loop_star(v, ring, SIZE_MAX / 2, 1, vp, e), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(loop_star(v, e, 4, 1, vp, e), NLS_STATUS_ALIASING_BUFFERS);
    CHECK_STATUS(loop_star(v, ring, 4, 1, e + 3, e), NLS_STATUS_ALIASING_BUFFERS);
    {
        double r2[3 * 4];
        memcpy(r2, ring, sizeof r2);
        r2[3] = 0.0;
        r2[4] = 0.0;
        r2[5] = 0.0; /* a neighbour on the centre */
        CHECK_STATUS(loop_star(v, r2, 4, 1, vp, e), NLS_STATUS_DEGENERATE_GEOMETRY);
        r2[4] = NAN;
        CHECK_STATUS(loop_star(v, r2, 4, 1, vp, e), NLS_STATUS_NON_FINITE_INPUT);
    }
    CHECK_STATUS(nls_mobius_loop_star(NULL, vp, e), NLS_STATUS_NULL_PARAMETER);
    CHECK(all_equal(vp, 3, sentinel) && all_equal(e, 3 * 4, sentinel));
    /* Catmull–Clark: four quads around the centre */
    {
        const uint32_t offs[5] = {0, 4, 8, 12, 16};
        double corners[3 * 16];
        int j, k;
        for (j = 0; j < 4; j++) {
            const double *a = ring + 3 * j, *b = ring + 3 * ((j + 1) % 4);
            double diag[3];
            for (k = 0; k < 3; k++) diag[k] = a[k] + b[k];
            memcpy(corners + 12 * j, v, sizeof v);
            memcpy(corners + 12 * j + 3, a, 3 * sizeof(double));
            memcpy(corners + 12 * j + 6, diag, sizeof diag);
            memcpy(corners + 12 * j + 9, b, 3 * sizeof(double));
        }
        CHECK_STATUS(cc_star(v, ring, 4, 1, offs, 4, corners, 16, vp, e, f), NLS_STATUS_OK);
        CHECK(isfinite(vp[0]) && isfinite(e[0]) && isfinite(f[0]) && isfinite(f[9]));
        CHECK_STATUS(cc_star(v, ring, 4, 0, offs, 3, corners, 12, vp, e, f), NLS_STATUS_OK);
        CHECK(isnan(vp[0]) && isnan(e[0]) && isnan(e[9]) && isfinite(e[3]) && isfinite(f[6]));
        fill(vp, 3, sentinel);
        fill(e, 3 * 4, sentinel);
        fill(f, 3 * 4, sentinel);
        CHECK_STATUS(cc_star(v, ring, 4, 1, offs, 3, corners, 12, vp, e, f),
                     NLS_STATUS_INVALID_ARGUMENT);
        {
            const uint32_t bad[5] = {0, 4, 9, 8, 16};
            CHECK_STATUS(cc_star(v, ring, 4, 1, bad, 4, corners, 16, vp, e, f),
                         NLS_STATUS_BAD_OFFSETS);
        }
        {
            const uint32_t small[5] = {0, 4, 6, 12, 16};
            CHECK_STATUS(cc_star(v, ring, 4, 1, small, 4, corners, 16, vp, e, f),
                         NLS_STATUS_FACE_TOO_SMALL);
        }
        {
            double c2[3 * 16];
            memcpy(c2, corners, sizeof c2);
            c2[0] = 5.0; /* face 0 no longer holds v */
            CHECK_STATUS(cc_star(v, ring, 4, 1, offs, 4, c2, 16, vp, e, f),
                         NLS_STATUS_INVALID_ARGUMENT);
        }
        CHECK_STATUS(cc_star(v, ring, 4, 1, offs, 4, corners, 16, vp, corners, f),
                     NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(cc_star(v, ring, 4, 1, NULL, 4, corners, 16, vp, e, f),
                     NLS_STATUS_NULL_PARAMETER);
        {
            double r2[3 * 4];
            memcpy(r2, ring, sizeof r2);
            r2[3] = r2[4] = r2[5] = 0.0; /* a neighbour on the centre: no canonical form */
            CHECK_STATUS(cc_star(v, r2, 4, 1, offs, 4, corners, 16, vp, e, f),
                         NLS_STATUS_DEGENERATE_GEOMETRY);
        }
        corners[20] = INFINITY;
        CHECK_STATUS(cc_star(v, ring, 4, 1, offs, 4, corners, 16, vp, e, f),
                     NLS_STATUS_NON_FINITE_INPUT);
        CHECK(all_equal(vp, 3, sentinel) && all_equal(e, 3 * 4, sentinel) &&
              all_equal(f, 3 * 4, sentinel));
    }
    /* nls_f4_hinted: like nls_f4 off the negative-real case */
    {
        const double a[3] = {0, 0, 0}, b[3] = {1, 0.2, 0}, c[3] = {2, 0.1, 0.3}, d[3] = {3, -0.2, 0.1},
                     x[3] = {1, 1, 1};
        double p1[3], p2[3];
        CHECK_STATUS(nls_f4(a, b, c, d, p1), NLS_STATUS_OK);
        CHECK_STATUS(nls_f4_hinted(a, b, c, d, x, p2), NLS_STATUS_OK);
        CHECK(memcmp(p1, p2, sizeof p1) == 0);
        CHECK(nls_dist3(p1, b) > 0.1 && nls_dist3(p1, c) > 0.1); /* between b and c */
        CHECK_STATUS(nls_f4_hinted(a, b, c, d, NULL, p2), NLS_STATUS_NULL_PARAMETER);
    }
}

/* ------------------------------------------------------------------------------ FP env */

static void test_fp_environment(void) {
#if defined(__x86_64__)
    mesh t = tetrahedron();
    uint32_t su[64];
    nls_plan plan = {{777, 777, 777}, 777, 777};
    if (getenv("NLS_TEST_UNDER_VALGRIND") != NULL) {
        printf("SKIP test_fp_environment under valgrind\n");
        mesh_free(&t);
        return;
    }
    {
        unsigned int saved = _mm_getcsr();
        nls_status s;
        _mm_setcsr(saved | 0x8040u); /* FTZ + DAZ */
        s = flat_plan(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, 1, t.p, t.nv, t.off, t.nf, t.idx, t.ni, su, 64, &plan, NULL);
        _mm_setcsr(saved);
        CHECK_STATUS(s, NLS_STATUS_FP_ENVIRONMENT);
        CHECK(plan.output.vertex_count == 777);
    }
    CHECK_STATUS(flat_plan(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, 1, t.p, t.nv, t.off, t.nf, t.idx, t.ni, su, 64, &plan,
                           NULL),
                 NLS_STATUS_OK);
    CHECK(plan.output.vertex_count == 10 && plan.output.face_count == 16 && plan.output.index_count == 48);
    mesh_free(&t);
#endif
}

int main(void) {
    test_constants();
    test_every_scheme();
    test_spheres();
    test_levels_linear();
    test_bad_meshes();
    test_capacities();
    test_bad_arguments();
    test_early_failure_element();
    test_strict();
    test_spectrum_and_literal();
    test_stride();
    test_memory_safe_sweep();
    test_star_rules_match_the_driver(0);
    test_star_rules_match_the_driver(1);
    test_star_rules_edge_cases();
    test_fp_environment();
    return nls_summary("ffi_tests/test_mesh");
}
