/* Check (formerly the reproducer of a defect, now fixed): the Möbius face points do not
 * depend on which corner a face starts at.
 *
 *   cc -std=c99 -Iinclude integrations/tests/face_point_start.c target/release/libnlsubdiv.a -lm -o face_point_start
 *   ./face_point_start        # prints the displacements; exit 1 if the dependence is back
 *
 * 1. One level of NLS_SCHEME_CATMULL_CLARK | NLS_SUBDIVIDE_MOBIUS on the tetrahedron of
 *    ../shared/data/meshes/tetrahedron.off, once as given and once with every face's corner
 *    list rotated by one (the same triangles, same orientation). The face points are output
 *    vertices nv + ne + f in face order, so they can be compared index by index.
 * 2. nls_face_point_with_ids on one face, with the vertices, candidates and ids rotated
 *    together (plain nls_face_point keeps the paper's face-order tie-break and depends on it).
 * The former cause (src/blend/face_point.rs): the quadruplets are sorted by noncircularity with a stable
 * sort; equal keys (always for quadruplets i and i + d/2 of an even face, and for every
 * quadruplet of a symmetric face such as the tetrahedron's) keep face order, and the F6
 * chain F6(a_prev, v_f, d_prev, a, p, d) is neither commutative in its order nor symmetric in
 * (a, d), so a rotation changed the result (3.6e-2 of the diagonal here). The drivers now
 * break ties by vertex id (blend::face_point_with_ids). */
#include <math.h>
#include <stdio.h>

#include "nlsubdiv.h"

static double dist(const double *a, const double *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

static int level(const uint32_t *idx, double *out) {
    static const double pos[] = {0.0, 0.0, 2.0, 1.632993, -0.942809, -0.666667, 0.0, 1.885618, -0.666667, -1.632993, -0.942809, -0.666667};
    static const uint32_t off[] = {0, 3, 6, 9, 12};
    uint32_t scratch[128], out_off[13], out_idx[48];
    double spts[3 * 24];
    const nls_mesh_view mesh = {pos, 4, 0, off, 4, idx, 12};
    const nls_subdivide_options options = {NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 1, 0.0, NULL, NULL};
    const nls_scratch s = {scratch, 128, spts, 24};
    const nls_mesh_buffers b = {out, 14, out_off, 12, out_idx, 48};
    nls_mesh_sizes written;
    return nls_mesh_subdivide(&mesh, &options, &s, &b, &written, NULL, NULL) != NLS_STATUS_OK;
}

int main(void) {
    static const uint32_t given[] = {0, 1, 2, 2, 1, 3, 3, 1, 0, 3, 0, 2};
    static const uint32_t rotated[] = {1, 2, 0, 1, 3, 2, 1, 0, 3, 0, 2, 3};
    double a[3 * 14], b[3 * 14], worst = 0.0;
    int f, k;
    if (level(given, a) || level(rotated, b)) return 2;
    for (f = 0; f < 4; f++) {
        double d = dist(a + 3 * (10 + f), b + 3 * (10 + f));
        printf("tetrahedron, Moebius Catmull-Clark, face point %d: moves by %.3e when the face starts one corner later\n", f, d);
        if (d > worst) worst = d;
    }
    printf("largest: %.3e = %.2e of the bounding-box diagonal (3.771)\n", worst, worst / 3.771);
    {
        const double v[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0.3, 0, 1, 0};
        const double c[12] = {0.62, 0.37, 0.19, 0.39, 0.62, 0.01, 0.37, 0.40, 0.21, 0.61, 0.59, -0.06};
        const uint32_t ids[4] = {5, 2, 9, 7}, idr[4] = {2, 9, 7, 5};
        double p0[3], p1[3], vr[12], cr[12];
        for (k = 0; k < 12; k++) {
            vr[k] = v[(k + 3) % 12];
            cr[k] = c[(k + 3) % 12];
        }
        if (nls_face_point_with_ids(v, c, ids, 4, p0) != NLS_STATUS_OK || nls_face_point_with_ids(vr, cr, idr, 4, p1) != NLS_STATUS_OK) return 2;
        printf("nls_face_point_with_ids on a quad, inputs rotated by one corner: moves by %.3e\n", dist(p0, p1));
        if (dist(p0, p1) > worst) worst = dist(p0, p1);
    }
    return worst > 1e-12;
}
