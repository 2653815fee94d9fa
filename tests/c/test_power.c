/*
 * test_power.c - power and sample size (power.c, noncentral.c) against R:
 * power.t.test and the closed forms of the chi-squared and F tests
 * (tests/data/power_ref.tsv, written by tools/refgen/make_power_ref.R);
 * symmetry of the alternatives; that libRmath's pnt never prints; statuses.
 */
#include "harness.h"
#include "internal.h"
#include "mcstat.h"
#include "ref_tsv.h"

#include <fcntl.h>
#include <unistd.h>

static int test_code(const char *s)
{
    return !strcmp(s, "t_1") ? MCSTAT_POWER_T_1 : !strcmp(s, "t_2") ? MCSTAT_POWER_T_2
         : !strcmp(s, "var_1") ? MCSTAT_POWER_VAR_1 : !strcmp(s, "var_2") ? MCSTAT_POWER_VAR_2 : -1;
}

static int nrows[4];

static void check_row(char **f, int nf, void *ctx)
{
    (void)ctx;
    CHECK_INT(nf, 10);
    if (nf != 10)
        return;
    mcstat_power_options o = MCSTAT_POWER_OPTIONS_INIT;
    o.test = test_code(f[1]);
    CHECK(mcstat_alternative_parse(f[2], &o.alternative) == MCSTAT_OK);
    o.strict = atoi(f[3]);
    o.n = atof(f[4]);
    o.n_ratio = atof(f[5]);
    o.sd_ratio = atof(f[6]);
    o.effect = atof(f[7]);
    o.alpha = atof(f[8]);
    o.power = atof(f[9]);
    int is_t = o.test <= MCSTAT_POWER_WELCH;
    mcstat_power_options r;
    if (!strcmp(f[0], "power")) {
        nrows[0]++;
        double p = NAN;
        int st = mcstat_power_compute(&o, &p);
        CHECK_INT(st, MCSTAT_OK);
        /* pnt is accurate to ~1e-12 absolutely; the quantiles differ from
         * R's qt / qchisq / qf in the last digits */
        CHECK_MSG(fabs(p - o.power) <= 1e-10 + 1e-9 * o.power, "%s %s %s strict %s n %s d %s alpha %s: %.15g, R %.15g",
                  f[0], f[1], f[2], f[3], f[4], f[7], f[8], p, o.power);
        CHECK_INT(mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_POWER, &r), MCSTAT_OK);
        CHECK(r.power == p);
    } else if (!strcmp(f[0], "n")) {
        nrows[1]++;
        double want = o.n;
        o.n = NAN;
        int st = mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_N, &r);
        CHECK_INT(st, MCSTAT_OK);
        if (is_t) { /* R's n is the continuous root: ours is the next integer */
            double up = ceil(want - 1e-7);
            CHECK_MSG(r.n == up || (fabs(want - round(want)) < 1e-6 && r.n == round(want) + 1),
                      "%s %s strict %s d %s power %s: n %g, R %.10g", f[1], f[2], f[3], f[7], f[9], r.n, want);
        } else {
            CHECK_MSG(r.n == want, "%s %s d %s power %s: n %g, R %g", f[1], f[2], f[7], f[9], r.n, want);
        }
        CHECK(r.power >= o.power);
        mcstat_power_options ex;
        CHECK_INT(mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_N_EXACT, &ex), MCSTAT_OK);
        CHECK_MSG(ex.n <= r.n && ex.n > r.n - 1.0, "n exact %.10g, integer %g", ex.n, r.n);
        if (is_t) /* R's uniroot stops at a tolerance of eps^(1/4) */
            CHECK_MSG(fabs(ex.n - want) <= 1e-3 * want, "%s %s strict %s d %s power %s: n %.10g, R %.10g",
                      f[1], f[2], f[3], f[7], f[9], ex.n, want);
        mcstat_power_options prev = r;
        prev.n = r.n - 1.0;
        double pp;
        if (mcstat_power_compute(&prev, &pp) == MCSTAT_OK)
            CHECK(pp < o.power);
    } else if (!strcmp(f[0], "effect")) {
        nrows[2]++;
        double want = o.effect;
        o.effect = NAN;
        CHECK_INT(mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_EFFECT, &r), MCSTAT_OK);
        CHECK_REL(r.effect, want, 1e-8, "%s %s n %s power %s", f[1], f[2], f[4], f[9]);
    } else {
        nrows[3]++;
        double want = o.alpha;
        o.alpha = NAN;
        CHECK_INT(mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_ALPHA, &r), MCSTAT_OK);
        CHECK_MSG(fabs(r.alpha - want) <= 1e-11 + 1e-7 * want, "alpha %.15g, R %.15g: " "%s %s n %s power %s", r.alpha, want, f[1], f[2], f[4], f[9]);
    }
}

/* The alternatives mirror each other: LESS at -d is GREATER at d, and for
 * the variance tests LESS at rho with (n, k) is ... checked through the
 * two-sided strict power = both one-sided powers at alpha/2. */
static void test_symmetry(void)
{
    for (int test = MCSTAT_POWER_T_1; test <= MCSTAT_POWER_VAR_2; test++) {
        for (double n = 3; n < 3000; n *= 3.7) {
            double e = test <= MCSTAT_POWER_WELCH ? 0.37 : 1.6;
            mcstat_power_options o = MCSTAT_POWER_OPTIONS_INIT;
            o.test = test;
            o.n = n;
            o.n_ratio = 1.5;
            o.sd_ratio = 2.0;
            o.alpha = 0.05;
            double two, less, greater, neg;
            o.effect = e;
            CHECK_INT(mcstat_power_compute(&o, &two), MCSTAT_OK);
            o.alpha = 0.025;
            o.alternative = MCSTAT_GREATER;
            CHECK_INT(mcstat_power_compute(&o, &greater), MCSTAT_OK);
            o.alternative = MCSTAT_LESS;
            CHECK_INT(mcstat_power_compute(&o, &less), MCSTAT_OK);
            CHECK_MSG(fabs(two - (less + greater)) < 1e-12, "test %d n %g: %.15g vs %.15g", test, n, two,
                      less + greater);
            if (test <= MCSTAT_POWER_WELCH) {
                o.effect = -e;
                CHECK_INT(mcstat_power_compute(&o, &neg), MCSTAT_OK);
                CHECK_MSG(fabs(neg - greater) < 1e-12, "test %d n %g: LESS(-d) %.15g GREATER(d) %.15g", test, n,
                          neg, greater);
            }
        }
    }
    /* Welch with equal sizes and sds is close to the pooled test at 2n */
    mcstat_power_options a = MCSTAT_POWER_OPTIONS_INIT, b;
    a.test = MCSTAT_POWER_WELCH;
    a.n = 40;
    a.effect = 0.5;
    b = a;
    b.test = MCSTAT_POWER_T_2;
    double pa, pb;
    CHECK_INT(mcstat_power_compute(&a, &pa), MCSTAT_OK);
    CHECK_INT(mcstat_power_compute(&b, &pb), MCSTAT_OK);
    CHECK_MSG(fabs(pa - pb) < 1e-12, "Welch %.15g pooled %.15g (equal n and sd: same df and ncp)", pa, pb);
}

/* libRmath's pnt prints warnings on stdout in standalone builds: call it over
 * a wide grid with fd 1 redirected to a file and check that nothing came. */
static void test_pnt_silent(void)
{
    fflush(stdout);
    char path[] = "/tmp/mcstat_pnt_XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd < 0)
        return;
    int saved = dup(1);
    dup2(fd, 1);
    static const double ts[] = {-1e6, -300, -40, -8, -2, -0.5, 0, 1e-3, 0.7, 1.96, 3, 9, 40, 100, 1e4, 1e8};
    static const double dfs[] = {0.5, 1, 2, 3, 7, 30, 200, 5e3, 1e5, 3.9e5, 4.1e5, 1e7, 1e12};
    static const double ncps[] = {-100, -40, -37.6, -20, -5, -1, -1e-3, 1e-6, 0.5, 2, 8, 25, 37, 37.7, 39, 60, 500};
    int bad = 0;
    for (size_t i = 0; i < sizeof ts / sizeof *ts; i++)
        for (size_t j = 0; j < sizeof dfs / sizeof *dfs; j++)
            for (size_t k = 0; k < sizeof ncps / sizeof *ncps; k++) {
                double lo, hi;
                int st = mcstat__nct_tails(ts[i], dfs[j], ncps[k], &lo, &hi);
                if (st != MCSTAT_OK || !(lo >= 0 && lo <= 1 && hi >= 0 && hi <= 1) || fabs(lo + hi - 1) > 1e-15) {
                    bad++;
                    fprintf(stderr, "nct(%g, %g, %g): status %d, %g %g\n", ts[i], dfs[j], ncps[k], st, lo, hi);
                }
            }
    /* and through the public calls: large n (df > 4e5), large effects */
    mcstat_power_options o = MCSTAT_POWER_OPTIONS_INIT, r;
    for (int t = MCSTAT_POWER_T_1; t <= MCSTAT_POWER_WELCH; t++)
        for (double n = 2; n < 1e9; n *= 7)
            for (double d = 1e-4; d < 1e3; d *= 5) {
                o.test = t;
                o.n = n;
                o.effect = d;
                double p;
                if (mcstat_power_compute(&o, &p) != MCSTAT_OK || !(p >= 0 && p <= 1)) {
                    bad++;
                    fprintf(stderr, "power test %d n %g d %g: %g\n", t, n, d, p);
                }
            }
    o.test = MCSTAT_POWER_T_1;
    o.effect = 1e-3; /* 0.1% bias at sd 1: n ~ 1e7, df > 4e5 */
    o.power = 0.9;
    if (mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_N, &r) != MCSTAT_OK)
        bad++;
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    off_t size = lseek(fd, 0, SEEK_END);
    close(fd);
    unlink(path);
    CHECK_MSG(size == 0, "pnt printed %ld bytes", (long)size);
    CHECK_INT(bad, 0);
    /* (z_{0.975} + z_{0.9})^2 / d^2 = 10.5074 / 1e-6, plus ~2 for the t */
    CHECK_MSG(r.n > 1.0507e7 && r.n < 1.0508e7, "n for d = 1e-3 at power 0.9: %.0f", r.n);
}

static void test_statuses(void)
{
    mcstat_power_options o = MCSTAT_POWER_OPTIONS_INIT, r;
    double p;
    o.n = 10;
    o.effect = 0.5;
    CHECK_INT(mcstat_power_compute(&o, &p), MCSTAT_OK);
    CHECK_INT(mcstat_power_compute(NULL, &p), MCSTAT_EINVAL);
    CHECK_INT(mcstat_power_compute(&o, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_power_options_init_size(NULL, sizeof r), MCSTAT_EINVAL);
    CHECK_INT((mcstat_power_options_init)(NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_power_options_init(&r), MCSTAT_OK);
    CHECK(r.size == sizeof r && r.test == MCSTAT_POWER_T_1 && r.alpha == 0.05 && r.strict == 1);
    CHECK(mcstat_sizeof_power_options() == sizeof(mcstat_power_options));
    mcstat_power_options b = o;
    b.size = 8;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.test = 9;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.alternative = 3;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.n = 1.5;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.n = NAN;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.n = INFINITY;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.effect = NAN;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.alpha = 0.0;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.alpha = 1.0;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.strict = 2;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.test = MCSTAT_POWER_VAR_1; b.effect = -1.0;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    b = o; b.test = MCSTAT_POWER_VAR_2; b.effect = 2.0; b.n_ratio = 0.1;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL); /* ny = 1 */
    b = o; b.test = MCSTAT_POWER_WELCH; b.sd_ratio = 0.0;
    CHECK_INT(mcstat_power_compute(&b, &p), MCSTAT_EINVAL);
    /* solving */
    b = o; b.power = 0.9;
    CHECK_INT(mcstat_power_solve(&b, 7, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_N, NULL), MCSTAT_EINVAL);
    b.power = 1.0;
    CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_N, &r), MCSTAT_EINVAL);
    b.power = 0.9; b.effect = 0.0; /* no n detects a zero effect */
    CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_N, &r), MCSTAT_EINVAL);
    b = o; b.power = 0.04; /* below alpha: what the null itself gives, no effect to solve for */
    CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_EFFECT, &r), MCSTAT_EINVAL);
    b.test = MCSTAT_POWER_VAR_1; b.alternative = MCSTAT_LESS; b.power = 0.05;
    CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_EFFECT, &r), MCSTAT_EINVAL);
    b.power = 0.5;
    CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_EFFECT, &r), MCSTAT_OK);
    CHECK(r.effect < 1.0); /* LESS: a variance ratio below 1 */
    b = o; b.power = 0.9; b.n = NAN; /* the unknown's field is ignored */
    CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_N, &r), MCSTAT_OK);
    CHECK(r.n == 44.0); /* power.t.test(delta = .5, power = .9, type = "one.sample") n = 43.99 */
    {
        mcstat_power_options ex;
        double pe;
        CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_N_EXACT, &ex), MCSTAT_OK);
        CHECK(ex.n > 43.9 && ex.n < 44.0);
        CHECK_INT(mcstat_power_compute(&ex, &pe), MCSTAT_OK);
        CHECK(fabs(pe - 0.9) < 1e-12);
        CHECK_INT(mcstat_power_solve(&b, MCSTAT_POWER_SOLVE_N_EXACT + 1, &ex), MCSTAT_EINVAL);
    }
    /* format */
    char buf[1024];
    size_t len;
    r.test = MCSTAT_POWER_T_1;
    CHECK_INT(mcstat_power_format(&r, buf, sizeof buf, &len), MCSTAT_OK);
    CHECK(strstr(buf, "\n     One-sample t test power calculation \n\n") == buf);
    CHECK(strstr(buf, "              n = 44\n") != NULL);
    CHECK(strstr(buf, "      sig.level = 0.05\n") != NULL);
    CHECK(strstr(buf, "    alternative = two.sided\n") != NULL);
    CHECK(len == strlen(buf));
    CHECK_INT(mcstat_power_format(&r, buf, 10, &len), MCSTAT_EBUFSIZE);
    CHECK(strlen(buf) == 9);
    CHECK_INT(mcstat_power_format(NULL, buf, sizeof buf, &len), MCSTAT_EINVAL);
}

int main(void)
{
    int n = tsv_read(MCSTAT_TEST_DATA_DIR "/power_ref.tsv", check_row, NULL);
    CHECK_MSG(n > 1500, "read %d rows of power_ref.tsv", n);
    CHECK(nrows[0] > 1000 && nrows[1] > 100 && nrows[2] > 30 && nrows[3] > 10);
    test_symmetry();
    test_pnt_silent();
    test_statuses();
    return h_report("test_power");
}
