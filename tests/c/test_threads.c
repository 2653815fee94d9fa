/*
 * test_threads.c - thread safety: T threads call every public function of
 * mcstat.h at the same time, on shared read-only inputs and one shared
 * mcstat_ks_cache, and each thread's outputs must be bit for bit those of a
 * single-threaded run of the same calls.
 *
 * A second shared cache is too small for more than a few entries, so threads
 * evict each other's entries while they use it.
 * Every call appends (status, output bytes) to a per-thread log; the logs are
 * compared with memcmp against a log made first by the main thread alone.
 * Per-thread accumulators (moments, streams, their serialized bytes) over
 * disjoint slices are merged by the main thread afterwards, in thread order,
 * and must equal the same merges done single-threaded.  The inputs must be
 * unchanged afterwards.  `make tsan-test` runs this under ThreadSanitizer,
 * which reports any data race even when the outputs happen to agree.
 *
 * Not called concurrently: mcstat_gsl_handler_off and _off_if_default, which
 * set GSL's process-wide handler (documented as a global; calling them from
 * several threads races inside GSL by design).
 *
 * Size knob: MCSTAT_TEST_THREADS=T (default 4, 2..16) and
 * MCSTAT_TEST_THREADS_REPS=R (default 2): each thread repeats the battery R
 * times.  Smaller values shrink the run under valgrind or sanitizers; every
 * call is still made by every thread.
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "mcstat.h"

#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t rng_state = 20261123;
#include "test_rng.h"

/* ---- shared read-only inputs ---------------------------------------------- */
#define NX 257
#define NY 311
#define NT 60      /* tied samples (values on a coarse grid) */
#define ROWS 24
#define RNX 13     /* row sizes and strides (larger than the rows) */
#define RSX 16
#define RNY 9
#define RSY 11
#define NBIG 40000 /* split into per-thread slices */
#define MAXT 16

static double X[NX], Y[NY], XN[NX], XT[NT], YT[NT + 7];
static double XROW[ROWS * RSX], YROW[ROWS * RSY];
static double BIG[NBIG];

static void fill_inputs(void)
{
    for (int i = 0; i < NX; i++)
        X[i] = 1e3 + 2.0 * normal();
    for (int i = 0; i < NY; i++)
        Y[i] = 1e3 + 0.3 + 2.5 * normal();
    memcpy(XN, X, sizeof X);
    for (int i = 3; i < NX; i += 41)
        XN[i] = NAN;
    for (int i = 0; i < NT; i++)
        XT[i] = floor(4.0 * unif());
    for (int i = 0; i < NT + 7; i++)
        YT[i] = floor(4.5 * unif());
    for (int i = 0; i < ROWS * RSX; i++)
        XROW[i] = normal() * (1 + i / RSX % 4) + (i / RSX % 3);
    for (int i = 0; i < ROWS * RSY; i++)
        YROW[i] = normal() * (1 + i / RSY % 5);
    XROW[5 * RSX + 2] = NAN; /* a row with a NaN: an error, or skipped with OMIT_NAN */
    for (int k = 0; k < RNX; k++)
        XROW[8 * RSX + k] = 3.25; /* a constant row: MCSTAT_EDEGENERATE */
    for (int i = 0; i < NBIG; i++)
        BIG[i] = 0.5 + normal() * (1 + (i % 7));
}

/* ---- the log -------------------------------------------------------------- */
typedef struct item {
    const char *label;
    int status;
    size_t off, len;
} item;

typedef struct log_t {
    unsigned char *buf;
    size_t used, cap;
    item *items;
    size_t n, icap;
    int oom;
} log_t;

static void log_put(log_t *L, const char *label, int status, const void *p, size_t len)
{
    if (L->oom)
        return;
    if (L->n == L->icap) {
        size_t c = L->icap ? 2 * L->icap : 256;
        item *it = realloc(L->items, c * sizeof *it);
        if (!it) {
            L->oom = 1;
            return;
        }
        L->items = it, L->icap = c;
    }
    if (L->used + len > L->cap) {
        size_t c = L->cap ? 2 * L->cap : 1 << 16;
        while (c < L->used + len)
            c *= 2;
        unsigned char *b = realloc(L->buf, c);
        if (!b) {
            L->oom = 1;
            return;
        }
        L->buf = b, L->cap = c;
    }
    if (len && p)
        memcpy(L->buf + L->used, p, len);
    L->items[L->n++] = (item){label, status, L->used, len};
    L->used += len;
}

static void log_str(log_t *L, const char *label, const char *s)
{
    log_put(L, label, s ? 0 : -1, s, s ? strlen(s) + 1 : 0);
}

static void log_free(log_t *L)
{
    free(L->buf);
    free(L->items);
    memset(L, 0, sizeof *L);
}

/* 1 when equal; otherwise reports the first difference. */
static int log_equal(const log_t *a, const log_t *b, const char *what, int t)
{
    if (a->oom || b->oom) {
        fprintf(stderr, "%s, thread %d: out of memory\n", what, t);
        return 0;
    }
    if (a->n != b->n) {
        fprintf(stderr, "%s, thread %d: %zu calls, single-threaded %zu\n", what, t, b->n, a->n);
        return 0;
    }
    for (size_t i = 0; i < a->n; i++) {
        const item *x = &a->items[i], *y = &b->items[i];
        if (x->status != y->status || x->len != y->len ||
            memcmp(a->buf + x->off, b->buf + y->off, x->len) != 0) {
            fprintf(stderr, "%s, thread %d: call %zu (%s) differs: status %d vs %d\n", what, t, i, x->label,
                    y->status, x->status);
            return 0;
        }
    }
    return 1;
}

/* A result struct starts from the same bytes in every run, so a field the
 * library leaves unwritten compares equal rather than as stack noise. */
static void blank(mcstat_result *r, size_t n)
{
    memset(r, 0x5a, n * sizeof *r);
}

/* ---- the battery: every public function ----------------------------------- */
static void log_result(log_t *L, const char *label, int st, const mcstat_result *r)
{
    log_put(L, label, st, r, sizeof *r);
    char text[2048];
    size_t len = 0;
    int fs = mcstat_result_format(r, "x", "y", text, sizeof text, &len);
    if (st == MCSTAT_OK) {
        log_put(L, "result_format", fs, &len, sizeof len);
        log_str(L, "result_format text", fs == MCSTAT_OK ? text : "");
        char small[40]; /* a prefix and MCSTAT_EBUFSIZE */
        fs = mcstat_result_format(r, NULL, NULL, small, sizeof small, &len);
        log_put(L, "result_format small", fs, &len, sizeof len);
        log_str(L, "result_format prefix", small);
    }
}

static void battery_classic(log_t *L)
{
    mcstat_result r;
    for (int alt = 0; alt < 3; alt++) {
        blank(&r, 1);
        log_result(L, "t_test_1", mcstat_t_test_1(X, NX, 1e3, alt, 0.05, &r), &r);
        blank(&r, 1);
        log_result(L, "t_test_2", mcstat_t_test_2(X, NX, Y, NY, -0.1, alt, 0.01, &r), &r);
        blank(&r, 1);
        log_result(L, "var_test_1", mcstat_var_test_1(X, NX, 4.0, alt, 0.05, &r), &r);
        blank(&r, 1);
        log_result(L, "var_test_2", mcstat_var_test_2(X, NX, Y, NY, 0.7, alt, 0.1, &r), &r);
    }
    /* bad input: the status, and the output left alone */
    blank(&r, 1);
    log_result(L, "t_test_1 too few", mcstat_t_test_1(X, 1, 0, 0, 0.05, &r), &r);
    blank(&r, 1);
    log_result(L, "t_test_1 NaN", mcstat_t_test_1(XN, NX, 0, 0, 0.05, &r), &r);
    blank(&r, 1);
    log_result(L, "var_test_2 alpha", mcstat_var_test_2(X, NX, Y, NY, 1, 0, 1.5, &r), &r);

    /* moments: by array, one at a time, skipping NaN; derived values */
    mcstat_moments mx, my, mn, mm;
    log_put(L, "moments_init", mcstat_moments_init(&mx), &mx, sizeof mx);
    log_put(L, "moments_add_array", mcstat_moments_add_array(&mx, X, NX), &mx, sizeof mx);
    mcstat_moments_init(&my);
    for (int i = 0; i < NY; i++) {
        int st = mcstat_moments_add(&my, Y[i]);
        if (st)
            log_put(L, "moments_add", st, &i, sizeof i);
    }
    log_put(L, "moments_add", 0, &my, sizeof my);
    mcstat_moments_init(&mn);
    size_t omitted = 0;
    log_put(L, "moments_add_array_omit_nan", mcstat_moments_add_array_omit_nan(&mn, XN, NX, &omitted), &mn,
            sizeof mn);
    log_put(L, "n_omitted", 0, &omitted, sizeof omitted);
    log_put(L, "moments_add_array NaN", mcstat_moments_add_array(&mn, XN, NX), &mn, sizeof mn);
    double d[5] = {mcstat_moments_mean(&mx), mcstat_moments_var(&mx), mcstat_moments_sd(&mx),
                   mcstat_moments_skewness(&mx), mcstat_moments_kurtosis(&mx)};
    log_put(L, "moments derived", 0, d, sizeof d);
    mm = mx;
    log_put(L, "moments_merge", mcstat_moments_merge(&mm, &my), &mm, sizeof mm);
    log_put(L, "moments_merge self", mcstat_moments_merge(&mm, &mm), &mm, sizeof mm);
    unsigned char bytes[MCSTAT_MOMENTS_BYTES];
    memset(bytes, 0, sizeof bytes);
    log_put(L, "moments_to_bytes", mcstat_moments_to_bytes(&mm, bytes, sizeof bytes), bytes, sizeof bytes);
    mcstat_moments back;
    memset(&back, 0x5a, sizeof back);
    log_put(L, "moments_from_bytes", mcstat_moments_from_bytes(bytes, sizeof bytes, &back), &back, sizeof back);
    bytes[17] ^= 4;
    log_put(L, "moments_from_bytes corrupt", mcstat_moments_from_bytes(bytes, sizeof bytes, &back), &back,
            sizeof back);

    /* the tests on accumulators */
    for (int alt = 0; alt < 3; alt++) {
        blank(&r, 1);
        log_result(L, "t_test_1_moments", mcstat_t_test_1_moments(&mx, 1e3, alt, 0.05, &r), &r);
        blank(&r, 1);
        log_result(L, "t_test_2_moments", mcstat_t_test_2_moments(&mx, &my, 0, alt, 0.05, &r), &r);
        blank(&r, 1);
        log_result(L, "var_test_1_moments", mcstat_var_test_1_moments(&mn, 3.5, alt, 0.05, &r), &r);
        blank(&r, 1);
        log_result(L, "var_test_2_moments", mcstat_var_test_2_moments(&mx, &my, 1, alt, 0.05, &r), &r);
    }
}

static void battery_rows(log_t *L)
{
    static const unsigned flags[3] = {0, MCSTAT_ROWS_NO_INTERVALS, MCSTAT_ROWS_OMIT_NAN};
    mcstat_result out[ROWS];
    int32_t status[ROWS];
    for (int f = 0; f < 3; f++)
        for (int alt = 0; alt < 3; alt++) {
            int st;
            memset(status, 0x5a, sizeof status);
            blank(out, ROWS);
            st = mcstat_t_test_1_matrix(XROW, RNX, RSX, ROWS, 0.2, alt, 0.05, flags[f], out, status);
            log_put(L, "t_test_1_rows", st, out, sizeof out);
            log_put(L, "t_test_1_rows status", st, status, sizeof status);
            blank(out, ROWS);
            st = mcstat_t_test_2_matrix(XROW, RNX, RSX, YROW, RNY, RSY, ROWS, 0.0, alt, 0.05, flags[f], out,
                                      status);
            log_put(L, "t_test_2_rows", st, out, sizeof out);
            log_put(L, "t_test_2_rows status", st, status, sizeof status);
            blank(out, ROWS);
            st = mcstat_var_test_1_matrix(XROW, RNX, RSX, ROWS, 2.0, alt, 0.05, flags[f], out, status);
            log_put(L, "var_test_1_rows", st, out, sizeof out);
            log_put(L, "var_test_1_rows status", st, status, sizeof status);
            blank(out, ROWS);
            st = mcstat_var_test_2_matrix(XROW, RNX, RSX, YROW, RNY, RSY, ROWS, 1.0, alt, 0.05, flags[f], out,
                                        NULL);
            log_put(L, "var_test_2_rows", st, out, sizeof out);
        }
}

/* K-S with every method, both weights, every alternative; the simulated
 * ones through `shared` (the cache every thread uses), through `tiny` (also
 * shared, too small for more than a few entries: threads evict each other's
 * entries) and through a cache private to this call. */
static void battery_ks(log_t *L, mcstat_ks_cache *shared, mcstat_ks_cache *tiny)
{
    mcstat_ks_cache *own = NULL;
    int st = mcstat_ks_cache_new(1 << 20, &own);
    log_put(L, "ks_cache_new", st, NULL, 0);
    static const int methods[4] = {MCSTAT_METHOD_EXACT, MCSTAT_METHOD_SIMULATE, MCSTAT_METHOD_ASYMPTOTIC,
                                   MCSTAT_METHOD_AUTO};
    struct {
        const double *x, *y;
        size_t nx, ny;
    } data[3] = {{X, Y, NX, NY}, {XT, YT, NT, NT + 7}, {X, Y + 5, 1, 1}};
    mcstat_result r;
    for (int dset = 0; dset < 3; dset++)
        for (int w = 0; w < 2; w++)
            for (int m = 0; m < 4; m++)
                for (int alt = 0; alt < 3; alt++) {
                    mcstat_ks_options o;
                    log_put(L, "ks_options_init", mcstat_ks_options_init(&o), &o, sizeof o);
                    o.weight = w;
                    o.method = methods[m];
                    o.n_sim = 1000;
                    o.seed = 99 + (uint64_t)alt;
                    o.threads = 2;
                    o.cache = shared;
                    blank(&r, 1);
                    st = mcstat_ks_test_2(data[dset].x, data[dset].nx, data[dset].y, data[dset].ny, alt, 0.05,
                                          &o, &r);
                    log_result(L, "ks_test_2", st, &r);
                    if (methods[m] == MCSTAT_METHOD_SIMULATE) {
                        o.cache = tiny;
                        blank(&r, 1);
                        st = mcstat_ks_test_2(data[dset].x, data[dset].nx, data[dset].y, data[dset].ny, alt,
                                              0.05, &o, &r);
                        log_result(L, "ks_test_2 tiny shared cache", st, &r);
                        uint64_t e = 0; /* read while others write: the value varies, the call must not race */
                        log_put(L, "ks_cache_stats shared", mcstat_ks_cache_stats(shared, NULL, NULL, &e), NULL, 0);
                        o.cache = own;
                        o.threads = 1;
                        blank(&r, 1);
                        st = mcstat_ks_test_2(data[dset].x, data[dset].nx, data[dset].y, data[dset].ny, alt,
                                              0.05, &o, &r);
                        log_result(L, "ks_test_2 own cache", st, &r);
                    }
                }
    blank(&r, 1);
    log_result(L, "ks_test_2 defaults", mcstat_ks_test_2(XT, NT, YT, NT + 7, 0, 0.05, NULL, &r), &r);
    uint64_t hits = 0, misses = 0, entries = 0;
    st = mcstat_ks_cache_stats(own, &hits, &misses, &entries);
    uint64_t s[3] = {hits, misses, entries};
    log_put(L, "ks_cache_stats own", st, s, sizeof s);
    mcstat_ks_cache_free(own);
}

static void battery_dist(log_t *L)
{
    static const double xs[] = {-40, -3.5, -0.7, 0, 0.25, 1.96, 9, 300};
    static const double dfs[] = {0.5, 3, 27.5, 1e6};
    static const double ps[] = {1e-300, 1e-12, 0.025, 0.5, 0.975, 1 - 1e-9};
    for (size_t k = 0; k < sizeof dfs / sizeof *dfs; k++) {
        double df = dfs[k];
        for (int upper = 0; upper < 2; upper++) {
            for (size_t i = 0; i < sizeof xs / sizeof *xs; i++) {
                double v[6];
                int st = mcstat_t_cdf(xs[i], df, upper, &v[0]);
                st |= mcstat_t_logcdf(xs[i], df, upper, &v[1]) << 4;
                v[2] = v[3] = v[4] = v[5] = -1;
                double ax = fabs(xs[i]);
                st |= mcstat_chisq_cdf(ax, df, upper, &v[2]) << 8;
                st |= mcstat_chisq_logcdf(ax, df, upper, &v[3]) << 12;
                st |= mcstat_f_cdf(ax, df, 2.5 * df, upper, &v[4]) << 16;
                st |= mcstat_f_logcdf(ax, 7, df, upper, &v[5]) << 20;
                log_put(L, "cdfs", st, v, sizeof v);
            }
            for (size_t i = 0; i < sizeof ps / sizeof *ps; i++) {
                double q[3] = {-1, -1, -1};
                int st = mcstat_t_quantile(ps[i], df, upper, &q[0]);
                st |= mcstat_chisq_quantile(ps[i], df, upper, &q[1]) << 4;
                st |= mcstat_f_quantile(ps[i], df, 11, upper, &q[2]) << 8;
                log_put(L, "quantiles", st, q, sizeof q);
            }
        }
    }
    double bad = 0;
    log_put(L, "t_cdf NaN", mcstat_t_cdf(NAN, 3, 0, &bad), &bad, sizeof bad);
    log_put(L, "chisq_quantile p=2", mcstat_chisq_quantile(2, 3, 0, &bad), &bad, sizeof bad);
}

static void battery_misc(log_t *L)
{
    for (int code = -1; code <= 10; code++)
        log_str(L, "strerror", mcstat_strerror(code));
    static const char *names[] = {"two-sided", "two.sided", "two_sided", "less", "greater", "bogus"};
    for (int i = 0; i < 6; i++) {
        int a = -7;
        log_put(L, "alternative_parse", mcstat_alternative_parse(names[i], &a), &a, sizeof a);
    }
    for (int a = -1; a <= 3; a++)
        log_str(L, "alternative_name", mcstat_alternative_name(a));
    for (int d = -2; d <= 2; d++)
        log_str(L, "decision_name", mcstat_decision_name(d));
    log_str(L, "version", mcstat_version());
    size_t sz[6] = {mcstat_version_number(), mcstat_sizeof_moments(), mcstat_sizeof_result(),
                    mcstat_sizeof_moments_bytes(),  mcstat_sizeof_ks_options(),  mcstat_sizeof_stream()};
    log_put(L, "sizes", 0, sz, sizeof sz);
}

static void battery_stream(log_t *L)
{
    mcstat_stream *s = malloc(3 * sizeof *s);
    if (!s) {
        log_put(L, "stream malloc", -1, NULL, 0);
        return;
    }
    mcstat_stream_init(&s[0]);
    mcstat_stream_init(&s[1]);
    for (int i = 0; i < NX; i++)
        mcstat_stream_add(&s[0], X[i]);
    for (int i = 0; i < 3 * NY; i++) /* crosses a flush */
        mcstat_stream_add(&s[1], Y[i % NY]);
    mcstat_moments m;
    log_put(L, "stream_moments", mcstat_stream_moments(&s[1], &m), &m, sizeof m);
    log_put(L, "stream_merge", mcstat_stream_merge(&s[0], &s[1]), &s[0], sizeof s[0]);
    log_put(L, "stream_flush", mcstat_stream_flush(&s[0]), &s[0], sizeof s[0]);
    mcstat_result r;
    blank(&r, 1);
    log_result(L, "stream_check_mean", mcstat_stream_check_mean(&s[0], 1e3, 0.0, 0.01, &r), &r);
    blank(&r, 1);
    log_result(L, "stream_check_mean tol", mcstat_stream_check_mean(&s[0], 1e3, 0.5, 0.01, &r), &r);
    blank(&r, 1);
    log_result(L, "stream_check_var", mcstat_stream_check_var(&s[0], 4.0, 0.01, &r), &r);
    mcstat_stream_init(&s[2]);
    for (int i = 0; i < NX; i++)
        mcstat_stream_add(&s[2], XN[i]);
    blank(&r, 1);
    log_result(L, "stream_check_mean NaN", mcstat_stream_check_mean(&s[2], 1e3, 0.0, 0.01, &r), &r);
    free(s);
}

/* The functions merged later (equivalence, power, binomial and battery
 * tests, diagnostics, chi-squared goodness of fit, accumulator rows). */
static void battery_more(log_t *L)
{
    mcstat_result r;
    mcstat_moments mx, my;
    mcstat_moments_init(&mx);
    mcstat_moments_init(&my);
    mcstat_moments_add_array(&mx, X, NX);
    mcstat_moments_add_array(&my, Y, NY);
    blank(&r, 1);
    log_result(L, "equivalence_test_1", mcstat_equivalence_test_1(X, NX, 1e3, -0.5, 0.5, 0.05, &r), &r);
    blank(&r, 1);
    log_result(L, "equivalence_test_1_moments",
               mcstat_equivalence_test_1_moments(&mx, 1e3, -0.5, 0.5, 0.05, &r), &r);
    blank(&r, 1);
    log_result(L, "equivalence_test_2", mcstat_equivalence_test_2(X, NX, Y, NY, -1, 1, 0.05, &r), &r);
    blank(&r, 1);
    log_result(L, "equivalence_test_2_moments",
               mcstat_equivalence_test_2_moments(&mx, &my, -1, 1, 0.05, &r), &r);

    for (int test = MCSTAT_POWER_T_1; test <= MCSTAT_POWER_VAR_2; test++) {
        mcstat_power_options o, solved;
        log_put(L, "power_options_init", mcstat_power_options_init(&o), &o, sizeof o);
        o.test = test;
        o.n = 30;
        o.effect = test >= MCSTAT_POWER_VAR_1 ? 2.0 : 0.5;
        o.n_ratio = 1.5;
        o.sd_ratio = 2.0;
        double pw = -1;
        log_put(L, "power_compute", mcstat_power_compute(&o, &pw), &pw, sizeof pw);
        o.power = 0.8;
        memset(&solved, 0x5a, sizeof solved);
        int st = mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_N, &solved);
        log_put(L, "power_solve n", st, &solved, sizeof solved);
        char text[1024];
        size_t len = 0;
        if (st == MCSTAT_OK) {
            log_put(L, "power_format", mcstat_power_format(&solved, text, sizeof text, &len), &len, sizeof len);
            log_str(L, "power_format text", text);
        }
        memset(&solved, 0x5a, sizeof solved);
        log_put(L, "power_solve effect", mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_EFFECT, &solved), &solved,
                sizeof solved);
    }

    for (int alt = 0; alt < 3; alt++) {
        blank(&r, 1);
        log_result(L, "binom_test", mcstat_binom_test(37, 1000, 0.05, alt, 0.05, &r), &r);
        blank(&r, 1);
        log_result(L, "binom_test large", mcstat_binom_test(500001234, 1000000000, 0.5, alt, 0.01, &r), &r);
        blank(&r, 1);
        log_result(L, "battery_test", mcstat_battery_test(9, 100, 0.05, alt, 0.01, &r), &r);
    }
    double pv[NT];
    for (int i = 0; i < NT; i++)
        pv[i] = fmod(XT[i] * 0.173 + i * 0.0161, 1.0);
    /* every adjustment, with the call's own allocation and with a caller's
     * workspace (one per thread: the workspace is the caller's state) */
    static const char *adj[] = {"none", "bonferroni", "holm", "hochberg", "hommel", "BH", "BY"};
    for (size_t k = 0; k < sizeof adj / sizeof adj[0]; k++) {
        int method = -1;
        log_put(L, "p_adjust_method_parse", mcstat_p_adjust_method_parse(adj[k], &method), &method, sizeof method);
        double out[NT], work[5 * NT];
        size_t bytes = 0;
        log_put(L, "p_adjust_work_size", mcstat_p_adjust_work_size(NT, method, &bytes), &bytes, sizeof bytes);
        memset(out, 0x5a, sizeof out);
        log_put(L, "p_adjust alloc", mcstat_p_adjust(pv, NT, method, NULL, 0, out), out, sizeof out);
        memset(out, 0x5a, sizeof out);
        log_put(L, "p_adjust work", mcstat_p_adjust(pv, NT, method, work, sizeof work, out), out, sizeof out);
    }
    blank(&r, 1);
    log_result(L, "battery_test_pvalues", mcstat_battery_test_pvalues(pv, NT, 0.05, MCSTAT_GREATER, 0.01, &r),
               &r);

    mcstat_diag_options dopt;
    log_put(L, "diag_options_init", mcstat_diag_options_init(&dopt), &dopt, sizeof dopt);
    mcstat_diagnostics dg;
    memset(&dg, 0x5a, sizeof dg);
    log_put(L, "diagnose", mcstat_diag_compute(BIG, 5000, &dopt, &dg), &dg, sizeof dg);
    dopt.k = 10;
    memset(&dg, 0x5a, sizeof dg);
    log_put(L, "diagnose k", mcstat_diag_compute(Y, NY, &dopt, &dg), &dg, sizeof dg);
    double idx[2] = {-1, -1}, size2[2] = {-1, -1};
    log_put(L, "tail_index", mcstat_diag_tail_index(BIG, 5000, 0, idx), idx, sizeof idx);
    log_put(L, "t_size_edgeworth", mcstat_diag_t_size(2.0, 9.0, 4, 30, 0.05, size2), size2, sizeof size2);
    uint64_t k = 0;
    log_put(L, "batch_size_recommend", mcstat_diag_batch_size(2.0, 9.0, 30, 0.05, 0.2, &k), &k, sizeof k);

    double obs[12], expct[12];
    for (int i = 0; i < 12; i++) {
        obs[i] = 40 + (i * 7) % 13 + (i == 11 ? -35 : 0);
        expct[i] = 1.0 / 12;
    }
    mcstat_gof_options copt;
    log_put(L, "chisq_options_init", mcstat_gof_options_init(&copt), &copt, sizeof copt);
    double dme = mcstat_gof_default_min_expected();
    log_put(L, "chisq_default_min_expected", 0, &dme, sizeof dme);
    blank(&r, 1);
    log_result(L, "chisq_gof", mcstat_gof_chisq_test(obs, expct, 12, &copt, 0.05, &r), &r);
    blank(&r, 1);
    log_result(L, "chisq_gof defaults", mcstat_gof_chisq_test(obs, expct, 12, NULL, 0.01, &r), &r);

    /* accumulator rows: add, merge, serialize, test */
    mcstat_moments rx[ROWS], ry[ROWS], rb[ROWS];
    int32_t status[ROWS];
    unsigned char bytes[ROWS * MCSTAT_MOMENTS_BYTES]; /* per thread: a static buffer here raced (TSan) */
    log_put(L, "moments_init_rows", mcstat_moments_init_rows(rx, ROWS), rx, sizeof rx);
    mcstat_moments_init_rows(ry, ROWS);
    memset(status, 0x5a, sizeof status);
    log_put(L, "moments_add_rows", mcstat_moments_add_rows(rx, ROWS, XROW, RNX, RSX, 0, status), rx, sizeof rx);
    log_put(L, "moments_add_rows status", 0, status, sizeof status);
    log_put(L, "moments_add_rows omit", mcstat_moments_add_rows(rx, ROWS, XROW, RNX, RSX, MCSTAT_ROWS_OMIT_NAN, NULL),
            rx, sizeof rx);
    log_put(L, "moments_add_rows y", mcstat_moments_add_rows(ry, ROWS, YROW, RNY, RSY, 0, NULL), ry, sizeof ry);
    memcpy(rb, rx, sizeof rb);
    log_put(L, "moments_merge_rows", mcstat_moments_merge_rows(rb, ry, ROWS), rb, sizeof rb);
    memset(bytes, 0, sizeof bytes);
    log_put(L, "moments_to_bytes_rows", mcstat_moments_to_bytes_rows(rb, ROWS, bytes, sizeof bytes), bytes,
            sizeof bytes);
    memset(rb, 0x5a, sizeof rb);
    log_put(L, "moments_from_bytes_rows", mcstat_moments_from_bytes_rows(bytes, sizeof bytes, ROWS, rb), rb,
            sizeof rb);
    mcstat_result out[ROWS];
    for (int alt = 0; alt < 3; alt++) {
        int st;
        blank(out, ROWS);
        st = mcstat_t_test_1_moments_rows(rx, ROWS, 0.2, alt, 0.05, 0, out, status);
        log_put(L, "t_test_1_moments_rows", st, out, sizeof out);
        blank(out, ROWS);
        st = mcstat_t_test_2_moments_rows(rx, ry, ROWS, 0.0, alt, 0.05, 0, out, status);
        log_put(L, "t_test_2_moments_rows", st, out, sizeof out);
        blank(out, ROWS);
        st = mcstat_var_test_1_moments_rows(rx, ROWS, 2.0, alt, 0.05, MCSTAT_ROWS_NO_INTERVALS, out, status);
        log_put(L, "var_test_1_moments_rows", st, out, sizeof out);
        blank(out, ROWS);
        st = mcstat_var_test_2_moments_rows(rx, ry, ROWS, 1.0, alt, 0.05, 0, out, NULL);
        log_put(L, "var_test_2_moments_rows", st, out, sizeof out);
    }
}

static void battery(log_t *L, mcstat_ks_cache *shared, mcstat_ks_cache *tiny)
{
    battery_misc(L);
    battery_classic(L);
    battery_rows(L);
    battery_dist(L);
    battery_stream(L);
    battery_ks(L, shared, tiny);
    battery_more(L);
}

/* ---- per-thread accumulators over disjoint slices ------------------------ */
typedef struct part {
    mcstat_moments m;
    mcstat_stream s;
    unsigned char bytes[MCSTAT_MOMENTS_BYTES];
    int st;
} part;

static void slice_bounds(int t, int T, size_t *lo, size_t *hi)
{
    *lo = (size_t)NBIG * (size_t)t / (size_t)T;
    *hi = (size_t)NBIG * (size_t)(t + 1) / (size_t)T;
}

static void accumulate(part *p, int t, int T)
{
    size_t lo, hi;
    slice_bounds(t, T, &lo, &hi);
    p->st = mcstat_moments_init(&p->m);
    p->st |= mcstat_moments_add_array(&p->m, BIG + lo, hi - lo);
    p->st |= mcstat_stream_init(&p->s);
    for (size_t i = lo; i < hi; i++)
        mcstat_stream_add(&p->s, BIG[i]);
    memset(p->bytes, 0, sizeof p->bytes);
    p->st |= mcstat_moments_to_bytes(&p->m, p->bytes, sizeof p->bytes);
}

/* The end-of-frame step, by one thread: merge the parts in order. */
static uint64_t merge_parts(const part *parts, int T, log_t *L)
{
    mcstat_moments m, fromb;
    mcstat_stream *s = malloc(sizeof *s);
    if (!s) {
        log_put(L, "merge malloc", -1, NULL, 0);
        return 0;
    }
    mcstat_moments_init(&m);
    mcstat_moments_init(&fromb);
    mcstat_stream_init(s);
    for (int t = 0; t < T; t++) {
        mcstat_moments b;
        log_put(L, "part status", parts[t].st, NULL, 0);
        log_put(L, "part merge", mcstat_moments_merge(&m, &parts[t].m), &m, sizeof m);
        log_put(L, "part from_bytes", mcstat_moments_from_bytes(parts[t].bytes, sizeof parts[t].bytes, &b), &b,
                sizeof b);
        mcstat_moments_merge(&fromb, &b);
        log_put(L, "part stream_merge", mcstat_stream_merge(s, &parts[t].s), s, sizeof *s);
    }
    log_put(L, "merged from bytes", 0, &fromb, sizeof fromb);
    mcstat_moments sm;
    log_put(L, "merged stream moments", mcstat_stream_moments(s, &sm), &sm, sizeof sm);
    mcstat_result r;
    blank(&r, 1);
    log_result(L, "merged t_test_1_moments", mcstat_t_test_1_moments(&m, 0.5, 0, 0.05, &r), &r);
    blank(&r, 1);
    log_result(L, "merged stream_check_var", mcstat_stream_check_var(s, 16.0, 0.05, &r), &r);
    free(s);
    return m.n == fromb.n && m.n == sm.n ? m.n : 0;
}

/* ---- the threads --------------------------------------------------------- */
typedef struct worker {
    int t, T, reps;
    mcstat_ks_cache *cache, *tiny;
    pthread_barrier_t *start;
    log_t *logs; /* reps of them */
    part *p;
} worker;

static void *work(void *arg)
{
    worker *w = arg;
    pthread_barrier_wait(w->start); /* all threads enter the library together */
    accumulate(w->p, w->t, w->T);
    for (int k = 0; k < w->reps; k++)
        battery(&w->logs[k], w->cache, w->tiny);
    return NULL;
}

static int env_int(const char *name, int def, int lo, int hi)
{
    const char *s = getenv(name);
    if (!s || !*s)
        return def;
    int v = atoi(s);
    return v < lo ? lo : v > hi ? hi : v;
}

int main(void)
{
    const int T = env_int("MCSTAT_TEST_THREADS", 4, 2, MAXT);
    const int reps = env_int("MCSTAT_TEST_THREADS_REPS", 2, 1, 100);
    fill_inputs();
    double *copy = malloc(sizeof X + sizeof Y + sizeof XN + sizeof XROW + sizeof YROW + sizeof BIG);
    CHECK(copy != NULL);
    if (!copy)
        return h_report("test_threads");
    {
        double *c = copy;
        memcpy(c, X, sizeof X), c += NX;
        memcpy(c, Y, sizeof Y), c += NY;
        memcpy(c, XN, sizeof XN), c += NX;
        memcpy(c, XROW, sizeof XROW), c += ROWS * RSX;
        memcpy(c, YROW, sizeof YROW), c += ROWS * RSY;
        memcpy(c, BIG, sizeof BIG);
    }

    /* the single-threaded run (its own cache: cached results must equal
     * freshly simulated ones) */
    log_t ref = {0}, ref_merge = {0};
    mcstat_ks_cache *ref_cache = NULL, *ref_tiny = NULL;
    CHECK_INT(mcstat_ks_cache_new(1 << 22, &ref_cache), MCSTAT_OK);
    CHECK_INT(mcstat_ks_cache_new(1 << 15, &ref_tiny), MCSTAT_OK);
    battery(&ref, ref_cache, ref_tiny);
    CHECK(!ref.oom && ref.n > 500);
    if (getenv("MCSTAT_VERBOSE")) /* which calls failed, on purpose or not */
        for (size_t i = 0; i < ref.n; i++)
            if (ref.items[i].status)
                printf("  call %zu %s: status %d\n", i, ref.items[i].label, ref.items[i].status);
    part *ref_parts = calloc((size_t)T, sizeof *ref_parts);
    part *parts = calloc((size_t)T, sizeof *parts);
    worker *ws = calloc((size_t)T, sizeof *ws);
    log_t *logs = calloc((size_t)T * (size_t)reps, sizeof *logs);
    CHECK(ref_parts && parts && ws && logs);
    if (!ref_parts || !parts || !ws || !logs)
        return h_report("test_threads");
    for (int t = 0; t < T; t++)
        accumulate(&ref_parts[t], t, T);
    /* the slices cover the data: their merges hold all of BIG */
    CHECK_INT(merge_parts(ref_parts, T, &ref_merge), NBIG);

    /* T threads at once, one cache shared by all */
    mcstat_ks_cache *shared = NULL, *tiny = NULL;
    CHECK_INT(mcstat_ks_cache_new(1 << 22, &shared), MCSTAT_OK);
    CHECK_INT(mcstat_ks_cache_new(1 << 15, &tiny), MCSTAT_OK);
    pthread_barrier_t start;
    pthread_barrier_init(&start, NULL, (unsigned)T);
    pthread_t th[MAXT];
    for (int t = 0; t < T; t++) {
        ws[t] = (worker){t, T, reps, shared, tiny, &start, &logs[t * reps], &parts[t]};
        int st = pthread_create(&th[t], NULL, work, &ws[t]);
        CHECK_INT(st, 0);
        if (st) /* cannot start: the barrier would never open */
            return h_report("test_threads");
    }
    for (int t = 0; t < T; t++)
        pthread_join(th[t], NULL);
    pthread_barrier_destroy(&start);

    for (int t = 0; t < T; t++)
        for (int k = 0; k < reps; k++)
            CHECK_MSG(log_equal(&ref, &logs[t * reps + k], "battery", t), "repetition %d", k);
    log_t merged = {0};
    merge_parts(parts, T, &merged);
    CHECK(log_equal(&ref_merge, &merged, "per-thread accumulators merged", -1));

    /* the shared cache was used by every thread: the lookups all counted */
    uint64_t hits = 0, misses = 0, entries = 0, rh = 0, rm = 0;
    CHECK_INT(mcstat_ks_cache_stats(shared, &hits, &misses, &entries), MCSTAT_OK);
    CHECK_INT(mcstat_ks_cache_stats(ref_cache, &rh, &rm, NULL), MCSTAT_OK);
    CHECK_MSG(hits + misses == (rh + rm) * (uint64_t)(T * reps), "shared cache: %llu hits + %llu misses, want %llu",
              (unsigned long long)hits, (unsigned long long)misses, (unsigned long long)((rh + rm) * T * reps));
    CHECK(entries > 0 && hits > 0);

    /* nothing wrote to the inputs */
    {
        double *c = copy;
        CHECK(memcmp(c, X, sizeof X) == 0); c += NX;
        CHECK(memcmp(c, Y, sizeof Y) == 0); c += NY;
        CHECK(memcmp(c, XN, sizeof XN) == 0); c += NX;
        CHECK(memcmp(c, XROW, sizeof XROW) == 0); c += ROWS * RSX;
        CHECK(memcmp(c, YROW, sizeof YROW) == 0); c += ROWS * RSY;
        CHECK(memcmp(c, BIG, sizeof BIG) == 0);
    }
    printf("test_threads: %d threads x %d repetitions, %zu calls each, %zu bytes of output each\n", T, reps,
           ref.n, ref.used);

    uint64_t tiny_entries = 0, tiny_lookups = 0;
    CHECK_INT(mcstat_ks_cache_stats(tiny, &hits, &misses, &tiny_entries), MCSTAT_OK);
    tiny_lookups = hits + misses;
    CHECK_MSG(tiny_entries < tiny_lookups / (uint64_t)(T * reps), "tiny cache: %llu entries, no eviction",
              (unsigned long long)tiny_entries);
    mcstat_ks_cache_free(shared);
    mcstat_ks_cache_free(tiny);
    mcstat_ks_cache_free(ref_tiny);
    mcstat_ks_cache_free(ref_cache);
    for (int i = 0; i < T * reps; i++)
        log_free(&logs[i]);
    log_free(&ref);
    log_free(&ref_merge);
    log_free(&merged);
    free(logs);
    free(ws);
    free(parts);
    free(ref_parts);
    free(copy);
    return h_report("test_threads");
}
