/*
 * rformat.c - numbers formatted the way R's format() and print() do.
 *
 * R chooses, for a vector of numbers and a number of significant digits,
 * one common layout: fixed notation with enough decimals that every element
 * shows up to `digits` significant digits (trailing zeros dropped), unless
 * scientific notation is narrower.  This reimplements that rule (R's
 * formatReal and scientific in src/main/format.c, default scipen = 0) so that
 * mcstat's text matches R's print.htest digit for digit; the tests compare it
 * with R's own output on thousands of values.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "rformat.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define KP_MAX 27

static long double pow10l_int(int k)
{
    long double r = 1.0L, b = 10.0L;
    int n = k < 0 ? -k : k;
    while (n) {
        if (n & 1)
            r *= b;
        b *= b;
        n >>= 1;
    }
    return k < 0 ? 1.0L / r : r;
}

/* For finite x and R significant digits: |x| ~ alpha * 10^kpower with the
 * mantissa rounded to R digits, nsig the digits left after dropping trailing
 * zeros, and roundingwidens when rounding to R digits adds an integer digit
 * that fixed notation would not show (9996 at 3 digits is 1e+04, but 9996). */
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
    long double r_prec = r;
    if (kp > 0)
        r_prec /= pow10l_int(kp);
    else if (kp < 0)
        r_prec *= pow10l_int(-kp);
    if (r_prec < pow10l_int(R - 1)) {
        r_prec *= 10.0L;
        kp--;
    }
    long double alpha = nearbyintl(r_prec);
    int ns = R;
    for (int j = 1; j <= R; j++) {
        alpha /= 10.0L;
        if (alpha == floorl(alpha))
            ns--;
        else
            break;
    }
    if (ns == 0 && R > 0) {
        ns = 1;
        kp += 1;
    }
    *nsig = ns;
    *kpower = kp + R - 1;
    int rgt = R - *kpower;
    rgt = rgt < 0 ? 0 : rgt > KP_MAX ? KP_MAX : rgt;
    long double fuzz = 0.5L / pow10l_int(rgt);
    *roundingwidens = *kpower > 0 && *kpower <= KP_MAX && (long double)r < pow10l_int(*kpower) - fuzz;
}

void mcstat__rformat_layout(const double *x, int n, int digits, mcstat_rlayout *f)
{
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
