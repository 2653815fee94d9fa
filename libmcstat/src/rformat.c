/*
 * rformat.c - numbers formatted the way R's format() and print() do.
 *
 * R chooses, for a vector of numbers and a number of significant digits,
 * one common layout: fixed notation with enough decimals that every element
 * shows up to `digits` significant digits (trailing zeros dropped), unless
 * scientific notation is narrower.  This reimplements that rule (R's
 * formatReal and scientific in src/main/format.c, default scipen = 0) so that
 * mcstat's text matches R's print.htest digit for digit; the tests compare it
 * with R's own output on thousands of values.  R on x86-64 is the reference:
 * its layout decisions depend on x87 long double arithmetic, which is
 * reproduced here on integers (below), so the text is the same whatever the
 * width of `long double` where mcstat is built.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "rformat.h"

#include "internal.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define KP_MAX 27

/* ---- R's scientific() without long double ---------------------------------
 * R (format.c, x86-64 builds) scales |x| by a power of ten in x87 long
 * double, whose significand has 64 bits, and rounds the result to an integer
 * (nearbyintl): two roundings, the first to 64 bits.  Near a rounding tie the
 * first one decides the digit count, so reproducing R's text means
 * reproducing that 64-bit rounding, whatever `long double` is here (64 bits
 * under MSVC, arm64 macOS and -mlong-double-64).  The products and quotients
 * involved need up to 117 exact bits, more than a double-double holds, so
 * they are done on integers: a positive value is m * 2^e with a 64-bit
 * significand m (top bit set), rounded to nearest, ties to even, as the x87
 * does in its default precision. */
typedef struct {
    uint64_t m;
    int e;
} x80;

__extension__ typedef unsigned __int128 u128;

static int bits128(u128 v)
{
    uint64_t hi = (uint64_t)(v >> 64), lo = (uint64_t)v;
    return hi ? 128 - __builtin_clzll(hi) : lo ? 64 - __builtin_clzll(lo) : 0;
}

/* (v + s) * 2^e rounded to 64 bits, v > 0, where 0 < s < 1 when sticky and
 * s = 0 otherwise (v must have more than 64 bits when sticky). */
static x80 x80_round(u128 v, int e, int sticky)
{
    x80 r;
    int nb = bits128(v);
    if (nb <= 64) {
        r.m = (uint64_t)v << (64 - nb);
        r.e = e - (64 - nb);
        return r;
    }
    int sh = nb - 64;
    u128 rem = v & (((u128)1 << sh) - 1), half = (u128)1 << (sh - 1);
    r.m = (uint64_t)(v >> sh);
    r.e = e + sh;
    if (rem > half || (rem == half && (sticky || (r.m & 1)))) {
        if (++r.m == 0) { /* carried out: 2^64 */
            r.m = 1ull << 63;
            r.e++;
        }
    }
    return r;
}

static x80 x80_from_double(double x) /* finite, x > 0 (subnormals too) */
{
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    int be = (int)(b >> 52) & 0x7ff;
    uint64_t m = b & 0xfffffffffffffull;
    if (be)
        m |= 1ull << 52;
    return x80_round(m, (be ? be : 1) - 1075, 0);
}

static x80 x80_mul(x80 a, x80 b)
{
    return x80_round((u128)a.m * b.m, a.e + b.e, 0);
}

static x80 x80_div(x80 a, x80 b)
{
    /* a.m * 2^63 / b.m by two steps of long division: 128 quotient bits and
     * the remainder's sticky bit (b.m >= 2^63, so each step fits) */
    u128 n = (u128)a.m << 63;
    u128 q1 = n / b.m, r1 = n % b.m;
    u128 n2 = r1 << 64;
    u128 q2 = n2 / b.m, r2 = n2 % b.m;
    return x80_round(q1 << 64 | q2, a.e - b.e - 127, r2 != 0);
}

/* a - b for a > b > 0 */
static x80 x80_sub(x80 a, x80 b)
{
    u128 A = (u128)a.m << 64, B;
    int sh = a.e - b.e; /* b aligned to the exponent a.e - 64 */
    int lost = 0;
    if (sh <= 64) {
        B = (u128)b.m << (64 - sh);
    } else if (sh < 128) {
        B = (u128)b.m >> (sh - 64);
        lost = (b.m & ((1ull << (sh - 64)) - 1)) != 0;
    } else {
        B = 0;
        lost = 1;
    }
    /* A - B - f with 0 < f < 1 when lost: (A - B - 1) + (1 - f) */
    return x80_round(A - B - (u128)lost, a.e - 64, lost);
}

static int x80_cmp(x80 a, x80 b)
{
    if (a.e != b.e)
        return a.e < b.e ? -1 : 1;
    return (a.m > b.m) - (a.m < b.m);
}

/* R's table of powers of ten, as long double: 10^0 ... 10^22 exactly, but
 * 10^23 ... 10^27 are written as double constants in R's source, so they
 * carry the double's rounding.  Index k is 10^k. */
static x80 r_tbl(int k)
{
    static const double big[5] = {1e23, 1e24, 1e25, 1e26, 1e27};
    if (k > 22)
        return x80_from_double(big[k - 23]);
    uint64_t p = 1;
    for (int i = 0; i < k; i++)
        p *= 5;
    x80 r = x80_round(p, k, 0); /* 5^k 2^k */
    return r;
}

/* 10^k rounded to 64 bits for |k| > 27 (R's powl(10, k); glibc's is within an
 * ulp): 5^|k| in double-double (below 2^790, so in range), inverted for k < 0,
 * then times 2^k.  The double-double is good to about 2^-100. */
static x80 pow10_x80(int k)
{
    int n = k < 0 ? -k : k;
    mcstat_dd p = {1.0, 0.0};
    for (; n >= 22; n -= 22)
        p = dd_mul_d(p, 2384185791015625.0); /* 5^22, exact */
    for (; n > 0; n--)
        p = dd_mul_d(p, 5.0);
    if (k < 0) { /* 1 / p: a Newton correction of 1 / p.hi */
        double q1 = 1.0 / p.hi;
        mcstat_dd e = dd_add((mcstat_dd){1.0, 0.0}, dd_neg(dd_mul_d(p, q1)));
        p = dd_fast_two_sum(q1, e.hi / p.hi);
    }
    /* hi + lo exactly as an integer times 2^(el - 53) */
    int eh, el = 0;
    int64_t mh = (int64_t)ldexp(frexp(p.hi, &eh), 53), ml = 0;
    if (p.lo != 0.0)
        ml = (int64_t)ldexp(frexp(p.lo, &el), 53);
    x80 r;
    if (ml == 0 || eh - el > 70) { /* |lo| below a quarter of hi's 64-bit ulp */
        r = x80_round((u128)mh, eh - 53, 0);
    } else {
        u128 v = (u128)mh << (eh - el);
        v = ml >= 0 ? v + (u128)ml : v - (u128)(-ml);
        r = x80_round(v, el - 53, 0);
    }
    r.e += k;
    return r;
}

static uint64_t x80_nearbyint(x80 a) /* 1 <= a < 2^63: to nearest, ties to even */
{
    if (a.e >= 0)
        return a.m << a.e;
    int sh = -a.e;
    uint64_t n = a.m >> sh, rem = a.m & ((1ull << sh) - 1), half = 1ull << (sh - 1);
    if (rem > half || (rem == half && (n & 1)))
        n++;
    return n;
}

/* For finite x and R significant digits (1 <= R <= 15): |x| ~ alpha * 10^kpower
 * with the mantissa rounded to R digits, nsig the digits left after dropping
 * trailing zeros, and roundingwidens when rounding to R digits adds an
 * integer digit that fixed notation would not show (9996 at 3 digits is
 * 1e+04, but 9996).  Step for step R's computation on x86-64. */
static void scientific(double x, int R, int *neg, int *kpower, int *nsig, int *roundingwidens)
{
    if (x == 0.0) {
        *kpower = 0;
        *nsig = 1;
        *neg = 0;
        *roundingwidens = 0;
        return;
    }
    double r = fabs(x);
    *neg = x < 0.0;
    int kp = (int)floor(log10(r)) - R + 1;
    x80 r_prec = x80_from_double(r);
    if (kp > 0 && kp <= KP_MAX)
        r_prec = x80_div(r_prec, r_tbl(kp));
    else if (kp < 0 && kp >= -KP_MAX)
        r_prec = x80_mul(r_prec, r_tbl(-kp));
    else if (kp != 0)
        r_prec = x80_div(r_prec, pow10_x80(kp));
    if (x80_cmp(r_prec, r_tbl(R - 1)) < 0) {
        r_prec = x80_mul(r_prec, r_tbl(1));
        kp--;
    }
    uint64_t alpha = x80_nearbyint(r_prec);
    int ns = R;
    for (int j = 1; j <= R && alpha % 10 == 0; j++) {
        alpha /= 10;
        ns--;
    }
    if (ns == 0 && R > 0) {
        ns = 1;
        kp += 1;
    }
    *nsig = ns;
    *kpower = kp + R - 1;
    /* r < 10^kpower - fuzz, the difference rounded to 64 bits as R's is */
    static const double p10[KP_MAX + 1] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,
                                           1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19,
                                           1e20, 1e21, 1e22, 1e23, 1e24, 1e25, 1e26, 1e27};
    int rgt = R - *kpower;
    rgt = rgt < 0 ? 0 : rgt > KP_MAX ? KP_MAX : rgt;
    double fuzz = 0.5 / p10[rgt];
    *roundingwidens = *kpower > 0 && *kpower <= KP_MAX &&
                      x80_cmp(x80_from_double(r), x80_sub(r_tbl(*kpower), x80_from_double(fuzz))) < 0;
}

void mcstat__rformat_layout(const double *x, int n, int digits, mcstat_rlayout *f)
{
    MCSTAT_IEEE_SCOPE(); /* a subnormal is not 0 here, whatever the caller's DAZ */
    int neg = 0, rgt = INT_MIN, mxsl = INT_MIN, mxe = INT_MIN, mne = INT_MAX, mxns = INT_MIN;
    int naflag = 0, posinf = 0, neginf = 0;
    for (int i = 0; i < n; i++) {
        double v = x[i];
        if (isnan(v)) {
            naflag = 1;
        } else if (isinf(v)) {
            if (v > 0)
                posinf = 1;
            else
                neginf = 1;
        } else {
            int ng, kp, ns, rw;
            scientific(v, digits, &ng, &kp, &ns, &rw);
            int left = kp + 1;
            if (rw)
                left--;
            int sleft = ng + ((left <= 0) ? 1 : left);
            int right = ns - left;
            if (ng)
                neg = 1;
            if (right > rgt)
                rgt = right;
            if (sleft > mxsl)
                mxsl = sleft;
            if (ns > mxns)
                mxns = ns;
            if (kp > mxe)
                mxe = kp;
            if (kp < mne)
                mne = kp;
        }
    }
    if (rgt < 0)
        rgt = 0;
    int wF = mxsl + rgt + (rgt != 0);
    f->e = (mxe >= 100 || mne <= -100) ? 2 : 1; /* three exponent digits */
    if (mxns != INT_MIN) {
        f->d = mxns - 1;
        f->w = neg + (f->d > 0) + f->d + 4 + f->e;
        if (wF <= f->w) { /* fixed notation when it is no wider (scipen = 0) */
            f->e = 0;
            f->d = rgt;
            f->w = wF;
        }
    } else {
        f->w = f->d = f->e = 0;
    }
    if (naflag && f->w < 3) /* printed as NaN */
        f->w = 3;
    if (posinf && f->w < 3)
        f->w = 3;
    if (neginf && f->w < 4)
        f->w = 4;
}

int mcstat__rformat_encode(double x, const mcstat_rlayout *f, int width, char *buf, size_t size)
{
    if (width < f->w)
        width = f->w;
    if (isnan(x))
        return snprintf(buf, size, "%*s", width, "NaN");
    if (isinf(x))
        return snprintf(buf, size, "%*s", width, x > 0 ? "Inf" : "-Inf");
    if (f->e) {
        if (f->d)
            return snprintf(buf, size, "%#*.*e", width, f->d, x);
        return snprintf(buf, size, "%*.*e", width, f->d, x);
    }
    return snprintf(buf, size, "%*.*f", width, f->d, x);
}

int mcstat__rformat1(double x, int digits, char *buf, size_t size)
{
    mcstat_rlayout f;
    mcstat__rformat_layout(&x, 1, digits, &f);
    return mcstat__rformat_encode(x, &f, 0, buf, size);
}

int mcstat__rformat_pval(double p, int digits, char *buf, size_t size)
{
    /* format.pval: below machine epsilon, "< 2.2e-16" (eps at digits - 2) */
    const double eps = 2.220446049250313e-16;
    if (p < eps) {
        char e[32];
        int d = digits - 2 < 1 ? 1 : digits - 2;
        mcstat__rformat1(eps, d, e, sizeof e);
        return snprintf(buf, size, "< %s", e);
    }
    return mcstat__rformat1(p, digits, buf, size);
}
