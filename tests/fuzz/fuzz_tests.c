/*
 * fuzz_tests.c - the analytic tests on arrays and on accumulators (the four,
 * Student's pooled and the paired t), the efficiency-ratio test, a result's
 * log p-value and interval at another level, and the stream checks built on
 * them.
 *
 * Input: a selector byte, x and y (fz_doubles, up to 64 values each), the
 * null value, the alternative, alpha, a flags byte.  Beyond the invariants of
 * fz_check_result: the array call is bit for bit the accumulator call on
 * mcstat_moments_add_array of the same data (they are documented as the same
 * test), a failed call leaves *out untouched, and NULL data are refused.
 * Flags bit 2: the same data through the sequential test of the same kind
 * (section "Sequential, anytime-valid tests"), pushed 8 values at a time.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#define MAXN 64

static int array_test(int which, const double *x, size_t nx, const double *y, size_t ny, double v, int alt,
                      double alpha, mcstat_result *r)
{
    switch (which) {
    case 0: return mcstat_t_test_1(x, nx, v, alt, alpha, r);
    case 1: return mcstat_t_test_2(x, nx, y, ny, v, alt, alpha, r);
    case 2: return mcstat_var_test_1(x, nx, v, alt, alpha, r);
    default: return mcstat_var_test_2(x, nx, y, ny, v, alt, alpha, r);
    }
}

static int moments_test(int which, const mcstat_moments *x, const mcstat_moments *y, double v, int alt,
                        double alpha, mcstat_result *r)
{
    switch (which) {
    case 0: return mcstat_t_test_1_moments(x, v, alt, alpha, r);
    case 1: return mcstat_t_test_2_moments(x, y, v, alt, alpha, r);
    case 2: return mcstat_var_test_1_moments(x, v, alt, alpha, r);
    default: return mcstat_var_test_2_moments(x, y, v, alt, alpha, r);
    }
}

/* A successful result's log p-value and its interval at another level
 * (mcstat_result_log_p_value, mcstat_result_conf_int). */
static void result_accessors(const mcstat_result *r, double level)
{
    double lp = NAN, ci[2] = {NAN, NAN};
    int st = mcstat_result_log_p_value(r, &lp);
    FZ_ASSERT(st == MCSTAT_OK, "log p-value: status %d", st);
    FZ_ASSERT(!isnan(lp) && lp <= 0.0, "log p %.17g", lp);
    if (r->p_value >= 1e-300) /* where p is a normal double, log p is its log (both to ~1e-13) */
        FZ_ASSERT(fabs(lp - log(r->p_value)) <= 1e-9 * fmax(1.0, fabs(lp)), "log p %.17g, p %.17g", lp,
                  r->p_value);
    st = mcstat_result_conf_int(r, level, ci);
    fz_check_status(st);
    if (!(level > 0.0 && level < 1.0))
        FZ_ASSERT(st == MCSTAT_EINVAL, "level %.17g: status %d", level, st);
    /* ordered up to the quantiles' accuracy: at a level near 0 both ends use
     * the median, solved to ~1e-15 each, so they may cross by a few ulps */
    if (st == MCSTAT_OK)
        FZ_ASSERT(!isnan(ci[0]) && !isnan(ci[1]) && fz_le(ci[0], ci[1], 1e-13), "interval %.17g %.17g at %.17g",
                  ci[0], ci[1], level);
}

/* Student's pooled test (arrays and accumulators, the same bits) and the
 * paired test on the first min(nx, ny) pairs. */
static void pooled_and_paired(const double *x, size_t nx, const double *y, size_t ny, double v, int alt,
                              double alpha, double level)
{
    mcstat_result r, rm;
    int st = mcstat_t_test_2_pooled(x, nx, y, ny, v, alt, alpha, &r);
    fz_check_result(st, &r, MCSTAT_TEST_T_2_POOLED, alt, alpha, 0);
    fz_check_not_enumeric(st, (double)(nx + ny), "pooled t");
    mcstat_moments mx, my;
    mcstat_moments_init(&mx);
    mcstat_moments_init(&my);
    if (!mcstat_moments_add_array(&mx, x, nx) && !mcstat_moments_add_array(&my, y, ny)) {
        int sm = mcstat_t_test_2_pooled_moments(&mx, &my, v, alt, alpha, &rm);
        FZ_ASSERT(sm == st, "pooled: array status %d, accumulator status %d", st, sm);
        if (st == MCSTAT_OK)
            FZ_ASSERT(memcmp(&r, &rm, sizeof r) == 0, "pooled: array and accumulator results differ");
    }
    if (st == MCSTAT_OK)
        result_accessors(&r, level);
    size_t n = nx < ny ? nx : ny;
    st = mcstat_t_test_paired(x, y, n, v, alt, alpha, &r);
    fz_check_result(st, &r, MCSTAT_TEST_T_PAIRED, alt, alpha, 0);
    fz_check_not_enumeric(st, (double)n, "paired t");
    if (st == MCSTAT_OK)
        result_accessors(&r, level);
}

/* The efficiency test with x and y as the samples, |y| and x as the two
 * timings (so negative times, zeros and single batches all occur); a
 * failure leaves *out untouched. */
static void efficiency(const double *x, size_t nx, const double *y, size_t ny, double v, int alt, double alpha,
                       double level)
{
    double ay[MAXN];
    for (size_t i = 0; i < ny; i++)
        ay[i] = fabs(y[i]);
    mcstat_moments m[4];
    const double *d[4] = {x, y, ay, x};
    size_t n[4] = {nx, ny, ny, nx};
    for (int k = 0; k < 4; k++) {
        mcstat_moments_init(&m[k]);
        if (mcstat_moments_add_array(&m[k], d[k], n[k]))
            return; /* NaN or Inf: no accumulator to test */
    }
    mcstat_result r, keep;
    memset(&r, 0x5a, sizeof r);
    keep = r;
    int st = mcstat_efficiency_test(&m[0], &m[1], &m[2], &m[3], v, alt, alpha, &r);
    fz_check_result(st, &r, MCSTAT_TEST_EFFICIENCY, alt, alpha, 0);
    fz_check_not_enumeric(st, (double)(nx + ny), "efficiency");
    if (!(v > 0.0) || !isfinite(v))
        FZ_ASSERT(st == MCSTAT_EINVAL, "efficiency: ratio %.17g, status %d", v, st);
    if (st == MCSTAT_OK)
        result_accessors(&r, level);
    else
        FZ_ASSERT(memcmp(&r, &keep, sizeof r) == 0, "efficiency: status %d but *out written", st);
}

static const int TEST_KIND[4] = {MCSTAT_TEST_T_1, MCSTAT_TEST_T_2, MCSTAT_TEST_VAR_1, MCSTAT_TEST_VAR_2};

/* The sequential test of kind which + 1 on x (and y), 8 values per look:
 * a refused push leaves the state as it was, a decision is final, and
 * every result is whole (p in [0, 1], an ordered sequence, a log p and a
 * block). */
static void sequential(int which, const double *x, size_t nx, const double *y, size_t ny, double v, int alt,
                       double alpha, uint8_t flags)
{
    mcstat_seq_options o;
    FZ_ASSERT(mcstat_seq_options_init(&o) == MCSTAT_OK, "seq options");
    o.alternative = alt;
    o.alpha = alpha;
    o.min_n = 2;
    o.kurtosis_gate = (flags & 8) ? 0.0 : 10.0;
    o.var_ucb_z = (flags & 16) ? 0.0 : 3.0;
    o.t_opt = (flags & 32) ? 50.0 : 1e4;
    o.eps = (flags & 64) && which < 2 ? fabs(v) * 0.5 + 1e-3 : 0.0;
    mcstat_seq s;
    int st = mcstat_seq_init(&s, which + 1, v, &o);
    fz_check_status(st);
    if (st != MCSTAT_OK) {
        FZ_ASSERT(st == MCSTAT_EINVAL, "seq init: status %d", st);
        return;
    }
    int two = which == 1 || which == 3, decided = 0, decision = 0;
    for (size_t i = 0; i < (nx > ny ? nx : ny); i += 8) {
        size_t kx = i < nx ? (nx - i < 8 ? nx - i : 8) : 0, ky = i < ny ? (ny - i < 8 ? ny - i : 8) : 0;
        mcstat_seq before = s;
        st = two ? mcstat_seq_push_2_array(&s, x + (i < nx ? i : 0), kx, y + (i < ny ? i : 0), ky)
                 : mcstat_seq_push_array(&s, x + (i < nx ? i : 0), kx);
        fz_check_status(st);
        if (st != MCSTAT_OK) {
            FZ_ASSERT(memcmp(&s, &before, sizeof s) == 0, "seq push: status %d but the state changed", st);
            continue;
        }
        mcstat_result r;
        FZ_ASSERT(mcstat_seq_result(&s, &r) == MCSTAT_OK, "seq result");
        FZ_ASSERT(r.p_value >= 0.0 && r.p_value <= 1.0, "seq p %.17g", r.p_value);
        FZ_ASSERT(!isnan(r.conf_int[0]) && !isnan(r.conf_int[1]) && r.conf_int[0] <= r.conf_int[1],
                  "seq sequence %.17g %.17g", r.conf_int[0], r.conf_int[1]);
        if (decided)
            FZ_ASSERT(r.seq_state == MCSTAT_SEQ_DECIDED && r.decision == decision, "seq decision changed");
        if (r.seq_state == MCSTAT_SEQ_DECIDED) {
            decided = 1;
            decision = r.decision;
            FZ_ASSERT(r.decision >= -1 && r.decision <= 1, "seq decision %d", r.decision);
            if (r.reject)
                FZ_ASSERT(r.p_value <= alpha, "seq rejected with p %.17g > alpha %.17g", r.p_value, alpha);
        } else {
            FZ_ASSERT(!r.reject, "seq rejects while continuing");
        }
        double lp;
        FZ_ASSERT(mcstat_result_log_p_value(&r, &lp) == MCSTAT_OK && lp <= 0.0, "seq log p %.17g", lp);
        char buf[1024];
        st = mcstat_result_format(&r, "x", "y", buf, sizeof buf, NULL);
        FZ_ASSERT(st == MCSTAT_OK, "seq format: status %d", st);
        st = mcstat_seq_finish(&s, &r);
        FZ_ASSERT(st == MCSTAT_OK || st == MCSTAT_EHEAVYTAIL, "seq finish: status %d", st);
    }
}

static void stream_checks(const double *x, size_t nx, double reference, double tolerance, double alpha)
{
    if (fz_verbose())
        fprintf(stderr, "stream: reference %a tolerance %a alpha %a\n", reference, tolerance, alpha);
    mcstat_stream s;
    FZ_ASSERT(mcstat_stream_init(&s) == MCSTAT_OK, "stream_init");
    size_t nonfinite = 0;
    for (size_t i = 0; i < nx; i++) {
        mcstat_stream_add(&s, x[i]);
        nonfinite += !isfinite(x[i]);
    }
    mcstat_result r, keep;
    memset(&r, 0x5a, sizeof r);
    keep = r;
    int st = mcstat_stream_check_mean(&s, reference, tolerance, alpha, &r);
    fz_check_status(st);
    fz_check_not_enumeric(st, (double)nx, "stream_check_mean");
    if (nonfinite)
        FZ_ASSERT(st != MCSTAT_OK, "check_mean OK on a stream with %zu non-finite values", nonfinite);
    if (st == MCSTAT_OK) {
        FZ_ASSERT(tolerance >= 0.0 && isfinite(tolerance), "check_mean OK with tolerance %.17g", tolerance);
        if (tolerance == 0.0)
            fz_check_result(st, &r, MCSTAT_TEST_T_1, MCSTAT_TWO_SIDED, alpha, 0);
        else
            fz_check_result(st, &r, MCSTAT_TEST_T_1, r.alternative == MCSTAT_LESS ? MCSTAT_LESS : MCSTAT_GREATER,
                            alpha / 2, 0);
    } else {
        FZ_ASSERT(memcmp(&r, &keep, sizeof r) == 0, "check_mean wrote *out with status %d", st);
    }
    st = mcstat_stream_check_var(&s, reference, alpha, &r);
    fz_check_status(st);
    fz_check_not_enumeric(st, (double)nx, "stream_check_var");
    if (nonfinite)
        FZ_ASSERT(st != MCSTAT_OK, "check_var OK on a stream with non-finite values");
    fz_check_result(st, &r, MCSTAT_TEST_VAR_1, MCSTAT_GREATER, alpha, 0);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    static double x[MAXN], y[MAXN];
    int which = fz_u8(&in) % 5;
    size_t nx = fz_doubles(&in, x, MAXN), ny = fz_doubles(&in, y, MAXN);
    double v = fz_double(&in);
    int alt = fz_alternative(&in);
    double alpha = fz_alpha(&in);
    uint8_t flags = fz_u8(&in);
    if (fz_verbose()) {
        fz_print_doubles("x", x, nx);
        fz_print_doubles("y", y, ny);
        fprintf(stderr, "which %d null %a alt %d alpha %a flags %u\n", which, v, alt, alpha, flags);
    }

    if (which == 4) {
        stream_checks(x, nx, v, fz_double(&in), alpha);
        return 0;
    }

    mcstat_result r, rm, keep;
    memset(&r, 0xa5, sizeof r);
    keep = rm = r;
    int two = which == 1 || which == 3;
    int st = array_test(which, x, nx, y, ny, v, alt, alpha, &r);
    fz_check_result(st, &r, TEST_KIND[which], alt, alpha, 0);
    fz_check_not_enumeric(st, (double)(nx + (two ? ny : 0)), "array test");
    if (st != MCSTAT_OK)
        FZ_ASSERT(memcmp(&r, &keep, sizeof r) == 0, "status %d but *out written", st);
    /* a second confidence level from the bytes already read (no new input,
     * so the committed corpus keeps its meaning) */
    double level = (flags & 2) ? 1.0 - alpha * alpha : alpha;
    if (st == MCSTAT_OK)
        result_accessors(&r, level);
    if (which == 1) {
        pooled_and_paired(x, nx, y, ny, v, alt, alpha, level);
        efficiency(x, nx, y, ny, v, alt, alpha, level);
    }
    if (flags & 4)
        sequential(which, x, nx, y, ny, v, alt, alpha, flags);

    /* The same test through accumulators. */
    mcstat_moments mx, my;
    mcstat_moments_init(&mx);
    mcstat_moments_init(&my);
    int sx = mcstat_moments_add_array(&mx, x, nx), sy = mcstat_moments_add_array(&my, y, ny);
    int sdata = sx ? sx : (two ? sy : 0);
    int sm = moments_test(which, &mx, &my, v, alt, alpha, &rm);
    fz_check_result(sm, &rm, TEST_KIND[which], alt, alpha, 0);
    fz_check_not_enumeric(sm, (double)(nx + (two ? ny : 0)), "accumulator test");
    if (sdata) {
        FZ_ASSERT(st == sdata || st == MCSTAT_EINVAL, "array status %d, data status %d", st, sdata);
    } else {
        FZ_ASSERT(st == sm, "array status %d, accumulator status %d", st, sm);
        if (st == MCSTAT_OK)
            FZ_ASSERT(memcmp(&r, &rm, sizeof r) == 0, "array and accumulator results differ");
    }

    /* NULL data, NULL out: refused whatever else is wrong. */
    if (flags & 1) {
        st = array_test(which, NULL, nx, y, ny, v, alt, alpha, &r);
        FZ_ASSERT(st == MCSTAT_EINVAL, "NULL x: status %d", st);
        st = moments_test(which, NULL, &my, v, alt, alpha, &r);
        FZ_ASSERT(st == MCSTAT_EINVAL, "NULL moments: status %d", st);
        st = array_test(which, x, nx, y, ny, v, alt, alpha, NULL);
        FZ_ASSERT(st == MCSTAT_EINVAL, "NULL out: status %d", st);
        if (two) {
            st = array_test(which, x, nx, NULL, ny, v, alt, alpha, &r);
            FZ_ASSERT(st == MCSTAT_EINVAL, "NULL y: status %d", st);
        }
    }
    return 0;
}
