/* C99 tests of the primitive exports of nlsubdiv.h: every function, NULL pointers,
 * misaligned pointers, degenerate input, non-finite input, the floating-point-environment
 * guard, and "outputs written only on success". Run under ASan+UBSan and valgrind. */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "nlsubdiv.h"
#include "check.h"

static const double SENTINEL = -12345.678;

static void fill(double *p, size_t n) {
    size_t i;
    for (i = 0; i < n; i++) p[i] = SENTINEL;
}

static int untouched(const double *p, size_t n) {
    size_t i;
    for (i = 0; i < n; i++)
        if (p[i] != SENTINEL) return 0;
    return 1;
}

static void on_circle(double t, double r, double out[3]) {
    out[0] = r * cos(t);
    out[1] = r * sin(t);
    out[2] = 0.0;
}

static void test_version_and_status(void) {
    uint32_t v = nls_version();
    CHECK(v == (((uint32_t)NLS_VERSION_MAJOR << 16) | ((uint32_t)NLS_VERSION_MINOR << 8) |
                (uint32_t)NLS_VERSION_PATCH));
    CHECK(strcmp(nls_status_str(NLS_STATUS_OK), "ok") == 0);
    CHECK(strlen(nls_status_str(NLS_STATUS_NULL_PARAMETER)) > 10);
    CHECK(strcmp(nls_status_str(99999u), "unknown status") == 0);
    CHECK(strcmp(nls_status_str(13u), "unknown status") == 0);
}

static void test_cross_ratio(void) {
    double a[3], b[3], c[3], d[3], out[4];
    on_circle(0.1, 1.0, a);
    on_circle(1.0, 1.0, b);
    on_circle(2.5, 1.0, c);
    on_circle(4.0, 1.0, d);
    CHECK_STATUS(nls_cross_ratio(a, b, c, d, out), NLS_STATUS_OK);
    /* cocircular: real cross-ratio */
    CHECK(fabs(out[1]) + fabs(out[2]) + fabs(out[3]) < 1e-14 * fabs(out[0]));
    fill(out, 4);
    CHECK_STATUS(nls_cross_ratio(NULL, b, c, d, out), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(nls_cross_ratio(a, b, c, d, NULL), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(nls_cross_ratio(a, b, b, d, out), NLS_STATUS_DEGENERATE_GEOMETRY);
    CHECK(untouched(out, 4));
    {
        double nan_point[3] = {NAN, 0.0, 0.0};
        CHECK_STATUS(nls_cross_ratio(a, nan_point, c, d, out), NLS_STATUS_NON_FINITE_INPUT);
        CHECK(untouched(out, 4));
    }
    {
        /* a misaligned double pointer inside a byte buffer */
        unsigned char raw[sizeof(double) * 4 + 1];
        double *mis = (double *)(void *)(raw + 1);
        CHECK_STATUS(nls_cross_ratio(a, b, c, d, mis), NLS_STATUS_MISALIGNED_POINTER);
    }
}

static void test_f4(void) {
    double a[3], b[3], c[3], d[3], p[3], q[3];
    const double r = 3.5;
    on_circle(0.0, r, a);
    on_circle(0.4, r, b);
    on_circle(1.3, r, c);
    on_circle(2.0, r, d);
    CHECK_STATUS(nls_f4(a, b, c, d, p), NLS_STATUS_OK);
    CHECK(fabs(sqrt(p[0] * p[0] + p[1] * p[1]) - r) < 1e-13 * r);
    CHECK(fabs(p[2]) < 1e-13);
    /* symmetry */
    CHECK_STATUS(nls_f4(d, c, b, a, q), NLS_STATUS_OK);
    CHECK(nls_dist3(p, q) < 1e-13 * r);
    /* output aliasing an input is allowed: inputs are read first */
    {
        double bb[3];
        memcpy(bb, b, sizeof bb);
        CHECK_STATUS(nls_f4(a, bb, c, d, bb), NLS_STATUS_OK);
        CHECK(nls_dist3(bb, p) == 0.0);
    }
    /* coincident b = c gives b */
    CHECK_STATUS(nls_f4(a, b, b, d, p), NLS_STATUS_OK);
    CHECK(nls_dist3(p, b) == 0.0);
    /* equally spaced line: midpoint */
    {
        double l0[3] = {0, 0, 0}, l1[3] = {1, 0, 0}, l2[3] = {2, 0, 0}, l3[3] = {3, 0, 0};
        double mid[3] = {1.5, 0, 0};
        CHECK_STATUS(nls_f4(l0, l1, l2, l3, p), NLS_STATUS_OK);
        CHECK(nls_dist3(p, mid) < 1e-15);
    }
    fill(q, 3);
    {
        double inf_point[3] = {INFINITY, 0, 0};
        CHECK_STATUS(nls_f4(a, b, c, inf_point, q), NLS_STATUS_NON_FINITE_INPUT);
    }
    CHECK_STATUS(nls_f4(a, b, c, NULL, q), NLS_STATUS_NULL_PARAMETER);
    CHECK(untouched(q, 3));
    CHECK_STATUS(nls_f4(a, b, c, d, NULL), NLS_STATUS_NULL_PARAMETER);
}

static void test_f6(void) {
    double a[3] = {0, 0.5, 0}, b[3] = {0.5, 0.5, 0}, c[3] = {1, 0.5, 0};
    double d[3] = {0.5, 0, 0}, e[3] = {0.5, 0.5, 0}, f[3] = {0.5, 1, 0}, p[3];
    CHECK_STATUS(nls_f6(a, b, c, d, e, f, p), NLS_STATUS_OK);
    CHECK(nls_dist3(p, b) == 0.0); /* b = e gives b */
    /* six cospherical points: the result is on the sphere */
    {
        double s[6][3];
        const double th[6] = {0.3, 0.7, 1.1, 0.5, 0.9, 1.4};
        const double ph[6] = {0.2, 0.5, 0.9, 1.4, 0.6, 0.1};
        int i;
        for (i = 0; i < 6; i++) {
            s[i][0] = 2.0 * sin(th[i]) * cos(ph[i]);
            s[i][1] = 2.0 * sin(th[i]) * sin(ph[i]);
            s[i][2] = 2.0 * cos(th[i]);
        }
        CHECK_STATUS(nls_f6(s[0], s[1], s[2], s[3], s[4], s[5], p), NLS_STATUS_OK);
        CHECK(fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 2.0) < 1e-12);
    }
    fill(p, 3);
    CHECK_STATUS(nls_f6(a, b, c, d, e, NULL, p), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(nls_f6(a, a, c, d, f, f, p), NLS_STATUS_DEGENERATE_GEOMETRY);
    CHECK(untouched(p, 3));
}

static void test_face_point(void) {
    double sq[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    double cand[12] = {0.5, 0.5, 0, 0.5, 0.5, 0, 0.5, 0.5, 0, 0.5, 0.5, 0};
    double p[3], centre[3] = {0.5, 0.5, 0};
    CHECK_STATUS(nls_face_point(sq, cand, 4, p), NLS_STATUS_OK);
    CHECK(nls_dist3(p, centre) == 0.0);
    CHECK_STATUS(nls_face_point(sq, cand, 2, p), NLS_STATUS_TOO_FEW_POINTS);
    CHECK_STATUS(nls_face_point(sq, NULL, 4, p), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(nls_face_point(sq, cand, 4, NULL), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(nls_face_point(NULL, NULL, 0, p), NLS_STATUS_TOO_FEW_POINTS);
}

/* The face point with ids does not depend on the corner a face starts at, bit for bit: a
 * quad (its quadruplets i and i+2 always tie) and a pentagon with distinct candidates near a
 * common point, listed from every corner. */
static void test_face_point_with_ids(void) {
    static const double quad[12] = {1.02, 0.03, 0.01, -0.04, 0.97, -0.02, -1.01, 0.05, 0.03, 0.02, -0.99, -0.01};
    static const double qc[12] = {0.01, -0.02, 0.31, -0.015, 0.02, 0.29, 0.02, 0.01, 0.305, -0.01, -0.02, 0.295};
    static const double pent[15] = {1, 0, 0, 0.31, 0.95, 0.02, -0.81, 0.59, -0.01, -0.8, -0.6, 0.03, 0.3, -0.96, 0};
    static const double pc[15] = {0.01, 0, 0.4, 0, 0.02, 0.41, -0.01, 0.01, 0.39, 0, -0.01, 0.4, 0.02, 0, 0.405};
    const double *faces[2] = {quad, pent}, *cands[2] = {qc, pc};
    const size_t sizes[2] = {4, 5};
    const uint32_t ids0[5] = {17, 3, 42, 8, 25};
    size_t f, s, i, k;
    for (f = 0; f < 2; f++) {
        size_t n = sizes[f];
        double ref[3], got[3], v[15], c[15], plain[3];
        uint32_t ids[5];
        CHECK_STATUS(nls_face_point_with_ids(faces[f], cands[f], ids0, n, ref), NLS_STATUS_OK);
        CHECK_STATUS(nls_face_point(faces[f], cands[f], n, plain), NLS_STATUS_OK);
        CHECK(nls_dist3(ref, plain) < 1e-6); /* only the tie-break differs */
        for (s = 1; s < n; s++) {
            for (i = 0; i < n; i++) {
                for (k = 0; k < 3; k++) {
                    v[3 * i + k] = faces[f][3 * ((i + s) % n) + k];
                    c[3 * i + k] = cands[f][3 * ((i + s) % n) + k];
                }
                ids[i] = ids0[(i + s) % n];
            }
            CHECK_STATUS(nls_face_point_with_ids(v, c, ids, n, got), NLS_STATUS_OK);
            CHECK(memcmp(got, ref, sizeof ref) == 0);
        }
    }
    {
        double p[3];
        fill(p, 3);
        CHECK_STATUS(nls_face_point_with_ids(quad, qc, NULL, 4, p), NLS_STATUS_NULL_PARAMETER);
        CHECK_STATUS(nls_face_point_with_ids(quad, qc, ids0, 2, p), NLS_STATUS_TOO_FEW_POINTS);
        CHECK(untouched(p, 3));
    }
}

static void test_small_primitives(void) {
    double a[3], b[3], c[3], d[3], t[3], x;
    on_circle(0.0, 1.0, a);
    on_circle(1.0, 1.0, b);
    on_circle(2.0, 1.0, c);
    on_circle(3.0, 1.0, d);
    CHECK_STATUS(nls_noncircularity(a, b, c, d, &x), NLS_STATUS_OK);
    CHECK(fabs(x) < 1e-14);
    d[2] = 0.5;
    CHECK_STATUS(nls_noncircularity(a, b, c, d, &x), NLS_STATUS_OK);
    CHECK(x > 1e-4);
    CHECK_STATUS(nls_noncircularity(a, b, c, d, NULL), NLS_STATUS_NULL_PARAMETER);
    /* corner tangent at b of the unit circle through a, b, c is tangent: orthogonal to b */
    CHECK_STATUS(nls_corner_tangent(a, b, c, t), NLS_STATUS_OK);
    CHECK(fabs(t[0] * b[0] + t[1] * b[1] + t[2] * b[2]) < 1e-14);
    CHECK_STATUS(nls_corner_tangent(a, a, c, t), NLS_STATUS_DEGENERATE_GEOMETRY);
}

static void test_quaternions(void) {
    double i[4] = {0, 1, 0, 0}, j[4] = {0, 0, 1, 0}, k[4], q[4] = {1.5, -2, 0.25, 3}, r[4], s[4];
    CHECK_STATUS(nls_quat_mul(i, j, k), NLS_STATUS_OK);
    CHECK(k[0] == 0 && k[1] == 0 && k[2] == 0 && k[3] == 1);
    CHECK_STATUS(nls_quat_inverse(q, r), NLS_STATUS_OK);
    CHECK_STATUS(nls_quat_mul(q, r, s), NLS_STATUS_OK);
    CHECK(fabs(s[0] - 1) < 1e-15 && fabs(s[1]) + fabs(s[2]) + fabs(s[3]) < 1e-15);
    CHECK_STATUS(nls_quat_sqrt(q, r), NLS_STATUS_OK);
    CHECK(r[0] >= 0);
    CHECK_STATUS(nls_quat_mul(r, r, s), NLS_STATUS_OK);
    CHECK(fabs(s[0] - q[0]) + fabs(s[1] - q[1]) + fabs(s[2] - q[2]) + fabs(s[3] - q[3]) < 1e-14);
    CHECK_STATUS(nls_quat_log(q, r), NLS_STATUS_OK);
    CHECK_STATUS(nls_quat_exp(r, s), NLS_STATUS_OK);
    CHECK(fabs(s[0] - q[0]) + fabs(s[1] - q[1]) + fabs(s[2] - q[2]) + fabs(s[3] - q[3]) < 1e-13);
    {
        double zero[4] = {0, 0, 0, 0}, neg[4] = {-4, 0, 0, 0}, bad[4] = {NAN, 0, 0, 0};
        fill(r, 4);
        CHECK_STATUS(nls_quat_inverse(zero, r), NLS_STATUS_DEGENERATE_GEOMETRY);
        CHECK_STATUS(nls_quat_sqrt(neg, r), NLS_STATUS_DEGENERATE_GEOMETRY);
        CHECK_STATUS(nls_quat_log(zero, r), NLS_STATUS_DEGENERATE_GEOMETRY);
        CHECK_STATUS(nls_quat_exp(bad, r), NLS_STATUS_NON_FINITE_INPUT);
        CHECK_STATUS(nls_quat_mul(NULL, q, r), NLS_STATUS_NULL_PARAMETER);
        CHECK(untouched(r, 4));
        {
            double big[4] = {1000, 0, 0, 0};
            CHECK_STATUS(nls_quat_exp(big, r), NLS_STATUS_NUMERICAL_FAILURE);
        }
    }
}

static void regular_ring(int n, double *ring) {
    int i;
    for (i = 0; i < n; i++) on_circle(2.0 * 3.14159265358979323846 * i / n, 1.0, ring + 3 * i);
}

static void test_tangent_polygon_and_metrics(void) {
    double v[3] = {0, 0, 0}, ring[3 * 6], t[3 * 6], w;
    int i;
    regular_ring(6, ring);
    CHECK_STATUS(nls_tangent_polygon(v, ring, 6, t), NLS_STATUS_OK);
    for (i = 0; i < 6; i++) CHECK(fabs(t[3 * i] + ring[3 * i]) < 1e-15);
    CHECK_STATUS(nls_tangent_polygon(v, ring, 6, ring + 3), NLS_STATUS_ALIASING_BUFFERS);
    CHECK_STATUS(nls_tangent_polygon(v, NULL, 6, t), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(nls_tangent_polygon(v, NULL, 0, NULL), NLS_STATUS_OK);
    {
        /* every too-small allocation of the output is caught before any write: the
           library cannot know the size, so the contract is the count; a neighbour at v is
           rejected before the first write */
        double bad_ring[3 * 3] = {1, 0, 0, 0, 0, 0, 0, 1, 0};
        double out[9];
        fill(out, 9);
        CHECK_STATUS(nls_tangent_polygon(v, bad_ring, 3, out), NLS_STATUS_DEGENERATE_GEOMETRY);
        CHECK(untouched(out, 9));
    }
    {
        /* SIZE_MAX / 2 points: the byte size overflows */
        CHECK_STATUS(nls_tangent_polygon(v, ring, SIZE_MAX / 2, t), NLS_STATUS_SIZE_OVERFLOW);
    }
    CHECK_STATUS(nls_star_willmore_energy(v, ring, 6, 1, &w), NLS_STATUS_OK);
    CHECK(w < 1e-15);
    CHECK_STATUS(nls_star_mobius_regularity(v, ring, 6, 1, &w), NLS_STATUS_OK);
    CHECK(w < 1e-28);
    CHECK_STATUS(nls_star_willmore_energy(v, ring, 6, 2, &w), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(nls_star_mobius_regularity(v, ring, 2, 1, &w), NLS_STATUS_TOO_FEW_POINTS);
    ring[2] = 0.4; /* lift one neighbour: no longer cospherical or regular */
    CHECK_STATUS(nls_star_willmore_energy(v, ring, 6, 1, &w), NLS_STATUS_OK);
    CHECK(w > 1e-4);
    CHECK_STATUS(nls_star_mobius_regularity(v, ring, 6, 1, &w), NLS_STATUS_OK);
    CHECK(w > 1e-4);
}

static void test_mobius_maps(void) {
    nls_mobius id, sim, inv, m, mi;
    double axis[3] = {0, 0, 2}, t[3] = {1, 2, 3}, centre[3] = {0.5, -0.2, 0.1};
    double p[3] = {0.3, -1.0, 2.0}, q[3], back[3];
    CHECK_STATUS(nls_mobius_identity(&id), NLS_STATUS_OK);
    CHECK_STATUS(nls_mobius_apply(&id, p, q), NLS_STATUS_OK);
    CHECK(nls_dist3(p, q) == 0.0);
    CHECK_STATUS(nls_mobius_similarity(axis, 1.5707963267948966, 2.0, t, &sim), NLS_STATUS_OK);
    CHECK_STATUS(nls_mobius_apply(&sim, p, q), NLS_STATUS_OK);
    {
        double expected[3] = {2.0 * 1.0 + 1, 2.0 * 0.3 + 2, 2.0 * 2.0 + 3};
        CHECK(nls_dist3(q, expected) < 1e-14);
    }
    CHECK_STATUS(nls_mobius_inversion(centre, 1.5, &inv), NLS_STATUS_OK);
    CHECK_STATUS(nls_mobius_compose(&inv, &sim, &m), NLS_STATUS_OK);
    CHECK_STATUS(nls_mobius_invert(&m, &mi), NLS_STATUS_OK);
    CHECK_STATUS(nls_mobius_apply(&m, p, q), NLS_STATUS_OK);
    CHECK_STATUS(nls_mobius_apply(&mi, q, back), NLS_STATUS_OK);
    CHECK(nls_dist3(back, p) < 1e-12);
    CHECK_STATUS(nls_mobius_apply(&inv, centre, q), NLS_STATUS_DEGENERATE_GEOMETRY);
    CHECK_STATUS(nls_mobius_inversion(centre, 0.0, &inv), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(nls_mobius_inversion(centre, NAN, &inv), NLS_STATUS_NON_FINITE_INPUT);
    CHECK_STATUS(nls_mobius_similarity(axis, 1.0, 0.0, t, &sim), NLS_STATUS_INVALID_ARGUMENT);
    {
        /* Fuzz finding (fuzz/regressions/primitives/inversion-huge-radius): finite inputs
         * far out in the double range gave OK with an infinite coefficient. */
        double c[3] = {-0.741761, 6.61637, 0.735879};
        nls_mobius before, after;
        memset(&before, 0x5a, sizeof before);
        after = before;
        CHECK_STATUS(nls_mobius_inversion(c, 1.035746192103199e+266, &after), NLS_STATUS_NUMERICAL_FAILURE);
        CHECK(memcmp(&before, &after, sizeof before) == 0);
        CHECK_STATUS(nls_mobius_inversion(c, 1e150, &after), NLS_STATUS_OK);
    }
    CHECK_STATUS(nls_mobius_compose(NULL, &sim, &m), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(nls_mobius_identity(NULL), NLS_STATUS_NULL_PARAMETER);
    {
        nls_mobius singular;
        int i;
        for (i = 0; i < 4; i++) {
            singular.a[i] = singular.b[i] = singular.c[i] = singular.d[i] = (i == 0) ? 1.0 : 0.0;
        }
        CHECK_STATUS(nls_mobius_invert(&singular, &mi), NLS_STATUS_DEGENERATE_GEOMETRY);
    }
}

static void test_canonical_forms(void) {
    double v[3] = {0.1, 0.0, 0.2};
    double ring[3 * 5] = {1.0, 0.1, 0.0, 0.3, 1.0, 0.2, -0.9, 0.4, 0.1, -0.5, -1.1, 0.0, 0.6, -0.8, -0.1};
    nls_canonical_form cf;
    nls_mobius m;
    double c[3], back[3], viam[3];
    int i;
    CHECK_STATUS(nls_canonical_form_new(v, ring, 5, NLS_STAR_INTERIOR, &cf), NLS_STATUS_OK);
    CHECK(cf.kind == NLS_STAR_INTERIOR && cf.r > 0);
    CHECK_STATUS(nls_canonical_form_to_canonical(&cf, v, c), NLS_STATUS_OK);
    CHECK(nls_dist3(c, cf.c) == 0.0);
    CHECK_STATUS(nls_canonical_form_map(&cf, 0, &m), NLS_STATUS_OK);
    for (i = 0; i < 5; i++) {
        CHECK_STATUS(nls_canonical_form_to_canonical(&cf, ring + 3 * i, c), NLS_STATUS_OK);
        CHECK_STATUS(nls_mobius_apply(&m, ring + 3 * i, viam), NLS_STATUS_OK);
        CHECK(nls_dist3(c, viam) < 1e-13);
        CHECK_STATUS(nls_canonical_form_from_canonical(&cf, c, back), NLS_STATUS_OK);
        CHECK(nls_dist3(back, ring + 3 * i) < 1e-13);
    }
    CHECK_STATUS(nls_canonical_form_map(&cf, 1, &m), NLS_STATUS_OK);
    CHECK_STATUS(nls_canonical_form_map(&cf, 7, &m), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(nls_canonical_form_new(v, ring, 1, NLS_STAR_INTERIOR, &cf), NLS_STATUS_TOO_FEW_POINTS);
    CHECK_STATUS(nls_canonical_form_new(v, ring, 2, NLS_STAR_INTERIOR, &cf), NLS_STATUS_OK);
    CHECK_STATUS(nls_canonical_form_new(v, ring, 2, NLS_STAR_BOUNDARY, &cf), NLS_STATUS_OK);
    CHECK_STATUS(nls_canonical_form_new(v, ring, 3, NLS_STAR_EAR, &cf), NLS_STATUS_OK);
    CHECK_STATUS(nls_canonical_form_new(v, ring, 5, 9u, &cf), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(nls_canonical_form_new(v, NULL, 5, NLS_STAR_INTERIOR, &cf), NLS_STATUS_NULL_PARAMETER);
    {
        double *big = (double *)calloc(3 * 200, sizeof(double));
        int k;
        for (k = 0; k < 200; k++) on_circle(0.01 * k, 1.0, big + 3 * k);
        CHECK_STATUS(nls_canonical_form_new(v, big, 200, NLS_STAR_INTERIOR, &cf), NLS_STATUS_VALENCE_TOO_HIGH);
        free(big);
    }
    ring[3] = v[0];
    ring[4] = v[1];
    ring[5] = v[2];
    CHECK_STATUS(nls_canonical_form_new(v, ring, 5, NLS_STAR_INTERIOR, &cf), NLS_STATUS_DEGENERATE_GEOMETRY);
    {
        nls_canonical_form broken = cf;
        broken.r = -1.0;
        CHECK_STATUS(nls_canonical_form_to_canonical(&broken, v, c), NLS_STATUS_INVALID_ARGUMENT);
    }
}

static void test_fp_environment(void) {
#if defined(__x86_64__)
    if (getenv("NLS_TEST_UNDER_VALGRIND") != NULL) {
        /* valgrind does not emulate MXCSR flush-to-zero or rounding control */
        printf("SKIP test_fp_environment under valgrind\n");
        return;
    }
    double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {2, 0, 0}, d[3] = {3, 0, 0}, p[3];
    unsigned int saved = _mm_getcsr();
    _mm_setcsr(saved | 0x8040u); /* flush-to-zero + denormals-are-zero, as -ffast-math does */
    {
        nls_status s = nls_f4(a, b, c, d, p);
        _mm_setcsr(saved);
        CHECK_STATUS(s, NLS_STATUS_FP_ENVIRONMENT);
    }
    _mm_setcsr((saved & ~0x6000u) | 0x6000u); /* round toward zero */
    {
        nls_status s = nls_f4(a, b, c, d, p);
        _mm_setcsr(saved);
        CHECK_STATUS(s, NLS_STATUS_FP_ENVIRONMENT);
    }
    CHECK_STATUS(nls_f4(a, b, c, d, p), NLS_STATUS_OK);
#endif
}

int main(void) {
    test_version_and_status();
    test_cross_ratio();
    test_f4();
    test_f6();
    test_small_primitives();
    test_face_point();
    test_face_point_with_ids();
    test_quaternions();
    test_tangent_polygon_and_metrics();
    test_mobius_maps();
    test_canonical_forms();
    test_fp_environment();
    return nls_summary("ffi_tests/test_primitives");
}
