/* nlsubdiv on a Cortex-M: F4 of four points on the unit circle, then two levels of the
 * canonical Möbius Catmull–Clark scheme on a cube inscribed in a sphere, in static buffers
 * (no heap). Both results must stay on their circle / sphere (seed 000 §4.4.1, §4); the
 * program prints them and exits 0 when they do, 1 otherwise. Output goes through
 * semihosting (QEMU's stdout). */
#include <math.h>
#include <stdio.h>

#include "nls_port.h"
#include "nlsubdiv.h"

/* Cube [−1, 1]³, radius √3; faces counter-clockwise seen from outside. */
static const double CUBE_P[8 * 3] = {-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1,
                                     -1, -1, 1,  1, -1, 1,  -1, 1, 1,  1, 1, 1};
static const uint32_t CUBE_O[7] = {0, 4, 8, 12, 16, 20, 24};
static const uint32_t CUBE_I[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 1, 3, 7, 5, 0, 4, 6, 2};

/* Two levels of Catmull–Clark on the cube: 26 then 98 vertices, 24 then 96 quads. The
 * scratch holds the topology, the intermediate level and the Möbius candidates; the sizes
 * here are generous, and nls_mesh_plan gives the exact ones at run time
 * (a short buffer is NLS_STATUS_BUFFER_TOO_SMALL, never an overrun). */
#define MAX_VERTICES 98
#define MAX_FACES 96
#define MAX_CORNERS 384
static double positions[3 * MAX_VERTICES];
static uint32_t offsets[MAX_FACES + 1], indices[MAX_CORNERS];
static uint32_t scratch_u32[4096];
static double scratch_points[3 * 1024];

int main(void) {
    static const double a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3] = {-1, 0, 0}, d[3] = {0, -1, 0};
    const port_mesh cube = {CUBE_P, 8, CUBE_O, 6, CUBE_I, 24};
    port_buffers out = {positions, MAX_VERTICES, offsets, MAX_FACES, indices, MAX_CORNERS,
                        scratch_u32, sizeof scratch_u32 / sizeof scratch_u32[0],
                        scratch_points, sizeof scratch_points / sizeof scratch_points[0] / 3, 0, 0, 0, 0};
    double p[3], worst = 0;
    size_t i;
    uint32_t s;

    printf("nlsubdiv %s on a Cortex-M\n", NLS_VERSION_STRING);
    s = nls_f4(a, b, c, d, p);
    if (s != NLS_STATUS_OK) {
        printf("nls_f4: %s\n", nls_status_str(s));
        return 1;
    }
    printf("F4 on the unit circle: (%.17g, %.17g, %.17g), |p| - 1 = %.3g\n", p[0], p[1], p[2],
           sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1);

    s = port_mesh_subdivide(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 2, &cube, &out);
    if (s != NLS_STATUS_OK) {
        printf("mesh: %s (element %u)\n", nls_status_str(s), (unsigned)out.element);
        return 1;
    }
    for (i = 0; i < out.vertex_count; i++) {
        const double *q = &positions[3 * i];
        double e = fabs(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - sqrt(3.0));
        if (e > worst) worst = e;
    }
    printf("Möbius Catmull–Clark, 2 levels: %u vertices, %u faces; largest distance from the sphere %.3g\n",
           (unsigned)out.vertex_count, (unsigned)out.face_count, worst);
    return fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1) < 1e-12 && worst < 1e-9 ? 0 : 1;
}
