/*
 * fuzz_input.h - decodes the fuzzer's bytes into arguments (a small C
 * cousin of LLVM's FuzzedDataProvider), shared by every harness.
 *
 * Everything is read front to back, so a seed can be written by hand
 * (tests/fuzz/make_corpus.py encodes the same layout).  Reads past the end
 * give zeros, so every input decodes to something.  Layout of each kind:
 *   fz_u8     1 byte
 *   fz_u16    2 bytes, little-endian; fz_u32 4 bytes; fz_u64 8 bytes
 *   fz_range  lo + v % (hi - lo + 1), v a u8 when the span fits in 8 bits,
 *             a u16 when in 16 bits, else a u32
 *   fz_double a tag byte t, then:
 *               t <  32  FZ_SPECIAL[t % FZ_NSPECIAL] (zeros, ones, the
 *                        extreme and subnormal doubles, +-Inf, NaN, ...)
 *               t < 128  (int16) u16 / 256: ordinary data in [-128, 128)
 *               t < 192  a raw u64 bit pattern: any double at all
 *               else     (int16) u16 * 2^(4 * (int8) u8): wide magnitudes
 *   fz_alpha  a byte b: b < 250 gives (b + 0.5) / 250, in (0, 1); else an
 *             arbitrary fz_double (mostly invalid: the error paths)
 *   fz_alternative  a byte b: b % 4 < 3 gives b % 4 (the valid values),
 *             else an arbitrary (int32) u32
 *   fz_doubles  n = fz_range(0, max), a mode byte m, then by m % 4:
 *               0  n fz_double values
 *               1  a base fz_double, a step fz_double, n int8 bytes k_i:
 *                  base + step * k_i (offset data: 1e9 + small noise)
 *               2  one fz_double repeated n times (degenerate data)
 *               3  n bytes k_i, each (int8) k_i (ties, small integers)
 *
 * A new harness includes this and fuzz_check.h, decodes its arguments,
 * calls the entry point, and checks the result (see fuzz_check.h).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_FUZZ_INPUT_H
#define MCSTAT_FUZZ_INPUT_H

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct fz_input {
    const uint8_t *p;
    size_t n;
} fz_input;

static inline fz_input fz_make(const uint8_t *data, size_t size)
{
    fz_input in = {data, size};
    return in;
}

static inline size_t fz_remaining(const fz_input *in) { return in->n; }

static inline uint8_t fz_u8(fz_input *in)
{
    if (!in->n)
        return 0;
    in->n--;
    return *in->p++;
}

static inline uint16_t fz_u16(fz_input *in)
{
    uint16_t lo = fz_u8(in);
    return (uint16_t)(lo | (uint16_t)fz_u8(in) << 8);
}

static inline uint32_t fz_u32(fz_input *in)
{
    uint32_t lo = fz_u16(in);
    return lo | (uint32_t)fz_u16(in) << 16;
}

static inline uint64_t fz_u64(fz_input *in)
{
    uint64_t lo = fz_u32(in);
    return lo | (uint64_t)fz_u32(in) << 32;
}

static inline int fz_bool(fz_input *in) { return fz_u8(in) & 1; }

/* An integer in [lo, hi]. */
static inline uint64_t fz_range(fz_input *in, uint64_t lo, uint64_t hi)
{
    uint64_t span = hi - lo, v;
    if (span <= 0xff)
        v = fz_u8(in);
    else if (span <= 0xffff)
        v = fz_u16(in);
    else
        v = fz_u32(in);
    return span == UINT64_MAX ? v : lo + v % (span + 1);
}

/* Up to max bytes, copied into buf; returns how many. */
static inline size_t fz_bytes(fz_input *in, uint8_t *buf, size_t max)
{
    size_t k = in->n < max ? in->n : max;
    memcpy(buf, in->p, k);
    in->p += k;
    in->n -= k;
    return k;
}

static const double FZ_SPECIAL[] = {
    0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-3, 1e3,
    DBL_MIN, -DBL_MIN, 4.9406564584124654e-324, -4.9406564584124654e-324,
    DBL_MAX, -DBL_MAX, INFINITY, -INFINITY,
    NAN, DBL_EPSILON, 1.0 + DBL_EPSILON, 1.0 - DBL_EPSILON / 2,
    1e9, -1e9, 1e-300, 1e300,
    0.05, 0.95, 1e12, 1e-12, 0x1p-1022 * 0.5, 9007199254740993.0, 3.0, 7.0};
#define FZ_NSPECIAL (sizeof FZ_SPECIAL / sizeof FZ_SPECIAL[0])

static inline double fz_double(fz_input *in)
{
    uint8_t t = fz_u8(in);
    if (t < 32)
        return FZ_SPECIAL[t % FZ_NSPECIAL];
    if (t < 128)
        return (int16_t)fz_u16(in) / 256.0;
    if (t < 192) {
        uint64_t bits = fz_u64(in);
        double d;
        memcpy(&d, &bits, sizeof d);
        return d;
    }
    double m = (int16_t)fz_u16(in);
    return ldexp(m, 4 * (int8_t)fz_u8(in));
}

static inline double fz_alpha(fz_input *in)
{
    uint8_t b = fz_u8(in);
    return b < 250 ? (b + 0.5) / 250.0 : fz_double(in);
}

static inline int fz_alternative(fz_input *in)
{
    uint8_t b = fz_u8(in);
    return b % 4 < 3 ? b % 4 : (int)(int32_t)fz_u32(in);
}

/* Fills x[0..n) (n <= max) by one of the modes above; returns n. */
static inline size_t fz_doubles(fz_input *in, double *x, size_t max)
{
    size_t n = (size_t)fz_range(in, 0, max);
    uint8_t mode = fz_u8(in) % 4;
    double base, step;
    switch (mode) {
    case 0:
        for (size_t i = 0; i < n; i++)
            x[i] = fz_double(in);
        break;
    case 1:
        base = fz_double(in);
        step = fz_double(in);
        for (size_t i = 0; i < n; i++)
            x[i] = base + step * (int8_t)fz_u8(in);
        break;
    case 2:
        base = fz_double(in);
        for (size_t i = 0; i < n; i++)
            x[i] = base;
        break;
    default:
        for (size_t i = 0; i < n; i++)
            x[i] = (int8_t)fz_u8(in);
        break;
    }
    return n;
}

/* MCSTAT_FUZZ_VERBOSE set in the environment: harnesses print the arguments
 * they decoded (stderr, %a doubles), to turn a crash file into a C test. */
static inline int fz_verbose(void)
{
    static int v = -1;
    if (v < 0)
        v = getenv("MCSTAT_FUZZ_VERBOSE") != NULL;
    return v;
}

static inline void fz_print_doubles(const char *name, const double *x, size_t n)
{
    fprintf(stderr, "%s[%zu] = {", name, n);
    for (size_t i = 0; i < n; i++)
        fprintf(stderr, "%s%a", i ? ", " : "", x[i]);
    fprintf(stderr, "}\n");
}

#endif /* MCSTAT_FUZZ_INPUT_H */
