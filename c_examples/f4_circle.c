/* F4 on four points of a circle: the new point lies on the same circle, between b and c.
 *
 * Build (from the repository root, after `cargo build --release -p nlsubdiv-ffi`):
 *   cc -std=c99 -Iinclude c_examples/f4_circle.c target/release/libnlsubdiv.a -lm -o f4_circle
 */
#include <math.h>
#include <stdio.h>

#include "nlsubdiv.h"

int main(void) {
    /* A circle of radius 2 centred at (1, 1, 1) in a tilted plane, sampled unevenly. */
    const double centre[3] = {1.0, 1.0, 1.0}, radius = 2.0;
    const double u[3] = {1.0, 0.0, 0.0};
    const double w[3] = {0.0, 0.6, 0.8}; /* orthonormal to u */
    const double angles[4] = {0.0, 0.5, 1.4, 2.1};
    double p[4][3], out[3];
    int i, k;
    for (i = 0; i < 4; i++)
        for (k = 0; k < 3; k++)
            p[i][k] = centre[k] + radius * (cos(angles[i]) * u[k] + sin(angles[i]) * w[k]);

    nls_status s = nls_f4(p[0], p[1], p[2], p[3], out);
    if (s != NLS_STATUS_OK) {
        fprintf(stderr, "nls_f4 failed: %s\n", nls_status_str(s));
        return 1;
    }
    double d[3], dist = 0.0, off_plane = 0.0;
    for (k = 0; k < 3; k++) d[k] = out[k] - centre[k];
    for (k = 0; k < 3; k++) dist += d[k] * d[k];
    dist = sqrt(dist);
    /* the plane normal is u x w */
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    for (k = 0; k < 3; k++) off_plane += d[k] * n[k];
    double angle = atan2(d[0] * w[0] + d[1] * w[1] + d[2] * w[2], d[0] * u[0] + d[1] * u[1] + d[2] * u[2]);

    printf("nlsubdiv %s: F4 of four points on a circle of radius %.1f\n", NLS_VERSION_STRING, radius);
    printf("  new point      (%.15f, %.15f, %.15f)\n", out[0], out[1], out[2]);
    printf("  |p - centre| - r = %.3e   distance from the plane = %.3e\n", dist - radius, off_plane);
    printf("  angle on the circle = %.6f (between b at %.1f and c at %.1f)\n", angle, angles[1], angles[2]);
    return (fabs(dist - radius) < 1e-12 && fabs(off_plane) < 1e-12 && angle > angles[1] && angle < angles[2]) ? 0 : 1;
}
