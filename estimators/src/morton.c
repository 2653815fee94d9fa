/*
 * morton.c - 64-bit Morton keys of directions through Lambert's equal-area
 * cylindrical map (documented in mcest.h).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

/* Spreads the 32 bits of x to the even bit positions of a 64-bit word. */
static inline uint64_t spread(uint64_t x)
{
    x &= 0xFFFFFFFFULL;
    x = (x | (x << 16)) & 0x0000FFFF0000FFFFULL;
    x = (x | (x << 8)) & 0x00FF00FF00FF00FFULL;
    x = (x | (x << 4)) & 0x0F0F0F0F0F0F0F0FULL;
    x = (x | (x << 2)) & 0x3333333333333333ULL;
    x = (x | (x << 1)) & 0x5555555555555555ULL;
    return x;
}

static int square_of(const double *w, double *s, double *t)
{
    if (!finite3(w))
        return 0;
    double l = norm3(w);
    if (!(l > 0.0) || !isfinite(l))
        return 0;
    double z = w[2] / l;
    *s = fmin(1.0, fmax(0.0, 0.5 * (1.0 - z)));
    double a = atan2(w[1], w[0]) / (2.0 * M_PI); /* (-1/2, 1/2] */
    if (a < 0.0)
        a += 1.0;
    if (a >= 1.0)
        a = 0.0;
    *t = a;
    return 1;
}

static inline uint64_t quantise(double x)
{
    double q = floor(x * 4294967296.0);
    return q >= 4294967295.0 ? 0xFFFFFFFFULL : (uint64_t)q;
}

int mcest_direction_square(const double *w, size_t n, double *st)
{
    if (n > 0 && (!w || !st))
        return MCEST_EINVAL;
    for (size_t k = 0; k < n; k++)
        if (!square_of(w + 3 * k, st + 2 * k, st + 2 * k + 1))
            return MCEST_EINVAL;
    return MCEST_OK;
}

int mcest_direction_key(const double *w, size_t n, uint64_t *keys)
{
    if (n > 0 && (!w || !keys))
        return MCEST_EINVAL;
    for (size_t k = 0; k < n; k++) {
        double s, t;
        if (!square_of(w + 3 * k, &s, &t))
            return MCEST_EINVAL;
        keys[k] = (spread(quantise(s)) << 1) | spread(quantise(t));
    }
    return MCEST_OK;
}
