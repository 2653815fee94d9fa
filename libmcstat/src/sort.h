/*
 * sort.h - sorting doubles by their order keys (sort.c).
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_SORT_H
#define MCSTAT_SORT_H

/* ---- sorting (sort.c) ------------------------------------------------------
 * Doubles as order-preserving unsigned keys (NaN excluded, -0 made +0 so
 * that equal values have equal keys), sorted by an LSD radix sort. */
static inline uint64_t mcstat__order_key(double x)
{
    uint64_t k;
    x = x == 0.0 ? 0.0 : x;
    memcpy(&k, &x, sizeof k);
    return (k >> 63) ? ~k : k | 0x8000000000000000ull;
}
static inline double mcstat__key_double(uint64_t k)
{
    k = (k >> 63) ? k & 0x7fffffffffffffffull : ~k;
    double x;
    memcpy(&x, &k, sizeof x);
    return x;
}
/* Sorts a[0..n) ascending; tmp has room for n keys.  MCSTAT_ENOMEM. */
MCSTAT_HIDDEN int mcstat__radix_sort_u64(uint64_t *a, size_t n, uint64_t *tmp);
/* keys[0..n) <- the order keys of x, sorted; tmp has room for n keys.
 * MCSTAT_ENONFINITE (keys unspecified) if x holds a NaN. */
MCSTAT_HIDDEN int mcstat__sort_double_keys(const double *x, size_t n, uint64_t *keys, uint64_t *tmp);

#endif /* MCSTAT_SORT_H */
