/* port_mesh_subdivide on C ABI 0.1: the levels call with its sizing call. */
#include "nls_port.h"
#include "nlsubdiv.h"

uint32_t port_mesh_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const port_mesh *m,
                             port_buffers *b) {
    size_t nv, nf, ni, need_u32, need_points;
    nls_subdivide_report report;
    /* Validates the mesh and gives the exact output and scratch sizes; checking them first
     * turns a short buffer into a status naming it before anything is computed. */
    nls_status s = nls_mesh_subdivide_levels_size(scheme, flags, m->positions, m->vertex_count, m->offsets,
                                                  m->face_count, m->indices, m->index_count, levels,
                                                  b->scratch_u32, b->scratch_u32_capacity, &nv, &nf, &ni,
                                                  &need_u32, &need_points, &b->element);
    if (s != NLS_STATUS_OK) return s;
    return nls_mesh_subdivide_levels(scheme, flags, m->positions, m->vertex_count, m->offsets, m->face_count,
                                     m->indices, m->index_count, levels, b->scratch_u32, b->scratch_u32_capacity,
                                     b->scratch_points, b->scratch_point_capacity, b->positions,
                                     b->vertex_capacity, b->offsets, b->face_capacity, b->indices,
                                     b->index_capacity, &b->vertex_count, &b->face_count, &b->index_count,
                                     &report, &b->element);
}
