/* C99 tests of the differential-space exports of nlsubdiv.h (seed 001): bad input with its
 * status and element, non-convergence under a tiny iteration cap (report written, counts
 * not), too-small scratch and output buffers (the needed sizes written, outputs untouched),
 * and successful runs checked against the mathematics: levels = 0 reproduces the control
 * mesh, a closed mesh's result is translation-invariant, the placement matches the centroid
 * of the spatial subdivision, and the connectivity is that of the spatial subdivision.
 * Run under ASan+UBSan and valgrind. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "nlsubdiv.h"
#include "check.h"
#include "flat_args.h"

typedef struct {
    size_t nv, nf, ni;
    double p[3 * 6];
    uint32_t off[9];
    uint32_t idx[24];
} octa;

/* A jittered octahedron (closed, genus 0, counter-clockwise from outside). */
static octa octahedron(void) {
    static const double P[18] = {1.0, 0.05, -0.02, -0.97, 0.0, 0.03, 0.02, 1.1, 0.0,
                                 0.0, -1.0, 0.04, -0.03, 0.01, 0.9, 0.0, 0.02, -1.05};
    static const uint32_t F[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    octa m;
    size_t i;
    m.nv = 6;
    m.nf = 8;
    m.ni = 24;
    memcpy(m.p, P, sizeof P);
    memcpy(m.idx, F, sizeof F);
    for (i = 0; i <= 8; i++) m.off[i] = (uint32_t)(3 * i);
    return m;
}

typedef struct {
    size_t nv, nf, ni;
    double *p;
    uint32_t *off;
    uint32_t *idx;
    nls_differential_report rep;
    uint32_t element;
} result;

static void result_free(result *r) {
    free(r->p);
    free(r->off);
    free(r->idx);
    r->p = NULL;
    r->off = NULL;
    r->idx = NULL;
}

/* Plans and runs one call with exactly sized buffers (minus `short_points` points of scratch). */
static nls_status run(const double *p, size_t nv, const uint32_t *off, size_t nf, const uint32_t *idx, size_t ni,
                      const nls_differential_options *o, size_t short_points, result *r) {
    size_t su0 = 0, su = 0, sp = 0, onv = 0, onf = 0, oni = 0;
    uint32_t *scratch_u32;
    double *scratch_points;
    nls_plan plan;
    nls_mesh_sizes w = {999, 999, 999};
    nls_status s;
    r->p = NULL;
    r->off = NULL;
    r->idx = NULL;
    r->element = 12345;
    CHECK_STATUS(flat_plan_scratch_size(nv, ni, &su0), NLS_STATUS_OK);
    scratch_u32 = (uint32_t *)malloc(su0 * sizeof(uint32_t) + 1);
    s = flat_diff_plan(p, nv, off, nf, idx, ni, o, scratch_u32, su0, &plan, &r->element);
    free(scratch_u32);
    if (s != NLS_STATUS_OK) return s;
    onv = plan.output.vertex_count;
    onf = plan.output.face_count;
    oni = plan.output.index_count;
    su = plan.scratch_u32;
    sp = plan.scratch_points;
    CHECK(su >= su0);
    scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t));
    scratch_points = (double *)malloc(3 * (sp - short_points) * sizeof(double) + 1);
    r->p = (double *)malloc(3 * onv * sizeof(double));
    r->off = (uint32_t *)malloc((onf + 1) * sizeof(uint32_t));
    r->idx = (uint32_t *)malloc(oni * sizeof(uint32_t));
    r->p[0] = 777.0;
    r->nv = r->nf = r->ni = 999;
    r->rep.iterations = 999;
    s = flat_diff_subdivide(p, nv, off, nf, idx, ni, o, scratch_u32, su, scratch_points, sp - short_points, r->p, onv,
                            r->off, onf, r->idx, oni, &w, &r->rep, &r->element);
    r->nv = w.vertex_count;
    r->nf = w.face_count;
    r->ni = w.index_count;
    if (s == NLS_STATUS_OK) CHECK(r->nv == onv && r->nf == onf && r->ni == oni);
    free(scratch_u32);
    free(scratch_points);
    return s;
}

static nls_differential_options defaults(uint32_t scheme, uint32_t levels) {
    nls_differential_options o;
    CHECK_STATUS(nls_differential_default_options(&o), NLS_STATUS_OK);
    o.scheme = scheme;
    o.levels = levels;
    o.dirmag_levels = scheme == NLS_DIFFERENTIAL_DIRMAG ? 1u : 0u;
    return o;
}

static void test_bad_input(void) {
    octa m = octahedron();
    result r;
    nls_differential_options o = defaults(NLS_DIFFERENTIAL_LOOP, 1);
    double bad_scale[6] = {1, 1, 1, NAN, 1, 1};
    size_t su = 777;
    /* NULL only with a count of 0 */
    CHECK_STATUS(nls_differential_default_options(NULL), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(flat_plan_scratch_size(6, 24, NULL), NLS_STATUS_NULL_PARAMETER);
    CHECK(o.strict == 0);
    /* strict is 0 or 1; without edits it changes nothing */
    o.strict = 2;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INVALID_ARGUMENT);
    o.strict = 1;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_OK);
    CHECK(r.rep.folded_faces == 0 && r.rep.first_folded_face == NLS_NO_ELEMENT && r.rep.folded_edges == 0);
    result_free(&r);
    {
        /* A strongly negative curvature turns vertex 0's neighbourhood inside out: counted
         * without strict, NLS_STATUS_FOLDED_SURFACE naming the first folded face with it. */
        static const double fold_scale[6] = {-20, 1, 1, 1, 1, 1};
        nls_differential_options f = defaults(NLS_DIFFERENTIAL_LOOP, 2);
        uint32_t counted = 0, first = 0;
        f.curvature_scale = fold_scale;
        CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &f, 0, &r), NLS_STATUS_OK);
        counted = r.rep.folded_faces;
        first = r.rep.first_folded_face;
        CHECK(counted > 0 && first != NLS_NO_ELEMENT);
        result_free(&r);
        f.strict = 1;
        r.element = 0;
        CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &f, 0, &r), NLS_STATUS_FOLDED_SURFACE);
        CHECK(r.element == first && r.rep.folded_faces == counted);
        result_free(&r);
    }
    o.strict = 0;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, NULL, 0, &r), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(run(NULL, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_NULL_PARAMETER);
    /* unknown scheme, DirMag levels not matching the scheme, too many levels, bad tolerance */
    o.scheme = 7;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INVALID_ARGUMENT);
    CHECK(r.element == NLS_NO_ELEMENT);
    o = defaults(NLS_DIFFERENTIAL_LOOP, 1);
    o.dirmag_levels = 1;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INVALID_ARGUMENT);
    o = defaults(NLS_DIFFERENTIAL_DIRMAG, 1);
    o.dirmag_levels = 0;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INVALID_ARGUMENT);
    o = defaults(NLS_DIFFERENTIAL_LOOP, NLS_MAX_LEVELS + 1);
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INVALID_ARGUMENT);
    o = defaults(NLS_DIFFERENTIAL_LOOP, 1);
    o.tolerance = NAN;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INVALID_ARGUMENT);
    o.tolerance = -1.0;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INVALID_ARGUMENT);
    /* a non-finite edit value names its vertex */
    o = defaults(NLS_DIFFERENTIAL_LOOP, 1);
    o.curvature_scale = bad_scale;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_NON_FINITE_INPUT);
    CHECK(r.element == 3);
    /* misaligned edit array */
    o.curvature_scale = (const double *)((const char *)bad_scale + 1);
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_MISALIGNED_POINTER);
    /* not a triangle mesh: two triangles of the octahedron glued as one quad */
    {
        uint32_t off[3] = {0, 4, 7};
        uint32_t idx[7] = {0, 2, 1, 3, 0, 3, 4};
        o = defaults(NLS_DIFFERENTIAL_BUTTERFLY, 1);
        CHECK_STATUS(run(m.p, m.nv, off, 2, idx, 7, &o, 0, &r), NLS_STATUS_UNSUPPORTED_FACE_TYPE);
        CHECK(r.element == 0);
    }
    /* a bad index is named */
    m.idx[5] = 6;
    o = defaults(NLS_DIFFERENTIAL_LOOP, 1);
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_INDEX_OUT_OF_RANGE);
    CHECK(r.element == 1);
    CHECK(su == 777);
}

static void test_not_converged_and_small_buffers(void) {
    octa m = octahedron();
    result r;
    nls_differential_options o = defaults(NLS_DIFFERENTIAL_LOOP, 2);
    o.max_iterations = 0;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_NOT_CONVERGED);
    CHECK(r.rep.iterations == 0 && r.rep.converged == 0);
    CHECK(r.rep.relative_residual > o.tolerance && r.rep.anchors == 1);
    CHECK(r.nv == 999 && r.nf == 999 && r.ni == 999);
    result_free(&r);
    o.max_iterations = 1;
    o.tolerance = 0.0;
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &r), NLS_STATUS_NOT_CONVERGED);
    CHECK(r.rep.iterations == 1 && r.rep.converged == 0);
    result_free(&r);
    /* one point of scratch short: the buffer is named, the sizes written, outputs untouched */
    o = defaults(NLS_DIFFERENTIAL_LOOP, 2);
    CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 1, &r), NLS_STATUS_BUFFER_TOO_SMALL);
    CHECK(r.element == NLS_MESH_BUFFER_SCRATCH_POINTS);
    CHECK(r.nv == 66 && r.nf == 128 && r.ni == 384);
    CHECK(r.p[0] == 777.0 && r.rep.iterations == 999);
    result_free(&r);
    /* a short output buffer */
    {
        size_t su0 = 0, su = 0, sp = 0, nv = 0, nf = 0, ni = 0;
        nls_mesh_sizes w = {0, 0, 0};
        nls_plan plan;
        uint32_t *s32, element = 0;
        double *spt, *outp;
        uint32_t *oo, *oi;
        CHECK_STATUS(flat_plan_scratch_size(m.nv, m.ni, &su0), NLS_STATUS_OK);
        s32 = (uint32_t *)malloc(su0 * sizeof(uint32_t));
        CHECK_STATUS(flat_diff_plan(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su0, &plan, NULL), NLS_STATUS_OK);
        nv = plan.output.vertex_count;
        nf = plan.output.face_count;
        ni = plan.output.index_count;
        su = plan.scratch_u32;
        sp = plan.scratch_points;
        CHECK_STATUS(flat_diff_plan(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su0 - 1, &plan, &element),
                     NLS_STATUS_BUFFER_TOO_SMALL);
        /* the plan inside the mesh: refused */
        CHECK_STATUS(flat_diff_plan(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su0, (nls_plan *)(void *)m.p, NULL),
                     NLS_STATUS_ALIASING_BUFFERS);
        CHECK(element == NLS_MESH_BUFFER_SCRATCH_U32);
        free(s32);
        s32 = (uint32_t *)malloc(su * sizeof(uint32_t));
        spt = (double *)malloc(3 * sp * sizeof(double));
        outp = (double *)malloc(3 * (nv - 1) * sizeof(double));
        oo = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
        oi = (uint32_t *)malloc(ni * sizeof(uint32_t));
        outp[0] = 777.0;
        CHECK_STATUS(flat_diff_subdivide(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su, spt, sp, outp, nv - 1, oo, nf,
                                         oi, ni, &w, NULL, &element),
                     NLS_STATUS_BUFFER_TOO_SMALL);
        CHECK(element == NLS_MESH_BUFFER_POSITIONS && w.vertex_count == nv && w.face_count == nf &&
              w.index_count == ni && outp[0] == 777.0);
        /* aliasing: the output positions over the scratch */
        CHECK_STATUS(flat_diff_subdivide(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su, spt, sp, spt, nv, oo, nf, oi,
                                         ni, &w, NULL, &element),
                     NLS_STATUS_ALIASING_BUFFERS);
        /* out-pointers into the output or an edit array: refused, nothing written there */
        {
            double scale[6] = {1, 1, 1, 1, 1, 1};
            nls_differential_report rep;
            CHECK_STATUS(flat_diff_subdivide(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su, spt, sp, outp, nv - 1, oo,
                                             nf, oi, ni, (nls_mesh_sizes *)(void *)(outp + 3), NULL, &element),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK_STATUS(flat_diff_subdivide(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su, spt, sp, outp, nv - 1, oo,
                                             nf, oi, ni, &w, (nls_differential_report *)(void *)oi, &element),
                         NLS_STATUS_ALIASING_BUFFERS);
            o.curvature_scale = scale;
            CHECK_STATUS(flat_diff_subdivide(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, s32, su, spt, sp, outp, nv - 1, oo,
                                             nf, oi, ni, &w, &rep, (uint32_t *)(void *)(scale + 2)),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK(scale[2] == 1.0);
            o.curvature_scale = NULL;
        }
        free(s32);
        free(spt);
        free(outp);
        free(oo);
        free(oi);
    }
}

static double diameter(const double *p, size_t n) {
    double d = 0.0;
    size_t i, j;
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            double e = nls_dist3(p + 3 * i, p + 3 * j);
            if (e > d) d = e;
        }
    return d;
}

static void test_mathematics(void) {
    static const uint32_t schemes[3] = {NLS_DIFFERENTIAL_LOOP, NLS_DIFFERENTIAL_BUTTERFLY, NLS_DIFFERENTIAL_DIRMAG};
    octa m = octahedron();
    double diam = diameter(m.p, m.nv);
    size_t s, i, k;
    for (s = 0; s < 3; s++) {
        result a, b;
        octa t = m;
        nls_differential_options o = defaults(schemes[s], 0);
        double err = 0.0;
        /* levels = 0 reproduces the control mesh (placement: centroid of the input) */
        if (schemes[s] != NLS_DIFFERENTIAL_DIRMAG) {
            CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &a), NLS_STATUS_OK);
            CHECK(a.nv == m.nv && a.rep.converged == 1);
            for (i = 0; i < m.nv; i++) {
                double e = nls_dist3(a.p + 3 * i, m.p + 3 * i);
                if (e > err) err = e;
            }
            CHECK(err <= 1e-8 * diam);
            for (i = 0; i < m.ni; i++) CHECK(a.idx[i] == m.idx[i]);
            result_free(&a);
        }
        /* two levels: converged, residual below the tolerance, translation-invariant */
        o = defaults(schemes[s], 2);
        for (i = 0; i < m.nv; i++) {
            t.p[3 * i] += 10.0;
            t.p[3 * i + 1] -= 3.0;
            t.p[3 * i + 2] += 5.0;
        }
        CHECK_STATUS(run(m.p, m.nv, m.off, m.nf, m.idx, m.ni, &o, 0, &a), NLS_STATUS_OK);
        CHECK_STATUS(run(t.p, t.nv, t.off, t.nf, t.idx, t.ni, &o, 0, &b), NLS_STATUS_OK);
        CHECK(a.rep.converged == 1 && a.rep.relative_residual <= o.tolerance && a.rep.iterations > 0);
        CHECK(a.nv == 66 && b.nv == 66);
        err = 0.0;
        for (i = 0; i < a.nv; i++) {
            double q[3] = {b.p[3 * i] - 10.0, b.p[3 * i + 1] + 3.0, b.p[3 * i + 2] - 5.0};
            double e = nls_dist3(a.p + 3 * i, q);
            if (e > err) err = e;
        }
        CHECK(err <= 1e-8 * diam);
        /* placement: the centroid equals that of the spatial subdivision, same connectivity */
        {
            uint32_t spatial = schemes[s] == NLS_DIFFERENTIAL_LOOP ? NLS_SCHEME_LOOP : NLS_SCHEME_MODIFIED_BUTTERFLY;
            size_t su = 0, sp = 0, nv = 0, nf = 0, ni = 0, wv, wf, wi;
            uint32_t *s32 = (uint32_t *)malloc(1000 * sizeof(uint32_t));
            double *ps, ca[3] = {0, 0, 0}, cs[3] = {0, 0, 0};
            uint32_t *oo, *oi;
            nls_plan plan;
            nls_mesh_sizes w = {0, 0, 0};
            CHECK_STATUS(flat_plan(spatial, 0, 2, m.p, m.nv, m.off, m.nf, m.idx, m.ni, s32, 1000, &plan, NULL),
                         NLS_STATUS_OK);
            nv = plan.output.vertex_count;
            nf = plan.output.face_count;
            ni = plan.output.index_count;
            su = plan.scratch_u32;
            sp = plan.scratch_points;
            free(s32);
            s32 = (uint32_t *)malloc(su * sizeof(uint32_t));
            ps = (double *)malloc(3 * (sp + nv) * sizeof(double));
            oo = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
            oi = (uint32_t *)malloc(ni * sizeof(uint32_t));
            CHECK_STATUS(flat_subdivide(spatial, 0, 2, m.p, m.nv, m.off, m.nf, m.idx, m.ni, s32, su, ps + 3 * nv, sp, ps,
                                        nv, oo, nf, oi, ni, &w, NULL, NULL),
                         NLS_STATUS_OK);
            wv = w.vertex_count;
            wf = w.face_count;
            wi = w.index_count;
            CHECK(wv == a.nv && wf == a.nf && wi == a.ni);
            for (i = 0; i < wi && i < a.ni; i++) CHECK(oi[i] == a.idx[i]);
            for (i = 0; i < wv; i++)
                for (k = 0; k < 3; k++) {
                    ca[k] += a.p[3 * i + k] / (double)wv;
                    cs[k] += ps[3 * i + k] / (double)wv;
                }
            CHECK(nls_dist3(ca, cs) <= 1e-12 * diam);
            free(s32);
            free(ps);
            free(oo);
            free(oi);
        }
        result_free(&a);
        result_free(&b);
    }
    /* an open mesh (the octahedron without its last two faces: one boundary loop) */
    {
        result a;
        nls_differential_options o = defaults(NLS_DIFFERENTIAL_BUTTERFLY, 3);
        CHECK_STATUS(run(m.p, m.nv, m.off, 6, m.idx, 18, &o, 0, &a), NLS_STATUS_OK);
        CHECK(a.rep.converged == 1 && a.rep.anchors == 1 && a.rep.relative_residual <= o.tolerance);
        for (i = 0; i < 3 * a.nv; i++) CHECK(isfinite(a.p[i]));
        result_free(&a);
    }
}

int main(void) {
    test_bad_input();
    test_not_converged_and_small_buffers();
    test_mathematics();
    return nls_summary("test_differential");
}
