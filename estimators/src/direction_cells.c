/*
 * direction_cells.c - cells of the sphere of (nearly) equal probability
 * under a BRDF sampler's density, and the exact probability of each by
 * cubature, for chi-squared goodness-of-fit tests of the sampler
 * (documented in mcest.h).
 *
 * Where: Lambert's equal-area square of the Morton keys, s = (1 - z)/2,
 * t = phi/(2 pi), dω = 4 pi ds dt, so the density in the square is
 * 4 pi p(w(s, t)) and a cell is a rectangle.  The cells are the leaves of a
 * k-d tree of the given depth: the node at depth d splits its rectangle
 * across s (d even) or t (d odd) where half its probability lies on each
 * side (bisection on a cheap cubature: the split need not be exact, the
 * probabilities are computed afterwards, accurately, per cell).
 *
 * Accuracy: each cell's probability comes from adaptive cubature
 * (7x7 Gauss-Legendre against the nested 4x4 estimate, splitting the worst
 * rectangle in four), to max(rel_tol * P_cell, 1e-3 * rel_tol / cells)
 * where reachable; the density's singular point at wi = -wo is handled
 * by the Duffy transform (integrate_rect).
 * A cell straddling the horizon s = 1/2 is integrated as two rectangles,
 * because the cosine-weighted part of a mixture jumps to 0 there.  The sum
 * of the probabilities is 1 to within the errors reported (tested to 1e-7
 * with rel_tol 1e-8), a check of the claimed density's normalisation too.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#define CELLS_NODES 2000 /* rectangles per integral: 2000 * 48 bytes of stack */

static const double GL7_X[7] = {-0.9491079123427585, -0.7415311855993945, -0.4058451513773972, 0.0,
                                0.4058451513773972, 0.7415311855993945, 0.9491079123427585};
static const double GL7_W[7] = {0.1294849661688697, 0.2797053914892767, 0.3818300505051189,
                                0.4179591836734694, 0.3818300505051189, 0.2797053914892767,
                                0.1294849661688697};
static const double GL4_X[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                0.8611363115940526};
static const double GL4_W[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                0.3478548451374538};

/* 4 pi p(w(s, t)): the density in the equal-area square. */
static double square_pdf(const mcest_brdf_plan *p, double s, double t)
{
    double z = 1.0 - 2.0 * s, r = 2.0 * sqrt(fmax(0.0, s * (1.0 - s)));
    double sn, cs;
    mcest_sincos(2.0 * M_PI * t, &sn, &cs);
    double w[3] = {r * cs, r * sn, z};
    return 4.0 * M_PI * mcest_plan_pdf(p, w);
}

typedef struct {
    double s0, t0, ds, dt, q, e;
} rect;

/* What is integrated over a rectangle of the (x, y) plane: the density in
 * the equal-area square itself (duffy == 0), or its Duffy transform over
 * the unit square (duffy == 1): the triangle (c, a, b) as
 * (s, t) = c + x (a - c) + x y (b - a), Jacobian x |det(a - c, b - a)|,
 * which cancels a 1/r singularity at the corner c. */
typedef struct {
    const mcest_brdf_plan *p;
    int duffy;
    double c[2], e1[2], e2[2], jac; /* e1 = a - c, e2 = b - a */
} integrand;

static inline double eval(const integrand *f, double x, double y)
{
    if (!f->duffy)
        return square_pdf(f->p, x, y);
    double s = f->c[0] + x * f->e1[0] + x * y * f->e2[0], t = f->c[1] + x * f->e1[1] + x * y * f->e2[1];
    return square_pdf(f->p, s, t) * x * f->jac;
}

static void rect_rule(const integrand *f, rect *r)
{
    double q7 = 0.0, q4 = 0.0;
    double hs = 0.5 * r->ds, ht = 0.5 * r->dt, cs = r->s0 + hs, ct = r->t0 + ht;
    for (int i = 0; i < 7; i++)
        for (int j = 0; j < 7; j++)
            q7 += GL7_W[i] * GL7_W[j] * eval(f, cs + hs * GL7_X[i], ct + ht * GL7_X[j]);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            q4 += GL4_W[i] * GL4_W[j] * eval(f, cs + hs * GL4_X[i], ct + ht * GL4_X[j]);
    r->q = q7 * hs * ht;
    r->e = fabs(q7 - q4) * hs * ht;
}

/* Global adaptive cubature of f over [x0,x1] x [y0,y1] to max(rel_tol |I|,
 * abs_tol): split the rectangle of largest error estimate in four.  No
 * allocation: a fixed array of rectangles on the stack. */
static double adapt(const integrand *f, double x0, double x1, double y0, double y1, double rel_tol, double abs_tol,
                    double *err)
{
    rect nodes[CELLS_NODES];
    int m = 0;
    if (!(x1 > x0) || !(y1 > y0)) {
        *err = 0.0;
        return 0.0;
    }
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            rect r = {x0 + 0.5 * i * (x1 - x0), y0 + 0.5 * j * (y1 - y0), 0.5 * (x1 - x0), 0.5 * (y1 - y0), 0, 0};
            rect_rule(f, &r);
            nodes[m++] = r;
        }
    for (;;) {
        double q = 0.0, e = 0.0;
        int worst = 0;
        for (int k = 0; k < m; k++) {
            q += nodes[k].q;
            e += nodes[k].e;
            if (nodes[k].e > nodes[worst].e)
                worst = k;
        }
        if (e <= fmax(rel_tol * fabs(q), abs_tol) || e == 0.0 || m + 3 > CELLS_NODES) {
            *err = e;
            return q;
        }
        rect w = nodes[worst];
        double hs = 0.5 * w.ds, ht = 0.5 * w.dt;
        rect c[4] = {{w.s0, w.t0, hs, ht, 0, 0},
                     {w.s0 + hs, w.t0, hs, ht, 0, 0},
                     {w.s0, w.t0 + ht, hs, ht, 0, 0},
                     {w.s0 + hs, w.t0 + ht, hs, ht, 0, 0}};
        for (int i = 0; i < 4; i++)
            rect_rule(f, &c[i]);
        nodes[worst] = c[0];
        nodes[m++] = c[1];
        nodes[m++] = c[2];
        nodes[m++] = c[3];
    }
}

/* The integral over the triangle (c, a, b) by the Duffy transform. */
static double duffy(const mcest_brdf_plan *p, const double *c, const double *a, const double *b, double rel_tol,
                    double abs_tol, double *err)
{
    integrand f = {p, 1, {c[0], c[1]}, {a[0] - c[0], a[1] - c[1]}, {b[0] - a[0], b[1] - a[1]}, 0.0};
    f.jac = fabs(f.e1[0] * f.e2[1] - f.e1[1] * f.e2[0]);
    if (!(f.jac > 0.0)) {
        *err = 0.0;
        return 0.0;
    }
    return adapt(&f, 0.0, 1.0, 0.0, 1.0, rel_tol, abs_tol, err);
}

/* Integral of the density over [s0,s1] x [t0,t1] (not straddling the
 * horizon) to max(rel_tol |I|, abs_tol); *err its estimated error.
 * A half-vector sampler's density is singular at wi = -wo, where h becomes
 * perpendicular to wo: with wi = -wo + d, wo.h = |d|/2, so p = p_h(h) /
 * (2 |d|), and h = d/|d| flips where d_z changes sign, so the singular
 * point also carries a jump.  Integrable, but a plain cubature's error
 * estimate misses it (one cell of Ward's 1024 lost 8% of its mass, and a
 * cell whose edge passed 1e-9 from the point lost 6%).  A rectangle holding
 * that point, or near it, is cut at the point (or the nearest point of the
 * rectangle) into eight triangles fanning around it, and each is
 * integrated by the Duffy transform, whose Jacobian cancels the 1/|d|; the
 * jump lies along s = const, the edges of two of the triangles. */
static double integrate_rect(const mcest_brdf_plan *p, double s0, double s1, double t0, double t1,
                             double rel_tol, double abs_tol, double *err)
{
    double mw[3] = {-p->wo[0], -p->wo[1], -p->wo[2]}, sing[2] = {-10.0, -10.0};
    if (p->mix < 1.0)
        mcest_direction_square(mw, 1, sing);
    /* the fan's apex: the singular point, or the point of the rectangle
     * nearest to it when it lies just outside (within a tenth of the rectangle's size;
     * 1e-3 missed a point 4e-7 outside, the whole size left 2e-7 at a kink):
     * there the Jacobian x bounds x / |x e - d| by 1 and leaves only a kink */
    const double c[2] = {fmin(fmax(sing[0], s0), s1), fmin(fmax(sing[1], t0), t1)};
    if (!(fabs(c[0] - sing[0]) <= 0.1 * (s1 - s0) && fabs(c[1] - sing[1]) <= 0.1 * (t1 - t0))) {
        integrand f = {p, 0, {0, 0}, {0, 0}, {0, 0}, 0.0};
        return adapt(&f, s0, s1, t0, t1, rel_tol, abs_tol, err);
    }
    const double corner[4][2] = {{s0, t0}, {s1, t0}, {s1, t1}, {s0, t1}};
    double total = 0.0, etot = 0.0;
    for (int k = 0; k < 4; k++) {
        /* the triangle c, corner k, the edge point between corners k and k+1 at c's height or abscissa,
         * and from there to corner k+1: eight triangles fanning around c */
        const double *a = corner[k], *b = corner[(k + 1) % 4];
        double mid[2] = {(k % 2 == 0) ? c[0] : a[0], (k % 2 == 0) ? a[1] : c[1]};
        double e1, e2;
        total += duffy(p, c, a, mid, rel_tol, 0.125 * abs_tol, &e1);
        total += duffy(p, c, mid, b, rel_tol, 0.125 * abs_tol, &e2);
        etot += e1 + e2;
    }
    *err = etot;
    return total;
}

/* The same, split at the horizon s = 1/2, where the cosine-weighted part of
 * a mixture jumps to 0. */
static double integrate(const mcest_brdf_plan *p, double s0, double s1, double t0, double t1,
                        double rel_tol, double abs_tol, double *err)
{
    if (s0 < 0.5 && s1 > 0.5) {
        double e1, e2;
        double a = integrate_rect(p, s0, 0.5, t0, t1, rel_tol, 0.5 * abs_tol, &e1);
        double b = integrate_rect(p, 0.5, s1, t0, t1, rel_tol, 0.5 * abs_tol, &e2);
        *err = e1 + e2;
        return a + b;
    }
    return integrate_rect(p, s0, s1, t0, t1, rel_tol, abs_tol, err);
}

/* ---- the splits, from a pilot of quasi-random directions --------------------
 * The splits need not be exact medians (the probabilities are computed
 * afterwards, accurately), but they must find the lobe: a cubature of the
 * whole sphere can miss a lobe 0.05 rad wide entirely.  So the tree is
 * built on M = 2^(depth + 8) directions drawn by the plan's own (correct)
 * sampler from a deterministic rank-1 lattice in its primary cube (the R3
 * sequence of Roberts 2018: u_j = frac(1/2 + k / phi^j), phi^4 = phi + 1),
 * as a k-d tree of medians: 256 pilot directions per cell. */
static void pilot(const mcest_brdf_plan *p, size_t m, double *st)
{
    const double phi = 1.2207440846057596;
    const double a1 = 1.0 / phi, a2 = a1 / phi, a3 = a2 / phi;
    for (size_t k = 0; k < m; k++) {
        double u[3] = {fmod(0.5 + (double)k * a1, 1.0), fmod(0.5 + (double)k * a2, 1.0),
                       fmod(0.5 + (double)k * a3, 1.0)};
        uint64_t r[3];
        for (int j = 0; j < 3; j++)
            r[j] = (uint64_t)(u[j] * 0x1p53) << 11; /* u01(r[j]) == u[j] */
        double w[3];
        mcest_plan_propose(p, r, w);
        if (mcest_direction_square(w, 1, st + 2 * k)) { /* a degenerate draw: the pole */
            st[2 * k] = 0.0;
            st[2 * k + 1] = 0.0;
        }
    }
}

/* Quickselect on (s, t) pairs by coordinate `axis`: afterwards pts[0..k)
 * <= pts[k] <= pts[k+1..n) in that coordinate. */
static void select_k(double *pts, size_t n, size_t k, int axis)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        double pivot = pts[2 * (lo + (hi - lo) / 2) + axis];
        size_t i = lo, j = hi;
        while (i <= j) {
            while (pts[2 * i + axis] < pivot)
                i++;
            while (pts[2 * j + axis] > pivot)
                j--;
            if (i <= j) {
                double a = pts[2 * i], b = pts[2 * i + 1];
                pts[2 * i] = pts[2 * j], pts[2 * i + 1] = pts[2 * j + 1];
                pts[2 * j] = a, pts[2 * j + 1] = b;
                i++;
                if (j == 0)
                    break;
                j--;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return;
    }
}

size_t mcest_cells_work_size(int depth)
{
    if (depth < 1 || depth > MCEST_CELLS_MAX_DEPTH)
        return 0;
    return (size_t)2 << (depth + 8);
}

int mcest_brdf_cells(const mcest_brdf_plan *plan, int depth, double rel_tol, double *work, double *split,
                     double *prob, double *err)
{
    if (!mcest_plan_ok(plan) || depth < 1 || depth > MCEST_CELLS_MAX_DEPTH || !work || !split || !prob ||
        !(rel_tol >= 1e-12 && rel_tol <= 1e-2))
        return MCEST_EINVAL;
    const size_t cells = (size_t)1 << depth, inner = cells - 1, m = (size_t)1 << (depth + 8);
    pilot(plan, m, work);
    /* node i at depth d (heap order) holds the pilot points of block j = i - (2^d - 1) */
    for (size_t i = 0; i < inner; i++) {
        int d = 0;
        while (((i + 1) >> (d + 1)) != 0)
            d++;
        size_t j = i - (((size_t)1 << d) - 1), len = m >> d, half = len / 2;
        double *pts = work + 2 * j * len;
        int axis = d % 2;
        select_k(pts, len, half, axis);
        /* the largest of the lower half */
        double below = pts[axis];
        for (size_t q = 1; q < half; q++)
            below = fmax(below, pts[2 * q + axis]);
        split[i] = 0.5 * (below + pts[2 * half + axis]);
    }
    int status = MCEST_OK;
    double total_err = 0.0;
    const double abs_tol = 1e-3 * rel_tol / (double)cells;
    for (size_t c = 0; c < cells; c++) {
        double b[4], e;
        mcest_cells_bounds_of(split, depth, inner + c, b);
        prob[c] = integrate(plan, b[0], b[1], b[2], b[3], rel_tol, abs_tol, &e);
        total_err += e;
        if (!isfinite(prob[c]))
            return MCEST_ENUMERIC;
    }
    /* Per cell the target is not always reachable (2000 rectangles), so the
     * status judges the total. */
    if (total_err > MCEST_CELLS_MAX_ERROR)
        status = MCEST_ENUMERIC;
    if (err)
        *err = total_err;
    return status;
}

/* Rectangle of heap node `node` (0 the root) from the splits above it;
 * returns the node's depth. */
int mcest_cells_bounds_of(const double *split, int depth, size_t node, double *b)
{
    b[0] = 0.0, b[1] = 1.0, b[2] = 0.0, b[3] = 1.0;
    /* the path from the root: the bits of node + 1 below its leading one */
    size_t id = node + 1;
    int d = 0;
    while ((id >> (d + 1)) != 0)
        d++;
    (void)depth;
    size_t cur = 0;
    for (int level = d - 1; level >= 0; level--) {
        int right = (int)((id >> level) & 1u);
        int axis = (d - 1 - level) % 2;
        double x = split[cur];
        if (right)
            b[axis == 0 ? 0 : 2] = x;
        else
            b[axis == 0 ? 1 : 3] = x;
        cur = 2 * cur + 1 + (size_t)right;
    }
    return d;
}

int mcest_cells_bounds(const double *split, int depth, double *bounds)
{
    if (!split || !bounds || depth < 1 || depth > MCEST_CELLS_MAX_DEPTH)
        return MCEST_EINVAL;
    const size_t cells = (size_t)1 << depth;
    for (size_t c = 0; c < cells; c++)
        mcest_cells_bounds_of(split, depth, cells - 1 + c, bounds + 4 * c);
    return MCEST_OK;
}

int mcest_cells_locate(const double *split, int depth, const double *w, size_t n, uint32_t *cell)
{
    if (!split || depth < 1 || depth > MCEST_CELLS_MAX_DEPTH || (n > 0 && (!w || !cell)))
        return MCEST_EINVAL;
    for (size_t k = 0; k < n; k++) {
        double st[2];
        if (mcest_direction_square(w + 3 * k, 1, st))
            return MCEST_EINVAL;
        size_t node = 0;
        for (int d = 0; d < depth; d++)
            node = 2 * node + 1 + (size_t)(st[d % 2] >= split[node]);
        cell[k] = (uint32_t)(node - (((size_t)1 << depth) - 1));
    }
    return MCEST_OK;
}

int mcest_cells_count(const double *split, int depth, const double *w, size_t n, double *counts)
{
    if (!split || depth < 1 || depth > MCEST_CELLS_MAX_DEPTH || !counts || (n > 0 && !w))
        return MCEST_EINVAL;
    const size_t cells = (size_t)1 << depth;
    for (size_t c = 0; c < cells; c++)
        counts[c] = 0.0;
    for (size_t k = 0; k < n; k++) {
        uint32_t c;
        int st = mcest_cells_locate(split, depth, w + 3 * k, 1, &c);
        if (st)
            return st;
        counts[c] += 1.0;
    }
    return MCEST_OK;
}
