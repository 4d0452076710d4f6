/* The built-in inputs: small meshes and curves given by exact decimal literals or exact
 * dyadic arithmetic, so every target starts from the same bits (no libm calls here: sin and
 * cos differ between C libraries). */
#ifndef FW_MESHES_H
#define FW_MESHES_H

#include "calls.h"

enum fw_face_kind { FW_TRIANGLES, FW_QUADS, FW_MIXED };

typedef struct fw_named_mesh {
    const char *name;
    enum fw_face_kind faces;
    /* > 0: every vertex lies on the sphere of this squared radius about the origin. */
    double sphere_r2;
    fw_mesh mesh;
} fw_named_mesh;

/* tetrahedron, octahedron, cube (closed, cospherical), a 3×3 quad grid and its
 * triangulation (open, bumpy), a fan of five triangles around an interior vertex of
 * valence 5 (open), a mixed star (triangles, quads and a pentagon around an interior vertex
 * of valence 5; open). */
extern const fw_named_mesh fw_meshes[];
extern const size_t fw_mesh_count;
/* Fills the grids (called once by the mesh suites before they use fw_meshes). */
void fw_meshes_init(void);

/* The fan's centre and ring, and the mixed star's centre, ring and faces (the star
 * rules take them apart). */
extern const double fw_fan_positions[6 * 3];
extern const double fw_mixed_positions[10 * 3];
extern const uint32_t fw_mixed_offsets[6];
extern const uint32_t fw_mixed_indices[19];

/* Curves: an open zigzag of 5 points, a closed non-planar hexagon, the cocircular square. */
extern const double fw_curve_open[5 * 3];
extern const double fw_curve_closed[6 * 3];
extern const double fw_curve_circle[4 * 3];

#endif
