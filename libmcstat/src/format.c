/*
 * format.c - the R-style text block of a result: R's print.htest layout
 * (options(digits = 7): statistic and parameters at 5 significant digits,
 * the p-value through format.pval at 4, interval and estimates at 7), then
 * mcstat's decision line before the closing blank line.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"
#include "rformat.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#define R_DIGITS 7
#define WRAP_WIDTH 72 /* strwrap's default width: 0.9 * getOption("width") */

/* A string builder over the caller's buffer that keeps counting past its end. */
typedef struct {
    char *buf;
    size_t size, len;
} sbuf;

static void sb_put(sbuf *s, const char *text, size_t n)
{
    if (s->len < s->size) {
        size_t room = s->size - s->len - 1;
        size_t k = n < room ? n : room;
        memcpy(s->buf + s->len, text, k);
        s->buf[s->len + k] = '\0';
    }
    s->len += n;
}

static void sb_puts(sbuf *s, const char *text)
{
    sb_put(s, text, strlen(text));
}

static void sb_printf(sbuf *s, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0)
        sb_put(s, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}

/* The words of `line` re-flowed like strwrap(): lines shorter than WRAP_WIDTH. */
static void sb_wrapped(sbuf *s, const char *line)
{
    size_t col = 0;
    const char *p = line;
    while (*p) {
        while (*p == ' ')
            p++;
        const char *w = p;
        while (*p && *p != ' ')
            p++;
        size_t wl = (size_t)(p - w);
        if (wl == 0)
            break;
        if (col > 0 && col + 1 + wl >= WRAP_WIDTH) {
            sb_puts(s, "\n");
            col = 0;
        }
        if (col > 0) {
            sb_puts(s, " ");
            col++;
        }
        sb_put(s, w, wl);
        col += wl;
    }
    sb_puts(s, "\n");
}

static const char *const DF_NAME[] = {"df"};

/* "t = -2.3376, df = 18.466, p-value = 0.03084" (print.htest: the statistic
 * and parameters at 5 digits, the p-value through format.pval at 4),
 * wrapped like strwrap. */
static void sb_stat_line(sbuf *s, const char *stat_name, double stat, const char *const *par_names,
                         const double *pars, int n_par, double p)
{
    char a[64], line[512];
    size_t ll = 0;
    mcstat__rformat1(stat, R_DIGITS - 2, a, sizeof a);
    ll += (size_t)snprintf(line + ll, sizeof line - ll, "%s = %s", stat_name, a);
    for (int k = 0; k < n_par; k++) {
        mcstat__rformat1(pars[k], R_DIGITS - 2, a, sizeof a);
        ll += (size_t)snprintf(line + ll, sizeof line - ll, ", %s = %s", par_names[k], a);
    }
    mcstat__rformat_pval(p, R_DIGITS - 3, a, sizeof a);
    snprintf(line + ll, sizeof line - ll, ", p-value %s%s", a[0] == '<' ? "" : "= ", a);
    sb_wrapped(s, line);
}

/* print() of a named vector: each column right-justified to the wider of
 * its name and the values' common width (R's format), one space after. */
static void sb_named(sbuf *s, const char *const *names, const double *v, int n)
{
    mcstat_rlayout lay;
    mcstat__rformat_layout(v, n, R_DIGITS, &lay);
    char a[64];
    for (int k = 0; k < n; k++) {
        int nl = (int)strlen(names[k]);
        sb_printf(s, "%*s ", nl > lay.w ? nl : lay.w, names[k]);
    }
    sb_puts(s, "\n");
    for (int k = 0; k < n; k++) {
        int nl = (int)strlen(names[k]);
        mcstat__rformat_encode(v[k], &lay, nl > lay.w ? nl : lay.w, a, sizeof a);
        sb_printf(s, "%s ", a);
    }
    sb_puts(s, "\n");
}

typedef struct {
    const char *method, *stat_name, *param_name[2], *null_name, *est_name[2];
    int two_sample;
} test_text;

static int describe(const mcstat_result *r, test_text *t)
{
    memset(t, 0, sizeof *t);
    switch (r->test) {
    case MCSTAT_TEST_T_1:
        *t = (test_text){"One Sample t-test", "t", {"df", NULL}, "mean", {"mean of x", NULL}, 0};
        return 1;
    case MCSTAT_TEST_T_2:
        *t = (test_text){"Welch Two Sample t-test", "t", {"df", NULL}, "difference in means",
                         {"mean of x", "mean of y"}, 1};
        return 1;
    case MCSTAT_TEST_T_2_POOLED:
        *t = (test_text){"Two Sample t-test", "t", {"df", NULL}, "difference in means",
                         {"mean of x", "mean of y"}, 1};
        return 1;
    case MCSTAT_TEST_T_PAIRED:
        *t = (test_text){"Paired t-test", "t", {"df", NULL}, "mean difference", {"mean difference", NULL}, 1};
        return 1;
    case MCSTAT_TEST_VAR_1:
        *t = (test_text){"One Sample Chi-squared test on variance", "X-squared", {"df", NULL}, "variance",
                         {"variance of x", NULL}, 0};
        return 1;
    case MCSTAT_TEST_VAR_2:
        *t = (test_text){"F test to compare two variances", "F", {"num df", "denom df"}, "ratio of variances",
                         {"ratio of variances", NULL}, 1};
        return 1;
    case MCSTAT_TEST_BINOM: /* R's binom.test: its parameter is n, not a df */
        *t = (test_text){"Exact binomial test", "number of successes", {"number of trials", NULL},
                         "probability of success", {"probability of success", NULL}, 1};
        return 1;
    default:
        return 0;
    }
}

/* The K-S block: R's print of ks.test (method names, D / D^+ / D^-, the
 * alternative's wording with R's literal "x" and "y"), the weight named in
 * the method line, and for a simulated p-value a line with its Monte Carlo
 * standard error and the number of replicates. */
static void format_ks(const mcstat_result *r, const char *x_name, const char *y_name, sbuf *s)
{
    static const char *how[] = {"Exact", "Monte-Carlo", "Asymptotic"};
    int m = r->method == MCSTAT_METHOD_SIMULATE ? 1 : r->method == MCSTAT_METHOD_ASYMPTOTIC ? 2 : 0;
    int canner = r->ks_weight == MCSTAT_KS_WEIGHT_CANNER;
    sb_printf(s, "\n\t%s two-sample Kolmogorov-Smirnov test%s\n\n", how[m], canner ? " with Canner's weight" : "");
    sb_printf(s, "data:  %s and %s\n", x_name, y_name);
    char a[64], line[512];
    static const char *suffix[] = {"", "^-", "^+"}; /* R's, by the CDF sense */
    const int cdf_alt = mcstat__ks_cdf_alternative(r->alternative);
    mcstat__rformat1(r->statistic, R_DIGITS - 2, a, sizeof a);
    size_t ll = (size_t)snprintf(line, sizeof line, "%s%s = %s", canner ? "D2" : "D", suffix[cdf_alt], a);
    mcstat__rformat_pval(r->p_value, R_DIGITS - 3, a, sizeof a);
    snprintf(line + ll, sizeof line - ll, ", p-value %s%s", a[0] == '<' ? "" : "= ", a);
    sb_wrapped(s, line);
    if (r->method == MCSTAT_METHOD_SIMULATE) {
        mcstat__rformat1(r->p_value_se, 2, a, sizeof a);
        sb_printf(s, "Monte Carlo standard error of the p-value: %s (%.0f replicates)\n", a, r->ks_n_sim);
    }
    static const char *alt[] = {"two-sided", "the CDF of x lies below that of y", "the CDF of x lies above that of y"};
    sb_printf(s, "alternative hypothesis: %s\n", alt[cdf_alt]);
    mcstat__rformat1(r->alpha, R_DIGITS, a, sizeof a);
    sb_printf(s, "decision at alpha = %s: %s\n\n", a, mcstat_decision_name(r->decision));
}

/* The chi-squared goodness-of-fit block: R's print of chisq.test(x, p = p),
 * then a line on pooling when cells were pooled or parameters estimated. */
static void format_chisq(const mcstat_result *r, const char *x_name, sbuf *s)
{
    sb_printf(s, "\n\tChi-squared test for given probabilities\n\n");
    sb_printf(s, "data:  %s\n", x_name);
    char a[64], b[64], line[512];
    sb_stat_line(s, "X-squared", r->statistic, DF_NAME, r->df, 1, r->p_value);
    double given = r->chisq_cells_given;
    int cells = r->chisq_cells, est = r->chisq_n_estimated;
    if ((double)cells != given || est > 0) {
        mcstat__rformat1(r->chisq_pool_below, R_DIGITS, a, sizeof a);
        mcstat__rformat1(r->chisq_min_expected, 4, b, sizeof b);
        size_t ll = (size_t)snprintf(line, sizeof line, "cells: %.0f given, %d after pooling expected counts below %s "
                              "(smallest expected count %s)", given, cells, a, b);
        if (est > 0)
            snprintf(line + ll, sizeof line - ll, "; %d estimated parameter%s", est, est == 1 ? "" : "s");
        sb_wrapped(s, line);
    }
    mcstat__rformat1(r->alpha, R_DIGITS, a, sizeof a);
    sb_printf(s, "decision at alpha = %s: %s\n\n", a, r->reject ? "reject" : "do not reject");
}

/* ---- equivalence (TOST) -------------------------------------------------------
 * No R function prints TOST; the block follows print.htest's layout, with
 * the two one-sided tests on lines of their own and the bounds in the
 * alternative's line. */
static void format_equiv(const mcstat_result *r, const char *x_name, const char *y_name, sbuf *s)
{
    int two = r->test == MCSTAT_TEST_EQUIV_2;
    char a[64], b[64], line[512];
    sb_printf(s, "\n\t%s\n\n", two ? "Welch Two Sample TOST equivalence t-test" : "One Sample TOST equivalence t-test");
    if (two)
        sb_printf(s, "data:  %s and %s\n", x_name, y_name);
    else
        sb_printf(s, "data:  %s\n", x_name);
    sb_stat_line(s, "t", r->statistic, DF_NAME, r->df, 1, r->p_value);
    static const char *side[] = {"lower", "upper"};
    for (int k = 0; k < 2; k++) {
        double t = k ? r->tost_t_upper : r->tost_t_lower;
        double p = k ? r->tost_p_upper : r->tost_p_lower;
        double bound = k ? r->tost_upper : r->tost_lower;
        mcstat__rformat1(bound, R_DIGITS, b, sizeof b);
        snprintf(line, sizeof line, "%s bound %s: t", side[k], b);
        sb_stat_line(s, line, t, NULL, NULL, 0, p);
    }
    mcstat__rformat1(r->tost_lower, R_DIGITS, a, sizeof a);
    mcstat__rformat1(r->tost_upper, R_DIGITS, b, sizeof b);
    sb_printf(s, "alternative hypothesis: true %s is between %s and %s\n", two ? "difference in means" : "mean", a, b);
    mcstat__rformat1(100.0 * (1.0 - 2.0 * r->alpha), R_DIGITS, a, sizeof a);
    sb_printf(s, "%s percent confidence interval:\n", a);
    mcstat_rlayout lay;
    mcstat__rformat_layout(r->conf_int, 2, R_DIGITS, &lay);
    mcstat__rformat_encode(r->conf_int[0], &lay, 0, a, sizeof a);
    mcstat__rformat_encode(r->conf_int[1], &lay, 0, b, sizeof b);
    sb_printf(s, " %s %s\n", a, b);
    sb_puts(s, "sample estimates:\n");
    static const char *names[] = {"mean of x", "mean of y"};
    int ne = two ? 2 : 1;
    sb_named(s, names, r->estimate, ne);
    mcstat__rformat1(r->alpha, R_DIGITS, a, sizeof a);
    sb_printf(s, "decision at alpha = %s: %s\n\n", a, r->reject ? "equivalent" : "not equivalent");
}

/* ---- efficiency ratio -----------------------------------------------------
 * print.htest's layout; the estimates are the ratio of efficiencies and its
 * two factors (y over x: above 1 is x's advantage), and a line gives the
 * timed batches behind the time factor. */
static void format_eff(const mcstat_result *r, const char *x_name, const char *y_name, sbuf *s)
{
    char a[64], b[64], line[512];
    sb_puts(s, "\n\tEfficiency ratio test (delta method)\n\n");
    sb_printf(s, "data:  %s and %s\n", x_name, y_name);
    sb_stat_line(s, "t", r->statistic, DF_NAME, r->df, 1, r->p_value);
    snprintf(line, sizeof line, "timed batches: %ld of %s, %ld of %s", (long)r->eff_batches_x, x_name,
             (long)r->eff_batches_y, y_name);
    sb_wrapped(s, line);
    static const char *alt_text[] = {"not equal to", "less than", "greater than"};
    mcstat__rformat1(r->null_value, R_DIGITS, a, sizeof a);
    sb_printf(s, "alternative hypothesis: true ratio of efficiencies is %s %s\n", alt_text[r->alternative], a);
    mcstat__rformat1(100.0 * (1.0 - r->alpha), R_DIGITS, a, sizeof a);
    sb_printf(s, "%s percent confidence interval:\n", a);
    mcstat_rlayout lay;
    mcstat__rformat_layout(r->conf_int, 2, R_DIGITS, &lay);
    mcstat__rformat_encode(r->conf_int[0], &lay, 0, a, sizeof a);
    mcstat__rformat_encode(r->conf_int[1], &lay, 0, b, sizeof b);
    sb_printf(s, " %s %s\n", a, b);
    sb_puts(s, "sample estimates:\n");
    static const char *names[] = {"ratio of efficiencies", "ratio of variances", "ratio of times"};
    double est[3] = {r->estimate[0], r->eff_var_ratio, r->eff_time_ratio};
    sb_named(s, names, est, 3);
    mcstat__rformat1(r->alpha, R_DIGITS, a, sizeof a);
    sb_printf(s, "decision at alpha = %s: %s\n\n", a, mcstat_decision_name(r->decision));
}

/* ---- sequential tests -------------------------------------------------------
 * No R function prints one; print.htest's layout with the looks on the
 * data line, the e-value beside the statistic, a confidence sequence in
 * place of the interval, and the decision ("continue" and why, or the
 * decision and the n at which it came). */
static int is_seq(int test) { return test >= MCSTAT_TEST_SEQ_MEAN_1 && test <= MCSTAT_TEST_SEQ_VAR_2; }

static void format_seq(const mcstat_result *r, const char *x_name, const char *y_name, sbuf *s)
{
    static const char *what[] = {"the mean", "the difference in means", "the variance", "the ratio of variances"};
    static const char *param[] = {"mean", "difference in means", "variance", "ratio of variances"};
    static const char *alt_text[] = {"not equal to", "less than", "greater than"};
    int k = r->test - MCSTAT_TEST_SEQ_MEAN_1, two = k == 1 || k == 3;
    char a[64], b[64], line[512];
    sb_printf(s, "\n\tAnytime-valid sequential test of %s (asymptotic, Gaussian mixture)\n\n", what[k]);
    /* the names go straight to the builder: any length (a fixed line
     * buffer would be overrun by the offsets of a truncated name) */
    sb_printf(s, "data:  ");
    sb_puts(s, x_name);
    if (two) {
        sb_puts(s, " and ");
        sb_puts(s, y_name);
    }
    sb_printf(s, ", n = %llu", (unsigned long long)r->n[0]);
    if (two)
        sb_printf(s, " and %llu", (unsigned long long)r->n[1]);
    sb_printf(s, " after %.0f look%s\n", r->seq_looks, r->seq_looks == 1.0 ? "" : "s");
    size_t ll = 0;
    if (isnan(r->statistic)) {
        ll += (size_t)snprintf(line, sizeof line, "z = NA");
    } else {
        mcstat__rformat1(r->statistic, R_DIGITS - 2, a, sizeof a);
        mcstat__rformat1(r->seq_log_e, R_DIGITS - 2, b, sizeof b);
        ll += (size_t)snprintf(line, sizeof line, "z = %s, log e-value = %s", a, b);
    }
    mcstat__rformat_pval(r->p_value, R_DIGITS - 3, a, sizeof a);
    snprintf(line + ll, sizeof line - ll, ", anytime p-value %s%s", a[0] == '<' ? "" : "= ", a);
    sb_wrapped(s, line);
    mcstat__rformat1(r->null_value, R_DIGITS, a, sizeof a);
    sb_printf(s, "alternative hypothesis: true %s is %s %s\n", param[k], alt_text[r->alternative], a);
    mcstat__rformat1(100.0 * (1.0 - r->alpha), R_DIGITS, a, sizeof a);
    sb_printf(s, "%s percent confidence sequence:\n", a);
    mcstat_rlayout lay;
    mcstat__rformat_layout(r->conf_int, 2, R_DIGITS, &lay);
    mcstat__rformat_encode(r->conf_int[0], &lay, 0, a, sizeof a);
    mcstat__rformat_encode(r->conf_int[1], &lay, 0, b, sizeof b);
    sb_printf(s, " %s %s\n", a, b);
    sb_puts(s, "sample estimates:\n");
    static const char *names[4][2] = {{"mean of x", NULL}, {"mean of x", "mean of y"},
                                      {"variance of x", NULL}, {"ratio of variances", NULL}};
    int ne = names[k][1] ? 2 : 1;
    sb_named(s, names[k], r->estimate, ne);
    if (r->seq_eps > 0.0) {
        mcstat__rformat1(r->seq_eps, R_DIGITS, a, sizeof a);
        sb_printf(s, "equivalence margin: %s\n", a);
    }
    mcstat__rformat1(r->alpha, R_DIGITS, a, sizeof a);
    if (r->seq_state == MCSTAT_SEQ_DECIDED) {
        sb_printf(s, "decision at alpha = %s: %s (at n = %.0f)\n\n", a, mcstat_decision_name(r->decision),
                  r->seq_n_decided);
        return;
    }
    ll = (size_t)snprintf(line, sizeof line, "decision at alpha = %s: continue", a);
    if (r->seq_hold & MCSTAT_SEQ_HOLD_DEGENERATE)
        ll += (size_t)snprintf(line + ll, sizeof line - ll, " (held: no spread yet)");
    else if (r->seq_hold & MCSTAT_SEQ_HOLD_KURTOSIS) {
        mcstat__rformat1(r->seq_n_gate, 4, b, sizeof b);
        ll += (size_t)snprintf(line + ll, sizeof line - ll, " (held: heavy tails, the kurtosis asks for n >= %s)", b);
    } else if (r->seq_hold & MCSTAT_SEQ_HOLD_FEW)
        ll += (size_t)snprintf(line + ll, sizeof line - ll, " (held: too few values)");
    else
        ll += (size_t)snprintf(line + ll, sizeof line - ll, " (no decision yet)");
    sb_puts(s, line);
    sb_puts(s, "\n\n");
}

/* ---- the tests with a block of their own ----------------------------------
 * Every test but the t, chi-squared, F and binomial ones (print.htest's
 * generic block below): its formatter, and whether its block reads the
 * alternative (the goodness-of-fit and TOST blocks print none). */
typedef void (*block_fn)(const mcstat_result *r, const char *x_name, const char *y_name, sbuf *s);

static void format_chisq_xy(const mcstat_result *r, const char *x_name, const char *y_name, sbuf *s)
{
    (void)y_name;
    format_chisq(r, x_name, s);
}

static block_fn own_block(const mcstat_result *r, int *reads_alternative)
{
    *reads_alternative = 1;
    switch (r->test) {
    case MCSTAT_TEST_CHISQ_GOF: *reads_alternative = 0; return format_chisq_xy;
    case MCSTAT_TEST_EQUIV_1:
    case MCSTAT_TEST_EQUIV_2: *reads_alternative = 0; return format_equiv;
    case MCSTAT_TEST_EFFICIENCY: return format_eff;
    case MCSTAT_TEST_KS_2: return format_ks;
    default: return is_seq(r->test) ? format_seq : NULL;
    }
}

int mcstat_result_format(const mcstat_result *r, const char *x_name, const char *y_name, char *buf,
                         size_t size, size_t *length)
{
    MCSTAT_IEEE_SCOPE();
    test_text tt;
    int reads_alternative = 0;
    block_fn own = r ? own_block(r, &reads_alternative) : NULL;
    if (own) {
        if ((!buf && size > 0) || (reads_alternative && !valid_alternative(r->alternative)))
            return MCSTAT_EINVAL;
        sbuf s = {buf, size, 0};
        if (size > 0)
            buf[0] = '\0';
        own(r, x_name ? x_name : "x", y_name ? y_name : "y", &s);
        if (length)
            *length = s.len;
        return s.len < size ? MCSTAT_OK : MCSTAT_EBUFSIZE;
    }
    if (!r || (!buf && size > 0) || !describe(r, &tt) || !valid_alternative(r->alternative))
        return MCSTAT_EINVAL;
    if (!x_name)
        x_name = "x";
    if (!y_name)
        y_name = r->test == MCSTAT_TEST_BINOM ? "n" : "y";
    sbuf s = {buf, size, 0};
    if (size > 0)
        buf[0] = '\0';
    char a[64], b[64];

    sb_printf(&s, "\n\t%s\n\n", tt.method);
    if (tt.two_sample)
        sb_printf(&s, "data:  %s and %s\n", x_name, y_name);
    else
        sb_printf(&s, "data:  %s\n", x_name);

    double pars[2] = {r->df[0], r->df[1]}; /* R's binom.test: its parameter is n, not a df */
    if (r->test == MCSTAT_TEST_BINOM)
        pars[0] = (double)r->n[0];
    sb_stat_line(&s, tt.stat_name, r->statistic, tt.param_name, pars, tt.param_name[1] ? 2 : 1, r->p_value);

    static const char *alt_text[] = {"not equal to", "less than", "greater than"};
    mcstat__rformat1(r->null_value, R_DIGITS, a, sizeof a);
    sb_printf(&s, "alternative hypothesis: true %s is %s %s\n", tt.null_name, alt_text[r->alternative], a);

    mcstat__rformat1(100.0 * (1.0 - r->alpha), R_DIGITS, a, sizeof a);
    sb_printf(&s, "%s percent confidence interval:\n", a);
    mcstat_rlayout lay;
    mcstat__rformat_layout(r->conf_int, 2, R_DIGITS, &lay);
    mcstat__rformat_encode(r->conf_int[0], &lay, 0, a, sizeof a);
    mcstat__rformat_encode(r->conf_int[1], &lay, 0, b, sizeof b);
    sb_printf(&s, " %s %s\n", a, b);

    /* print() of a named vector: each column right-justified to the wider of
     * its name and the common width of the values, followed by one space. */
    sb_puts(&s, "sample estimates:\n");
    int ne = tt.est_name[1] ? 2 : 1;
    sb_named(&s, tt.est_name, r->estimate, ne);

    mcstat__rformat1(r->alpha, R_DIGITS, a, sizeof a);
    sb_printf(&s, "decision at alpha = %s: %s\n\n", a, mcstat_decision_name(r->decision));

    if (length)
        *length = s.len;
    return s.len < size ? MCSTAT_OK : MCSTAT_EBUFSIZE;
}

/* ---- power (R's print.power.htest) ------------------------------------------
 * The method line, then "name = value" with the names right-justified to 15
 * columns, the values at 7 significant digits, then a NOTE. */
int mcstat_power_format(const mcstat_power_options *opt, char *buf, size_t size, size_t *length)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_power_options full, *o = &full;
    if (mcstat__power_options_read(opt, o) || (!buf && size > 0) || o->test < MCSTAT_POWER_T_1 ||
        o->test > MCSTAT_POWER_VAR_2 || !valid_alternative(o->alternative))
        return MCSTAT_EINVAL;
    static const char *method[] = {"", "One-sample t test power calculation", "Two-sample t test power calculation",
                                   "Welch two-sample t test power calculation",
                                   "One-sample chi-squared variance test power calculation",
                                   "Two-sample F variance test power calculation"};
    static const char *alt[] = {"two.sided", "less", "greater"};
    int is_t = o->test <= MCSTAT_POWER_WELCH;
    sbuf s = {buf, size, 0};
    if (size > 0)
        buf[0] = '\0';
    char a[64];
    sb_printf(&s, "\n     %s \n\n", method[o->test]);
#define PF_NUM(name, v)                                \
    do {                                               \
        mcstat__rformat1((v), R_DIGITS, a, sizeof a);  \
        sb_printf(&s, "%15s = %s\n", name, a);         \
    } while (0)
    PF_NUM("n", o->n);
    if (o->test == MCSTAT_POWER_WELCH || o->test == MCSTAT_POWER_VAR_2)
        PF_NUM("n.y", o->n * o->n_ratio);
    if (o->test == MCSTAT_POWER_WELCH)
        PF_NUM("sd.ratio", o->sd_ratio);
    PF_NUM(is_t ? "d" : "rho", o->effect);
    PF_NUM("sig.level", o->alpha);
    PF_NUM("power", o->power);
#undef PF_NUM
    sb_printf(&s, "%15s = %s\n", "alternative", alt[o->alternative]);
    if (o->alternative == MCSTAT_TWO_SIDED)
        sb_printf(&s, "%15s = %s\n", "strict", o->strict ? "TRUE" : "FALSE");
    static const char *note[] = {"",
                                 "d = (mean - mu0) / sd",
                                 "n is number in *each* group; d = (mean.x - mean.y) / sd",
                                 "n is the size of x, n.y that of y; d = (mean.x - mean.y) / sd.x, sd.ratio = sd.y / sd.x",
                                 "rho = variance / sigma0^2",
                                 "n is the size of x, n.y that of y; rho = (var.x / var.y) / ratio0"};
    sb_printf(&s, "\nNOTE: %s\n\n", note[o->test]);
    if (length)
        *length = s.len;
    return s.len < size ? MCSTAT_OK : MCSTAT_EBUFSIZE;
}
