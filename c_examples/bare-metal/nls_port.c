/* port_mesh_subdivide on C ABI 0.2: the plan, then the subdivision call. */
#include "nls_port.h"
#include "nlsubdiv.h"

uint32_t port_mesh_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const port_mesh *m,
                             port_buffers *b) {
    nls_mesh_view view;
    nls_subdivide_options options;
    nls_scratch scratch;
    nls_mesh_buffers out;
    nls_mesh_sizes written;
    nls_subdivide_report report;
    nls_plan plan;
    nls_status s;
    view.positions = m->positions;
    view.vertex_count = m->vertex_count;
    view.positions_stride = 0;
    view.offsets = m->offsets;
    view.face_count = m->face_count;
    view.indices = m->indices;
    view.index_count = m->index_count;
    s = nls_subdivide_default_options(&options);
    if (s != NLS_STATUS_OK) return s;
    options.scheme = scheme;
    options.flags = flags;
    options.levels = levels;
    /* Validates the mesh and gives the exact output and scratch sizes; checking them first
     * turns a short buffer into a status naming it before anything is computed. */
    s = nls_mesh_plan(&view, &options, b->scratch_u32, b->scratch_u32_capacity, &plan, &b->element);
    if (s != NLS_STATUS_OK) return s;
    scratch.u32s = b->scratch_u32;
    scratch.u32_capacity = b->scratch_u32_capacity;
    scratch.points = b->scratch_points;
    scratch.point_capacity = b->scratch_point_capacity;
    out.positions = b->positions;
    out.vertex_capacity = b->vertex_capacity;
    out.offsets = b->offsets;
    out.face_capacity = b->face_capacity;
    out.indices = b->indices;
    out.index_capacity = b->index_capacity;
    s = nls_mesh_subdivide(&view, &options, &scratch, &out, &written, &report, &b->element);
    if (s == NLS_STATUS_OK) {
        b->vertex_count = written.vertex_count;
        b->face_count = written.face_count;
        b->index_count = written.index_count;
    }
    return s;
}
