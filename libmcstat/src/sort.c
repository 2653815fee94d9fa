/*
 * sort.c - LSD radix sort of 64-bit keys (doubles mapped to order-preserving
 * keys by mcstat__order_key).
 *
 * Why not qsort: the unweighted K-S test on 1e6 + 1e6 values is all sorting;
 * comparison sorts take ~n log n branchy comparisons through a function
 * pointer, a radix sort takes a fixed number of streaming passes.  Six passes
 * of 11 bits cover 64 bits; a pass whose digit is the same for every key
 * (the top bits of data in a narrow range, common for estimates) is skipped,
 * which the histograms, all counted in one read, tell in advance.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <stdlib.h>

#define RADIX_BITS 11
#define RADIX_SIZE (1u << RADIX_BITS)
#define RADIX_PASSES 6
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

int mcstat__radix_sort_u64(uint64_t *a, size_t n, uint64_t *tmp)
{
    if (n <= SMALL_N) {
        insertion_sort(a, n);
        return MCSTAT_OK;
    }
    size_t *hist = calloc((size_t)RADIX_PASSES * RADIX_SIZE, sizeof *hist);
    if (!hist)
        return MCSTAT_ENOMEM;
    for (size_t i = 0; i < n; i++) {
        uint64_t k = a[i];
        for (int p = 0; p < RADIX_PASSES; p++)
            hist[(size_t)p * RADIX_SIZE + ((k >> (p * RADIX_BITS)) & (RADIX_SIZE - 1))]++;
    }
    uint64_t *src = a, *dst = tmp;
    for (int p = 0; p < RADIX_PASSES; p++) {
        size_t *h = hist + (size_t)p * RADIX_SIZE;
        unsigned first = (unsigned)((src[0] >> (p * RADIX_BITS)) & (RADIX_SIZE - 1));
        if (h[first] == n) /* every key has this digit: the pass would copy */
            continue;
        size_t sum = 0;
        for (unsigned b = 0; b < RADIX_SIZE; b++) {
            size_t c = h[b];
            h[b] = sum;
            sum += c;
        }
        const int shift = p * RADIX_BITS;
        for (size_t i = 0; i < n; i++) {
            uint64_t k = src[i];
            dst[h[(k >> shift) & (RADIX_SIZE - 1)]++] = k;
        }
        uint64_t *t = src;
        src = dst;
        dst = t;
    }
    if (src != a)
        memcpy(a, src, n * sizeof *a);
    free(hist);
    return MCSTAT_OK;
}
