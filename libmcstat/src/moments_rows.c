/*
 * moments_rows.c - arrays of accumulators, one mcstat_moments per pixel: add
 * an image (or a pixel-major stack of images), merge two arrays, and the
 * byte form of an array, for render farms that accumulate per pixel on many
 * machines and merge the results.
 *
 * A row is added as "add_array on a fresh accumulator, then merge" rather
 * than add_array on m[i] directly: add_array shifts its sums by the
 * accumulator's current mean, so adding into a non-empty accumulator rounds
 * differently from adding on another machine and merging.  With the fresh
 * accumulator, push(A); push(B) is bit for bit merge(push(A), push(B)).
 *
 * Every function validates all its arguments before writing anything; the
 * accumulators themselves live in the caller's array (no allocation).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

static int valid(const mcstat_moments *m)
{
    return m->n == 0 || m->version == MCSTAT_MOMENTS_VERSION;
}

static int all_valid(const mcstat_moments *m, size_t rows)
{
    for (size_t i = 0; i < rows; i++)
        if (!valid(&m[i]))
            return 0;
    return 1;
}

int mcstat_moments_init_rows(mcstat_moments *m, size_t rows)
{
    if (rows > 0 && !m)
        return MCSTAT_EINVAL;
    for (size_t i = 0; i < rows; i++)
        mcstat_moments_init(&m[i]);
    return MCSTAT_OK;
}

int mcstat_moments_add_rows(mcstat_moments *m, size_t rows, const double *x, size_t n, size_t x_stride,
                            unsigned flags, int32_t *status)
{
    MCSTAT_IEEE_SCOPE();
    if (rows > 0 && (!m || (n > 0 && !x)))
        return MCSTAT_EINVAL;
    if (flags & ~(unsigned)MCSTAT_ROWS_OMIT_NAN)
        return MCSTAT_EINVAL;
    if (!all_valid(m, rows))
        return MCSTAT_EINVAL;
    int first = MCSTAT_OK;
    for (size_t i = 0; i < rows; i++) {
        int st = MCSTAT_OK;
        if (n > 0) {
            mcstat_moments a;
            mcstat_moments_init(&a);
            const double *row = x + i * x_stride;
            st = (flags & MCSTAT_ROWS_OMIT_NAN) ? mcstat_moments_add_array_omit_nan(&a, row, n, NULL)
                                                : mcstat_moments_add_array(&a, row, n);
            if (!st)
                st = mcstat_moments_merge(&m[i], &a);
        }
        if (st && first == MCSTAT_OK)
            first = st;
        if (status)
            status[i] = st;
    }
    return first;
}

int mcstat_moments_merge_rows(mcstat_moments *dst, const mcstat_moments *src, size_t rows)
{
    MCSTAT_IEEE_SCOPE();
    if (rows > 0 && (!dst || !src))
        return MCSTAT_EINVAL;
    if (!all_valid(dst, rows) || !all_valid(src, rows))
        return MCSTAT_EINVAL;
    for (size_t i = 0; i < rows; i++)
        if (src[i].n > UINT64_MAX - dst[i].n) /* a count would wrap: nothing merged */
            return MCSTAT_ETOOBIG;
    for (size_t i = 0; i < rows; i++)
        mcstat_moments_merge(&dst[i], &src[i]); /* cannot fail: all checked */
    return MCSTAT_OK;
}

int mcstat_moments_to_bytes_rows(const mcstat_moments *m, size_t rows, unsigned char *buf, size_t size)
{
    if (rows > 0 && (!m || !buf))
        return MCSTAT_EINVAL;
    if (!all_valid(m, rows))
        return MCSTAT_EINVAL;
    if (rows > SIZE_MAX / MCSTAT_MOMENTS_BYTES || size < rows * MCSTAT_MOMENTS_BYTES)
        return MCSTAT_EBUFSIZE;
    for (size_t i = 0; i < rows; i++) {
        int st = mcstat_moments_to_bytes(&m[i], buf + i * MCSTAT_MOMENTS_BYTES, MCSTAT_MOMENTS_BYTES);
        if (st)
            return st; /* not reached: every record was checked */
    }
    return MCSTAT_OK;
}

int mcstat_moments_from_bytes_rows(const unsigned char *buf, size_t size, size_t rows, mcstat_moments *m)
{
    MCSTAT_IEEE_SCOPE();
    if (rows > 0 && (!buf || !m))
        return MCSTAT_EINVAL;
    if (rows > SIZE_MAX / MCSTAT_MOMENTS_BYTES || size != rows * MCSTAT_MOMENTS_BYTES)
        return MCSTAT_ECORRUPT;
    /* Two passes, so that m is untouched when any record is bad: checking a
     * 96-byte record costs far less than the caller's handling of a partly
     * overwritten image would. */
    for (size_t i = 0; i < rows; i++) {
        mcstat_moments tmp;
        int st = mcstat_moments_from_bytes(buf + i * MCSTAT_MOMENTS_BYTES, MCSTAT_MOMENTS_BYTES, &tmp);
        if (st)
            return st;
    }
    for (size_t i = 0; i < rows; i++)
        (void)mcstat_moments_from_bytes(buf + i * MCSTAT_MOMENTS_BYTES, MCSTAT_MOMENTS_BYTES, &m[i]);
    return MCSTAT_OK;
}
