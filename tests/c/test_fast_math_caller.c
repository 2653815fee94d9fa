/*
 * test_fast_math_caller.c - a caller compiled and linked with -ffast-math
 * (CMakeLists.txt): it includes mcstat.h and mcstat/embedded.h with checks on,
 * and, on x86-64 and arm64, GCC and clang link crtfastmath.o into it, which
 * starts the process with subnormals flushed to zero.  The library must
 * answer as in a default environment.  This file compares results as bit
 * patterns only: under -ffast-math its own comparisons with Inf or NaN
 * could be folded away.
 */
#define MCSTAT_CHECKS 1
#include "harness.h"
#include "mcstat.h"
#include "mcstat/embedded.h"

#include <stdint.h>
#include <string.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

static uint64_t bits(double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return u;
}

int main(void)
{
#if defined(__x86_64__)
    /* crtfastmath.o sets FTZ and DAZ before main: the environment under test
     * (valgrind does not emulate them, and shows MXCSR without them) */
    if ((_mm_getcsr() & 0x8040) != 0x8040)
        printf("test_fast_math_caller: FTZ/DAZ are off (MXCSR %#x; valgrind?): the checks run in the "
               "default environment\n", _mm_getcsr());
#endif
    double v;
    /* quantiles whose exact answers underflow to 0 and overflow to Inf */
    CHECK_INT(mcstat_chisq_quantile(1e-300, 1.0, 0, &v), MCSTAT_OK);
    CHECK(bits(v) == 0);
    CHECK_INT(mcstat_f_quantile(1e-300, 1.0, 1.0, 1, &v), MCSTAT_OK);
    CHECK(bits(v) == 0x7ff0000000000000ull);
    /* subnormal data is not zero to the library: sd({1, 3, 0} 2^-1074) =
     * 1.53 2^-1074, rounded to 2^-1073 */
    const double s[3] = {0x0.0000000000001p-1022, 0x0.0000000000003p-1022, 0.0};
    mcstat_moments m;
    mcstat_moments_init(&m);
    CHECK_INT(mcstat_moments_add_array(&m, s, 3), MCSTAT_OK);
    double sd = mcstat_moments_sd(&m);
    CHECK_MSG(bits(sd) == 2, "sd of subnormal data: %a", sd);
    /* the embedded check macros */
    mcstat_stream st;
    MCSTAT_CHECK_INIT(st);
    for (int i = 0; i < 2000; i++)
        MCSTAT_CHECK_ADD(st, (double)(i % 10) - 4.5);
    CHECK_INT(MCSTAT_CHECK_MEAN(st, 0.0, 0.0, 0.01), 0);
    /* R-style text, as R prints it: t.test(c(0.1, 0.2, 0.3, 0.4, 0.55)) */
    const double x[5] = {0.1, 0.2, 0.3, 0.4, 0.55};
    mcstat_result r;
    CHECK_INT(mcstat_t_test_1(x, 5, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    char text[2048];
    CHECK_INT(mcstat_result_format(&r, "x", NULL, text, sizeof text, NULL), MCSTAT_OK);
    CHECK_MSG(strstr(text, "t = 3.9691, df = 4, p-value = 0.01655") != NULL, "%s", text);
    return h_report("test_fast_math_caller");
}
