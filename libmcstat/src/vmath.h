/*
 * vmath.h - exp, log and log1p of four doubles at a time, for the per-pixel
 * tails (pixels_dist.c, pixels_var.c): straight-line code in GCC's vector extensions (AVX2
 * registers where the caller is compiled for AVX2, two SSE2 halves
 * otherwise), so a block's pixels need not call libm one at a time.
 * Accuracy, measured against libm in tests/c/test_vmath.c: within 2 ulps
 * over the ranges used (exp on [-708, 709], log1p on [0, 1e300], log on
 * the normal positive doubles).
 * Included by pixels_dist.c and pixels_var.c; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_VMATH_H
#define MCSTAT_VMATH_H

#include <stdint.h>

/* Vectors pass by value only into these always-inlined functions, so the
 * warning that a 32-byte vector's calling convention differs without AVX
 * does not apply; off for the files that include this one (pixels_dist.c,
 * pixels_var.c and the test), which pass them so throughout. */
#pragma GCC diagnostic ignored "-Wpsabi"

typedef double mcs_v4d __attribute__((vector_size(32)));
typedef long long mcs_v4i __attribute__((vector_size(32)));

/* ln 2 in two parts: the first with 21 trailing zero bits, so n * VM_LN2_HI
 * is exact for |n| < 2^21; the second ln 2 - VM_LN2_HI (mpmath). */
#define VM_LN2_HI 0x1.62e42fee00000p-1
#define VM_LN2_LO 0x1.a39ef35793c76p-33
#define VM_INV_LN2 1.4426950408889634
#define VM_SHIFTER 0x1.8p52 /* x + 1.5 2^52 - 1.5 2^52 rounds x to an integer */

static inline __attribute__((always_inline)) mcs_v4d vm_splat(double v)
{
    return (mcs_v4d){v, v, v, v};
}

/* mask ? a : b lane by lane (C has no ?: on vectors); mask lanes all ones or 0 */
static inline __attribute__((always_inline)) mcs_v4d vm_select(mcs_v4i mask, mcs_v4d a, mcs_v4d b)
{
    return (mcs_v4d)(((mcs_v4i)a & mask) | ((mcs_v4i)b & ~mask));
}

/* |v| lane by lane: the sign bits cleared */
static inline __attribute__((always_inline)) mcs_v4d vm_fabs(mcs_v4d v)
{
    return (mcs_v4d)((mcs_v4i)v & (mcs_v4i){INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX});
}

/* small integers (|k| < 2^51) to double, exactly, without a conversion
 * instruction (x86 has none for 64-bit integers before AVX-512) */
static inline __attribute__((always_inline)) mcs_v4d vm_int_to_double(mcs_v4i k)
{
    const mcs_v4d sh = vm_splat(VM_SHIFTER);
    return (mcs_v4d)(k + (mcs_v4i)sh) - sh;
}

/* exp(e) for -708 <= e <= 709 (2^n stays normal): e = n ln 2 + r with n the
 * integer nearest e / ln 2 and |r| <= ln 2 / 2 (Cody and Waite: r exact to
 * the rounding of the two products), exp(r) by its Taylor polynomial of
 * degree 13 (truncation below 5e-18 relative), 2^n by its bits. */
static inline __attribute__((always_inline)) mcs_v4d vm_exp4(mcs_v4d e)
{
    const mcs_v4d sh = vm_splat(VM_SHIFTER);
    mcs_v4d t = e * VM_INV_LN2 + sh;
    mcs_v4d n = t - sh;
    mcs_v4d r = (e - n * VM_LN2_HI) - n * VM_LN2_LO;
    /* sum_{i=3..13} r^(i-3)/i! in pairs (Estrin's scheme: a chain of four
     * multiplications instead of ten Horner steps; these terms are below
     * r^3/6, so their rounding stays far below the result's), then the
     * three leading terms by Horner as before */
    mcs_v4d r2 = r * r, r4 = r2 * r2, r8 = r4 * r4;
    mcs_v4d p01 = r * (1.0 / 24.0) + 1.0 / 6.0, p23 = r * (1.0 / 720.0) + 1.0 / 120.0;
    mcs_v4d p45 = r * (1.0 / 40320.0) + 1.0 / 5040.0, p67 = r * (1.0 / 3628800.0) + 1.0 / 362880.0;
    mcs_v4d p89 = r * (1.0 / 479001600.0) + 1.0 / 39916800.0, p10 = vm_splat(1.0 / 6227020800.0); /* 1/13! */
    mcs_v4d p = ((p01 + r2 * p23) + r4 * (p45 + r2 * p67)) + r8 * (p89 + r2 * p10);
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    mcs_v4i bits = ((mcs_v4i)t - (mcs_v4i)sh + 1023) << 52; /* t holds n in its low bits */
    return p * (mcs_v4d)bits;
}

/* log(u) for normal positive u, as a multiple of ln 2 and the rest: u =
 * m 2^k with m in [sqrt(1/2), sqrt(2)), f = m - 1 (exact), s = f/(2+f):
 *   log(m) = 2 atanh(s) = 2s + 2s z Q(z),  z = s^2 <= 0.0295,
 *   Q(z) = sum_{i<=10} z^i / (2i+3)   (truncation below 1e-18 relative),
 * written f - s (f - 2 z Q) since 2s = f - s f, so that the leading f is
 * exact and the rest small beside it.  *dk = k; returns log(m). */
static inline __attribute__((always_inline)) mcs_v4d vm_log_parts(mcs_v4d u, mcs_v4d *dk)
{
    mcs_v4i bits = (mcs_v4i)u;
    mcs_v4i k = (bits >> 52) - 1023;
    mcs_v4d m = (mcs_v4d)((bits & 0x000fffffffffffffLL) | 0x3ff0000000000000LL); /* in [1, 2) */
    mcs_v4i big = (mcs_v4i)(m > 0x1.6a09e667f3bcdp+0); /* sqrt(2) */
    m = vm_select(big, m * 0.5, m);
    k = k - big; /* big is -1 where true */
    mcs_v4d f = m - 1.0, s = f / (f + 2.0), z = s * s;
    /* Q in pairs (Estrin, as in vm_exp4): a chain of four multiplications */
    mcs_v4d z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
    mcs_v4d q01 = z * (1.0 / 5) + 1.0 / 3, q23 = z * (1.0 / 9) + 1.0 / 7, q45 = z * (1.0 / 13) + 1.0 / 11;
    mcs_v4d q67 = z * (1.0 / 17) + 1.0 / 15, q89 = z * (1.0 / 21) + 1.0 / 19, q10 = vm_splat(1.0 / 23);
    mcs_v4d q = ((q01 + z2 * q23) + z4 * (q45 + z2 * q67)) + z8 * (q89 + z2 * q10);
    *dk = vm_int_to_double(k);
    return f - s * (f - 2.0 * z * q);
}

/* log1p(x) for 0 <= x <= 1e300: u = 1 + x rounded, c = the rounding
 * (exact: x - (u - 1) for x < 1, 1 - (u - x) above), log1p(x) = log(u) +
 * c/u to far below an ulp. */
static inline __attribute__((always_inline)) mcs_v4d vm_log1p4(mcs_v4d x)
{
    mcs_v4d u = x + 1.0;
    mcs_v4d c_small = x - (u - 1.0), c_big = 1.0 - (u - x);
    mcs_v4d c = vm_select((mcs_v4i)(x < 1.0), c_small, c_big);
    mcs_v4d dk, lm = vm_log_parts(u, &dk);
    return dk * VM_LN2_HI + (lm + (dk * VM_LN2_LO + c / u));
}

/* log(x) for normal positive x (DBL_MIN <= x <= DBL_MAX) */
static inline __attribute__((always_inline)) mcs_v4d vm_log4(mcs_v4d x)
{
    mcs_v4d dk, lm = vm_log_parts(x, &dk);
    return dk * VM_LN2_HI + (lm + dk * VM_LN2_LO);
}

#endif /* MCSTAT_VMATH_H */
