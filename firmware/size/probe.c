/* One firmware image per PROBE_* macro, for the code-size table (firmware/size.sh): each
 * calls one path of the library and nothing else (no printf), with inputs read through
 * volatile so that nothing is folded away. Mesh and curve calls go through the harness's
 * adapter (firmware/harness/calls.c), as every caller in firmware/ does. */
#include <stdint.h>

#include "calls.h"
#include "nlsubdiv.h"

static volatile double sink;
static volatile uint32_t runtime_scheme = NLS_SCHEME_LOOP, runtime_flags = 0;

static const double TRI_P[4 * 3] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
static const uint32_t TRI_O[5] = {0, 3, 6, 9, 12};
static const uint32_t TRI_I[12] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};

int main(void) {
    volatile double x = 1.0;
    const double a[3] = {x, 0, 0}, b[3] = {0, x, 0}, c[3] = {-x, 0, 0}, d[3] = {0, -x, 0};
    double out[3] = {0};
    uint32_t s = 0;
    (void)a, (void)b, (void)c, (void)d, (void)out;
#if defined(PROBE_BASELINE)
    s = nls_version();
#elif defined(PROBE_F4)
    s = nls_f4(a, b, c, d, out);
#elif defined(PROBE_CURVE)
    {
        const double pts[4 * 3] = {a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2]};
        fw_curve_result r;
        s = fw_curve_subdivide(NLS_CURVE_MOBIUS_INTERPOLATING, pts, 4, 1, 2, &r);
        out[0] = r.points ? r.points[0] : 0;
    }
#elif defined(PROBE_MESH)
    {
        /* PROBE_MESH: the flags, and PROBE_SCHEME the scheme (Loop unless given), as
         * constants (one scheme's path) or, with PROBE_RUNTIME, read at run time (any
         * scheme). The library still receives them as run-time arguments: what it links
         * depends on the schemes it was built with (its Cargo features), not on these. */
        const fw_mesh m = {TRI_P, 4, TRI_O, 4, TRI_I, 12};
        fw_mesh_result r;
#if defined(PROBE_RUNTIME)
        s = fw_mesh_subdivide(runtime_scheme, runtime_flags, 1, &m, &r);
#else
#if !defined(PROBE_SCHEME)
#define PROBE_SCHEME NLS_SCHEME_LOOP
#endif
        s = fw_mesh_subdivide(PROBE_SCHEME, PROBE_MESH, 1, &m, &r);
#endif
        out[0] = r.positions ? r.positions[0] : 0;
    }
#endif
    sink = out[0];
    return (int)s;
}
