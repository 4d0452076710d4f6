/* C99 tests of the curve exports of nlsubdiv.h: sizes, every scheme, circle reproduction,
 * interpolation, NULL / misaligned / aliasing pointers, every too-small buffer size (fresh
 * heap buffers so that ASan sees any overrun), bad input, the floating-point-environment
 * guard, and "out-params written only on success". Run under ASan+UBSan and valgrind. */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include "nlsubdiv.h"
#include "check.h"
#include "flat_args.h"

#define NSCHEMES 7
static const uint32_t SCHEMES[NSCHEMES] = {
    NLS_CURVE_FOUR_POINT,          NLS_CURVE_BSPLINE,      NLS_CURVE_MOBIUS_INTERPOLATING,
    NLS_CURVE_MOBIUS_APPROXIMATING, NLS_CURVE_CIRCLE_BLEND, NLS_CURVE_DIFFERENTIAL_FOUR_POINT,
    NLS_CURVE_DIFFERENTIAL_BSPLINE};

static int is_interpolating(uint32_t s) {
    return s == NLS_CURVE_FOUR_POINT || s == NLS_CURVE_MOBIUS_INTERPOLATING || s == NLS_CURVE_CIRCLE_BLEND;
}

static int is_circle_preserving(uint32_t s) {
    return s == NLS_CURVE_MOBIUS_INTERPOLATING || s == NLS_CURVE_MOBIUS_APPROXIMATING || s == NLS_CURVE_CIRCLE_BLEND;
}

/* A circle of radius r about (1, -2, 0.5) in a tilted plane, unevenly sampled. */
static const double CENTRE[3] = {1.0, -2.0, 0.5};
static const double U[3] = {0.6, 0.8, 0.0};
static const double W[3] = {0.0, 0.0, 1.0};

static void on_circle(double t, double r, double *out) {
    int k;
    for (k = 0; k < 3; k++) out[k] = CENTRE[k] + r * (cos(t) * U[k] + sin(t) * W[k]);
}

static double circle_deviation(const double *p, double r) {
    double d[3], z = 0.0, inplane[3], len = 0.0;
    const double n[3] = {U[1] * W[2] - U[2] * W[1], U[2] * W[0] - U[0] * W[2], U[0] * W[1] - U[1] * W[0]};
    int k;
    for (k = 0; k < 3; k++) d[k] = p[k] - CENTRE[k];
    for (k = 0; k < 3; k++) z += d[k] * n[k];
    for (k = 0; k < 3; k++) inplane[k] = d[k] - z * n[k];
    for (k = 0; k < 3; k++) len += inplane[k] * inplane[k];
    len = sqrt(len);
    return sqrt(z * z + (len - r) * (len - r)) / r;
}

static void sample(double *pts, size_t n, double r, int closed) {
    size_t i;
    double t = 0.3;
    for (i = 0; i < n; i++) {
        on_circle(t, r, pts + 3 * i);
        /* uneven steps; an open curve covers about 1.6 pi, a closed one the whole circle */
        t += (closed ? 2.0 * 3.14159265358979323846 / (double)n : 1.6 * 3.14159265358979323846 / (double)(n - 1)) *
             (1.0 + 0.4 * sin(3.0 * (double)i));
    }
}

/* Subdivides with exactly sized heap buffers; returns the status, the output in *res. */
static nls_status run(uint32_t scheme, const double *pts, size_t n, uint32_t closed, uint32_t levels, double **res,
                      size_t *count) {
    size_t need = 0, need_s = 0;
    nls_status s = nls_curve_refined_size(n, closed, levels, &need);
    if (s != NLS_STATUS_OK) return s;
    s = nls_curve_scratch_size(scheme, n, closed, levels, &need_s);
    if (s != NLS_STATUS_OK) return s;
    *res = (double *)malloc(3 * need * sizeof(double));
    {
        double *scratch = need_s ? (double *)malloc(3 * need_s * sizeof(double)) : NULL;
        uint32_t element = 0;
        s = flat_curve_subdivide(scheme, pts, n, closed, levels, *res, need, scratch, need_s, count, &element);
        free(scratch);
    }
    return s;
}

static void test_sizes(void) {
    size_t len = 777;
    CHECK_STATUS(nls_curve_refined_size(4, 1, 3, &len), NLS_STATUS_OK);
    CHECK(len == 32);
    CHECK_STATUS(nls_curve_refined_size(4, 0, 3, &len), NLS_STATUS_OK);
    CHECK(len == 25);
    CHECK_STATUS(nls_curve_refined_size(7, 1, 0, &len), NLS_STATUS_OK);
    CHECK(len == 7);
    len = 777;
    CHECK_STATUS(nls_curve_refined_size(2, 1, 3, &len), NLS_STATUS_TOO_FEW_POINTS);
    CHECK_STATUS(nls_curve_refined_size(1, 0, 3, &len), NLS_STATUS_TOO_FEW_POINTS);
    CHECK_STATUS(nls_curve_refined_size(3, 1, 64, &len), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(nls_curve_refined_size(SIZE_MAX / 2 + 1, 1, 1, &len), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(nls_curve_refined_size(4, 2, 3, &len), NLS_STATUS_INVALID_ARGUMENT);
    CHECK(len == 777); /* not written on failure */
    CHECK_STATUS(nls_curve_refined_size(4, 1, 3, NULL), NLS_STATUS_NULL_PARAMETER);

    CHECK_STATUS(nls_curve_scratch_size(NLS_CURVE_FOUR_POINT, 5, 1, 1, &len), NLS_STATUS_OK);
    CHECK(len == 0);
    CHECK_STATUS(nls_curve_scratch_size(NLS_CURVE_DIFFERENTIAL_BSPLINE, 5, 1, 1, &len), NLS_STATUS_OK);
    CHECK(len == 5);
    CHECK_STATUS(nls_curve_scratch_size(NLS_CURVE_CIRCLE_BLEND, 5, 0, 3, &len), NLS_STATUS_OK);
    CHECK(len == 17);
    len = 777;
    CHECK_STATUS(nls_curve_scratch_size(7u, 5, 1, 1, &len), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(nls_curve_scratch_size(0xFFFFFFFFu, 5, 1, 1, &len), NLS_STATUS_INVALID_ARGUMENT);
    CHECK(len == 777);
    {
        union {
            size_t s[2];
            unsigned char c[2 * sizeof(size_t)];
        } raw; /* aligned for size_t, so c + 1 is not */
        size_t *mis = (size_t *)(void *)(raw.c + 1);
        CHECK_STATUS(nls_curve_refined_size(4, 1, 3, mis), NLS_STATUS_MISALIGNED_POINTER);
    }
}

static void test_circles_and_interpolation(void) {
    const double r = 2.5;
    int si, closed;
    double worst = 0.0;
    for (si = 0; si < NSCHEMES; si++) {
        for (closed = 0; closed <= 1; closed++) {
            double pts[3 * 7];
            double *res = NULL;
            size_t count = 0, i, need = 0;
            const uint32_t levels = 4;
            sample(pts, 7, r, closed);
            CHECK_STATUS(run(SCHEMES[si], pts, 7, (uint32_t)closed, levels, &res, &count), NLS_STATUS_OK);
            CHECK_STATUS(nls_curve_refined_size(7, (uint32_t)closed, levels, &need), NLS_STATUS_OK);
            CHECK(count == need);
            for (i = 0; i < count; i++) CHECK(isfinite(res[3 * i]) && isfinite(res[3 * i + 1]) && isfinite(res[3 * i + 2]));
            if (is_circle_preserving(SCHEMES[si])) {
                for (i = 0; i < count; i++) {
                    double dev = circle_deviation(res + 3 * i, r);
                    if (dev > worst) worst = dev;
                    CHECK(dev < 1e-12);
                }
            }
            if (is_interpolating(SCHEMES[si])) {
                for (i = 0; i < 7; i++) CHECK(memcmp(res + 3 * (i << levels), pts + 3 * i, 3 * sizeof(double)) == 0);
            }
            if (!closed) { /* end points kept by every scheme */
                CHECK(memcmp(res, pts, 3 * sizeof(double)) == 0);
                CHECK(memcmp(res + 3 * (count - 1), pts + 3 * 6, 3 * sizeof(double)) == 0);
            }
            free(res);
        }
    }
    printf("test_curve: worst circle deviation %.2e\n", worst);
}

static void test_levels_zero_and_two_points(void) {
    const double two[6] = {0.0, 0.0, 0.0, 2.0, 4.0, -6.0};
    int si;
    for (si = 0; si < NSCHEMES; si++) {
        double *res = NULL;
        size_t count = 0;
        CHECK_STATUS(run(SCHEMES[si], two, 2, 0, 1, &res, &count), NLS_STATUS_OK);
        CHECK(count == 3);
        {
            const double mid[3] = {1.0, 2.0, -3.0};
            CHECK(nls_dist3(res + 3, mid) < 1e-15);
        }
        free(res);
        CHECK_STATUS(run(SCHEMES[si], two, 2, 0, 0, &res, &count), NLS_STATUS_OK);
        CHECK(count == 2 && memcmp(res, two, sizeof two) == 0);
        free(res);
    }
}

static void test_buffer_sizes(void) {
    double pts[3 * 5];
    int si, closed;
    sample(pts, 5, 1.0, 1);
    for (si = 0; si < NSCHEMES; si++) {
        for (closed = 0; closed <= 1; closed++) {
            const uint32_t levels = 3;
            size_t need = 0, need_s = 0, cap;
            CHECK_STATUS(nls_curve_refined_size(5, (uint32_t)closed, levels, &need), NLS_STATUS_OK);
            CHECK_STATUS(nls_curve_scratch_size(SCHEMES[si], 5, (uint32_t)closed, levels, &need_s), NLS_STATUS_OK);
            /* every short output, with a fresh exact-size heap buffer */
            for (cap = 0; cap < need; cap++) {
                double *out = cap ? (double *)malloc(3 * cap * sizeof(double)) : NULL;
                double *scratch = (double *)malloc(3 * need_s * sizeof(double) + 1);
                size_t count = 0;
                CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], pts, 5, (uint32_t)closed, levels, out, cap, scratch,
                                                 need_s, &count, NULL),
                             NLS_STATUS_BUFFER_TOO_SMALL);
                CHECK(count == need);
                free(out);
                free(scratch);
            }
            /* every short scratch */
            for (cap = 0; cap < need_s; cap++) {
                double *out = (double *)malloc(3 * need * sizeof(double));
                double *scratch = cap ? (double *)malloc(3 * cap * sizeof(double)) : NULL;
                size_t count = 0;
                CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], pts, 5, (uint32_t)closed, levels, out, need, scratch,
                                                 cap, &count, NULL),
                             NLS_STATUS_BUFFER_TOO_SMALL);
                CHECK(count == need_s);
                free(out);
                free(scratch);
            }
            /* exact sizes succeed */
            {
                double *out = (double *)malloc(3 * need * sizeof(double));
                double *scratch = need_s ? (double *)malloc(3 * need_s * sizeof(double)) : NULL;
                size_t count = 0;
                CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], pts, 5, (uint32_t)closed, levels, out, need, scratch,
                                                 need_s, &count, NULL),
                             NLS_STATUS_OK);
                CHECK(count == need);
                free(out);
                free(scratch);
            }
        }
    }
}

static void test_bad_input(void) {
    double pts[3 * 6], out[3 * 96], scratch[3 * 48];
    size_t count = 777;
    uint32_t element = 12345;
    int si;
    sample(pts, 6, 1.0, 1);

    /* unknown scheme, bad flag */
    CHECK_STATUS(flat_curve_subdivide(7u, pts, 6, 1, 2, out, 96, scratch, 48, &count, &element),
                 NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 3, 2, out, 96, scratch, 48, &count, &element),
                 NLS_STATUS_INVALID_ARGUMENT);
    CHECK(element == NLS_NO_ELEMENT);
    /* NULL pointers */
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, NULL, 6, 1, 2, out, 96, scratch, 48, &count, NULL),
                 NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 2, NULL, 96, scratch, 48, &count, NULL),
                 NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 2, out, 96, NULL, 48, &count, NULL),
                 NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 2, out, 96, scratch, 48, NULL, NULL),
                 NLS_STATUS_NULL_PARAMETER);
    /* NULL with capacity 0 is an empty buffer: too small here */
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 2, NULL, 0, scratch, 48, &count, NULL),
                 NLS_STATUS_BUFFER_TOO_SMALL);
    CHECK(count == 24);
    count = 777;
    /* ... and fine for one level, which needs no scratch */
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 1, out, 96, NULL, 0, &count, NULL), NLS_STATUS_OK);
    CHECK(count == 12);
    count = 777;
    /* misaligned buffers */
    {
        union {
            double d[3 * 24 + 1];
            unsigned char c[sizeof(double) * (3 * 24 + 1)];
        } raw; /* aligned for double, so c + 1 is aligned for neither double nor uint32_t */
        double *mis = (double *)(void *)(raw.c + 1);
        CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 2, mis, 24, scratch, 48, &count, NULL),
                     NLS_STATUS_MISALIGNED_POINTER);
        CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 2, out, 96, scratch, 48, &count,
                                         (uint32_t *)(void *)(raw.c + 1)),
                     NLS_STATUS_MISALIGNED_POINTER);
    }
    /* huge counts */
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, SIZE_MAX / 8, 1, 2, out, 96, scratch, 48, &count, NULL),
                 NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_BSPLINE, pts, 6, 1, 62, out, 96, scratch, 48, &count, NULL),
                 NLS_STATUS_SIZE_OVERFLOW);
    CHECK(count == 777);
    /* aliasing: output over the input, scratch over the output, input inside scratch */
    {
        double *buf = (double *)malloc(3 * 200 * sizeof(double));
        memcpy(buf, pts, sizeof pts);
        CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf, 6, 1, 2, buf + 3, 24, scratch, 48, &count, NULL),
                     NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, pts, 6, 1, 2, buf, 24, buf + 3 * 23, 12, &count, NULL),
                     NLS_STATUS_ALIASING_BUFFERS);
        CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf + 3 * 100, 6, 1, 2, out, 24, buf + 3 * 95, 12,
                                         &count, NULL),
                     NLS_STATUS_ALIASING_BUFFERS);
        /* adjacent but disjoint is fine */
        CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf, 6, 1, 2, buf + 3 * 6, 24, buf + 3 * 30, 12, &count,
                                         NULL),
                     NLS_STATUS_OK);
        CHECK(count == 24);
        /* out_count or out_element inside the input, the output or the scratch: refused, nothing
         * written there */
        {
            uint32_t element = 12345;
            double keep = buf[3 * 6 + 4];
            CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf, 6, 1, 2, buf + 3 * 6, 24, buf + 3 * 30, 12,
                                              (size_t *)(void *)(buf + 3 * 6 + 4), &element),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK(buf[3 * 6 + 4] == keep && element == NLS_NO_ELEMENT);
            CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf, 6, 1, 2, buf + 3 * 6, 24, buf + 3 * 30, 12,
                                              (size_t *)(void *)(buf + 1), NULL),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf, 6, 1, 2, buf + 3 * 6, 24, buf + 3 * 30, 12,
                                              (size_t *)(void *)(buf + 3 * 31), NULL),
                         NLS_STATUS_ALIASING_BUFFERS);
            keep = buf[3 * 10];
            CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf, 6, 1, 2, buf + 3 * 6, 24, buf + 3 * 30, 12,
                                              &count, (uint32_t *)(void *)(buf + 3 * 10)),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK(buf[3 * 10] == keep);
            CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_FOUR_POINT, buf, 6, 1, 2, buf + 3 * 6, 24, buf + 3 * 30, 12,
                                              &count, (uint32_t *)(void *)&count),
                         NLS_STATUS_ALIASING_BUFFERS);
            CHECK_STATUS(nls_curve_subdivide(NLS_CURVE_FOUR_POINT, NULL, 2, buf + 3 * 6, 24, buf + 3 * 30, 12, &count,
                                             &element),
                         NLS_STATUS_NULL_PARAMETER);
        }
        free(buf);
    }
    count = 777;
    /* too few points */
    for (si = 0; si < NSCHEMES; si++) {
        CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], pts, 2, 1, 2, out, 96, scratch, 48, &count, NULL),
                     NLS_STATUS_TOO_FEW_POINTS);
        CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], pts, 1, 0, 2, out, 96, scratch, 48, &count, NULL),
                     NLS_STATUS_TOO_FEW_POINTS);
        CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], NULL, 0, 0, 2, out, 96, scratch, 48, &count, NULL),
                     NLS_STATUS_TOO_FEW_POINTS);
    }
    CHECK(count == 777);
    /* non-finite input names the point */
    for (si = 0; si < NSCHEMES; si++) {
        double bad[3 * 6];
        memcpy(bad, pts, sizeof bad);
        bad[3 * 4 + 1] = NAN;
        element = 0;
        CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], bad, 6, 1, 2, out, 96, scratch, 48, &count, &element),
                     NLS_STATUS_NON_FINITE_INPUT);
        CHECK(element == 4);
        bad[3 * 4 + 1] = 0.0;
        bad[0] = -INFINITY;
        CHECK_STATUS(flat_curve_subdivide(SCHEMES[si], bad, 6, 0, 0, out, 96, scratch, 48, &count, &element),
                     NLS_STATUS_NON_FINITE_INPUT);
        CHECK(element == 0);
    }
    CHECK(count == 777);
    /* repeated points: the circle blend refuses, the Möbius schemes keep the point */
    {
        double rep[3 * 6];
        double *res = NULL;
        size_t n = 0;
        memcpy(rep, pts, sizeof rep);
        memcpy(rep + 3 * 3, rep + 3 * 2, 3 * sizeof(double));
        element = 0;
        CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_CIRCLE_BLEND, rep, 6, 1, 1, out, 96, scratch, 48, &count, &element),
                     NLS_STATUS_DEGENERATE_GEOMETRY);
        CHECK(element == 1); /* segment P1 P2 is the first whose second circle uses P2 = P3 */
        CHECK_STATUS(run(NLS_CURVE_MOBIUS_INTERPOLATING, rep, 6, 1, 1, &res, &n), NLS_STATUS_OK);
        CHECK(n == 12 && memcmp(res + 3 * 5, rep + 3 * 2, 3 * sizeof(double)) == 0);
        free(res);
    }
}

static void test_fp_environment(void) {
#if defined(__x86_64__)
    double pts[3 * 4], out[3 * 8];
    size_t count = 777;
    if (getenv("NLS_TEST_UNDER_VALGRIND") != NULL) {
        printf("SKIP test_fp_environment under valgrind\n");
        return;
    }
    sample(pts, 4, 1.0, 1);
    {
        unsigned int saved = _mm_getcsr();
        nls_status s;
        _mm_setcsr(saved | 0x8040u); /* FTZ + DAZ */
        s = flat_curve_subdivide(NLS_CURVE_MOBIUS_INTERPOLATING, pts, 4, 1, 1, out, 8, NULL, 0, &count, NULL);
        _mm_setcsr(saved);
        CHECK_STATUS(s, NLS_STATUS_FP_ENVIRONMENT);
        CHECK(count == 777);
    }
    CHECK_STATUS(flat_curve_subdivide(NLS_CURVE_MOBIUS_INTERPOLATING, pts, 4, 1, 1, out, 8, NULL, 0, &count, NULL),
                 NLS_STATUS_OK);
    CHECK(count == 8);
#endif
}

int main(void) {
    test_sizes();
    test_circles_and_interpolation();
    test_levels_zero_and_two_points();
    test_buffer_sizes();
    test_bad_input();
    test_fp_environment();
    return nls_summary("ffi_tests/test_curve");
}
