/*
 * test_binom.c - mcstat_binom_test and the battery meta-test against R's
 * binom.test (tests/data/ref_binom.h, made by tools/refgen/make_binom_ref.R),
 * the acceptance region against the p-values it summarises, and bad input.
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "mcstat.h"
#include "ref_binom.h"

#include <stdint.h>
#include <string.h>

/* The block without mcstat's decision line: what R prints. */
static void strip_decision(char *s)
{
    char *d = strstr(s, "decision at alpha");
    if (d) {
        char *e = strchr(d, '\n');
        memmove(d, e + 1, strlen(e + 1) + 1);
    }
}

static void test_reference(void)
{
    size_t nc = sizeof ref_binom / sizeof ref_binom[0];
    for (size_t i = 0; i < nc; i++) {
        const ref_binom_case *c = &ref_binom[i];
        mcstat_result r;
        int st = mcstat_binom_test((uint64_t)c->x, (uint64_t)c->n, c->p, c->alt, c->alpha, &r);
        CHECK_MSG(st == MCSTAT_OK, "case %zu: status %d", i, st);
        if (st)
            continue;
        /* R's p-value underflows where ours is still a normal double */
        if (c->p_value > 1e-300)
            CHECK_REL(r.p_value, c->p_value, 1e-10, "case %zu (x=%g n=%g p=%g alt=%d)", i, c->x, c->n, c->p, c->alt);
        else
            CHECK_MSG(r.p_value < 1e-290, "case %zu: p = %g", i, r.p_value);
        /* R's two-sided log is the log of its sum, denormal below 1e-300 */
        if (isfinite(c->log_p) && c->log_p < -1e-3 && (c->alt != MCSTAT_TWO_SIDED || c->p_value > 1e-300))
            CHECK_REL(MCSTAT_RESULT_LOG_P_VALUE(&r), c->log_p, 1e-10, "case %zu log p", i);
        CHECK_REL(r.conf_int[0], c->lo, 1e-9, "case %zu lower bound", i);
        CHECK_REL(r.conf_int[1], c->hi, 1e-9, "case %zu upper bound", i);
        CHECK_INT(r.reject, r.p_value <= c->alpha);
        CHECK(r.test == MCSTAT_TEST_BINOM && r.method == MCSTAT_METHOD_EXACT && r.n[0] == (uint64_t)c->n);
        CHECK(r.estimate[0] == c->x / c->n && r.null_value == c->p && r.statistic == c->x);
        char buf[2048];
        size_t len = 0;
        st = mcstat_result_format(&r, NULL, NULL, buf, sizeof buf, &len);
        CHECK(st == MCSTAT_OK && len == strlen(buf));
        /* R names the data by the literal arguments: compare with R's names */
        char xn[64], nn[64];
        const char *data = strstr(c->text, "data:  ");
        if (data && sscanf(data, "data:  %63s and %63s", xn, nn) == 2) {
            mcstat_result_format(&r, xn, nn, buf, sizeof buf, &len);
            strip_decision(buf);
            /* p-values R prints as 0 where it underflowed: compare only the rest */
            /* (R prints "p-value = TRUE" when x == n p: its value is x == m) */
            if ((c->p_value > 1e-300 || strstr(c->text, "p-value < 2.2e-16")) && !strstr(c->text, "TRUE"))
                CHECK_MSG(strcmp(buf, c->text) == 0, "case %zu block:\n%s\nR:\n%s", i, buf, c->text);
        }
    }
}

/* reject iff x outside [critical[0], critical[1]], for every x of small n. */
static void test_critical(void)
{
    const double ps[] = {0.5, 0.3, 0.05, 0.01, 0.9, 0.999, 0.123456};
    const uint64_t ns[] = {1, 2, 5, 17, 60, 333};
    const double alphas[] = {0.05, 0.01, 0.3};
    for (int a = 0; a < 3; a++)
        for (size_t ip = 0; ip < sizeof ps / sizeof ps[0]; ip++)
            for (size_t in = 0; in < sizeof ns / sizeof ns[0]; in++)
                for (size_t ia = 0; ia < 3; ia++)
                    for (uint64_t x = 0; x <= ns[in]; x++) {
                        mcstat_result r;
                        if (mcstat_binom_test(x, ns[in], ps[ip], a, alphas[ia], &r)) {
                            CHECK(0);
                            continue;
                        }
                        int outside = (double)x < r.critical[0] || (double)x > r.critical[1];
                        CHECK_MSG(outside == r.reject, "x=%llu n=%llu p=%g alt=%d alpha=%g: [%g, %g], p=%g",
                                  (unsigned long long)x, (unsigned long long)ns[in], ps[ip], a, alphas[ia],
                                  r.critical[0], r.critical[1], r.p_value);
                        CHECK(r.decision == (r.reject ? ((double)x < ns[in] * ps[ip] ? -1 : 1) : 0));
                    }
}

static void test_battery(void)
{
    mcstat_result a, b;
    /* 14 rejections in 1000 tests at 0.01: binom.test(14, 1000, 0.01) */
    CHECK(mcstat_battery_test(14, 1000, 0.01, MCSTAT_TWO_SIDED, 0.05, &a) == MCSTAT_OK);
    CHECK_REL(a.p_value, 0.20057462486658628, 1e-10, "battery");
    CHECK(a.reject == 0 && a.critical[1] >= 14);
    double pv[1000];
    for (int i = 0; i < 1000; i++)
        pv[i] = i < 14 ? 0.01 * (i + 1) / 14.0 : 0.0101 + 0.989 * i / 1000.0;
    CHECK(mcstat_battery_test_pvalues(pv, 1000, 0.01, MCSTAT_TWO_SIDED, 0.05, &b) == MCSTAT_OK);
    CHECK(b.p_value == a.p_value && b.statistic == 14);
    /* many rejections: the battery is not calibrated */
    CHECK(mcstat_battery_test(40, 1000, 0.01, MCSTAT_GREATER, 0.05, &a) == MCSTAT_OK);
    CHECK(a.reject == 1 && a.decision == 1 && a.p_value < 1e-10);
    pv[3] = NAN;
    CHECK(mcstat_battery_test_pvalues(pv, 1000, 0.01, 0, 0.05, &b) == MCSTAT_ENONFINITE);
    pv[3] = 1.5;
    CHECK(mcstat_battery_test_pvalues(pv, 1000, 0.01, 0, 0.05, &b) == MCSTAT_EINVAL);
    CHECK(mcstat_battery_test_pvalues(NULL, 10, 0.01, 0, 0.05, &b) == MCSTAT_EINVAL);
    CHECK(mcstat_battery_test_pvalues(pv, 0, 0.01, 0, 0.05, &b) == MCSTAT_ETOOFEW);
    CHECK(mcstat_battery_test(1, 10, 0.0, 0, 0.05, &b) == MCSTAT_EINVAL);
    CHECK(mcstat_battery_test(1, 10, 1.0, 0, 0.05, &b) == MCSTAT_EINVAL);
}

static void test_bad_input(void)
{
    mcstat_result r;
    memset(&r, 0x5a, sizeof r);
    mcstat_result before = r;
    CHECK(mcstat_binom_test(5, 4, 0.5, 0, 0.05, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, NAN, 0, 0.05, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, -0.1, 0, 0.05, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, 1.1, 0, 0.05, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, 0.5, 3, 0.05, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, 0.5, 0, 0.0, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, 0.5, 0, 1.0, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, 0.5, 0, NAN, &r) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(1, 4, 0.5, 0, 0.05, NULL) == MCSTAT_EINVAL);
    CHECK(mcstat_binom_test(0, 0, 0.5, 0, 0.05, &r) == MCSTAT_ETOOFEW);
    CHECK(mcstat_binom_test(0, (uint64_t)1 << 60, 0.5, 0, 0.05, &r) == MCSTAT_ETOOBIG);
    CHECK(memcmp(&r, &before, sizeof r) == 0); /* nothing written on failure */
}

/* Far below the smallest double: log p-values in closed form.  P[X <= 0] =
 * q^n; P[X >= n] = p^n. */
static void test_deep_tails(void)
{
    mcstat_result r;
    CHECK(mcstat_binom_test(0, 1000000000, 0.01, MCSTAT_LESS, 0.05, &r) == MCSTAT_OK);
    CHECK(r.p_value == 0.0);
    CHECK_REL(MCSTAT_RESULT_LOG_P_VALUE(&r), 1e9 * log1p(-0.01), 1e-13, "q^n");
    CHECK(mcstat_binom_test(200, 200, 0.01, MCSTAT_GREATER, 0.05, &r) == MCSTAT_OK);
    CHECK_REL(MCSTAT_RESULT_LOG_P_VALUE(&r), 200 * log(0.01), 1e-13, "p^n");
    /* two-sided at x = 0: P[X = 0] is the smallest density of all when p = 1/2 */
    CHECK(mcstat_binom_test(0, 5000, 0.5, MCSTAT_TWO_SIDED, 0.05, &r) == MCSTAT_OK);
    CHECK_REL(MCSTAT_RESULT_LOG_P_VALUE(&r), log(2.0) + 5000 * log(0.5), 1e-13, "2 (1/2)^n");
}

int main(void)
{
    test_reference();
    test_critical();
    test_battery();
    test_bad_input();
    test_deep_tails();
    return h_report("test_binom");
}
