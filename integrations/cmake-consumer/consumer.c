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
    size_t su, sp, nv, nf, ni, k;
    double worst = 0.0;
    for (k = 0; k < 9; k++) off[k] = (uint32_t)(3 * k);
    if (nls_mesh_scratch_size(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, 6, 24, &su, &sp) != NLS_STATUS_OK) return 1;
    {
        uint32_t *scratch = malloc(su * sizeof *scratch);
        double *spts = malloc(3 * sp * sizeof *spts);
        double out_p[3 * 18];
        uint32_t out_o[33], out_i[96];
        nls_status s = nls_mesh_subdivide(NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, pos, 6, off, 8, idx, 24, scratch, su, spts, sp,
                                          out_p, 18, out_o, 32, out_i, 96, &nv, &nf, &ni, NULL, NULL);
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
