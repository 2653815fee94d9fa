/*
 * est_stats.h - small statistics shared by the estimator tests: sample
 * moments, batch means (ERRATA 7) and a chi-squared goodness-of-fit test
 * with low-expectation cells pooled (p-value from libmcstat).
 */
#ifndef MCEST_TEST_STATS_H
#define MCEST_TEST_STATS_H

#include "mcstat.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>

typedef struct {
    double mean, sd, se;
} est_summary;

static inline est_summary summarize(const double *x, size_t n)
{
    mcstat_moments m;
    mcstat_moments_init(&m);
    mcstat_moments_add_array(&m, x, n);
    est_summary s;
    s.mean = mcstat_moments_mean(&m);
    s.sd = mcstat_moments_sd(&m);
    s.se = s.sd / sqrt((double)n);
    return s;
}

/* y[j] = mean of x[j*k .. j*k+k-1], j < n/k. Returns n/k. */
static inline size_t batch_means(const double *x, size_t n, size_t k, double *y)
{
    size_t m = n / k;
    for (size_t j = 0; j < m; j++) {
        double s = 0.0;
        for (size_t i = 0; i < k; i++)
            s += x[j * k + i];
        y[j] = s / (double)k;
    }
    return m;
}

/* Pearson's chi-squared statistic of observed counts against expected
 * probabilities (which need not sum to 1: the remainder is one more cell,
 * observed `rest`), cells with expectation < 5 pooled into one (merged into
 * the smallest regular cell if the pool itself is below 5).  Returns the
 * upper-tail p-value; *df receives the degrees of freedom. */
static inline double chisq_gof(const double *obs, const double *prob, size_t cells, double rest,
                               double n, int *df_out)
{
    double stat = 0.0, po = 0.0, pe = 0.0, ptot = 0.0;
    int df = 0;
    double small_o = 0.0, small_e = INFINITY, small_stat = 0.0;
    for (size_t c = 0; c < cells; c++)
        ptot += prob[c];
    double prob_rest = 1.0 - ptot;
    for (size_t c = 0; c <= cells; c++) {
        double o = c < cells ? obs[c] : rest;
        double e = (c < cells ? prob[c] : prob_rest) * n;
        if (c == cells && e <= 0.0 && o == 0.0)
            continue;
        if (e < 5.0) {
            po += o;
            pe += e;
            continue;
        }
        double t = (o - e) * (o - e) / e;
        stat += t;
        df++;
        if (e < small_e)
            small_e = e, small_o = o, small_stat = t;
    }
    if (pe >= 5.0) {
        stat += (po - pe) * (po - pe) / pe;
        df++;
    } else if (pe > 0.0 || po > 0.0) {
        if (isfinite(small_e)) { /* merge the pool into the smallest cell */
            stat -= small_stat;
            double o = small_o + po, e = small_e + pe;
            stat += (o - e) * (o - e) / e;
        } else {
            stat = INFINITY;
        }
    }
    df -= 1;
    *df_out = df;
    if (df < 1)
        return 1.0;
    double p;
    if (mcstat_chisq_cdf(stat, (double)df, 1, &p) != MCSTAT_OK)
        return 0.0;
    return p;
}

#endif
