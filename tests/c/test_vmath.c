/*
 * test_vmath.c - the per-pixel tails' vector exp and log1p (src/vmath.h)
 * against libm's, in ulps, over the ranges pixels_dist.c uses: exp on
 * [-708, 709], log1p on [0, 1e300] (uniform in [0, 2], log-uniform beyond,
 * the tiny arguments where log1p(x) = x, and the edges), log on the
 * normal positive doubles (log-uniform, near 1, the edges); also the
 * integer-to-double conversion they rely on.  Under IEEE defaults whatever
 * the caller's mode (FTZ/DAZ in the portability run), as in the library.  glibc's exp and log1p are
 * within an ulp of the truth, so 2 ulps here bound the error at 3.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "harness.h"
#include "internal.h"
#include "vmath.h"


#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

static double ulps(double got, double want)
{
    if (got == want)
        return 0.0;
    if (!isfinite(got) || !isfinite(want))
        return INFINITY;
    return fabs(got - want) / (nextafter(fabs(want), INFINITY) - fabs(want));
}

static uint64_t state = 0x9e3779b97f4a7c15ULL;
static double urand(void)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (double)(state >> 11) * 0x1p-53;
}

typedef double (*scalar_fn)(double);

/* n arguments from gen, four at a time; the largest error in ulps */
static double worst(void (*vf)(const double *, double *), scalar_fn f, double (*gen)(long), long n, double *at)
{
    double w = 0.0;
    for (long i = 0; i < n; i += 4) {
        double x[4] = {gen(i), gen(i + 1), gen(i + 2), gen(i + 3)}, y[4];
        vf(x, y);
        for (int l = 0; l < 4; l++) {
            double e = ulps(y[l], f(x[l]));
            if (e > w) {
                w = e;
                *at = x[l];
            }
        }
    }
    return w;
}

static double gen_exp(long i)
{
    static const double edge[] = {-708.0, 709.0, 0.0, -0.0, 0.34657359027997264, -0.34657359027997264, 1e-300,
                                  -1e-300, 0.5 * 0.6931471805599453, -700.0};
    if (i < (long)(sizeof edge / sizeof edge[0]))
        return edge[i];
    return i % 2 ? -708.0 + 1417.0 * urand() : -2.0 * urand(); /* the tails' e is mostly small and negative */
}

static double gen_log1p(long i)
{
    static const double edge[] = {0.0, 1e-300, 1e-200, 0x1p-53, 0x1p-52, 0.41421356237309503, 0.41421356237309515,
                                  1.0, 0x1p-1, 2.0, 1e300, 1e100, 0.99999999999999989, 1.0000000000000002};
    if (i < (long)(sizeof edge / sizeof edge[0]))
        return edge[i];
    switch (i % 3) {
    case 0:
        return 2.0 * urand();
    case 1:
        return pow(10.0, -300.0 + 600.0 * urand());
    default:
        return 1e-8 * urand();
    }
}

static double gen_log(long i)
{
    static const double edge[] = {DBL_MIN, DBL_MAX, 1.0, 0x1p-1, 2.0, 0.70710678118654746, 0.70710678118654757,
                                  1.4142135623730949, 1.4142135623730951, 0.99999999999999989, 1.0000000000000002,
                                  7.0, 1e-300, 1e300};
    if (i < (long)(sizeof edge / sizeof edge[0]))
        return edge[i];
    switch (i % 3) {
    case 0:
        return 0.5 + 1.5 * urand();
    case 1:
        return pow(2.0, -1022.0 + 2046.0 * urand());
    default:
        return 1.0 + 1e-6 * (urand() - 0.5);
    }
}

/* through memory: a vector passed by value would change the ABI without AVX */
static void exp4(const double *x, double *y)
{
    mcs_v4d v = {x[0], x[1], x[2], x[3]}, r = vm_exp4(v);
    memcpy(y, &r, sizeof r);
}

static void log1p4(const double *x, double *y)
{
    mcs_v4d v = {x[0], x[1], x[2], x[3]}, r = vm_log1p4(v);
    memcpy(y, &r, sizeof r);
}

static void log4(const double *x, double *y)
{
    mcs_v4d v = {x[0], x[1], x[2], x[3]}, r = vm_log4(v);
    memcpy(y, &r, sizeof r);
}

int main(void)
{
    MCSTAT_IEEE_SCOPE(); /* as inside the library, the only caller: libm's results too */
    double at = NAN;
    double we = worst(exp4, exp, gen_exp, 2000000, &at);
    printf("vm_exp4: max %.3g ulps (at %.17g)\n", we, at);
    CHECK_MSG(we <= 2.0, "vm_exp4 off by %.3g ulps at %.17g", we, at);
    double wl = worst(log1p4, log1p, gen_log1p, 2000000, &at);
    printf("vm_log1p4: max %.3g ulps (at %.17g)\n", wl, at);
    CHECK_MSG(wl <= 2.0, "vm_log1p4 off by %.3g ulps at %.17g", wl, at);
    double wg = worst(log4, log, gen_log, 2000000, &at);
    printf("vm_log4: max %.3g ulps (at %.17g)\n", wg, at);
    CHECK_MSG(wg <= 2.0, "vm_log4 off by %.3g ulps at %.17g", wg, at);
    mcs_v4i k = {-1023, -1, 0, 1 << 20};
    mcs_v4d dv = vm_int_to_double(k);
    double d[4];
    memcpy(d, &dv, sizeof d);
    CHECK(d[0] == -1023.0 && d[1] == -1.0 && d[2] == 0.0 && d[3] == (double)(1 << 20));
    return h_report("test_vmath");
}
