/* One level of Möbius Loop on an octahedron inscribed in the unit sphere, through the
 * installed C ABI; exits 0 when the counts are V+E, 4F and every new vertex is on the sphere. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "nlsubdiv.h"

int main(void) {
    static const double pos[] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const uint32_t idx[] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    uint32_t off[9];
    size_t su, sp, nv = 0, nf = 0, k;
    double worst = 0.0;
    nls_mesh_view mesh = {pos, 6, 0, NULL, 8, idx, 24};
    nls_subdivide_options options;
    nls_plan plan;
    for (k = 0; k < 9; k++) off[k] = (uint32_t)(3 * k);
    mesh.offsets = off;
    if (nls_subdivide_default_options(&options) != NLS_STATUS_OK) return 1;
    options.scheme = NLS_SCHEME_LOOP;
    options.flags = NLS_SUBDIVIDE_MOBIUS;
    if (nls_mesh_plan_scratch_size(&mesh, &su) != NLS_STATUS_OK) return 1;
    {
        uint32_t *scratch = malloc(su * sizeof *scratch);
        nls_status s = nls_mesh_plan(&mesh, &options, scratch, su, &plan, NULL);
        free(scratch);
        if (s != NLS_STATUS_OK) return 1;
        su = plan.scratch_u32;
        sp = plan.scratch_points;
    }
    {
        uint32_t *scratch = malloc(su * sizeof *scratch);
        double *spts = malloc(3 * sp * sizeof *spts);
        double out_p[3 * 18];
        uint32_t out_o[33], out_i[96];
        nls_scratch sc;
        nls_mesh_buffers out = {NULL, 18, NULL, 32, NULL, 96};
        nls_mesh_sizes written = {0, 0, 0};
        nls_status s;
        sc.u32s = scratch;
        sc.u32_capacity = su;
        sc.points = spts;
        sc.point_capacity = sp;
        out.positions = out_p;
        out.offsets = out_o;
        out.indices = out_i;
        s = nls_mesh_subdivide(&mesh, &options, &sc, &out, &written, NULL, NULL);
        nv = written.vertex_count;
        nf = written.face_count;
        free(scratch);
        free(spts);
        if (s != NLS_STATUS_OK) {
            printf("consumer: %s\n", nls_status_str(s));
            return 1;
        }
        for (k = 0; k < nv; k++) {
            double r = sqrt(out_p[3 * k] * out_p[3 * k] + out_p[3 * k + 1] * out_p[3 * k + 1] + out_p[3 * k + 2] * out_p[3 * k + 2]);
            if (fabs(r - 1.0) > worst) worst = fabs(r - 1.0);
        }
    }
    printf("consumer: nlsubdiv %u.%u.%u (header %s): Moebius Loop octahedron -> %zu vertices, %zu faces, max |r-1| = %.1e\n",
           nls_version() >> 16, (nls_version() >> 8) & 255u, nls_version() & 255u, NLS_VERSION_STRING, nv, nf, worst);
    return (nv == 18 && nf == 32 && worst < 1e-12) ? 0 : 1;
}
