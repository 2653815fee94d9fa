/*
 * test_fpenv.c - results do not depend on the caller's floating-point
 * environment (internal.h, MCSTAT_IEEE_SCOPE): a set of calls that meet
 * subnormals, underflow, overflow and rounding ties gives the same bytes
 * with subnormals flushed to zero and read as zero (FTZ/DAZ: a renderer
 * built with -ffast-math runs so), under each rounding direction and with
 * exceptions trapping; and the caller's mode is as it was after each call.
 */
#define _GNU_SOURCE /* feenableexcept */
#include "harness.h"
#include "mcstat.h"

#include <fenv.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

typedef struct {
    double v[32];
    int st[32];
    char text[2048];
} digest;

static void run_all(digest *d)
{
    memset(d, 0, sizeof *d);
    int k = 0;
    /* quantiles whose answer underflows or overflows: 0 and Inf exactly */
    d->st[k] = mcstat_chisq_quantile(1e-300, 1.0, 0, &d->v[k]), k++;
    d->st[k] = mcstat_f_quantile(1e-300, 1.0, 1.0, 1, &d->v[k]), k++;
    d->st[k] = mcstat_f_quantile(1e-300, 2.0, 1e9, 0, &d->v[k]), k++;
    d->st[k] = mcstat_f_quantile(1e-300, 1.0, 12.0, 0, &d->v[k]), k++;
    d->st[k] = mcstat_t_cdf(-1e300, 0.5, 0, &d->v[k]), k++;
    d->st[k] = mcstat_chisq_cdf(1e-310, 3.0, 0, &d->v[k]), k++; /* subnormal x */
    d->st[k] = mcstat_chisq_logcdf(1e-310, 3.0, 0, &d->v[k]), k++;
    /* an accumulator whose variance in the data's units underflows */
    mcstat_moments m;
    mcstat_moments_init(&m);
    m.n = 42949672985ull;
    m.mean = 1e-170;
    m.m2 = 0x1.4ffff60ff1919p-1015;
    m.min = -1e-160;
    m.max = 1e-160;
    mcstat_result r;
    d->st[k] = mcstat_t_test_1_moments(&m, 0.0, MCSTAT_TWO_SIDED, 0.05, &r);
    d->v[k++] = r.statistic;
    d->v[k++] = r.p_value;
    /* subnormal data */
    const double s[4] = {-0x0.114034bc6a7fp-1022, 0x0.0000000000007p-1022, 0.0, 0x0.8p-1022};
    d->st[k] = mcstat_t_test_1(s, 4, 0.0, MCSTAT_TWO_SIDED, 0.05, &r);
    d->v[k++] = r.statistic;
    d->v[k++] = r.conf_int[0];
    mcstat_moments a;
    mcstat_moments_init(&a);
    d->st[k] = mcstat_moments_add_array(&a, s, 4);
    d->v[k++] = a.m2;
    d->v[k++] = mcstat_moments_var(&a);
    /* a t test whose text R formats near a rounding tie, and a subnormal */
    const double x[5] = {0.1, 0.2, 0.3, 0.4, 0.55};
    d->st[k] = mcstat_t_test_1(x, 5, 4.9406564584124654e-324, MCSTAT_LESS, 0.05, &r), k++;
    size_t len = 0;
    d->st[k++] = mcstat_result_format(&r, "x", NULL, d->text, sizeof d->text, &len);
    /* the K-S test's simulation threads inherit the mode of their creator */
    const double y[6] = {0.3, 0.25, 0.9, 0.1, 0.7, 0.65};
    mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
    o.method = MCSTAT_METHOD_SIMULATE;
    o.n_sim = 20000;
    o.threads = 2;
    d->st[k] = mcstat_ks_test_2(x, 5, y, 6, MCSTAT_TWO_SIDED, 0.05, &o, &r);
    d->v[k++] = r.p_value;
    CHECK(k <= 32);
}

static int same(const digest *a, const digest *b, const char *what)
{
    int ok = !memcmp(a->v, b->v, sizeof a->v) && !memcmp(a->st, b->st, sizeof a->st) && !strcmp(a->text, b->text);
    CHECK_MSG(ok, "results differ %s", what);
    if (!ok)
        for (int i = 0; i < 32; i++)
            if (memcmp(&a->v[i], &b->v[i], sizeof(double)) || a->st[i] != b->st[i])
                fprintf(stderr, "  [%d] %a (status %d), default %a (status %d)\n", i, b->v[i], b->st[i], a->v[i],
                        a->st[i]);
    return ok;
}

int main(void)
{
#if defined(__x86_64__)
    /* make portability-test runs every test with FTZ and DAZ set from the
     * start (tests/ftz/ftz_daz.c) and says so: then the mode must be on */
    int started_ftz = (_mm_getcsr() & 0x8040) == 0x8040;
    printf("test_fpenv: started %s FTZ/DAZ\n", started_ftz ? "with" : "without");
    if (getenv("MCSTAT_EXPECT_FTZ"))
        CHECK_MSG(started_ftz, "MCSTAT_EXPECT_FTZ is set but the process did not start with FTZ and DAZ");
#endif
    digest ref, got;
    run_all(&ref);
    CHECK(ref.v[0] == 0.0 && ref.v[1] == INFINITY && ref.st[0] == MCSTAT_OK && ref.st[1] == MCSTAT_OK);

    static const struct { int mode; const char *name; } rounding[] = {
        {FE_UPWARD, "rounding upward"}, {FE_DOWNWARD, "rounding downward"}, {FE_TOWARDZERO, "rounding toward zero"}};
    for (size_t i = 0; i < sizeof rounding / sizeof rounding[0]; i++) {
        fesetround(rounding[i].mode);
        run_all(&got);
        CHECK_MSG(fegetround() == rounding[i].mode, "%s: the caller's mode was not restored", rounding[i].name);
        fesetround(FE_TONEAREST);
        same(&ref, &got, rounding[i].name);
    }
#if defined(__GLIBC__)
    /* exceptions that trap: the library's own Inf and NaN must not fire them */
    feenableexcept(FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
    if (fegetexcept() != (FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW)) { /* valgrind ignores it */
        printf("test_fpenv: skipped trapping exceptions: this machine does not enable them\n");
    } else {
        run_all(&got);
        CHECK_INT(fegetexcept(), FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW);
        fedisableexcept(FE_ALL_EXCEPT);
        same(&ref, &got, "with exceptions trapping");
    }
    fedisableexcept(FE_ALL_EXCEPT);
#endif
#if defined(__x86_64__)
    unsigned csr = _mm_getcsr();
    _mm_setcsr(csr | 0x8040); /* FTZ and DAZ */
    volatile double tiny = 0x1p-1074;
    if (!(tiny == 0.0)) { /* valgrind keeps the bits but not the behaviour */
        printf("test_fpenv: skipped FTZ/DAZ: this machine does not honour them (a subnormal is not 0)\n");
    } else {
        run_all(&got);
        CHECK_INT(_mm_getcsr() & 0x8040, 0x8040);
        same(&ref, &got, "with FTZ and DAZ");
    }
    _mm_setcsr(csr);
#else
    printf("test_fpenv: no FTZ/DAZ control on this architecture; rounding directions only\n");
#endif
    return h_report("test_fpenv");
}
