/*
 * deprecated.c - the names this release replaced, kept as thin wrappers so
 * that binaries and sources built against them still link and give the
 * same results (the shared library must not lose an exported symbol within
 * a SOVERSION; libmcstat/abi/).  Each calls its replacement; nothing here
 * computes anything.  mcstat.h marks them MCSTAT_DEPRECATED.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

/* ---- sizes: one form, mcstat_sizeof_<thing> ----------------------------- */
size_t mcstat_moments_bytes(void) { return mcstat_sizeof_moments_bytes(); }
size_t mcstat_sizeof_chisq_options(void) { return mcstat_sizeof_gof_options(); }

/* ---- options initialisers of 0.1.0: its callers' structs are 0.1.0's size
 * (the names are parenthesised against the header's macros) ------------- */
int(mcstat_diag_options_init)(mcstat_diag_options *opt)
{
    return mcstat_diag_options_init_size(opt, MCSTAT_DIAG_OPTIONS_SIZE_0_1);
}

int(mcstat_chisq_options_init)(mcstat_chisq_options *opt)
{
    return mcstat_gof_options_init_size(opt, MCSTAT_GOF_OPTIONS_SIZE_0_1);
}

/* ---- sequential tests, two samples: mcstat_seq_push_2_<form> ----------- */
int mcstat_seq_push_moments_2(mcstat_seq *s, const mcstat_moments *bx, const mcstat_moments *by)
{
    return mcstat_seq_push_2_moments(s, bx, by);
}

int mcstat_seq_push_array_2(mcstat_seq *s, const double *x, size_t nx, const double *y, size_t ny)
{
    return mcstat_seq_push_2_array(s, x, nx, y, ny);
}

/* ---- goodness of fit: the mcstat_gof_ stem ------------------------------ */
int mcstat_chisq_options_init_size(mcstat_chisq_options *opt, size_t size)
{
    return mcstat_gof_options_init_size(opt, size);
}

double mcstat_chisq_default_min_expected(void) { return mcstat_gof_default_min_expected(); }

int mcstat_chisq_gof(const double *observed, const double *expected, size_t k, const mcstat_chisq_options *opt,
                     double alpha, mcstat_result *out)
{
    return mcstat_gof_chisq_test(observed, expected, k, opt, alpha, out);
}

/* ---- diagnostics: the mcstat_diag_ stem --------------------------------- */
int mcstat_diagnose(const double *x, size_t n, const mcstat_diag_options *opt, mcstat_diagnostics *out)
{
    return mcstat_diag_compute(x, n, opt, out);
}

int mcstat_tail_index(const double *x, size_t n, size_t tail_k, double index[2])
{
    return mcstat_diag_tail_index(x, n, tail_k, index);
}

int mcstat_t_size_edgeworth(double skewness, double kurtosis, uint64_t k, uint64_t m, double alpha, double size[2])
{
    return mcstat_diag_t_size(skewness, kurtosis, k, m, alpha, size);
}

int mcstat_batch_size_recommend(double skewness, double kurtosis, uint64_t m, double alpha, double tolerance,
                                uint64_t *k)
{
    return mcstat_diag_batch_size(skewness, kurtosis, m, alpha, tolerance, k);
}

/* ---- row-wise tests: one argument order, each matrix (x, n, stride), then
 * rows; the one-sample calls had rows before n ------------------------------ */
int mcstat_t_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride, double mu0, int alternative,
                         double alpha, unsigned flags, mcstat_result *out, int32_t *status)
{
    return mcstat_t_test_1_matrix(x, n, x_stride, rows, mu0, alternative, alpha, flags, out, status);
}

int mcstat_var_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride, double sigma2,
                           int alternative, double alpha, unsigned flags, mcstat_result *out, int32_t *status)
{
    return mcstat_var_test_1_matrix(x, n, x_stride, rows, sigma2, alternative, alpha, flags, out, status);
}

int mcstat_t_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y, size_t ny,
                         size_t y_stride, size_t rows, double mu0, int alternative, double alpha, unsigned flags,
                         mcstat_result *out, int32_t *status)
{
    return mcstat_t_test_2_matrix(x, nx, x_stride, y, ny, y_stride, rows, mu0, alternative, alpha, flags, out,
                                  status);
}

int mcstat_var_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y, size_t ny,
                           size_t y_stride, size_t rows, double ratio, int alternative, double alpha,
                           unsigned flags, mcstat_result *out, int32_t *status)
{
    return mcstat_var_test_2_matrix(x, nx, x_stride, y, ny, y_stride, rows, ratio, alternative, alpha, flags,
                                    out, status);
}
