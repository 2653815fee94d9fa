/*
 * tests_core.h - what the tests share: the moments a test reads (moments.c),
 * filling a result (result.c), the quantile cache (quantile_cache.c) and
 * the tests on accumulators that the row-wise calls drive (rows.c).
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_TESTS_CORE_H
#define MCSTAT_TESTS_CORE_H

/* ---- moments (moments.c) ------------------------------------------------ */
/* The variance as v * 2^(2*e) with v finite: *v = m2/(n-1) in scaled units. */
/* The scale exponent an accumulator holding values up to amax in magnitude has. */
MCSTAT_HIDDEN int mcstat__moments_scale_for(double amax);
MCSTAT_HIDDEN void mcstat__moments_var_scaled(const mcstat_moments *m, double *v, int *e);
MCSTAT_HIDDEN mcstat_dd mcstat__moments_mean_dd(const mcstat_moments *m);
/* MCSTAT_ETOOFEW / MCSTAT_EDEGENERATE / MCSTAT_EINVAL checks of a sample. */
MCSTAT_HIDDEN int mcstat__moments_check(const mcstat_moments *m);
/* The moments of two samples, for the two-sample tests on arrays: mx and my
 * initialised and filled; the first failing status otherwise. */
MCSTAT_HIDDEN int mcstat__moments_of_two(const double *x, size_t nx, const double *y, size_t ny, mcstat_moments *mx,
                                         mcstat_moments *my);

/* *m <- every value of the stream; MCSTAT_ETOOBIG or MCSTAT_ENONFINITE when
 * it has left values out or holds NaN or +-Inf (stream.c). */
MCSTAT_HIDDEN int mcstat__stream_moments_checked(const mcstat_stream *s, mcstat_moments *m);

/* ---- results (result.c) -------------------------------------------------- */
/* Fills p_value, critical[], reject, decision from the statistic's tails.
 * `quantile(p, upper, ctx, &x)` inverts the null distribution. */
typedef int (*mcstat_quantile_fn)(double p, int upper, const void *ctx, double *x);
MCSTAT_HIDDEN int mcstat__finish(mcstat_result *r, const mcstat_tails *tails,
                                 mcstat_quantile_fn quantile, const void *ctx);
MCSTAT_HIDDEN void mcstat__result_clear(mcstat_result *r);

/* ---- quantile reuse (t_test.c, var_test.c, rows.c; quantile_cache.c) -----------------------
 * The critical values depend only on alpha, the alternative and the degrees
 * of freedom, so rows of equal sizes share them.  A cache holds the last two
 * quantiles of one distribution; mcstat__qcache_quantile is a
 * mcstat_quantile_fn over it.  Results are bit for bit those of a fresh
 * solve (the solvers are deterministic; the t is symmetric bit for bit). */
enum { MCSTAT_Q_T = 1, MCSTAT_Q_CHISQ = 2, MCSTAT_Q_F = 3 };
typedef struct {
    int kind, n, next;
    double df1, df2;
    struct { double p, x; int upper; } e[2];
} mcstat_qcache;
MCSTAT_HIDDEN void mcstat__qcache_init(mcstat_qcache *c);
/* Selects the distribution; forgets the entries when it changed. */
MCSTAT_HIDDEN void mcstat__qcache_use(mcstat_qcache *c, int kind, double df1, double df2);
MCSTAT_HIDDEN int mcstat__qcache_quantile(double p, int upper, const void *ctx, double *x);

/* The tests on accumulators with a caller's cache; qc == NULL skips the
 * critical values and the confidence interval (left NaN). */
MCSTAT_HIDDEN int mcstat__t_test_1(const mcstat_moments *x, double mu0, int alternative, double alpha,
                                   mcstat_qcache *qc, mcstat_result *out);
MCSTAT_HIDDEN int mcstat__t_test_2(const mcstat_moments *x, const mcstat_moments *y, double mu0,
                                   int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out);
/* The per-pixel render guards (mcstat.h, MCSTAT_PIXELS_RENDER): eps, the
 * numerical floor's relative resolution, and each side's count of nonzero
 * values. */
typedef struct {
    double eps;
    uint64_t hx, hy;
} mcstat__render_guard;
/* Welch's variances and df under the guards: vx, vy floored, df Hsu's; a
 * pixel both of whose sides are constant is both_constant (untested when
 * they do not differ beyond the floor; when they do, both sides take the
 * rule-of-three floor: at a few samples per pixel a light's edge gives the
 * same count of hits in every seed by chance).  All in one scale: vx,
 * vy the sample variances, mmax the larger |mean|, sh the difference of
 * the means less the null value. */
typedef struct {
    double vx, vy, df;
    int both_constant, differ;
} mcstat__render_welch;
MCSTAT_HIDDEN double mcstat__rule3_ratio(double n);
/* rx, ry: mcstat__rule3_ratio(nx), (ny).  Inline: the per-pixel block
 * loops (pixels.c) and the single call run this same code. */
static inline void mcstat__render_adjust(const mcstat__render_guard *rg, double nx, double ny, double rx, double ry,
                                         double vx, double vy, double mmax, double sh, mcstat__render_welch *g)
{
    double num = rg->eps * mmax;
    num *= num;
    int cx = vx <= num, cy = vy <= num;
    g->both_constant = cx && cy;
    g->differ = g->both_constant && fabs(sh) > rg->eps * mmax;
    /* A side showing at most one value besides zeros says nothing of what
     * it hides: under H0 whatever it hides makes up the difference sh. */
    int sx = cx || rg->hx <= 1, sy = cy || rg->hy <= 1;
    double fx = sh * sh * rx, fy = sh * sh * ry;
    vx = vx > num ? vx : num;
    vy = vy > num ? vy : num;
    g->vx = sx && fx > vx ? fx : vx;
    g->vy = sy && fy > vy ? fy : vy;
    /* Hsu's df, min(nx, ny) - 1: Satterthwaite's estimated df is too
     * liberal in the far tails a whole image's adjustment reaches at a few
     * seeds; a side with zeros has its spread from its nonzero values. */
    double nux = sx || (double)rg->hx >= nx ? nx - 1.0 : (double)rg->hx - 1.0;
    double nuy = sy || (double)rg->hy >= ny ? ny - 1.0 : (double)rg->hy - 1.0;
    nux = nux < 1.0 ? 1.0 : nux;
    nuy = nuy < 1.0 ? 1.0 : nuy;
    g->df = nux < nuy ? nux : nuy;
}
/* Welch's test with the guards (the single call's code for such pixels). */
MCSTAT_HIDDEN int mcstat__t_test_2_render(const mcstat_moments *x, const mcstat_moments *y,
                                          const mcstat__render_guard *rg, double mu0, int alternative,
                                          double alpha, mcstat_qcache *qc, mcstat_result *out);
/* An interval's bound est - c se, scaled by 2^e, in double-double (the
 * t tests' and the per-pixel path's; safe for |c| or c se beyond 2^900). */
MCSTAT_HIDDEN double mcstat__ci_bound(mcstat_dd est, double c, double se, int e);
/* Student's pooled-variance two-sample t (Welch's code with the pooled
 * standard error and nx + ny - 2 degrees of freedom). */
MCSTAT_HIDDEN int mcstat__t_test_2_pooled(const mcstat_moments *x, const mcstat_moments *y, double mu0,
                                          int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out);
/* The paired t test on x - y (arguments checked but the data; qc as above). */
MCSTAT_HIDDEN int mcstat__t_test_paired(const double *x, const double *y, size_t n, double mu0, int alternative,
                                        double alpha, mcstat_qcache *qc, mcstat_result *out);
/* The paired test under the render guards (mcstat.h, MCSTAT_PIXELS_RENDER):
 * the differences' variance takes Welch's floors for a side (numerical,
 * eps times the larger |mean| of the sides; the rule of three when a side
 * or the differences are constant or show at most one nonzero value, or a
 * side is zero where the other is not), differences constant and equal
 * within the numerical floor are MCSTAT_EDEGENERATE, and the degrees of
 * freedom are Hsu's over the sides and the differences. */
MCSTAT_HIDDEN int mcstat__t_test_paired_render(const double *x, const double *y, size_t n, double eps, double mu0,
                                               int alternative, double alpha, mcstat_qcache *qc,
                                               mcstat_result *out);
MCSTAT_HIDDEN int mcstat__var_test_1(const mcstat_moments *x, double sigma2, int alternative, double alpha,
                                     mcstat_qcache *qc, mcstat_result *out);
MCSTAT_HIDDEN int mcstat__var_test_2(const mcstat_moments *x, const mcstat_moments *y, double ratio,
                                     int alternative, double alpha, mcstat_qcache *qc, mcstat_result *out);

/* The Clopper-Pearson interval of binom_test.c for x successes in n trials
 * at level 1 - alpha (one-sided alternatives keep the end 0 or 1). */
MCSTAT_HIDDEN int mcstat__binom_conf_int(double x, double n, int alternative, double alpha, double ci[2]);

#endif /* MCSTAT_TESTS_CORE_H */
