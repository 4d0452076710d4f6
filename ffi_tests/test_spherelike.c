/* C99 tests of NLS_SCHEME_SPHERELIKE through the nls_mesh_* exports (seed 003 §3): sizes of
 * Catmull–Clark's connectivity, old vertices bit for bit, rows of an unevenly sampled torus
 * staying on the torus, one call of several levels against repeated single levels, and the
 * statuses: Möbius flag refused, coincident vertices DEGENERATE_GEOMETRY naming the output
 * vertex, short buffers refused with nothing written. Run under ASan+UBSan and valgrind. */
#include <stdint.h>
#include <stdlib.h>

#include "nlsubdiv.h"
#include "check.h"
#include "flat_args.h"

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

/* An nu × nv quad torus, rows at the given angles (vertex (i, j) is j*nu + i). */
static mesh torus(const double *us, size_t nu, const double *vs, size_t nv, double big, double small) {
    mesh m;
    size_t i, j, k = 0;
    m.nv = nu * nv;
    m.nf = nu * nv;
    m.ni = 4 * m.nf;
    m.p = (double *)malloc(3 * m.nv * sizeof(double));
    m.off = (uint32_t *)malloc((m.nf + 1) * sizeof(uint32_t));
    m.idx = (uint32_t *)malloc(m.ni * sizeof(uint32_t));
    for (j = 0; j < nv; j++) {
        for (i = 0; i < nu; i++) {
            double r = big + small * cos(vs[j]);
            m.p[3 * (j * nu + i) + 0] = r * cos(us[i]);
            m.p[3 * (j * nu + i) + 1] = r * sin(us[i]);
            m.p[3 * (j * nu + i) + 2] = small * sin(vs[j]);
        }
    }
    m.off[0] = 0;
    for (j = 0; j < nv; j++) {
        for (i = 0; i < nu; i++) {
            size_t i1 = (i + 1) % nu, j1 = (j + 1) % nv;
            m.idx[k++] = (uint32_t)(j * nu + i);
            m.idx[k++] = (uint32_t)(j * nu + i1);
            m.idx[k++] = (uint32_t)(j1 * nu + i1);
            m.idx[k++] = (uint32_t)(j1 * nu + i);
            m.off[j * nu + i + 1] = (uint32_t)k;
        }
    }
    return m;
}

static mesh cube(void) {
    static const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    mesh m;
    size_t k;
    m.nv = 8;
    m.nf = 6;
    m.ni = 24;
    m.p = (double *)malloc(24 * sizeof(double));
    m.off = (uint32_t *)malloc(7 * sizeof(uint32_t));
    m.idx = (uint32_t *)malloc(24 * sizeof(uint32_t));
    for (k = 0; k < 8; k++) {
        m.p[3 * k + 0] = (k == 1 || k == 2 || k == 5 || k == 6) ? 1.0 : 0.0;
        m.p[3 * k + 1] = (k == 2 || k == 3 || k == 6 || k == 7) ? 1.0 : 0.0;
        m.p[3 * k + 2] = k >= 4 ? 1.0 : 0.0;
    }
    for (k = 0; k < 6; k++) {
        m.idx[4 * k + 0] = (uint32_t)f[k][0];
        m.idx[4 * k + 1] = (uint32_t)f[k][1];
        m.idx[4 * k + 2] = (uint32_t)f[k][2];
        m.idx[4 * k + 3] = (uint32_t)f[k][3];
        m.off[k] = (uint32_t)(4 * k);
    }
    m.off[6] = 24;
    return m;
}

/* One level (levels == 0 or 1) or `levels` levels in one call, exactly sized; the output is
 * pre-filled with a pattern so that "nothing written" can be checked on failure. */
static nls_status run(uint32_t flags, const mesh *m, uint32_t levels, mesh *out, uint32_t *element) {
    size_t su = 0, sp = 0, nv = 0, nf = 0, ni = 0;
    uint32_t *scratch_u32;
    double *scratch_points;
    nls_plan plan;
    nls_mesh_sizes w = {0, 0, 0};
    const uint32_t n = levels == 0 ? 1 : levels;
    nls_status s = flat_plan_scratch_size(m->nv, m->ni, &su);
    out->p = NULL;
    out->off = NULL;
    out->idx = NULL;
    if (s != NLS_STATUS_OK) return s;
    scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t) + 1);
    s = flat_plan(NLS_SCHEME_SPHERELIKE, 0, n, m->p, m->nv, m->off, m->nf, m->idx, m->ni, scratch_u32, su, &plan,
                  element);
    free(scratch_u32);
    if (s != NLS_STATUS_OK) return s;
    su = plan.scratch_u32;
    sp = plan.scratch_points;
    nv = plan.output.vertex_count;
    nf = plan.output.face_count;
    ni = plan.output.index_count;
    scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t) + 1);
    scratch_points = (double *)malloc(3 * sp * sizeof(double) + 8);
    out->p = (double *)malloc(3 * nv * sizeof(double) + 1);
    out->off = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
    out->idx = (uint32_t *)malloc(ni * sizeof(uint32_t) + 1);
    memset(out->p, 0x7f, 3 * nv * sizeof(double));
    out->nv = nv;
    out->nf = nf;
    out->ni = ni;
    s = flat_subdivide(NLS_SCHEME_SPHERELIKE, flags, n, m->p, m->nv, m->off, m->nf, m->idx, m->ni, scratch_u32, su,
                       scratch_points, sp, out->p, nv, out->off, nf, out->idx, ni, &w, NULL, element);
    if (s == NLS_STATUS_OK) CHECK(w.vertex_count == nv && w.face_count == nf && w.index_count == ni);
    free(scratch_u32);
    free(scratch_points);
    return s;
}

static void test_constant_and_sizes(void) {
    mesh m = cube(), o;
    size_t k;
    int quads = 1;
    CHECK(NLS_SCHEME_SPHERELIKE == 9);
    CHECK_STATUS(run(0, &m, 0, &o, NULL), NLS_STATUS_OK);
    /* Catmull–Clark's counts: V + E + F vertices, one quad per corner. */
    CHECK(o.nv == 8 + 12 + 6 && o.nf == 24 && o.ni == 96);
    for (k = 0; k < o.nf; k++) quads &= o.off[k + 1] - o.off[k] == 4;
    CHECK(quads);
    CHECK(memcmp(o.p, m.p, 3 * m.nv * sizeof(double)) == 0); /* interpolating, bit for bit */
    for (k = 0; k < 3 * o.nv; k++) CHECK(isfinite(o.p[k]));
    {
        /* The cube's symmetry: the six face points (and the twelve edge points) are equally
         * far from its centre, and outside the cube (the scheme bulges like a sphere). */
        static const double c[3] = {0.5, 0.5, 0.5};
        double f0 = nls_dist3(o.p + 3 * 20, c), e0 = nls_dist3(o.p + 3 * 8, c);
        for (k = 20; k < 26; k++) CHECK(fabs(nls_dist3(o.p + 3 * k, c) - f0) < 1e-12);
        for (k = 8; k < 20; k++) CHECK(fabs(nls_dist3(o.p + 3 * k, c) - e0) < 1e-12);
        CHECK(f0 > 0.5 && e0 > sqrt(0.5));
    }
    mesh_free(&o);
    mesh_free(&m);
}

static void test_torus_rows(void) {
    /* Unevenly spaced rows: every output vertex stays on the torus (its rows and meridians
     * are circles, which the circle blend reproduces). */
    static const double us[7] = {0.0, 0.5, 1.7, 2.2, 3.9, 4.6, 5.5};
    static const double vs[6] = {-0.3, 0.4, 1.9, 2.6, 4.0, 5.1};
    const double big = 3.0, small = 1.2;
    mesh m = torus(us, 7, vs, 6, big, small), o, chain, next;
    double worst = 0.0;
    size_t k;
    uint32_t level;
    CHECK_STATUS(run(0, &m, 3, &o, NULL), NLS_STATUS_OK);
    for (k = 0; k < o.nv; k++) {
        const double *p = o.p + 3 * k;
        double rho = sqrt(p[0] * p[0] + p[1] * p[1]);
        double d = fabs(sqrt((rho - big) * (rho - big) + p[2] * p[2]) - small) / (big + small);
        if (d > worst) worst = d;
    }
    printf("spherelike torus 3 levels: max relative distance from the torus %.2e\n", worst);
    CHECK(worst < 1e-12);
    /* The multi-level call equals three one-level calls, bit for bit; old vertices kept. */
    chain = m;
    for (level = 0; level < 3; level++) {
        CHECK_STATUS(run(0, &chain, 0, &next, NULL), NLS_STATUS_OK);
        CHECK(memcmp(next.p, chain.p, 3 * chain.nv * sizeof(double)) == 0);
        if (level > 0) mesh_free(&chain);
        chain = next;
    }
    CHECK(chain.nv == o.nv && memcmp(chain.p, o.p, 3 * o.nv * sizeof(double)) == 0);
    CHECK(memcmp(chain.idx, o.idx, o.ni * sizeof(uint32_t)) == 0);
    mesh_free(&chain);
    mesh_free(&o);
    mesh_free(&m);
}

static void test_statuses(void) {
    mesh m = cube(), o;
    uint32_t element = 12345;
    size_t su = 0, sp = 0;
    nls_mesh_sizes sizes = {0, 0, 0};
    uint32_t *scratch;
    double *pts, *outp;
    uint32_t *outo, *outi;
    size_t k;
    int untouched = 1;

    /* No Möbius form. */
    CHECK_STATUS(run(NLS_SUBDIVIDE_MOBIUS, &m, 0, &o, &element), NLS_STATUS_INVALID_ARGUMENT);
    mesh_free(&o);
    CHECK_STATUS(run(NLS_SUBDIVIDE_MOBIUS, &m, 2, &o, NULL), NLS_STATUS_INVALID_ARGUMENT);
    mesh_free(&o);

    /* Coincident vertices 0 and 1: the circle of edge (0, 1) (edge id 0) is undefined; the
     * element is its output vertex, V + 0 = 8. */
    m.p[3] = m.p[0];
    m.p[4] = m.p[1];
    m.p[5] = m.p[2];
    element = 12345;
    CHECK_STATUS(run(0, &m, 0, &o, &element), NLS_STATUS_DEGENERATE_GEOMETRY);
    CHECK(element == 8);
    mesh_free(&o);
    CHECK_STATUS(run(0, &m, 2, &o, NULL), NLS_STATUS_DEGENERATE_GEOMETRY);
    mesh_free(&o);
    mesh_free(&m);

    /* A short positions buffer: BUFFER_TOO_SMALL naming it, exact sizes, nothing written. */
    m = cube();
    CHECK_STATUS(flat_plan_scratch_size(m.nv, m.ni, &su), NLS_STATUS_OK);
    scratch = (uint32_t *)malloc(su * sizeof(uint32_t));
    {
        nls_plan plan;
        CHECK_STATUS(flat_plan(NLS_SCHEME_SPHERELIKE, 0, 1, m.p, m.nv, m.off, m.nf, m.idx, m.ni, scratch, su, &plan, NULL),
                     NLS_STATUS_OK);
        CHECK(plan.scratch_u32 == su);
        sp = plan.scratch_points;
    }
    pts = (double *)malloc(3 * sp * sizeof(double) + 8);
    outp = (double *)malloc(3 * 25 * sizeof(double));
    outo = (uint32_t *)malloc(25 * sizeof(uint32_t));
    outi = (uint32_t *)malloc(96 * sizeof(uint32_t));
    memset(outp, 0x5a, 3 * 25 * sizeof(double));
    CHECK_STATUS(flat_subdivide(NLS_SCHEME_SPHERELIKE, 0, 1, m.p, m.nv, m.off, m.nf, m.idx, m.ni, scratch, su, pts, sp,
                                outp, 25, outo, 24, outi, 96, &sizes, NULL, &element),
                 NLS_STATUS_BUFFER_TOO_SMALL);
    CHECK(element == NLS_MESH_BUFFER_POSITIONS);
    CHECK(sizes.vertex_count == 26 && sizes.face_count == 24 && sizes.index_count == 96);
    for (k = 0; k < 3 * 25 * sizeof(double); k++) untouched &= ((unsigned char *)outp)[k] == 0x5a;
    CHECK(untouched);
    free(scratch);
    free(pts);
    free(outp);
    free(outo);
    free(outi);
    mesh_free(&m);
}

int main(void) {
    test_constant_and_sizes();
    test_torus_rows();
    test_statuses();
    return nls_summary("test_spherelike");
}
