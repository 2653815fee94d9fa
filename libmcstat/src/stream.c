/*
 * stream.c - the buffered per-thread accumulator and the checks on it.
 *
 * The hot path (mcstat_stream_add, inline in mcstat.h) only stores a value;
 * everything else happens here once per MCSTAT_STREAM_CAPACITY values.  A
 * flush is mcstat_moments_add_array on the buffer, so a stream's moments are
 * exactly those add_array computes for the same blocks of values.  add_array
 * refuses a block holding NaN or Inf as a whole; the flush then compacts the
 * finite values in place and counts the others, which a check reports as
 * MCSTAT_ENONFINITE: a renderer that produced a NaN has a bug, whatever the
 * mean of the rest says.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

_Static_assert(sizeof(mcstat_stream) == MCSTAT_STREAM_BYTES, "mcstat_stream is MCSTAT_STREAM_BYTES bytes");

static int is_valid(const mcstat_stream *s)
{
    return s && s->version == MCSTAT_STREAM_VERSION && s->count < MCSTAT_STREAM_CAPACITY + 1u;
}

/* Adds x[0..n) to m; non-finite values are left out and counted.  x may be
 * compacted in place (only when it holds a non-finite value). */
static int add_values(mcstat_moments *m, double *x, size_t n, uint64_t *n_nonfinite)
{
    int st = mcstat_moments_add_array(m, x, n);
    if (st != MCSTAT_ENONFINITE)
        return st;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (isfinite(x[i]))
            x[k++] = x[i];
        else
            (*n_nonfinite)++;
    }
    return mcstat_moments_add_array(m, x, k);
}

int mcstat_stream_init(mcstat_stream *s)
{
    MCSTAT_IEEE_SCOPE();
    if (!s)
        return MCSTAT_EINVAL;
    memset(s, 0, sizeof *s);
    mcstat_moments_init(&s->moments);
    s->version = MCSTAT_STREAM_VERSION;
    return MCSTAT_OK;
}

int mcstat_stream_flush(mcstat_stream *s)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(s))
        return MCSTAT_EINVAL;
    if (s->count > UINT64_MAX - s->moments.n) {
        /* The count would wrap.  The buffer must still empty (the inline
         * mcstat_stream_add writes past a full one), so the values are left
         * out and counted; the checks then refuse the stream. */
        s->n_overflow = s->count > UINT64_MAX - s->n_overflow ? UINT64_MAX : s->n_overflow + s->count;
        s->count = 0;
        return MCSTAT_ETOOBIG;
    }
    int st = add_values(&s->moments, s->buf, s->count, &s->n_nonfinite);
    if (st == MCSTAT_OK)
        s->count = 0;
    return st;
}

int mcstat_stream_merge(mcstat_stream *dst, const mcstat_stream *src)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(dst) || !is_valid(src))
        return MCSTAT_EINVAL;
    /* src's buffer goes through a copy: src stays untouched (and may be dst) */
    double tmp[MCSTAT_STREAM_CAPACITY];
    size_t n = src->count;
    memcpy(tmp, src->buf, n * sizeof *tmp);
    mcstat_moments sm = src->moments;
    uint64_t bad = src->n_nonfinite;
    /* Counts must not wrap: refused with dst unchanged.  (Buffered values
     * count as both finite and not: at most 2 * 492 too strict.) */
    uint64_t buffered = (uint64_t)dst->count + n;
    if (sm.n > UINT64_MAX - dst->moments.n || buffered > UINT64_MAX - dst->moments.n - sm.n ||
        bad > UINT64_MAX - dst->n_nonfinite || buffered > UINT64_MAX - dst->n_nonfinite - bad ||
        src->n_overflow > UINT64_MAX - dst->n_overflow)
        return MCSTAT_ETOOBIG;
    uint64_t overflow = src->n_overflow;
    int st = mcstat_stream_flush(dst);
    if (st != MCSTAT_OK)
        return st;
    if ((st = mcstat_moments_merge(&dst->moments, &sm)) != MCSTAT_OK)
        return st;
    if ((st = add_values(&dst->moments, tmp, n, &bad)) != MCSTAT_OK)
        return st;
    dst->n_nonfinite += bad;
    dst->n_overflow += overflow;
    return MCSTAT_OK;
}

int mcstat_stream_moments(const mcstat_stream *s, mcstat_moments *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!is_valid(s) || !out)
        return MCSTAT_EINVAL;
    double tmp[MCSTAT_STREAM_CAPACITY];
    memcpy(tmp, s->buf, s->count * sizeof *tmp);
    mcstat_moments m = s->moments;
    uint64_t bad = 0;
    int st = add_values(&m, tmp, s->count, &bad);
    if (st == MCSTAT_OK)
        *out = m;
    return st;
}

int mcstat__stream_moments_checked(const mcstat_stream *s, mcstat_moments *m)
{
    int st = mcstat_stream_moments(s, m);
    if (st != MCSTAT_OK)
        return st;
    if (s->n_overflow > 0)
        return MCSTAT_ETOOBIG;
    if (s->n_nonfinite > 0)
        return MCSTAT_ENONFINITE;
    for (uint32_t i = 0; i < s->count; i++)
        if (!isfinite(s->buf[i]))
            return MCSTAT_ENONFINITE;
    return MCSTAT_OK;
}

int mcstat_stream_check_mean(const mcstat_stream *s, double reference, double tolerance, double alpha,
                             mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out || !isfinite(reference) || !isfinite(tolerance) || !(tolerance >= 0.0))
        return MCSTAT_EINVAL;
    mcstat_moments m;
    int st = mcstat__stream_moments_checked(s, &m);
    if (st != MCSTAT_OK)
        return st;
    if (tolerance == 0.0)
        return mcstat_t_test_1_moments(&m, reference, MCSTAT_TWO_SIDED, alpha, out);
    if (!(alpha > 0.0 && alpha < 1.0))
        return MCSTAT_EINVAL;
    /* Two one-sided tests at alpha/2: with tolerance -> 0 they become the
     * two-sided test at alpha, and on the boundary of H0 (mean = reference
     * +- tolerance) each rejects with probability alpha/2. */
    mcstat_result hi, lo;
    if ((st = mcstat_t_test_1_moments(&m, reference + tolerance, MCSTAT_GREATER, alpha / 2, &hi)) != MCSTAT_OK)
        return st;
    if ((st = mcstat_t_test_1_moments(&m, reference - tolerance, MCSTAT_LESS, alpha / 2, &lo)) != MCSTAT_OK)
        return st;
    *out = hi.p_value <= lo.p_value ? hi : lo;
    return MCSTAT_OK;
}

int mcstat_stream_check_var(const mcstat_stream *s, double bound, double alpha, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!out)
        return MCSTAT_EINVAL;
    mcstat_moments m;
    int st = mcstat__stream_moments_checked(s, &m);
    if (st != MCSTAT_OK)
        return st;
    return mcstat_var_test_1_moments(&m, bound, MCSTAT_GREATER, alpha, out);
}
