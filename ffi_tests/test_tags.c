/* C99 tests of sharp-feature tags through nls_mesh_plan_scratch_size_tagged,
 * nls_mesh_plan_tagged and nls_mesh_subdivide_tagged (OpenSubdiv's crease conventions).
 *
 * Expected values come from geometry, not from recorded output:
 *  - no tags: the tagged calls equal the untagged ones bit for bit (sizes, scratch, output);
 *  - a unit cube with all 12 edges infinitely sharp (Catmull–Clark): the edge lines are
 *    straight creases and the corners keep their place, so after k levels exactly
 *    12 (2^k - 1) + 8 output vertices lie on the cube's edges, every vertex lies on the
 *    cube's surface, and the 8 corners are unchanged bit for bit (the tags are carried to
 *    the child edges level by level: without that, level 2 would round the edges);
 *  - sharpness 1 (uniform decay): one sharp level, then smooth, so 2 tagged levels equal one
 *    infinitely sharp level followed by one untagged level;
 *  - a corner tag keeps its vertex bit for bit on a smooth Loop octahedron;
 *  - the interpolating schemes: Kobbelt on the cube with all 12 edges infinitely sharp keeps
 *    its edges straight and its faces flat (the same counts as Catmull–Clark; the untagged
 *    surface bulges), and a lone infinitely sharp Modified Butterfly edge gets its midpoint
 *    (the 4-point rule with the virtual end points 2 v - w at both ends), old vertices bit
 *    for bit;
 *  - Möbius Loop and Modified Butterfly on the octahedron with its equator sharp keep every
 *    vertex on the unit sphere and the equator's vertices on it (a great circle);
 *  - the statuses of bad tags, each naming the tag (crease i = i, corner j = crease_count + j),
 *    a short scratch, aliasing, NULL arrays and an unknown method.
 * Run under ASan+UBSan and valgrind like every C suite. */
#include <stdint.h>
#include <stdlib.h>

#include "nlsubdiv.h"
#include "check.h"

typedef struct {
    size_t nv, nf, ni;
    double *p;
    uint32_t *off;
    uint32_t *idx;
} mesh;

static void mesh_free(mesh *m) {
    free(m->p);
    free(m->off);
    free(m->idx);
    m->p = NULL;
    m->off = NULL;
    m->idx = NULL;
}

static mesh make(size_t nv, const double *p, size_t nf, size_t corners, const int *idx) {
    mesh m;
    size_t k;
    m.nv = nv;
    m.nf = nf;
    m.ni = nf * corners;
    m.p = (double *)malloc(3 * nv * sizeof(double));
    m.off = (uint32_t *)malloc((nf + 1) * sizeof(uint32_t));
    m.idx = (uint32_t *)malloc(m.ni * sizeof(uint32_t));
    memcpy(m.p, p, 3 * nv * sizeof(double));
    for (k = 0; k <= nf; k++) m.off[k] = (uint32_t)(k * corners);
    for (k = 0; k < m.ni; k++) m.idx[k] = (uint32_t)idx[k];
    return m;
}

/* Unit cube, faces outward. */
static mesh cube(void) {
    static const double p[24] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
    static const int f[24] = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
    return make(8, p, 6, 4, f);
}

/* Regular octahedron, faces outward. */
static mesh octahedron(void) {
    static const double p[18] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
    static const int f[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    return make(6, p, 8, 3, f);
}

/* The 12 edges of cube(). */
static const uint32_t CUBE_EDGES[24] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4, 0, 4, 1, 5, 2, 6, 3, 7};

static nls_mesh_view view_of(const mesh *m) {
    nls_mesh_view v;
    v.positions = m->p;
    v.vertex_count = m->nv;
    v.positions_stride = 0;
    v.offsets = m->off;
    v.face_count = m->nf;
    v.indices = m->idx;
    v.index_count = m->ni;
    return v;
}

static nls_subdivide_options options(uint32_t scheme, uint32_t flags, uint32_t levels) {
    nls_subdivide_options o;
    nls_subdivide_default_options(&o);
    o.scheme = scheme;
    o.flags = flags;
    o.levels = levels;
    return o;
}

/* Plans and subdivides with exactly sized buffers; `tags` NULL runs the untagged calls. */
static nls_status run(const mesh *m, nls_subdivide_options o, const nls_tags *tags, mesh *out, uint32_t *element) {
    nls_mesh_view v = view_of(m);
    size_t su = 0;
    uint32_t *scratch_u32;
    double *scratch_points;
    nls_plan plan;
    nls_scratch s;
    nls_mesh_buffers b;
    nls_mesh_sizes w = {0, 0, 0};
    nls_status st;
    out->p = NULL;
    out->off = NULL;
    out->idx = NULL;
    st = tags ? nls_mesh_plan_scratch_size_tagged(&v, tags, &su) : nls_mesh_plan_scratch_size(&v, &su);
    if (st != NLS_STATUS_OK) return st;
    scratch_u32 = (uint32_t *)malloc(su * sizeof(uint32_t) + 4);
    st = tags ? nls_mesh_plan_tagged(&v, &o, tags, scratch_u32, su, &plan, element)
              : nls_mesh_plan(&v, &o, scratch_u32, su, &plan, element);
    free(scratch_u32);
    if (st != NLS_STATUS_OK) return st;
    scratch_u32 = (uint32_t *)malloc(plan.scratch_u32 * sizeof(uint32_t) + 4);
    scratch_points = (double *)malloc(3 * plan.scratch_points * sizeof(double) + 8);
    out->nv = plan.output.vertex_count;
    out->nf = plan.output.face_count;
    out->ni = plan.output.index_count;
    out->p = (double *)malloc(3 * out->nv * sizeof(double) + 8);
    out->off = (uint32_t *)malloc((out->nf + 1) * sizeof(uint32_t));
    out->idx = (uint32_t *)malloc(out->ni * sizeof(uint32_t) + 4);
    s.u32s = scratch_u32;
    s.u32_capacity = plan.scratch_u32;
    s.points = scratch_points;
    s.point_capacity = plan.scratch_points;
    b.positions = out->p;
    b.vertex_capacity = out->nv;
    b.offsets = out->off;
    b.face_capacity = out->nf;
    b.indices = out->idx;
    b.index_capacity = out->ni;
    st = tags ? nls_mesh_subdivide_tagged(&v, &o, tags, &s, &b, &w, NULL, element)
              : nls_mesh_subdivide(&v, &o, &s, &b, &w, NULL, element);
    if (st == NLS_STATUS_OK) CHECK(w.vertex_count == out->nv && w.face_count == out->nf && w.index_count == out->ni);
    free(scratch_u32);
    free(scratch_points);
    return st;
}

static int same_mesh(const mesh *a, const mesh *b) {
    return a->nv == b->nv && a->nf == b->nf && a->ni == b->ni && memcmp(a->p, b->p, 3 * a->nv * sizeof(double)) == 0 &&
           memcmp(a->off, b->off, (a->nf + 1) * sizeof(uint32_t)) == 0 &&
           memcmp(a->idx, b->idx, a->ni * sizeof(uint32_t)) == 0;
}

static nls_tags no_tags(void) {
    nls_tags t;
    memset(&t, 0, sizeof t);
    return t;
}

static nls_tags cube_creases(const double *sharpness) {
    nls_tags t = no_tags();
    t.crease_vertices = CUBE_EDGES;
    t.crease_sharpness = sharpness;
    t.crease_count = 12;
    return t;
}

static void test_empty_tags_are_untagged(void) {
    mesh c = cube(), o = octahedron(), a, b;
    nls_tags t = no_tags();
    nls_mesh_view v = view_of(&c);
    size_t s1 = 0, s2 = 0;
    uint32_t levels;
    CHECK_STATUS(nls_mesh_plan_scratch_size(&v, &s1), NLS_STATUS_OK);
    CHECK_STATUS(nls_mesh_plan_scratch_size_tagged(&v, &t, &s2), NLS_STATUS_OK);
    CHECK(s1 == s2);
    for (levels = 0; levels <= 3; levels++) {
        CHECK_STATUS(run(&c, options(NLS_SCHEME_CATMULL_CLARK, 0, levels), NULL, &a, NULL), NLS_STATUS_OK);
        CHECK_STATUS(run(&c, options(NLS_SCHEME_CATMULL_CLARK, 0, levels), &t, &b, NULL), NLS_STATUS_OK);
        CHECK(same_mesh(&a, &b));
        mesh_free(&a);
        mesh_free(&b);
        /* Any scheme and the Möbius versions take empty tags. */
        CHECK_STATUS(run(&o, options(NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS, levels), NULL, &a, NULL),
                     NLS_STATUS_OK);
        CHECK_STATUS(run(&o, options(NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS, levels), &t, &b, NULL),
                     NLS_STATUS_OK);
        CHECK(same_mesh(&a, &b));
        mesh_free(&a);
        mesh_free(&b);
    }
    mesh_free(&c);
    mesh_free(&o);
}

/* Coordinates exactly 0 or 1 (within rounding of dyadic weights). */
static int on_face(double x) { return fabs(x) <= 1e-15 || fabs(x - 1.0) <= 1e-15; }

static void sharp_cube_keeps_its_edges(uint32_t scheme) {
    static const double inf[12] = {10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10};
    mesh c = cube(), r, plain;
    nls_tags t = cube_creases(inf);
    uint32_t levels;
    for (levels = 1; levels <= 3; levels++) {
        size_t k, on_edges = 0, off_surface = 0, moved_corners = 0;
        CHECK_STATUS(run(&c, options(scheme, 0, levels), &t, &r, NULL), NLS_STATUS_OK);
        for (k = 0; k < r.nv; k++) {
            int n = on_face(r.p[3 * k]) + on_face(r.p[3 * k + 1]) + on_face(r.p[3 * k + 2]);
            if (n >= 2) on_edges++;
            if (n == 0) off_surface++;
        }
        /* Old vertices keep their indices: the corners are the first 8 outputs. */
        for (k = 0; k < 8; k++) {
            if (memcmp(&r.p[3 * k], &c.p[3 * k], 3 * sizeof(double)) != 0) moved_corners++;
        }
        CHECK(on_edges == 12 * (((size_t)1 << levels) - 1) + 8);
        CHECK(off_surface == 0);
        CHECK(moved_corners == 0);
        /* The untagged surface is smooth: Catmull–Clark's corners move off the cube, Kobbelt's
         * edge points bulge out of it. */
        CHECK_STATUS(run(&c, options(scheme, 0, levels), NULL, &plain, NULL), NLS_STATUS_OK);
        if (scheme == NLS_SCHEME_CATMULL_CLARK) {
            CHECK(memcmp(plain.p, c.p, 3 * sizeof(double)) != 0);
        } else {
            size_t bulging = 0;
            for (k = 0; k < plain.nv; k++) {
                int n = on_face(plain.p[3 * k]) + on_face(plain.p[3 * k + 1]) + on_face(plain.p[3 * k + 2]);
                if (n == 0) bulging++;
            }
            CHECK(bulging > 0);
        }
        mesh_free(&r);
        mesh_free(&plain);
    }
    mesh_free(&c);
}

static void test_sharp_cube_keeps_its_edges(void) {
    sharp_cube_keeps_its_edges(NLS_SCHEME_CATMULL_CLARK);
    sharp_cube_keeps_its_edges(NLS_SCHEME_KOBBELT);
}

/* A lone infinitely sharp Butterfly edge ends at both ends: 9/16 (a + b) - 1/16 ((2a - b) + (2b - a))
 * is its midpoint, exactly here. The untagged point (Zorin's valence-4 stencils) is
 * (0.625, 0, 0.625). */
static void test_butterfly_lone_crease_is_its_midpoint(void) {
    static const uint32_t edge[2] = {0, 4};
    static const double s[1] = {10};
    static const double mid[3] = {0.5, 0.0, 0.5};
    mesh o = octahedron(), r, plain;
    nls_tags t = no_tags();
    size_t k, found = 0, found_plain = 0;
    uint32_t levels;
    t.crease_vertices = edge;
    t.crease_sharpness = s;
    t.crease_count = 1;
    CHECK_STATUS(run(&o, options(NLS_SCHEME_MODIFIED_BUTTERFLY, 0, 1), &t, &r, NULL), NLS_STATUS_OK);
    CHECK_STATUS(run(&o, options(NLS_SCHEME_MODIFIED_BUTTERFLY, 0, 1), NULL, &plain, NULL), NLS_STATUS_OK);
    for (k = 0; k < r.nv; k++) found += memcmp(&r.p[3 * k], mid, sizeof mid) == 0;
    for (k = 0; k < plain.nv; k++) found_plain += memcmp(&plain.p[3 * k], mid, sizeof mid) == 0;
    CHECK(found == 1);
    CHECK(found_plain == 0);
    mesh_free(&r);
    mesh_free(&plain);
    /* Interpolating with tags: the old vertices stay bit for bit. */
    for (levels = 1; levels <= 3; levels++) {
        CHECK_STATUS(run(&o, options(NLS_SCHEME_MODIFIED_BUTTERFLY, 0, levels), &t, &r, NULL), NLS_STATUS_OK);
        CHECK(memcmp(r.p, o.p, 3 * o.nv * sizeof(double)) == 0);
        mesh_free(&r);
    }
    mesh_free(&o);
}

/* Möbius Loop and Modified Butterfly on the regular octahedron (on the unit sphere) with its
 * equator (a great circle) infinitely sharp: the crease takes the Möbius curve rule, which
 * keeps points of a circle on it, and each half takes the Möbius rules, which reproduce the
 * sphere; so after 3 levels every output vertex is on the unit sphere and every vertex of
 * the plane z = 0 on the equator. The linear tagged scheme leaves the sphere, and the
 * untagged Möbius output differs from the tagged one. */
static void test_mobius_crease_keeps_the_sphere(void) {
    static const uint32_t equator[8] = {0, 2, 2, 1, 1, 3, 3, 0};
    static const double s[4] = {10, 10, 10, 10};
    static const uint32_t schemes[2] = {NLS_SCHEME_LOOP, NLS_SCHEME_MODIFIED_BUTTERFLY};
    mesh o = octahedron(), r, lin, plain;
    nls_tags t = no_tags();
    size_t k, i, on_equator;
    double worst, lin_worst;
    t.crease_vertices = equator;
    t.crease_sharpness = s;
    t.crease_count = 4;
    for (i = 0; i < 2; i++) {
        CHECK_STATUS(run(&o, options(schemes[i], NLS_SUBDIVIDE_MOBIUS, 3), &t, &r, NULL), NLS_STATUS_OK);
        CHECK_STATUS(run(&o, options(schemes[i], 0, 3), &t, &lin, NULL), NLS_STATUS_OK);
        CHECK_STATUS(run(&o, options(schemes[i], NLS_SUBDIVIDE_MOBIUS, 3), NULL, &plain, NULL), NLS_STATUS_OK);
        worst = 0.0;
        lin_worst = 0.0;
        on_equator = 0;
        for (k = 0; k < r.nv; k++) {
            const double *p = &r.p[3 * k], *q = &lin.p[3 * k];
            double d = fabs(sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0);
            double dl = fabs(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - 1.0);
            worst = d > worst ? d : worst;
            lin_worst = dl > lin_worst ? dl : lin_worst;
            on_equator += fabs(p[2]) <= 1e-12;
        }
        CHECK(worst < 1e-12);
        CHECK(lin_worst > 1e-3);
        /* The equator's 4 edges become 4 * 2^3 segments, with as many vertices. */
        CHECK(on_equator == 32);
        CHECK(!same_mesh(&r, &plain));
        mesh_free(&r);
        mesh_free(&lin);
        mesh_free(&plain);
    }
    mesh_free(&o);
}

static void test_semi_sharp_decays(void) {
    static const double one[12] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    static const double inf[12] = {10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10};
    mesh c = cube(), two, sharp1, then;
    nls_tags t1 = cube_creases(one), t10 = cube_creases(inf);
    size_t k;
    double worst = 0.0;
    CHECK_STATUS(run(&c, options(NLS_SCHEME_CATMULL_CLARK, 0, 2), &t1, &two, NULL), NLS_STATUS_OK);
    CHECK_STATUS(run(&c, options(NLS_SCHEME_CATMULL_CLARK, 0, 1), &t10, &sharp1, NULL), NLS_STATUS_OK);
    CHECK_STATUS(run(&sharp1, options(NLS_SCHEME_CATMULL_CLARK, 0, 1), NULL, &then, NULL), NLS_STATUS_OK);
    CHECK(two.nv == then.nv && two.ni == then.ni);
    CHECK(memcmp(two.idx, then.idx, two.ni * sizeof(uint32_t)) == 0);
    for (k = 0; k < two.nv && k < then.nv; k++) {
        double d = nls_dist3(&two.p[3 * k], &then.p[3 * k]);
        if (d > worst) worst = d;
    }
    CHECK(worst <= 1e-15);
    mesh_free(&two);
    mesh_free(&sharp1);
    mesh_free(&then);
    mesh_free(&c);
}

static void test_corner_keeps_its_vertex(void) {
    static const uint32_t corner[1] = {4};
    static const double s[1] = {10};
    mesh o = octahedron(), r;
    nls_tags t = no_tags();
    t.corner_vertices = corner;
    t.corner_sharpness = s;
    t.corner_count = 1;
    CHECK_STATUS(run(&o, options(NLS_SCHEME_LOOP, 0, 3), &t, &r, NULL), NLS_STATUS_OK);
    CHECK(memcmp(&r.p[3 * 4], &o.p[3 * 4], 3 * sizeof(double)) == 0);
    CHECK(memcmp(&r.p[3 * 5], &o.p[3 * 5], 3 * sizeof(double)) != 0); /* the untagged apex moves */
    mesh_free(&r);
    mesh_free(&o);
}

static void test_statuses(void) {
    mesh c = cube(), o = octahedron(), r;
    uint32_t e = 0;
    static const uint32_t diagonal[4] = {0, 1, 0, 2};
    static const uint32_t repeated[4] = {0, 1, 1, 0};
    static const uint32_t out_of_range[4] = {0, 1, 1, 99};
    static const double ok2[2] = {10, 2};
    static const uint32_t corners[2] = {3, 3};
    static const double corner_s[2] = {10, 10};
    double bad[2] = {10, 0};
    nls_tags t = no_tags();
    nls_mesh_view v = view_of(&c);
    nls_subdivide_options cc = options(NLS_SCHEME_CATMULL_CLARK, 0, 1);
    nls_plan plan;
    size_t need = 0, plain = 0;
    uint32_t *su;

    t.crease_vertices = diagonal;
    t.crease_sharpness = ok2;
    t.crease_count = 2;
    e = 0;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_TAG_NOT_AN_EDGE);
    CHECK(e == 1);
    mesh_free(&r);
    t.crease_vertices = repeated;
    e = 0;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_REPEATED_TAG);
    CHECK(e == 1);
    mesh_free(&r);
    t.crease_vertices = out_of_range;
    e = 0;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_INDEX_OUT_OF_RANGE);
    CHECK(e == 1);
    mesh_free(&r);
    t.crease_vertices = CUBE_EDGES;
    t.crease_sharpness = bad;
    bad[1] = NAN;
    e = 0;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_INVALID_SHARPNESS);
    CHECK(e == 1);
    mesh_free(&r);
    bad[1] = -1.0;
    e = 0;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_INVALID_SHARPNESS);
    CHECK(e == 1);
    mesh_free(&r);
    bad[1] = INFINITY;
    e = 0;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_INVALID_SHARPNESS);
    CHECK(e == 1);
    mesh_free(&r);
    /* A repeated corner is named after the creases. */
    t.crease_sharpness = ok2;
    t.corner_vertices = corners;
    t.corner_sharpness = corner_s;
    t.corner_count = 2;
    e = 0;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_REPEATED_TAG);
    CHECK(e == 3);
    mesh_free(&r);
    t.corner_count = 1;
    /* Tags with a scheme that does not take them, linear or Möbius. */
    CHECK_STATUS(run(&c, options(NLS_SCHEME_DOO_SABIN, 0, 1), &t, &r, &e), NLS_STATUS_TAGS_NOT_SUPPORTED);
    mesh_free(&r);
    CHECK_STATUS(run(&c, options(NLS_SCHEME_DOO_SABIN, NLS_SUBDIVIDE_MOBIUS, 1), &t, &r, &e),
                 NLS_STATUS_TAGS_NOT_SUPPORTED);
    mesh_free(&r);
    /* An unknown method; NULL arrays with a count. */
    t.method = 7;
    CHECK_STATUS(nls_mesh_plan_scratch_size_tagged(&v, &t, &need), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_INVALID_ARGUMENT);
    mesh_free(&r);
    t.method = NLS_CREASE_CHAIKIN;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_OK);
    mesh_free(&r);
    t.crease_vertices = NULL;
    CHECK_STATUS(run(&c, cc, &t, &r, &e), NLS_STATUS_NULL_PARAMETER);
    mesh_free(&r);
    CHECK_STATUS(nls_mesh_plan_scratch_size_tagged(&v, NULL, &need), NLS_STATUS_NULL_PARAMETER);
    t.crease_vertices = CUBE_EDGES;

    /* The tagged plan needs more scratch than the untagged one: one short entry is refused. */
    CHECK_STATUS(nls_mesh_plan_scratch_size_tagged(&v, &t, &need), NLS_STATUS_OK);
    CHECK_STATUS(nls_mesh_plan_scratch_size(&v, &plain), NLS_STATUS_OK);
    CHECK(need == plain + c.nv + c.ni);
    su = (uint32_t *)malloc(need * sizeof(uint32_t));
    CHECK_STATUS(nls_mesh_plan_tagged(&v, &cc, &t, su, need - 1, &plan, &e), NLS_STATUS_BUFFER_TOO_SMALL);
    CHECK(e == NLS_MESH_BUFFER_SCRATCH_U32);
    CHECK_STATUS(nls_mesh_plan_tagged(&v, &cc, &t, su, need, &plan, &e), NLS_STATUS_OK);
    free(su);

    /* A tag array inside the scratch, and an out-pointer into a tag array. */
    su = (uint32_t *)malloc((need + 24) * sizeof(uint32_t));
    memcpy(su + need, CUBE_EDGES, sizeof CUBE_EDGES);
    t.crease_vertices = su + need;
    CHECK_STATUS(nls_mesh_plan_tagged(&v, &cc, &t, su, need + 24, &plan, &e), NLS_STATUS_ALIASING_BUFFERS);
    CHECK_STATUS(nls_mesh_plan_tagged(&v, &cc, &t, su, need, &plan, (uint32_t *)(su + need)),
                 NLS_STATUS_ALIASING_BUFFERS);
    CHECK(su[need] == 0); /* out_element pointed into a tag array: not written */
    t.method = 7;          /* an unknown method is found after the out-pointer check */
    CHECK_STATUS(nls_mesh_plan_tagged(&v, &cc, &t, su, need, &plan, (uint32_t *)(su + need)),
                 NLS_STATUS_ALIASING_BUFFERS);
    CHECK(su[need] == 0);
    t.method = NLS_CREASE_UNIFORM;
    free(su);
    mesh_free(&c);
    mesh_free(&o);
}

/* An early failure (a NULL or misaligned argument struct) never writes out_element into a tag
 * array, and keeps the caller's value when the tags' arrays cannot be named. */
static void test_early_failure_element(void) {
    mesh c = cube();
    nls_mesh_view v = view_of(&c);
    nls_subdivide_options cc = options(NLS_SCHEME_CATMULL_CLARK, 0, 1);
    double sharp[12];
    union {
        double d[8];
        unsigned char b[sizeof(double) * 8];
    } raw;
    nls_tags t, *mis = (nls_tags *)(void *)(raw.b + 1);
    nls_plan plan;
    uint32_t su[4096], e = 12345;
    uint32_t *into = (uint32_t *)(void *)&sharp[3];
    size_t k;
    for (k = 0; k < 12; k++) sharp[k] = 10.0;
    t = cube_creases(sharp);
    /* NULL view: out_element inside the crease sharpness array is not written */
    CHECK_STATUS(nls_mesh_plan_tagged(NULL, &cc, &t, su, 4096, &plan, into), NLS_STATUS_NULL_PARAMETER);
    CHECK(sharp[3] == 10.0);
    /* NULL view, separate out_element: NLS_NO_ELEMENT */
    CHECK_STATUS(nls_mesh_plan_tagged(NULL, &cc, &t, su, 4096, &plan, &e), NLS_STATUS_NULL_PARAMETER);
    CHECK(e == NLS_NO_ELEMENT);
    /* a misaligned tags struct: its arrays cannot be named, out_element keeps its value */
    memcpy(raw.b + 1, &t, sizeof t);
    e = 12345;
    CHECK_STATUS(nls_mesh_plan_tagged(&v, &cc, mis, su, 4096, &plan, &e), NLS_STATUS_MISALIGNED_POINTER);
    CHECK(e == 12345);
    mesh_free(&c);
}

int main(void) {
    test_early_failure_element();
    test_empty_tags_are_untagged();
    test_sharp_cube_keeps_its_edges();
    test_semi_sharp_decays();
    test_corner_keeps_its_vertex();
    test_butterfly_lone_crease_is_its_midpoint();
    test_mobius_crease_keeps_the_sphere();
    test_statuses();
    return nls_summary("test_tags");
}
