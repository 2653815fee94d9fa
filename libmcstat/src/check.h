/*
 * check.h - the renderer checks' internals (check_*.c): the domains and
 * their equal-area squares, counter-based uniforms, the cell tree and its
 * cubature.  Nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_CHECK_INTERNAL_H
#define MCSTAT_CHECK_INTERNAL_H

#include "internal.h"

/* ---- domains (check_domain.c) ---------------------------------------------
 * Every domain is the image of the unit square (s, t) under a map of
 * constant Jacobian `jacobian` (measure of the domain per unit area of the
 * square), so cells and uniform points are rectangles and uniform (s, t):
 *   SPHERE      z = 1 - 2s, phi = 2 pi t           jacobian 4 pi
 *   HEMISPHERE  z = 1 - s,  phi = 2 pi t           jacobian 2 pi
 *   SQUARE      (x, y) = (s, t)                     1
 *   DISK        r = sqrt(s), phi = 2 pi t           pi
 *   INTERVAL    x = s (t unused)                    1 */
typedef struct mcstat__domain {
    int kind;        /* enum mcstat_check_domain */
    int dims;        /* coordinates per point */
    int two_d;       /* 0 for INTERVAL: cells split along s only */
    double jacobian;
} mcstat__domain;

MCSTAT_HIDDEN int mcstat__domain_get(int kind, mcstat__domain *d);
/* x[0..dims) <- the point of (s, t). */
MCSTAT_HIDDEN void mcstat__domain_point(const mcstat__domain *d, double s, double t, double *x);
/* (s, t) of the point x: 0, or 1 when x is outside the domain (beyond
 * round-off: directions of length 1 within 1e-4, the hemisphere's z >=
 * -1e-4, the square and interval within 1e-6 of [0, 1], the disk's radius
 * within 1 + 1e-6), or not finite. */
MCSTAT_HIDDEN int mcstat__domain_coords(const mcstat__domain *d, const double *x, double *s, double *t);
/* The Morton key of (s, t): each quantised to 32 bits, s's bit b at key bit
 * 2b + 1 and t's at 2b (libmcest's mcest_direction_key on directions);
 * 1-D domains: s quantised to 64 bits. */
MCSTAT_HIDDEN uint64_t mcstat__domain_key(const mcstat__domain *d, double s, double t);

/* ---- uniforms ---------------------------------------------------------------
 * Counter-based: number `index` of stream `stream` under `seed` is a pure
 * function of the three (SplitMix64's output function applied to a Weyl
 * sequence keyed by seed and stream), so batches and restarts draw the same
 * numbers.  Values are multiples of 2^-53 in [0, 1). */
static inline uint64_t mcstat__mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}
static inline uint64_t mcstat__stream_key(uint64_t seed, uint64_t stream)
{
    return mcstat__mix64(seed ^ mcstat__mix64(stream * 0x9e3779b97f4a7c15ull + 0x632be59bd9b4e019ull));
}
static inline double mcstat__uniform(uint64_t key, uint64_t index)
{
    return (double)(mcstat__mix64(key + (index + 1) * 0x9e3779b97f4a7c15ull) >> 11) * 0x1.0p-53;
}

/* ---- the cell tree (check_cells.c) ----------------------------------------
 * A k-d tree over the square: nodes[0] is the root; an inner node splits
 * along `axis` (0: s, 1: t) at `split`, children `left` (coordinate <
 * split) and `right`; a leaf has left = -1 and `cell` its number.  Cells are
 * numbered in left-to-right leaf order, so consecutive cells touch. */
typedef struct mcstat__node {
    double split;
    int32_t axis, left, right, cell;
} mcstat__node;

typedef struct mcstat__cell {
    double s0, s1, t0, t1;
    double prob, err; /* integral of pdf over the cell, its estimated error */
    int32_t n_rects;  /* cubature rectangles in the cell */
    int32_t group;    /* the region (a run of consecutive cells) it belongs to */
    uint64_t p_first, p_count; /* its pilot points: st[2 p_first ..] of the tree's pilot */
} mcstat__cell;

typedef struct mcstat__tree {
    mcstat__node *nodes;
    mcstat__cell *cells;
    int32_t n_nodes, n_cells, max_nodes, max_cells;
    double *st;        /* the pilot's (s, t) pairs, grouped by cell (then by rectangle) */
    uint64_t n_points;
} mcstat__tree;

/* Nodes and cells a tree over m pilot points with `leaf` points per leaf
 * can need. */
MCSTAT_HIDDEN size_t mcstat__tree_max_cells(uint64_t m, int leaf);
/* Builds the tree from the pilot's (s, t) pairs st[0..2m) (reordered):
 * nodes split at the median of their points along s and t in turn while
 * they hold at least 1.4 leaf points; `horizon` cuts the root at s = 1/2
 * first (the sphere: upper and lower hemispheres apart). */
MCSTAT_HIDDEN void mcstat__tree_build(mcstat__tree *tr, const mcstat__domain *d, double *st, uint64_t m, int leaf,
                                      int horizon);
MCSTAT_HIDDEN int32_t mcstat__tree_locate(const mcstat__tree *tr, double s, double t);

/* Adaptive cubature of a density over every cell (Genz-Malik degree 7
 * with its embedded degree 5 rule on rectangles, 17 points each, and 4
 * probes just inside the corners; a halved
 * rectangle's halves also carry half the change of the estimate the split
 * made, a second error estimate that sees what the rule alone misses near
 * singular points):
 * cells[c].prob and .err, cells[c].prob being the integral of
 * density(x(s, t)) * jacobian over the cell.  A cell is done when its
 * error estimate is at most tol_scale * sqrt(prob) (plus 1e-15); rectangles
 * whose error share is above the cell's average are halved along the axis
 * of the larger fourth difference.  A rule's 17 points can all miss a thin
 * feature (the rim of a cone of directions, a sliver of support), so the
 * pilot points guide it too: a rectangle holding pilot points far beyond
 * what its integral predicts is halved as well.  Where the density is 0
 * at some of a rectangle's 21 points and not at others (the support's
 * edge), the rules' difference means nothing: the error is at least the
 * estimate's distance to the further of area * (least, largest value),
 * and the rectangle is halved across the edge.  At most max_rects
 * rectangles; when fewer are left than candidates, the largest errors
 * are halved first.
 * `density` is called with up to `batch` points (x in xbuf, results in
 * fbuf).  Returns the callback's status (non-zero stops). */
typedef int (*mcstat__density_cb)(void *ctx, const double *x, size_t n, double *out);
typedef struct mcstat__rect {
    double s0, s1, t0, t1, est, err;
    int32_t cell, axis;
    uint64_t p0, p1; /* its pilot points: st[2 p0 .. 2 p1) */
    double parent;   /* the estimate of the rectangle it was halved from, until compared */
    int64_t sibling; /* the other half, until compared; -1 after */
} mcstat__rect;
MCSTAT_HIDDEN int mcstat__cells_integrate(mcstat__tree *tr, const mcstat__domain *d, mcstat__density_cb density,
                                          void *ctx, double tol_scale, mcstat__rect *rects, size_t max_rects,
                                          double *xbuf, double *fbuf, size_t batch, size_t *rects_used);

#endif /* MCSTAT_CHECK_INTERNAL_H */
