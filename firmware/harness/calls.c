/* C ABI 0.1 calls behind the harness's adapter (calls.h). This is the file to rewrite when
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

/* One level: nls_mesh_subdivide_size, then nls_mesh_subdivide. Several levels (or 0):
 * nls_mesh_subdivide_levels_size, then nls_mesh_subdivide_levels. Both take the input's
 * topology scratch from nls_mesh_scratch_size first. */
uint32_t fw_mesh_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *m,
                           fw_mesh_result *out) {
    size_t topo_u32 = 0, topo_points = 0, nv = 0, nf = 0, ni = 0, need_u32 = 0, need_points = 0;
    uint32_t *scratch_u32;
    double *scratch_points;
    nls_subdivide_report report;
    nls_status s;
    clear(out);
    s = nls_mesh_scratch_size(scheme, flags, m->vertex_count, m->index_count, &topo_u32, &topo_points);
    if (s != NLS_STATUS_OK) return s;
    if ((scratch_u32 = ALLOC(uint32_t, topo_u32)) == NULL) return FW_STATUS_NO_MEMORY;
    if (levels == 1) {
        s = nls_mesh_subdivide_size(scheme, flags, m->positions, m->vertex_count, m->offsets, m->face_count,
                                    m->indices, m->index_count, scratch_u32, topo_u32, &nv, &nf, &ni,
                                    &out->element);
        need_u32 = topo_u32;
        need_points = topo_points;
    } else {
        s = nls_mesh_subdivide_levels_size(scheme, flags, m->positions, m->vertex_count, m->offsets,
                                           m->face_count, m->indices, m->index_count, levels, scratch_u32,
                                           topo_u32, &nv, &nf, &ni, &need_u32, &need_points, &out->element);
        if (s == NLS_STATUS_OK && need_u32 > topo_u32) {
            fw_arena_reset();
            if ((scratch_u32 = ALLOC(uint32_t, need_u32)) == NULL) return FW_STATUS_NO_MEMORY;
        }
    }
    if (s != NLS_STATUS_OK) return s;
    scratch_points = ALLOC(double, 3 * need_points);
    out->positions = ALLOC(double, 3 * nv);
    out->offsets = ALLOC(uint32_t, nf + 1);
    out->indices = ALLOC(uint32_t, ni);
    if (scratch_points == NULL || out->positions == NULL || out->offsets == NULL || out->indices == NULL)
        return FW_STATUS_NO_MEMORY;
    if (levels == 1)
        s = nls_mesh_subdivide(scheme, flags, m->positions, m->vertex_count, m->offsets, m->face_count,
                               m->indices, m->index_count, scratch_u32, need_u32, scratch_points, need_points,
                               out->positions, nv, out->offsets, nf, out->indices, ni, &out->vertex_count,
                               &out->face_count, &out->index_count, &report, &out->element);
    else
        s = nls_mesh_subdivide_levels(scheme, flags, m->positions, m->vertex_count, m->offsets, m->face_count,
                                      m->indices, m->index_count, levels, scratch_u32, need_u32,
                                      scratch_points, need_points, out->positions, nv, out->offsets, nf,
                                      out->indices, ni, &out->vertex_count, &out->face_count,
                                      &out->index_count, &report, &out->element);
    if (s != NLS_STATUS_OK) return s;
    out->fallbacks = report.fallbacks;
    out->first_fallback = report.first_fallback;
    out->first_fallback_level = report.first_fallback_level;
    return s;
}

uint32_t fw_curve_subdivide(uint32_t scheme, const double *points, size_t count, uint32_t closed,
                            uint32_t levels, fw_curve_result *out) {
    size_t len = 0, scratch_len = 0;
    double *scratch;
    nls_status s;
    memset(out, 0, sizeof *out);
    out->element = NLS_NO_ELEMENT;
    s = nls_curve_refined_len(count, closed, levels, &len);
    if (s != NLS_STATUS_OK) return s;
    s = nls_curve_scratch_len(scheme, count, closed, levels, &scratch_len);
    if (s != NLS_STATUS_OK) return s;
    out->points = ALLOC(double, 3 * len);
    scratch = ALLOC(double, 3 * scratch_len);
    if (out->points == NULL || scratch == NULL) return FW_STATUS_NO_MEMORY;
    return nls_curve_subdivide(scheme, points, count, closed, levels, out->points, len, scratch, scratch_len,
                               &out->count, &out->element);
}

uint32_t fw_differential_subdivide(uint32_t scheme, uint32_t levels, uint32_t dirmag_levels,
                                   const fw_mesh *m, fw_mesh_result *out,
                                   fw_differential_report *report) {
    nls_differential_options options;
    nls_differential_report r;
    size_t topo_u32 = 0, nv = 0, nf = 0, ni = 0, need_u32 = 0, need_points = 0;
    uint32_t *scratch_u32;
    double *scratch_points;
    nls_status s;
    clear(out);
    memset(report, 0, sizeof *report);
    s = nls_differential_default_options(&options);
    if (s != NLS_STATUS_OK) return s;
    options.scheme = scheme;
    options.levels = levels;
    options.dirmag_levels = dirmag_levels;
    s = nls_differential_scratch_size(m->vertex_count, m->index_count, &topo_u32);
    if (s != NLS_STATUS_OK) return s;
    if ((scratch_u32 = ALLOC(uint32_t, topo_u32)) == NULL) return FW_STATUS_NO_MEMORY;
    s = nls_differential_plan(m->positions, m->vertex_count, m->offsets, m->face_count, m->indices,
                              m->index_count, &options, scratch_u32, topo_u32, &nv, &nf, &ni, &need_u32,
                              &need_points, &out->element);
    if (s != NLS_STATUS_OK) return s;
    fw_arena_reset();
    scratch_u32 = ALLOC(uint32_t, need_u32);
    scratch_points = ALLOC(double, 3 * need_points);
    out->positions = ALLOC(double, 3 * nv);
    out->offsets = ALLOC(uint32_t, nf + 1);
    out->indices = ALLOC(uint32_t, ni);
    if (scratch_u32 == NULL || scratch_points == NULL || out->positions == NULL || out->offsets == NULL ||
        out->indices == NULL)
        return FW_STATUS_NO_MEMORY;
    s = nls_differential_subdivide(m->positions, m->vertex_count, m->offsets, m->face_count, m->indices,
                                   m->index_count, &options, scratch_u32, need_u32, scratch_points,
                                   need_points, out->positions, nv, out->offsets, nf, out->indices, ni,
                                   &out->vertex_count, &out->face_count, &out->index_count, &r,
                                   &out->element);
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

uint32_t fw_loop_star(const fw_star *st, double *vertex_point, double *edge_candidates) {
    return nls_mobius_loop_star(st->v, st->ring, st->ring_count, st->closed, vertex_point, edge_candidates);
}

uint32_t fw_catmull_clark_star(const fw_star *st, double *vertex_point, double *edge_candidates,
                               double *face_candidates) {
    return nls_mobius_catmull_clark_star(st->v, st->ring, st->ring_count, st->closed, st->face_offsets,
                                         st->face_count, st->face_corners, st->corner_count, vertex_point,
                                         edge_candidates, face_candidates);
}

uint32_t fw_butterfly_star(const fw_star *st, const uint32_t *irregular, double *edge_candidates) {
    return nls_mobius_butterfly_star(st->v, st->ring, st->ring_count, st->closed, irregular, edge_candidates);
}
