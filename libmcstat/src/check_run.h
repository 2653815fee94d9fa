/*
 * check_run.h - a renderer check's run as the runner (check_run.c) fills
 * it and the routes' statistics (check_routes.c) read it: the plan, the
 * scratch, the run's state and the sample's sums.  Nothing here is
 * exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_CHECK_RUN_H
#define MCSTAT_CHECK_RUN_H

#include "check.h"

#define MAX_GROUPS 16 /* regions of the integrals route, at most */
/* Points per side of the KS route: its exact p-value costs O(N^1.5) (9 ms
 * at 20000 + 20000, 17 ms at 40000 + 45000, most of a check with cheap
 * callbacks); the kept points are i.i.d., so the first KS_MAX are a sample. */
#define KS_MAX 20000

/* ---- the plan: sizes, and the scratch carved from one block --------------- */

typedef struct plan {
    mcstat__domain d;
    int kind, nu, reports, has_eval;
    uint64_t n, n_pilot, n_eval, cells_target;
    size_t batch, max_cells, max_rects;
} plan;

typedef struct scratch {
    double *u, *x, *w, *p, *xs, *ws, *ps, *f, *p2; /* one batch each */
    double *sb;                                    /* (s, t) of a batch's points: 2 per point */
    int32_t *cellb;                                /* the cell of each compacted point */
    double *st;                                    /* pilot (s, t): 2 n_pilot */
    double *wsave, *vsave;                         /* weights and eval-only values: n, n_eval */
    double *rsave;                                 /* pdf/table at the table points: n_eval */
    double *keys_a, *keys_b;                       /* KS: kept sampled points' keys (n), eval's (n_eval/2) */
    double *recip;                                 /* reciprocity points: 4 each */
    double *counts;                                /* per cell */
    double *cell_r, *cell_r2;                      /* per cell: sums of pdf/table at the table points */
    double *cdf;                                   /* per cubature rectangle */
    mcstat__node *nodes;
    mcstat__cell *cells;
    mcstat__rect *rects;
} scratch;

typedef struct run {
    const mcstat_check_model *m;
    const double *wi;
    plan pl;
    mcstat_check_options o;
    scratch s;
    mcstat__tree tr;
    mcstat_check_report *out;
    uint64_t key_pilot, key_test, key_eval, key_keep_sample, key_keep_eval;
    /* KS: envelopes, their breaches, the points kept */
    double w_envelope, v_largest, v_envelope;
    int w_breach, v_breach;
    double breach_x[3], breach_v[2];
    uint64_t n_keys_a, n_keys_b;
    double rtol;
    double resolution; /* the numerical floor the statistical routes apply (options' resolution) */
    /* deterministic routes: points beyond rtol re-evaluated at their float32
     * neighbours (check_run.c's rounding_nearest), and the most allowed */
    uint64_t rounding_checks, rounding_cap;
    int not_float32;   /* a value a callback returned is not a float32 */
    /* deterministic comparisons: points beyond tolerance and the worst */
    uint64_t bad[MCSTAT_CHECK_ROUTE_COUNT], checked[MCSTAT_CHECK_ROUTE_COUNT];
    /* failures the tolerated share does not excuse: a discrete lobe is one
     * claim, not one point among many */
    int hard[MCSTAT_CHECK_ROUTE_COUNT];
    double worst[MCSTAT_CHECK_ROUTE_COUNT], worst_x[MCSTAT_CHECK_ROUTE_COUNT][3], worst_v[MCSTAT_CHECK_ROUTE_COUNT][2];
    uint64_t pdf_without_eval; /* pdf > 0 where eval = 0 (counted, not a failure) */
    uint64_t zero_weight;      /* successes (pdf > 0) whose weight is 0 where eval() > 0 */
    size_t n_rects;            /* cubature rectangles: a fine partition of the domain */
    uint64_t seed;
    /* discrete lobes (model->lobes), and the tested samples that fell on each */
    int n_lobes;
    double lobe_x[MCSTAT_CHECK_MAX_LOBES][3], lobe_mass[MCSTAT_CHECK_MAX_LOBES],
        lobe_value[MCSTAT_CHECK_MAX_LOBES];
    uint64_t lobe_count[MCSTAT_CHECK_MAX_LOBES];
} run;

/* Regions of the integrals route: up to 16, with about 500 samples each at
 * least (a Wald test with an estimated covariance is liberal when its
 * regions hold few samples). */
static inline int region_count(const run *r)
{
    uint64_t g = r->pl.n / 500;
    if (g > MAX_GROUPS)
        g = MAX_GROUPS;
    if (g > (uint64_t)r->tr.n_cells)
        g = (uint64_t)r->tr.n_cells;
    return g < 2 ? (r->tr.n_cells < 2 ? 1 : 2) : (int)g;
}

/* The tested sample's and the eval-only estimator's sums (check_run.c's stages 2 and 3). */
typedef struct sums {
    double a[MAX_GROUPS], a2[MAX_GROUPS]; /* sampler: sums of weights and squares per region */
    double b[MAX_GROUPS], b2[MAX_GROUPS]; /* eval-only */
    double r, r2;                         /* pdf/table at the table points: the mass, sampled */
    mcstat_moments all;                  /* every weight (0 for failed samples) */
    uint64_t n_succ, n_w, n_v, n_recip;   /* n_succ: successes off the discrete lobes */
    uint64_t n_lobe;                      /* successes on them */
    mcstat_moments escapes;               /* escape_transmittance >= 0: the escapes' weights */
    uint64_t n_escape;                    /* escapes of weight > 0 */
} sums;

/* ---- the routes' statistics (check_routes.c) ------------------------------ */
/* A route's result before it runs: SKIPPED, its numbers NaN. */
MCSTAT_HIDDEN void mcstat__check_route_init(mcstat_check_route_result *rr);
/* Hill's estimate of the upper tail index of x[0..n) (reordered; NaN below
 * 100 values, +Inf where the tail is not Pareto-like). */
MCSTAT_HIDDEN double mcstat__check_hill_upper(double *x, uint64_t n);
/* Route `route`'s statistic, p-value and detectable effect into
 * r->out->route[route]; `level` is what `detectable` is computed at. */
MCSTAT_HIDDEN void mcstat__check_route(run *r, const sums *sm, int route, double level);
/* The integral of eval from the weights and from eval alone, reported
 * whether or not the integrals route runs. */
MCSTAT_HIDDEN void mcstat__check_report_albedos(run *r, const sums *sm);

#endif /* MCSTAT_CHECK_RUN_H */
