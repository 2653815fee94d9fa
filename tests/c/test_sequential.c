/*
 * test_sequential.c - the sequential tests of section "Sequential, anytime-valid tests": every look of
 * the scenarios in tests/data/seq_ref.tsv (50-digit values from an
 * independent implementation of the header's formulas, written by
 * tools/refgen/make_seq_ref.py), the boundary against published values,
 * the hold on data that would fool the method, extreme magnitudes, the
 * result block, and bad input.
 */
#include "harness.h"
#include "mcstat.h"
#include "ref_tsv.h"

#include <float.h>
#include <stdint.h>
#include <string.h>

static uint64_t rng_state = 20261203;
#include "test_rng.h"

static double num(const char *s)
{
    if (!strcmp(s, "NaN"))
        return NAN;
    if (!strcmp(s, "Inf"))
        return INFINITY;
    if (!strcmp(s, "-Inf"))
        return -INFINITY;
    return strtod(s, NULL);
}

/* make_seq_ref.py's value(): the same doubles in C. */
static double value(const char *gen, long i, double shift)
{
    double u = (double)((i * 7919) % 1000) / 1000.0 - 0.5;
    if (!strcmp(gen, "lin"))
        return u + shift;
    if (!strcmp(gen, "big"))
        return ldexp(u + shift, 500);
    if (!strcmp(gen, "tiny"))
        return ldexp(u + shift, -600);
    if (!strcmp(gen, "offset"))
        return 1e9 + (u + shift) * 1e-3;
    if (!strcmp(gen, "zeros"))
        return (i * 7919) % 1000 < 10 ? (double)(((i * 31) % 17 + 1) * 10) + shift : 0.0;
    if (!strcmp(gen, "skew"))
        return (u + 0.5) * (u + 0.5) * 4.0 + shift;
    return NAN;
}

/* The scenario being replayed: its state carries over from row to row. */
typedef struct {
    char name[64];
    mcstat_seq s;
    long nx, ny;
    int rows;
} replay;

static void same(double got, double want, double tol, const char *what, const char *name, int look)
{
    if (isinf(want) || isnan(want)) {
        CHECK_MSG(got == want || (isnan(got) && isnan(want)), "%s %s look %d: %.17g, want %.17g", name, what, look,
                  got, want);
        return;
    }
    CHECK_REL(got, want, tol, "%s %s look %d", name, what, look);
}

static void row(char **f, int nf, void *ctx)
{
    replay *r = ctx;
    CHECK_INT(nf, 29);
    if (nf != 29)
        return;
    const char *name = f[0];
    int kind = atoi(f[1]), alt = atoi(f[2]);
    if (strcmp(r->name, name)) {
        mcstat_seq_options o;
        mcstat_seq_options_init(&o);
        o.alternative = alt;
        o.alpha = num(f[3]);
        o.eps = num(f[4]);
        o.t_opt = num(f[5]);
        o.kurtosis_gate = num(f[6]);
        o.var_ucb_z = num(f[7]);
        o.min_n = (uint64_t)atol(f[8]);
        CHECK_INT(mcstat_seq_init(&r->s, kind, num(f[9]), &o), MCSTAT_OK);
        snprintf(r->name, sizeof r->name, "%s", name);
        r->nx = r->ny = 0;
    }
    int look = atoi(f[16]);
    long bx = atol(f[14]), by = atol(f[15]);
    double x[1000], y[1000];
    for (long i = 0; i < bx; i++)
        x[i] = value(f[10], r->nx + i, num(f[11]));
    for (long i = 0; i < by; i++)
        y[i] = value(f[12], r->ny + i + 500000, num(f[13]));
    r->nx += bx;
    r->ny += by;
    int st = kind == MCSTAT_SEQ_MEAN_2 || kind == MCSTAT_SEQ_VAR_2
                 ? mcstat_seq_push_2_array(&r->s, x, (size_t)bx, y, (size_t)by)
                 : mcstat_seq_push_array(&r->s, x, (size_t)bx);
    CHECK_INT(st, MCSTAT_OK);
    mcstat_result res;
    CHECK_INT(mcstat_seq_result(&r->s, &res), MCSTAT_OK);
    CHECK_INT((long)res.n[0], atol(f[17]));
    CHECK_INT((long)res.n[1], atol(f[18]));
    CHECK_INT(res.seq_hold, atoi(f[19]));
    CHECK_INT(res.seq_looks, look);
    /* z and log E are quotients of sums: a few ulps of the accumulator's
     * sums, amplified where the estimate is close to its null value */
    same(res.statistic, num(f[20]), 1e-12, "z", name, look);
    same(r->s.log_e, num(f[21]), 1e-11, "log e", name, look);
    if (!res.seq_hold)
        same(res.critical[1] == INFINITY ? -res.critical[0] : res.critical[1], num(f[22]), 1e-13, "boundary",
             name, look);
    double p = num(f[23]);
    if (p > 1e-300)
        same(res.p_value, p, 1e-11, "p", name, look);
    else
        CHECK(res.p_value < 1e-290);
    same(res.conf_int[0], num(f[24]), 1e-12, "cs lower", name, look);
    same(res.conf_int[1], num(f[25]), 1e-12, "cs upper", name, look);
    CHECK_INT(res.seq_state, atoi(f[26]));
    CHECK_INT(res.seq_state ? res.decision : 0, atoi(f[27]));
    CHECK_INT((long)res.seq_n_decided, atol(f[28]));
    CHECK_INT(res.reject, res.seq_state && res.decision != 0);
    r->rows++;
}

static void test_reference(void)
{
    replay r;
    memset(&r, 0, sizeof r);
    int rows = tsv_read(MCSTAT_TEST_DATA_DIR "/seq_ref.tsv", row, &r);
    CHECK(rows > 250);
    CHECK_INT(r.rows, rows);
}

/* The two-sided boundary sqrt(t) r_t at alpha = 0.05, t_opt = 1e4 for t =
 * 1e2 ... 1e6: 9.08, 3.86, 3.04, 3.24, 3.56 (Waudby-Smith et al.'s normal-
 * mixture margin, as in their R helper std_conjmix_margin); the fixed-n
 * value 1.96 is the floor no t reaches. */
static void test_boundary_published(void)
{
    const double want[] = {9.08, 3.86, 3.04, 3.24, 3.56};
    double n = 100.0;
    for (int k = 0; k < 5; k++, n *= 10.0) {
        mcstat_moments m;
        CHECK_INT(mcstat_moments_from_summary((uint64_t)n, 0.1, n - 1.0, &m), MCSTAT_OK);
        mcstat_seq_options o;
        mcstat_seq_options_init(&o);
        o.min_n = 2;
        mcstat_seq s;
        CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &o), MCSTAT_OK);
        CHECK_INT(mcstat_seq_push_moments(&s, &m), MCSTAT_OK);
        mcstat_result r;
        CHECK_INT(mcstat_seq_result(&s, &r), MCSTAT_OK);
        CHECK_MSG(fabs(r.critical[1] - want[k]) < 0.006, "t = %g: %g, want %g", n, r.critical[1], want[k]);
        CHECK(r.critical[0] == -r.critical[1]);
    }
}

/* One-sided: the boundary is where the e-value reaches 1/alpha. */
static void test_one_sided_root(void)
{
    for (int alt = MCSTAT_LESS; alt <= MCSTAT_GREATER; alt++) {
        for (double alpha = 1e-6; alpha < 0.5; alpha *= 7.0) {
            mcstat_seq_options o;
            mcstat_seq_options_init(&o);
            o.alternative = alt;
            o.alpha = alpha;
            o.min_n = 2;
            o.kurtosis_gate = 0.0;
            mcstat_seq s;
            CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &o), MCSTAT_OK);
            mcstat_moments m;
            mcstat_moments_from_summary(1000, 0.0, 999.0, &m);
            mcstat_seq_push_moments(&s, &m);
            mcstat_result r;
            mcstat_seq_result(&s, &r);
            double b = alt == MCSTAT_GREATER ? r.critical[1] : -r.critical[0];
            CHECK(alt == MCSTAT_GREATER ? r.critical[0] == -INFINITY : r.critical[1] == INFINITY);
            /* the e-value at the boundary, as the header defines it */
            double a = 1000.0 * (-2.0 * log(2 * alpha) + log1p(-2.0 * log(2 * alpha))) / 1e4;
            double k = sqrt(a / (1.0 + a));
            double le = 0.5 * b * b * a / (1.0 + a) - 0.5 * log1p(a) + log(2.0) + log(0.5 * erfc(-b * k / sqrt(2.0)));
            CHECK_MSG(fabs(le + log(alpha)) < 1e-12, "alt %d alpha %g: log e at b = %.17g, want %.17g", alt,
                      alpha, le, -log(alpha));
        }
    }
}

/* A first batch of zeros has no spread, and 99% zeros have kurtosis ~600:
 * without the hold both "prove" a mean of 1 wrong at once. */
static void test_hold(void)
{
    mcstat_seq s;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 1.0, NULL), MCSTAT_OK);
    double x[1000] = {0};
    CHECK_INT(mcstat_seq_push_array(&s, x, 100), MCSTAT_OK);
    mcstat_result r;
    CHECK_INT(mcstat_seq_result(&s, &r), MCSTAT_OK);
    CHECK_INT(r.seq_hold, (int)MCSTAT_SEQ_HOLD_DEGENERATE);
    CHECK(r.p_value == 1.0 && r.conf_int[0] == -INFINITY && r.conf_int[1] == INFINITY);
    CHECK(isnan(r.statistic) && r.seq_state == MCSTAT_SEQ_CONTINUE && !r.reject);
    x[7] = 100.0; /* one non-zero in 200: kurtosis ~200, the gate asks ~2000 */
    CHECK_INT(mcstat_seq_push_array(&s, x, 100), MCSTAT_OK);
    CHECK_INT(mcstat_seq_result(&s, &r), MCSTAT_OK);
    CHECK_INT(r.seq_hold, (int)MCSTAT_SEQ_HOLD_KURTOSIS);
    CHECK(r.seq_n_gate > 1500.0 && r.seq_n_gate < 2500.0);
    CHECK_INT(mcstat_seq_finish(&s, &r), MCSTAT_EHEAVYTAIL);
    CHECK(r.seq_looks == 2.0);
    char buf[2048];
    CHECK_INT(mcstat_result_format(&r, "radiance", NULL, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "data:  radiance, n = 200 after 2 looks\n") != NULL);
    CHECK(strstr(buf, "continue (held: heavy tails, the kurtosis asks for n >= ") != NULL);
    /* Two small non-zeros in 100 values whose mean is 1 (they have not yet
     * met the rare large ones): held by the gate, while the plain mixture
     * (no gate, no bound) "proves" the mean wrong at once. */
    double y[100] = {0};
    y[10] = y[60] = 1.0;
    mcstat_seq_options o;
    mcstat_seq_options_init(&o);
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 1.0, &o), MCSTAT_OK);
    CHECK_INT(mcstat_seq_push_array(&s, y, 100), MCSTAT_OK);
    CHECK_INT(mcstat_seq_finish(&s, &r), MCSTAT_EHEAVYTAIL);
    CHECK(r.seq_state == MCSTAT_SEQ_CONTINUE && r.p_value == 1.0);
    o.kurtosis_gate = 0.0;
    o.var_ucb_z = 0.0;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 1.0, &o), MCSTAT_OK);
    CHECK_INT(mcstat_seq_push_array(&s, y, 100), MCSTAT_OK);
    CHECK_INT(mcstat_seq_finish(&s, &r), MCSTAT_OK);
    CHECK(r.seq_state == MCSTAT_SEQ_DECIDED && r.decision == MCSTAT_DECISION_LESS);
}

/* Pushing batches or their merge gives the same accumulators bit for bit;
 * one look at the merge equals the last look of a state that saw them. */
static void test_merge(void)
{
    double x[3000];
    for (int i = 0; i < 3000; i++)
        x[i] = normal() * 2.0 + 0.05;
    mcstat_seq a, b;
    CHECK_INT(mcstat_seq_init(&a, MCSTAT_SEQ_MEAN_1, 0.0, NULL), MCSTAT_OK);
    b = a;
    for (int k = 0; k < 3; k++)
        CHECK_INT(mcstat_seq_push_array(&a, x + 1000 * k, 1000), MCSTAT_OK);
    mcstat_moments m[3];
    for (int k = 0; k < 3; k++) {
        mcstat_moments_init(&m[k]);
        mcstat_moments_add_array(&m[k], x + 1000 * k, 1000);
    }
    mcstat_moments_merge(&m[0], &m[1]);
    mcstat_moments_merge(&m[0], &m[2]);
    CHECK_INT(mcstat_seq_push_moments(&b, &m[0]), MCSTAT_OK);
    CHECK(a.x.n == b.x.n && a.x.mean == b.x.mean && a.x.m2 == b.x.m2);
    CHECK(a.looks == 3 && b.looks == 1);
    mcstat_result ra, rb;
    mcstat_seq_result(&a, &ra);
    mcstat_seq_result(&b, &rb);
    CHECK(ra.statistic == rb.statistic);
}

/* A stream (mcstat/embedded.h's frame) pushes its values, and refuses NaN. */
static void test_stream(void)
{
    static mcstat_stream st;
    mcstat_stream_init(&st);
    double x[700];
    for (int i = 0; i < 700; i++) {
        x[i] = normal();
        mcstat_stream_add(&st, x[i]);
    }
    mcstat_seq a, b;
    mcstat_seq_init(&a, MCSTAT_SEQ_MEAN_1, 0.0, NULL);
    b = a;
    CHECK_INT(mcstat_seq_push_stream(&a, &st), MCSTAT_OK);
    CHECK_INT(mcstat_seq_push_array(&b, x, 700), MCSTAT_OK);
    CHECK(a.x.n == 700 && fabs(a.x.mean - b.x.mean) <= 1e-15);
    mcstat_stream_add(&st, NAN);
    mcstat_seq c = a;
    CHECK_INT(mcstat_seq_push_stream(&a, &st), MCSTAT_ENONFINITE);
    CHECK(memcmp(&a, &c, sizeof a) == 0);
}

static void test_bad_input(void)
{
    mcstat_seq s;
    mcstat_seq_options o;
    mcstat_seq_options_init(&o);
    CHECK_INT(mcstat_seq_init(NULL, MCSTAT_SEQ_MEAN_1, 0.0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_init(&s, 0, 0.0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_init(&s, 5, 0.0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, NAN, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_VAR_1, 0.0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_VAR_2, -1.0, NULL), MCSTAT_EINVAL);
    const double bad_alpha[] = {0.0, 1.0, -0.1, NAN, INFINITY};
    for (int k = 0; k < 5; k++) {
        mcstat_seq_options b = o;
        b.alpha = bad_alpha[k];
        CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    }
    mcstat_seq_options b = o;
    b.eps = -1.0;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    b = o;
    b.eps = 0.1;
    b.alternative = MCSTAT_GREATER;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    b = o;
    b.eps = 0.1;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_VAR_1, 1.0, &b), MCSTAT_EINVAL);
    b = o;
    b.t_opt = 0.0;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    b = o;
    b.min_n = 1;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    b = o;
    b.kurtosis_gate = -1.0;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    b = o;
    b.var_ucb_z = NAN;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    b = o;
    b.alternative = 3;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    b = o;
    b.size = 12;
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, &b), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_options_init_size(&b, 40), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_options_init_size(NULL, sizeof b), MCSTAT_EINVAL);

    /* pushes: wrong arity, NULLs, non-finite data, garbage accumulators */
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, NULL), MCSTAT_OK);
    mcstat_seq before = s;
    double x[3] = {1.0, NAN, 2.0};
    CHECK_INT(mcstat_seq_push_array(&s, x, 3), MCSTAT_ENONFINITE);
    CHECK_INT(mcstat_seq_push_array(&s, NULL, 3), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_push_2_array(&s, x, 1, x, 1), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_push_moments(&s, NULL), MCSTAT_EINVAL);
    mcstat_moments m;
    memset(&m, 0, sizeof m);
    CHECK_INT(mcstat_seq_push_moments(&s, &m), MCSTAT_EINVAL); /* never initialised */
    mcstat_moments_init(&m);
    mcstat_moments_add_array(&m, x, 1);
    mcstat_moments g = m;
    g.m2 = -1.0;
    CHECK_INT(mcstat_seq_push_moments(&s, &g), MCSTAT_EINVAL);
    g = m;
    g.mean = NAN;
    CHECK_INT(mcstat_seq_push_moments(&s, &g), MCSTAT_EINVAL);
    g = m;
    g.n = UINT64_MAX;
    mcstat_seq full = s;
    full.x.n = 5;
    CHECK_INT(mcstat_seq_push_moments(&full, &g), MCSTAT_ETOOBIG);
    CHECK(memcmp(&s, &before, sizeof s) == 0);
    CHECK_INT(mcstat_seq_push_stream(&s, NULL), MCSTAT_EINVAL);
    mcstat_seq junk;
    memset(&junk, 0xff, sizeof junk);
    mcstat_result r;
    CHECK_INT(mcstat_seq_push_array(&junk, x, 1), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_result(&junk, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_finish(NULL, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_result(&s, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_2, 0.0, NULL), MCSTAT_OK);
    CHECK_INT(mcstat_seq_push_array(&s, x, 1), MCSTAT_EINVAL);
    CHECK_INT(mcstat_seq_push_2_moments(&s, &m, NULL), MCSTAT_EINVAL);
    /* a sequence exists only at its own level */
    double ci[2];
    CHECK_INT(mcstat_seq_result(&s, &r), MCSTAT_OK);
    CHECK_INT(mcstat_result_conf_int(&r, 0.9, ci), MCSTAT_EINVAL);
    double lp;
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK(lp == 0.0);
    CHECK(!strcmp(mcstat_seq_kind_name(MCSTAT_SEQ_VAR_2), "var2") && mcstat_seq_kind_name(9) == NULL);
    CHECK(mcstat_sizeof_seq() == sizeof(mcstat_seq) && mcstat_sizeof_seq_options() == sizeof(mcstat_seq_options));
    CHECK(strstr(mcstat_strerror(MCSTAT_EHEAVYTAIL), "heavy") != NULL);
}

/* The log p-value stays finite where the p-value underflows. */
static void test_log_p(void)
{
    mcstat_seq s;
    mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, NULL);
    double x[2000];
    for (int i = 0; i < 2000; i++)
        x[i] = 10.0 + normal();
    mcstat_seq_push_array(&s, x, 2000);
    mcstat_result r;
    mcstat_seq_result(&s, &r);
    double lp;
    CHECK_INT(mcstat_result_log_p_value(&r, &lp), MCSTAT_OK);
    CHECK(r.p_value == 0.0 && lp < -1000.0 && isfinite(lp) && lp == -r.seq_log_e_max);
}

int main(void)
{
    test_reference();
    test_boundary_published();
    test_one_sided_root();
    test_hold();
    test_merge();
    test_stream();
    test_bad_input();
    test_log_p();
    return h_report("test_sequential");
}
