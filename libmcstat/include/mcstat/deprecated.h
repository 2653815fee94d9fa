/*
 * mcstat/deprecated.h - the names this release replaced, kept so that older
 * code still builds and links.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_DEPRECATED_FAMILY_H
#define MCSTAT_DEPRECATED_FAMILY_H

#include "tests.h"
#include "pixels.h"
#include "sequential.h"
#ifndef MCSTAT_NO_EXPERIMENTAL
#include "diagnostics.h"
#include "gof.h"
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 14. Deprecated names.                                                  */
/* The names this release replaced, one form per family: old -> new.        */
/* They still link (the ABI keeps every exported symbol of its SOVERSION)   */
/* and give bit-identical results; MCSTAT_DEPRECATED names the replacement. */
/* ======================================================================== */
/* renderer checks: MCSTAT_DOMAIN_*, MCSTAT_WEIGHT_* and MCSTAT_ROUTE_RAN,
 * _SKIPPED, _INVALID became MCSTAT_CHECK_DOMAIN_*, MCSTAT_CHECK_WEIGHT_*
 * and MCSTAT_CHECK_STATE_*; the old names stay in their enums
 * (mcstat/check.h), so that they keep their enum's type. */

/* sizes: mcstat_sizeof_<thing> */
MCSTAT_DEPRECATED("mcstat_sizeof_moments_bytes") MCSTAT_API size_t mcstat_moments_bytes(void);
MCSTAT_DEPRECATED("mcstat_sizeof_gof_options") MCSTAT_API size_t mcstat_sizeof_chisq_options(void);

#ifndef MCSTAT_NO_EXPERIMENTAL
/* diagnostics: the mcstat_diag_ stem */
MCSTAT_DEPRECATED("mcstat_diag_compute")
MCSTAT_API int mcstat_diagnose(const double *x, size_t n, const mcstat_diag_options *opt, mcstat_diagnostics *out);
MCSTAT_DEPRECATED("mcstat_diag_tail_index")
MCSTAT_API int mcstat_tail_index(const double *x, size_t n, size_t tail_k, double index[2]);
MCSTAT_DEPRECATED("mcstat_diag_t_size")
MCSTAT_API int mcstat_t_size_edgeworth(double skewness, double kurtosis, uint64_t k, uint64_t m, double alpha,
                                       double size[2]);
MCSTAT_DEPRECATED("mcstat_diag_batch_size")
MCSTAT_API int mcstat_batch_size_recommend(double skewness, double kurtosis, uint64_t m, double alpha,
                                           double tolerance, uint64_t *k);

/* goodness of fit: the mcstat_gof_ stem (mcstat_chisq_ is the distribution) */
/* 0.1.0's name of the options, as a typedef and as a struct tag alike (a
 * macro, so that `struct mcstat_chisq_options` still names them) */
#define mcstat_chisq_options mcstat_gof_options
#define mcstat_chisq_expected mcstat_gof_expected
#define MCSTAT_CHISQ_PROBABILITIES MCSTAT_GOF_PROBABILITIES
#define MCSTAT_CHISQ_COUNTS MCSTAT_GOF_COUNTS
#define MCSTAT_CHISQ_DEFAULT_MIN_EXPECTED MCSTAT_GOF_DEFAULT_MIN_EXPECTED
#define MCSTAT_CHISQ_OPTIONS_INIT MCSTAT_GOF_OPTIONS_INIT
#define MCSTAT_CHISQ_OPTIONS_SIZE_0_1 MCSTAT_GOF_OPTIONS_SIZE_0_1
MCSTAT_DEPRECATED("mcstat_gof_options_init_size")
MCSTAT_API int mcstat_chisq_options_init_size(mcstat_chisq_options *opt, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_GOF_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_chisq_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_DEPRECATED("mcstat_gof_options_init")
MCSTAT_API int(mcstat_chisq_options_init)(mcstat_chisq_options *opt);
#define mcstat_chisq_options_init(opt) mcstat_chisq_options_init_size((opt), sizeof *(opt))
MCSTAT_DEPRECATED("mcstat_gof_default_min_expected") MCSTAT_API double mcstat_chisq_default_min_expected(void);
MCSTAT_DEPRECATED("mcstat_gof_chisq_test")
MCSTAT_API int mcstat_chisq_gof(const double *observed, const double *expected, size_t k,
                                const mcstat_chisq_options *opt, double alpha, mcstat_result *out);

/* sequential tests, two samples: mcstat_seq_push_2_<form>, as the tests'
 * mcstat_<test>_test_2_<form> */
MCSTAT_DEPRECATED("mcstat_seq_push_2_moments")
MCSTAT_API int mcstat_seq_push_moments_2(mcstat_seq *s, const mcstat_moments *bx, const mcstat_moments *by);
MCSTAT_DEPRECATED("mcstat_seq_push_2_array")
MCSTAT_API int mcstat_seq_push_array_2(mcstat_seq *s, const double *x, size_t nx, const double *y, size_t ny);
#endif /* MCSTAT_NO_EXPERIMENTAL */

/* row-wise tests: mcstat_<test>_test_<k>_matrix, each matrix (x, n, stride)
 * then rows.  The one-sample _rows calls put rows before n: swapping the
 * two compiles and answers for another matrix. */
MCSTAT_DEPRECATED("mcstat_t_test_1_matrix (rows moves after x_stride)")
MCSTAT_API int mcstat_t_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride, double mu0,
                                    int alternative, double alpha, unsigned flags, mcstat_result *out,
                                    int32_t *status);
MCSTAT_DEPRECATED("mcstat_t_test_2_matrix (same arguments)")
MCSTAT_API int mcstat_t_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y,
                                    size_t ny, size_t y_stride, size_t rows, double mu0, int alternative,
                                    double alpha, unsigned flags, mcstat_result *out, int32_t *status);
MCSTAT_DEPRECATED("mcstat_var_test_1_matrix (rows moves after x_stride)")
MCSTAT_API int mcstat_var_test_1_rows(const double *x, size_t rows, size_t n, size_t x_stride,
                                      double sigma2, int alternative, double alpha, unsigned flags,
                                      mcstat_result *out, int32_t *status);
MCSTAT_DEPRECATED("mcstat_var_test_2_matrix (same arguments)")
MCSTAT_API int mcstat_var_test_2_rows(const double *x, size_t nx, size_t x_stride, const double *y,
                                      size_t ny, size_t y_stride, size_t rows, double ratio,
                                      int alternative, double alpha, unsigned flags, mcstat_result *out,
                                      int32_t *status);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_DEPRECATED_FAMILY_H */
