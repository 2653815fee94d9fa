/*
 * rows.c - one test per row of a matrix: the per-pixel case (an image whose
 * every pixel holds k secondary estimates).
 *
 * Each row goes through exactly the code of the single-sample call, so row i
 * of a batch is bit for bit mcstat_*_test_* on row i.  What a batch adds:
 * critical values are reused between rows of equal degrees of freedom (a
 * t_1 or var test over rows of equal length solves its quantiles once, not
 * once per row), and MCSTAT_ROWS_NO_INTERVALS skips them altogether.
 * Nothing allocates: the moments live on the stack, the caller owns out[]
 * and status[], and disjoint row ranges may run on different threads.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

static int check_rows(const double *x, size_t rows, unsigned flags, const mcstat_result *out,
                      const int32_t *status)
{
    (void)status;
    if (rows > 0 && (!x || !out))
        return MCSTAT_EINVAL;
    if (flags & ~(unsigned)(MCSTAT_ROWS_NO_INTERVALS | MCSTAT_ROWS_OMIT_NAN))
        return MCSTAT_EINVAL;
    return MCSTAT_OK;
}

static int row_moments(const double *x, size_t n, unsigned flags, mcstat_moments *m)
{
    mcstat_moments_init(m);
    if (flags & MCSTAT_ROWS_OMIT_NAN)
        return mcstat_moments_add_array_omit_nan(m, x, n, NULL);
    return mcstat_moments_add_array(m, x, n);
}

/* Records row i's status; a failed row's result is cleared (NaN fields). */
static void finish_row(int st, size_t i, mcstat_result *out, int32_t *status, int *first)
{
    if (st) {
        mcstat__result_clear(&out[i]);
        if (*first == MCSTAT_OK)
            *first = st;
    }
    if (status)
        status[i] = st;
}

/* The tests on accumulators, as the row loops drive them (internal.h). */
typedef int (*test_1_fn)(const mcstat_moments *x, double null_value, int alternative, double alpha,
                         mcstat_qcache *qc, mcstat_result *out);
typedef int (*test_2_fn)(const mcstat_moments *x, const mcstat_moments *y, double null_value, int alternative,
                         double alpha, mcstat_qcache *qc, mcstat_result *out);

static int rows_1(test_1_fn test, const double *x, size_t rows, size_t n, size_t x_stride, double null_value,
                  int alternative, double alpha, unsigned flags, mcstat_result *out, int32_t *status)
{
    int st = check_rows(x, rows, flags, out, status);
    if (st)
        return st;
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    mcstat_qcache *q = (flags & MCSTAT_ROWS_NO_INTERVALS) ? NULL : &qc;
    int first = MCSTAT_OK;
    for (size_t i = 0; i < rows; i++) {
        mcstat_moments m;
        st = row_moments(x + i * x_stride, n, flags, &m);
        if (!st)
            st = test(&m, null_value, alternative, alpha, q, &out[i]);
        finish_row(st, i, out, status, &first);
    }
    return first;
}

static int rows_2(test_2_fn test, const double *x, size_t nx, size_t x_stride, const double *y, size_t ny,
                  size_t y_stride, size_t rows, double null_value, int alternative, double alpha, unsigned flags,
                  mcstat_result *out, int32_t *status)
{
    int st = check_rows(x, rows, flags, out, status);
    if (st || (rows > 0 && !y))
        return st ? st : MCSTAT_EINVAL;
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    mcstat_qcache *q = (flags & MCSTAT_ROWS_NO_INTERVALS) ? NULL : &qc;
    int first = MCSTAT_OK;
    for (size_t i = 0; i < rows; i++) {
        mcstat_moments mx, my;
        st = row_moments(x + i * x_stride, nx, flags, &mx);
        if (!st)
            st = row_moments(y + i * y_stride, ny, flags, &my);
        if (!st)
            st = test(&mx, &my, null_value, alternative, alpha, q, &out[i]);
        finish_row(st, i, out, status, &first);
    }
    return first;
}

int mcstat_t_test_1_matrix(const double *x, size_t n, size_t x_stride, size_t rows, double mu0, int alternative,
                           double alpha, unsigned flags, mcstat_result *out, int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return rows_1(mcstat__t_test_1, x, rows, n, x_stride, mu0, alternative, alpha, flags, out, status);
}

int mcstat_var_test_1_matrix(const double *x, size_t n, size_t x_stride, size_t rows, double sigma2,
                             int alternative, double alpha, unsigned flags, mcstat_result *out, int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return rows_1(mcstat__var_test_1, x, rows, n, x_stride, sigma2, alternative, alpha, flags, out, status);
}

int mcstat_t_test_2_matrix(const double *x, size_t nx, size_t x_stride, const double *y, size_t ny,
                           size_t y_stride, size_t rows, double mu0, int alternative, double alpha, unsigned flags,
                         mcstat_result *out, int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return rows_2(mcstat__t_test_2, x, nx, x_stride, y, ny, y_stride, rows, mu0, alternative, alpha, flags, out,
                  status);
}

int mcstat_var_test_2_matrix(const double *x, size_t nx, size_t x_stride, const double *y, size_t ny,
                             size_t y_stride, size_t rows, double ratio, int alternative, double alpha,
                           unsigned flags, mcstat_result *out, int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return rows_2(mcstat__var_test_2, x, nx, x_stride, y, ny, y_stride, rows, ratio, alternative, alpha, flags,
                  out, status);
}

/* ---- rows of accumulators (the per-pixel arrays of moments_rows.c) --------
 * The same loop without the data pass: row i is x[i] (and y[i]). */

static int check_moments_rows(const mcstat_moments *x, const mcstat_moments *y, int two, size_t rows,
                              unsigned flags, const mcstat_result *out)
{
    if (rows > 0 && (!x || !out || (two && !y)))
        return MCSTAT_EINVAL;
    if (flags & ~(unsigned)MCSTAT_ROWS_NO_INTERVALS)
        return MCSTAT_EINVAL;
    return MCSTAT_OK;
}

static int moments_rows(test_1_fn test1, test_2_fn test2, const mcstat_moments *x, const mcstat_moments *y,
                        size_t rows, double null_value, int alternative, double alpha, unsigned flags,
                        mcstat_result *out, int32_t *status)
{
    int st = check_moments_rows(x, y, test2 != NULL, rows, flags, out);
    if (st)
        return st;
    mcstat_qcache qc;
    mcstat__qcache_init(&qc);
    mcstat_qcache *q = (flags & MCSTAT_ROWS_NO_INTERVALS) ? NULL : &qc;
    int first = MCSTAT_OK;
    for (size_t i = 0; i < rows; i++) {
        st = test2 ? test2(&x[i], &y[i], null_value, alternative, alpha, q, &out[i])
                   : test1(&x[i], null_value, alternative, alpha, q, &out[i]);
        finish_row(st, i, out, status, &first);
    }
    return first;
}

int mcstat_t_test_1_moments_rows(const mcstat_moments *x, size_t rows, double mu0, int alternative, double alpha,
                                 unsigned flags, mcstat_result *out, int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return moments_rows(mcstat__t_test_1, NULL, x, NULL, rows, mu0, alternative, alpha, flags, out, status);
}

int mcstat_t_test_2_moments_rows(const mcstat_moments *x, const mcstat_moments *y, size_t rows, double mu0,
                                 int alternative, double alpha, unsigned flags, mcstat_result *out,
                                 int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return moments_rows(NULL, mcstat__t_test_2, x, y, rows, mu0, alternative, alpha, flags, out, status);
}

int mcstat_var_test_1_moments_rows(const mcstat_moments *x, size_t rows, double sigma2, int alternative,
                                   double alpha, unsigned flags, mcstat_result *out, int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return moments_rows(mcstat__var_test_1, NULL, x, NULL, rows, sigma2, alternative, alpha, flags, out, status);
}

int mcstat_var_test_2_moments_rows(const mcstat_moments *x, const mcstat_moments *y, size_t rows, double ratio,
                                   int alternative, double alpha, unsigned flags, mcstat_result *out,
                                   int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    return moments_rows(NULL, mcstat__var_test_2, x, y, rows, ratio, alternative, alpha, flags, out, status);
}
