/*
 * check_cells.c - cells of nearly equal probability for the renderer
 * checks, and the probability of each under the renderer's pdf (check.h).
 *
 * The cells are the leaves of a k-d tree over the domain's equal-area
 * square, split at medians of a pilot sample drawn by the sampler under
 * test.  Cells drawn from the sampler are fine whatever the sampler does:
 * the pilot is independent of the tested sample, and the expected counts
 * come from pdf(), not from the pilot.  Following the pilot puts the cells
 * where the lobe is, however narrow (a fixed grid would spend its cells
 * where nothing is sampled, which is what makes a binned test of a sharp
 * lobe need millions of samples).
 *
 * Each cell's probability is then integrated by adaptive cubature:
 * Genz and Malik's degree-7 rule on a rectangle, 17 points, with its
 * embedded degree-5 rule for the error (J. Comput. Appl. Math. 6, 1980;
 * the weights below for dimension 2, normalised to sum to 1).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "check.h"

#include <float.h>

/* ---- the tree ------------------------------------------------------------ */

size_t mcstat__tree_max_cells(uint64_t m, int leaf)
{
    return (size_t)(3 * (m / (uint64_t)leaf) + 4);
}

static void swap_pair(double *st, uint64_t i, uint64_t j)
{
    double a = st[2 * i], b = st[2 * i + 1];
    st[2 * i] = st[2 * j];
    st[2 * i + 1] = st[2 * j + 1];
    st[2 * j] = a;
    st[2 * j + 1] = b;
}

/* Quickselect with three-way partitions (ties at the pivot cost nothing:
 * a pilot may hold many equal coordinates): afterwards st[2k + axis] is the
 * k-th smallest coordinate, smaller or equal ones before it, larger or
 * equal ones after. */
static void select_pairs(double *st, uint64_t n, uint64_t k, int axis)
{
    uint64_t lo = 0, hi = n; /* [lo, hi) holds position k */
    while (hi - lo > 1) {
        uint64_t mid = lo + (hi - lo) / 2;
        double a = st[2 * lo + axis], b = st[2 * mid + axis], c = st[2 * (hi - 1) + axis];
        double pivot = (a < b) ? ((b < c) ? b : ((a < c) ? c : a)) : ((a < c) ? a : ((b < c) ? c : b));
        /* [lo, lt) < pivot, [lt, i) == pivot, [gt, hi) > pivot */
        uint64_t lt = lo, i = lo, gt = hi;
        while (i < gt) {
            double v = st[2 * i + axis];
            if (v < pivot)
                swap_pair(st, lt++, i++);
            else if (v > pivot)
                swap_pair(st, i, --gt);
            else
                i++;
        }
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else
            return;
    }
}

static int32_t add_leaf(mcstat__tree *tr, int32_t node, const double *st, uint64_t m, double s0, double s1, double t0,
                        double t1)
{
    int32_t c = tr->n_cells++;
    mcstat__cell *cell = &tr->cells[c];
    memset(cell, 0, sizeof *cell);
    cell->p_first = (uint64_t)(st - tr->st) / 2;
    cell->p_count = m;
    cell->s0 = s0;
    cell->s1 = s1;
    cell->t0 = t0;
    cell->t1 = t1;
    tr->nodes[node].left = tr->nodes[node].right = -1;
    tr->nodes[node].cell = c;
    return c;
}

static void build_node(mcstat__tree *tr, const mcstat__domain *d, int32_t node, double *st, uint64_t m,
                       double s0, double s1, double t0, double t1, int depth, int leaf, int horizon)
{
    int have_room = tr->n_nodes + 2 <= tr->max_nodes && tr->n_cells + 2 <= tr->max_cells;
    int axis = -1;
    double split = 0.0;
    uint64_t k = 0;
    if (horizon && have_room) {
        axis = 0;
        split = 0.5;
        for (uint64_t i = 0; i < m; i++)
            if (st[2 * i] < split)
                swap_pair(st, i, k++);
    } else if (10 * m >= 14 * (uint64_t)leaf && depth < 48 && have_room) {
        /* split from 1.4 leaf points: leaves of 0.7..1.4 leaf points, so
         * that their number is within a factor 1.4 of pilot/leaf */
        int first = d->two_d ? (depth & 1) : 0;
        for (int attempt = 0; attempt < (d->two_d ? 2 : 1) && axis < 0; attempt++) {
            int a = first ^ attempt;
            double lo = a ? t0 : s0, hi = a ? t1 : s1;
            k = m / 2;
            select_pairs(st, m, k, a);
            double v = st[2 * k + a];
            /* a split must cut the node into two of positive area; ties at
             * the median (a point mass) leave it a leaf */
            if (v > lo && v < hi) {
                axis = a;
                split = v;
            }
        }
    }
    if (axis < 0) {
        add_leaf(tr, node, st, m, s0, s1, t0, t1);
        return;
    }
    int32_t left = tr->n_nodes++, right = tr->n_nodes++;
    tr->nodes[node].split = split;
    tr->nodes[node].axis = axis;
    tr->nodes[node].left = left;
    tr->nodes[node].right = right;
    tr->nodes[node].cell = -1;
    if (axis == 0) {
        build_node(tr, d, left, st, k, s0, split, t0, t1, depth + 1, leaf, 0);
        build_node(tr, d, right, st + 2 * k, m - k, split, s1, t0, t1, depth + 1, leaf, 0);
    } else {
        build_node(tr, d, left, st, k, s0, s1, t0, split, depth + 1, leaf, 0);
        build_node(tr, d, right, st + 2 * k, m - k, s0, s1, split, t1, depth + 1, leaf, 0);
    }
}

void mcstat__tree_build(mcstat__tree *tr, const mcstat__domain *d, double *st, uint64_t m, int leaf, int horizon)
{
    tr->n_nodes = 1;
    tr->n_cells = 0;
    tr->st = st;
    tr->n_points = m;
    build_node(tr, d, 0, st, m, 0.0, 1.0, 0.0, 1.0, 0, leaf, horizon);
}

int32_t mcstat__tree_locate(const mcstat__tree *tr, double s, double t)
{
    const mcstat__node *nd = tr->nodes;
    int32_t i = 0;
    while (nd[i].left >= 0)
        i = ((nd[i].axis ? t : s) < nd[i].split) ? nd[i].left : nd[i].right;
    return nd[i].cell;
}

/* ---- cubature ------------------------------------------------------------ */

/* Genz-Malik, d = 2: abscissae (in half-widths) and weights summing to 1. */
#define GM_L2 0.35856858280031809199064515390793749545406372969943 /* sqrt(9/70) */
#define GM_L3 0.94868329805051379959966806332981556011586654179757 /* sqrt(9/10) */
#define GM_L4 0.94868329805051379959966806332981556011586654179757 /* sqrt(9/10) */
#define GM_L5 0.68824720161168529772162873429362352512689535661564 /* sqrt(9/19) */
static const double gm_w[5] = {-3816.0 / 19683.0, 980.0 / 6561.0, 1020.0 / 19683.0, 200.0 / 19683.0,
                               6859.0 / 19683.0 / 4.0};
static const double gm_e[4] = {-971.0 / 729.0, 245.0 / 486.0, 65.0 / 1458.0, 25.0 / 729.0};
#define GM_POINTS 17
/* Past the rule's points, the rectangle's corners (just inside, where a
 * density singular on the domain's edge is still finite): a support whose
 * edge runs along the rectangle's side, in the margin the rule's points
 * never reach, shows there. */
#define GM_PROBE 0.999
#define RECT_POINTS (GM_POINTS + 4)

/* The 17 points of the rule on rect r, then the 4 probes, as offsets in
 * half-widths. */
static const double gm_off[RECT_POINTS][2] = {
    {0, 0},
    {GM_L2, 0}, {-GM_L2, 0}, {0, GM_L2}, {0, -GM_L2},
    {GM_L3, 0}, {-GM_L3, 0}, {0, GM_L3}, {0, -GM_L3},
    {GM_L4, GM_L4}, {GM_L4, -GM_L4}, {-GM_L4, GM_L4}, {-GM_L4, -GM_L4},
    {GM_L5, GM_L5}, {GM_L5, -GM_L5}, {-GM_L5, GM_L5}, {-GM_L5, -GM_L5},
    {GM_PROBE, GM_PROBE}, {GM_PROBE, -GM_PROBE}, {-GM_PROBE, GM_PROBE}, {-GM_PROBE, -GM_PROBE},
};

static void rule(mcstat__rect *r, const double *f, double jacobian, int two_d)
{
    double s2 = f[1] + f[2] + f[3] + f[4], s3 = f[5] + f[6] + f[7] + f[8];
    double s4 = f[9] + f[10] + f[11] + f[12], s5 = f[13] + f[14] + f[15] + f[16];
    double area = (r->s1 - r->s0) * (r->t1 - r->t0) * jacobian;
    double i7 = gm_w[0] * f[0] + gm_w[1] * s2 + gm_w[2] * s3 + gm_w[3] * s4 + gm_w[4] * s5;
    double i5 = gm_e[0] * f[0] + gm_e[1] * s2 + gm_e[2] * s3 + gm_e[3] * s4;
    r->est = area * i7;
    r->err = area * fabs(i7 - i5);
    /* split across the axis of the larger fourth difference */
    double r23 = (GM_L2 * GM_L2) / (GM_L3 * GM_L3);
    double ds = fabs(f[1] + f[2] - 2 * f[0] - r23 * (f[5] + f[6] - 2 * f[0]));
    double dt = fabs(f[3] + f[4] - 2 * f[0] - r23 * (f[7] + f[8] - 2 * f[0]));
    /* Zero at some points and not at others: the support's edge crosses
     * the rectangle, and a rule's error estimate means nothing across a
     * jump (both rules can agree while missing most of a sliver).  Between
     * the smallest and the largest value seen, the integral is anywhere in
     * [area fmin, area fmax]: the error is at most the estimate's distance
     * to the further end, which makes such rectangles split until the
     * edge's strip is below tolerance (or the rectangles run out, the
     * error then honest). */
    double least = f[0], most = f[0];
    int zeros = 0;
    for (int p = 0; p < RECT_POINTS; p++) {
        least = fmin(least, f[p]);
        most = fmax(most, f[p]);
        zeros += f[p] == 0.0;
    }
    int edge = zeros > 0 && zeros < RECT_POINTS;
    if (edge)
        r->err = fmax(r->err, fmax(r->est - area * least, area * most - r->est));
    if (!two_d) {
        r->axis = 0;
    } else if (edge) {
        /* across the edge: the axis whose halves see the jump in fewer of
         * them (halving along the edge leaves two halves as uncertain as
         * their parent, the error bound no smaller); ties, the longer side */
        int mixed[2] = {0, 0};
        for (int a = 0; a < 2; a++) {
            int seen[2][2] = {{0, 0}, {0, 0}}; /* [half][zero or not] */
            for (int p = 0; p < RECT_POINTS; p++)
                if (gm_off[p][a] != 0.0)
                    seen[gm_off[p][a] > 0.0][f[p] == 0.0] = 1;
            mixed[a] = (seen[0][0] && seen[0][1]) + (seen[1][0] && seen[1][1]);
        }
        r->axis = mixed[0] != mixed[1] ? (mixed[1] < mixed[0]) : (r->t1 - r->t0) > (r->s1 - r->s0);
    } else if (ds == dt) { /* flat in both (or ties): the longer side */
        r->axis = (r->t1 - r->t0) > (r->s1 - r->s0) ? 1 : 0;
    } else {
        r->axis = dt > ds ? 1 : 0;
    }
}

/* Evaluates every rect whose axis is -1 (new or changed), in chunks of at
 * most batch points. */
static int evaluate_dirty(mcstat__rect *rects, size_t nr, const mcstat__domain *d, mcstat__density_cb density,
                          void *ctx, double *xbuf, double *fbuf, size_t batch)
{
    size_t per_chunk = batch / RECT_POINTS;
    if (per_chunk == 0)
        per_chunk = 1;
    size_t i = 0;
    while (i < nr) {
        size_t start = i, got = 0, np = 0;
        for (; i < nr && got < per_chunk; i++) {
            mcstat__rect *r = &rects[i];
            if (r->axis != -1)
                continue;
            double cs = 0.5 * (r->s0 + r->s1), ct = 0.5 * (r->t0 + r->t1);
            double hs = 0.5 * (r->s1 - r->s0), ht = 0.5 * (r->t1 - r->t0);
            for (int p = 0; p < RECT_POINTS; p++, np++)
                mcstat__domain_point(d, cs + gm_off[p][0] * hs, ct + gm_off[p][1] * ht, xbuf + np * d->dims);
            got++;
        }
        if (got == 0)
            break;
        int st = density(ctx, xbuf, np, fbuf);
        if (st)
            return st;
        size_t k = 0;
        for (size_t j = start; j < i; j++)
            if (rects[j].axis == -1) {
                rule(&rects[j], fbuf + k * RECT_POINTS, d->jacobian, d->two_d);
                k++;
            }
    }
    return 0;
}

/* Does the rectangle hold far more or far fewer pilot points than its
 * integral predicts (a feature its rule's points missed, or a peak it
 * overshot)?  Beyond 4 Poisson sd of the expectation (at least 3 points
 * above it), or any point where the integral is not positive; rectangles
 * below 1e-12 of the square are left alone.  A sampler that disagrees with
 * pdf() everywhere makes this split everywhere: max_rects bounds the cost. */
static int pilot_disagrees(const mcstat__rect *r, uint64_t n_points, double mass)
{
    uint64_t count = r->p1 - r->p0;
    if (n_points == 0 || (r->s1 - r->s0) * (r->t1 - r->t0) < 1e-12)
        return 0;
    if (count > 0 && (!(r->est > 0.0) || !(mass > 0.0)))
        return 1;
    if (!(mass > 0.0))
        return 0;
    double expected = (double)n_points * fmax(r->est, 0.0) / mass, c = (double)count;
    double sd = sqrt(fmax(expected, 1.0));
    return (c - expected > 4.0 * sd && c - expected >= 3.0) || (expected - c > 4.0 * sd && expected >= 16.0);
}

/* Each pair of fresh halves: the change the split made to the estimate is
 * an error estimate of the halves' sum too; each half keeps at least half
 * of it (the rule's own estimate can miss a singular point's behaviour
 * at both levels alike; this one sees it shrink). */
static void compare_halves(mcstat__rect *rects, size_t nr)
{
    for (size_t i = 0; i < nr; i++) {
        int64_t j = rects[i].sibling;
        if (j < 0)
            continue;
        double change = fabs(rects[i].parent - (rects[i].est + rects[j].est));
        rects[i].err = fmax(rects[i].err, 0.5 * change);
        rects[j].err = fmax(rects[j].err, 0.5 * change);
        rects[i].sibling = rects[j].sibling = -1;
    }
}

/* The axis along which the rectangle's pilot points span the smallest
 * share of its width. */
static int32_t pilot_axis(const double *st, const mcstat__rect *r)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (uint64_t j = r->p0; j < r->p1; j++)
        for (int a = 0; a < 2; a++) {
            lo[a] = fmin(lo[a], st[2 * j + a]);
            hi[a] = fmax(hi[a], st[2 * j + a]);
        }
    double share_s = (hi[0] - lo[0]) / (r->s1 - r->s0), share_t = (hi[1] - lo[1]) / (r->t1 - r->t0);
    return share_t < share_s ? 1 : 0;
}

static void sum_cells(mcstat__tree *tr, const mcstat__rect *rects, size_t nr)
{
    for (int32_t c = 0; c < tr->n_cells; c++) {
        tr->cells[c].prob = tr->cells[c].err = 0.0;
        tr->cells[c].n_rects = 0;
    }
    for (size_t i = 0; i < nr; i++) {
        mcstat__cell *cell = &tr->cells[rects[i].cell];
        cell->prob += rects[i].est;
        cell->err += rects[i].err;
        cell->n_rects++;
    }
}

/* Whether a rectangle is to be halved, as its priority: its error if it
 * carries at least its cell's average error in a cell above tolerance; if
 * the pilot disagrees with it, the larger of its error and the pilot's
 * estimate of what it misses; 0 otherwise. */
static double split_priority(const mcstat__tree *tr, const mcstat__rect *r, double tol_scale, double mass,
                             int *by_pilot)
{
    const mcstat__cell *cell = &tr->cells[r->cell];
    double tol = tol_scale * sqrt(fmax(cell->prob, 0.0)) + 1e-15;
    *by_pilot = 0;
    if (cell->err > tol && r->err * cell->n_rects >= cell->err)
        return r->err;
    if (!pilot_disagrees(r, tr->n_points, mass))
        return 0.0;
    *by_pilot = 1;
    double seen = fmax(mass, 0.0) * (double)(r->p1 - r->p0) / (double)tr->n_points;
    return fmax(fmax(r->err, fabs(seen - r->est)), DBL_MIN);
}

/* The least priority halved this round: 0 while the rectangles left can
 * halve every candidate; otherwise the largest errors go first, wherever
 * they are (in index order, the budget would go to whichever cells come
 * first, and a support's edge in a later cell would keep its error). */
static double split_threshold(const mcstat__tree *tr, const mcstat__rect *rects, size_t nr, size_t room, double tol_scale,
                              double mass)
{
    size_t count = 0;
    double lo = INFINITY, hi = 0.0;
    int by_pilot;
    for (size_t i = 0; i < nr; i++) {
        double p = split_priority(tr, &rects[i], tol_scale, mass, &by_pilot);
        if (p > 0.0) {
            count++;
            lo = fmin(lo, p);
            hi = fmax(hi, p);
        }
    }
    if (count <= room)
        return 0.0;
    /* bisect (geometrically) for the least threshold that fits the room */
    for (int it = 0; it < 100 && lo < hi; it++) {
        double mid = sqrt(lo) * sqrt(hi);
        if (!(mid > lo && mid < hi))
            break;
        size_t above = 0;
        for (size_t i = 0; i < nr; i++)
            above += split_priority(tr, &rects[i], tol_scale, mass, &by_pilot) >= mid;
        if (above > room)
            lo = mid;
        else
            hi = mid;
    }
    return hi;
}

#define TWO_PI 6.283185307179586476925286766559

/* A rectangle's sides as lengths on the domain (radians on the sphere's
 * surface), from the map's metric at its centre: with z = 1 - k s (k = 1
 * the hemisphere, 2 the sphere) and rho = sin(theta), the polar side is
 * k ds / rho and the azimuthal 2 pi rho dt; the disk's r = sqrt(s) gives
 * ds / (2 r) and 2 pi r dt; the square is its own. */
static void rect_sides(const mcstat__domain *d, const mcstat__rect *r, double *ls, double *lt)
{
    double s = 0.5 * (r->s0 + r->s1), ds = r->s1 - r->s0, dt = r->t1 - r->t0, rho;
    switch (d->kind) {
    case MCSTAT_CHECK_DOMAIN_SPHERE:
        rho = 2.0 * sqrt(s * (1.0 - s));
        *ls = 2.0 * ds / rho;
        *lt = TWO_PI * rho * dt;
        break;
    case MCSTAT_CHECK_DOMAIN_HEMISPHERE:
        rho = sqrt(s * (2.0 - s));
        *ls = ds / rho;
        *lt = TWO_PI * rho * dt;
        break;
    case MCSTAT_CHECK_DOMAIN_DISK:
        rho = sqrt(s);
        *ls = ds / (2.0 * rho);
        *lt = TWO_PI * rho * dt;
        break;
    default: *ls = ds, *lt = dt; break;
    }
}

/* The tree's cells are slabs wherever the pilot is dense along s: a cell
 * 0.01 by 0.6 of the hemisphere's square is 0.01 rad by 3.5 rad of
 * azimuth, and a rule's seven points along 3.5 rad miss a lobe a tenth of a
 * radian wide (its error estimate, seeing nothing, is tiny, so nothing
 * halves it).  Before the rules run, rectangles whose azimuthal side is more
 * than ASPECT_MAX times their polar side are halved across it, in passes
 * over all of them, for at most ASPECT_PASSES passes and an eighth of the
 * rectangles' budget (the rest is the halving's).  Only across t: cells
 * long in s are the pole's (layered apart below) or a lobe's own shape (a
 * mirror-like lobe at grazing incidence is 1e-6 across in azimuth and a
 * tenth of a radian in elevation; cutting it along s only spends the
 * budget its halving needs). */
#define ASPECT_MAX 4.0
#define ASPECT_PASSES 3
static size_t aspect_cuts(mcstat__tree *tr, const mcstat__domain *d, mcstat__rect *rects, size_t nr,
                          size_t max_rects)
{
    if (!d->two_d)
        return nr;
    size_t budget = nr + max_rects / 8 < max_rects ? nr + max_rects / 8 : max_rects;
    for (int pass = 0; pass < ASPECT_PASSES; pass++) {
        size_t n0 = nr;
        for (size_t i = 0; i < n0 && nr < budget; i++) {
            mcstat__rect *r = &rects[i];
            double ls, lt;
            rect_sides(d, r, &ls, &lt);
            if (!(lt > ASPECT_MAX * ls))
                continue;
            mcstat__rect b = *r;
            double mid = 0.5 * (r->t0 + r->t1);
            r->t1 = b.t0 = mid;
            uint64_t q = r->p0;
            for (uint64_t j = r->p0; j < r->p1; j++)
                if (tr->st[2 * j + 1] < mid)
                    swap_pair(tr->st, j, q++);
            r->p1 = b.p0 = q;
            rects[nr++] = b;
        }
        if (nr == n0)
            break;
    }
    return nr;
}

/* The poles of the sphere (the hemisphere's pole, the disk's centre) are
 * the lines s = 0 and s = 1 of the equal-area square: a feature a
 * thousandth of a radian across there is a strip 1e-6 wide spanning every
 * t, cut among many cells, each piece too thin for its rectangle's rule
 * and holding too few pilot points to be noticed (a narrow specular peak
 * at normal incidence).  Rectangles on such a line start as layers whose
 * widths shrink by 4 toward it, down to 4^-POLE_LAYERS of the cell's; the
 * rules and the halving go on from there.  Returns the rectangles in use. */
#define POLE_LAYERS 10
static size_t pole_layers(mcstat__tree *tr, const mcstat__domain *d, mcstat__rect *rects, size_t nr,
                          size_t max_rects)
{
    int low = d->kind == MCSTAT_CHECK_DOMAIN_SPHERE || d->kind == MCSTAT_CHECK_DOMAIN_HEMISPHERE ||
              d->kind == MCSTAT_CHECK_DOMAIN_DISK;
    int high = d->kind == MCSTAT_CHECK_DOMAIN_SPHERE;
    size_t n0 = nr;
    for (size_t i = 0; i < n0 && nr + POLE_LAYERS <= max_rects; i++) {
        mcstat__rect *r = &rects[i];
        int at_low = low && r->s0 == 0.0, at_high = !at_low && high && r->s1 == 1.0;
        if (!at_low && !at_high)
            continue;
        double w = r->s1 - r->s0, inner = 0.0;
        uint64_t q = r->p0;
        for (int k = POLE_LAYERS; k >= 1; k--) { /* innermost first */
            double outer = w * pow(0.25, k);
            mcstat__rect b = *r;
            if (at_low) {
                b.s0 = r->s0 + inner;
                b.s1 = r->s0 + outer;
            } else {
                b.s0 = r->s1 - outer;
                b.s1 = r->s1 - inner;
            }
            /* the pilot points nearer the line than `outer` follow the layer */
            b.p0 = q;
            for (uint64_t j = q; j < r->p1; j++) {
                double dist = at_low ? tr->st[2 * j] - r->s0 : r->s1 - tr->st[2 * j];
                if (dist < outer)
                    swap_pair(tr->st, j, q++);
            }
            b.p1 = q;
            b.axis = -1;
            b.est = b.err = b.parent = 0.0;
            b.sibling = -1;
            rects[nr++] = b;
            inner = outer;
        }
        /* the rectangle keeps the rest, beyond the outermost layer */
        if (at_low)
            r->s0 += inner;
        else
            r->s1 -= inner;
        r->p0 = q;
    }
    return nr;
}

int mcstat__cells_integrate(mcstat__tree *tr, const mcstat__domain *d, mcstat__density_cb density, void *ctx,
                            double tol_scale, mcstat__rect *rects, size_t max_rects, double *xbuf, double *fbuf,
                            size_t batch, size_t *rects_used)
{
    size_t nr = 0;
    int32_t nc = tr->n_cells;
    for (int32_t c = 0; c < nc && nr < max_rects; c++) {
        const mcstat__cell *cell = &tr->cells[c];
        mcstat__rect r = {cell->s0, cell->s1, cell->t0, cell->t1, 0.0, 0.0, c, -1,
                          cell->p_first, cell->p_first + cell->p_count, 0.0, -1};
        rects[nr++] = r;
    }
    nr = aspect_cuts(tr, d, rects, nr, max_rects);
    nr = pole_layers(tr, d, rects, nr, max_rects);
    int st = evaluate_dirty(rects, nr, d, density, ctx, xbuf, fbuf, batch);
    for (int round = 0; st == 0 && round < 64; round++) {
        /* per cell: probability, error, the error of its worst rect */
        sum_cells(tr, rects, nr);
        /* halve the rects carrying at least their cell's average error, in
         * cells above tolerance */
        double mass = 0.0;
        for (int32_t c = 0; c < nc; c++)
            mass += fmax(tr->cells[c].prob, 0.0);
        size_t n_split = 0, nr0 = nr;
        double least = split_threshold(tr, rects, nr0, max_rects - nr, tol_scale, mass);
        for (size_t i = 0; i < nr0 && nr < max_rects; i++) {
            mcstat__rect *r = &rects[i];
            int by_pilot;
            double priority = split_priority(tr, r, tol_scale, mass, &by_pilot);
            if (!(priority > 0.0) || priority < least)
                continue;
            /* the rule saw nothing of what the pilot found: halve across
             * the axis along which the points are most concentrated, so
             * that a sliver (a lobe against the horizon) gets isolated */
            if (by_pilot && d->two_d && r->p1 - r->p0 >= 2)
                r->axis = pilot_axis(tr->st, r);
            mcstat__rect b = *r;
            if (r->axis == 0) {
                double mid = 0.5 * (r->s0 + r->s1);
                r->s1 = mid;
                b.s0 = mid;
            } else {
                double mid = 0.5 * (r->t0 + r->t1);
                r->t1 = mid;
                b.t0 = mid;
            }
            /* the pilot points follow their halves */
            uint64_t q = r->p0;
            for (uint64_t j = r->p0; j < r->p1; j++)
                if (tr->st[2 * j + r->axis] < (r->axis == 0 ? r->s1 : r->t1))
                    swap_pair(tr->st, j, q++);
            r->p1 = b.p0 = q;
            r->axis = b.axis = -1;
            r->parent = b.parent = r->est;
            r->sibling = (int64_t)nr;
            b.sibling = (int64_t)i;
            rects[nr++] = b;
            n_split++;
        }
        if (n_split == 0)
            break;
        st = evaluate_dirty(rects, nr, d, density, ctx, xbuf, fbuf, batch);
        if (st == 0)
            compare_halves(rects, nr);
    }
    if (st == 0)
        sum_cells(tr, rects, nr);
    *rects_used = nr;
    return st;
}
