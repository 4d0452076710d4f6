/* Minimal reproducer: nls_face_point is not invariant under a cyclic rotation of the face
 * (vertices and candidates rotated together; the same polygon with another first corner).
 *
 *   cc -std=c99 -Iinclude integrations/tests/face_point_start.c target/release/libnlsubdiv.a -lm && ./a.out
 *
 * A non-planar quad and four distinct candidates: the quadruplets i and i+2 are the same four
 * points reversed, so their noncircularity keys tie, the stable sort keeps face order, and the
 * F6 chain runs in another order / orientation when the face starts elsewhere. */
#include <math.h>
#include <stdio.h>

#include "nlsubdiv.h"

int main(void) {
    const double v[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.3}, {0, 1, 0}};
    const double c[4][3] = {{0.52, 0.47, 0.09}, {0.49, 0.52, 0.06}, {0.47, 0.50, 0.11}, {0.51, 0.49, 0.04}};
    double worst = 0.0, p0[3] = {0, 0, 0};
    int k, i, j;
    for (k = 0; k < 4; k++) {
        double vr[12], cr[12], p[3];
        for (i = 0; i < 4; i++)
            for (j = 0; j < 3; j++) {
                vr[3 * i + j] = v[(i + k) % 4][j];
                cr[3 * i + j] = c[(i + k) % 4][j];
            }
        if (nls_face_point(vr, cr, 4, p) != NLS_STATUS_OK) return 2;
        if (k == 0) for (j = 0; j < 3; j++) p0[j] = p[j];
        printf("start at corner %d: face point (%.17g, %.17g, %.17g)\n", k, p[0], p[1], p[2]);
        worst = fmax(worst, sqrt((p[0] - p0[0]) * (p[0] - p0[0]) + (p[1] - p0[1]) * (p[1] - p0[1]) + (p[2] - p0[2]) * (p[2] - p0[2])));
    }
    printf("largest distance from the start-0 result: %.3e (quad diagonal %.3f)\n", worst, sqrt(2.09));
    return worst > 1e-12;
}
