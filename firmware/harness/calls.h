/* The harness's only door to the C functions whose signatures change with C ABI 0.2: the
 * curve, mesh, differential and star-rule calls. Everything else (case definitions, inputs,
 * hashing, checks) uses the types below, which follow the 0.2 view structs field for field,
 * so an ABI change means rewriting calls.c alone.
 *
 * Each function sizes the call with the library's own sizing functions, takes the buffers
 * from the harness arena (arena.h) and returns the library's status (or
 * FW_STATUS_NO_MEMORY). Results point into the arena and live until the next case. */
#ifndef FW_CALLS_H
#define FW_CALLS_H

#include <stddef.h>
#include <stdint.h>

/* An input mesh: packed x, y, z per vertex; offsets[face_count + 1]; indices. */
typedef struct fw_mesh {
    const double *positions;
    size_t vertex_count;
    const uint32_t *offsets;
    size_t face_count;
    const uint32_t *indices;
    size_t index_count;
} fw_mesh;

/* What a mesh call wrote. `element` is the library's out_element (NLS_NO_ELEMENT when it
 * named none); the fallback fields are nls_subdivide_report's. */
typedef struct fw_mesh_result {
    double *positions;
    size_t vertex_count;
    uint32_t *offsets;
    size_t face_count;
    uint32_t *indices;
    size_t index_count;
    uint32_t fallbacks, first_fallback, first_fallback_level;
    uint32_t element;
} fw_mesh_result;

/* `levels` levels of mesh scheme `scheme` (NLS_SCHEME_*) with `flags` (NLS_SUBDIVIDE_*). */
uint32_t fw_mesh_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *mesh,
                           fw_mesh_result *out);

/* Sharp-feature tags (nls_tags field for field): crease edges as vertex pairs with their
 * sharpness, corner vertices with theirs, the crease method (NLS_CREASE_*). */
typedef struct fw_tags {
    const uint32_t *crease_vertices;
    const double *crease_sharpness;
    size_t crease_count;
    const uint32_t *corner_vertices;
    const double *corner_sharpness;
    size_t corner_count;
    uint32_t method;
} fw_tags;

/* fw_mesh_subdivide with sharp-feature tags (the _tagged plan and subdivide calls). */
uint32_t fw_mesh_subdivide_tagged(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *mesh,
                                  const fw_tags *tags, fw_mesh_result *out);

/* The Möbius–linear spectrum (nls_subdivide_options.linear_weight, .linear_weights): the weight
 * of the linear result, global, or one per input vertex (NULL: the global one). */
typedef struct fw_spectrum {
    double linear_weight;
    const double *linear_weights;
} fw_spectrum;

/* fw_mesh_subdivide with the spectrum's weights in the options (flags as there, for instance
 * NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_LITERAL). */
uint32_t fw_mesh_subdivide_spectrum(uint32_t scheme, uint32_t flags, uint32_t levels, const fw_mesh *mesh,
                                    const fw_spectrum *spectrum, fw_mesh_result *out);

typedef struct fw_curve_result {
    double *points;
    size_t count;
    uint32_t element;
} fw_curve_result;

/* `levels` levels of curve scheme `scheme` (NLS_CURVE_*), `closed` 0 or 1. */
uint32_t fw_curve_subdivide(uint32_t scheme, const double *points, size_t count, uint32_t closed,
                            uint32_t levels, fw_curve_result *out);

/* The solver figures of nls_differential_report. */
typedef struct fw_differential_report {
    uint32_t iterations, converged, anchors, dirmag_degenerate;
    double relative_residual, initial_residual;
} fw_differential_report;

/* Differential-space subdivision with the default options except `scheme`
 * (NLS_DIFFERENTIAL_*), `levels` and `dirmag_levels`. */
uint32_t fw_differential_subdivide(uint32_t scheme, uint32_t levels, uint32_t dirmag_levels,
                                   const fw_mesh *mesh, fw_mesh_result *out,
                                   fw_differential_report *report);

/* A vertex star for the tier-1 star rules: centre `v`, `ring_count` neighbours, `closed`
 * 1 (interior) or 0 (boundary); the faces (Catmull–Clark only, else 0/NULL) as
 * face_corners[face_offsets[j] .. face_offsets[j+1]], points, `v` included. */
typedef struct fw_star {
    const double *v;
    const double *ring;
    size_t ring_count;
    uint32_t closed;
    const uint32_t *face_offsets;
    size_t face_count;
    const double *face_corners;
    size_t corner_count;
} fw_star;

/* Outputs: vertex_point[3]; edge_candidates[3*ring_count]; face_candidates[3*face_count]. */
uint32_t fw_loop_star(const fw_star *star, double *vertex_point, double *edge_candidates);
uint32_t fw_catmull_clark_star(const fw_star *star, double *vertex_point, double *edge_candidates,
                               double *face_candidates);
/* `irregular` holds ring_count flags (0/1) or is NULL. */
uint32_t fw_butterfly_star(const fw_star *star, const uint32_t *irregular, double *edge_candidates);

#endif
