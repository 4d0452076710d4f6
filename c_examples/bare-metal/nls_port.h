/* The firmware's door to nlsubdiv's mesh call: one function with fixed, caller-owned
 * buffers. Keeping every call whose signature may change between versions of the C ABI
 * (mesh, curve, differential, star rules) behind a file like this one keeps an update of
 * the library a change of one file. */
#ifndef NLS_PORT_H
#define NLS_PORT_H

#include <stddef.h>
#include <stdint.h>

/* A mesh: packed x, y, z per vertex, offsets[face_count + 1], indices. */
typedef struct port_mesh {
    const double *positions;
    size_t vertex_count;
    const uint32_t *offsets;
    size_t face_count;
    const uint32_t *indices;
    size_t index_count;
} port_mesh;

/* Output and scratch buffers with their capacities (counts of elements: vertices, faces,
 * corners, uint32_t entries, points), and what the call wrote. */
typedef struct port_buffers {
    double *positions;
    size_t vertex_capacity;
    uint32_t *offsets; /* face_capacity + 1 entries */
    size_t face_capacity;
    uint32_t *indices;
    size_t index_capacity;
    uint32_t *scratch_u32;
    size_t scratch_u32_capacity;
    double *scratch_points; /* 3 doubles per point */
    size_t scratch_point_capacity;
    size_t vertex_count, face_count, index_count; /* written on success */
    uint32_t element; /* the element or buffer a failure names */
} port_buffers;

/* `levels` levels of `scheme` (NLS_SCHEME_*) with `flags` (NLS_SUBDIVIDE_*). Returns an
 * nls_status; NLS_STATUS_BUFFER_TOO_SMALL when a capacity is short (`element` says which,
 * NLS_MESH_BUFFER_*). */
uint32_t port_mesh_subdivide(uint32_t scheme, uint32_t flags, uint32_t levels, const port_mesh *mesh,
                             port_buffers *buffers);

#endif
