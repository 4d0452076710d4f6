/* Cases over the primitives of the C ABI (seed 000 §3–4.4): cross-ratio, F4, hinted F4, F6,
 * noncircularity, corner tangent, tangent polygon, quaternion operations, Möbius maps,
 * canonical forms, star measures and face points; plus a few documented error statuses. */
#include <math.h>
#include <string.h>

#include "harness.h"
#include "nlsubdiv.h"

/* Points in general position (no four cocircular, not coplanar). */
static const double A[3] = {0.1, 0.2, 0.3}, B[3] = {1.1, -0.4, 0.25}, C[3] = {2.3, 0.9, -0.6},
                    D[3] = {3.2, -0.1, 0.45}, E[3] = {1.7, 1.3, 0.8}, F[3] = {0.4, -1.2, -0.35};
/* The unit circle in the plane z = 0, in the order 0°, 90°, 270°, 180°: (b, c) separates
 * (a, d), the negative-real case of F4. */
static const double U0[3] = {1, 0, 0}, U90[3] = {0, 1, 0}, U270[3] = {0, -1, 0}, U180[3] = {-1, 0, 0},
                    NORTH[3] = {0, 0, 1};
/* A star: centre and six neighbours around it (not cospherical). */
static const double SV[3] = {0.01, -0.02, 0.2};
static const double SRING[6 * 3] = {1,    0,    -0.03, 0.5,  0.875, 0.05, -0.5, 0.875, -0.03,
                                    -1.0, 0.01, 0.05,  -0.5, -0.875, -0.03, 0.5, -0.875, 0.05};
/* A cospherical star: the north pole of the octahedron and its four neighbours. */
static const double OV[3] = {0, 0, 1};
static const double ORING[4 * 3] = {1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
static const double QP[4] = {0.5, -1.25, 2.0, 0.75}, QQ[4] = {1.5, 0.25, -0.5, 2.0};

static double r2(const double *p) { return p[0] * p[0] + p[1] * p[1] + p[2] * p[2]; }

/* Ends a case whose output is `n` doubles, hashed when the call succeeded (outputs are
 * written on success only). */
static void end_points(fw_hash *h, uint32_t s, const double *out, size_t n, uint32_t expected) {
    if (s == NLS_STATUS_OK) fw_hash_f64s(h, out, n);
    fw_case_end(s, expected);
}

static void blends(void) {
    double out[4] = {0};
    fw_hash *h;
    uint32_t s;

    h = fw_case_begin("nls_cross_ratio", "cross_ratio/general");
    s = nls_cross_ratio(A, B, C, D, out);
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_cross_ratio", "cross_ratio/cocircular");
    s = nls_cross_ratio(U0, U90, U180, U270, out);
    /* cocircular points: the cross-ratio is real (seed 000 §3.2) */
    fw_check(s != NLS_STATUS_OK || (fabs(out[1]) < 1e-15 && fabs(out[2]) < 1e-15 && fabs(out[3]) < 1e-15),
             "cocircular cross-ratio not real");
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_cross_ratio", "cross_ratio/b=c");
    s = nls_cross_ratio(A, B, B, D, out);
    end_points(h, s, out, 4, NLS_STATUS_DEGENERATE_GEOMETRY);

    h = fw_case_begin("nls_f4", "f4/general");
    s = nls_f4(A, B, C, D, out);
    end_points(h, s, out, 3, NLS_STATUS_OK);

    {
        static const double L0[3] = {0, 0, 0}, L1[3] = {1, 0, 0}, L2[3] = {2, 0, 0}, L3[3] = {3, 0, 0};
        h = fw_case_begin("nls_f4", "f4/line");
        s = nls_f4(L0, L1, L2, L3, out);
        /* four equally spaced points on a line: the midpoint, exactly */
        fw_check(s != NLS_STATUS_OK || (out[0] == 1.5 && out[1] == 0 && out[2] == 0), "F4 on a line not 1.5");
        end_points(h, s, out, 3, NLS_STATUS_OK);
    }

    h = fw_case_begin("nls_f4", "f4/circle");
    s = nls_f4(U270, U0, U90, U180, out);
    fw_check(s != NLS_STATUS_OK || fabs(r2(out) - 1) < 1e-14, "F4 of cocircular points off the circle");
    end_points(h, s, out, 3, NLS_STATUS_OK);

    {
        double nan_point[3];
        nan_point[0] = NAN;
        nan_point[1] = nan_point[2] = 0;
        h = fw_case_begin("nls_f4", "f4/nan");
        s = nls_f4(A, nan_point, C, D, out);
        end_points(h, s, out, 3, NLS_STATUS_NON_FINITE_INPUT);
    }

    h = fw_case_begin("nls_f4_hinted", "f4_hinted/separated");
    s = nls_f4_hinted(U0, U90, U270, U180, NORTH, out);
    /* the negative-real case: the point on the sphere through a, b, c, x (the unit sphere) */
    fw_check(s != NLS_STATUS_OK || fabs(r2(out) - 1) < 1e-14, "hinted F4 off the unit sphere");
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_f4_hinted", "f4_hinted/general");
    s = nls_f4_hinted(A, B, C, D, E, out);
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_f6", "f6/general");
    s = nls_f6(A, B, C, D, E, F, out);
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_noncircularity", "noncircularity/general");
    s = nls_noncircularity(A, B, C, D, out);
    end_points(h, s, out, 1, NLS_STATUS_OK);

    h = fw_case_begin("nls_noncircularity", "noncircularity/cocircular");
    s = nls_noncircularity(U0, U90, U180, U270, out);
    fw_check(s != NLS_STATUS_OK || fabs(out[0]) < 1e-15, "noncircularity of cocircular points not 0");
    end_points(h, s, out, 1, NLS_STATUS_OK);

    h = fw_case_begin("nls_corner_tangent", "corner_tangent/general");
    s = nls_corner_tangent(A, B, C, out);
    end_points(h, s, out, 3, NLS_STATUS_OK);
}

static void polygons(void) {
    double out[6 * 3] = {0}, v = 0;
    fw_hash *h;
    uint32_t s;

    h = fw_case_begin("nls_tangent_polygon", "tangent_polygon/star6");
    s = nls_tangent_polygon(SV, SRING, 6, out);
    end_points(h, s, out, 18, NLS_STATUS_OK);

    h = fw_case_begin("nls_star_willmore_energy", "willmore/star6");
    s = nls_star_willmore_energy(SV, SRING, 6, 1, &v);
    end_points(h, s, &v, 1, NLS_STATUS_OK);

    h = fw_case_begin("nls_star_willmore_energy", "willmore/cospherical");
    s = nls_star_willmore_energy(OV, ORING, 4, 1, &v);
    fw_check(s != NLS_STATUS_OK || fabs(v) < 1e-15, "Willmore energy of a cospherical star not 0");
    end_points(h, s, &v, 1, NLS_STATUS_OK);

    h = fw_case_begin("nls_star_willmore_energy", "willmore/open");
    s = nls_star_willmore_energy(SV, SRING, 6, 0, &v);
    end_points(h, s, &v, 1, NLS_STATUS_OK);

    h = fw_case_begin("nls_star_mobius_regularity", "regularity/star6");
    s = nls_star_mobius_regularity(SV, SRING, 6, 1, &v);
    end_points(h, s, &v, 1, NLS_STATUS_OK);

    {
        /* a square face and candidates near its corners */
        static const double fv[4 * 3] = {0, 0, 0, 1, 0, 0.1, 1, 1, 0, 0, 1, -0.1};
        static const double fc[4 * 3] = {0.5, 0.5, 0.05, 0.52, 0.49, 0.02, 0.5, 0.51, -0.01, 0.49, 0.5, 0.03};
        static const double tv[3 * 3] = {0, 0, 0, 1, 0, 0.2, 0.25, 1, 0};
        static const double tc[3 * 3] = {0.4, 0.35, 0.05, 0.42, 0.33, 0.07, 0.41, 0.36, 0.06};
        static const uint32_t ids[4] = {17, 3, 8, 42};
        h = fw_case_begin("nls_face_point", "face_point/quad");
        s = nls_face_point(fv, fc, 4, out);
        end_points(h, s, out, 3, NLS_STATUS_OK);

        h = fw_case_begin("nls_face_point", "face_point/triangle");
        s = nls_face_point(tv, tc, 3, out);
        end_points(h, s, out, 3, NLS_STATUS_OK);

        h = fw_case_begin("nls_face_point_with_ids", "face_point_with_ids/quad");
        s = nls_face_point_with_ids(fv, fc, ids, 4, out);
        end_points(h, s, out, 3, NLS_STATUS_OK);

        h = fw_case_begin("nls_face_point", "face_point/too_few");
        s = nls_face_point(fv, fc, 2, out);
        end_points(h, s, out, 3, NLS_STATUS_TOO_FEW_POINTS);
    }
}

static void quaternions(void) {
    static const double I[4] = {0, 1, 0, 0}, J[4] = {0, 0, 1, 0}, ZERO[4] = {0, 0, 0, 0},
                        MINUS_ONE[4] = {-1, 0, 0, 0}, FOUR[4] = {4, 0, 0, 0};
    double out[4] = {0};
    fw_hash *h;
    uint32_t s;

    h = fw_case_begin("nls_quat_mul", "quat_mul/general");
    s = nls_quat_mul(QP, QQ, out);
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_quat_mul", "quat_mul/ij");
    s = nls_quat_mul(I, J, out);
    fw_check(s != NLS_STATUS_OK || (out[0] == 0 && out[1] == 0 && out[2] == 0 && out[3] == 1), "i·j is not k");
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_quat_inverse", "quat_inverse/general");
    s = nls_quat_inverse(QP, out);
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_quat_inverse", "quat_inverse/zero");
    s = nls_quat_inverse(ZERO, out);
    end_points(h, s, out, 4, NLS_STATUS_DEGENERATE_GEOMETRY);

    h = fw_case_begin("nls_quat_sqrt", "quat_sqrt/general");
    s = nls_quat_sqrt(QP, out);
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_quat_sqrt", "quat_sqrt/four");
    s = nls_quat_sqrt(FOUR, out);
    fw_check(s != NLS_STATUS_OK || (out[0] == 2 && out[1] == 0 && out[2] == 0 && out[3] == 0), "√4 is not 2");
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_quat_sqrt", "quat_sqrt/negative_real");
    s = nls_quat_sqrt(MINUS_ONE, out);
    end_points(h, s, out, 4, NLS_STATUS_DEGENERATE_GEOMETRY);

    h = fw_case_begin("nls_quat_log", "quat_log/general");
    s = nls_quat_log(QP, out);
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_quat_exp", "quat_exp/general");
    s = nls_quat_exp(QQ, out);
    end_points(h, s, out, 4, NLS_STATUS_OK);

    h = fw_case_begin("nls_quat_exp", "quat_exp/zero");
    s = nls_quat_exp(ZERO, out);
    fw_check(s != NLS_STATUS_OK || (out[0] == 1 && out[1] == 0 && out[2] == 0 && out[3] == 0), "exp 0 is not 1");
    end_points(h, s, out, 4, NLS_STATUS_OK);
}

static void hash_mobius(fw_hash *h, const nls_mobius *m) {
    fw_hash_f64s(h, m->a, 4);
    fw_hash_f64s(h, m->b, 4);
    fw_hash_f64s(h, m->c, 4);
    fw_hash_f64s(h, m->d, 4);
}

static void mobius(void) {
    static const double AXIS[3] = {0.25, -0.5, 1}, T[3] = {0.1, 0.2, 0.3}, CENTRE[3] = {0.3, -0.2, 0.5};
    nls_mobius sim, inv, comp, back, id;
    nls_canonical_form cf;
    double out[3] = {0};
    fw_hash *h;
    uint32_t s;

    memset(&sim, 0, sizeof sim);
    inv = comp = back = id = sim;
    memset(&cf, 0, sizeof cf);

    h = fw_case_begin("nls_mobius_identity", "mobius_identity/apply");
    s = nls_mobius_identity(&id);
    if (s == NLS_STATUS_OK) s = nls_mobius_apply(&id, E, out);
    fw_check(s != NLS_STATUS_OK || fw_same_bits(out, E, 3), "the identity moved a point");
    if (s == NLS_STATUS_OK) hash_mobius(h, &id);
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_mobius_similarity", "mobius_similarity/apply");
    s = nls_mobius_similarity(AXIS, 0.7, 1.5, T, &sim);
    if (s == NLS_STATUS_OK) {
        hash_mobius(h, &sim);
        s = nls_mobius_apply(&sim, E, out);
    }
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_mobius_inversion", "mobius_inversion/apply");
    s = nls_mobius_inversion(CENTRE, 0.8, &inv);
    if (s == NLS_STATUS_OK) {
        hash_mobius(h, &inv);
        s = nls_mobius_apply(&inv, E, out);
    }
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_mobius_compose", "mobius_compose/apply");
    s = nls_mobius_compose(&inv, &sim, &comp);
    if (s == NLS_STATUS_OK) {
        hash_mobius(h, &comp);
        s = nls_mobius_apply(&comp, F, out);
    }
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_mobius_invert", "mobius_invert/apply");
    s = nls_mobius_invert(&comp, &back);
    if (s == NLS_STATUS_OK) {
        hash_mobius(h, &back);
        s = nls_mobius_apply(&back, F, out);
    }
    end_points(h, s, out, 3, NLS_STATUS_OK);

    h = fw_case_begin("nls_mobius_apply", "mobius_apply/to_infinity");
    s = nls_mobius_apply(&inv, CENTRE, out);
    end_points(h, s, out, 3, NLS_STATUS_DEGENERATE_GEOMETRY);

    h = fw_case_begin("nls_canonical_form_new", "canonical_form/interior");
    s = nls_canonical_form_new(SV, SRING, 6, NLS_STAR_INTERIOR, &cf);
    if (s == NLS_STATUS_OK) {
        fw_hash_f64s(h, cf.v, 3);
        fw_hash_f64s(h, cf.c, 3);
        fw_hash_f64s(h, &cf.r, 1);
        fw_hash_u32(h, cf.kind);
        s = nls_canonical_form_to_canonical(&cf, A, out);
    }
    if (s == NLS_STATUS_OK) {
        fw_hash_f64s(h, out, 3);
        s = nls_canonical_form_from_canonical(&cf, B, out);
    }
    if (s == NLS_STATUS_OK) {
        fw_hash_f64s(h, out, 3);
        s = nls_canonical_form_map(&cf, 0, &comp);
    }
    if (s == NLS_STATUS_OK) {
        hash_mobius(h, &comp);
        s = nls_canonical_form_map(&cf, 1, &comp);
    }
    if (s == NLS_STATUS_OK) hash_mobius(h, &comp);
    fw_case_end(s, NLS_STATUS_OK);

    h = fw_case_begin("nls_canonical_form_new", "canonical_form/boundary");
    s = nls_canonical_form_new(SV, SRING, 6, NLS_STAR_BOUNDARY, &cf);
    if (s == NLS_STATUS_OK) {
        fw_hash_f64s(h, cf.c, 3);
        fw_hash_f64s(h, &cf.r, 1);
        s = nls_canonical_form_to_canonical(&cf, C, out);
    }
    end_points(h, s, out, 3, NLS_STATUS_OK);
}

void fw_cases_primitives(void) {
    blends();
    polygons();
    quaternions();
    mobius();
}
