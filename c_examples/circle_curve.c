/* A circular curve from 4 control points: five levels of the circle blend (seed 003 §2) on a
 * closed polygon of 4 unevenly spaced points of a circle give 128 points of the same circle.
 * The points are written to circle_curve.txt, one "x y z" per line (the format of
 * `nlsubdiv curve`). For contrast, the linear 4-point scheme on the same polygon is printed
 * too: it leaves the circle.
 *
 * Build (from the repository root, after `cargo build --release -p nlsubdiv-ffi`):
 *   cc -std=c99 -Iinclude c_examples/circle_curve.c target/release/libnlsubdiv.a -lm -o circle_curve
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "nlsubdiv.h"

static const double CENTRE[3] = {1.0, 1.0, 1.0};
static const double RADIUS = 2.0;
static const double U[3] = {1.0, 0.0, 0.0};
static const double W[3] = {0.0, 0.6, 0.8}; /* orthonormal to U: a tilted plane */

/* The largest distance of the points from the circle, relative to the radius. */
static double deviation(const double *p, size_t count) {
    const double n[3] = {U[1] * W[2] - U[2] * W[1], U[2] * W[0] - U[0] * W[2], U[0] * W[1] - U[1] * W[0]};
    double worst = 0.0;
    size_t i;
    int k;
    for (i = 0; i < count; i++) {
        double d[3], z = 0.0, r2 = 0.0;
        for (k = 0; k < 3; k++) d[k] = p[3 * i + k] - CENTRE[k];
        for (k = 0; k < 3; k++) z += d[k] * n[k];
        for (k = 0; k < 3; k++) r2 += (d[k] - z * n[k]) * (d[k] - z * n[k]);
        {
            double dev = sqrt(z * z + (sqrt(r2) - RADIUS) * (sqrt(r2) - RADIUS)) / RADIUS;
            if (dev > worst) worst = dev;
        }
    }
    return worst;
}

/* Subdivides `control` with `scheme`; returns a malloc'd buffer of *count points or NULL. */
static double *subdivide(uint32_t scheme, const double *control, size_t n, uint32_t levels, size_t *count) {
    size_t need = 0, need_scratch = 0;
    double *out, *scratch;
    nls_status s;
    nls_curve_view curve;
    curve.points = control;
    curve.count = n;
    curve.closed = 1;
    if (nls_curve_refined_size(n, 1, levels, &need) != NLS_STATUS_OK ||
        nls_curve_scratch_size(scheme, n, 1, levels, &need_scratch) != NLS_STATUS_OK)
        return NULL;
    out = (double *)malloc(3 * need * sizeof(double));
    scratch = need_scratch ? (double *)malloc(3 * need_scratch * sizeof(double)) : NULL;
    if (out == NULL || (need_scratch && scratch == NULL)) {
        free(out);
        free(scratch);
        return NULL;
    }
    s = nls_curve_subdivide(scheme, &curve, levels, out, need, scratch, need_scratch, count, NULL);
    free(scratch);
    if (s != NLS_STATUS_OK) {
        fprintf(stderr, "nls_curve_subdivide: %s\n", nls_status_str(s));
        free(out);
        return NULL;
    }
    return out;
}

int main(void) {
    const double angles[4] = {0.0, 1.2, 2.9, 4.4}; /* unevenly spaced */
    const uint32_t levels = 5;
    double control[4 * 3];
    double *curve, *linear;
    size_t count = 0, linear_count = 0, i;
    int k;
    FILE *f;

    for (i = 0; i < 4; i++)
        for (k = 0; k < 3; k++)
            control[3 * i + k] = CENTRE[k] + RADIUS * (cos(angles[i]) * U[k] + sin(angles[i]) * W[k]);

    curve = subdivide(NLS_CURVE_CIRCLE_BLEND, control, 4, levels, &count);
    linear = subdivide(NLS_CURVE_FOUR_POINT, control, 4, levels, &linear_count);
    if (curve == NULL || linear == NULL) {
        free(curve);
        free(linear);
        return 1;
    }

    f = fopen("circle_curve.txt", "w");
    if (f == NULL) {
        perror("circle_curve.txt");
        free(curve);
        free(linear);
        return 1;
    }
    for (i = 0; i < count; i++) fprintf(f, "%.17g %.17g %.17g\n", curve[3 * i], curve[3 * i + 1], curve[3 * i + 2]);
    fclose(f);

    printf("nlsubdiv %s: %u levels of the circle blend on 4 points of a circle of radius %.1f\n", NLS_VERSION_STRING,
           (unsigned)levels, RADIUS);
    printf("  wrote %lu points to circle_curve.txt\n", (unsigned long)count);
    printf("  circle blend: largest distance from the circle / radius = %.2e\n", deviation(curve, count));
    printf("  4-point:      largest distance from the circle / radius = %.2e\n", deviation(linear, linear_count));
    {
        int ok = count == 128 && deviation(curve, count) < 1e-12;
        free(curve);
        free(linear);
        return ok ? 0 : 1;
    }
}
