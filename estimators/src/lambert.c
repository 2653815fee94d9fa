/*
 * lambert.c - the scene's frame, clipping to the receiver's hemisphere, and
 * Lambert's formula for the irradiance from a polygon (section 3.1, eq. 5).
 *
 * The visible polygon (at most 4 vertices) is kept in barycentric
 * coordinates of the triangle, so that any of its edges is
 * d_lambda1 * e01 + d_lambda2 * e02 with e01, e02 the triangle's edges
 * computed from the input coordinates: a polygon far from the receiver
 * keeps its shape to full relative precision, which differences of
 * translated vertices would lose.
 *
 * Lambert's formula, E = (L/2) |sum_k Theta_k n.gamma_k|, has terms of the
 * size of the polygon's angular extent (edge/distance) that cancel down to
 * its solid angle (edge/distance)^2: written naively it loses a factor
 * distance/edge, i.e. 1e-11 relative error at a solid angle of 1e-10,
 * 1e-10 at 1e-12 (and acos-based angles lose far more: sqrt(eps) in each
 * Theta_k).  With c_k = q_k x e_k (accurate: an edge, not a difference of
 * vertices) and a_k = |q_k|, each term is c_k.z h_k / (a_k a_{k+1}) with
 * h_k = Theta_k / sin(Theta_k), and
 *   sum = (1/R^2) sum c_k.z                    (exact: twice the projected
 *                                              area, from e01 x e02)
 *       + sum c_k.z (1/(a_k a_{k+1}) - 1/R^2)  (differences of distances,
 *                                              from edges: no cancellation)
 *       + sum c_k.z (h_k - 1)/(a_k a_{k+1})    (h_k - 1 ~ Theta^2/6, by
 *                                              series where small),
 * R = a_0, every term of the size of the result.  Used when the polygon is
 * small as seen from the receiver (all Theta_k <= 0.5, distances within
 * 1.5x); otherwise the direct sum has no cancellation to fear.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

/* theta - sin(theta) for 0 <= theta <= 0.5, by its series (relative error
 * ~1e-18 at 0.5). */
static double theta_minus_sin(double t)
{
    double t2 = t * t;
    double s = 1.0 / 355687428096000.0;
    s = 1.0 / 1307674368000.0 - t2 * s;
    s = 1.0 / 6227020800.0 - t2 * s;
    s = 1.0 / 39916800.0 - t2 * s;
    s = 1.0 / 362880.0 - t2 * s;
    s = 1.0 / 5040.0 - t2 * s;
    s = 1.0 / 120.0 - t2 * s;
    s = 1.0 / 6.0 - t2 * s;
    return t * t2 * s;
}

typedef struct {
    int m;
    double lam[4][2]; /* barycentric (lambda1, lambda2): q = v0 + l1 e01 + l2 e02 */
    double q[4][3];
} polygon;

static void poly_edge(const polygon *p, int i, int j, const double *e01, const double *e02,
                      double *e)
{
    double d1 = p->lam[j][0] - p->lam[i][0], d2 = p->lam[j][1] - p->lam[i][1];
    for (int k = 0; k < 3; k++)
        e[k] = d1 * e01[k] + d2 * e02[k];
}

/* Clips the triangle to z >= 0 (Sutherland-Hodgman against one plane). */
static void clip_upper(const double v[3][3], const double *e01, const double *e02, polygon *out)
{
    static const double tri_lam[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    out->m = 0;
    for (int k = 0; k < 3; k++) {
        int k1 = (k + 1) % 3;
        double za = v[k][2], zb = v[k1][2];
        if (za >= 0.0) {
            out->lam[out->m][0] = tri_lam[k][0];
            out->lam[out->m][1] = tri_lam[k][1];
            for (int i = 0; i < 3; i++)
                out->q[out->m][i] = v[k][i];
            out->m++;
        }
        if ((za >= 0.0) != (zb >= 0.0) && za != zb) {
            double t = za / (za - zb);
            if (t > 0.0 && t < 1.0) {
                double l1 = tri_lam[k][0] + t * (tri_lam[k1][0] - tri_lam[k][0]);
                double l2 = tri_lam[k][1] + t * (tri_lam[k1][1] - tri_lam[k][1]);
                out->lam[out->m][0] = l1;
                out->lam[out->m][1] = l2;
                for (int i = 0; i < 3; i++)
                    out->q[out->m][i] = v[0][i] + l1 * e01[i] + l2 * e02[i];
                out->q[out->m][2] = 0.0; /* on the horizon by construction */
                out->m++;
            }
        }
    }
    if (out->m < 3)
        out->m = 0;
}

/* (1/2) sum_k Theta_k gamma_k.z over the polygon: the signed projected
 * solid angle (its sign is the polygon's orientation). */
static double lambert_sum(const polygon *p, const double *e01, const double *e02)
{
    int m = p->m;
    double c[4][3], a[4], th[4], s[4];
    double thmax = 0.0, amin = INFINITY, amax = 0.0;
    for (int k = 0; k < m; k++) {
        int k1 = (k + 1) % m;
        double e[3];
        poly_edge(p, k, k1, e01, e02, e);
        cross3(p->q[k], e, c[k]);
        s[k] = norm3(c[k]);
        a[k] = norm3(p->q[k]);
        double d = dot3(p->q[k], p->q[k]) + dot3(p->q[k], e);
        th[k] = atan2(s[k], d);
        thmax = fmax(thmax, th[k]);
        amin = fmin(amin, a[k]);
        amax = fmax(amax, a[k]);
    }
    if (thmax <= 0.5 && amax <= 1.5 * amin) {
        /* Rearranged sum (see the file's comment). */
        double x[3];
        cross3(e01, e02, x);
        double det = 0.0;
        for (int j = 1; j + 1 < m; j++) {
            double d1a = p->lam[j][0] - p->lam[0][0], d2a = p->lam[j][1] - p->lam[0][1];
            double d1b = p->lam[j + 1][0] - p->lam[0][0], d2b = p->lam[j + 1][1] - p->lam[0][1];
            det += d1a * d2b - d2a * d1b;
        }
        double R2 = a[0] * a[0];
        double t1 = det * x[2] / R2;
        double dd[4]; /* a_k - a_0 */
        dd[0] = 0.0;
        for (int k = 1; k < m; k++) {
            double e[3], sum[3];
            poly_edge(p, 0, k, e01, e02, e);
            for (int i = 0; i < 3; i++)
                sum[i] = p->q[k][i] + p->q[0][i];
            dd[k] = dot3(e, sum) / (a[k] + a[0]);
        }
        double t2 = 0.0, t3 = 0.0;
        for (int k = 0; k < m; k++) {
            int k1 = (k + 1) % m;
            double Pk = a[k] * a[k1];
            double dP = a[0] * (dd[k] + dd[k1]) + dd[k] * dd[k1]; /* Pk - R2 */
            t2 += c[k][2] * (-dP / (R2 * Pk));
            if (s[k] > 0.0) {
                double sn = s[k] / Pk; /* sin(theta) */
                t3 += c[k][2] * (theta_minus_sin(th[k]) / sn) / Pk;
            }
        }
        return 0.5 * (t1 + t2 + t3);
    }
    double sum = 0.0;
    for (int k = 0; k < m; k++)
        if (s[k] > 0.0)
            sum += th[k] * (c[k][2] / s[k]);
    return 0.5 * sum;
}

/* ---- the plan ---------------------------------------------------------- */

/* An orthonormal basis with n as third vector (Duff et al. 2017). */
static void frame(const double *n, double *t, double *b)
{
    double sign = copysign(1.0, n[2]);
    double a = -1.0 / (sign + n[2]);
    double c = n[0] * n[1] * a;
    t[0] = 1.0 + sign * n[0] * n[0] * a;
    t[1] = sign * c;
    t[2] = -sign * n[0];
    b[0] = c;
    b[1] = sign + n[1] * n[1] * a;
    b[2] = -n[1];
}

static int scene_valid(const mcest_scene *s)
{
    for (int i = 0; i < 9; i++)
        if (!isfinite(s->triangle[i]))
            return 0;
    if (!finite3(s->point) || !finite3(s->normal) || !isfinite(s->radiance) || s->radiance < 0.0)
        return 0;
    double nn = norm3_scaled(s->normal);
    return nn > 0.0 && isfinite(nn);
}

int mcest_irradiance_plan_init(const mcest_scene *scene, mcest_irradiance_plan *plan)
{
    if (!scene || !plan || !scene_valid(scene))
        return MCEST_EINVAL;
    mcest_irradiance_plan P;
    double *raw = (double *)&P;
    for (size_t i = 0; i < sizeof P / sizeof(double); i++)
        raw[i] = 0.0;
    P.version = MCEST_IRRADIANCE_PLAN_VERSION;
    P.radiance = scene->radiance;

    double n[3], t[3], b[3];
    /* normalise in two steps: by the largest component, then by the length */
    double big = fmax(fabs(scene->normal[0]), fmax(fabs(scene->normal[1]), fabs(scene->normal[2])));
    for (int i = 0; i < 3; i++)
        n[i] = scene->normal[i] / big;
    double ln = norm3(n);
    for (int i = 0; i < 3; i++)
        n[i] /= ln;
    frame(n, t, b);
    const double *p = scene->triangle;
    /* Translate first (p_k - x), then rotate.  Edges from the inputs. */
    for (int k = 0; k < 3; k++) {
        double d[3] = {p[3 * k] - scene->point[0], p[3 * k + 1] - scene->point[1],
                       p[3 * k + 2] - scene->point[2]};
        P.v[k][0] = dot3(d, t);
        P.v[k][1] = dot3(d, b);
        P.v[k][2] = dot3(d, n);
    }
    double d01[3] = {p[3] - p[0], p[4] - p[1], p[5] - p[2]};
    double d02[3] = {p[6] - p[0], p[7] - p[1], p[8] - p[2]};
    P.e01[0] = dot3(d01, t), P.e01[1] = dot3(d01, b), P.e01[2] = dot3(d01, n);
    P.e02[0] = dot3(d02, t), P.e02[1] = dot3(d02, b), P.e02[2] = dot3(d02, n);

    double x[3];
    cross3(P.e01, P.e02, x);
    double lx = norm3(x);
    double triple = dot3(P.v[0], x);
    P.area = 0.5 * lx;
    P.height = lx > 0.0 ? fabs(triple) / lx : 0.0;
    P.a_coef = scene->radiance * 0.5 * fabs(triple);
    P.la_coef = scene->radiance * P.area;

    if (lx > 0.0 && triple != 0.0) {
        /* Inward normals of the cone through the triangle: w is inside
         * iff w . edge_n[k] >= 0 for all k. */
        double sign = triple > 0.0 ? 1.0 : -1.0;
        double e12[3], e20[3];
        for (int i = 0; i < 3; i++) {
            e12[i] = P.e02[i] - P.e01[i];
            e20[i] = -P.e02[i];
        }
        cross3(P.v[0], P.e01, P.edge_n[0]);
        cross3(P.v[1], e12, P.edge_n[1]);
        cross3(P.v[2], e20, P.edge_n[2]);
        for (int k = 0; k < 3; k++)
            for (int i = 0; i < 3; i++)
                P.edge_n[k][i] *= sign;

        polygon poly;
        clip_upper((const double(*)[3])P.v, P.e01, P.e02, &poly);
        P.n_poly = poly.m;
        P.straddles = (P.v[0][2] < 0.0 || P.v[1][2] < 0.0 || P.v[2][2] < 0.0) && poly.m > 0;
        if (poly.m >= 3) {
            double psa = fabs(lambert_sum(&poly, P.e01, P.e02));
            P.proj_solid_angle = psa;
            P.exact = scene->radiance * psa;
            /* S: a fan of spherical triangles (q0, q_j, q_j+1). */
            int nf = 0;
            double omega = 0.0;
            for (int j = 1; j + 1 < poly.m; j++) {
                double eab[3], eac[3];
                poly_edge(&poly, 0, j, P.e01, P.e02, eab);
                poly_edge(&poly, 0, j + 1, P.e01, P.e02, eac);
                double o = mcest_sph_tri_prepare(poly.q[0], poly.q[j], poly.q[j + 1], eab, eac,
                                                 P.fan[nf]);
                if (o > 0.0) {
                    omega += o;
                    nf++;
                }
            }
            P.n_fan = nf;
            P.solid_angle = omega;
        }
    }
    *plan = P;
    return MCEST_OK;
}

int mcest_irradiance_exact(const mcest_scene *scene, double *E)
{
    if (!E)
        return MCEST_EINVAL;
    mcest_irradiance_plan P;
    int st = mcest_irradiance_plan_init(scene, &P);
    if (st == MCEST_OK)
        *E = P.exact;
    return st;
}
