/* C tests of nls_mobius_butterfly_star (the tier-1 Möbius Modified Butterfly rule):
 * a whole level assembled from the star rules as its docs say equals nls_mesh_subdivide,
 * bit for bit, on meshes that exercise every branch (Zorin's stencil at irregular interior
 * vertices, the skipped spokes next to them, the regular half-stencil with its wings and with
 * OpenMesh's reflection across boundary edges, ears, the boundary curve rule); and the
 * argument checks, with nothing written on error. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "flat_args.h"
#include "nlsubdiv.h"

#define NONE UINT32_MAX

typedef struct {
    size_t nv, nf;
    double p[3 * 64];
    uint32_t idx[3 * 96];
} tri_mesh;

static uint32_t nxt(uint32_t c) { return 3 * (c / 3) + (c % 3 + 1) % 3; }
static uint32_t prv(uint32_t c) { return 3 * (c / 3) + (c % 3 + 2) % 3; }
static uint32_t twin(const tri_mesh *m, uint32_t c) {
    uint32_t d;
    for (d = 0; d < 3 * m->nf; d++)
        if (m->idx[d] == m->idx[nxt(c)] && m->idx[nxt(d)] == m->idx[c]) return d;
    return NONE;
}

/* The driver's star of v: spokes (outgoing corners, NONE for the closing spoke of a boundary
 * star) counter-clockwise from the lowest outgoing corner (interior) or from the outgoing
 * boundary corner; returns the spoke count, *closed whether v is interior. */
static size_t star(const tri_mesh *m, uint32_t v, uint32_t *spokes, uint32_t *ring, int *closed) {
    uint32_t c, h0 = NONE, h;
    size_t n = 0;
    *closed = 1;
    for (c = 0; c < 3 * m->nf; c++)
        if (m->idx[c] == v && twin(m, c) == NONE) {
            h0 = c;
            *closed = 0;
            break;
        }
    if (h0 == NONE)
        for (c = 0; c < 3 * m->nf; c++)
            if (m->idx[c] == v) {
                h0 = c;
                break;
            }
    if (h0 == NONE) return 0;
    h = h0;
    do {
        uint32_t p = prv(h), t = twin(m, p);
        spokes[n] = h;
        ring[n++] = m->idx[nxt(h)];
        if (t == NONE) {
            spokes[n] = NONE;
            ring[n++] = m->idx[p];
            break;
        }
        h = t;
    } while (h != h0 && n < 64);
    return n;
}

static size_t edge_id(const tri_mesh *m, uint32_t a, uint32_t b) {
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a, c, d;
    size_t id = 0;
    for (c = 0; c < 3 * m->nf; c++) {
        uint32_t x = m->idx[c], y = m->idx[nxt(c)], l = x < y ? x : y, u = x < y ? y : x;
        int first = 1; /* count each edge once: at its first corner in corner order */
        for (d = 0; d < c; d++) {
            uint32_t x2 = m->idx[d], y2 = m->idx[nxt(d)];
            if ((x2 == x && y2 == y) || (x2 == y && y2 == x)) first = 0;
        }
        if (first && (l < lo || (l == lo && u < hi))) id++;
    }
    return id;
}

/* The level from the star rules, compared with the driver point by point. */
static void level_from_star_rules(tri_mesh *m, const char *what) {
    static double cand[64][3 * 64], out[3 * 512], spts[3 * 4096];
    static uint32_t spokes[64][65], ring[64][65], scratch[4096], ooff[512], oidx[2048], off[97];
    size_t n[64], nv, k, same = 0, nsingle = 0, nzorin = 0;
    int closed[64];
    uint32_t v, c, f;
    for (f = 0; f <= m->nf; f++) off[f] = 3 * f;
    nls_mesh_sizes sz = {0, 0, 0};
    /* The star rules are the paper's rules: the driver's literal mode (the default's fold guard
     * changes the driver's output wherever it distrusts a star). */
    CHECK_STATUS(flat_subdivide(NLS_SCHEME_MODIFIED_BUTTERFLY, NLS_SUBDIVIDE_MOBIUS | NLS_SUBDIVIDE_LITERAL, 1, m->p, m->nv,
                                off, m->nf, m->idx,
                                3 * m->nf, scratch, 4096, spts, 4096, out, 512, ooff, 511, oidx, 2048, &sz, NULL, NULL),
                 NLS_STATUS_OK);
    nv = sz.vertex_count;
    for (v = 0; v < m->nv; v++) n[v] = star(m, v, spokes[v], ring[v], &closed[v]);
    for (v = 0; v < m->nv; v++) {
        double rxyz[3 * 64];
        uint32_t irr[64];
        for (k = 0; k < n[v]; k++) {
            uint32_t u = ring[v][k];
            memcpy(rxyz + 3 * k, m->p + 3 * u, sizeof(double) * 3);
            irr[k] = (closed[u] && n[u] != 6) ? 1u : 0u;
        }
        if (closed[v] && n[v] != 6) nzorin++;
        CHECK_STATUS(flat_butterfly_star(m->p + 3 * v, rxyz, n[v], (uint32_t)closed[v], irr, cand[v]), NLS_STATUS_OK);
        CHECK(memcmp(out + 3 * v, m->p + 3 * v, sizeof(double) * 3) == 0); /* interpolating */
        same++;
    }
    for (c = 0; c < 3 * m->nf; c++) {
        uint32_t a = m->idx[c], b = m->idx[nxt(c)], t = twin(m, c);
        const double *pe = out + 3 * (m->nv + edge_id(m, a, b));
        double e[3];
        if (t == NONE) { /* boundary: F4(P_{i-1}, a, b, P_{i+2}) */
            uint32_t d, p0 = NONE, p3 = NONE;
            for (d = 0; d < 3 * m->nf; d++) {
                if (twin(m, d) != NONE) continue;
                if (m->idx[nxt(d)] == a) p0 = m->idx[d];
                if (m->idx[d] == b) p3 = m->idx[nxt(d)];
            }
            CHECK_STATUS(nls_f4(m->p + 3 * p0, m->p + 3 * a, m->p + 3 * b, m->p + 3 * p3, e), NLS_STATUS_OK);
            CHECK(memcmp(e, pe, sizeof e) == 0);
            same++;
            continue;
        }
        if (a > b) continue;
        {
            const double *ca = NULL, *cb = NULL;
            for (k = 0; k < n[a]; k++)
                if (ring[a][k] == b && !isnan(cand[a][3 * k])) ca = cand[a] + 3 * k;
            for (k = 0; k < n[b]; k++)
                if (ring[b][k] == a && !isnan(cand[b][3 * k])) cb = cand[b] + 3 * k;
            if (ca && cb) {
                CHECK_STATUS(nls_f4_hinted(m->p + 3 * a, ca, cb, m->p + 3 * b, m->p + 3 * m->idx[nxt(nxt(c))], e), NLS_STATUS_OK);
            } else if (ca || cb) {
                memcpy(e, ca ? ca : cb, sizeof e);
                nsingle++;
            } else {
                continue; /* the linear fallback (none on these meshes: checked below) */
            }
            CHECK(memcmp(e, pe, sizeof e) == 0);
            same++;
        }
    }
    CHECK(same == nv); /* every output point was rebuilt from the star rules */
    printf("test_star_butterfly: %s: star rules = driver on %zu points, bit for bit (%zu single-candidate edges, %zu Zorin stars)\n", what,
           same, nsingle, nzorin);
}

/* A (w+1) x (h+1) grid of triangles, gently curved; `flip` flips one diagonal in the middle
 * (two interior vertices of valence 5 and two of valence 7). */
static void grid(tri_mesh *m, int w, int h, int flip) {
    int i, j;
    m->nv = (size_t)((w + 1) * (h + 1));
    m->nf = 0;
    for (j = 0; j <= h; j++)
        for (i = 0; i <= w; i++) {
            double *p = m->p + 3 * (j * (w + 1) + i);
            p[0] = i + 0.05 * j;
            p[1] = j;
            p[2] = 0.08 * (i - 1.5) * (i - 1.5) - 0.05 * j * j + 0.01 * i * j;
        }
    for (j = 0; j < h; j++)
        for (i = 0; i < w; i++) {
            uint32_t a = (uint32_t)(j * (w + 1) + i), b = a + 1, c = a + (uint32_t)w + 2, d = a + (uint32_t)w + 1;
            uint32_t *t = m->idx + 3 * m->nf;
            if (flip && i == w / 2 && j == h / 2) {
                t[0] = a, t[1] = b, t[2] = d, t[3] = b, t[4] = c, t[5] = d;
            } else {
                t[0] = a, t[1] = b, t[2] = c, t[3] = a, t[4] = c, t[5] = d;
            }
            m->nf += 2;
        }
}

static void icosahedron(tri_mesh *m) {
    static const uint32_t f[60] = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                                   3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double v[36] = {-1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1};
    size_t k;
    m->nv = 12;
    m->nf = 20;
    for (k = 0; k < 36; k++) m->p[k] = v[k] * (1.0 + 0.03 * (double)(k % 5)); /* off the sphere */
    memcpy(m->idx, f, sizeof f);
}

static void edge_cases(void) {
    static const double v[3] = {0, 0, 0};
    static const double ring[3 * 6] = {1, 0, 0.1, 0.5, 0.9, -0.1, -0.5, 0.9, 0.1, -1, 0, -0.1, -0.5, -0.9, 0.1, 0.5, -0.9, -0.1};
    const uint32_t bad_flags[6] = {0, 0, 2, 0, 0, 0}, flags[6] = {0, 1, 0, 0, 0, 0};
    double e[3 * 6], sentinel = 777.0;
    size_t k;
    /* regular interior star: six candidates; a flagged neighbour gets none */
    CHECK_STATUS(flat_butterfly_star(v, ring, 6, 1, NULL, e), NLS_STATUS_OK);
    CHECK(isfinite(e[0]) && isfinite(e[15]));
    {
        double all[3 * 6];
        memcpy(all, e, sizeof all);
        CHECK_STATUS(flat_butterfly_star(v, ring, 6, 1, flags, e), NLS_STATUS_OK);
        CHECK(isnan(e[3]) && nls_dist3(e, all) == 0.0 && nls_dist3(e + 6, all + 6) == 0.0); /* the others unchanged */
    }
    /* irregular interior star (valence 5): Zorin's stencil on every spoke, flags ignored */
    CHECK_STATUS(flat_butterfly_star(v, ring, 5, 1, flags, e), NLS_STATUS_OK);
    CHECK(isfinite(e[3]));
    /* boundary star: no candidates on its two boundary spokes; an ear gets none at all */
    CHECK_STATUS(flat_butterfly_star(v, ring, 4, 0, NULL, e), NLS_STATUS_OK);
    CHECK(isnan(e[0]) && isnan(e[9]) && isfinite(e[3]) && isfinite(e[6]));
    CHECK_STATUS(flat_butterfly_star(v, ring, 2, 0, NULL, e), NLS_STATUS_OK);
    CHECK(isnan(e[0]) && isnan(e[3]));
    /* errors: nothing written (the rule writes the caller's buffer directly, only once it
     * cannot fail) */
    for (k = 0; k < 3 * 6; k++) e[k] = sentinel;
    CHECK_STATUS(flat_butterfly_star(v, ring, 6, 2, NULL, e), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(flat_butterfly_star(v, ring, 6, 1, bad_flags, e), NLS_STATUS_INVALID_ARGUMENT);
    CHECK_STATUS(flat_butterfly_star(v, ring, 1, 0, NULL, e), NLS_STATUS_TOO_FEW_POINTS);
    CHECK_STATUS(flat_butterfly_star(v, NULL, 6, 1, NULL, e), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(flat_butterfly_star(NULL, ring, 6, 1, NULL, e), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(flat_butterfly_star(v, ring, 6, 1, NULL, NULL), NLS_STATUS_NULL_PARAMETER);
    CHECK_STATUS(flat_butterfly_star(v, ring, 200, 1, NULL, e), NLS_STATUS_VALENCE_TOO_HIGH);
    CHECK_STATUS(flat_butterfly_star(v, ring, SIZE_MAX / 2, 1, NULL, e), NLS_STATUS_SIZE_OVERFLOW);
    CHECK_STATUS(flat_butterfly_star(v, e, 6, 1, NULL, e), NLS_STATUS_ALIASING_BUFFERS);
    CHECK_STATUS(flat_butterfly_star(v, ring, 6, 1, (const uint32_t *)(void *)e, e), NLS_STATUS_ALIASING_BUFFERS);
    CHECK_STATUS(flat_butterfly_star(v, (const double *)((const char *)ring + 1), 6, 1, NULL, e), NLS_STATUS_MISALIGNED_POINTER);
    {
        double r2[3 * 6];
        memcpy(r2, ring, sizeof r2);
        r2[3] = r2[4] = r2[5] = 0.0; /* a neighbour on the centre: no canonical form */
        CHECK_STATUS(flat_butterfly_star(v, r2, 6, 1, NULL, e), NLS_STATUS_DEGENERATE_GEOMETRY);
        r2[4] = NAN;
        CHECK_STATUS(flat_butterfly_star(v, r2, 6, 1, NULL, e), NLS_STATUS_NON_FINITE_INPUT);
    }
    for (k = 0; k < 3 * 6; k++) CHECK(e[k] == sentinel);
}

int main(void) {
    tri_mesh *m = (tri_mesh *)calloc(1, sizeof *m);
    if (m == NULL) return 2;
    grid(m, 5, 4, 0);
    level_from_star_rules(m, "regular grid with boundary");
    grid(m, 5, 4, 1);
    level_from_star_rules(m, "grid with a flipped diagonal (valence 5 and 7)");
    icosahedron(m);
    level_from_star_rules(m, "icosahedron (valence 5 everywhere)");
    free(m);
    edge_cases();
    return nls_summary("test_star_butterfly");
}
