/*
 * sort.c - LSD radix sort of 64-bit keys (doubles mapped to order-preserving
 * keys by mcstat__order_key).
 *
 * Why not qsort: the unweighted K-S test on 1e6 + 1e6 values is all sorting;
 * comparison sorts take ~n log n branchy comparisons through a function
 * pointer, a radix sort takes a fixed number of streaming passes.  Eight
 * passes of 8 bits cover 64 bits; a pass whose digit is the same for every
 * key (the top bits of data in a narrow range, common for estimates) is
 * skipped, which the AND and OR of all keys, taken in the first read, tell
 * in advance.
 * Digits of 8 bits measured faster than 11 (9.3 against 11.8 ms for 1e6
 * normal deviates, bench/RESULTS_ks.md): 256 destinations per pass stay
 * within what the store buffers and L1 absorb, 2048 do not, and the extra
 * two passes cost less than that.  Each scatter pass also counts the next
 * pass's digit (8.0 against 9.4 ms with all counts in a first read: the
 * counting hides behind the scatter's stores).  Sorting doubles, the key
 * transform, the NaN check and the AND / OR share one read.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <stdlib.h>

#define RADIX_BITS 8
#define RADIX_SIZE (1u << RADIX_BITS)
#define RADIX_PASSES 8
#define SMALL_N 64

static void insertion_sort(uint64_t *a, size_t n)
{
    for (size_t i = 1; i < n; i++) {
        uint64_t v = a[i];
        size_t j = i;
        while (j > 0 && a[j - 1] > v) {
            a[j] = a[j - 1];
            j--;
        }
        a[j] = v;
    }
}

/* The scatter passes over the digits that vary among the keys (diff = the
 * AND of all keys XOR their OR: a digit whose bits never differ would only
 * copy).  Each pass counts the next live digit while it scatters the
 * current one; only the first digit has a read of its own (counting it in
 * the caller's first read measured slower: that loop then no longer
 * vectorises). */
static void passes(uint64_t *a, size_t n, uint64_t *tmp, uint64_t diff)
{
    int live[RADIX_PASSES], nl = 0;
    for (int p = 0; p < RADIX_PASSES; p++)
        if ((diff >> (p * RADIX_BITS)) & (RADIX_SIZE - 1))
            live[nl++] = p;
    if (nl == 0)
        return;
    size_t h[2][RADIX_SIZE] = {{0}};
    {
        const int shift = live[0] * RADIX_BITS;
        for (size_t i = 0; i < n; i++)
            h[0][(a[i] >> shift) & (RADIX_SIZE - 1)]++;
    }
    uint64_t *src = a, *dst = tmp;
    for (int q = 0; q < nl; q++) {
        size_t *cur = h[q & 1], *next = h[(q + 1) & 1];
        size_t sum = 0;
        for (unsigned b = 0; b < RADIX_SIZE; b++) {
            size_t c = cur[b];
            cur[b] = sum;
            sum += c;
        }
        const int shift = live[q] * RADIX_BITS;
        if (q + 1 < nl) {
            const int nshift = live[q + 1] * RADIX_BITS;
            memset(next, 0, RADIX_SIZE * sizeof *next);
            for (size_t i = 0; i < n; i++) {
                uint64_t k = src[i];
                next[(k >> nshift) & (RADIX_SIZE - 1)]++;
                dst[cur[(k >> shift) & (RADIX_SIZE - 1)]++] = k;
            }
        } else {
            for (size_t i = 0; i < n; i++) {
                uint64_t k = src[i];
                dst[cur[(k >> shift) & (RADIX_SIZE - 1)]++] = k;
            }
        }
        uint64_t *t = src;
        src = dst;
        dst = t;
    }
    if (src != a)
        memcpy(a, src, n * sizeof *a);
}

int mcstat__radix_sort_u64(uint64_t *a, size_t n, uint64_t *tmp)
{
    if (n <= SMALL_N) {
        insertion_sort(a, n);
        return MCSTAT_OK;
    }
    uint64_t all = ~UINT64_C(0), any = 0;
    for (size_t i = 0; i < n; i++) {
        all &= a[i];
        any |= a[i];
    }
    passes(a, n, tmp, all ^ any);
    return MCSTAT_OK;
}

int mcstat__sort_double_keys(const double *x, size_t n, uint64_t *keys, uint64_t *tmp)
{
    uint64_t all = ~UINT64_C(0), any = 0, nan = 0;
    for (size_t i = 0; i < n; i++) { /* branch-free, so that it vectorises */
        uint64_t b;
        memcpy(&b, &x[i], sizeof b);
        nan |= (b & 0x7fffffffffffffffull) > 0x7ff0000000000000ull; /* a NaN's exponent and mantissa */
        uint64_t k = mcstat__order_key(x[i]);
        keys[i] = k;
        all &= k;
        any |= k;
    }
    if (nan)
        return MCSTAT_ENONFINITE;
    if (n <= SMALL_N)
        insertion_sort(keys, n);
    else
        passes(keys, n, tmp, all ^ any);
    return MCSTAT_OK;
}
