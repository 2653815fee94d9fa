/*
 * ref_accuracy.h - the accuracy table tests/data/accuracy.tsv (written by
 * tools/refgen/make_accuracy.py, explained in libmcstat/ACCURACY.md): the
 * bound each (function, domain) is held to, and the error measures it was
 * measured with.
 */
#ifndef MCSTAT_TEST_REF_ACCURACY_H
#define MCSTAT_TEST_REF_ACCURACY_H

#include "ref_tsv.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef MCSTAT_TEST_DATA_DIR
#error "MCSTAT_TEST_DATA_DIR must name tests/data"
#endif

#define ACC_MAX_ROWS 512

typedef struct {
    char func[32];
    char domain[128];
    int cases;     /* cases the table was measured on */
    double bound;  /* what the tests enforce */
    int failed;    /* cases the library failed (error status, non-finite) when measured */
    int seen;      /* cases checked by this run */
    int nfail;     /* failed in this run */
    double worst;  /* largest error seen by this run */
} acc_row;

static acc_row acc_rows[ACC_MAX_ROWS];
static int acc_nrows = -1;

static void acc_read_row(char **f, int nf, void *ctx)
{
    (void)ctx;
    if (nf < 7 || acc_nrows >= ACC_MAX_ROWS)
        return;
    acc_row *r = &acc_rows[acc_nrows++];
    snprintf(r->func, sizeof r->func, "%s", f[0]);
    snprintf(r->domain, sizeof r->domain, "%s", f[1]);
    r->cases = atoi(f[2]);
    r->bound = strtod(f[5], NULL);
    r->failed = atoi(f[6]);
    r->seen = 0;
    r->nfail = 0;
    r->worst = 0.0;
}

/* The row of (func, domain); exits when the table or the row is missing (a
 * test must not pass by finding nothing to check). */
static inline acc_row *acc_find(const char *func, const char *domain)
{
    if (acc_nrows < 0) {
        acc_nrows = 0;
        if (tsv_read(MCSTAT_TEST_DATA_DIR "/accuracy.tsv", acc_read_row, NULL) < 1) {
            fprintf(stderr, "cannot read %s\n", MCSTAT_TEST_DATA_DIR "/accuracy.tsv");
            exit(2);
        }
    }
    for (int i = 0; i < acc_nrows; i++)
        if (!strcmp(acc_rows[i].func, func) && !strcmp(acc_rows[i].domain, domain))
            return &acc_rows[i];
    fprintf(stderr, "accuracy.tsv has no row %s / %s (rerun tools/refgen/make_accuracy.py)\n", func, domain);
    exit(2);
}

static inline double acc_bound(const char *func, const char *domain)
{
    return acc_find(func, domain)->bound;
}

/* Relative error of a probability, quantile or p-value. */
static inline double acc_rel(double got, double ref)
{
    if (got == ref)
        return 0.0;
    if (!isfinite(got))
        return INFINITY;
    return fabs(got - ref) / fabs(ref);
}

/* Error of a log probability: relative error of p where |log p| < 1, of
 * log p beyond. */
static inline double acc_log_err(double got, double ref)
{
    if (got == ref)
        return 0.0;
    if (!isfinite(got))
        return INFINITY;
    return fabs(got - ref) / fmax(1.0, fabs(ref));
}

#endif
