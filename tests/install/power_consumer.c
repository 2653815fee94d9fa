/* A consumer of the installed libmcstat that reaches libRmath (the power
 * calculations): prints the sample size for d = 0.5 at power 0.9, one-sample
 * t, two-sided (R: power.t.test(delta = 0.5, power = 0.9, type =
 * "one.sample") gives n = 43.99548, so 44). */
#define MCSTAT_EXPERIMENTAL /* the power calculations */
#include <mcstat.h>
#include <stdio.h>

int main(void)
{
    mcstat_power_options o = MCSTAT_POWER_OPTIONS_INIT, r;
    o.effect = 0.5;
    o.power = 0.9;
    int st = mcstat_power_solve(&o, MCSTAT_POWER_SOLVE_N, &r);
    if (st) {
        printf("error: %s\n", mcstat_strerror(st));
        return 1;
    }
    printf("n = %.0f\n", r.n);
    return r.n == 44.0 ? 0 : 1;
}
