/*
 * check_routes.c - the renderer checks' routes' statistics (mcstat.h's
 * section "Renderer checks"): for each route, from what the run of
 * check_run.c gathered, its statistic and p-value (or its deterministic
 * count), the effect and the detectable effect; the tail index the
 * mean-based routes depend on; the albedos.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "check_run.h"

#define POWER_Z 0.8416212335729143 /* z of power 0.8 */

/* ---- the routes' statistics ----------------------------------------------- */

/* Moves the k + 1 largest of x[0..n) to the front (three-way quickselect:
 * equal weights, common for good samplers, cost nothing). */
static void select_largest(double *x, uint64_t n, uint64_t k)
{
    uint64_t lo = 0, hi = n;
    while (hi - lo > 1) {
        double pivot = x[lo + (hi - lo) / 2];
        uint64_t gt = lo, i = lo, lt = hi; /* [lo, gt) > pivot, [gt, i) == pivot, [lt, hi) < pivot */
        while (i < lt) {
            double v = x[i];
            if (v > pivot) {
                x[i] = x[gt];
                x[gt++] = v;
                i++;
            } else if (v < pivot) {
                x[i] = x[--lt];
                x[lt] = v;
            } else {
                i++;
            }
        }
        if (k < gt)
            hi = gt;
        else if (k >= lt)
            lo = lt;
        else
            return;
    }
}

/* Hill's estimate of the upper tail index from the largest sqrt(n) values
 * (clamped to [10, 1000]) of x[0..n) (reordered); +Inf when the tail is not
 * Pareto-like (fewer positive values than the estimate needs, or ties). */
double mcstat__check_hill_upper(double *x, uint64_t n)
{
    if (n < 100)
        return NAN;
    uint64_t k = (uint64_t)sqrt((double)n);
    k = k < 10 ? 10 : (k > 1000 ? 1000 : k);
    select_largest(x, n, k);
    double threshold = x[k];
    if (!(threshold > 0.0))
        return INFINITY;
    double sum = 0.0;
    for (uint64_t i = 0; i < k; i++)
        sum += log(x[i] / threshold);
    return sum > 0.0 ? (double)k / sum : INFINITY;
}

void mcstat__check_route_init(mcstat_check_route_result *rr)
{
    memset(rr, 0, sizeof *rr);
    rr->state = MCSTAT_CHECK_STATE_SKIPPED;
    rr->statistic = rr->df = rr->p_value = rr->p_adjusted = NAN;
    rr->effect = rr->detectable = rr->n_for_1pct = NAN;
    rr->where[0] = rr->where[1] = rr->where[2] = NAN;
    rr->value[0] = rr->value[1] = NAN;
    rr->resolution = NAN;
}

static void finish_deterministic(run *r, int route)
{
    mcstat_check_route_result *rr = &r->out->route[route];
    rr->state = MCSTAT_CHECK_STATE_RAN;
    rr->deterministic = 1;
    rr->checked = r->checked[route];
    rr->count = r->bad[route];
    double n = (double)r->checked[route], tau = r->o.tolerated;
    rr->reject = (double)r->bad[route] > floor(tau * n) || r->hard[route];
    rr->effect = r->worst[route];
    /* a wrong region of probability q gives about n q points beyond rtol:
     * seen with probability ~0.8 once n q exceeds the tolerated count by
     * 0.84 of its Poisson sd, and at least -ln(0.2) points are expected */
    rr->detectable = n > 0 ? fmax(tau + POWER_Z * sqrt(tau / n), 0.0) + -log(0.2) / n : NAN;
    /* a region of 1%: hit -ln(0.2) times; with tau >= 1%, never */
    rr->n_for_1pct = tau < 0.01 ? -log(0.2) / (0.01 - tau) : INFINITY;
    for (int c = 0; c < 3; c++)
        rr->where[c] = r->worst_x[route][c];
    rr->value[0] = r->worst_v[route][0];
    rr->value[1] = r->worst_v[route][1];
    if (r->checked[route] == 0) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        rr->why = MCSTAT_CHECK_WHY_TOO_FEW;
    }
}

/* Noncentrality at which chi^2(df) beyond its upper level-a quantile has
 * probability 0.8 (normal approximation: mean df + l, variance 2(df + 2l)). */
static double detectable_noncentrality(double df, double a)
{
    double crit;
    if (mcstat_chisq_quantile(a, df, 1, &crit) != MCSTAT_OK)
        return NAN;
    double z2 = POWER_Z * POWER_Z, c0 = df - crit, b = c0 - 2 * z2;
    double disc = b * b - c0 * c0 + 2 * z2 * df;
    return disc > 0 ? -b + sqrt(disc) : NAN;
}

/* A route whose statistic is chi-squared with df degrees of freedom under
 * H0: its upper tail as the p-value; 0 (the route INVALID) if that fails. */
static int ran_chisq(mcstat_check_route_result *rr, double statistic, double df)
{
    double p;
    if (mcstat_chisq_cdf(statistic, df, 1, &p) != MCSTAT_OK) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        rr->why = MCSTAT_CHECK_WHY_NUMERIC;
        return 0;
    }
    rr->state = MCSTAT_CHECK_STATE_RAN;
    rr->statistic = statistic;
    rr->df = df;
    rr->p_value = p;
    return 1;
}

/* Pearson's statistic over the cells pooled in leaf order (consecutive
 * cells touch) into groups of expected count at least `target`; each
 * group's variance grows by the square of its expectation's cubature
 * error.  Returns the number of groups. */
static int pooled_chisq(const run *r, const sums *sm, double mass, double target, double *x2_out)
{
    double x2 = 0.0, O = 0.0, E = 0.0, V = 0.0, lastO = 0, lastE = 0, lastV = 0;
    int groups = 0, have_last = 0;
    double N = (double)sm->n_succ, m_eval = (double)r->pl.n_eval;
    for (int32_t c = 0; c < r->tr.n_cells; c++) {
        /* The cubature's error estimate can fall short (a feature its points
         * miss, a singular point): the table points give an unbiased
         * estimate of the cell's probability; where the two differ by more
         * than 3 of its standard errors, the difference is the error. */
        double err = 2.0 * r->tr.cells[c].err; /* the estimate can be short near singular points */
        double p_mc = r->s.cell_r[c] / m_eval;
        double se = sqrt(fmax(r->s.cell_r2[c] / m_eval - p_mc * p_mc, 0.0) / m_eval);
        double diff = fabs(r->tr.cells[c].prob - p_mc);
        if (diff > 3.0 * se && diff > err)
            err = diff;
        err += r->resolution * fabs(r->tr.cells[c].prob); /* the numerical floor */
        O += r->s.counts[c];
        E += N * fmax(r->tr.cells[c].prob, 0.0) / mass;
        V += N * err / mass;
        if (E >= target) {
            if (have_last) {
                x2 += (lastO - lastE) * (lastO - lastE) / (lastE + lastV * lastV);
                groups++;
            }
            lastO = O, lastE = E, lastV = V, have_last = 1;
            O = E = V = 0.0;
        }
    }
    if (have_last) { /* a short tail joins the last group */
        lastO += O, lastE += E, lastV += V;
        x2 += (lastO - lastE) * (lastO - lastE) / (lastE + lastV * lastV);
        groups++;
    } else if (E > 0.0) {
        x2 += (O - E) * (O - E) / (E + V * V);
        groups++;
    }
    *x2_out = x2;
    return groups;
}

/* Cells of the coarse level: a smooth error (a sampler's parameter a few
 * percent off, a pdf a few percent high over half the domain) moves
 * probability between large regions, which the fine level's hundreds of
 * cells dilute over as many degrees of freedom (bench/RESULTS_power.md). */
#define COARSE_GROUPS 16.0

/* The cells route: Pearson's test at two levels of the same cells, the
 * fine one (groups of expected count 5, for narrow features) and a coarse
 * one (about COARSE_GROUPS groups, for smooth errors), Bonferroni across
 * the two.  The statistic and df reported are the deciding level's. */
static void route_cells(run *r, const sums *sm, double level)
{
    mcstat_check_route_result *rr = &r->out->route[MCSTAT_CHECK_ROUTE_CELLS];
    double mass = 0.0;
    for (int32_t c = 0; c < r->tr.n_cells; c++)
        mass += fmax(r->tr.cells[c].prob, 0.0);
    double N = (double)sm->n_succ;
    if (!(mass > 0.0) || sm->n_succ < 2) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        /* no smooth part claimed and none sampled (a purely discrete BSDF):
         * nothing to compare, not too little */
        rr->why = !(mass > 0.0) && sm->n_succ == 0 ? MCSTAT_CHECK_WHY_NOTHING : MCSTAT_CHECK_WHY_TOO_FEW;
        return;
    }
    double x2;
    int groups = pooled_chisq(r, sm, mass, 5.0, &x2);
    rr->checked = sm->n_succ;
    rr->count = (uint64_t)groups;
    if (groups < 2) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        return;
    }
    double df = groups - 1, x2c = 0.0;
    int coarse = groups > 2.0 * COARSE_GROUPS ? pooled_chisq(r, sm, mass, N / COARSE_GROUPS, &x2c) : 0;
    rr->resolution = r->resolution;
    if (coarse >= 2) {
        double pf, pc;
        if (mcstat_chisq_cdf(x2, df, 1, &pf) != MCSTAT_OK || mcstat_chisq_cdf(x2c, coarse - 1.0, 1, &pc) != MCSTAT_OK) {
            rr->state = MCSTAT_CHECK_STATE_INVALID;
            rr->why = MCSTAT_CHECK_WHY_NUMERIC;
            return;
        }
        int use_coarse = pc < pf;
        rr->state = MCSTAT_CHECK_STATE_RAN;
        rr->statistic = use_coarse ? x2c : x2;
        rr->df = use_coarse ? coarse - 1.0 : df;
        rr->p_value = fmin(1.0, 2.0 * fmin(pf, pc));
        level *= 0.5; /* each level's share */
    } else if (!ran_chisq(rr, x2, df))
        return;
    rr->effect = sqrt(x2 / N);
    double lambda = detectable_noncentrality(df, level);
    rr->detectable = sqrt(lambda / N);
    rr->n_for_1pct = lambda / 1e-4;
}

/* The mass route: the share of samples that succeed, x/n, against the mass
 * of pdf().  Two estimates of the mass: the cubature's (precise, but its
 * error estimate can fall short where a rule's points miss a feature) and
 * the Monte Carlo mean of pdf/table at the table points (unbiased whatever
 * the cubature did, but noisier).  When they agree (within 3 standard
 * errors of the second plus 4 times the cubature's error estimate), the
 * exact binomial test against the cubature's mass, conservative over 4
 * times its error; when they do not, and pdf/table is not heavy-tailed
 * (tail index >= 2.5, so that its variance can be trusted), the two-sample
 * z test against the Monte Carlo mass m,
 *   z = (x/n - m) / sqrt(m (1 - m)/n + var(pdf/table)/n_eval),
 * m clipped to [1/n, 1 - 1/n] in the binomial variance; otherwise the
 * binomial test as above.  "pdf() integrates above 1" (p = 0) needs both
 * estimates above 1. */
/* The discrete lobes' counts, each against n mass[k] by the exact binomial
 * test, with the smooth part's p-value p: the smallest times (lobes + 1).
 * where/value: the lobe furthest off, its share and its mass. */
/* The parts of the MASS route: the smooth successes, each discrete lobe,
 * and a medium's escape weights; Bonferroni across them. */
static int mass_parts(const run *r) { return 1 + r->n_lobes + (r->o.escape_transmittance >= 0.0); }

/* A medium's escapes: the mean over the n flights of their weights (0 for
 * a scattering) against T(tmax), a two-sided t test; p = 1 (no answer)
 * with fewer than 2 escapes of weight > 0, whose spread says nothing. */
static double escape_weights(run *r, const sums *sm)
{
    double T = r->o.escape_transmittance;
    mcstat_moments y = sm->escapes, zeros;
    uint64_t n = r->pl.n;
    if (mcstat_moments_from_summary(n - y.n, 0.0, 0.0, &zeros) != MCSTAT_OK ||
        mcstat_moments_merge(&y, &zeros) != MCSTAT_OK)
        return 1.0;
    r->out->escape_weight = mcstat_moments_mean(&y);
    r->out->route[MCSTAT_CHECK_ROUTE_MASS].value[0] = r->out->escape_weight;
    r->out->route[MCSTAT_CHECK_ROUTE_MASS].value[1] = T;
    if (sm->n_escape < 2)
        return 1.0;
    r->out->escape_weight_se = mcstat_moments_sd(&y) / sqrt((double)n);
    mcstat_result res;
    int st = mcstat_t_test_1_moments(&y, T, MCSTAT_TWO_SIDED, 0.5, &res);
    if (st == MCSTAT_EDEGENERATE) /* every flight escaped with the same weight */
        return fabs(r->out->escape_weight - T) <= r->rtol * fmax(T, r->out->escape_weight) ? 1.0 : 0.0;
    return st == MCSTAT_OK ? res.p_value : 1.0;
}

static double lobe_counts(run *r, mcstat_check_route_result *rr, double p, double level)
{
    int K = r->n_lobes;
    if (K == 0)
        return p;
    double least = p, least_lobe = 2.0, n = (double)r->pl.n;
    double z = mcstat__norm_quantile(level / 2 / mass_parts(r), 1) + POWER_Z;
    /* the budget is the weakest part's: a smooth part of mass 0 has none */
    if (!(r->out->mass > 0.0))
        rr->effect = rr->detectable = rr->n_for_1pct = NAN;
    for (int k = 0; k < K; k++) {
        double pk, mass = r->lobe_mass[k];
        uint64_t x = r->lobe_count[k];
        mcstat_result res;
        if (mcstat_binom_test(x, r->pl.n, mass, MCSTAT_TWO_SIDED, 0.5, &res) == MCSTAT_OK)
            pk = res.p_value;
        else
            pk = (double)x == n * mass ? 1.0 : 0.0;
        if (mass > 0.0 && mass < 1.0) {
            double det = z * sqrt(mass * (1.0 - mass) / n) / mass;
            double n1 = z * z * (1.0 - mass) / mass / (0.01 * 0.01);
            if (!(rr->detectable >= det))
                rr->detectable = det;
            if (!(rr->n_for_1pct >= n1))
                rr->n_for_1pct = n1;
        }
        if (pk < least_lobe) {
            least_lobe = pk;
            if (pk < p || isnan(rr->effect))
                rr->effect = mass > 0.0 ? ((double)x / n - mass) / mass : NAN;
            for (int c = 0; c < 3; c++)
                rr->where[c] = r->lobe_x[k][c];
            rr->value[0] = (double)x / n;
            rr->value[1] = mass;
        }
        least = fmin(least, pk);
    }
    return least;
}

static void route_mass(run *r, const sums *sm, double level)
{
    mcstat_check_route_result *rr = &r->out->route[MCSTAT_CHECK_ROUTE_MASS];
    uint64_t n = r->pl.n, x = sm->n_succ;
    double m_eval = (double)r->pl.n_eval;
    double mhat = sm->r / m_eval, var_m = fmax(sm->r2 / m_eval - mhat * mhat, 0.0) / m_eval;
    double tail = mcstat__check_hill_upper(r->s.rsave, r->pl.n_eval);
    r->out->mass_sampled = mhat;
    r->out->mass_sampled_se = sqrt(var_m);
    double phat = (double)x / (double)n, p;
    /* with lobes, each part is held to level/(lobes + 1) (Bonferroni) */
    double z = mcstat__norm_quantile(level / 2 / mass_parts(r), 1) + POWER_Z;
    rr->checked = n;
    rr->count = x;
    rr->state = MCSTAT_CHECK_STATE_RAN;
    rr->statistic = phat;
    rr->resolution = r->resolution;
    int agree = fabs(r->out->mass - mhat) <= 3.0 * sqrt(var_m) + 4.0 * r->out->mass_error;
    if (!isfinite(r->out->mass) || !isfinite(mhat)) {
        /* pdf() so large that its integral overflowed: no sampler can match it */
        rr->p_value = 0.0;
        rr->effect = rr->detectable = rr->n_for_1pct = NAN;
        return;
    }
    /* The cubature's error is a bound where it saw a support's edge, and
     * can be large there (its rectangles run out before the edge is
     * resolved): then the unbiased estimate is the more precise one. */
    if (tail >= 2.5 && (!agree || 3.0 * sqrt(var_m) < 4.0 * r->out->mass_error)) {
        double mc = fmin(fmax(mhat, 1.0 / (double)n), 1.0 - 1.0 / (double)n);
        double sd = sqrt(mc * (1.0 - mc) / (double)n + var_m + (r->resolution * mhat) * (r->resolution * mhat));
        double d = phat - mhat;
        p = sd > 0.0 ? erfc(fabs(d) / sd / sqrt(2.0)) : (fabs(d) <= 1e-12 ? 1.0 : 0.0);
        rr->effect = mhat > 0.0 ? d / mhat : NAN;
        rr->detectable = mhat > 0.0 ? z * sd / mhat : NAN;
        double room = 0.01 * mhat - z * sqrt(var_m * m_eval / (double)n); /* n_eval grows with n */
        rr->n_for_1pct = room > 0.0 ? z * z * (mc * (1.0 - mc) + var_m * m_eval) / (0.01 * mhat * 0.01 * mhat)
                                    : INFINITY;
    } else {
        double mass = r->out->mass, err = 4.0 * r->out->mass_error + r->resolution * fabs(r->out->mass);
        /* The two estimates can agree only because the unbiased one is
         * noisy while the cubature's error estimate fell short (a support's
         * edge its points missed): a narrow interval around the cubature
         * then excludes the truth, and a sampler whose samples all succeed
         * is rejected at p = 0.  The interval covers both estimates' (the
         * truth is in it when either error statement holds). */
        double lo = fmin(mass - err, mhat - 3.0 * sqrt(var_m)), hi = fmax(mass + err, mhat + 3.0 * sqrt(var_m));
        err = fmax(mass - lo, hi - mass);
        double p_lo = fmin(fmax(lo, 0.0), 1.0), p_hi = fmin(fmax(hi, 0.0), 1.0);
        rr->effect = mass > 0.0 ? (phat - mass) / mass : NAN;
        if (lo > 1.0) {
            p = 0.0; /* pdf() integrates above 1 by both estimates: no sampler can match it */
        } else if (phat >= p_lo && phat <= p_hi) {
            p = 1.0;
        } else {
            mcstat_result res;
            if (mcstat_binom_test(x, n, phat < p_lo ? p_lo : p_hi, MCSTAT_TWO_SIDED, 0.5, &res) != MCSTAT_OK) {
                rr->state = MCSTAT_CHECK_STATE_INVALID;
                return;
            }
            p = res.p_value;
        }
        double mm = fmin(fmax(mass, 1e-300), 1.0);
        /* near mass 1 the binomial's spread vanishes: a loss q is seen once
         * some sample fails, with probability 0.8 when n q >= -ln(0.2) */
        rr->detectable = (fmax(z * sqrt(mm * (1.0 - mm) / (double)n), -log(0.2) / (double)n) + err) / mm;
        double room = 0.01 * mm - err;
        rr->n_for_1pct = room > 0.0 ? fmax(z * z * mm * (1.0 - mm) / (room * room), -log(0.2) / 0.01) : INFINITY;
    }
    double least = lobe_counts(r, rr, p, level);
    if (r->o.escape_transmittance >= 0.0)
        least = fmin(least, escape_weights(r, sm));
    rr->p_value = fmin(1.0, (double)mass_parts(r) * least);
}

/* Solves the Wald statistic d' S^-1 d by Cholesky, dropping regions whose
 * pivot vanishes (no mass on either side); *df the regions kept. */
static double wald(const double *d, double S[MAX_GROUPS][MAX_GROUPS], int g, int *df)
{
    int keep[MAX_GROUPS], nk = 0;
    double L[MAX_GROUPS][MAX_GROUPS];
    for (int i = 0; i < g; i++) {
        keep[nk] = i;
        /* try adding region i */
        int k = nk;
        int ok = 1;
        for (int j = 0; j <= k; j++) {
            double sum = S[keep[k]][keep[j]];
            for (int q = 0; q < j; q++)
                sum -= L[k][q] * L[j][q];
            if (j == k) {
                if (!(sum > 1e-12 * S[keep[k]][keep[k]]) || !(S[keep[k]][keep[k]] > 0.0)) {
                    ok = 0;
                    break;
                }
                L[k][k] = sqrt(sum);
            } else {
                L[k][j] = sum / L[j][j];
            }
        }
        if (ok)
            nk++;
    }
    double y[MAX_GROUPS], t = 0.0;
    for (int i = 0; i < nk; i++) {
        double sum = d[keep[i]];
        for (int q = 0; q < i; q++)
            sum -= L[i][q] * y[q];
        y[i] = sum / L[i][i];
        t += y[i] * y[i];
    }
    *df = nk;
    return t;
}

/* The regions' integrals of eval from the sampler (A) and from the
 * eval-only estimator (B), their difference D and its covariance S, and
 * the totals with their variances; returns the number of regions. */
static int region_integrals(const run *r, const sums *sm, double A[MAX_GROUPS], double B[MAX_GROUPS],
                            double D[MAX_GROUPS], double S[MAX_GROUPS][MAX_GROUPS], double tot[2], double var[2])
{
    int g = region_count(r);
    double n = (double)r->pl.n, m = (double)r->pl.n_eval;
    double ta = 0.0, tb = 0.0;
    for (int i = 0; i < g; i++) {
        A[i] = sm->a[i] / n;
        B[i] = sm->b[i] / m;
        D[i] = A[i] - B[i];
        ta += A[i];
        tb += B[i];
    }
    /* region indicators are disjoint: Cov(w 1_i, w 1_j) = E[w^2 1_i] delta_ij - mu_i mu_j */
    double va = 0.0, vb = 0.0;
    for (int i = 0; i < g; i++)
        for (int j = 0; j < g; j++) {
            double ca = (i == j ? sm->a2[i] / n : 0.0) - A[i] * A[j];
            double cb = (i == j ? sm->b2[i] / m : 0.0) - B[i] * B[j];
            S[i][j] = ca / n + cb / m;
            va += ca / n;
            vb += cb / m;
        }
    tot[0] = ta, tot[1] = tb, var[0] = va, var[1] = vb;
    return g;
}

/* The numerical floor of the regions' difference: a relative error of size
 * res common to every region (a normalisation rounded once) and one of
 * each region (rounding that varies over the domain), both as variance,
 * each of the two sides' mean magnitude: S += res^2 (a a' + diag(a^2)).
 * Adding a positive semi-definite matrix only lowers the Wald statistic.
 * *total: the same floor's variance of the totals' difference. */
static void add_floor(const double A[MAX_GROUPS], const double B[MAX_GROUPS], double S[MAX_GROUPS][MAX_GROUPS],
                      int g, double res, double *total)
{
    double a[MAX_GROUPS], sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < g; i++) {
        a[i] = 0.5 * (fabs(A[i]) + fabs(B[i]));
        sum += a[i];
        sum2 += a[i] * a[i];
    }
    for (int i = 0; i < g; i++)
        for (int j = 0; j < g; j++)
            S[i][j] += res * res * (a[i] * a[j] + (i == j ? a[i] * a[i] : 0.0));
    *total = res * res * (sum * sum + sum2);
}

/* Samples a mean-based route needs for a 1% relative departure, when at n
 * its sampling variance is v_n and the floor's is v_floor (relative to the
 * squared integral), z the quantile sum: n v_n / ((0.01/z)^2 - v_floor),
 * never below the smallest check (1000); INFINITY when the floor alone
 * hides 1%. */
static double n_for_one_percent(double n, double v_n, double v_floor, double z)
{
    double room = (0.01 / z) * (0.01 / z) - v_floor;
    if (!(room > 0.0))
        return INFINITY;
    return fmax(n * v_n / room, 1000.0);
}

/* The integral of eval from the weights and from eval alone (check_run.h). */
void mcstat__check_report_albedos(run *r, const sums *sm)
{
    double A[MAX_GROUPS], B[MAX_GROUPS], D[MAX_GROUPS], S[MAX_GROUPS][MAX_GROUPS], tot[2], var[2];
    region_integrals(r, sm, A, B, D, S, tot, var);
    r->out->albedo = tot[0];
    r->out->albedo_se = sqrt(fmax(var[0], 0.0));
    r->out->albedo_eval = tot[1];
    r->out->albedo_eval_se = sqrt(fmax(var[1], 0.0));
}

static void route_integrals(run *r, const sums *sm, double level)
{
    mcstat_check_route_result *rr = &r->out->route[MCSTAT_CHECK_ROUTE_INTEGRALS];
    double n = (double)r->pl.n, m = (double)r->pl.n_eval;
    double A[MAX_GROUPS], B[MAX_GROUPS], D[MAX_GROUPS], S[MAX_GROUPS][MAX_GROUPS], tot[2], var[2];
    int g = region_integrals(r, sm, A, B, D, S, tot, var);
    double ta = tot[0], tb = tot[1], va = var[0], vb = var[1];
    if (r->out->heavy_tailed) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        rr->why = MCSTAT_CHECK_WHY_HEAVY_TAIL;
        return;
    }
    double v_floor;
    add_floor(A, B, S, g, r->resolution, &v_floor);
    rr->resolution = r->resolution;
    int df = 0;
    double t = wald(D, S, g, &df);
    rr->checked = (uint64_t)(n + m);
    rr->count = (uint64_t)df;
    if (df < 1) {
        rr->state = MCSTAT_CHECK_STATE_INVALID; /* eval is zero wherever either estimator looked */
        rr->why = MCSTAT_CHECK_WHY_NOTHING;
        return;
    }
    if (!ran_chisq(rr, t, df))
        return;
    rr->effect = tb != 0.0 ? (ta - tb) / tb : NAN;
    double z = mcstat__norm_quantile(level / 2, 1) + POWER_Z;
    double v = fmax(va + vb, 0.0);
    rr->detectable = tb > 0.0 ? z * sqrt(v + v_floor) / tb : NAN;
    rr->n_for_1pct = tb > 0.0 ? n_for_one_percent(n, v / (tb * tb), v_floor / (tb * tb), z) : NAN;
}

static void route_energy(run *r, const sums *sm, double level)
{
    mcstat_check_route_result *rr = &r->out->route[MCSTAT_CHECK_ROUTE_ENERGY];
    if (r->out->tail_index[0] < 2.0) { /* it reads the weights only */
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        rr->why = MCSTAT_CHECK_WHY_HEAVY_TAIL;
        return;
    }
    double mean = mcstat_moments_mean(&sm->all), sd = mcstat_moments_sd(&sm->all);
    double n = (double)sm->all.n;
    rr->checked = sm->all.n;
    rr->effect = mean - 1.0;
    rr->resolution = r->resolution;
    /* a phase function is normalised: its albedo is 1, not at most 1 */
    int exact = r->pl.kind == MCSTAT_CHECK_KIND_PHASE;
    rr->state = MCSTAT_CHECK_STATE_RAN;
    if (!(sd > 0.0) && isfinite(mean)) {
        /* constant weights (a sampler proportional to eval): no spread to test */
        rr->deterministic = 1;
        double tol = fmax(r->rtol, r->resolution);
        rr->reject = exact ? fabs(mean - 1.0) > tol : mean > 1.0 + tol;
        rr->count = rr->reject;
        rr->value[0] = mean;
        rr->value[1] = 1.0;
        return;
    }
    if (!isfinite(mean) || !isfinite(sd) || n < 2.0) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        rr->why = isfinite(mean) ? MCSTAT_CHECK_WHY_TOO_FEW : MCSTAT_CHECK_WHY_NUMERIC;
        return;
    }
    /* the t statistic of the mean weight against 1, the floor's relative
     * error of the albedo added to the mean's variance */
    double v_n = sd * sd / n, v_floor = r->resolution * r->resolution * fmax(mean * mean, 1.0);
    double t = (mean - 1.0) / sqrt(v_n + v_floor), p;
    if (mcstat_t_cdf(exact ? -fabs(t) : t, n - 1.0, !exact, &p) != MCSTAT_OK) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        rr->why = MCSTAT_CHECK_WHY_NUMERIC;
        return;
    }
    rr->statistic = t;
    rr->df = n - 1.0;
    rr->p_value = exact ? fmin(1.0, 2.0 * p) : p;
    double z = mcstat__norm_quantile(exact ? level / 2 : level, 1) + POWER_Z;
    rr->detectable = z * sqrt(v_n + v_floor);
    rr->n_for_1pct = n_for_one_percent(n, v_n, v_floor, z);
}

static void route_ks(run *r, double level)
{
    mcstat_check_route_result *rr = &r->out->route[MCSTAT_CHECK_ROUTE_KS];
    uint64_t na = r->n_keys_a, nb = r->n_keys_b;
    rr->checked = na + nb;
    if (r->w_breach || r->v_breach) {
        /* an envelope was exceeded: the kept points do not follow what they should */
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        for (int c = 0; c < 3; c++)
            rr->where[c] = c < r->pl.d.dims ? r->breach_x[c] : NAN;
        rr->value[0] = r->breach_v[0];
        rr->value[1] = r->breach_v[1];
        rr->count = (uint64_t)(r->w_breach ? 1 : 2);
        rr->why = MCSTAT_CHECK_WHY_ENVELOPE;
        return;
    }
    if (na < 50 || nb < 50) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        /* every weight and every eval() 0 (albedo 0, or no smooth part):
         * nothing to resample on either side */
        rr->why = !(r->w_envelope > 0.0) && !(r->v_largest > 0.0) ? MCSTAT_CHECK_WHY_NOTHING : MCSTAT_CHECK_WHY_TOO_FEW;
        return;
    }
    mcstat_ks_options ko;
    mcstat_ks_options_init(&ko);
    ko.weight = MCSTAT_KS_WEIGHT_CANNER;
    ko.critical = 0;
    uint64_t small = na < nb ? na : nb;
    if ((double)(small + 1) * (double)(na + nb + 1) <= 4e10) {
        ko.method = MCSTAT_METHOD_EXACT;
    } else {
        ko.method = MCSTAT_METHOD_SIMULATE;
        ko.n_sim = 2000;
        ko.seed = r->seed;
    }
    mcstat_result res;
    int st = mcstat_ks_test_2(r->s.keys_a, na, r->s.keys_b, nb, MCSTAT_TWO_SIDED, 0.5, &ko, &res);
    if (st != MCSTAT_OK) {
        rr->state = MCSTAT_CHECK_STATE_INVALID;
        rr->why = MCSTAT_CHECK_WHY_NUMERIC;
        return;
    }
    rr->state = MCSTAT_CHECK_STATE_RAN;
    rr->count = na;
    rr->statistic = res.statistic;
    rr->p_value = res.p_value;
    double ne = (double)na * (double)nb / (double)(na + nb);
    rr->effect = res.statistic / sqrt(ne); /* Canner-weighted sup distance of the two CDFs */
    /* about: the unweighted statistic's critical distance at this level
     * (Kolmogorov's limit), what is detected with probability ~0.5 */
    double c = sqrt(-0.5 * log(level / 2));
    rr->detectable = c / sqrt(ne);
    /* ne grows with n until a side reaches KS_MAX; a 1% distance needs
     * ne = 2 (c/0.01)^2, beyond what the cap allows */
    double need = 2.0 * (c / 0.01) * (c / 0.01), kept = (double)na / (double)r->pl.n;
    rr->n_for_1pct = need <= KS_MAX / 2.0 ? need / (kept > 0.0 ? kept : NAN) : INFINITY;
}

void mcstat__check_route(run *r, const sums *sm, int route, double level)
{
    switch (route) {
    case MCSTAT_CHECK_ROUTE_CELLS: route_cells(r, sm, level); break;
    case MCSTAT_CHECK_ROUTE_MASS: route_mass(r, sm, level); break;
    case MCSTAT_CHECK_ROUTE_INTEGRALS: route_integrals(r, sm, level); break;
    case MCSTAT_CHECK_ROUTE_ENERGY: route_energy(r, sm, level); break;
    case MCSTAT_CHECK_ROUTE_KS: route_ks(r, level); break;
    default: finish_deterministic(r, route); break;
    }
    mcstat_check_route_result *rr = &r->out->route[route];
    if (rr->state == MCSTAT_CHECK_STATE_INVALID && rr->why == MCSTAT_CHECK_WHY_NONE)
        rr->why = MCSTAT_CHECK_WHY_TOO_FEW; /* the routes' other exits: too little to test */
}
