/* Every export of the C ABI in a hostile floating-point environment (docs/DECISIONS.md,
 * "Host floating-point traps"; docs/bad-input-catalogue.md, class 24).
 *
 * 1. Unmasked traps: with FE_INVALID, FE_DIVBYZERO and FE_OVERFLOW (and then every
 *    exception, FE_UNDERFLOW and FE_INEXACT too) unmasked by feenableexcept, every export
 *    returns the same status and writes the same bytes as in the default environment, on
 *    ordinary inputs and on inputs that overflow inside (points at +-1e308, Moebius meshes
 *    at 1e300, curves, the differential call) -- and the host is not killed by SIGFPE. After
 *    each call the host's traps are still enabled and no sticky flag of the library's
 *    internal (handled) exceptions is left behind.
 * 2. Modes that change results: under flush-to-zero, denormals-are-zero (x86 MXCSR) and each
 *    rounding mode other than to-nearest, every export that computes in floating point
 *    returns NLS_STATUS_FP_ENVIRONMENT; those that do not (sizes, constants, strings) return
 *    what they return in the default environment.
 *
 * The expected bytes are those of the same call in the default environment, made first. */
#define _GNU_SOURCE
#include <fenv.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "check.h"
#include "flat_args.h"
#include "nlsubdiv.h"

/* ---------------------------------------------------------------- inputs, per scale */

static double S;                  /* the scale of this round of inputs */
static double P[8][3];            /* points: a tetrahedron-like set and a few more */
static double RING[6][3];         /* a hexagonal ring around CENTRE */
static double CENTRE[3];
static double QA[4], QB[4];       /* quaternions */
static double OCTA[6][3];         /* octahedron */
static double CUBE[8][3];         /* cube */
static double CURVE[6][3];        /* closed polygon */
static double FACE_V[4][3], FACE_C[4][3];
static double SCALE_HALF;         /* S / 2 */
static double CC_RING[4][3], CC_CORNERS[4][3]; /* four quads around CENTRE */

static const uint32_t OCTA_OFF[9] = {0, 3, 6, 9, 12, 15, 18, 21, 24};
static const uint32_t OCTA_IDX[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
static const uint32_t CUBE_OFF[7] = {0, 4, 8, 12, 16, 20, 24};
static const uint32_t CUBE_IDX[24] = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 2, 3, 7, 6, 1, 2, 6, 5, 0, 4, 7, 3};

/* Fills the inputs for scale s (in the default environment: nothing here may trap). */
static void prepare(double s) {
    static const double p[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0}, {-1, 0.25, 0}, {0, -1, 0.5}, {-0.5, -0.5, -0.5}};
    static const double o[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    int i, k;
    S = s;
    SCALE_HALF = s * 0.5;
    for (i = 0; i < 8; i++)
        for (k = 0; k < 3; k++) P[i][k] = p[i][k] * s;
    CENTRE[0] = 0.01 * s;
    CENTRE[1] = -0.02 * s;
    CENTRE[2] = 0.2 * s;
    for (i = 0; i < 6; i++) {
        double ang = 6.283185307179586 * i / 6.0;
        RING[i][0] = cos(ang) * s;
        RING[i][1] = sin(ang) * s;
        RING[i][2] = (i % 2 ? 0.05 : -0.03) * s;
        CURVE[i][0] = cos(ang) * s;
        CURVE[i][1] = sin(ang) * (0.5 * s);
        CURVE[i][2] = (i % 3) * (0.1 * s);
    }
    for (i = 0; i < 6; i++)
        for (k = 0; k < 3; k++) OCTA[i][k] = o[i][k] * s;
    for (i = 0; i < 8; i++) {
        CUBE[i][0] = (i & 1 ? 1.0 : -1.0) * s;
        CUBE[i][1] = (i & 2 ? 1.0 : -1.0) * s;
        CUBE[i][2] = (i & 4 ? 1.0 : -1.0) * s;
    }
    /* cube corner order used by CUBE_IDX: 0..7 as (x,y,z) bits */
    for (i = 0; i < 4; i++) {
        double ang = 1.5707963267948966 * i;
        FACE_V[i][0] = cos(ang) * s;
        FACE_V[i][1] = sin(ang) * s;
        FACE_V[i][2] = 0;
        FACE_C[i][0] = cos(ang + 0.7853981633974483) * (0.7 * s);
        FACE_C[i][1] = sin(ang + 0.7853981633974483) * (0.7 * s);
        FACE_C[i][2] = (i % 2 ? 0.1 : -0.1) * s;
    }
    for (i = 0; i < 4; i++)
        for (k = 0; k < 3; k++) {
            CC_RING[i][k] = FACE_V[i][k];
            CC_CORNERS[i][k] = 0.5 * FACE_V[i][k] + 0.5 * FACE_V[(i + 1) % 4][k];
        }
    QA[0] = 0.5 * s; QA[1] = -0.25 * s; QA[2] = 0.125 * s; QA[3] = s;
    QB[0] = -0.75 * s; QB[1] = 0.5 * s; QB[2] = s; QB[3] = -0.125 * s;
}

/* ---------------------------------------------------------------- output capture */

#define OUT_MAX (1 << 16)
typedef struct {
    unsigned char bytes[OUT_MAX];
    size_t len;
} capture;

static void put(capture *c, const void *p, size_t n) {
    if (c->len + n <= OUT_MAX) {
        memcpy(c->bytes + c->len, p, n);
        c->len += n;
    }
}

/* Big zeroed buffers for the mesh calls (allocated once, cleared per call). */
#define BIG_U32 (1 << 16)
#define BIG_PTS (1 << 14)
static uint32_t *SU;
static double *SP, *OP;
static uint32_t *OO, *OI;

static void clear_big(void) {
    memset(SU, 0, sizeof(uint32_t) * BIG_U32);
    memset(SP, 0, sizeof(double) * 3 * BIG_PTS);
    memset(OP, 0, sizeof(double) * 3 * BIG_PTS);
    memset(OO, 0, sizeof(uint32_t) * BIG_PTS);
    memset(OI, 0, sizeof(uint32_t) * BIG_U32);
}

/* ---------------------------------------------------------------- one case per export */

typedef nls_status (*case_fn)(capture *c);

static nls_status c_version(capture *c) {
    uint32_t v = nls_version();
    put(c, &v, sizeof v);
    return NLS_STATUS_OK;
}
static nls_status c_status_str(capture *c) {
    const char *s = nls_status_str(NLS_STATUS_FP_ENVIRONMENT);
    put(c, s, strlen(s));
    return NLS_STATUS_OK;
}
static nls_status c_curve_refined_size(capture *c) {
    size_t n = 0;
    nls_status s = nls_curve_refined_size(6, 1, 3, &n);
    put(c, &n, sizeof n);
    return s;
}
static nls_status c_curve_scratch_size(capture *c) {
    size_t n = 0;
    nls_status s = nls_curve_scratch_size(NLS_CURVE_CIRCLE_BLEND, 6, 1, 3, &n);
    put(c, &n, sizeof n);
    return s;
}
static nls_status curve_case(capture *c, uint32_t scheme) {
    double out[3 * 64], scratch[3 * 256];
    size_t n = 0;
    uint32_t el = 0;
    nls_status s;
    memset(out, 0, sizeof out);
    memset(scratch, 0, sizeof scratch);
    s = flat_curve_subdivide(scheme, &CURVE[0][0], 6, 1, 3, out, 64, scratch, 256, &n, &el);
    put(c, out, sizeof out);
    put(c, &n, sizeof n);
    put(c, &el, sizeof el);
    return s;
}
static nls_status c_curve_subdivide(capture *c) { return curve_case(c, NLS_CURVE_CIRCLE_BLEND); }
static nls_status c_curve_subdivide_mob(capture *c) { return curve_case(c, NLS_CURVE_MOBIUS_INTERPOLATING); }
static nls_status c_curve_subdivide_diff(capture *c) { return curve_case(c, NLS_CURVE_DIFFERENTIAL_FOUR_POINT); }
static nls_status c_subdivide_default_options(capture *c) {
    nls_subdivide_options o;
    nls_status s;
    memset(&o, 0, sizeof o);
    s = nls_subdivide_default_options(&o);
    put(c, &o, sizeof o);
    return s;
}
static nls_status c_mesh_plan_scratch_size(capture *c) {
    size_t a = 0;
    nls_status s = flat_plan_scratch_size(6, 24, &a);
    put(c, &a, sizeof a);
    return s;
}

/* The mesh of a case: the octahedron (triangles) or the cube (quads). */
static void mesh_of(uint32_t scheme, const double **p, size_t *nv, const uint32_t **off, size_t *nf,
                    const uint32_t **idx, size_t *ni) {
    if (scheme == NLS_SCHEME_CATMULL_CLARK) {
        *p = &CUBE[0][0]; *nv = 8; *off = CUBE_OFF; *nf = 6; *idx = CUBE_IDX; *ni = 24;
    } else {
        *p = &OCTA[0][0]; *nv = 6; *off = OCTA_OFF; *nf = 8; *idx = OCTA_IDX; *ni = 24;
    }
}

static nls_status mesh_size_case(capture *c, uint32_t scheme, uint32_t flags) {
    const double *p; const uint32_t *off, *idx; size_t nv, nf, ni;
    nls_plan plan;
    uint32_t el = 0;
    nls_status s;
    memset(&plan, 0, sizeof plan);
    mesh_of(scheme, &p, &nv, &off, &nf, &idx, &ni);
    clear_big();
    s = flat_plan(scheme, flags, 1, p, nv, off, nf, idx, ni, SU, BIG_U32, &plan, &el);
    put(c, &plan, sizeof plan); put(c, &el, sizeof el);
    return s;
}
static nls_status c_mesh_plan(capture *c) { return mesh_size_case(c, NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS); }

static nls_status mesh_case(capture *c, uint32_t scheme, uint32_t flags) {
    const double *p; const uint32_t *off, *idx; size_t nv, nf, ni;
    nls_mesh_sizes sz = {0, 0, 0};
    uint32_t el = 0;
    nls_subdivide_report rep;
    nls_status s;
    memset(&rep, 0, sizeof rep);
    mesh_of(scheme, &p, &nv, &off, &nf, &idx, &ni);
    clear_big();
    s = flat_subdivide(scheme, flags, 1, p, nv, off, nf, idx, ni, SU, BIG_U32, SP, BIG_PTS, OP, BIG_PTS, OO, BIG_PTS, OI,
                       BIG_U32, &sz, &rep, &el);
    put(c, OP, sizeof(double) * 3 * 64);
    put(c, OO, sizeof(uint32_t) * 64);
    put(c, OI, sizeof(uint32_t) * 256);
    put(c, &sz, sizeof sz); put(c, &el, sizeof el);
    put(c, &rep, sizeof rep);
    return s;
}
static nls_status c_mesh_subdivide_mob_loop(capture *c) { return mesh_case(c, NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS); }
static nls_status c_mesh_subdivide_mob_cc(capture *c) { return mesh_case(c, NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS); }
static nls_status c_mesh_subdivide_mob_bf(capture *c) { return mesh_case(c, NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS); }
static nls_status c_mesh_subdivide_spherelike(capture *c) { return mesh_case(c, NLS_SCHEME_SPHERELIKE, 0); }
static nls_status c_mesh_subdivide_linear(capture *c) { return mesh_case(c, NLS_SCHEME_DOO_SABIN, 0); }

static nls_status c_mesh_plan_levels(capture *c) {
    nls_plan plan;
    uint32_t el = 0;
    nls_status s;
    memset(&plan, 0, sizeof plan);
    clear_big();
    s = flat_plan(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, 2, &OCTA[0][0], 6, OCTA_OFF, 8, OCTA_IDX, 24, SU, BIG_U32, &plan,
                  &el);
    put(c, &plan, sizeof plan);
    put(c, &el, sizeof el);
    return s;
}
static nls_status c_mesh_subdivide_levels(capture *c) {
    nls_mesh_sizes sz = {0, 0, 0};
    uint32_t el = 0;
    nls_subdivide_report rep;
    nls_status s;
    memset(&rep, 0, sizeof rep);
    clear_big();
    s = flat_subdivide(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, 2, &OCTA[0][0], 6, OCTA_OFF, 8, OCTA_IDX, 24, SU, BIG_U32, SP,
                       BIG_PTS, OP, BIG_PTS, OO, BIG_PTS, OI, BIG_U32, &sz, &rep, &el);
    put(c, OP, sizeof(double) * 3 * 66);
    put(c, OI, sizeof(uint32_t) * 384);
    put(c, &sz, sizeof sz); put(c, &el, sizeof el);
    put(c, &rep, sizeof rep);
    return s;
}
static nls_status c_differential_default_options(capture *c) {
    nls_differential_options o;
    nls_status s;
    memset(&o, 0, sizeof o);
    s = nls_differential_default_options(&o);
    put(c, &o, sizeof o);
    return s;
}
static void diff_options(nls_differential_options *o) {
    memset(o, 0, sizeof *o);
    o->scheme = NLS_DIFFERENTIAL_LOOP;
    o->levels = 1;
    o->dirmag_levels = 0;
    o->max_iterations = 100;
    o->tolerance = 1e-10;
    o->strict = 0;
}
static nls_status c_differential_plan(capture *c) {
    nls_differential_options o;
    nls_plan plan;
    uint32_t el = 0;
    nls_status s;
    diff_options(&o);
    memset(&plan, 0, sizeof plan);
    clear_big();
    s = flat_diff_plan(&OCTA[0][0], 6, OCTA_OFF, 8, OCTA_IDX, 24, &o, SU, BIG_U32, &plan, &el);
    put(c, &plan, sizeof plan);
    put(c, &el, sizeof el);
    return s;
}
static nls_status c_differential_subdivide(capture *c) {
    nls_differential_options o;
    nls_differential_report rep;
    nls_mesh_sizes sz = {0, 0, 0};
    uint32_t el = 0;
    nls_status s;
    diff_options(&o);
    memset(&rep, 0, sizeof rep);
    clear_big();
    s = flat_diff_subdivide(&OCTA[0][0], 6, OCTA_OFF, 8, OCTA_IDX, 24, &o, SU, BIG_U32, SP, BIG_PTS, OP, BIG_PTS, OO,
                            BIG_PTS, OI, BIG_U32, &sz, &rep, &el);
    put(c, OP, sizeof(double) * 3 * 18);
    put(c, OI, sizeof(uint32_t) * 96);
    put(c, &sz, sizeof sz); put(c, &el, sizeof el);
    put(c, &rep, sizeof rep);
    return s;
}
static nls_status c_mobius_identity(capture *c) {
    nls_mobius m;
    nls_status s;
    memset(&m, 0, sizeof m);
    s = nls_mobius_identity(&m);
    put(c, &m, sizeof m);
    return s;
}
static nls_status c_mobius_similarity(capture *c) {
    nls_mobius m;
    double axis[3] = {0, 0, 1};
    nls_status s;
    memset(&m, 0, sizeof m);
    s = nls_mobius_similarity(axis, 0.75, SCALE_HALF, P[1], &m);
    put(c, &m, sizeof m);
    return s;
}
static nls_status c_mobius_inversion(capture *c) {
    nls_mobius m;
    nls_status s;
    memset(&m, 0, sizeof m);
    s = nls_mobius_inversion(P[1], SCALE_HALF, &m);
    put(c, &m, sizeof m);
    return s;
}
/* A Moebius map from this round's inputs (made in the default environment by the caller
 * of every case: see run_round). */
static nls_mobius M1, M2;
static nls_canonical_form CF;
static nls_status c_mobius_compose(capture *c) {
    nls_mobius m;
    nls_status s;
    memset(&m, 0, sizeof m);
    s = nls_mobius_compose(&M1, &M2, &m);
    put(c, &m, sizeof m);
    return s;
}
static nls_status c_mobius_invert(capture *c) {
    nls_mobius m;
    nls_status s;
    memset(&m, 0, sizeof m);
    s = nls_mobius_invert(&M1, &m);
    put(c, &m, sizeof m);
    return s;
}
static nls_status c_mobius_apply(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_mobius_apply(&M1, P[3], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_canonical_form_new(capture *c) {
    nls_canonical_form f;
    nls_status s;
    memset(&f, 0, sizeof f);
    s = nls_canonical_form_new(CENTRE, &RING[0][0], 6, NLS_STAR_INTERIOR, &f);
    put(c, &f, sizeof f);
    return s;
}
static nls_status c_canonical_form_to_canonical(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_canonical_form_to_canonical(&CF, P[4], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_canonical_form_from_canonical(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_canonical_form_from_canonical(&CF, P[4], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_canonical_form_map(capture *c) {
    nls_mobius m;
    nls_status s;
    memset(&m, 0, sizeof m);
    s = nls_canonical_form_map(&CF, 0, &m);
    put(c, &m, sizeof m);
    return s;
}
static nls_status c_cross_ratio(capture *c) {
    double out[4] = {0, 0, 0, 0};
    nls_status s = nls_cross_ratio(P[0], P[1], P[4], P[5], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_f4(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_f4(P[5], P[1], P[2], P[6], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_f4_hinted(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_f4_hinted(P[5], P[1], P[2], P[6], P[4], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_f6(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_f6(P[0], P[1], P[2], P[3], P[5], P[6], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_noncircularity(capture *c) {
    double out = 0;
    nls_status s = nls_noncircularity(P[0], P[1], P[4], P[7], &out);
    put(c, &out, sizeof out);
    return s;
}
static nls_status c_corner_tangent(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_corner_tangent(P[5], P[1], P[6], out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_tangent_polygon(capture *c) {
    double out[18];
    nls_status s;
    memset(out, 0, sizeof out);
    s = nls_tangent_polygon(CENTRE, &RING[0][0], 6, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_quat_mul(capture *c) {
    double out[4] = {0, 0, 0, 0};
    nls_status s = nls_quat_mul(QA, QB, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_quat_inverse(capture *c) {
    double out[4] = {0, 0, 0, 0};
    nls_status s = nls_quat_inverse(QA, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_quat_sqrt(capture *c) {
    double out[4] = {0, 0, 0, 0};
    nls_status s = nls_quat_sqrt(QB, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_quat_log(capture *c) {
    double out[4] = {0, 0, 0, 0};
    nls_status s = nls_quat_log(QA, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_quat_exp(capture *c) {
    double out[4] = {0, 0, 0, 0};
    nls_status s = nls_quat_exp(QB, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_star_willmore_energy(capture *c) {
    double out = 0;
    nls_status s = nls_star_willmore_energy(CENTRE, &RING[0][0], 6, 1, &out);
    put(c, &out, sizeof out);
    return s;
}
static nls_status c_star_mobius_regularity(capture *c) {
    double out = 0;
    nls_status s = nls_star_mobius_regularity(CENTRE, &RING[0][0], 6, 1, &out);
    put(c, &out, sizeof out);
    return s;
}
static nls_status c_face_point(capture *c) {
    double out[3] = {0, 0, 0};
    nls_status s = nls_face_point(&FACE_V[0][0], &FACE_C[0][0], 4, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_face_point_with_ids(capture *c) {
    double out[3] = {0, 0, 0};
    static const uint32_t ids[4] = {7, 3, 9, 1};
    nls_status s = nls_face_point_with_ids(&FACE_V[0][0], &FACE_C[0][0], ids, 4, out);
    put(c, out, sizeof out);
    return s;
}
static nls_status c_mobius_loop_star(capture *c) {
    double vp[3] = {0, 0, 0}, ec[18];
    nls_status s;
    memset(ec, 0, sizeof ec);
    nls_star_view star = {CENTRE, &RING[0][0], 6, 1, NULL, 0, NULL, 0};
    s = nls_mobius_loop_star(&star, vp, ec);
    put(c, vp, sizeof vp);
    put(c, ec, sizeof ec);
    return s;
}
static nls_status c_mobius_catmull_clark_star(capture *c) {
    /* Four quads around CENTRE: ring of 4 edge neighbours, one far corner per face. */
    static const uint32_t fo[5] = {0, 1, 2, 3, 4};
    double vp[3] = {0, 0, 0}, ec[12], fc[12];
    nls_status s;
    memset(ec, 0, sizeof ec);
    memset(fc, 0, sizeof fc);
    nls_star_view star = {CENTRE, &CC_RING[0][0], 4, 1, fo, 4, &CC_CORNERS[0][0], 4};
    s = nls_mobius_catmull_clark_star(&star, vp, ec, fc);
    put(c, vp, sizeof vp);
    put(c, ec, sizeof ec);
    put(c, fc, sizeof fc);
    return s;
}
static nls_status c_mobius_butterfly_star(capture *c) {
    double ec[18];
    nls_status s;
    memset(ec, 0, sizeof ec);
    nls_star_view star = {CENTRE, &RING[0][0], 6, 1, NULL, 0, NULL, 0};
    s = nls_mobius_butterfly_star(&star, NULL, ec);
    put(c, ec, sizeof ec);
    return s;
}

typedef struct {
    const char *name;
    case_fn fn;
    int computes; /* 1: checks the FP environment (NLS_STATUS_FP_ENVIRONMENT in its docs) */
} export_case;

static const export_case CASES[] = {
    {"nls_version", c_version, 0},
    {"nls_status_str", c_status_str, 0},
    {"nls_curve_refined_size", c_curve_refined_size, 0},
    {"nls_curve_scratch_size", c_curve_scratch_size, 0},
    {"nls_curve_subdivide (circle blend)", c_curve_subdivide, 1},
    {"nls_curve_subdivide (Moebius)", c_curve_subdivide_mob, 1},
    {"nls_curve_subdivide (differential)", c_curve_subdivide_diff, 1},
    {"nls_subdivide_default_options", c_subdivide_default_options, 0},
    {"nls_mesh_plan_scratch_size", c_mesh_plan_scratch_size, 0},
    {"nls_mesh_plan", c_mesh_plan, 1},
    {"nls_mesh_subdivide (Moebius Loop)", c_mesh_subdivide_mob_loop, 1},
    {"nls_mesh_subdivide (Moebius Catmull-Clark)", c_mesh_subdivide_mob_cc, 1},
    {"nls_mesh_subdivide (Moebius Butterfly)", c_mesh_subdivide_mob_bf, 1},
    {"nls_mesh_subdivide (spherelike)", c_mesh_subdivide_spherelike, 1},
    {"nls_mesh_subdivide (Doo-Sabin)", c_mesh_subdivide_linear, 1},
    {"nls_mesh_plan (2 levels)", c_mesh_plan_levels, 1},
    {"nls_mesh_subdivide (2 levels)", c_mesh_subdivide_levels, 1},
    {"nls_differential_default_options", c_differential_default_options, 0},
    {"nls_differential_plan", c_differential_plan, 1},
    {"nls_differential_subdivide", c_differential_subdivide, 1},
    {"nls_mobius_identity", c_mobius_identity, 0},
    {"nls_mobius_similarity", c_mobius_similarity, 1},
    {"nls_mobius_inversion", c_mobius_inversion, 1},
    {"nls_mobius_compose", c_mobius_compose, 1},
    {"nls_mobius_invert", c_mobius_invert, 1},
    {"nls_mobius_apply", c_mobius_apply, 1},
    {"nls_canonical_form_new", c_canonical_form_new, 1},
    {"nls_canonical_form_to_canonical", c_canonical_form_to_canonical, 1},
    {"nls_canonical_form_from_canonical", c_canonical_form_from_canonical, 1},
    {"nls_canonical_form_map", c_canonical_form_map, 1},
    {"nls_cross_ratio", c_cross_ratio, 1},
    {"nls_f4", c_f4, 1},
    {"nls_f4_hinted", c_f4_hinted, 1},
    {"nls_f6", c_f6, 1},
    {"nls_noncircularity", c_noncircularity, 1},
    {"nls_corner_tangent", c_corner_tangent, 1},
    {"nls_tangent_polygon", c_tangent_polygon, 1},
    {"nls_quat_mul", c_quat_mul, 1},
    {"nls_quat_inverse", c_quat_inverse, 1},
    {"nls_quat_sqrt", c_quat_sqrt, 1},
    {"nls_quat_log", c_quat_log, 1},
    {"nls_quat_exp", c_quat_exp, 1},
    {"nls_star_willmore_energy", c_star_willmore_energy, 1},
    {"nls_star_mobius_regularity", c_star_mobius_regularity, 1},
    {"nls_face_point", c_face_point, 1},
    {"nls_face_point_with_ids", c_face_point_with_ids, 1},
    {"nls_mobius_loop_star", c_mobius_loop_star, 1},
    {"nls_mobius_catmull_clark_star", c_mobius_catmull_clark_star, 1},
    {"nls_mobius_butterfly_star", c_mobius_butterfly_star, 1},
};
#define NCASES (sizeof CASES / sizeof CASES[0])

static capture REF[NCASES], GOT;
static nls_status REF_STATUS[NCASES];

/* --------------------------------------------------------------------- environments */

static int under_valgrind(void) { return getenv("NLS_TEST_UNDER_VALGRIND") != NULL; }

/* Compares one call in the current environment with the reference. */
static void same_as_reference(size_t i, const char *env) {
    nls_status s;
    GOT.len = 0;
    s = CASES[i].fn(&GOT);
    if (s != REF_STATUS[i] || GOT.len != REF[i].len || memcmp(GOT.bytes, REF[i].bytes, GOT.len) != 0) {
        nls_failed++;
        fprintf(stderr, "%s under %s: status %u (%s), bytes %s; default environment: status %u (%s)\n", CASES[i].name,
                env, (unsigned)s, nls_status_str(s), GOT.len == REF[i].len && memcmp(GOT.bytes, REF[i].bytes, GOT.len) == 0 ? "same" : "DIFFERENT",
                (unsigned)REF_STATUS[i], nls_status_str(REF_STATUS[i]));
    } else {
        nls_passed++;
    }
}

static void with_traps(int excepts, const char *env) {
    size_t i;
    for (i = 0; i < NCASES; i++) {
        int flags, enabled;
        feclearexcept(FE_ALL_EXCEPT);
        if (feenableexcept(excepts) == -1 || fegetexcept() != excepts) {
            /* valgrind, for one, does not emulate unmasked exceptions */
            fedisableexcept(FE_ALL_EXCEPT);
            printf("SKIP %s: this environment does not keep unmasked traps\n", env);
            return;
        }
        same_as_reference(i, env);
        enabled = fegetexcept();
        flags = fetestexcept(FE_ALL_EXCEPT);
        fedisableexcept(FE_ALL_EXCEPT);
        feclearexcept(FE_ALL_EXCEPT);
        if (enabled != excepts) {
            nls_failed++;
            fprintf(stderr, "%s under %s: the host's traps were not restored (0x%x, expected 0x%x)\n", CASES[i].name, env,
                    (unsigned)enabled, (unsigned)excepts);
        }
        if (flags != 0) {
            nls_failed++;
            fprintf(stderr, "%s under %s: the library left exception flags 0x%x to the host\n", CASES[i].name, env,
                    (unsigned)flags);
        }
    }
}

/* Under a mode that changes results: computing exports refuse, the others are unchanged. */
static void under_mode(const char *env) {
    size_t i;
    for (i = 0; i < NCASES; i++) {
        if (CASES[i].computes) {
            GOT.len = 0;
            CHECK_STATUS(CASES[i].fn(&GOT), NLS_STATUS_FP_ENVIRONMENT);
        } else {
            same_as_reference(i, env);
        }
    }
}

static void run_round(double scale) {
    size_t i;
    char env[96];
    prepare(scale);
    /* Maps and a canonical form to feed the calls that take them (default environment). */
    {
        double axis[3] = {1, 0, 0};
        memset(&M1, 0, sizeof M1);
        memset(&M2, 0, sizeof M2);
        memset(&CF, 0, sizeof CF);
        (void)nls_mobius_inversion(P[2], SCALE_HALF, &M1);
        (void)nls_mobius_similarity(axis, 0.5, 0.5, P[3], &M2);
        (void)nls_canonical_form_new(CENTRE, &RING[0][0], 6, NLS_STAR_INTERIOR, &CF);
    }
    for (i = 0; i < NCASES; i++) {
        REF[i].len = 0;
        REF_STATUS[i] = CASES[i].fn(&REF[i]);
    }
    snprintf(env, sizeof env, "FE_INVALID|FE_DIVBYZERO|FE_OVERFLOW traps (scale %g)", scale);
    with_traps(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW, env);
    snprintf(env, sizeof env, "FE_ALL_EXCEPT traps (scale %g)", scale);
    with_traps(FE_ALL_EXCEPT, env);
    if (under_valgrind()) {
        /* valgrind emulates neither MXCSR flush-to-zero nor the rounding modes */
        printf("SKIP FP modes under valgrind (scale %g)\n", scale);
        return;
    }
    {
        static const int modes[3] = {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO};
        static const char *names[3] = {"FE_UPWARD", "FE_DOWNWARD", "FE_TOWARDZERO"};
        int m;
        for (m = 0; m < 3; m++) {
            snprintf(env, sizeof env, "rounding %s (scale %g)", names[m], scale);
            fesetround(modes[m]);
            under_mode(env);
            fesetround(FE_TONEAREST);
        }
    }
#if defined(__x86_64__)
    {
        static const unsigned bits[3] = {0x8000u, 0x0040u, 0x8040u};
        static const char *names[3] = {"FTZ", "DAZ", "FTZ+DAZ"};
        int m;
        unsigned saved = _mm_getcsr();
        for (m = 0; m < 3; m++) {
            snprintf(env, sizeof env, "MXCSR %s (scale %g)", names[m], scale);
            _mm_setcsr(saved | bits[m]);
            under_mode(env);
            _mm_setcsr(saved);
        }
    }
#endif
}

int main(void) {
    static const double scales[] = {1.0, 1e300, 1e308, -1e308, 1e-300};
    size_t k;
    (void)nls_dist3; /* check.h's helper, not needed here */
    SU = calloc(BIG_U32, sizeof(uint32_t));
    SP = calloc(3 * BIG_PTS, sizeof(double));
    OP = calloc(3 * BIG_PTS, sizeof(double));
    OO = calloc(BIG_PTS, sizeof(uint32_t));
    OI = calloc(BIG_U32, sizeof(uint32_t));
    if (!SU || !SP || !OP || !OO || !OI) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    for (k = 0; k < sizeof scales / sizeof scales[0]; k++) run_round(scales[k]);
    printf("test_fp_env: %u exports and variants, %u scales\n", (unsigned)NCASES, (unsigned)(sizeof scales / sizeof scales[0]));
    free(SU);
    free(SP);
    free(OP);
    free(OO);
    free(OI);
    return nls_summary("test_fp_env");
}
