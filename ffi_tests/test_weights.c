/* C99 tests of per-vertex weights of the Möbius–linear spectrum (seed 000 §7.2) through
 * nls_subdivide_options.linear_weights (the weight u of the linear result at each input
 * vertex), with nls_mesh_plan, nls_mesh_subdivide and nls_mesh_subdivide_tagged.
 *
 * Expected values come from the definition, not from recorded output:
 *  - NULL weights and weights all equal to linear_weight give the global weight's bits; all
 *    0 is the Möbius result, all 1 the linear one, bit for bit;
 *  - one level with mixed weights: an old vertex (Catmull–Clark keeps them at their
 *    indices) is (1 - u) Möbius + u linear at its own weight, an edge point at the mean of its
 *    ends' weights (an edge of two vertices of weight 0 is the Möbius edge point exactly);
 *  - the tagged call takes the weights too (all equal = the global weight);
 *  - a weight that is NaN or outside [0, 1] is NLS_STATUS_INVALID_ARGUMENT naming the
 *    vertex, from the plan and from the subdivision, and nothing is written; a misaligned
 *    array is NLS_STATUS_MISALIGNED_POINTER; an array inside an output or scratch buffer is
 *    NLS_STATUS_ALIASING_BUFFERS.
 * Run under ASan+UBSan and valgrind like every C suite. */
#include <stdint.h>
#include <stdlib.h>

#include "nlsubdiv.h"
#include "check.h"

/* A 4 x 4 quad grid (25 vertices) bent into a saddle: Möbius and linear differ. */
#define GN 4
#define NV ((GN + 1) * (GN + 1))
#define NF (GN * GN)

static double P[3 * NV];
static uint32_t OFF[NF + 1], IDX[4 * NF];

static void make_grid(void) {
    int i, j, f = 0;
    for (j = 0; j <= GN; j++) {
        for (i = 0; i <= GN; i++) {
            double x = i / (double)GN, y = j / (double)GN;
            double *p = P + 3 * (j * (GN + 1) + i);
            p[0] = x + 0.02 * ((i * 7 + j * 3) % 5);
            p[1] = y;
            p[2] = 0.4 * (x * x - y * y) + 0.1 * x * y;
        }
    }
    OFF[0] = 0;
    for (j = 0; j < GN; j++) {
        for (i = 0; i < GN; i++) {
            uint32_t v = (uint32_t)(j * (GN + 1) + i);
            IDX[4 * f + 0] = v;
            IDX[4 * f + 1] = v + 1;
            IDX[4 * f + 2] = v + GN + 2;
            IDX[4 * f + 3] = v + GN + 1;
            f++;
            OFF[f] = (uint32_t)(4 * f);
        }
    }
}

typedef struct {
    nls_status plan_status, status;
    uint32_t plan_element, element;
    size_t nv;
    double *p; /* 3 * nv, or NULL */
} result;

/* Plan and subdivide (tagged when tags is not NULL) with the options; the output positions
 * start as NaN so an unwritten one shows. `alias` (when not NULL) is set to point into the
 * output positions (0) or the point scratch (1) before the call. */
static result run(const nls_subdivide_options *o, const nls_tags *tags, int alias) {
    result r;
    nls_mesh_view m;
    nls_plan plan;
    nls_mesh_sizes sizes;
    nls_subdivide_options oo = *o;
    size_t nsu = 1u << 15, nsp = 1u << 13, cap = 1024, k;
    uint32_t *su = (uint32_t *)malloc(nsu * sizeof *su);
    double *sp = (double *)malloc(3 * nsp * sizeof *sp);
    double *op = (double *)malloc(3 * cap * sizeof *op);
    uint32_t *of = (uint32_t *)malloc((cap + 1) * sizeof *of), *oi = (uint32_t *)malloc(4 * cap * sizeof *oi);
    nls_scratch sc;
    nls_mesh_buffers b;
    m.positions = P;
    m.vertex_count = NV;
    m.positions_stride = 0;
    m.offsets = OFF;
    m.face_count = NF;
    m.indices = IDX;
    m.index_count = 4 * NF;
    for (k = 0; k < 3 * cap; k++) op[k] = NAN;
    if (alias == 0) {
        for (k = 0; k < NV; k++) op[k] = 0.5;
        oo.linear_weights = op;
    } else if (alias == 1) {
        for (k = 0; k < NV; k++) sp[k] = 0.5;
        oo.linear_weights = sp;
    }
    r.plan_element = r.element = 4242;
    r.plan_status = tags ? nls_mesh_plan_tagged(&m, &oo, tags, su, nsu, &plan, &r.plan_element)
                         : nls_mesh_plan(&m, &oo, su, nsu, &plan, &r.plan_element);
    sc.u32s = su;
    sc.u32_capacity = nsu;
    sc.points = sp;
    sc.point_capacity = nsp;
    b.positions = op;
    b.vertex_capacity = cap;
    b.offsets = of;
    b.face_capacity = cap;
    b.indices = oi;
    b.index_capacity = 4 * cap;
    sizes.vertex_count = 0;
    r.status = tags ? nls_mesh_subdivide_tagged(&m, &oo, tags, &sc, &b, &sizes, NULL, &r.element)
                    : nls_mesh_subdivide(&m, &oo, &sc, &b, &sizes, NULL, &r.element);
    r.nv = 0;
    r.p = NULL;
    if (r.status == NLS_STATUS_OK) {
        r.nv = sizes.vertex_count;
        r.p = op;
    } else {
        /* Nothing written: every position is still NaN (past the aliased weights). */
        int untouched = 1;
        for (k = alias == 0 ? NV : 0; k < 3 * cap; k++) untouched &= op[k] != op[k];
        CHECK(untouched);
        free(op);
    }
    free(su);
    free(sp);
    free(of);
    free(oi);
    return r;
}

static nls_subdivide_options options(uint32_t flags, uint32_t levels, double u, const double *w) {
    nls_subdivide_options o;
    nls_subdivide_default_options(&o);
    o.scheme = NLS_SCHEME_CATMULL_CLARK;
    o.flags = flags;
    o.levels = levels;
    o.linear_weight = u;
    o.linear_weights = w;
    return o;
}

static int same(const result *a, const result *b) {
    return a->status == NLS_STATUS_OK && b->status == NLS_STATUS_OK && a->nv == b->nv &&
           memcmp(a->p, b->p, 3 * a->nv * sizeof(double)) == 0;
}

static void test_uniform_weights_are_the_global_weight(void) {
    const double us[4] = {0.0, 1.0, 0.3, 0.75};
    double w[NV];
    int k;
    size_t v;
    nls_subdivide_options lo = options(0, 2, 0.0, NULL);
    result lin = run(&lo, NULL, -1);
    for (k = 0; k < 4; k++) {
        nls_subdivide_options g = options(NLS_SUBDIVIDE_MOBIUS, 2, us[k], NULL);
        nls_subdivide_options o = options(NLS_SUBDIVIDE_MOBIUS, 2, 0.0, w);
        result a, b;
        for (v = 0; v < NV; v++) w[v] = us[k];
        a = run(&g, NULL, -1);
        b = run(&o, NULL, -1);
        CHECK(same(&a, &b));
        if (us[k] == 1.0) CHECK(same(&b, &lin));
        free(a.p);
        free(b.p);
    }
    free(lin.p);
}

/* Catmull–Clark's edge points follow the old vertices in (min, max) edge order: the first
 * edge is (0, 1). */
static void test_one_level_blends_at_the_carried_weight(void) {
    double w[NV];
    size_t v;
    int k;
    nls_subdivide_options lo = options(0, 1, 0.0, NULL), mo = options(NLS_SUBDIVIDE_MOBIUS, 1, 0.0, NULL);
    nls_subdivide_options o = options(NLS_SUBDIVIDE_MOBIUS, 1, 0.0, w);
    result lin = run(&lo, NULL, -1), mob = run(&mo, NULL, -1), got;
    for (v = 0; v < NV; v++) w[v] = (double)(v % 4) / 3.0;
    w[0] = w[1] = 0.0;
    got = run(&o, NULL, -1);
    CHECK(got.status == NLS_STATUS_OK && got.nv == lin.nv);
    if (got.status == NLS_STATUS_OK) {
        int ok = 1, differ = 0;
        for (v = 0; v < NV; v++) {
            for (k = 0; k < 3; k++) {
                double want = (1.0 - w[v]) * mob.p[3 * v + k] + w[v] * lin.p[3 * v + k];
                ok &= fabs(got.p[3 * v + k] - want) <= 1e-14 * (1.0 + fabs(want));
                differ |= mob.p[3 * v + k] != lin.p[3 * v + k];
            }
        }
        CHECK(ok && differ);
        /* Edge (0, 1), both of weight 0: the Möbius edge point exactly. */
        CHECK(memcmp(got.p + 3 * NV, mob.p + 3 * NV, 3 * sizeof(double)) == 0);
        CHECK(memcmp(mob.p + 3 * NV, lin.p + 3 * NV, 3 * sizeof(double)) != 0);
    }
    free(got.p);
    free(lin.p);
    free(mob.p);
}

static void test_tagged(void) {
    const uint32_t crease[2] = {6, 7};
    const double sharp[1] = {10.0};
    double w[NV];
    size_t v;
    nls_tags t;
    nls_subdivide_options g = options(NLS_SUBDIVIDE_MOBIUS, 2, 0.4, NULL), o = options(NLS_SUBDIVIDE_MOBIUS, 2, 0.0, w);
    result a, b;
    memset(&t, 0, sizeof t);
    t.crease_vertices = crease;
    t.crease_sharpness = sharp;
    t.crease_count = 1;
    for (v = 0; v < NV; v++) w[v] = 0.4;
    a = run(&g, &t, -1);
    b = run(&o, &t, -1);
    CHECK(same(&a, &b));
    free(a.p);
    free(b.p);
}

static void test_statuses(void) {
    const double bad[5] = {NAN, -0.25, 1.5, INFINITY, -INFINITY};
    double w[NV + 1];
    int k;
    size_t v;
    for (k = 0; k < 5; k++) {
        nls_subdivide_options o = options(NLS_SUBDIVIDE_MOBIUS, 2, 0.0, w);
        result r;
        for (v = 0; v < NV; v++) w[v] = 0.5;
        w[9] = w[12] = bad[k];
        r = run(&o, NULL, -1);
        CHECK_STATUS(r.plan_status, NLS_STATUS_INVALID_ARGUMENT);
        CHECK_STATUS(r.status, NLS_STATUS_INVALID_ARGUMENT);
        CHECK(r.plan_element == 9 && r.element == 9);
    }
    {
        /* Misaligned: one byte into the array. */
        nls_subdivide_options o = options(NLS_SUBDIVIDE_MOBIUS, 1, 0.0, (const double *)(const void *)((const char *)w + 1));
        result r = run(&o, NULL, -1);
        CHECK_STATUS(r.plan_status, NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(r.status, NLS_STATUS_MISALIGNED_POINTER);
    }
    {
        /* Inside the output positions, inside the point scratch. */
        nls_subdivide_options o = options(NLS_SUBDIVIDE_MOBIUS, 1, 0.0, NULL);
        result r0 = run(&o, NULL, 0), r1 = run(&o, NULL, 1);
        CHECK_STATUS(r0.status, NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(r1.status, NLS_STATUS_ALIASING_BUFFERS);
    }
}

int main(void) {
    make_grid();
    test_uniform_weights_are_the_global_weight();
    test_one_level_blends_at_the_carried_weight();
    test_tagged();
    test_statuses();
    return nls_summary("test_weights");
}
