/*
 * mcstat/power.h - power and sample size (experimental).
 *
 * Included by mcstat.h (unless MCSTAT_NO_EXPERIMENTAL); an experimental
 * family: define MCSTAT_EXPERIMENTAL before including it (base.h,
 * MCSTAT_EXPERIMENTAL_API).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_POWER_FAMILY_H
#define MCSTAT_POWER_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------ */
/* 11. Power and sample size.                              (experimental) */
/* Given all but one of n, effect, alpha and power, mcstat_power_solve finds */
/* the missing one (as R's power.t.test and statsmodels' solve_power); n is */
/* the smallest integer whose power reaches the target.  The tests and what */
/* `effect` means (the statistic's distribution under the alternative):     */
/*   T_1    one-sample t: d = (mean - mu0)/sd; noncentral t, df n-1,         */
/*          ncp sqrt(n) d                                                    */
/*   T_2    two-sample t with n per group and a common sd (R's               */
/*          power.t.test type = "two.sample"): d = (mean_x - mean_y)/sd;     */
/*          noncentral t, df 2(n-1), ncp sqrt(n/2) d                          */
/*   WELCH  Welch's t with nx = n, ny = n_ratio n, sd_y = sd_ratio sd_x:     */
/*          d = (mean_x - mean_y)/sd_x; noncentral t with the Welch-         */
/*          Satterthwaite df of the true variances, ncp d/sqrt(1/nx +        */
/*          sd_ratio^2/ny) (an approximation, checked by simulation in the  */
/*          tests; ny may be fractional: round it up)                        */
/*   VAR_1  chi-squared test: rho = sigma^2/sigma0^2 > 0; exact, the         */
/*          statistic is rho chi^2(n-1)                                      */
/*   VAR_2  F test with nx = n, ny = n_ratio n: rho = (var_x/var_y)/ratio0;  */
/*          exact, the statistic is rho F(nx-1, ny-1)                        */
/* alternative as in the tests (LESS: the effect is negative, rho < 1).     */
/* Two-sided: strict = 1 (default) counts rejections in both tails, the     */
/* true rejection probability (R's strict = TRUE); strict = 0 only the tail */
/* the effect points to (R's default).  Solving for the effect gives the    */
/* solution on the side the alternative names (d > 0, rho > 1 when two-    */
/* sided).  Accuracy: chi-squared and F power to ~1e-13 relative; the      */
/* noncentral t is R's pnt (libRmath), about 1e-12 absolute (not relative:  */
/* a power below 1e-12 is noise), and for |ncp| > 37.62 or df > 4e5 it is  */
/* Abramowitz & Stegun 26.7.10's normal approximation, whose error is      */
/* O(1/df): negligible at df > 4e5; at |ncp| > 37.62 the power is 1 to     */
/* double precision from df = 2 on (SciPy's nct: 1 - 2.5e-31 at df 2, ncp */
/* 38), but at df = 1 (n = 2) it is off by 2e-3 (0.99918 for 0.99713).    */
/* pnt is called so that it never prints (see                               */
/* src/noncentral.c).                                                        */
/* ------------------------------------------------------------------------ */
/* The power enum names the designs, not the tests: it has the pooled
 * two-sample t (T_2) that mcstat_test lacks, so its values differ from
 * enum mcstat_test's (MCSTAT_POWER_VAR_1 is 4, MCSTAT_TEST_VAR_1 is 3).
 * Both numberings are ABI and stay; never pass one enum's value as the
 * other's. */
enum mcstat_power_test {
    MCSTAT_POWER_T_1 = 1,
    MCSTAT_POWER_T_2 = 2,
    MCSTAT_POWER_WELCH = 3,
    MCSTAT_POWER_VAR_1 = 4,
    MCSTAT_POWER_VAR_2 = 5
};
enum mcstat_power_unknown {
    MCSTAT_POWER_SOLVE_POWER = 0,
    MCSTAT_POWER_SOLVE_N = 1,
    MCSTAT_POWER_SOLVE_EFFECT = 2,
    MCSTAT_POWER_SOLVE_ALPHA = 3,
    /* n as a real number, the root of power(n) = target (R's power.t.test's
     * n; SOLVE_N gives the smallest integer reaching the target, this
     * rounded up when it is not one); out->power is left at the target */
    MCSTAT_POWER_SOLVE_N_EXACT = 4
};

/* Grows by appending fields ("Conventions", compatibility): always start
 * from the initialiser (n, effect and power start at 0: unset, invalid
 * until given). */
typedef struct mcstat_power_options {
    uint32_t size;       /* sizeof(mcstat_power_options): set by the initialiser */
    int32_t test;        /* enum mcstat_power_test; default T_1 */
    int32_t alternative; /* enum mcstat_alternative; default TWO_SIDED */
    int32_t strict;      /* two-sided: 1 both tails (default), 0 the effect's tail */
    double n;            /* observations (per group for T_2, of x for WELCH and VAR_2), >= 2 */
    double n_ratio;      /* WELCH, VAR_2: ny = n_ratio n (ny >= 2); default 1 */
    double sd_ratio;     /* WELCH: sd_y / sd_x > 0; default 1 */
    double effect;       /* d (t tests, finite) or rho (variance tests, > 0) */
    double alpha;        /* significance level in (0, 1); default 0.05 */
    double power;        /* in (0, 1) */
    double reserved[4];  /* zero */
} mcstat_power_options;

#define MCSTAT_POWER_OPTIONS_INIT \
    {sizeof(mcstat_power_options), MCSTAT_POWER_T_1, MCSTAT_TWO_SIDED, 1, 0.0, 1.0, 1.0, 0.0, \
     0.05, 0.0, {0.0, 0.0, 0.0, 0.0}}

/* sizeof(mcstat_power_options) in each release that changed it. */
#define MCSTAT_POWER_OPTIONS_SIZE_0_1 96u
/* Sets the first `size` bytes of *o to MCSTAT_POWER_OPTIONS_INIT, with
 * o->size = size: `size` is sizeof(mcstat_power_options) as the caller
 * compiled it (FFI callers: their struct's size), so nothing beyond the
 * caller's struct is written.  MCSTAT_EINVAL (nothing written) for NULL or
 * a size no release had. */
MCSTAT_EXPERIMENTAL_API int mcstat_power_options_init_size(mcstat_power_options *o, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_POWER_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_power_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_EXPERIMENTAL_API int(mcstat_power_options_init)(mcstat_power_options *o);
#define mcstat_power_options_init(o) mcstat_power_options_init_size((o), sizeof *(o))
MCSTAT_EXPERIMENTAL_API size_t mcstat_sizeof_power_options(void);
/* *power <- the power at o->n, o->effect, o->alpha (o->power is ignored).
 * MCSTAT_EINVAL (NULL, bad enum or size, n < 2, ny < 2, an effect out of
 * its domain, alpha outside (0, 1)), MCSTAT_ENUMERIC. */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_power_compute(const mcstat_power_options *o, double *power);
/* *out <- *o with the field named by `unknown` (enum mcstat_power_unknown)
 * solved for; the other three must be valid (the unknown's field is
 * ignored); out receives o->size bytes, the caller's version of the
 * struct (out may equal o).  Solving for n also sets out->power to the
 * power at that n (>= the target).  MCSTAT_EINVAL as above, and when no
 * value reaches the power (an effect of 0; a power at or below what alpha
 * alone gives; n beyond 1e15); MCSTAT_ENUMERIC. */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_power_solve(const mcstat_power_options *o, int unknown,
                                  mcstat_power_options *out);
/* R's print.power.htest block ("Two-sample t test power calculation", the
 * named values aligned, NOTE lines) for a solved *o, into buf as
 * mcstat_result_format does.  MCSTAT_EINVAL, MCSTAT_EBUFSIZE. */
MCSTAT_NODISCARD MCSTAT_EXPERIMENTAL_API int mcstat_power_format(const mcstat_power_options *o, char *buf, size_t size,
                                   size_t *length);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_POWER_FAMILY_H */
