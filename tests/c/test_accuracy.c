/*
 * test_accuracy.c - every case of the accuracy table (tests/data/
 * accuracy_cases.tsv: the distributions' cdf, log cdf and quantile and the
 * tests' p-values over the domains of libmcstat/ACCURACY.md, with 50-digit
 * references) within its domain's bound (tests/data/accuracy.tsv); and every
 * domain checked on as many cases as the table was measured on.
 * Both files are written by tools/refgen/make_accuracy.py.
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "mcstat.h"
#include "ref_accuracy.h"

#include <stdint.h>

static int ncases;

static int is(const char *func, const char *name)
{
    return !strcmp(func, name);
}

/* The sample "n,base,mult,off,mod,s": x_i = base + ((i mult + off) % mod)
 * 2^-s, i < n (make_accuracy.py's lattice(): every value exact, so both
 * sides build the same sample); NULL for "-". */
static double *lattice(const char *spec, size_t *n)
{
    *n = 0;
    if (!strcmp(spec, "-"))
        return NULL;
    char *p;
    unsigned long long len = strtoull(spec, &p, 10);
    double base = strtod(p + 1, &p);
    unsigned long long mult = strtoull(p + 1, &p, 10);
    unsigned long long off = strtoull(p + 1, &p, 10);
    unsigned long long mod = strtoull(p + 1, &p, 10);
    int s = (int)strtol(p + 1, &p, 10);
    double *x = malloc((len ? len : 1) * sizeof *x);
    if (!x || mod == 0) {
        fprintf(stderr, "bad sample %s\n", spec);
        exit(2);
    }
    for (unsigned long long i = 0; i < len; i++)
        x[i] = base + ldexp((double)((i * mult + off) % mod), -s);
    *n = (size_t)len;
    return x;
}

static double test_p_value(const char *func, double a, double b, double c, int alt, const char *xs,
                           const char *ys, int *status)
{
    size_t nx, ny;
    double *x = lattice(xs, &nx), *y = lattice(ys, &ny);
    mcstat_result r;
    int st;
    if (is(func, "t_test_1"))
        st = mcstat_t_test_1(x, nx, a, alt, 0.05, &r);
    else if (is(func, "t_test_2"))
        st = mcstat_t_test_2(x, nx, y, ny, a, alt, 0.05, &r);
    else if (is(func, "var_test_1"))
        st = mcstat_var_test_1(x, nx, a, alt, 0.05, &r);
    else if (is(func, "var_test_2"))
        st = mcstat_var_test_2(x, nx, y, ny, a, alt, 0.05, &r);
    else if (is(func, "equivalence_test_1"))
        st = mcstat_equivalence_test_1(x, nx, a, b, c, 0.05, &r);
    else if (is(func, "equivalence_test_2"))
        st = mcstat_equivalence_test_2(x, nx, y, ny, b, c, 0.05, &r);
    else if (is(func, "binom_test"))
        st = mcstat_binom_test((uint64_t)a, (uint64_t)b, c, alt, 0.05, &r);
    else {
        fprintf(stderr, "unknown function %s in accuracy_cases.tsv\n", func);
        exit(2);
    }
    free(x);
    free(y);
    *status = st;
    return st == MCSTAT_OK ? r.p_value : NAN;
}

static double dist(const char *func, double a, double df1, double df2, int upper, int *status)
{
    double v = NAN;
    int st;
    if (is(func, "t_cdf"))
        st = mcstat_t_cdf(a, df1, upper, &v);
    else if (is(func, "t_logcdf"))
        st = mcstat_t_logcdf(a, df1, upper, &v);
    else if (is(func, "t_quantile"))
        st = mcstat_t_quantile(a, df1, upper, &v);
    else if (is(func, "chisq_cdf"))
        st = mcstat_chisq_cdf(a, df1, upper, &v);
    else if (is(func, "chisq_logcdf"))
        st = mcstat_chisq_logcdf(a, df1, upper, &v);
    else if (is(func, "chisq_quantile"))
        st = mcstat_chisq_quantile(a, df1, upper, &v);
    else if (is(func, "f_cdf"))
        st = mcstat_f_cdf(a, df1, df2, upper, &v);
    else if (is(func, "f_logcdf"))
        st = mcstat_f_logcdf(a, df1, df2, upper, &v);
    else if (is(func, "f_quantile"))
        st = mcstat_f_quantile(a, df1, df2, upper, &v);
    else
        return test_p_value(func, a, df1, df2, upper, "-", "-", status);
    *status = st;
    return v;
}

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && !strcmp(s + n - m, tail);
}

/* f: func domain a b c flag ref x y (make_accuracy.py's write_cases) */
static void check_case(char **f, int nf, void *ctx)
{
    (void)ctx;
    CHECK_INT(nf, 9);
    if (nf != 9)
        return;
    const char *func = f[0];
    double a = strtod(f[2], NULL), b = strtod(f[3], NULL), c = strtod(f[4], NULL), ref = strtod(f[6], NULL);
    int flag = atoi(f[5]), st;
    int is_dist = ends_with(func, "_cdf") || ends_with(func, "_logcdf") || ends_with(func, "_quantile");
    double got = is_dist ? dist(func, a, b, c, flag, &st) : test_p_value(func, a, b, c, flag, f[7], f[8], &st);
    /* the domain's probability band, as make_accuracy.py's band() */
    char domain[160];
    if (ends_with(func, "_logcdf"))
        snprintf(domain, sizeof domain, "%s", f[1]);
    else
        snprintf(domain, sizeof domain, "%s, %s", f[1],
                 (ends_with(func, "_quantile") ? a : ref) >= 1e-30 ? "p >= 1e-30" : "p < 1e-30");
    acc_row *row = acc_find(func, domain);
    row->seen++;
    ncases++;
    if (st != MCSTAT_OK || !isfinite(got)) {
        /* allowed only as often as the table says (a known defect) */
        if (++row->nfail > row->failed)
            CHECK_MSG(0, "%s [%s] at (%s, %s, %s, flag %d): %s, result %g", func, domain, f[2], f[3], f[4], flag,
                      mcstat_strerror(st), got);
        return;
    }
    double e = ends_with(func, "_logcdf") ? acc_log_err(got, ref) : acc_rel(got, ref);
    if (e > row->worst)
        row->worst = e;
    CHECK_MSG(e <= row->bound, "%s [%s] at (%s, %s, %s, flag %d): %.17g, want %.17g: error %.3g > bound %g",
              func, domain, f[2], f[3], f[4], flag, got, ref, e, row->bound);
}

int main(void)
{
    int n = tsv_read(MCSTAT_TEST_DATA_DIR "/accuracy_cases.tsv", check_case, NULL);
    CHECK_MSG(n > 1000, "read %d cases from accuracy_cases.tsv", n);
    /* every domain of the table checked on all its cases (the rows measured
     * on other tests' tables, ref_data.h and ref_ks.h, are those tests') */
    int domains = 0;
    for (int i = 0; i < acc_nrows; i++) {
        acc_row *r = &acc_rows[i];
        if (!strncmp(r->domain, "ref_", 4))
            continue;
        domains++;
        CHECK_MSG(r->seen == r->cases, "%s / %s: %d cases checked, the table has %d", r->func, r->domain,
                  r->seen, r->cases);
        if (getenv("MCSTAT_VERBOSE"))
            printf("%-20s %-60s %4d  worst %.3g  bound %g  failed %d\n", r->func, r->domain, r->seen, r->worst,
                   r->bound, r->nfail);
    }
    printf("%d cases in %d domains\n", ncases, domains);
    return h_report("test_accuracy");
}
