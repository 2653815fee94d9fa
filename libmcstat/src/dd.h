/*
 * dd.h - double-double arithmetic (Dekker, Knuth) and exact scaling by
 * powers of two.
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_DD_H
#define MCSTAT_DD_H

/* ---- double-double arithmetic (Dekker, Knuth) ----------------------------
 * Exact when the compiler neither reorders nor contracts these operations;
 * the build passes -ffp-contract=off, and -ffast-math is refused above. */
typedef struct {
    double hi, lo;
} mcstat_dd;

static inline mcstat_dd dd_two_sum(double a, double b)
{
    double s = a + b;
    double bb = s - a;
    double e = (a - (s - bb)) + (b - bb);
    mcstat_dd r = {s, e};
    return r;
}

static inline mcstat_dd dd_fast_two_sum(double a, double b) /* |a| >= |b| */
{
    double s = a + b;
    mcstat_dd r = {s, b - (s - a)};
    return r;
}

static inline mcstat_dd dd_add(mcstat_dd a, mcstat_dd b)
{
    mcstat_dd s = dd_two_sum(a.hi, b.hi);
    mcstat_dd t = dd_two_sum(a.lo, b.lo);
    s.lo += t.hi;
    s = dd_fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return dd_fast_two_sum(s.hi, s.lo);
}

static inline mcstat_dd dd_neg(mcstat_dd a)
{
    mcstat_dd r = {-a.hi, -a.lo};
    return r;
}

/* a * b for doubles, exactly, by Dekker's splitting (no FMA needed). */
static inline mcstat_dd dd_two_prod(double a, double b)
{
    const double split = 134217729.0; /* 2^27 + 1 */
    double p = a * b;
    double ta = split * a, ah = ta - (ta - a), al = a - ah;
    double tb = split * b, bh = tb - (tb - b), bl = b - bh;
    double e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    mcstat_dd r = {p, e};
    return r;
}

static inline mcstat_dd dd_mul_d(mcstat_dd a, double b)
{
    mcstat_dd p = dd_two_prod(a.hi, b);
    p.lo += a.lo * b;
    return dd_fast_two_sum(p.hi, p.lo);
}

/* a / b for a double-double and a double, to about 2^-104 relative. */
static inline mcstat_dd dd_div_d(mcstat_dd a, double b)
{
    double q1 = a.hi / b;
    mcstat_dd p = dd_two_prod(q1, b);
    mcstat_dd r = dd_two_sum(a.hi, -p.hi);
    r.lo += a.lo - p.lo;
    double q2 = (r.hi + r.lo) / b;
    return dd_fast_two_sum(q1, q2);
}

/* x * 2^e; the common e == 0 costs nothing (ldexp is a libm call). */
static inline double scale2(double x, int e)
{
    return e ? ldexp(x, e) : x;
}

#endif /* MCSTAT_DD_H */
