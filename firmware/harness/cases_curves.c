/* Every curve scheme on an open and a closed polygon at 1 and 3 levels, the circle blend and
 * the Möbius schemes on a circle, and one documented error. */
#include <math.h>
#include <stdio.h>

#include "calls.h"
#include "harness.h"
#include "meshes.h"
#include "nlsubdiv.h"

static const struct {
    uint32_t scheme;
    const char *name;
    int interpolating; /* the old points stay, bit for bit, at every 2^levels-th place */
} SCHEMES[] = {
    {NLS_CURVE_FOUR_POINT, "four_point", 1},
    {NLS_CURVE_BSPLINE, "bspline", 0},
    {NLS_CURVE_MOBIUS_INTERPOLATING, "mobius_interpolating", 1},
    {NLS_CURVE_MOBIUS_APPROXIMATING, "mobius_approximating", 0},
    {NLS_CURVE_CIRCLE_BLEND, "circle_blend", 1},
    {NLS_CURVE_DIFFERENTIAL_FOUR_POINT, "differential_four_point", 0},
    {NLS_CURVE_DIFFERENTIAL_BSPLINE, "differential_bspline", 0},
};

static void one(uint32_t scheme, const char *scheme_name, int interpolating, const char *curve_name,
                const double *points, size_t count, uint32_t closed, uint32_t levels, int on_circle,
                uint32_t expected) {
    char name[96];
    fw_curve_result r;
    fw_hash *h;
    uint32_t s;
    snprintf(name, sizeof name, "curve/%s/%s/L%u", scheme_name, curve_name, (unsigned)levels);
    h = fw_case_begin("curve subdivide", name);
    s = fw_curve_subdivide(scheme, points, count, closed, levels, &r);
    if (s == NLS_STATUS_OK) {
        size_t step = (size_t)1 << levels, i;
        fw_hash_u64(h, r.count);
        fw_hash_f64s(h, r.points, 3 * r.count);
        fw_check(r.count == (closed ? count * step : (count - 1) * step + 1), "wrong point count");
        /* interpolating schemes keep the old points (except the differential ones, which are
         * reconstructed; they are not in this group) */
        for (i = 0; interpolating && i < count && i * step < r.count; i++)
            fw_check(fw_same_bits(&r.points[3 * i * step], &points[3 * i], 3), "an old point moved");
        for (i = 0; on_circle && i < r.count; i++) {
            const double *p = &r.points[3 * i];
            fw_check(fabs(p[0] * p[0] + p[1] * p[1] - 1) < 1e-13 && p[2] == 0, "a point left the circle");
        }
    } else {
        fw_hash_u32(h, r.element);
    }
    fw_case_end(s, expected);
}

void fw_cases_curves(void) {
    size_t k;
    uint32_t levels;
    for (k = 0; k < sizeof SCHEMES / sizeof SCHEMES[0]; k++)
        for (levels = 1; levels <= 3; levels += 2) {
            one(SCHEMES[k].scheme, SCHEMES[k].name, SCHEMES[k].interpolating, "open5", fw_curve_open, 5, 0,
                levels, 0, NLS_STATUS_OK);
            one(SCHEMES[k].scheme, SCHEMES[k].name, SCHEMES[k].interpolating, "closed6", fw_curve_closed, 6, 1,
                levels, 0, NLS_STATUS_OK);
        }
    /* circle preserving schemes keep the cocircular square on its circle (seed 000 §4.4.1,
     * seed 003 §2) */
    one(NLS_CURVE_MOBIUS_INTERPOLATING, "mobius_interpolating", 1, "circle4", fw_curve_circle, 4, 1, 3, 1,
        NLS_STATUS_OK);
    one(NLS_CURVE_MOBIUS_APPROXIMATING, "mobius_approximating", 0, "circle4", fw_curve_circle, 4, 1, 3, 1,
        NLS_STATUS_OK);
    one(NLS_CURVE_CIRCLE_BLEND, "circle_blend", 1, "circle4", fw_curve_circle, 4, 1, 3, 1, NLS_STATUS_OK);
    /* a closed curve needs 3 points */
    one(NLS_CURVE_FOUR_POINT, "four_point", 1, "closed2", fw_curve_circle, 2, 1, 1, 0, NLS_STATUS_TOO_FEW_POINTS);
}
