/*
 * test_fuzz_regressions.c - every defect the fuzz harnesses (tests/fuzz)
 * found, as an ordinary test that needs neither clang nor libFuzzer.  The
 * crashing inputs themselves are replayed from tests/fuzz/regressions/.
 * GSL's default handler (abort) stays installed: a call that reaches it
 * kills the test.
 */
#include "harness.h"
#include "mcstat.h"

#include <float.h>
#include <string.h>

/* fuzz_ks: Canner's weight at 1 + 1 values.  The critical value's first
 * guess used log log N, NaN at N = 2, then converted it to an integer
 * (undefined behaviour; UBSan: "-nan is outside the range of unsigned long"). */
static void test_ks_canner_one_each(void)
{
    const double x[1] = {0.0}, y0[1] = {0.0}, y1[1] = {1.0};
    const double *ys[2] = {y0, y1};
    for (int k = 0; k < 2; k++) {
        mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
        o.method = MCSTAT_METHOD_EXACT;
        mcstat_result r;
        int st = mcstat_ks_test_2(x, 1, ys[k], 1, MCSTAT_TWO_SIDED, 0.022, &o, &r);
        CHECK_INT(st, MCSTAT_OK);
        /* both labelings of two values give the same D2: p = 1, never rejected */
        CHECK_REL(r.p_value, 1.0, 0.0, "1 + 1 values, case %d", k);
        CHECK(r.reject == 0 && r.decision == 0);
        CHECK(!isnan(r.critical[1]) && r.statistic <= r.critical[1]);
    }
}

int main(void)
{
    test_ks_canner_one_each();
    return h_report("test_fuzz_regressions");
}
