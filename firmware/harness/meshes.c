#include "meshes.h"

/* Tetrahedron inscribed in the sphere of radius √3; faces counter-clockwise from outside. */
static const double TET_P[4 * 3] = {1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1};
static const uint32_t TET_O[5] = {0, 3, 6, 9, 12};
static const uint32_t TET_I[12] = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};

/* Octahedron on the unit sphere. */
static const double OCTA_P[6 * 3] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
static const uint32_t OCTA_O[9] = {0, 3, 6, 9, 12, 15, 18, 21, 24};
static const uint32_t OCTA_I[24] = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};

/* Cube [−1, 1]³ (sphere of radius √3); vertex i has x, y, z from bits 0, 1, 2 of i. */
static const double CUBE_P[8 * 3] = {-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1,
                                     -1, -1, 1,  1, -1, 1,  -1, 1, 1,  1, 1, 1};
static const uint32_t CUBE_O[7] = {0, 4, 8, 12, 16, 20, 24};
static const uint32_t CUBE_I[24] = {0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 1, 3, 7, 5, 0, 4, 6, 2};

/* 4×4 vertices, x = i, y = j, z a bump in eighths; 3×3 quads, or each split in two. */
static double GRID_P[16 * 3];
static uint32_t GRIDQ_O[10], GRIDQ_I[36], GRIDT_O[19], GRIDT_I[54];

/* Centre (vertex 0) and five ring vertices counter-clockwise seen from +z. */
const double fw_fan_positions[6 * 3] = {0.1,   -0.05, 0.3,  1,    0,     0,   0.25, 0.9, 0.1,
                                        -0.8,  0.6,   -0.05, -0.7, -0.7, 0.15, 0.35, -0.95, -0.1};
static const uint32_t FAN_O[6] = {0, 3, 6, 9, 12, 15};
static const uint32_t FAN_I[15] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5, 0, 5, 1};

/* Centre 0, ring 1..5 as the fan's, and the outer corners a (6), b1, b2 (7, 8), d (9):
 * quad (0 1 6 2), triangle (0 2 3), pentagon (0 3 7 8 4), triangle (0 4 5), quad (0 5 9 1). */
const double fw_mixed_positions[10 * 3] = {0.05, 0.1,   0.25, 1,    0,   0,    0.25, 0.9, 0.1,  -0.8,
                                           0.6,  -0.05, -0.7, -0.7, 0.15, 0.35, -0.95, -0.1, 1.1,  1.0,
                                           -0.1, -1.5,  0.2,  0.1,  -1.3, -0.9, 0.0,   1.2,  -1.0, 0.05};
const uint32_t fw_mixed_offsets[6] = {0, 4, 7, 12, 15, 19};
const uint32_t fw_mixed_indices[19] = {0, 1, 6, 2, 0, 2, 3, 0, 3, 7, 8, 4, 0, 4, 5, 0, 5, 9, 1};

const fw_named_mesh fw_meshes[] = {
    {"tet", FW_TRIANGLES, 3, {TET_P, 4, TET_O, 4, TET_I, 12}},
    {"octa", FW_TRIANGLES, 1, {OCTA_P, 6, OCTA_O, 8, OCTA_I, 24}},
    {"cube", FW_QUADS, 3, {CUBE_P, 8, CUBE_O, 6, CUBE_I, 24}},
    {"gridq", FW_QUADS, 0, {GRID_P, 16, GRIDQ_O, 9, GRIDQ_I, 36}},
    {"gridt", FW_TRIANGLES, 0, {GRID_P, 16, GRIDT_O, 18, GRIDT_I, 54}},
    {"fan5", FW_TRIANGLES, 0, {fw_fan_positions, 6, FAN_O, 5, FAN_I, 15}},
    {"mixed5", FW_MIXED, 0, {fw_mixed_positions, 10, fw_mixed_offsets, 5, fw_mixed_indices, 19}},
};
const size_t fw_mesh_count = sizeof fw_meshes / sizeof fw_meshes[0];

void fw_meshes_init(void) {
    uint32_t i, j, q = 0, t = 0;
    for (j = 0; j < 4; j++)
        for (i = 0; i < 4; i++) {
            double *p = &GRID_P[3 * (4 * j + i)];
            p[0] = (double)i;
            p[1] = (double)j;
            p[2] = 0.125 * (double)((i * i + 2 * j + i * j) % 5);
        }
    GRIDQ_O[0] = GRIDT_O[0] = 0;
    for (j = 0; j < 3; j++)
        for (i = 0; i < 3; i++) {
            uint32_t a = 4 * j + i, b = a + 1, c = a + 5, d = a + 4;
            uint32_t quad[4] = {a, b, c, d}, k;
            for (k = 0; k < 4; k++) GRIDQ_I[4 * q + k] = quad[k];
            q++;
            GRIDQ_O[q] = 4 * q;
            /* alternate the diagonal so that the triangulation has vertices of valence 4,
             * 6 and 8 */
            if ((i + j) % 2 == 0) {
                uint32_t tri[6] = {a, b, c, a, c, d};
                for (k = 0; k < 6; k++) GRIDT_I[3 * t + k] = tri[k];
            } else {
                uint32_t tri[6] = {a, b, d, b, c, d};
                for (k = 0; k < 6; k++) GRIDT_I[3 * t + k] = tri[k];
            }
            GRIDT_O[t + 1] = 3 * (t + 1);
            GRIDT_O[t + 2] = 3 * (t + 2);
            t += 2;
        }
}

const double fw_curve_open[5 * 3] = {0, 0, 0, 1, 0.5, 0.1, 2, -0.25, 0.3, 3, 0.75, -0.2, 4.5, 0.125, 0};
const double fw_curve_closed[6 * 3] = {1,     0,    0.1,  0.5,  0.875, -0.2, -0.5, 0.75, 0.3,
                                       -1.25, 0.05, 0,    -0.5, -0.875, 0.25, 0.625, -0.75, -0.1};
const double fw_curve_circle[4 * 3] = {1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
