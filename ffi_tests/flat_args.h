/* Test helpers: the argument structs of the C ABI (nls_mesh_view, nls_scratch,
 * nls_mesh_buffers, nls_subdivide_options, nls_curve_view) built from flat arguments, so that a
 * test can name one buffer or count per argument (NULL, misaligned, short, overlapping) in one
 * line. Each helper only fills structs and calls the export; nothing is checked here. */
#ifndef NLS_FLAT_ARGS_H
#define NLS_FLAT_ARGS_H
#include "nlsubdiv.h"

static inline nls_mesh_view flat_view(const double *p, size_t nv, const uint32_t *off, size_t nf, const uint32_t *idx,
                               size_t ni) {
    nls_mesh_view v;
    v.positions = p;
    v.vertex_count = nv;
    v.positions_stride = 0;
    v.offsets = off;
    v.face_count = nf;
    v.indices = idx;
    v.index_count = ni;
    return v;
}

/* The linear_weight every flat_* call passes (the default 0 unless a test sets it). */
static double flat_linear_weight = 0.0;

static inline nls_subdivide_options flat_options(uint32_t scheme, uint32_t flags, uint32_t levels) {
    nls_subdivide_options o;
    nls_subdivide_default_options(&o);
    o.scheme = scheme;
    o.flags = flags;
    o.levels = levels;
    o.linear_weight = flat_linear_weight;
    return o;
}

static inline nls_scratch flat_scratch(uint32_t *su, size_t nsu, double *sp, size_t nsp) {
    nls_scratch s;
    s.u32s = su;
    s.u32_capacity = nsu;
    s.points = sp;
    s.point_capacity = nsp;
    return s;
}

static inline nls_mesh_buffers flat_buffers(double *p, size_t nv, uint32_t *off, size_t nf, uint32_t *idx, size_t ni) {
    nls_mesh_buffers b;
    b.positions = p;
    b.vertex_capacity = nv;
    b.offsets = off;
    b.face_capacity = nf;
    b.indices = idx;
    b.index_capacity = ni;
    return b;
}

/* nls_mesh_plan_scratch_size of a packed mesh of nv vertices and ni corners (counts only). */
static inline nls_status flat_plan_scratch_size(size_t nv, size_t ni, size_t *out) {
    nls_mesh_view v = flat_view(NULL, nv, NULL, 0, NULL, ni);
    return nls_mesh_plan_scratch_size(&v, out);
}

/* nls_plan with flat arguments. */
static inline nls_status flat_plan(uint32_t scheme, uint32_t flags, uint32_t levels, const double *p, size_t nv,
                            const uint32_t *off, size_t nf, const uint32_t *idx, size_t ni, uint32_t *su, size_t nsu,
                            nls_plan *plan, uint32_t *element) {
    nls_mesh_view v = flat_view(p, nv, off, nf, idx, ni);
    nls_subdivide_options o = flat_options(scheme, flags, levels);
    return nls_mesh_plan(&v, &o, su, nsu, plan, element);
}

/* nls_mesh_subdivide with flat arguments. */
static inline nls_status flat_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const double *p, size_t nv,
                                 const uint32_t *off, size_t nf, const uint32_t *idx, size_t ni, uint32_t *su,
                                 size_t nsu, double *sp, size_t nsp, double *op, size_t ovc, uint32_t *oo, size_t ofc,
                                 uint32_t *oi, size_t oic, nls_mesh_sizes *sizes, nls_subdivide_report *rep,
                                 uint32_t *element) {
    nls_mesh_view v = flat_view(p, nv, off, nf, idx, ni);
    nls_subdivide_options o = flat_options(scheme, flags, levels);
    nls_scratch s = flat_scratch(su, nsu, sp, nsp);
    nls_mesh_buffers b = flat_buffers(op, ovc, oo, ofc, oi, oic);
    return nls_mesh_subdivide(&v, &o, &s, &b, sizes, rep, element);
}

/* nls_differential_plan with flat arguments. */
static inline nls_status flat_diff_plan(const double *p, size_t nv, const uint32_t *off, size_t nf, const uint32_t *idx,
                                        size_t ni, const nls_differential_options *o, uint32_t *su, size_t nsu,
                                        nls_plan *plan, uint32_t *element) {
    nls_mesh_view v = flat_view(p, nv, off, nf, idx, ni);
    return nls_differential_plan(&v, o, su, nsu, plan, element);
}

/* nls_differential_subdivide with flat arguments. */
static inline nls_status flat_diff_subdivide(const double *p, size_t nv, const uint32_t *off, size_t nf,
                                             const uint32_t *idx, size_t ni, const nls_differential_options *o,
                                             uint32_t *su, size_t nsu, double *sp, size_t nsp, double *op, size_t ovc,
                                             uint32_t *oo, size_t ofc, uint32_t *oi, size_t oic, nls_mesh_sizes *sizes,
                                             nls_differential_report *rep, uint32_t *element) {
    nls_mesh_view v = flat_view(p, nv, off, nf, idx, ni);
    nls_scratch s = flat_scratch(su, nsu, sp, nsp);
    nls_mesh_buffers b = flat_buffers(op, ovc, oo, ofc, oi, oic);
    return nls_differential_subdivide(&v, o, &s, &b, sizes, rep, element);
}

/* nls_mobius_butterfly_star with the star's fields as flat arguments (no faces). */
static inline nls_status flat_butterfly_star(const double *v, const double *ring, size_t n, uint32_t closed,
                                             const uint32_t *irregular, double *out) {
    nls_star_view star;
    star.v = v;
    star.ring = ring;
    star.ring_count = n;
    star.closed = closed;
    star.face_offsets = NULL;
    star.face_count = 0;
    star.face_corners = NULL;
    star.corner_count = 0;
    return nls_mobius_butterfly_star(&star, irregular, out);
}

/* nls_curve_subdivide with the curve's fields as flat arguments. */
static inline nls_status flat_curve_subdivide(uint32_t scheme, const double *points, size_t count, uint32_t closed,
                                              uint32_t levels, double *out, size_t out_capacity, double *scratch,
                                              size_t scratch_capacity, size_t *out_count, uint32_t *out_element) {
    nls_curve_view c;
    c.points = points;
    c.count = count;
    c.closed = closed;
    return nls_curve_subdivide(scheme, &c, levels, out, out_capacity, scratch, scratch_capacity, out_count,
                               out_element);
}
#endif
