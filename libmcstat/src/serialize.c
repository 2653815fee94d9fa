/*
 * serialize.c - a versioned, endian-defined byte form of mcstat_moments, so
 * accumulators can cross processes, machines and languages.
 *
 * Layout (MCSTAT_MOMENTS_BYTES = 96 bytes, all integers little-endian,
 * doubles as the little-endian bytes of their IEEE 754 binary64 pattern):
 *    0  4  magic "MCSM"
 *    4  4  format version (1)
 *    8  8  n
 *   16  4  scale (int32)
 *   20  4  zero
 *   24 56  mean, mean_lo, m2, m3, m4, min, max
 *   80  8  zero
 *   88  8  FNV-1a 64 checksum of bytes 0..87
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <string.h>

#define FORMAT_VERSION 1u
#define CHECKED_BYTES 88

static void put_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; i++)
        p[i] = (unsigned char)(v >> (8 * i));
}

static void put_u64(unsigned char *p, uint64_t v)
{
    for (int i = 0; i < 8; i++)
        p[i] = (unsigned char)(v >> (8 * i));
}

static uint32_t get_u32(const unsigned char *p)
{
    uint32_t v = 0;
    for (int i = 0; i < 4; i++)
        v |= (uint32_t)p[i] << (8 * i);
    return v;
}

static uint64_t get_u64(const unsigned char *p)
{
    uint64_t v = 0;
    for (int i = 0; i < 8; i++)
        v |= (uint64_t)p[i] << (8 * i);
    return v;
}

static void put_f64(unsigned char *p, double d)
{
    uint64_t v;
    memcpy(&v, &d, sizeof v);
    put_u64(p, v);
}

static double get_f64(const unsigned char *p)
{
    uint64_t v = get_u64(p);
    double d;
    memcpy(&d, &v, sizeof d);
    return d;
}

static uint64_t fnv1a(const unsigned char *p, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

int mcstat_moments_to_bytes(const mcstat_moments *m, unsigned char *buf, size_t size)
{
    if (!m || !buf || (m->n > 0 && m->version != MCSTAT_MOMENTS_VERSION))
        return MCSTAT_EINVAL;
    if (size < MCSTAT_MOMENTS_BYTES)
        return MCSTAT_EBUFSIZE;
    memset(buf, 0, MCSTAT_MOMENTS_BYTES);
    memcpy(buf, "MCSM", 4);
    put_u32(buf + 4, FORMAT_VERSION);
    put_u64(buf + 8, m->n);
    if (m->n > 0) { /* an empty accumulator has one canonical form */
        put_u32(buf + 16, (uint32_t)m->scale);
        const double f[7] = {m->mean, m->mean_lo, m->m2, m->m3, m->m4, m->min, m->max};
        for (int i = 0; i < 7; i++)
            put_f64(buf + 24 + 8 * i, f[i]);
    }
    put_u64(buf + CHECKED_BYTES, fnv1a(buf, CHECKED_BYTES));
    return MCSTAT_OK;
}

/* The invariants every accumulator mcstat produces satisfies. */
static int consistent(const mcstat_moments *m)
{
    if (m->n == 0)
        return 1;
    const double f[7] = {m->mean, m->mean_lo, m->m2, m->m3, m->m4, m->min, m->max};
    for (int i = 0; i < 7; i++)
        if (!isfinite(f[i]))
            return 0;
    if (m->scale < -1100 || m->scale > 1100 || m->m2 < 0.0 || m->m4 < 0.0 || m->min > m->max)
        return 0;
    /* the scale follows the largest magnitude (moments.c): m2 = 1.6e-303 at
     * scale 0 for data up to 2^-511, whose m4 had underflowed to 0, merged
     * into an accumulator that broke m4 >= m2^2/n (fuzz_bytes) */
    if (m->scale != mcstat__moments_scale_for(fmax(fabs(m->min), fabs(m->max))))
        return 0;
    /* (mean, mean_lo) is a double-double: |mean_lo| <= ulp(mean).  (Half an
     * ulp when normalised; a full ulp allows for mean_lo rounded to the
     * subnormal grid by the scale, which a tie or an exponent near -1022
     * can push past half: fuzz_moments, data at 2^-1019.)
     * The looser |mean_lo| <= |mean| 2^-50 + 2^-1074 accepted mean 0 with
     * mean_lo 2^-1074, which a merge turned into a mean above max (found by
     * tests/fuzz/fuzz_bytes).  A mean of 0 has no lower part: (0, 2^-1074)
     * is not a double-double (hi = fl(hi + lo) fails), and its intervals,
     * formed from hi + lo, left the estimate hi outside them (fuzz_bytes). */
    double am = fabs(m->mean);
    if (am == 0.0 ? m->mean_lo != 0.0 : fabs(m->mean_lo) > nextafter(am, INFINITY) - am)
        return 0;
    /* The sums of powers of the same deviations bound each other: with
     * u = M3/M2^1.5, w = M4/M2^2 (scale-free), |u| <= 1, 1/n <= w <= 1, and
     * the moment matrix [[n, 0, M2], [0, M2, M3], [M2, M3, M4]] is positive
     * semidefinite: w - u^2 >= 1/n (equality for data on two points, hence
     * the 2^-20 slack).  Found by fuzz_bytes: m3 = 2^1008 with m2 = 0; m4
     * below m2^2/n; m2 = 7.2, m3 = -12.5, m4 = 9 at n = 21 (each bound alone
     * holds): merges of these gave m4 < 0.  The lower bounds only where m4
     * cannot have underflowed: genuine accumulators of data near 2^-199
     * with a tiny spread have m4 near 2^-1000 (fuzz_moments). */
    const double tol = 0x1p-20;
    if (m->m2 == 0.0) {
        if (m->m3 != 0.0 || m->m4 != 0.0)
            return 0;
    } else {
        double u = (m->m3 / m->m2) / sqrt(m->m2), w = (m->m4 / m->m2) / m->m2, inv_n = 1.0 / (double)m->n;
        if (!(fabs(u) <= 1.0 + tol) || !(w <= 1.0 + tol))
            return 0;
        if ((m->m2 / (double)m->n) * m->m2 >= 0x1p-900 &&
            (w < inv_n * (1.0 - tol) || w - u * u - inv_n < -tol * (w + u * u + inv_n)))
            return 0;
    }
    /* min and max are two of the values, so M2 >= (max - min)^2 / 2 (the
     * pair's own spread; any other value and any other centre only add).
     * Found by fuzz_bytes in CI: n = 2, m2 = 3.6 with min 0.0625 and max
     * 1.1e6 was accepted, and its merge with 30 equal values was refused.
     * In the accumulator's scaled units, where the range cannot overflow;
     * only for data far above the subnormal range, where the mean and so
     * M2 carry full precision (fuzz_moments: {-0, 2^-1074, 0, 0, ...} has
     * M2 below the bound once the mean rounds to 0). */
    if (m->n >= 2 && fmax(fabs(m->min), fabs(m->max)) >= 0x1p-960) {
        double range = ldexp(m->max, -m->scale) - ldexp(m->min, -m->scale);
        double least = 0.5 * range * range;
        if (least >= 0x1p-900 && m->m2 < least * (1.0 - tol))
            return 0;
    }
    /* all values equal: no spread */
    if (m->min == m->max && (m->mean != m->min || m->mean_lo != 0.0 || m->m2 != 0.0 || m->m3 != 0.0 || m->m4 != 0.0))
        return 0;
    double slack = fmax(fabs(m->min), fabs(m->max)) * 0x1p-48;
    if (m->mean < m->min - slack || m->mean > m->max + slack)
        return 0;
    if (m->n == 1 && (m->m2 != 0.0 || m->min != m->max))
        return 0;
    return 1;
}

int mcstat_moments_from_bytes(const unsigned char *buf, size_t size, mcstat_moments *m)
{
    MCSTAT_IEEE_SCOPE();
    if (!buf || !m)
        return MCSTAT_EINVAL;
    if (size != MCSTAT_MOMENTS_BYTES || memcmp(buf, "MCSM", 4) != 0 || get_u32(buf + 4) != FORMAT_VERSION ||
        get_u64(buf + CHECKED_BYTES) != fnv1a(buf, CHECKED_BYTES) || get_u32(buf + 20) != 0 ||
        get_u64(buf + 80) != 0)
        return MCSTAT_ECORRUPT;
    mcstat_moments r;
    mcstat_moments_init(&r);
    r.n = get_u64(buf + 8);
    if (r.n > 0) {
        r.scale = (int32_t)get_u32(buf + 16);
        r.mean = get_f64(buf + 24);
        r.mean_lo = get_f64(buf + 32);
        r.m2 = get_f64(buf + 40);
        r.m3 = get_f64(buf + 48);
        r.m4 = get_f64(buf + 56);
        r.min = get_f64(buf + 64);
        r.max = get_f64(buf + 72);
    } else {
        for (int i = 16; i < 80; i++)
            if (buf[i] != 0)
                return MCSTAT_ECORRUPT;
    }
    if (!consistent(&r))
        return MCSTAT_ECORRUPT;
    *m = r;
    return MCSTAT_OK;
}
