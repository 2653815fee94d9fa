/*
 * mcstat/tests.h - the tests and their result: mcstat_result; t, chi-
 * squared, F, efficiency, Kolmogorov-Smirnov.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_TESTS_FAMILY_H
#define MCSTAT_TESTS_FAMILY_H

#include "moments.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 3. The tests and their result.                                         */
/* Every test writes an mcstat_result: statistic, p-value, confidence       */
/* interval, critical values, the reject flag and the paper's three-way     */
/* decision; mcstat_result_format prints R's block.  The t, chi-squared and */
/* F tests come on arrays and on accumulators (_moments); the               */
/* Kolmogorov-Smirnov test needs the values themselves.  The equivalence   */
/* tests (mcstat/equivalence.h) and goodness of fit (mcstat/gof.h) fill the */
/* same struct.                                                             */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Test results.                                                             */
/* A plain struct filled by every test.  Fields that do not apply are NaN    */
/* (df[1] of a t test) or +-Inf (the open end of a one-sided confidence      */
/* interval or the missing critical value of a one-sided test).              */
/* ------------------------------------------------------------------------ */
enum mcstat_test {
    MCSTAT_TEST_T_1 = 1,   /* one-sample t */
    MCSTAT_TEST_T_2 = 2,   /* Welch two-sample t */
    MCSTAT_TEST_VAR_1 = 3, /* one-sample chi-squared test on the variance */
    MCSTAT_TEST_VAR_2 = 4, /* two-sample F test on the ratio of variances */
    MCSTAT_TEST_KS_2 = 5,  /* two-sample Kolmogorov-Smirnov, unweighted or with Canner's weight */
    MCSTAT_TEST_EQUIV_1 = 6, /* one-sample equivalence (TOST), mcstat_equivalence_test_1 */
    MCSTAT_TEST_EQUIV_2 = 7, /* Welch two-sample equivalence (TOST), mcstat_equivalence_test_2 */
    MCSTAT_TEST_BINOM = 8,   /* exact binomial test (also the battery meta-test) */
    MCSTAT_TEST_CHISQ_GOF = 9, /* Pearson's chi-squared goodness of fit of cell counts */
    MCSTAT_TEST_T_2_POOLED = 10, /* Student's two-sample t, pooled variance */
    MCSTAT_TEST_T_PAIRED = 11,   /* paired t (one-sample t on the differences) */
    MCSTAT_TEST_EFFICIENCY = 12, /* ratio of two estimators' efficiencies, mcstat_efficiency_test */
    MCSTAT_TEST_SEQ_MEAN_1 = 13, /* sequential (anytime-valid) tests, mcstat/sequential.h */
    MCSTAT_TEST_SEQ_MEAN_2 = 14,
    MCSTAT_TEST_SEQ_VAR_1 = 15,
    MCSTAT_TEST_SEQ_VAR_2 = 16
};

enum mcstat_method {
    MCSTAT_METHOD_ANALYTIC = 0,  /* p-value from the statistic's exact null distribution (t, chi^2, F) */
    MCSTAT_METHOD_AUTO = 1,      /* (K-S option only) let the test choose; results never carry it */
    MCSTAT_METHOD_EXACT = 2,     /* exact permutation distribution (K-S: lattice paths) */
    MCSTAT_METHOD_SIMULATE = 3,  /* Monte Carlo: p_value_se > 0 */
    MCSTAT_METHOD_ASYMPTOTIC = 4 /* a large-sample approximation */
};

struct mcstat_result {
    int32_t test;          /* enum mcstat_test */
    int32_t method;        /* enum mcstat_method: how the p-value was obtained */
    int32_t alternative;   /* enum mcstat_alternative */
    int32_t reject;        /* 1 if H0 is rejected at level alpha against `alternative` */
    int32_t decision;      /* the paper's three-way outcome: MCSTAT_DECISION_LESS (-1),
                              _EQUAL (0), _GREATER (+1) */
    /* Per-test integer outputs, 0 for tests that set none; read only those of
     * `test`.  reserved_i is 0.1.0's name of the same storage. */
    MCSTAT_ANONYMOUS union {
        int32_t reserved_i[3];
        struct {
            int32_t ks_weight;         /* KS_2: enum mcstat_ks_weight */
            int32_t chisq_cells;       /* CHISQ_GOF: cells after pooling */
            int32_t chisq_n_estimated; /* CHISQ_GOF: parameters estimated (n_estimated) */
        };
        struct {
            int32_t seq_state;         /* SEQ_*: MCSTAT_SEQ_CONTINUE or MCSTAT_SEQ_DECIDED */
            int32_t seq_hold;          /* SEQ_*: why no decision is allowed yet (MCSTAT_SEQ_HOLD_*) */
            int32_t seq_unused_;
        };
        struct {
            int32_t eff_batches_x;     /* EFFICIENCY: timed batches of x (saturates at INT32_MAX) */
            int32_t eff_batches_y;     /* EFFICIENCY: timed batches of y */
        };
    };
    uint64_t n[2];         /* sample sizes (n[1] = 0 for one-sample tests) */
    double statistic;      /* t, X-squared or F */
    double df[2];          /* degrees of freedom (df[1] NaN unless F) */
    double p_value;        /* for `alternative` */
    double p_value_se;     /* Monte Carlo standard error of p_value; 0 when exact */
    double conf_int[2];    /* (1 - alpha) confidence interval for the tested parameter */
    double estimate[2];    /* mean of x (,mean of y); variance of x; ratio of variances */
    double null_value;     /* mu0, mu0 (difference), sigma0^2 or ratio under H0 */
    double alpha;          /* significance level used for reject/decision/critical/conf_int */
    double critical[2];    /* reject when statistic < critical[0] or > critical[1] */
    double std_error;      /* standard error of the estimate (t tests); NaN otherwise */
    /* Per-test outputs (described with each test below), 0 for tests that set
     * none.  The structs share storage: read only those of `test`.  reserved
     * is 0.1.0's name of the same storage. */
    MCSTAT_ANONYMOUS union {
        double reserved[7];
        struct {                      /* KS_2 */
            double ks_critical_se;    /* Monte Carlo standard error of critical[1] */
            double ks_n_sim;          /* replicates simulated (0 unless simulated) */
        };
        struct {                      /* EQUIV_1, EQUIV_2 */
            double tost_t_lower;      /* t for H1: mean > lower bound */
            double tost_t_upper;      /* t for H1: mean < upper bound */
            double tost_p_lower;      /* their one-sided p-values */
            double tost_p_upper;
            double tost_lower;        /* the bounds tested */
            double tost_upper;
        };
        struct {                      /* BINOM */
            double binom_unused_[2];
            double binom_log_p_value; /* log(p_value), finite where p_value underflows */
        };
        struct {                      /* CHISQ_GOF */
            double chisq_unused_[2];
            double chisq_cells_given;  /* k */
            double chisq_min_expected; /* smallest expected count after pooling */
            double chisq_pool_below;   /* min_expected, 0 when pooling was off */
        };
        struct {                       /* SEQ_* (mcstat/sequential.h) */
            double seq_looks;          /* pushes so far */
            double seq_n_decided;      /* n (of x) at the look that decided; 0 while continuing */
            double seq_log_e;          /* log of the e-value (test martingale) at the last look */
            double seq_log_e_max;      /* its running maximum: p_value = min(1, exp(-seq_log_e_max)) */
            double seq_eps;            /* equivalence margin (0: none) */
            double seq_t_opt;          /* the n where the confidence sequence is tightest */
            double seq_n_gate;         /* the n the kurtosis gate asks for (0 when open) */
        };
        struct {                       /* EFFICIENCY */
            double eff_var_ratio;      /* s_y^2 / s_x^2 (x's advantage in variance) */
            double eff_time_ratio;     /* mean time y / mean time x (x's advantage in time) */
            double eff_se_log_var_x;   /* delta-method standard errors of the four logs */
            double eff_se_log_var_y;
            double eff_se_log_time_x;
            double eff_se_log_time_y;
        };
    };
};

/* Values of mcstat_result.decision. */
#define MCSTAT_DECISION_LESS (-1)
#define MCSTAT_DECISION_EQUAL 0
#define MCSTAT_DECISION_GREATER 1

/* Deprecated (0.1.0) accessors of the per-test outputs, kept so that old
 * code compiles: use the named fields (MCSTAT_RESULT_KS_WEIGHT(r) is
 * r->ks_weight, MCSTAT_RESULT_N_SIM(r) r->ks_n_sim, ...). */
#define MCSTAT_RESULT_TOST_T_LOWER(r) ((r)->tost_t_lower)
#define MCSTAT_RESULT_TOST_T_UPPER(r) ((r)->tost_t_upper)
#define MCSTAT_RESULT_TOST_P_LOWER(r) ((r)->tost_p_lower)
#define MCSTAT_RESULT_TOST_P_UPPER(r) ((r)->tost_p_upper)
#define MCSTAT_RESULT_TOST_LOWER(r) ((r)->tost_lower)
#define MCSTAT_RESULT_TOST_UPPER(r) ((r)->tost_upper)
#define MCSTAT_RESULT_KS_WEIGHT(r) ((r)->ks_weight)
#define MCSTAT_RESULT_CRITICAL_SE(r) ((r)->ks_critical_se)
#define MCSTAT_RESULT_N_SIM(r) ((r)->ks_n_sim)
#define MCSTAT_RESULT_LOG_P_VALUE(r) ((r)->binom_log_p_value)
#define MCSTAT_RESULT_CHISQ_CELLS(r) ((r)->chisq_cells)
#define MCSTAT_RESULT_CHISQ_ESTIMATED(r) ((r)->chisq_n_estimated)
#define MCSTAT_RESULT_CHISQ_CELLS_GIVEN(r) ((r)->chisq_cells_given)
#define MCSTAT_RESULT_CHISQ_MIN_EXPECTED(r) ((r)->chisq_min_expected)
#define MCSTAT_RESULT_CHISQ_POOL_BELOW(r) ((r)->chisq_pool_below)

/* The decision rule (the paper's three-way outcome, its figure 4): `reject`
 * is the test against the chosen alternative at level alpha; `decision` is
 * 0 (MCSTAT_DECISION_EQUAL) when H0 is not rejected, else the sign of the
 * estimate's deviation from the null value (MCSTAT_DECISION_LESS or
 * _GREATER).  With the two-sided alternative this is the paper's less /
 * equal / greater outcome. */

/* Writes the R-style block (the layout and number formatting of R's
 * print.htest, plus a final "decision at alpha = ...: ..." line) into buf.
 * x_name and y_name name the data ("x" and "y" when NULL).  *length (may be
 * NULL) receives the length of the full text, without the terminating NUL;
 * MCSTAT_EBUFSIZE when it does not fit in size bytes (buf then holds a
 * NUL-terminated prefix). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_result_format(const mcstat_result *r, const char *x_name,
                                    const char *y_name, char *buf, size_t size,
                                    size_t *length);

/* "less", "equal" or "greater" for a decision value, NULL otherwise. */
MCSTAT_API const char *mcstat_decision_name(int decision);

/* *log_p <- the natural log of r's p-value, finite wherever the tail is
 * representable in log even when p_value underflows to 0: t, chi-squared
 * and F tests from the statistic and df through the log tails of section
 * 11 (two-sided: log 2 + the smaller log tail, capped at 0; the
 * efficiency test's t likewise); TOST the
 * larger of its two one-sided log p's; the binomial test its
 * binom_log_p_value; K-S the log of Kolmogorov's limit when asymptotic
 * (unweighted), else log(p_value) (exact and simulated p-values carry no
 * more).  MCSTAT_EINVAL for NULL, an unknown test or a result whose fields
 * are NaN (a failed row). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_result_log_p_value(const mcstat_result *r, double *log_p);

/* conf_int <- r's confidence interval at confidence_level in (0, 1) in
 * place of 1 - alpha, for the same alternative (one-sided ones keep their
 * infinite end, or 0 for a variance):
 *   t tests   estimate +- t quantile * std_error on the result's df, the
 *             estimate (the difference for two samples) taken from the
 *             stored estimates or as null_value + statistic * std_error,
 *             whichever rounds less (so a 1e9 offset keeps its digits);
 *   TOST      the two-sided t interval at that level (the result's own
 *             conf_int is the one at 1 - 2 alpha that TOST amounts to);
 *   variance  [X^2 sigma0^2 / c1, X^2 sigma0^2 / c0], chi-squared quantiles;
 *   F         [F ratio0 / c1, F ratio0 / c0], F quantiles;
 *   binomial  Clopper-Pearson, as the test's.
 *   efficiency exp(log rho_hat +- t quantile * std_error) (log rho_hat =
 *             log null_value + statistic * std_error).
 * At level 1 - alpha it reproduces r->conf_int to rounding.  MCSTAT_EINVAL
 * for NULL, a level outside (0, 1) (or NaN), a test with no parameter
 * interval (K-S, chi-squared goodness of fit) or a result whose fields are
 * NaN; MCSTAT_ENUMERIC if a bound cannot be formed. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_result_conf_int(const mcstat_result *r, double confidence_level, double conf_int[2]);

/* ------------------------------------------------------------------------ */
/* The tests.                                                                */
/* Each comes on arrays and on accumulators.  Common arguments:              */
/*   alternative  enum mcstat_alternative                                    */
/*   alpha        significance level in (0, 1); conf_int has level 1-alpha   */
/* Statuses: MCSTAT_EINVAL (NULL pointer, bad enum, alpha or a null value    */
/* out of range or non-finite), MCSTAT_ETOOFEW (n < 2 in a sample),          */
/* MCSTAT_ENONFINITE (NaN/Inf in data), MCSTAT_EDEGENERATE (a sample is      */
/* constant to within rounding: its standard deviation is zero or below      */
/* 10*DBL_EPSILON*|mean|; Welch needs this of only one of its samples),      */
/* MCSTAT_ENUMERIC.  (R's t.test applies 10*eps*|mean| to the standard       */
/* error instead, which refuses large samples at large offsets.)             */
/* ------------------------------------------------------------------------ */

/* One-sample t test of mean(x) against mu0 (section 2.1, eq. 1). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_1(const double *x, size_t n, double mu0, int alternative,
                               double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_1_moments(const mcstat_moments *x, double mu0, int alternative,
                                       double alpha, mcstat_result *out);

/* Welch's two-sample t test of mean(x) - mean(y) against mu0 (section 2.3,
 * eq. 3, Welch-Satterthwaite degrees of freedom). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2(const double *x, size_t nx, const double *y, size_t ny,
                               double mu0, int alternative, double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_moments(const mcstat_moments *x, const mcstat_moments *y,
                                       double mu0, int alternative, double alpha,
                                       mcstat_result *out);

/* Student's two-sample t test with pooled variance (R's t.test(var.equal =
 * TRUE), SciPy's ttest_ind default): s_p^2 = (M2_x + M2_y)/(nx + ny - 2),
 * standard error s_p sqrt(1/nx + 1/ny), df = nx + ny - 2; test
 * MCSTAT_TEST_T_2_POOLED, estimates as Welch's.  MCSTAT_EDEGENERATE only
 * when both samples are constant (as Welch). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_pooled(const double *x, size_t nx, const double *y, size_t ny,
                                      double mu0, int alternative, double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_2_pooled_moments(const mcstat_moments *x, const mcstat_moments *y,
                                              double mu0, int alternative, double alpha,
                                              mcstat_result *out);

/* Paired t test of mean(x - y) against mu0 (R's t.test(paired = TRUE),
 * SciPy's ttest_rel): the one-sample t on the n differences x_i - y_i, each
 * one rounding of the exact difference, accumulated as mcstat_moments (a
 * difference that overflows is taken halved, with mu0 halved: t, df and p
 * are unchanged).  Test MCSTAT_TEST_T_PAIRED; n[0] = n[1] = n pairs;
 * estimate[0] the mean difference; df = n - 1.  MCSTAT_ENONFINITE for NaN
 * or +-Inf in x or y, MCSTAT_ETOOFEW for n < 2, MCSTAT_EDEGENERATE when the
 * differences are constant. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_t_test_paired(const double *x, const double *y, size_t n, double mu0,
                                    int alternative, double alpha, mcstat_result *out);

/* One-sample chi-squared test of var(x) against sigma2 > 0: statistic
 * (n-1) s^2 / sigma2 on n-1 degrees of freedom (section 2.2, eq. 2). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_1(const double *x, size_t n, double sigma2, int alternative,
                                 double alpha, mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_1_moments(const mcstat_moments *x, double sigma2,
                                         int alternative, double alpha, mcstat_result *out);

/* Two-sample F test of var(x)/var(y) against ratio > 0: statistic
 * (s_x^2 / s_y^2) / ratio on (nx-1, ny-1) degrees of freedom (section 2.4). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_2(const double *x, size_t nx, const double *y, size_t ny,
                                 double ratio, int alternative, double alpha,
                                 mcstat_result *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_var_test_2_moments(const mcstat_moments *x, const mcstat_moments *y,
                                         double ratio, int alternative, double alpha,
                                         mcstat_result *out);

/* ------------------------------------------------------------------------ */
/* Efficiency ratio of two estimators.                                       */
/* "B converges 2x faster than A" is a claim about efficiency, 1 / (variance */
/* per sample x time per sample) (Kalos & Whitlock), both factors measured   */
/* with error. The parameter is rho = eff(x) / eff(y) = (var_y tau_y) /      */
/* (var_x tau_x); MCSTAT_GREATER means x is the more efficient. x and y      */
/* accumulate the estimators' samples; time_x and time_y the time per sample */
/* of k >= 2 timed batches each (a batch's wall time / its size), timed      */
/* interleaved so that machine load affects both. log rho_hat = log s_y^2 -  */
/* log s_x^2 + log tau_y - log tau_x; its standard error adds the delta      */
/* method's (beta2 - (n-3)/(n-1))/n for each log s^2 (beta2 = n M4/M2^2, the */
/* exact variance of s^2 without assuming normal data) and s_tau^2/(k tau^2) */
/* for each log mean time; the statistic (log rho_hat - log ratio) / se is   */
/* referred to a t on Satterthwaite's df (k - 1 per time part, 2/Var per     */
/* variance part). Assumptions: independent samples and batches, finite      */
/* fourth moments; asymptotic in the samples and the batches.                */
/* Calibration (tests/c/test_efficiency.c holds it to binomial bounds): the */
/* rejection rate under H0 is alpha for exponential data (n = 1000, 5 or 10  */
/* timed batches) and for 99%-zero data with ~500 non-zero values per        */
/* sample; with ~20 non-zero values the sample kurtosis underestimates the   */
/* tail and the rate is up to twice alpha: a claim needs hundreds of         */
/* non-zero samples, and a p-value near alpha is weaker evidence than it     */
/* reads.                                                                    */
/* Result: test MCSTAT_TEST_EFFICIENCY, method MCSTAT_METHOD_ASYMPTOTIC;     */
/* statistic and critical values on the t scale, df[0]; conf_int the         */
/* interval for rho (exp of the log interval; 0 and +Inf the open ends);     */
/* estimate[0] rho_hat, estimate[1] s_y^2 / s_x^2; null_value ratio;         */
/* std_error the standard error of log rho_hat; decision the sign of log     */
/* rho_hat - log ratio when rejected; n[] the sample sizes; per-test fields  */
/* eff_var_ratio, eff_time_ratio, the four standard errors eff_se_log_*,     */
/* eff_batches_x/_y. An estimate or bound beyond the doubles is +Inf or 0;   */
/* statistic and p-value, formed in logs, stay exact.                        */
/* Statuses: MCSTAT_EINVAL (NULL, alpha outside (0, 1), ratio <= 0 or not    */
/* finite, a bad alternative, an uninitialised accumulator, a negative       */
/* time), MCSTAT_ETOOFEW (n < 2 in x or y, fewer than 2 timed batches),      */
/* MCSTAT_EDEGENERATE (x or y constant, or every batch timed as 0: a timer   */
/* too coarse), MCSTAT_ENUMERIC (not expected: a guard against NaN). Equal   */
/* batch times are accepted: an exact cost (operation counts) contributes no */
/* error.                                                                    */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_API int mcstat_efficiency_test(const mcstat_moments *x, const mcstat_moments *y,
                                      const mcstat_moments *time_x, const mcstat_moments *time_y,
                                      double ratio, int alternative, double alpha, mcstat_result *out);

/* ------------------------------------------------------------------------ */
/* Two-sample Kolmogorov-Smirnov test (the paper's section 2.5).            */
/* F and G are the empirical CDFs #{x_i <= t}/nx and #{y_j <= t}/ny, z =     */
/* (nx F + ny G)/(nx + ny) the pooled one.  They are compared at the pooled  */
/* jump points only, and where values are tied only after the last of a run */
/* of equal values.  The statistic is                                        */
/*   weight NONE:   D  = sup |F - G|                     (as R and SciPy)    */
/*   weight CANNER: D2 = sqrt(nx ny/(nx+ny)) sup |F - G| / sqrt(z (1 - z)),  */
/*                  the sup over jump points with 0 < z < 1.                 */
/* Alternatives are claims about the first sample, as for every mcstat test */
/* (the paper's section 3 words one of them the other way): MCSTAT_LESS =  */
/* x tends to be smaller than y, i.e. its CDF lies above, sup (F - G);      */
/* MCSTAT_GREATER = x tends to be larger, sup (G - F).                      */
/* NOTE: R's ks.test and SciPy's ks_2samp name one-sided alternatives by the */
/* CDF, the other way round: mcstat's LESS is their "greater".  The printed */
/* block uses R's wording ("the CDF of x lies above that of y").  One-sided  */
/* statistics include the end point where F = G, so they are >= 0.          */
/* Under H0 only the order of the labels matters; p-values are conditional  */
/* on the tie pattern.  Methods:                                             */
/*   EXACT      the permutation distribution by a lattice-path recursion in */
/*              probability scale (O(nx ny) time at most, O(N^1.5) in        */
/*              practice, O(min(nx, ny)) memory),                            */
/*              exact integer comparisons, ties handled; relative error      */
/*              about 1e-13, absolute error below 1e-290.  MCSTAT_ETOOBIG    */
/*              when (min(nx,ny)+1)(nx+ny+1) > MCSTAT_KS_EXACT_MAX_WORK.     */
/*   SIMULATE   n_sim random label arrangements (over the fixed tie blocks): */
/*              p = (1 + #{D* >= D})/(n_sim + 1), p_value_se its Monte Carlo */
/*              standard error sqrt(p(1-p)/n_sim); bit-identical for any     */
/*              number of threads and with or without AVX2 (8 replicates    */
/*              per AVX2 kernel step; O(N) per replicate, costs in          */
/*              bench/RESULTS_ks.md); optionally cached (mcstat_ks_cache).   */
/*   ASYMPTOTIC weight NONE only: Kolmogorov's limit at sqrt(ne) D (ne =    */
/*              nx ny/N), one-sided exp(-2 ne D^2); conservative, p within  */
/*              2% at 300+300 and beyond (bench/RESULTS_ks.md; Stephens'     */
/*              correction was measured and is anti-conservative here).      */
/*              Canner's statistic has no usable limit (it grows like       */
/*              sqrt(2 log log n)):                                          */
/*              MCSTAT_EINVAL.                                               */
/*   AUTO       EXACT when (min+1)(N+1) <= MCSTAT_KS_AUTO_EXACT_WORK, else   */
/*              SIMULATE (Canner, or NONE with ties) or ASYMPTOTIC (NONE     */
/*              without ties).                                               */
/* Result fields: statistic D or D2; critical[1] is the value above which H0 */
/* is rejected at alpha (reject == statistic > critical[1] == p <= alpha),   */
/* critical[0] = -Inf; decision is 0, or -1 ("less": x tends to be smaller, */
/* its CDF lies above where the (weighted) deviation is largest) or +1.  df, */
/* estimate, conf_int, null_value, std_error are NaN.  Per-test fields:     */
/*   ks_weight       enum mcstat_ks_weight                                   */
/*   ks_critical_se  Monte Carlo standard error of critical[1] (0 unless     */
/*                   simulated)                                              */
/*   ks_n_sim        replicates simulated                                    */
/* ------------------------------------------------------------------------ */
enum mcstat_ks_weight {
    MCSTAT_KS_WEIGHT_NONE = 0,  /* the classical (Smirnov) statistic */
    MCSTAT_KS_WEIGHT_CANNER = 1 /* Canner's [z(1-z)]^(-1/2) (the paper's) */
};

/* Size limits of the exact method, in lattice cells (min(nx,ny)+1)(nx+ny+1).
 * The recursion only visits the band of points that the threshold has not
 * absorbed and whose probability is above 2^-1000, O(sqrt(N)) wide, so its
 * time grows like N^1.5; the critical value (a search) costs 10-40
 * p-values (figures: bench/RESULTS_ks.md). */
#define MCSTAT_KS_EXACT_MAX_WORK 2e11  /* ~3.2e5 + 3.2e5, seconds: beyond, MCSTAT_ETOOBIG */
#define MCSTAT_KS_AUTO_EXACT_WORK 1.6e7 /* ~2800 + 2800 (costs: bench/RESULTS_ks.md) */
#define MCSTAT_KS_DEFAULT_N_SIM 10000

/* A cache of simulated null distributions, owned by the caller and shared by
 * any number of threads (it has its own lock).  Entries are keyed by (nx, ny,
 * weight, alternative, n_sim, seed, tie pattern), so a battery of tests at
 * the same sizes simulates once.  When adding an entry would exceed
 * max_bytes, the least recently used entries are dropped. */
typedef struct mcstat_ks_cache mcstat_ks_cache;
/* MCSTAT_EINVAL (cache NULL), MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_ks_cache_new(size_t max_bytes, mcstat_ks_cache **cache);
/* Frees the cache (NULL is a no-op); no test may be using it. */
MCSTAT_API void mcstat_ks_cache_free(mcstat_ks_cache *cache);
/* Lookups that found an entry, lookups that did not, entries held (any may be NULL). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_ks_cache_stats(const mcstat_ks_cache *cache, uint64_t *hits,
                                     uint64_t *misses, uint64_t *entries);

/* Options; grows by appending fields ("Conventions", compatibility), so
 * always start from the initialiser. */
typedef struct mcstat_ks_options {
    uint32_t size;          /* sizeof(mcstat_ks_options): set by the initialiser */
    int32_t weight;         /* enum mcstat_ks_weight; default CANNER */
    int32_t method;         /* MCSTAT_METHOD_AUTO (default), _EXACT, _SIMULATE, _ASYMPTOTIC */
    int32_t threads;        /* threads for simulation and sorting, 1..64; default 1:
                               no thread is started unless the caller asks */
    int64_t n_sim;          /* replicates when simulating, >= 1; default 10000 */
    uint64_t seed;          /* simulation seed; default 0 */
    mcstat_ks_cache *cache; /* simulated distributions to reuse; NULL: none */
    int32_t critical;       /* 1: compute critical[1] (exact: a search costing 10-40
                               p-value computations); 0: leave it NaN; default 1 */
    int32_t reserved;       /* zero */
} mcstat_ks_options;

#define MCSTAT_KS_OPTIONS_INIT \
    {sizeof(mcstat_ks_options), MCSTAT_KS_WEIGHT_CANNER, MCSTAT_METHOD_AUTO, 1, \
     MCSTAT_KS_DEFAULT_N_SIM, 0u, NULL, 1, 0}

/* sizeof(mcstat_ks_options) in each release that changed it. */
#define MCSTAT_KS_OPTIONS_SIZE_0_1 48u
/* Sets the first `size` bytes of *opt to MCSTAT_KS_OPTIONS_INIT, with
 * opt->size = size: `size` is sizeof(mcstat_ks_options) as the caller
 * compiled it (FFI callers: their struct's size), so nothing beyond the
 * caller's struct is written.  MCSTAT_EINVAL (nothing written) for NULL or
 * a size no release had. */
MCSTAT_API int mcstat_ks_options_init_size(mcstat_ks_options *opt, size_t size);
/* 0.1.0's initialiser, still exported for binaries built against it:
 * writes MCSTAT_KS_OPTIONS_SIZE_0_1 bytes.  Source code calling
 * mcstat_ks_options_init(&o) gets the macro, which passes sizeof o. */
MCSTAT_API int(mcstat_ks_options_init)(mcstat_ks_options *opt);
#define mcstat_ks_options_init(opt) mcstat_ks_options_init_size((opt), sizeof *(opt))
MCSTAT_API size_t mcstat_sizeof_ks_options(void);

/* The two-sample K-S test of x against y.  opt may be NULL (the defaults).
 * Statuses: MCSTAT_EINVAL (NULL data or out, bad enum, alpha outside (0,1),
 * n_sim < 1, threads outside 1..64, an options size this library does not
 * know, ASYMPTOTIC with Canner's weight), MCSTAT_ETOOFEW (an empty sample),
 * MCSTAT_ENONFINITE (NaN in the data; +-Inf are ordinary, ordered values),
 * MCSTAT_ETOOBIG (nx*ny >= 2^62, or EXACT beyond MCSTAT_KS_EXACT_MAX_WORK),
 * MCSTAT_ENOMEM. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_ks_test_2(const double *x, size_t nx, const double *y, size_t ny,
                                int alternative, double alpha, const mcstat_ks_options *opt,
                                mcstat_result *out);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_TESTS_FAMILY_H */
