/* A parent project's program using a vendored mcstat: a t-test (GSL), a
 * power calculation (libRmath) and an embedded check (mcstat/embedded.h),
 * so the static library's dependencies must reach the parent's link. */
#define MCSTAT_CHECKS 1
#define MCSTAT_EXPERIMENTAL /* the power calculation */
#include <mcstat.h>
#include <mcstat/embedded.h>
#include <stdio.h>

int main(void)
{
    const double x[] = {0.9, 1.1, 1.0, 0.95, 1.05, 1.02, 0.98, 1.01};
    mcstat_result r;
    int st = mcstat_t_test_1(x, 8, 1.0, MCSTAT_TWO_SIDED, 0.05, &r);
    if (st != MCSTAT_OK || r.reject) {
        printf("t test: %s, reject %d\n", mcstat_strerror(st), st == MCSTAT_OK ? r.reject : -1);
        return 1;
    }
    mcstat_power_options o = MCSTAT_POWER_OPTIONS_INIT, p;
    o.effect = 0.5;
    o.power = 0.9;
    st = mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_N, &p);
    if (st != MCSTAT_OK || p.n != 44.0) { /* R: power.t.test(delta = 0.5, power = 0.9, type = "one.sample") */
        printf("power: %s, n = %g\n", mcstat_strerror(st), st == MCSTAT_OK ? p.n : -1.0);
        return 1;
    }
    mcstat_stream s;
    MCSTAT_CHECK_INIT(s);
    for (int i = 0; i < 8; i++)
        MCSTAT_CHECK_ADD(s, x[i]);
    if (MCSTAT_CHECK_MEAN(s, 1.0, 0.1, 0.01))
        return 1;
    printf("vendored mcstat %s: ok\n", mcstat_version());
    return 0;
}
