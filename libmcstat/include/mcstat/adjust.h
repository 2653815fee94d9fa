/*
 * mcstat/adjust.h - multiple testing: adjusted p-values.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_ADJUST_FAMILY_H
#define MCSTAT_ADJUST_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 5. Multiple testing.                                                   */
/* A per-pixel comparison makes millions of tests: adjust their p-values    */
/* before reading the map.                                                  */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Multiple testing: adjusted p-values, as R's p.adjust.                     */
/* A per-pixel comparison makes millions of tests; at level alpha each, a    */
/* fraction alpha of the unchanged pixels is rejected by chance.  Adjusted   */
/* p-values compared with alpha control the family-wise error rate          */
/* (Bonferroni, Holm, Hochberg, Hommel) or the false discovery rate (BH:     */
/* Benjamini & Hochberg; BY: Benjamini & Yekutieli, valid under any          */
/* dependence; e-BH, mcstat_e_bh below, too).  The values are R's          */
/* p.adjust's, to rounding (R has no e-BH): NaN entries are R's NA (they     */
/* stay NaN, and n, the number of tests, counts the others);                 */
/* with n <= 1 the p-values come back unchanged.  O(n log n) (Hommel too).   */
/* Values match across versions; FFI callers may use the integers.          */
/* ------------------------------------------------------------------------ */
enum mcstat_p_adjust_method {
    MCSTAT_P_ADJUST_NONE = 0,       /* unchanged */
    MCSTAT_P_ADJUST_BONFERRONI = 1, /* min(1, n p) */
    MCSTAT_P_ADJUST_HOLM = 2,       /* step-down Bonferroni (FWER, any dependence) */
    MCSTAT_P_ADJUST_HOCHBERG = 3,   /* step-up (FWER, independent or positively dependent tests) */
    MCSTAT_P_ADJUST_HOMMEL = 4,     /* Simes closed testing (FWER, as Hochberg; more powerful) */
    MCSTAT_P_ADJUST_BH = 5,         /* Benjamini-Hochberg (FDR, independent or positively dependent) */
    MCSTAT_P_ADJUST_BY = 6,         /* Benjamini-Yekutieli (FDR, any dependence) */
    MCSTAT_P_ADJUST_E_BH = 7        /* e-BH on calibrated p-values (FDR, any dependence) */
};

/* Parses R's names: "none", "bonferroni", "holm", "hochberg", "hommel", "BH"
 * (also "fdr"), "BY"; and statsmodels' multipletests names for the same
 * methods: "b", "bonf"; "h" (Holm); "sh", "simes-hochberg"; "ho";
 * "fdr_bh", "fdr_i", "fdr_p", "fdri", "fdrp"; "fdr_by", "fdr_n", "fdr_c",
 * "fdrn", "fdrcorr"; "e-BH" (also "ebh", "e_bh").  Case is ignored (ASCII).  MCSTAT_EINVAL for anything
 * else, statsmodels' methods this library lacks included ("sidak",
 * "holm-sidak", "fdr_tsbh", "fdr_tsbky", "fdr_gbs", ...). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_p_adjust_method_parse(const char *name, int *method);
/* R's name of a method ("BH", "holm", ...), or NULL for an invalid value. */
MCSTAT_API const char *mcstat_p_adjust_method_name(int method);
/* *bytes <- the workspace mcstat_p_adjust needs for n p-values: 0 for none
 * and bonferroni, 32 n for holm, hochberg, BH, BY and e-BH (and
 * mcstat_e_bh), 40 n for hommel (on
 * 64-bit machines).  MCSTAT_EINVAL (bad method, bytes NULL), MCSTAT_ETOOBIG
 * (the size does not fit in a size_t). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_p_adjust_work_size(size_t n, int method, size_t *bytes);
/* adjusted[0..n) <- the adjusted p[0..n) (adjusted may equal p: in place).
 * work: work_bytes of scratch aligned for double (mcstat_p_adjust_work_size),
 * or NULL, in which case the call allocates it with malloc and frees it
 * before returning.  Statuses: MCSTAT_EINVAL (p or adjusted NULL with n > 0,
 * a bad method, a p-value outside [0, 1] other than NaN, misaligned work;
 * nothing written), MCSTAT_EBUFSIZE (work_bytes too small), MCSTAT_ENOMEM
 * (work NULL and the allocation failed), MCSTAT_ETOOBIG. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_p_adjust(const double *p, size_t n, int method, void *work, size_t work_bytes,
                               double *adjusted);
/* e-BH (Wang & Ramdas 2022): FDR control from e-values, valid under any
 * dependence among them.  With e_(1) >= ... >= e_(n) it rejects the k*
 * largest, k* = max{k : k e_(k) / n >= 1/alpha}; adjusted[i] <- the
 * value of e[i], min over k >= its rank of n / (k e_(k)), capped at 1, so
 * that "reject iff adjusted <= alpha" is that rule at every alpha.  e[i] in
 * [0, +inf]; NaN entries stay NaN and are not counted in n; one e-value
 * gives min(1, 1/e).  Workspace and statuses as mcstat_p_adjust's with
 * method MCSTAT_P_ADJUST_E_BH (MCSTAT_EINVAL: an e-value < 0).
 * MCSTAT_P_ADJUST_E_BH in mcstat_p_adjust is this on the e-values e =
 * kappa p^(kappa - 1), kappa = 1/10, of the p-values (E[e] <= 1 for a valid
 * p): valid under any dependence among the p-values, but less powerful
 * than BY on the same p-values (the k-th rejection needs p_(k) <= (k alpha
 * / (10 n))^(10/9), BY's p_(k) <= k alpha / (n H_n), H_n = 1 + ... + 1/n;
 * about 5 times smaller for a first rejection among 2304 tests at 0.05).
 * Up to n = 12366 (H_n <= 10: H_n p <= 10 p^(9/10) term by term) BY's
 * adjusted values are never larger.
 * On p-values BY is the more powerful of the two; mcstat_e_bh is for
 * e-values proper (likelihood ratios, sequential tests' betting wealth). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_e_bh(const double *e, size_t n, void *work, size_t work_bytes, double *adjusted);

/* ------------------------------------------------------------------------ */
/* Escalation instead of reruns: a two-stage test (Bauer & Koehne 1994).     */
/* A test suite that reruns a failed statistical test until it passes has   */
/* no error rate left.  Escalation keeps it: stage 1 tests n samples and     */
/* gives p1; p1 <= alpha1 rejects, p1 > alpha0 passes, and in between the   */
/* test continues on fresh samples (an independent stage 2, of any size     */
/* chosen after seeing stage 1) giving p2, and rejects when p1 p2 <= c     */
/* (Fisher's product).  With c = (alpha - alpha1) / ln(alpha0 / alpha1) the  */
/* probability of a rejection under H0 is alpha1 + c ln(alpha0 / alpha1) =   */
/* alpha exactly for uniform p-values, at most alpha for valid (super-      */
/* uniform) ones such as discrete tests' or a Holm battery's smallest       */
/* adjusted p-value; the stages must be independent (fresh random numbers). */
/* A correct test escalates with probability alpha0 - alpha1, so it costs    */
/* on average n1 + (alpha0 - alpha1) n2 samples; a borderline error, whose   */
/* p1 falls between the bounds, is judged on n1 + n2.                        */
/* ------------------------------------------------------------------------ */
typedef struct mcstat_escalation {
    double alpha;  /* the level of the whole two-stage test */
    double alpha1; /* stage 1 rejects when p1 <= alpha1 */
    double alpha0; /* stage 1 passes when p1 > alpha0, escalates when alpha1 < p1 <= alpha0 */
    double c;      /* stage 2 rejects when p1 p2 <= c (c <= alpha1) */
} mcstat_escalation;

/* The decisions of mcstat_escalation_decide. */
enum mcstat_escalation_decision {
    MCSTAT_ESCALATION_PASS = 0,     /* no evidence against H0 at alpha */
    MCSTAT_ESCALATION_REJECT = 1,   /* H0 rejected at alpha */
    MCSTAT_ESCALATION_CONTINUE = 2  /* stage 1 was inconclusive: run stage 2 */
};

/* *out <- the design of level alpha in (0, 1) that spends alpha1 = share1
 * alpha at stage 1 (share1 in (0, 1); 1/2 is a good default) and escalates
 * up to alpha0 in (alpha1, 1].  MCSTAT_EINVAL for arguments outside those
 * ranges, NaN included, or when alpha0 is so close to alpha1 that stage 2
 * could not spend the rest (c > alpha1, i.e. alpha0 < alpha1
 * e^((1 - share1) / share1)); nothing written then. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_escalation_design(double alpha, double share1, double alpha0, mcstat_escalation *out);
/* *decision <- the design's decision (enum mcstat_escalation_decision) on
 * stage 1's p1 alone (p2 NaN), or on both stages (p2 in [0, 1]: valid only
 * when stage 1 said MCSTAT_ESCALATION_CONTINUE, MCSTAT_EINVAL otherwise).
 * MCSTAT_EINVAL: design or decision NULL, a design mcstat_escalation_design
 * would not make, p1 outside [0, 1] (NaN included), p2 neither NaN nor in
 * [0, 1]. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_escalation_decide(const mcstat_escalation *design, double p1, double p2, int *decision);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_ADJUST_FAMILY_H */
