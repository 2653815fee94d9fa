/*
 * fuzz_moments.c - the accumulator API (add, add_array, omit_nan, merge, the
 * derived quantities, serialization) and the buffered stream on top of it.
 *
 * Input: a sequence of operations, each a byte then its arguments, applied
 * to an accumulator A, a second accumulator B and a stream S; every finite
 * value that reaches A is also kept in a plain list.  Invariants after each
 * step: n counts exactly the values added, min and max are exact, the mean
 * lies in [min, max], the variance is >= 0 and its square root is sd, the
 * skewness and kurtosis respect their sample bounds, serialization round-
 * trips byte for byte, a failed call leaves the accumulator untouched.  At
 * the end A agrees with one add_array over the whole list (merges and
 * single adds are exact to rounding), and S with add_array over what it saw.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#define MAXOPS 24
#define MAXARR 48
#define MAXALL 2048 /* values kept per list; operations that would exceed it are skipped */

static double all_a[MAXALL], all_s[MAXALL];
static size_t n_a, n_s;

static double max_abs(const double *v, size_t n)
{
    double m = 0.0;
    for (size_t i = 0; i < n; i++)
        m = fmax(m, fabs(v[i]));
    return m;
}

static void check_invariants(const mcstat_moments *m, const char *what)
{
    FZ_ASSERT(m->version == MCSTAT_MOMENTS_VERSION, "%s: version %u", what, m->version);
    double mean = mcstat_moments_mean(m), var = mcstat_moments_var(m), sd = mcstat_moments_sd(m);
    double g1 = mcstat_moments_skewness(m), g2 = mcstat_moments_kurtosis(m);
    if (m->n == 0) {
        FZ_ASSERT(m->min == INFINITY && m->max == -INFINITY, "%s: empty min/max", what);
        FZ_ASSERT(isnan(mean) && isnan(var), "%s: empty mean %g var %g", what, mean, var);
    } else {
        FZ_ASSERT(m->min <= m->max, "%s: min %.17g > max %.17g", what, m->min, m->max);
        FZ_ASSERT(mean >= m->min && mean <= m->max, "%s: mean %.17g outside [%.17g, %.17g]", what, mean, m->min,
                  m->max);
    }
    if (m->n < 2) {
        FZ_ASSERT(isnan(var) && isnan(sd), "%s: n %llu var %g sd %g", what, (unsigned long long)m->n, var, sd);
        return;
    }
    FZ_ASSERT(var >= 0.0 && sd >= 0.0, "%s: var %.17g sd %.17g", what, var, sd);
    if (isfinite(var) && var >= 1e-290)
        FZ_ASSERT(fabs(sd - sqrt(var)) <= 1e-14 * sd, "%s: sd %.17g, sqrt(var) %.17g", what, sd, sqrt(var));
    /* The spread can never exceed the range: sd <= (max - min) sqrt(n / (4 (n-1))) */
    double n = (double)m->n, range = m->max - m->min;
    if (isfinite(range))
        FZ_ASSERT(sd <= range * sqrt(n / (4.0 * (n - 1.0))) * (1.0 + 1e-9) + 0x1p-1073, /* subnormal rounding */
                  "%s: sd %.17g, range %.17g", what, sd, range);
    if (!isnan(g1)) /* |g1| <= (n-2)/sqrt(n-1) */
        FZ_ASSERT(fabs(g1) <= (n - 2.0) / sqrt(n - 1.0) * (1.0 + 1e-6) + 1e-9, "%s: skewness %.17g at n %g",
                  what, g1, n);
    if (!isnan(g2)) /* 1 <= n M4/M2^2 <= (n^2 - 3n + 3)/(n - 1) */
        FZ_ASSERT(g2 + 3.0 >= 1.0 - 1e-6 && g2 + 3.0 <= (n * n - 3.0 * n + 3.0) / (n - 1.0) * (1.0 + 1e-6) + 1e-9,
                  "%s: kurtosis %.17g at n %g", what, g2, n);

    unsigned char b[MCSTAT_MOMENTS_BYTES], b2[MCSTAT_MOMENTS_BYTES];
    mcstat_moments back;
    FZ_ASSERT(mcstat_moments_to_bytes(m, b, sizeof b) == MCSTAT_OK, "%s: to_bytes", what);
    int st = mcstat_moments_from_bytes(b, sizeof b, &back);
    FZ_ASSERT(st == MCSTAT_OK, "%s: from_bytes of its own bytes: status %d (n %llu scale %d mean %a lo %a m2 %a m3 %a m4 %a min %a max %a)",
              what, st, (unsigned long long)m->n, m->scale, m->mean, m->mean_lo, m->m2, m->m3, m->m4, m->min, m->max);
    FZ_ASSERT(mcstat_moments_to_bytes(&back, b2, sizeof b2) == MCSTAT_OK && memcmp(b, b2, sizeof b) == 0,
              "%s: bytes do not round-trip", what);
}

/* m agrees with one add_array over v[0..n): exact n, min, max; mean and
 * variance to rounding (relative to the data's magnitude and the variance). */
static void check_against(const mcstat_moments *m, const double *v, size_t n, const char *what)
{
    mcstat_moments ref;
    mcstat_moments_init(&ref);
    FZ_ASSERT(mcstat_moments_add_array(&ref, v, n) == MCSTAT_OK, "%s: reference add_array", what);
    FZ_ASSERT(m->n == ref.n, "%s: n %llu, want %llu", what, (unsigned long long)m->n, (unsigned long long)ref.n);
    if (!n)
        return;
    FZ_ASSERT(m->min == ref.min && m->max == ref.max, "%s: min/max", what);
    double big = max_abs(v, n);
    double mean = mcstat_moments_mean(m), want = mcstat_moments_mean(&ref);
    FZ_ASSERT(fabs(mean - want) <= 1e-12 * big + 0x1p-1068, /* 64 subnormal ulps */ "%s: mean %.17g, want %.17g (max |x| %g)", what, mean, want, big);
    double var = mcstat_moments_var(m), wvar = mcstat_moments_var(&ref);
    if (n >= 2 && isfinite(wvar) && wvar > 1e-280 && big < 1e150)
        FZ_ASSERT(fabs(var - wvar) <= 1e-6 * wvar + 1e-20 * big * big, "%s: var %.17g, want %.17g", what, var,
                  wvar);
}

/* A failed call must leave the accumulator as it was. */
#define UNCHANGED_UNLESS_OK(st, before, m, what)                                                    \
    do {                                                                                            \
        if ((st) != MCSTAT_OK)                                                                      \
            FZ_ASSERT(memcmp(&(before), (m), sizeof(before)) == 0, "%s: status %d changed it", what, st); \
    } while (0)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    mcstat_moments a, bm, before;
    mcstat_moments_init(&a);
    mcstat_moments_init(&bm);
    static mcstat_stream s, s2;
    mcstat_stream_init(&s);
    n_a = n_s = 0;
    double v[MAXARR];
    size_t b_count = 0;
    static double b_vals[MAXALL];
    uint64_t s_nonfinite = 0;

    for (int op = 0; op < MAXOPS && fz_remaining(&in); op++) {
        int st;
        size_t k, omitted;
        double x;
        before = a;
        int code = fz_u8(&in) % 9;
        if (fz_verbose())
            fprintf(stderr, "op %d: A n %llu mean %a scale %d m2 %a min %a max %a; B n %llu mean %a scale %d\n", code,
                    (unsigned long long)a.n, a.mean, a.scale, a.m2, a.min, a.max, (unsigned long long)bm.n, bm.mean,
                    bm.scale);
        switch (code) {
        case 0: /* one value */
            if (n_a + 1 > MAXALL)
                break;
            x = fz_double(&in);
            st = mcstat_moments_add(&a, x);
            FZ_ASSERT(st == (isfinite(x) ? MCSTAT_OK : MCSTAT_ENONFINITE), "add(%g): status %d", x, st);
            UNCHANGED_UNLESS_OK(st, before, &a, "add");
            if (!st)
                all_a[n_a++] = x;
            break;
        case 1: /* an array */
            if (n_a + MAXARR > MAXALL)
                break;
            k = fz_doubles(&in, v, MAXARR);
            if (fz_verbose())
                fz_print_doubles("add_array", v, k);
            st = mcstat_moments_add_array(&a, v, k);
            fz_check_status(st);
            UNCHANGED_UNLESS_OK(st, before, &a, "add_array");
            if (!st) {
                memcpy(all_a + n_a, v, k * sizeof *v);
                n_a += k;
            } else {
                FZ_ASSERT(st == MCSTAT_ENONFINITE, "add_array: status %d", st);
            }
            break;
        case 2: { /* an array, NaN skipped */
            if (n_a + MAXARR > MAXALL)
                break;
            k = fz_doubles(&in, v, MAXARR);
            omitted = 12345;
            st = mcstat_moments_add_array_omit_nan(&a, v, k, (fz_u8(&in) & 1) ? NULL : &omitted);
            UNCHANGED_UNLESS_OK(st, before, &a, "omit_nan");
            size_t nans = 0, infs = 0;
            for (size_t i = 0; i < k; i++)
                nans += isnan(v[i]) != 0, infs += isinf(v[i]) != 0; /* glibc: isinf(-Inf) = -1 */
            if (fz_verbose())
                fz_print_doubles("omit_nan", v, k);
            FZ_ASSERT(st == (infs ? MCSTAT_ENONFINITE : MCSTAT_OK), "omit_nan: status %d with %zu Inf", st, infs);
            if (!st) {
                FZ_ASSERT(omitted == 12345 || omitted == nans, "omitted %zu, NaN %zu", omitted, nans);
                for (size_t i = 0; i < k; i++)
                    if (!isnan(v[i]))
                        all_a[n_a++] = v[i];
            }
            break;
        }
        case 3: /* values into B */
            if (b_count + MAXARR > MAXALL)
                break;
            k = fz_doubles(&in, v, MAXARR);
            if (mcstat_moments_add_array(&bm, v, k) == MCSTAT_OK) {
                memcpy(b_vals + b_count, v, k * sizeof *v);
                b_count += k;
            }
            break;
        case 4: /* A <- A + B */
            if (n_a + b_count > MAXALL)
                break;
            st = mcstat_moments_merge(&a, &bm);
            FZ_ASSERT(st == MCSTAT_OK, "merge: status %d", st);
            memcpy(all_a + n_a, b_vals, b_count * sizeof *v);
            n_a += b_count;
            break;
        case 5: /* A <- A + A */
            if (2 * n_a > MAXALL)
                break;
            st = mcstat_moments_merge(&a, &a);
            FZ_ASSERT(st == MCSTAT_OK, "self merge: status %d", st);
            memcpy(all_a + n_a, all_a, n_a * sizeof *v);
            n_a += n_a;
            break;
        case 6: /* values into the stream (non-finite ones are counted, not added) */
            if (n_s + MAXARR > MAXALL)
                break;
            k = fz_doubles(&in, v, MAXARR);
            for (size_t i = 0; i < k; i++) {
                mcstat_stream_add(&s, v[i]);
                if (isfinite(v[i]))
                    all_s[n_s++] = v[i];
                else
                    s_nonfinite++;
            }
            break;
        case 7: /* flush, or merge the stream into itself via a copy */
            if (fz_u8(&in) & 1) {
                FZ_ASSERT(mcstat_stream_flush(&s) == MCSTAT_OK, "stream_flush");
                FZ_ASSERT(s.count == 0, "flush left %u", s.count);
            } else if (2 * n_s <= MAXALL) {
                s2 = s;
                FZ_ASSERT(mcstat_stream_merge(&s, &s2) == MCSTAT_OK, "stream_merge");
                memcpy(all_s + n_s, all_s, n_s * sizeof *v);
                n_s += n_s;
                s_nonfinite *= 2;
            }
            break;
        default: { /* B <- B + A, checked against the list, then B emptied */
            mcstat_moments c = bm;
            FZ_ASSERT(mcstat_moments_merge(&c, &a) == MCSTAT_OK, "merge into copy");
            if (b_count + n_a <= MAXALL) {
                memcpy(b_vals + b_count, all_a, n_a * sizeof *v);
                check_against(&c, b_vals, b_count + n_a, "B+A");
            }
            mcstat_moments_init(&bm);
            b_count = 0;
            break;
        }
        }
        check_invariants(&a, "A");
        check_invariants(&bm, "B");
    }
    check_against(&a, all_a, n_a, "A");

    mcstat_moments sm;
    FZ_ASSERT(mcstat_stream_moments(&s, &sm) == MCSTAT_OK, "stream_moments");
    FZ_ASSERT(mcstat_stream_flush(&s) == MCSTAT_OK, "stream_flush"); /* counts the buffered non-finite values */
    FZ_ASSERT(s.n_nonfinite == s_nonfinite, "n_nonfinite %llu, want %llu", (unsigned long long)s.n_nonfinite,
              (unsigned long long)s_nonfinite);
    check_invariants(&sm, "stream");
    check_against(&sm, all_s, n_s, "stream");
    return 0;
}
