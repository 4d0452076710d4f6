/* C99 tests of the host-driven parallel form of nls_mesh_subdivide (nls_subdivide_options.executor):
 * a host's pool runs the tasks of each pass. Expected values are not recorded output: the
 * library promises the same bits as with no executor, so every result is compared with the
 * NULL-executor call of the same input, bit for bit, for every scheme, linear and Möbius,
 * 1 to 3 levels, with
 *  - a pthread pool of 1, 2, 3 and 7 threads (tasks dealt round-robin, run concurrently),
 *  - the public persistent pool of nlsubdiv_pool.h with 1, 2, 3, 7, all and 64 threads,
 *  - a serial executor that runs the tasks in reverse order, with max_tasks 2, 5, 64 and 1000,
 *  - a host that calls one task twice or an index out of range (ignored: same bits);
 * a host that skips a task gets NLS_STATUS_INVALID_ARGUMENT, as does max_tasks > 1 with a
 * NULL run; a pool whose threads round upward gets NLS_STATUS_FP_ENVIRONMENT (the tasks check
 * their own thread's modes). Run under ASan+UBSan and valgrind like every C suite (helgrind
 * is not run). */
#define _POSIX_C_SOURCE 200809L
#include <fenv.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>

#include "nlsubdiv.h"
#include "nlsubdiv_pool.h"
#include "check.h"

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
}

/* An n × m quad torus with uneven rows (no symmetry that could hide a misplaced chunk). */
static mesh torus(size_t n, size_t m) {
    mesh t;
    size_t i, j, k = 0;
    t.nv = n * m;
    t.nf = n * m;
    t.ni = 4 * t.nf;
    t.p = (double *)malloc(3 * t.nv * sizeof(double));
    t.off = (uint32_t *)malloc((t.nf + 1) * sizeof(uint32_t));
    t.idx = (uint32_t *)malloc(t.ni * sizeof(uint32_t));
    for (j = 0; j < m; j++) {
        for (i = 0; i < n; i++) {
            double u = 6.283185307179586 * ((double)i + 0.3 * sin((double)i)) / (double)n;
            double v = 6.283185307179586 * ((double)j + 0.2 * cos((double)j)) / (double)m;
            double r = 2.0 + 0.7 * cos(v);
            t.p[3 * (j * n + i) + 0] = r * cos(u);
            t.p[3 * (j * n + i) + 1] = r * sin(u);
            t.p[3 * (j * n + i) + 2] = 0.7 * sin(v);
        }
    }
    t.off[0] = 0;
    for (j = 0; j < m; j++) {
        for (i = 0; i < n; i++) {
            t.idx[k++] = (uint32_t)(j * n + i);
            t.idx[k++] = (uint32_t)(j * n + (i + 1) % n);
            t.idx[k++] = (uint32_t)(((j + 1) % m) * n + (i + 1) % n);
            t.idx[k++] = (uint32_t)(((j + 1) % m) * n + i);
            t.off[j * n + i + 1] = (uint32_t)k;
        }
    }
    return t;
}

/* The torus split into triangles (Loop, Butterfly). */
static mesh triangulate(const mesh *q) {
    mesh t;
    size_t f, k = 0;
    t.nv = q->nv;
    t.nf = 2 * q->nf;
    t.ni = 3 * t.nf;
    t.p = (double *)malloc(3 * t.nv * sizeof(double));
    memcpy(t.p, q->p, 3 * t.nv * sizeof(double));
    t.off = (uint32_t *)malloc((t.nf + 1) * sizeof(uint32_t));
    t.idx = (uint32_t *)malloc(t.ni * sizeof(uint32_t));
    t.off[0] = 0;
    for (f = 0; f < q->nf; f++) {
        const uint32_t *c = &q->idx[4 * f];
        t.idx[k++] = c[0];
        t.idx[k++] = c[1];
        t.idx[k++] = c[2];
        t.off[2 * f + 1] = (uint32_t)k;
        t.idx[k++] = c[0];
        t.idx[k++] = c[2];
        t.idx[k++] = c[3];
        t.off[2 * f + 2] = (uint32_t)k;
    }
    return t;
}

/* ---- executors ---------------------------------------------------------------------- */

/* A pthread pool: `threads` workers, worker w runs tasks w, w + threads, ... */
typedef struct {
    unsigned threads;
    int round_upward; /* the worker threads (not the caller) run with FE_UPWARD */
    unsigned long calls;
} pool;
typedef struct {
    nls_task_fn task;
    void *ctx;
    uint32_t count, first, step;
    int round_upward;
} work;
static void *worker(void *arg) {
    work *w = (work *)arg;
    uint32_t i;
    int saved = fegetround();
    if (w->round_upward) fesetround(FE_UPWARD);
    for (i = w->first; i < w->count; i += w->step) w->task(w->ctx, i);
    fesetround(saved);
    return NULL;
}
static void pool_run(void *host, uint32_t count, nls_task_fn task, void *ctx) {
    pool *p = (pool *)host;
    pthread_t tid[16];
    work w[16];
    unsigned k, n = p->threads < 16 ? p->threads : 16;
    p->calls++;
    for (k = 0; k < n; k++) {
        w[k].round_upward = k > 0 && p->round_upward;
        w[k].task = task;
        w[k].ctx = ctx;
        w[k].count = count;
        w[k].first = k;
        w[k].step = n;
        if (k > 0 && pthread_create(&tid[k], NULL, worker, &w[k]) != 0) abort();
    }
    worker(&w[0]); /* the calling thread is worker 0 */
    for (k = 1; k < n; k++) pthread_join(tid[k], NULL);
}

/* Serial, in reverse order; counts its calls (the passes it was given). */
static unsigned long reverse_calls;
static void reverse_run(void *host, uint32_t count, nls_task_fn task, void *ctx) {
    uint32_t i;
    (void)host;
    reverse_calls++;
    for (i = count; i > 0; i--) task(ctx, i - 1);
}

/* Contract breaches: mode 0 calls task 0 twice and index `count`; mode 1 skips the last task. */
static int breach_mode;
static void breach_run(void *host, uint32_t count, nls_task_fn task, void *ctx) {
    uint32_t i;
    (void)host;
    for (i = 0; i < count; i++) {
        if (breach_mode == 1 && i + 1 == count) continue;
        task(ctx, i);
    }
    if (breach_mode == 0) {
        task(ctx, 0);
        task(ctx, count);
        task(ctx, 0xffffffffu);
    }
}

/* ---- one call ----------------------------------------------------------------------- */

static nls_status run(const mesh *m, uint32_t scheme, uint32_t flags, uint32_t levels, const nls_executor *ex, mesh *out,
                      nls_subdivide_report *rep) {
    nls_mesh_view v;
    nls_subdivide_options o;
    nls_plan plan;
    nls_scratch sc;
    nls_mesh_buffers b;
    nls_mesh_sizes w;
    size_t su0 = 0;
    uint32_t *s0, *su;
    double *sp;
    uint32_t el = 0;
    nls_status s;
    v.positions = m->p;
    v.vertex_count = m->nv;
    v.positions_stride = 0;
    v.offsets = m->off;
    v.face_count = m->nf;
    v.indices = m->idx;
    v.index_count = m->ni;
    nls_subdivide_default_options(&o);
    o.scheme = scheme;
    o.flags = flags;
    o.levels = levels;
    o.executor = ex;
    out->p = NULL;
    out->off = NULL;
    out->idx = NULL;
    if (nls_mesh_plan_scratch_size(&v, &su0) != NLS_STATUS_OK) return NLS_STATUS_INVALID_ARGUMENT;
    s0 = (uint32_t *)malloc(su0 * sizeof(uint32_t) + 4);
    s = nls_mesh_plan(&v, &o, s0, su0, &plan, &el);
    free(s0);
    if (s != NLS_STATUS_OK) return s;
    su = (uint32_t *)malloc(plan.scratch_u32 * sizeof(uint32_t) + 4);
    sp = (double *)malloc(3 * plan.scratch_points * sizeof(double) + 8);
    out->nv = plan.output.vertex_count;
    out->nf = plan.output.face_count;
    out->ni = plan.output.index_count;
    out->p = (double *)malloc(3 * out->nv * sizeof(double));
    out->off = (uint32_t *)malloc((out->nf + 1) * sizeof(uint32_t));
    out->idx = (uint32_t *)malloc(out->ni * sizeof(uint32_t));
    sc.u32s = su;
    sc.u32_capacity = plan.scratch_u32;
    sc.points = sp;
    sc.point_capacity = plan.scratch_points;
    b.positions = out->p;
    b.vertex_capacity = out->nv;
    b.offsets = out->off;
    b.face_capacity = out->nf;
    b.indices = out->idx;
    b.index_capacity = out->ni;
    s = nls_mesh_subdivide(&v, &o, &sc, &b, &w, rep, &el);
    free(su);
    free(sp);
    return s;
}

static int same(const mesh *a, const mesh *b, const nls_subdivide_report *ra, const nls_subdivide_report *rb) {
    return a->nv == b->nv && a->nf == b->nf && a->ni == b->ni && memcmp(a->p, b->p, 3 * a->nv * sizeof(double)) == 0 &&
           memcmp(a->off, b->off, (a->nf + 1) * sizeof(uint32_t)) == 0 && memcmp(a->idx, b->idx, a->ni * sizeof(uint32_t)) == 0 &&
           memcmp(ra, rb, sizeof *ra) == 0;
}

static void test_same_bits(void) {
    mesh quads = torus(13, 9), tris = triangulate(&quads);
    static const uint32_t schemes[] = {NLS_SCHEME_LOOP,       NLS_SCHEME_CATMULL_CLARK,   NLS_SCHEME_MODIFIED_BUTTERFLY,
                                       NLS_SCHEME_KOBBELT,    NLS_SCHEME_DOO_SABIN,       NLS_SCHEME_SIMPLEST,
                                       NLS_SCHEME_DUAL,       NLS_SCHEME_VERTEX_INSERTION, NLS_SCHEME_DUAL_TRUNCATION,
                                       NLS_SCHEME_SPHERELIKE};
    static const unsigned threads[] = {1, 2, 3, 7};
    static const uint32_t tasks[] = {2, 5, 64, 1000};
    size_t s, k;
    uint32_t levels, mob;
    for (s = 0; s < sizeof schemes / sizeof schemes[0]; s++) {
        const uint32_t sch = schemes[s];
        const mesh *m = (sch == NLS_SCHEME_LOOP || sch == NLS_SCHEME_MODIFIED_BUTTERFLY) ? &tris : &quads;
        for (mob = 0; mob < 2; mob++) {
            const uint32_t flags = mob ? NLS_SUBDIVIDE_MOBIUS : 0;
            if (mob && sch == NLS_SCHEME_SPHERELIKE) continue;
            for (levels = 1; levels <= 3; levels += 2) {
                mesh ref, got;
                nls_subdivide_report rref, rgot;
                int ok = 1;
                CHECK_STATUS(run(m, sch, flags, levels, NULL, &ref, &rref), NLS_STATUS_OK);
                for (k = 0; k < sizeof threads / sizeof threads[0]; k++) {
                    pool p;
                    nls_executor ex;
                    p.threads = threads[k];
                    p.round_upward = 0;
                    p.calls = 0;
                    ex.run = pool_run;
                    ex.host_context = &p;
                    ex.max_tasks = 2 * threads[k] + 1;
                    CHECK_STATUS(run(m, sch, flags, levels, &ex, &got, &rgot), NLS_STATUS_OK);
                    ok &= same(&ref, &got, &rref, &rgot);
                    ok &= p.calls > 0; /* this scheme's passes went to the pool */
                    mesh_free(&got);
                }
                for (k = 0; k < sizeof threads / sizeof threads[0]; k++) {
                    /* The public persistent pool (nlsubdiv_pool.h), used twice. */
                    nls_pool np;
                    int rep;
                    CHECK(nls_pool_init(&np, threads[k]) == 0);
                    CHECK((nls_pool_executor(&np) == NULL) == (threads[k] == 1));
                    for (rep = 0; rep < 2; rep++) {
                        CHECK_STATUS(run(m, sch, flags, levels, nls_pool_executor(&np), &got, &rgot), NLS_STATUS_OK);
                        ok &= same(&ref, &got, &rref, &rgot);
                        mesh_free(&got);
                    }
                    nls_pool_destroy(&np);
                }
                for (k = 0; k < sizeof tasks / sizeof tasks[0]; k++) {
                    nls_executor ex;
                    ex.run = reverse_run;
                    ex.host_context = NULL;
                    ex.max_tasks = tasks[k];
                    CHECK_STATUS(run(m, sch, flags, levels, &ex, &got, &rgot), NLS_STATUS_OK);
                    ok &= same(&ref, &got, &rref, &rgot);
                    mesh_free(&got);
                }
                if (!ok) fprintf(stderr, "scheme %u flags %u levels %u: executor output differs\n", sch, flags, levels);
                CHECK(ok);
                mesh_free(&ref);
            }
        }
    }
    CHECK(reverse_calls > 100); /* the passes were handed to the host, not run inline */
    mesh_free(&quads);
    mesh_free(&tris);
}

static void test_contract_breaches(void) {
    mesh m = torus(13, 9), ref, got;
    nls_subdivide_report rref, rgot;
    nls_executor ex;
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, NULL, &ref, &rref), NLS_STATUS_OK);
    ex.run = breach_run;
    ex.host_context = NULL;
    ex.max_tasks = 6;
    breach_mode = 0; /* duplicates and out-of-range indices: ignored */
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, &ex, &got, &rgot), NLS_STATUS_OK);
    CHECK(same(&ref, &got, &rref, &rgot));
    mesh_free(&got);
    breach_mode = 1; /* a skipped task: the call fails */
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, &ex, &got, &rgot), NLS_STATUS_INVALID_ARGUMENT);
    mesh_free(&got);
    ex.run = NULL; /* no run with max_tasks > 1 */
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, 0, 1, &ex, &got, &rgot), NLS_STATUS_INVALID_ARGUMENT);
    mesh_free(&got);
    {
        /* The pool's worker threads round upward: the tasks refuse, the call says why. */
        pool p;
        nls_executor px;
        p.threads = 3;
        p.round_upward = 1;
        p.calls = 0;
        px.run = pool_run;
        px.host_context = &p;
        px.max_tasks = 6;
        CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, &px, &got, &rgot), NLS_STATUS_FP_ENVIRONMENT);
        mesh_free(&got);
        CHECK(fegetround() == FE_TONEAREST);
    }
    ex.max_tasks = 1; /* one task: the calling thread, run never called */
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, &ex, &got, &rgot), NLS_STATUS_OK);
    CHECK(same(&ref, &got, &rref, &rgot));
    mesh_free(&got);
    mesh_free(&ref);
    mesh_free(&m);
}

/* nls_pool_init(0) takes the online cores; an error from the pool's start is not reached here,
 * but a pool of the maximal size is, and its executor asks for one task per thread. */
static void test_public_pool(void) {
    mesh m = torus(13, 9), ref, got;
    nls_subdivide_report rref, rgot;
    nls_pool np;
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, NULL, &ref, &rref), NLS_STATUS_OK);
    CHECK(nls_pool_init(&np, 0) == 0);
    CHECK(nls_max_tasks() >= 1 && nls_max_tasks() <= NLS_MAX_TASKS);
    CHECK(np.threads == (cores > 1 ? (cores < (long)nls_max_tasks() ? (unsigned)cores : nls_max_tasks()) : 1u));
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, nls_pool_executor(&np), &got, &rgot), NLS_STATUS_OK);
    CHECK(same(&ref, &got, &rref, &rgot));
    mesh_free(&got);
    nls_pool_destroy(&np);
    nls_pool_destroy(&np); /* harmless twice */
    CHECK(nls_pool_init(&np, 1000) == 0);
    CHECK(np.threads == nls_max_tasks() && nls_pool_executor(&np)->max_tasks == nls_max_tasks());
    CHECK_STATUS(run(&m, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, nls_pool_executor(&np), &got, &rgot), NLS_STATUS_OK);
    CHECK(same(&ref, &got, &rref, &rgot));
    mesh_free(&got);
    nls_pool_destroy(&np);
    mesh_free(&ref);
    mesh_free(&m);
}

int main(void) {
    test_same_bits();
    test_public_pool();
    test_contract_breaches();
    return nls_summary("test_executor");
}
