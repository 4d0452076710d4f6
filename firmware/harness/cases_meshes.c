/* Every mesh scheme, linear and Möbius, 1 and 2 levels, on every built-in mesh whose faces it
 * accepts; the tagged schemes, linear and Möbius; the Möbius options (literal, strict, the
 * spectrum's weights); spherelike (linear only); documented errors; the differential schemes; the
 * tier-1 star rules. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "calls.h"
#include "harness.h"
#include "meshes.h"
#include "nlsubdiv.h"

enum accepts { TRIANGLES_ONLY, QUADS_ONLY, ANY_FACES };

static const struct {
    uint32_t scheme;
    const char *name;
    enum accepts faces;
    int mobius;        /* has a Möbius form */
    int interpolating; /* primal and interpolating: the old vertices come first, unchanged */
} SCHEMES[] = {
    {NLS_SCHEME_LOOP, "loop", TRIANGLES_ONLY, 1, 0},
    {NLS_SCHEME_CATMULL_CLARK, "catmull_clark", ANY_FACES, 1, 0},
    {NLS_SCHEME_MODIFIED_BUTTERFLY, "butterfly", TRIANGLES_ONLY, 1, 1},
    {NLS_SCHEME_KOBBELT, "kobbelt", QUADS_ONLY, 1, 1},
    {NLS_SCHEME_DOO_SABIN, "doo_sabin", ANY_FACES, 1, 0},
    {NLS_SCHEME_SIMPLEST, "simplest", ANY_FACES, 1, 0},
    {NLS_SCHEME_DUAL, "dual", ANY_FACES, 1, 0},
    {NLS_SCHEME_VERTEX_INSERTION, "vertex_insertion", ANY_FACES, 1, 1},
    {NLS_SCHEME_DUAL_TRUNCATION, "dual_truncation", ANY_FACES, 1, 0},
    {NLS_SCHEME_SPHERELIKE, "spherelike", ANY_FACES, 0, 1},
};
#define SCHEME_COUNT (sizeof SCHEMES / sizeof SCHEMES[0])

static int accepts(enum accepts a, enum fw_face_kind f) {
    return a == ANY_FACES || (a == TRIANGLES_ONLY && f == FW_TRIANGLES) || (a == QUADS_ONLY && f == FW_QUADS);
}

static void hash_mesh(fw_hash *h, const fw_mesh_result *r) {
    fw_hash_u64(h, r->vertex_count);
    fw_hash_u64(h, r->face_count);
    fw_hash_u64(h, r->index_count);
    fw_hash_f64s(h, r->positions, 3 * r->vertex_count);
    fw_hash_u32s(h, r->offsets, r->face_count + 1);
    fw_hash_u32s(h, r->indices, r->index_count);
}

static void one(size_t k, const fw_named_mesh *m, int mobius, uint32_t levels, uint32_t expected) {
    char name[96], entry[64];
    uint32_t flags = mobius ? NLS_SUBDIVIDE_MOBIUS : 0, s;
    fw_mesh_result r;
    fw_hash *h;
    snprintf(name, sizeof name, "mesh/%s/%s/%s/L%u", SCHEMES[k].name, mobius ? "mobius" : "linear", m->name,
             (unsigned)levels);
    snprintf(entry, sizeof entry, "mesh %s (%s)", SCHEMES[k].name, mobius ? "Möbius" : "linear");
    h = fw_case_begin(entry, name);
    s = fw_mesh_subdivide(SCHEMES[k].scheme, flags, levels, &m->mesh, &r);
    if (s == NLS_STATUS_OK) {
        size_t i;
        hash_mesh(h, &r);
        fw_hash_u32(h, r.fallbacks);
        fw_hash_u32(h, r.first_fallback);
        fw_hash_u32(h, r.first_fallback_level);
        fw_check(r.offsets[0] == 0 && r.offsets[r.face_count] == r.index_count, "malformed output offsets");
        if (SCHEMES[k].interpolating)
            fw_check(r.vertex_count >= m->mesh.vertex_count &&
                         fw_same_bits(r.positions, m->mesh.positions, 3 * m->mesh.vertex_count),
                     "an interpolating scheme moved an old vertex");
        /* Möbius schemes keep cospherical meshes on their sphere (seed 000 §4) */
        for (i = 0; mobius && m->sphere_r2 > 0 && i < r.vertex_count; i++) {
            const double *p = &r.positions[3 * i];
            fw_check(fabs(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - m->sphere_r2) < 1e-9 * m->sphere_r2,
                     "a Möbius output vertex left the sphere");
        }
    } else {
        fw_hash_u32(h, r.element);
    }
    fw_case_end(s, expected);
}

/* The tagged rules (Loop, Catmull–Clark: OpenSubdiv's creases, corners and darts; Modified
 * Butterfly, Kobbelt: interpolating creases) on mesh `m`: the first face's first two edges
 * tagged semi-sharp and its third corner a semi-sharp corner, so that both levels run the
 * crease, corner and fractional blend rules. */
static void one_tagged(size_t k, const fw_named_mesh *m, uint32_t method, uint32_t levels, int mobius) {
    char name[96], entry[64];
    const uint32_t *f = &m->mesh.indices[m->mesh.offsets[0]];
    const uint32_t creases[4] = {f[0], f[1], f[1], f[2]}, corners[1] = {f[2]};
    static const double crease_sharpness[2] = {1.5, 3.0}, corner_sharpness[1] = {0.5};
    fw_tags tags = {creases, crease_sharpness, 2, corners, corner_sharpness, 1, method};
    fw_mesh_result r;
    fw_hash *h;
    uint32_t s;
    snprintf(name, sizeof name, "mesh/%s/tagged_%s%s/%s/L%u", SCHEMES[k].name,
             method == NLS_CREASE_CHAIKIN ? "chaikin" : "uniform", mobius ? "_mobius" : "", m->name,
             (unsigned)levels);
    snprintf(entry, sizeof entry, "mesh %s tagged (%s)", SCHEMES[k].name, mobius ? "Möbius" : "linear");
    h = fw_case_begin(entry, name);
    s = fw_mesh_subdivide_tagged(SCHEMES[k].scheme, mobius ? NLS_SUBDIVIDE_MOBIUS : 0, levels, &m->mesh, &tags,
                                 &r);
    if (s == NLS_STATUS_OK) {
        hash_mesh(h, &r);
        fw_check(r.offsets[0] == 0 && r.offsets[r.face_count] == r.index_count, "malformed output offsets");
        if (SCHEMES[k].interpolating)
            fw_check(r.vertex_count >= m->mesh.vertex_count &&
                         fw_same_bits(r.positions, m->mesh.positions, 3 * m->mesh.vertex_count),
                     "an interpolating scheme moved an old vertex");
        /* Loop and Catmull–Clark, one level: f[1] lies on two sharp edges (1.5 and 3.0, both
         * still sharp after the step), so its vertex point is the cubic B-spline crease rule
         * 3/4 v + 1/8 (f[0] + f[2]) (OpenSubdiv's crease mask), bit for bit */
        if (!SCHEMES[k].interpolating && levels == 1 && !mobius) {
            const double *v = &m->mesh.positions[3 * f[1]], *a = &m->mesh.positions[3 * f[0]],
                         *b = &m->mesh.positions[3 * f[2]];
            double crease[3];
            size_t c;
            for (c = 0; c < 3; c++) crease[c] = 0.75 * v[c] + 0.125 * (a[c] + b[c]);
            fw_check(fw_same_bits(&r.positions[3 * f[1]], crease, 3), "a crease vertex is not the crease rule");
        }
    } else {
        fw_hash_u32(h, r.element);
    }
    fw_case_end(s, NLS_STATUS_OK);
}

/* One Möbius mesh call with options, as the "mesh options (Möbius)" entry point. */
static void one_option(size_t k, const fw_named_mesh *m, uint32_t levels, const char *what, uint32_t flags,
                       const fw_spectrum *spectrum, uint32_t expected) {
    char name[96];
    fw_mesh_result r;
    fw_hash *h;
    uint32_t s;
    snprintf(name, sizeof name, "mesh/%s/mobius_%s/%s/L%u", SCHEMES[k].name, what, m->name, (unsigned)levels);
    h = fw_case_begin("mesh options (Möbius)", name);
    s = fw_mesh_subdivide_spectrum(SCHEMES[k].scheme, NLS_SUBDIVIDE_MOBIUS | flags, levels, &m->mesh, spectrum, &r);
    if (s == NLS_STATUS_OK) {
        hash_mesh(h, &r);
        fw_hash_u32(h, r.fallbacks);
        fw_hash_u32(h, r.first_fallback);
        fw_hash_u32(h, r.first_fallback_level);
        fw_check(r.offsets[0] == 0 && r.offsets[r.face_count] == r.index_count, "malformed output offsets");
    } else {
        fw_hash_u32(h, r.element);
    }
    fw_case_end(s, expected);
}

/* The Möbius options on mesh `m`: literal (the paper's rules, no fold guard), strict, the
 * spectrum at the global linear weight 0.25, and per-vertex weights (exact multiples of 1/4,
 * so that every architecture reads the same doubles). */
static void one_options(size_t k, const fw_named_mesh *m, uint32_t levels) {
    static double weights[64];
    fw_spectrum global = {0.25, NULL}, per_vertex = {0.0, weights};
    size_t i;
    for (i = 0; i < m->mesh.vertex_count && i < 64; i++) weights[i] = 0.25 * (double)(i % 5);
    one_option(k, m, levels, "literal", NLS_SUBDIVIDE_LITERAL, NULL, NLS_STATUS_OK);
    one_option(k, m, levels, "strict", NLS_SUBDIVIDE_STRICT, NULL, NLS_STATUS_OK);
    one_option(k, m, levels, "spectrum", 0, &global, NLS_STATUS_OK);
    if (m->mesh.vertex_count <= 64) one_option(k, m, levels, "weights", 0, &per_vertex, NLS_STATUS_OK);
}

void fw_cases_meshes(void) {
    size_t k, i;
    int mobius;
    uint32_t levels;
    fw_meshes_init();
    for (k = 0; k < SCHEME_COUNT; k++)
        for (mobius = 0; mobius <= SCHEMES[k].mobius; mobius++)
            for (i = 0; i < fw_mesh_count; i++)
                for (levels = 1; levels <= 2; levels++)
                    if (accepts(SCHEMES[k].faces, fw_meshes[i].faces))
                        one(k, &fw_meshes[i], mobius, levels, NLS_STATUS_OK);
    /* sharp-feature tags: the four schemes that take them, both crease methods, linear and
     * Möbius (the Möbius tagged rules, docs/creases.md) */
    for (levels = 1; levels <= 2; levels++) {
        uint32_t method;
        for (mobius = 0; mobius <= 1; mobius++)
            for (method = NLS_CREASE_UNIFORM; method <= NLS_CREASE_CHAIKIN; method++) {
                one_tagged(0, &fw_meshes[1], method, levels, mobius); /* Loop, octa */
                one_tagged(1, &fw_meshes[2], method, levels, mobius); /* Catmull–Clark, cube */
                one_tagged(2, &fw_meshes[1], method, levels, mobius); /* Modified Butterfly, octa */
                one_tagged(3, &fw_meshes[2], method, levels, mobius); /* Kobbelt, cube */
            }
    }
    /* the Möbius options: the paper's literal rules, the spectrum's global weight and its
     * per-vertex weights, and strict mode */
    for (levels = 1; levels <= 2; levels++) {
        one_options(0, &fw_meshes[1], levels); /* Loop, octa */
        one_options(1, &fw_meshes[2], levels); /* Catmull–Clark, cube */
        one_options(2, &fw_meshes[1], levels); /* Modified Butterfly, octa */
        one_options(4, &fw_meshes[2], levels); /* Doo–Sabin, cube */
    }
    /* documented errors: Loop on quads; spherelike has no Möbius form */
    one(0, &fw_meshes[2], 0, 1, NLS_STATUS_UNSUPPORTED_FACE_TYPE);
    one(SCHEME_COUNT - 1, &fw_meshes[2], 1, 1, NLS_STATUS_INVALID_ARGUMENT);
}

void fw_cases_differential(void) {
    static const struct {
        uint32_t scheme, levels, dirmag_levels;
        const char *name;
    } CASES[] = {
        {NLS_DIFFERENTIAL_LOOP, 1, 0, "differential/loop/octa/L1"},
        {NLS_DIFFERENTIAL_BUTTERFLY, 2, 0, "differential/butterfly/octa/L2"},
        {NLS_DIFFERENTIAL_DIRMAG, 1, 1, "differential/dirmag/gridt/L1"},
    };
    size_t k;
    fw_meshes_init();
    for (k = 0; k < sizeof CASES / sizeof CASES[0]; k++) {
        const fw_named_mesh *m = CASES[k].scheme == NLS_DIFFERENTIAL_DIRMAG ? &fw_meshes[4] : &fw_meshes[1];
        fw_mesh_result r;
        fw_differential_report rep;
        fw_hash *h = fw_case_begin("differential subdivide", CASES[k].name);
        uint32_t s = fw_differential_subdivide(CASES[k].scheme, CASES[k].levels, CASES[k].dirmag_levels, &m->mesh,
                                               &r, &rep);
        if (s == NLS_STATUS_OK) {
            hash_mesh(h, &r);
            fw_hash_u32(h, rep.iterations);
            fw_hash_u32(h, rep.converged);
            fw_hash_u32(h, rep.anchors);
            fw_hash_u32(h, rep.dirmag_degenerate);
            fw_hash_f64s(h, &rep.relative_residual, 1);
            fw_hash_f64s(h, &rep.initial_residual, 1);
            fw_check(rep.converged == 1, "the reconstruction did not converge");
        } else {
            fw_hash_u32(h, r.element);
        }
        fw_case_end(s, NLS_STATUS_OK);
    }
}

void fw_cases_stars(void) {
    /* the fan: centre fw_fan_positions[0], ring 1..5 (interior), or 1..5 as an open ring */
    double vp[3] = {0}, edges[5 * 3] = {0}, faces[5 * 3] = {0}, corners[19 * 3];
    fw_star fan = {fw_fan_positions, fw_fan_positions + 3, 5, 1, NULL, 0, NULL, 0};
    fw_star mixed = {fw_mixed_positions, fw_mixed_positions + 3, 5, 1, fw_mixed_offsets, 5, corners, 19};
    static const uint32_t IRREGULAR[5] = {0, 1, 0, 0, 1};
    fw_hash *h;
    uint32_t s;
    size_t i;
    for (i = 0; i < 19; i++) memcpy(&corners[3 * i], &fw_mixed_positions[3 * fw_mixed_indices[i]], sizeof(double[3]));

    h = fw_case_begin("star rules", "star/loop/fan5/interior");
    s = fw_loop_star(&fan, vp, edges);
    if (s == NLS_STATUS_OK) fw_hash_f64s(h, vp, 3), fw_hash_f64s(h, edges, 15);
    fw_case_end(s, NLS_STATUS_OK);

    fan.closed = 0;
    h = fw_case_begin("star rules", "star/loop/fan5/boundary");
    s = fw_loop_star(&fan, vp, edges);
    /* a boundary star: no vertex point and no candidates on its two boundary spokes (NaN) */
    fw_check(s != NLS_STATUS_OK || (vp[0] != vp[0] && edges[0] != edges[0] && edges[12] != edges[12]),
             "boundary star rules not NaN where nothing exists");
    if (s == NLS_STATUS_OK) fw_hash_f64s(h, edges + 3, 9);
    fw_case_end(s, NLS_STATUS_OK);
    fan.closed = 1;

    h = fw_case_begin("star rules", "star/catmull_clark/mixed5/interior");
    s = fw_catmull_clark_star(&mixed, vp, edges, faces);
    if (s == NLS_STATUS_OK) fw_hash_f64s(h, vp, 3), fw_hash_f64s(h, edges, 15), fw_hash_f64s(h, faces, 15);
    fw_case_end(s, NLS_STATUS_OK);

    h = fw_case_begin("star rules", "star/butterfly/fan5/interior");
    s = fw_butterfly_star(&fan, NULL, edges);
    if (s == NLS_STATUS_OK) fw_hash_f64s(h, edges, 15);
    fw_case_end(s, NLS_STATUS_OK);

    h = fw_case_begin("star rules", "star/butterfly/fan5/irregular_neighbours");
    s = fw_butterfly_star(&fan, IRREGULAR, edges);
    if (s == NLS_STATUS_OK) fw_hash_f64s(h, edges, 15);
    fw_case_end(s, NLS_STATUS_OK);
}
