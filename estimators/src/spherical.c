/*
 * spherical.c - uniform sampling of a spherical triangle (estimator S),
 * Arvo's 1995 algorithm rewritten to keep full precision on tiny, sliver and
 * grazing triangles.
 *
 * Where Arvo's formulas (and their usual transcriptions) lose precision:
 *   1. The area Omega = alpha + beta + gamma - pi cancels catastrophically
 *      for small triangles: the absolute error is ~eps*pi, so a solid angle
 *      of 1e-10 comes out with a relative error of ~1e-6 (1e-4 at 1e-12).
 *      The vertex angles themselves come from acos of dot products of
 *      normalised cross products, which loses half the digits near 0 and pi
 *      (sliver triangles have angles near both).
 *   2. The sub-triangle's new vertex is C' = q A + sqrt(1 - q^2) T with q =
 *      cos(arc AC') near 1 for small triangles: sqrt(1 - q^2) carries an
 *      absolute error of ~sqrt(eps) = 1e-8, as large as the whole triangle
 *      when it spans 1e-8 radians, and a sizeable fraction at 1e-5.
 *   3. The final step, cos(theta) = 1 - u2 (1 - C'.B), forms 1 - C'.B ~
 *      theta^2/2 from a dot product near 1: the same sqrt(eps) loss.
 *   pbrt-v4 takes the vertex angles with an atan2-based AngleBetween and
 *   draws the sub-area plus pi between pi and A_pi (no subtraction there),
 *   but its density 1/(A_pi - pi), the weight estimator S multiplies by,
 *   keeps the cancellation of (1), its sin and cos of A'_pi ~ pi carry
 *   A'_pi's absolute rounding, and it keeps (2) and (3) (SafeSqrt(1 - x^2)
 *   for sin(b') and sin(theta)).
 *
 * The reformulation used here works only with differences of unit vectors
 * computed from the triangle's edges (never from differences of nearly
 * equal unit vectors), and solves for C' in closed form:
 *   - Omega by Van Oosterom & Strackee: tan(Omega/2) = A.(B x C) /
 *     (1 + A.B + A.C + B.C), with A.(B x C) = A.((B-A) x (C-A)) and the
 *     denominator 4 - (|B-A|^2 + |C-A|^2 + |C-B|^2)/2: no cancellation.
 *   - With C' = cos(phi) A + sin(phi) T (T the unit tangent at A towards C),
 *     the same formula gives tan(Omega'/2) = t P / (K + t bT), where
 *     t = tan(phi/2), P = A.(B x T), bT = B.T, K = 1 + A.B.  So the arc
 *     length phi whose sub-triangle has area Omega' = u1 Omega solves a
 *     linear equation: t = sin(psi) K / (P cos(psi) - sin(psi) bT), with
 *     psi = Omega'/2, and sin(phi), 1 - cos(phi) follow rationally from t.
 *   - The arc from B to C' is sampled through its chord d = |C' - B|
 *     (accurate, from differences): 1 - cos(theta) = u2 d^2/2 exactly as
 *     Arvo's step, sin(theta) = sqrt(u2) d sqrt(1 - u2 d^2/4), and the
 *     direction is cos(theta) B + sin(theta) W with W built from C' - B.
 * Nothing here takes acos or sqrt(1 - x^2) of an x near 1; the only
 * transcendental per sample is sincos(psi).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#define _GNU_SOURCE
#include "internal.h"

/* fan layout */
enum {
    F_A = 0,     /* unit vertex A (3) */
    F_B = 3,     /* unit vertex B (3) */
    F_T = 6,     /* unit tangent at A towards C (3) */
    F_DAB = 9,   /* B - A, accurate (3) */
    F_P = 12,    /* A.(B x T) > 0 */
    F_BT = 13,   /* B.T */
    F_K = 14,    /* 1 + A.B */
    F_TMAX = 15, /* tan(arc AC / 2) */
    F_OMEGA = 16 /* solid angle */
};

void mcest_sincos(double x, double *s, double *c)
{
    sincos(x, s, c);
}

/* b/|b| - a/|a| from a, b and e = b - a, without cancellation. */
static void unit_diff(const double *a, double la, const double *b, double lb, const double *e,
                      double *out)
{
    double apb[3] = {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
    double dl = -dot3(e, apb) / (la + lb); /* la - lb */
    double k = dl / (la * lb);
    for (int i = 0; i < 3; i++)
        out[i] = e[i] / lb + a[i] * k;
}

double mcest_sph_tri_prepare(const double *a, const double *b, const double *c,
                             const double *e_ab, const double *e_ac, double *fan)
{
    for (int i = 0; i < 20; i++)
        fan[i] = 0.0;
    double la = norm3(a), lb = norm3(b), lc = norm3(c);
    if (!(la > 0.0) || !(lb > 0.0) || !(lc > 0.0))
        return 0.0;
    double A[3], B[3], dab[3], dac[3];
    for (int i = 0; i < 3; i++) {
        A[i] = a[i] / la;
        B[i] = b[i] / lb;
    }
    unit_diff(a, la, b, lb, e_ab, dab);
    unit_diff(a, la, c, lc, e_ac, dac);
    double x[3];
    cross3(dab, dac, x);
    double triple = dot3(A, x);
    if (triple < 0.0) { /* orient A, B, C counter-clockwise: swap B and C */
        double tmp[3];
        for (int i = 0; i < 3; i++) {
            tmp[i] = dab[i];
            dab[i] = dac[i];
            dac[i] = tmp[i];
            B[i] = c[i] / lc;
        }
        triple = -triple;
    }
    if (!(triple > 0.0))
        return 0.0;
    double dbc[3] = {dac[0] - dab[0], dac[1] - dab[1], dac[2] - dab[2]};
    double sab = dot3(dab, dab), sac = dot3(dac, dac), sbc = dot3(dbc, dbc);
    double den = 4.0 - 0.5 * (sab + sac + sbc);
    double omega = 2.0 * atan2(triple, den);
    /* T = normalise(C - (C.A) A) = normalise(dac + (|dac|^2/2) A) */
    double T[3];
    for (int i = 0; i < 3; i++)
        T[i] = dac[i] + 0.5 * sac * A[i];
    double lt = norm3(T);
    for (int i = 0; i < 3; i++)
        T[i] /= lt;
    double axd[3];
    cross3(A, dab, axd);
    double P = dot3(T, axd);
    double bT = dot3(dab, T);
    double K = 2.0 - 0.5 * sab;
    double h = 0.5 * sqrt(sac); /* sin(arc AC / 2) */
    double tmax = h / sqrt((1.0 - h) * (1.0 + h));
    if (!(P > 0.0) || !(omega > 0.0))
        return 0.0;
    for (int i = 0; i < 3; i++) {
        fan[F_A + i] = A[i];
        fan[F_B + i] = B[i];
        fan[F_T + i] = T[i];
        fan[F_DAB + i] = dab[i];
    }
    fan[F_P] = P;
    fan[F_BT] = bT;
    fan[F_K] = K;
    fan[F_TMAX] = tmax;
    fan[F_OMEGA] = omega;
    return omega;
}

/* C' - B and the chord's square for the sub-area psi = Omega'/2. */
static inline double sub_vertex(const double *fan, double psi, double *dbc)
{
    double s, c;
    mcest_sincos(psi, &s, &c);
    double num = s * fan[F_K];
    double den = fan[F_P] * c - s * fan[F_BT];
    /* The exact solution lies in [0, tmax]; rounding may push it past. */
    if (!(den > 0.0) || num > fan[F_TMAX] * den) {
        num = fan[F_TMAX];
        den = 1.0;
    }
    double r2 = num * num + den * den;
    double sinphi = 2.0 * num * den / r2;
    double omc = 2.0 * num * num / r2; /* 1 - cos(phi) */
    for (int i = 0; i < 3; i++)
        dbc[i] = -fan[F_DAB + i] - omc * fan[F_A + i] + sinphi * fan[F_T + i];
    return dot3(dbc, dbc);
}

static inline void arc_coefs(double d2, double u2, double *cb, double *cw)
{
    double q = 1.0 - 0.25 * d2; /* cos^2(theta_max / 2) */
    *cb = 1.0 - 0.5 * u2 * d2;
    *cw = q > 0.0 ? sqrt(u2 * (1.0 - 0.25 * u2 * d2) / q) : 0.0;
}

double mcest_sph_tri_sample_z(const double *fan, double psi, double u2)
{
    double dbc[3];
    double d2 = sub_vertex(fan, psi, dbc);
    double cb, cw;
    arc_coefs(d2, u2, &cb, &cw);
    double bz = fan[F_B + 2];
    /* w = cb B + cw (dbc + d2/2 B) */
    return cb * bz + cw * (dbc[2] + 0.5 * d2 * bz);
}

void mcest_sph_tri_sample(const double *fan, double psi, double u2, double *w)
{
    double dbc[3];
    double d2 = sub_vertex(fan, psi, dbc);
    double cb, cw;
    arc_coefs(d2, u2, &cb, &cw);
    for (int i = 0; i < 3; i++)
        w[i] = cb * fan[F_B + i] + cw * (dbc[i] + 0.5 * d2 * fan[F_B + i]);
}
