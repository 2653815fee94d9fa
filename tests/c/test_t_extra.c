/*
 * test_t_extra.c - Student's pooled and the paired t test, the log p-value
 * and the interval at another level (mcstat_result_log_p_value,
 * mcstat_result_conf_int) against R (tests/data/t_ref.tsv, written by
 * tools/refgen/make_t_ref.R: t.test, var.test, pt(log.p = TRUE), qt), and
 * their bad input.
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "mcstat.h"
#include "ref_tsv.h"

#include <float.h>
#include <stdint.h>
#include <string.h>

static uint64_t rng_state = 20261203;
#include "test_rng.h"

/* |got - want| <= tol * scale, plus a few of want's ulps (R rounds est,
 * then est -+ c se): bounds near 0 are judged on the interval's scale, not
 * their own. */
#define CHECK_NEAR(got, want, scale, tol, ...)                                       \
    do {                                                                             \
        double g_ = (got), w_ = (want), s_ = (scale);                                \
        int ok_ = g_ == w_ || fabs(g_ - w_) <= (tol) * s_ + 8.0 * DBL_EPSILON * fabs(w_); \
        CHECK_MSG(ok_, "%s = %.17g, want %.17g (scale %g): ", #got, g_, w_, s_);     \
        if (!ok_)                                                                    \
            fprintf(stderr, __VA_ARGS__), fputc('\n', stderr);                       \
    } while (0)

static double num(const char *s)
{
    if (!strcmp(s, "NA") || !strcmp(s, "NaN"))
        return NAN;
    if (!strcmp(s, "Inf"))
        return INFINITY;
    if (!strcmp(s, "-Inf"))
        return -INFINITY;
    return strtod(s, NULL);
}

/* R's text: \n and \t escaped in the table. */
static void unescape(const char *s, char *out, size_t size)
{
    size_t k = 0;
    for (; *s && k + 1 < size; s++) {
        if (s[0] == '\\' && (s[1] == 'n' || s[1] == 't')) {
            out[k++] = s[1] == 'n' ? '\n' : '\t';
            s++;
        } else {
            out[k++] = *s;
        }
    }
    out[k] = '\0';
}

static void strip_decision(char *s)
{
    char *d = strstr(s, "decision at alpha");
    if (d) {
        char *e = strchr(d, '\n');
        memmove(d, e + 1, strlen(e + 1) + 1);
    }
}

static int rows_seen[8];

/* The log p-value: relative to |log p|, absolute near p = 1. */
static void check_log_p(const mcstat_result *r, double want, int line)
{
    double lp = NAN;
    int st = mcstat_result_log_p_value(r, &lp);
    CHECK_MSG(st == MCSTAT_OK, "row %d: log p status %d", line, st);
    CHECK_NEAR(lp, want, fmax(1.0, fabs(want)), 1e-12, "row %d log p", line);
    /* where p is a normal double, log p is its log */
    if (r->p_value > 1e-300 && r->p_value < 1.0)
        CHECK_NEAR(lp, log(r->p_value), fmax(1.0, fabs(lp)), 1e-12, "row %d log p vs p", line);
    if (r->p_value == 0.0)
        CHECK_MSG(isfinite(lp) && lp < -708.0, "row %d: p underflowed, log p %g", line, lp);
}

static void check_interval(const mcstat_result *r, double level, double lo, double hi, double scale, double tol,
                           int line)
{
    double ci[2] = {NAN, NAN};
    int st = mcstat_result_conf_int(r, level, ci);
    CHECK_MSG(st == MCSTAT_OK, "row %d: conf_int(%g) status %d", line, level, st);
    CHECK_NEAR(ci[0], lo, scale, tol, "row %d: lower bound at level %g", line, level);
    CHECK_NEAR(ci[1], hi, scale, tol, "row %d: upper bound at level %g", line, level);
}

static void t_row(char **f, int line)
{
    const char *kind = f[0];
    int alt = atoi(f[1]);
    double mu = num(f[2]), alpha = num(f[3]);
    size_t nx = 0, ny = 0;
    double *x = tsv_doubles(f[4], &nx), *y = strcmp(f[5], "-") ? tsv_doubles(f[5], &ny) : NULL;
    double stat = num(f[6]), df = num(f[7]), p = num(f[8]), logp = num(f[9]), lo = num(f[10]), hi = num(f[11]);
    double est = num(f[12]), est2 = num(f[13]), se = num(f[14]), conf2 = num(f[15]), lo2 = num(f[16]),
           hi2 = num(f[17]);
    mcstat_result r;
    int st, test;
    if (!strcmp(kind, "pooled")) {
        st = mcstat_t_test_2_pooled(x, nx, y, ny, mu, alt, alpha, &r);
        test = MCSTAT_TEST_T_2_POOLED;
        rows_seen[0]++;
        /* on accumulators: the same bits */
        mcstat_moments mx, my;
        mcstat_result rm;
        mcstat_moments_init(&mx);
        mcstat_moments_init(&my);
        mcstat_moments_add_array(&mx, x, nx);
        mcstat_moments_add_array(&my, y, ny);
        CHECK(mcstat_t_test_2_pooled_moments(&mx, &my, mu, alt, alpha, &rm) == st);
        CHECK_MSG(st || memcmp(&rm, &r, sizeof r) == 0, "row %d: moments differ", line);
    } else if (!strcmp(kind, "paired")) {
        CHECK(nx == ny);
        st = mcstat_t_test_paired(x, y, nx, mu, alt, alpha, &r);
        test = MCSTAT_TEST_T_PAIRED;
        rows_seen[1]++;
    } else if (!strcmp(kind, "welch")) {
        st = mcstat_t_test_2(x, nx, y, ny, mu, alt, alpha, &r);
        test = MCSTAT_TEST_T_2;
        rows_seen[2]++;
    } else {
        st = mcstat_t_test_1(x, nx, mu, alt, alpha, &r);
        test = MCSTAT_TEST_T_1;
        rows_seen[3]++;
    }
    CHECK_MSG(st == MCSTAT_OK, "row %d (%s): status %d", line, kind, st);
    if (st)
        goto done;
    CHECK_INT(r.test, test);
    CHECK_REL(r.statistic, stat, 1e-11, "row %d (%s) statistic", line, kind);
    CHECK_REL(r.df[0], df, 1e-13, "row %d df", line);
    if (p > 1e-300)
        CHECK_REL(r.p_value, p, 1e-11, "row %d (%s) p", line, kind);
    else
        CHECK_MSG(r.p_value < 1e-290, "row %d: p = %g", line, r.p_value);
    check_log_p(&r, logp, line);
    double width = isfinite(hi - lo) ? hi - lo : se;
    CHECK_NEAR(r.conf_int[0], lo, width, 1e-10, "row %d lower bound", line);
    CHECK_NEAR(r.conf_int[1], hi, width, 1e-10, "row %d upper bound", line);
    CHECK_REL(r.estimate[0], est, 1e-12, "row %d estimate", line);
    if (!isnan(est2))
        CHECK_REL(r.estimate[1], est2, 1e-12, "row %d estimate of y", line);
    CHECK_REL(r.std_error, se, 1e-11, "row %d stderr", line);
    /* the interval at the test's own level, and at R's second level */
    check_interval(&r, 1.0 - alpha, r.conf_int[0], r.conf_int[1], width, 1e-12, line);
    double width2 = isfinite(hi2 - lo2) ? hi2 - lo2 : se;
    check_interval(&r, conf2, lo2, hi2, width2, 1e-10, line);
    if (test == MCSTAT_TEST_T_PAIRED)
        CHECK(r.n[0] == nx && r.n[1] == nx && isnan(r.estimate[1]));
    /* R's block, for the two new tests */
    if ((test == MCSTAT_TEST_T_2_POOLED || test == MCSTAT_TEST_T_PAIRED) && strcmp(f[18], "-")) {
        static char want[4096], got[4096];
        unescape(f[18], want, sizeof want);
        size_t len = 0;
        st = mcstat_result_format(&r, "x", "y", got, sizeof got, &len);
        CHECK(st == MCSTAT_OK && len == strlen(got));
        strip_decision(got);
        CHECK_MSG(strcmp(got, want) == 0, "row %d block:\n%s\nR:\n%s", line, got, want);
    }
done:
    free(x);
    free(y);
}

static void var_row(char **f, int line)
{
    int two = !strcmp(f[0], "var2");
    int alt = atoi(f[1]);
    double null = num(f[2]), alpha = num(f[3]);
    size_t nx = 0, ny = 0;
    double *x = tsv_doubles(f[4], &nx), *y = two ? tsv_doubles(f[5], &ny) : NULL;
    double stat = num(f[6]), df = num(f[7]), p = num(f[8]), logp = num(f[9]), lo = num(f[10]), hi = num(f[11]);
    double est = num(f[12]), df2 = num(f[13]), conf2 = num(f[15]), lo2 = num(f[16]), hi2 = num(f[17]);
    mcstat_result r;
    int st = two ? mcstat_var_test_2(x, nx, y, ny, null, alt, alpha, &r) : mcstat_var_test_1(x, nx, null, alt, alpha, &r);
    rows_seen[two ? 4 : 5]++;
    CHECK_MSG(st == MCSTAT_OK, "row %d: status %d", line, st);
    if (!st) {
        CHECK_REL(r.statistic, stat, 1e-12, "row %d statistic", line);
        CHECK(r.df[0] == df && (!two || r.df[1] == df2));
        CHECK_REL(r.p_value, p, 1e-11, "row %d p", line);
        CHECK_REL(r.estimate[0], est, 1e-12, "row %d estimate", line);
        check_log_p(&r, logp, line);
        /* relative: variance bounds are positive */
        CHECK_REL(r.conf_int[0], lo, 1e-11, "row %d lower bound", line);
        CHECK_REL(r.conf_int[1], hi, 1e-11, "row %d upper bound", line);
        double ci[2];
        CHECK(mcstat_result_conf_int(&r, 1.0 - alpha, ci) == MCSTAT_OK);
        CHECK_REL(ci[0], r.conf_int[0], 1e-13, "row %d own lower", line);
        CHECK_REL(ci[1], r.conf_int[1], 1e-13, "row %d own upper", line);
        CHECK(mcstat_result_conf_int(&r, conf2, ci) == MCSTAT_OK);
        CHECK_REL(ci[0], lo2, 1e-11, "row %d lower bound at %g", line, conf2);
        CHECK_REL(ci[1], hi2, 1e-11, "row %d upper bound at %g", line, conf2);
    }
    free(x);
    free(y);
}

/* A result built from t, df and se alone. */
static void tsyn_row(char **f, int line)
{
    mcstat_result r;
    memset(&r, 0, sizeof r);
    r.test = MCSTAT_TEST_T_1;
    r.alternative = atoi(f[1]);
    r.null_value = num(f[2]);
    r.statistic = num(f[6]);
    r.df[0] = num(f[7]);
    r.df[1] = NAN;
    r.p_value = num(f[8]);
    r.std_error = num(f[14]);
    r.estimate[0] = num(f[12]); /* R's mu + t se */
    r.estimate[1] = NAN;
    r.alpha = 0.05;
    rows_seen[6]++;
    double logp = num(f[9]), conf2 = num(f[15]), lo2 = num(f[16]), hi2 = num(f[17]);
    check_log_p(&r, logp, line);
    double scale = isfinite(hi2 - lo2) ? fmax(hi2 - lo2, 1e-300) : fmax(fabs(isfinite(lo2) ? lo2 : hi2), r.std_error);
    /* est = null + t se formed in double-double here, rounded in R */
    check_interval(&r, conf2, lo2, hi2, fmax(scale, DBL_EPSILON * fabs(num(f[12]))), 1e-10, line);
}

static void row(char **f, int nf, void *ctx)
{
    int *line = ctx;
    ++*line;
    CHECK_MSG(nf == 19, "row %d has %d fields", *line, nf);
    if (nf != 19)
        return;
    if (!strncmp(f[0], "var", 3))
        var_row(f, *line);
    else if (!strcmp(f[0], "tsyn"))
        tsyn_row(f, *line);
    else
        t_row(f, *line);
}

static void test_reference(void)
{
    int line = 0;
    int n = tsv_read(MCSTAT_TEST_DATA_DIR "/t_ref.tsv", row, &line);
    CHECK_MSG(n >= 150, "read %d rows of t_ref.tsv", n);
    for (int k = 0; k < 7; k++)
        CHECK_MSG(rows_seen[k] >= 3, "kind %d: %d rows", k, rows_seen[k]);
}

static void test_bad_input(void)
{
    const double x[] = {1.0, 2.0, 3.5, 4.0}, y[] = {2.0, 2.5, 3.0, 6.1};
    const double c[] = {3.0, 3.0, 3.0, 3.0}, nanx[] = {1.0, NAN, 3.0, 4.0}, infx[] = {1.0, INFINITY, 3.0, 4.0};
    mcstat_result r;
    /* pooled */
    CHECK_INT(mcstat_t_test_2_pooled(NULL, 4, y, 4, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, NULL, 4, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 4, 0, 0, 0.05, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(x, 1, y, 4, 0, 0, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 0, 0, 0, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 4, 0, 0, 0.0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 4, 0, 0, 1.0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 4, 0, 0, NAN, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 4, NAN, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 4, 0, 3, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_2_pooled(nanx, 4, y, 4, 0, 0, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, infx, 4, 0, 0, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_t_test_2_pooled(c, 4, c, 3, 0, 0, 0.05, &r), MCSTAT_EDEGENERATE);
    CHECK_INT(mcstat_t_test_2_pooled(c, 4, y, 4, 0, 0, 0.05, &r), MCSTAT_OK); /* one constant sample */
    CHECK_INT(mcstat_t_test_2_pooled_moments(NULL, NULL, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    /* paired */
    CHECK_INT(mcstat_t_test_paired(NULL, y, 4, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_paired(x, NULL, 4, 0, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_paired(x, y, 4, 0, 0, 0.05, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_paired(x, y, 1, 0, 0, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_t_test_paired(x, y, 0, 0, 0, 0.05, &r), MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_t_test_paired(x, y, 4, 0, 0, -0.1, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_paired(x, y, 4, INFINITY, 0, 0.05, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_paired(nanx, y, 4, 0, 0, 0.05, &r), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_t_test_paired(x, infx, 4, 0, 0, 0.05, &r), MCSTAT_ENONFINITE);
    const double xs[] = {1.0, 2.0, 3.0}, ys[] = {0.5, 1.5, 2.5}; /* constant differences */
    CHECK_INT(mcstat_t_test_paired(xs, ys, 3, 0, 0, 0.05, &r), MCSTAT_EDEGENERATE);
    /* log p and interval */
    double lp, ci[2];
    CHECK_INT(mcstat_t_test_2_pooled(x, 4, y, 4, 0, 0, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_log_p_value(NULL, &lp), MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_log_p_value(&r, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_conf_int(NULL, 0.9, ci), MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_conf_int(&r, 0.9, NULL), MCSTAT_EINVAL);
    const double levels[] = {0.0, 1.0, -0.5, 1.5, NAN, INFINITY};
    for (int k = 0; k < 6; k++)
        CHECK_INT(mcstat_result_conf_int(&r, levels[k], ci), MCSTAT_EINVAL);
    /* a failed row's result (NaN fields), and an unknown test */
    mcstat_result bad;
    int32_t status;
    const double one[] = {1.0};
    mcstat_t_test_1_matrix(one, 1, 1, 1, 0.0, 0, 0.05, 0, &bad, &status);
    CHECK_INT(status, MCSTAT_ETOOFEW);
    CHECK_INT(mcstat_result_log_p_value(&bad, &lp), MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_conf_int(&bad, 0.9, ci), MCSTAT_EINVAL);
    bad = r;
    bad.test = 99;
    CHECK_INT(mcstat_result_log_p_value(&bad, &lp), MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_conf_int(&bad, 0.9, ci), MCSTAT_EINVAL);
    /* K-S and chi-squared GOF have no parameter interval */
    mcstat_result ks;
    CHECK_INT(mcstat_ks_test_2(x, 4, y, 4, 0, 0.05, NULL, &ks), MCSTAT_OK);
    CHECK_INT(mcstat_result_conf_int(&ks, 0.9, ci), MCSTAT_EINVAL);
    CHECK_INT(mcstat_result_log_p_value(&ks, &lp), MCSTAT_OK);
    CHECK_REL(lp, log(ks.p_value), 1e-15, "K-S exact log p");
}

/* A difference beyond DBL_MAX: the halved differences, t unchanged. */
static void test_paired_overflow(void)
{
    const double x[] = {1.7e308, 0.0, 1.0, 2.0}, y[] = {-1.0e308, 0.0, 0.0, 3.0};
    double h[4];
    for (int i = 0; i < 4; i++)
        h[i] = x[i] / 2 - y[i] / 2;
    mcstat_result r, q;
    CHECK_INT(mcstat_t_test_paired(x, y, 4, 1e307, 0, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_t_test_1(h, 4, 5e306, 0, 0.05, &q), MCSTAT_OK);
    CHECK(r.statistic == q.statistic && r.p_value == q.p_value && r.df[0] == 3.0);
    CHECK(r.estimate[0] == 2.0 * q.estimate[0] && isfinite(r.estimate[0]));
    CHECK(r.std_error == 2.0 * q.std_error && r.null_value == 1e307);
    CHECK(r.conf_int[0] == 2.0 * q.conf_int[0] || (isinf(r.conf_int[0]) && fabs(q.conf_int[0]) > DBL_MAX / 2));
    CHECK(!isnan(r.conf_int[1]));
    /* ordinary data: the one-sample test on the differences, bit for bit */
    const double a[] = {1.25, 2.5, 3.0, 4.75, 5.0}, b[] = {1.0, 2.0, 3.5, 4.0, 4.0};
    double d[5];
    for (int i = 0; i < 5; i++)
        d[i] = a[i] - b[i];
    CHECK_INT(mcstat_t_test_paired(a, b, 5, 0.1, 2, 0.1, &r), MCSTAT_OK);
    CHECK_INT(mcstat_t_test_1(d, 5, 0.1, 2, 0.1, &q), MCSTAT_OK);
    CHECK(r.statistic == q.statistic && r.p_value == q.p_value && r.conf_int[0] == q.conf_int[0] &&
          r.estimate[0] == q.estimate[0]);
}

/* The other tests' log p-values and intervals against their own fields. */
static void test_other_results(void)
{
    mcstat_result r;
    double lp, ci[2];
    /* binomial: its stored log, its Clopper-Pearson interval */
    CHECK_INT(mcstat_binom_test(3, 1000000000, 0.5, 1, 0.05, &r), MCSTAT_OK);
    CHECK(r.p_value == 0.0);
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK(lp == r.binom_log_p_value && isfinite(lp));
    for (int alt = 0; alt < 3; alt++) {
        CHECK_INT(mcstat_binom_test(7, 20, 0.3, alt, 0.1, &r), MCSTAT_OK);
        CHECK_INT(mcstat_result_conf_int(&r, 0.9, ci), MCSTAT_OK);
        CHECK_REL(ci[0], r.conf_int[0], 1e-14, "binomial lower, alt %d", alt);
        CHECK_REL(ci[1], r.conf_int[1], 1e-14, "binomial upper, alt %d", alt);
    }
    /* TOST: log of the larger one-sided p; the interval at 1 - 2 alpha */
    const double x[] = {0.1, -0.2, 0.05, 0.3, -0.1, 0.0, 0.15}, y[] = {0.2, 0.1, -0.3, 0.0, 0.25};
    CHECK_INT(mcstat_equivalence_test_2(x, 7, y, 5, -0.5, 0.4, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK_REL(lp, log(r.p_value), 1e-13, "TOST log p");
    CHECK_INT(mcstat_result_conf_int(&r, 0.9, ci), MCSTAT_OK);
    CHECK_REL(ci[0], r.conf_int[0], 1e-13, "TOST lower");
    CHECK_REL(ci[1], r.conf_int[1], 1e-13, "TOST upper");
    CHECK_INT(mcstat_equivalence_test_1(x, 7, 1e9, -0.5, 0.4, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_conf_int(&r, 0.9, ci), MCSTAT_OK);
    CHECK_NEAR(ci[0], r.conf_int[0], r.conf_int[1] - r.conf_int[0], 1e-9, "TOST offset lower");
    /* chi-squared GOF: the log of its upper tail */
    const double obs[] = {10, 20, 30, 40}, ex[] = {0.25, 0.25, 0.25, 0.25};
    CHECK_INT(mcstat_gof_chisq_test(obs, ex, 4, NULL, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK_REL(lp, log(r.p_value), 1e-13, "GOF log p");
    /* K-S asymptotic: the log of Kolmogorov's limit where p underflows */
    size_t n = 3000;
    double *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    for (size_t i = 0; i < n; i++) {
        a[i] = (double)i + 0.25;
        b[i] = (double)i + 1e6;
    }
    mcstat_ks_options o;
    mcstat_ks_options_init(&o);
    o.weight = MCSTAT_KS_WEIGHT_NONE;
    o.method = MCSTAT_METHOD_ASYMPTOTIC;
    for (int alt = 0; alt < 3; alt += 1) {
        CHECK_INT(mcstat_ks_test_2(a, n, b, n, alt, 0.05, &o, &r), MCSTAT_OK);
        CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
        double t2 = 1500.0 * r.statistic * r.statistic; /* t^2 = ne D^2 */
        if (alt == MCSTAT_GREATER) { /* x is smaller: the other tail, D = 0 */
            CHECK(lp == 0.0);
            continue;
        }
        CHECK(r.p_value == 0.0);
        CHECK_REL(lp, (alt == 0 ? M_LN2 : 0.0) - 2.0 * t2, 1e-14, "K-S log p alt %d", alt);
    }
    /* and where it does not underflow, the log of the p-value */
    for (size_t i = 0; i < n; i++)
        b[i] = (double)i + 300.5;
    CHECK_INT(mcstat_ks_test_2(a, n, b, n, 0, 0.05, &o, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK(r.p_value > 1e-300 && r.p_value < 0.5);
    CHECK_REL(lp, log(r.p_value), 1e-12, "K-S asymptotic log p");
    free(a);
    free(b);
}

/* Results at the edges of the doubles: the interval at another level is
 * still formed (no NaN, no refusal) where the statistic is infinite or
 * std_error * t would overflow Dekker's split. */
static void test_interval_edges(void)
{
    mcstat_result r;
    double ci[2], lp;
    /* data near 1 against mu0 = 1e308: t = -Inf, the interval from the mean */
    const double x[] = {1.0, 1.0 + 1e-10, 1.0 + 2e-10};
    CHECK_INT(mcstat_t_test_1(x, 3, 1e308, 0, 0.05, &r), MCSTAT_OK);
    CHECK(isinf(r.statistic) && r.statistic < 0);
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK(lp == -INFINITY); /* the tail is exactly 0 */
    CHECK_INT(mcstat_result_conf_int(&r, 0.95, ci), MCSTAT_OK);
    CHECK_NEAR(ci[0], r.conf_int[0], r.conf_int[1] - r.conf_int[0], 1e-9, "mean interval, t = -Inf");
    CHECK_NEAR(ci[1], r.conf_int[1], r.conf_int[1] - r.conf_int[0], 1e-9, "mean interval, t = -Inf");
    /* values near +-DBL_MAX: std_error 1.4e308, t 4e-309 */
    const double y[] = {-1.7e308, 1.7e308, 0.0}, z[] = {1.7e308, -1.7e308, 1.0};
    CHECK_INT(mcstat_t_test_2_pooled(y, 3, z, 3, 0.0, 0, 0.05, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_conf_int(&r, 0.5, ci), MCSTAT_OK);
    CHECK(isfinite(ci[0]) && isfinite(ci[1]) && ci[0] < 0.0 && ci[1] > 0.0);
    CHECK_REL(-ci[0], ci[1], 1e-12, "symmetric interval near DBL_MAX");
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK(lp == 0.0 || (lp < 0.0 && lp > -1e-300));
}

/* A value of any magnitude: 10^[-300, 300], either sign, sometimes 0. */
static double wild(void)
{
    double u = unif();
    if (u < 0.05)
        return 0.0;
    return (unif() < 0.5 ? -1.0 : 1.0) * pow(10.0, 600.0 * unif() - 300.0);
}

/* No result with status OK carries NaN, and its log p-value and intervals
 * at other levels are never NaN with OK either: random data across the
 * doubles' range (offsets, spreads, sizes), nulls, levels and alternatives. */
static void test_never_nan_with_ok(void)
{
    double x[40], y[40];
    int ok = 0;
    for (int it = 0; it < 4000; it++) {
        size_t nx = 2 + (size_t)(unif() * 30), ny = 2 + (size_t)(unif() * 30);
        double cx = wild(), cy = unif() < 0.5 ? cx : wild(), sx = fabs(wild()), sy = fabs(wild());
        for (size_t i = 0; i < nx; i++)
            x[i] = cx + sx * normal();
        for (size_t i = 0; i < ny; i++)
            y[i] = unif() < 0.3 ? x[i % nx] + sy * normal() : cy + sy * normal();
        double mu0 = unif() < 0.5 ? 0.0 : wild(), alpha = unif() < 0.5 ? 0.05 : pow(10.0, -300.0 * unif());
        int alt = (int)(unif() * 3);
        mcstat_result r;
        int st;
        switch (it % 3) {
        case 0: st = mcstat_t_test_2_pooled(x, nx, y, ny, mu0, alt, alpha, &r); break;
        case 1: st = mcstat_t_test_paired(x, y, nx < ny ? nx : ny, mu0, alt, alpha, &r); break;
        default: st = mcstat_t_test_2(x, nx, y, ny, mu0, alt, alpha, &r); break;
        }
        if (st)
            continue;
        ok++;
        CHECK_MSG(!isnan(r.statistic) && !isnan(r.p_value) && !isnan(r.df[0]) && !isnan(r.conf_int[0]) &&
                      !isnan(r.conf_int[1]) && !isnan(r.std_error) && !isnan(r.estimate[0]),
                  "iteration %d: NaN with OK", it);
        double lp, ci[2];
        st = mcstat_result_log_p_value(&r, &lp);
        CHECK_MSG(st == MCSTAT_OK && !isnan(lp) && lp <= 0.0, "iteration %d: log p %g, status %d", it, lp, st);
        if (st == MCSTAT_OK && r.p_value > 1e-300)
            CHECK_NEAR(lp, log(r.p_value), fmax(1.0, fabs(lp)), 1e-10, "iteration %d", it);
        const double levels[] = {0.5, 0.95, 0.999999, 1e-300, 1.0 - 1e-16};
        for (int k = 0; k < 5; k++) {
            st = mcstat_result_conf_int(&r, levels[k], ci);
            if (st == MCSTAT_OK)
                CHECK_MSG(!isnan(ci[0]) && !isnan(ci[1]) && ci[0] <= ci[1], "iteration %d level %g: [%g, %g]", it,
                          levels[k], ci[0], ci[1]);
            else
                CHECK_MSG(st == MCSTAT_ENUMERIC, "iteration %d level %g: status %d", it, levels[k], st);
        }
    }
    CHECK_MSG(ok > 2000, "only %d of 4000 random tests ran", ok);
    /* results with arbitrary fields (a caller's struct, a corrupt file):
     * an error status or a non-NaN answer, never a crash */
    const double vals[] = {NAN, INFINITY, -INFINITY, 0.0, -1.0, 1e-320, 1e308, 3.0, 0.5};
    for (int it = 0; it < 20000; it++) {
        mcstat_result r;
        memset(&r, 0, sizeof r);
        r.test = (int)(unif() * 13);
        r.method = (int)(unif() * 5);
        r.alternative = (int)(unif() * 4);
        r.n[0] = (uint64_t)(unif() * 5);
        r.n[1] = (uint64_t)(unif() * 5);
        double *f[] = {&r.statistic, &r.df[0], &r.df[1], &r.p_value, &r.std_error, &r.null_value,
                       &r.estimate[0], &r.estimate[1], &r.reserved[0], &r.reserved[1], &r.reserved[2],
                       &r.reserved[3], &r.reserved[4], &r.reserved[5]};
        for (size_t k = 0; k < sizeof f / sizeof f[0]; k++)
            *f[k] = vals[(int)(unif() * 9)];
        double lp, ci[2];
        if (mcstat_result_log_p_value(&r, &lp) == MCSTAT_OK)
            CHECK_MSG(!isnan(lp), "fields %d: NaN log p with OK (test %d)", it, r.test);
        if (mcstat_result_conf_int(&r, unif(), ci) == MCSTAT_OK)
            CHECK_MSG(!isnan(ci[0]) && !isnan(ci[1]), "fields %d: NaN interval with OK (test %d)", it, r.test);
    }
}

int main(void)
{
    test_reference();
    test_bad_input();
    test_paired_overflow();
    test_other_results();
    test_interval_edges();
    test_never_nan_with_ok();
    printf("test_t_extra: %d checks, %d failures\n", h_checks, h_failures);
    return h_failures != 0;
}
