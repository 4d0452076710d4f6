/* C ABI 0.2 calls behind the harness's adapter (calls.h). This is the file to rewrite when
 * the mesh, curve, differential or star-rule signatures change; nothing else in firmware/
 * calls those functions. */
#include <string.h>

#include "arena.h"
#include "calls.h"
#include "harness.h"
#include "nlsubdiv.h"

#define ALLOC(type, n) ((type *)fw_alloc((n) * sizeof(type)))

static void clear(fw_mesh_result *out) {
    memset(out, 0, sizeof *out);
    out->element = NLS_NO_ELEMENT;
    out->first_fallback = NLS_NO_ELEMENT;
}

/* The harness's mesh as the library's view (packed positions). */
static nls_mesh_view view_of(const fw_mesh *m) {
    nls_mesh_view v;
    v.positions = m->positions;
    v.vertex_count = m->vertex_count;
    v.positions_stride = 0;
    v.offsets = m->offsets;
    v.face_count = m->face_count;
    v.indices = m->indices;
    v.index_count = m->index_count;
    return v;
}

/* Allocates the plan's scratch and output buffers from the arena. */
static uint32_t buffers_of(const nls_plan *plan, fw_mesh_result *out, nls_scratch *scratch,
                           nls_mesh_buffers *buffers) {
    fw_arena_reset();
    scratch->u32s = ALLOC(uint32_t, plan->scratch_u32);
    scratch->u32_capacity = plan->scratch_u32;
    scratch->points = ALLOC(double, 3 * plan->scratch_points);
    scratch->point_capacity = plan->scratch_points;
    out->positions = ALLOC(double, 3 * plan->output.vertex_count);
    out->offsets = ALLOC(uint32_t, plan->output.face_count + 1);
    out->indices = ALLOC(uint32_t, plan->output.index_count);
    if (scratch->u32s == NULL || scratch->points == NULL || out->positions == NULL || out->offsets == NULL ||
        out->indices == NULL)
        return FW_STATUS_NO_MEMORY;
    buffers->positions = out->positions;
    buffers->vertex_capacity = plan->output.vertex_count;
    buffers->offsets = out->offsets;
    buffers->face_capacity = plan->output.face_count;
    buffers->indices = out->indices;
    buffers->index_capacity = plan->output.index_count;
    return NLS_STATUS_OK;
}

/* nls_mesh_plan_scratch_size (the input's topology), nls_mesh_plan, nls_mesh_subdivide; their
 * _tagged forms when `tags` is not NULL. */
static uint32_t mesh_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *m,
                               const nls_tags *tags, const fw_spectrum *spectrum, fw_mesh_result *out) {
    nls_mesh_view view = view_of(m);
    nls_subdivide_options options;
    nls_plan plan;
    nls_scratch scratch;
    nls_mesh_buffers buffers;
    nls_mesh_sizes written;
    size_t topo_u32 = 0;
    uint32_t *topo;
    nls_subdivide_report report;
    nls_status s;
    clear(out);
    s = nls_subdivide_default_options(&options);
    if (s != NLS_STATUS_OK) return s;
    options.scheme = scheme;
    options.flags = flags;
    options.levels = levels;
    if (spectrum != NULL) {
        options.linear_weight = spectrum->linear_weight;
        options.linear_weights = spectrum->linear_weights;
    }
    s = tags ? nls_mesh_plan_scratch_size_tagged(&view, tags, &topo_u32) : nls_mesh_plan_scratch_size(&view, &topo_u32);
    if (s != NLS_STATUS_OK) return s;
    if ((topo = ALLOC(uint32_t, topo_u32)) == NULL) return FW_STATUS_NO_MEMORY;
    s = tags ? nls_mesh_plan_tagged(&view, &options, tags, topo, topo_u32, &plan, &out->element)
             : nls_mesh_plan(&view, &options, topo, topo_u32, &plan, &out->element);
    if (s != NLS_STATUS_OK) return s;
    s = buffers_of(&plan, out, &scratch, &buffers);
    if (s != NLS_STATUS_OK) return s;
    s = tags ? nls_mesh_subdivide_tagged(&view, &options, tags, &scratch, &buffers, &written, &report, &out->element)
             : nls_mesh_subdivide(&view, &options, &scratch, &buffers, &written, &report, &out->element);
    if (s != NLS_STATUS_OK) return s;
    out->vertex_count = written.vertex_count;
    out->face_count = written.face_count;
    out->index_count = written.index_count;
    out->fallbacks = report.fallbacks;
    out->first_fallback = report.first_fallback;
    out->first_fallback_level = report.first_fallback_level;
    return s;
}

uint32_t fw_mesh_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *m,
                           fw_mesh_result *out) {
    return mesh_subdivide(scheme, flags, levels, m, NULL, NULL, out);
}

uint32_t fw_mesh_subdivide_spectrum(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *m,
                                    const fw_spectrum *spectrum, fw_mesh_result *out) {
    return mesh_subdivide(scheme, flags, levels, m, NULL, spectrum, out);
}

uint32_t fw_mesh_subdivide_tagged(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *m,
                                  const fw_tags *t, fw_mesh_result *out) {
    nls_tags tags;
    tags.crease_vertices = t->crease_vertices;
    tags.crease_sharpness = t->crease_sharpness;
    tags.crease_count = t->crease_count;
    tags.corner_vertices = t->corner_vertices;
    tags.corner_sharpness = t->corner_sharpness;
    tags.corner_count = t->corner_count;
    tags.method = t->method;
    return mesh_subdivide(scheme, flags, levels, m, &tags, NULL, out);
}

uint32_t fw_curve_subdivide(uint32_t scheme, const double *points, size_t count, uint32_t closed,
                            uint32_t levels, fw_curve_result *out) {
    size_t len = 0, scratch_len = 0;
    double *scratch;
    nls_status s;
    memset(out, 0, sizeof *out);
    out->element = NLS_NO_ELEMENT;
    nls_curve_view curve;
    curve.points = points;
    curve.count = count;
    curve.closed = closed;
    s = nls_curve_refined_size(count, closed, levels, &len);
    if (s != NLS_STATUS_OK) return s;
    s = nls_curve_scratch_size(scheme, count, closed, levels, &scratch_len);
    if (s != NLS_STATUS_OK) return s;
    out->points = ALLOC(double, 3 * len);
    scratch = ALLOC(double, 3 * scratch_len);
    if (out->points == NULL || scratch == NULL) return FW_STATUS_NO_MEMORY;
    return nls_curve_subdivide(scheme, &curve, levels, out->points, len, scratch, scratch_len, &out->count,
                               &out->element);
}

uint32_t fw_differential_subdivide(uint32_t scheme, uint32_t levels, uint32_t dirmag_levels,
                                   const fw_mesh *m, fw_mesh_result *out,
                                   fw_differential_report *report) {
    nls_mesh_view view = view_of(m);
    nls_differential_options options;
    nls_differential_report r;
    nls_plan plan;
    nls_scratch scratch;
    nls_mesh_buffers buffers;
    nls_mesh_sizes written;
    size_t topo_u32 = 0;
    uint32_t *topo;
    nls_status s;
    clear(out);
    memset(report, 0, sizeof *report);
    s = nls_differential_default_options(&options);
    if (s != NLS_STATUS_OK) return s;
    options.scheme = scheme;
    options.levels = levels;
    options.dirmag_levels = dirmag_levels;
    s = nls_mesh_plan_scratch_size(&view, &topo_u32);
    if (s != NLS_STATUS_OK) return s;
    if ((topo = ALLOC(uint32_t, topo_u32)) == NULL) return FW_STATUS_NO_MEMORY;
    s = nls_differential_plan(&view, &options, topo, topo_u32, &plan, &out->element);
    if (s != NLS_STATUS_OK) return s;
    s = buffers_of(&plan, out, &scratch, &buffers);
    if (s != NLS_STATUS_OK) return s;
    s = nls_differential_subdivide(&view, &options, &scratch, &buffers, &written, &r, &out->element);
    if (s == NLS_STATUS_OK) {
        out->vertex_count = written.vertex_count;
        out->face_count = written.face_count;
        out->index_count = written.index_count;
    }
    if (s == NLS_STATUS_OK || s == NLS_STATUS_NOT_CONVERGED) {
        report->iterations = r.iterations;
        report->converged = r.converged;
        report->anchors = r.anchors;
        report->dirmag_degenerate = r.dirmag_degenerate;
        report->relative_residual = r.relative_residual;
        report->initial_residual = r.initial_residual;
    }
    return s;
}

/* The harness's star as the library's view. */
static nls_star_view star_of(const fw_star *st) {
    nls_star_view v;
    v.v = st->v;
    v.ring = st->ring;
    v.ring_count = st->ring_count;
    v.closed = st->closed;
    v.face_offsets = st->face_offsets;
    v.face_count = st->face_count;
    v.face_corners = st->face_corners;
    v.corner_count = st->corner_count;
    return v;
}

uint32_t fw_loop_star(const fw_star *st, double *vertex_point, double *edge_candidates) {
    nls_star_view v = star_of(st);
    return nls_mobius_loop_star(&v, vertex_point, edge_candidates);
}

uint32_t fw_catmull_clark_star(const fw_star *st, double *vertex_point, double *edge_candidates,
                               double *face_candidates) {
    nls_star_view v = star_of(st);
    return nls_mobius_catmull_clark_star(&v, vertex_point, edge_candidates, face_candidates);
}

uint32_t fw_butterfly_star(const fw_star *st, const uint32_t *irregular, double *edge_candidates) {
    nls_star_view v = star_of(st);
    return nls_mobius_butterfly_star(&v, irregular, edge_candidates);
}
