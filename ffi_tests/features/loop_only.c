/* C99 test of a library built with only the `loop` feature
 * (cargo build -p nlsubdiv-ffi --no-default-features --features loop; scripts/test-features.sh
 * builds and runs it): Loop computes, and every scheme, form and method left out of the build
 * is NLS_STATUS_SCHEME_NOT_BUILT through the C ABI, from the plan and from the call, with
 * nothing written but out_element (NLS_NO_ELEMENT). Not one of the ffi_tests/test_*.c
 * suites, which link the default library. */
#include <stdint.h>
#include <string.h>

#include "nlsubdiv.h"
#include "check.h"

/* The octahedron on the unit sphere (triangles) and a cube (quads). */
static const double OCT_P[6 * 3] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
static const uint32_t OCT_O[9] = {0, 3, 6, 9, 12, 15, 18, 21, 24};
static const uint32_t OCT_I[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
static const double CUBE_P[8 * 3] = {-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1,
                                     -1, -1, 1,  1, -1, 1,  -1, 1, 1,  1, 1, 1};
static const uint32_t CUBE_O[7] = {0, 4, 8, 12, 16, 20, 24};
static const uint32_t CUBE_I[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5};

static uint32_t u32s[4096];
static double points[3 * 4096];
static double out_p[3 * 1024];
static uint32_t out_o[1025], out_i[4096];

/* Plans and runs one level of `scheme` with `flags`; the plan's status must be `expected`,
 * and so must the call's (with ample buffers); on a refusal nothing is written. */
static void mesh_case(const nls_mesh_view *m, uint32_t scheme, uint32_t flags, nls_status expected) {
    nls_subdivide_options o;
    nls_plan plan;
    nls_scratch sc = {u32s, 4096, points, 4096};
    nls_mesh_buffers out = {out_p, 1024, out_o, 1024, out_i, 4096};
    nls_mesh_sizes sizes = {7, 7, 7};
    nls_subdivide_report rep;
    size_t topo = 0;
    uint32_t element = 7;
    CHECK_STATUS(nls_subdivide_default_options(&o), NLS_STATUS_OK);
    o.scheme = scheme;
    o.flags = flags;
    CHECK_STATUS(nls_mesh_plan_scratch_size(m, &topo), NLS_STATUS_OK);
    memset(&plan, 0x5a, sizeof plan);
    CHECK_STATUS(nls_mesh_plan(m, &o, u32s, topo, &plan, &element), expected);
    if (expected != NLS_STATUS_OK) {
        CHECK(element == NLS_NO_ELEMENT);
        CHECK(plan.scratch_u32 == (size_t)0x5a5a5a5a5a5a5a5aULL || sizeof(size_t) != 8);
    }
    memset(out_p, 0, sizeof out_p);
    memset(&rep, 0x5a, sizeof rep);
    element = 7;
    CHECK_STATUS(nls_mesh_subdivide(m, &o, &sc, &out, &sizes, &rep, &element), expected);
    if (expected != NLS_STATUS_OK) {
        size_t k;
        int zero = 1;
        for (k = 0; k < 3 * 1024; k++) zero &= out_p[k] == 0.0;
        CHECK(zero);
        CHECK(element == NLS_NO_ELEMENT);
        CHECK(sizes.vertex_count == 7 && sizes.face_count == 7 && sizes.index_count == 7);
        CHECK(rep.fallbacks == 0x5a5a5a5aU);
    }
}

int main(void) {
    const nls_mesh_view oct = {OCT_P, 6, 0, OCT_O, 8, OCT_I, 24};
    const nls_mesh_view cube = {CUBE_P, 8, 0, CUBE_O, 6, CUBE_I, 24};
    uint32_t s;
    /* Built: linear Loop. */
    mesh_case(&oct, NLS_SCHEME_LOOP, 0, NLS_STATUS_OK);
    /* Left out: the Möbius form of Loop, and every other scheme. */
    mesh_case(&oct, NLS_SCHEME_LOOP, NLS_SUBDIVIDE_MOBIUS, NLS_STATUS_SCHEME_NOT_BUILT);
    mesh_case(&oct, NLS_SCHEME_MODIFIED_BUTTERFLY, 0, NLS_STATUS_SCHEME_NOT_BUILT);
    for (s = NLS_SCHEME_CATMULL_CLARK; s <= NLS_SCHEME_SPHERELIKE; s++) {
        if (s == NLS_SCHEME_MODIFIED_BUTTERFLY) continue;
        mesh_case(&cube, s, 0, NLS_STATUS_SCHEME_NOT_BUILT);
    }
    /* Curves (the `curves` feature) and differential-space subdivision (`differential`). */
    {
        const double pts[4 * 3] = {1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
        const nls_curve_view c = {pts, 4, 1};
        size_t count = 7;
        uint32_t element = 7;
        memset(out_p, 0, sizeof out_p);
        CHECK_STATUS(nls_curve_subdivide(NLS_CURVE_FOUR_POINT, &c, 1, out_p, 1024, points, 4096, &count, &element),
                     NLS_STATUS_SCHEME_NOT_BUILT);
        CHECK(count == 7 && element == NLS_NO_ELEMENT && out_p[0] == 0.0);
    }
    {
        nls_differential_options d;
        nls_plan plan;
        size_t topo = 0;
        uint32_t element = 7;
        CHECK_STATUS(nls_differential_default_options(&d), NLS_STATUS_OK);
        CHECK_STATUS(nls_mesh_plan_scratch_size(&oct, &topo), NLS_STATUS_OK);
        CHECK_STATUS(nls_differential_plan(&oct, &d, u32s, topo, &plan, &element), NLS_STATUS_SCHEME_NOT_BUILT);
        CHECK(element == NLS_NO_ELEMENT);
    }
    CHECK(strstr(nls_status_str(NLS_STATUS_SCHEME_NOT_BUILT), "not compiled into this build") != NULL);
    return nls_summary("features_loop_only");
}
