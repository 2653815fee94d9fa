/*
 * fuzz_bytes.c - mcstat_moments_from_bytes on arbitrary bytes, then
 * everything that may be done with what it accepts.
 *
 * Input: a mode byte, then 96 bytes.  Mode bit 0 clear: the bytes go to
 * from_bytes as they are (corrupt, truncated: the checksum almost always
 * refuses them).  Bit 0 set: the harness writes the magic, the version and
 * the FNV-1a checksum of the format (serialize.c's layout, recomputed here
 * independently), so the fuzzer reaches the consistency checks and, past
 * them, accumulators that no sequence of adds would produce.  The rest of
 * the input: data for a second sample, a null value, the alternative, alpha.
 * Invariants: an accepted accumulator re-serializes to the same bytes; the
 * tests and merges on it keep fz_check_result's invariants; the derived
 * quantities are NaN or in range; a refused input leaves *m untouched.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#define NB MCSTAT_MOMENTS_BYTES

static uint64_t fnv1a(const unsigned char *p, size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

static void put_u64(unsigned char *p, uint64_t v)
{
    for (int i = 0; i < 8; i++)
        p[i] = (unsigned char)(v >> (8 * i));
}

static void use_moments(const mcstat_moments *m, fz_input *in)
{
    double mean = mcstat_moments_mean(m), var = mcstat_moments_var(m), sd = mcstat_moments_sd(m);
    (void)mcstat_moments_skewness(m);
    (void)mcstat_moments_kurtosis(m);
    if (m->n > 0)
        FZ_ASSERT(!isnan(mean), "mean NaN at n %llu", (unsigned long long)m->n);
    FZ_ASSERT(isnan(var) || var >= 0.0, "var %.17g", var);
    FZ_ASSERT(isnan(sd) || sd >= 0.0, "sd %.17g", sd);

    double y[32];
    size_t ny = fz_doubles(in, y, 32);
    double v = fz_double(in);
    int alt = fz_alternative(in);
    double alpha = fz_alpha(in);
    mcstat_moments my;
    mcstat_moments_init(&my);
    (void)mcstat_moments_add_array(&my, y, ny);

    if (fz_verbose()) {
        fz_print_doubles("y", y, ny);
        fprintf(stderr, "null %a alt %d alpha %a\n", v, alt, alpha);
    }
    mcstat_result r;
    double n1 = (double)m->n, n2 = (double)m->n + (double)my.n;
    int ts = mcstat_t_test_1_moments(m, v, alt, alpha, &r);
    fz_check_result(ts, &r, MCSTAT_TEST_T_1, alt, alpha, 0);
    fz_check_not_enumeric(ts, n1, "t_test_1_moments");
    ts = mcstat_var_test_1_moments(m, fabs(v), alt, alpha, &r);
    fz_check_result(ts, &r, MCSTAT_TEST_VAR_1, alt, alpha, 0);
    fz_check_not_enumeric(ts, n1, "var_test_1_moments");
    ts = mcstat_t_test_2_moments(m, &my, v, alt, alpha, &r);
    fz_check_result(ts, &r, MCSTAT_TEST_T_2, alt, alpha, 0);
    fz_check_not_enumeric(ts, n2, "t_test_2_moments");
    ts = mcstat_t_test_2_moments(&my, m, v, alt, alpha, &r);
    fz_check_result(ts, &r, MCSTAT_TEST_T_2, alt, alpha, 0);
    fz_check_not_enumeric(ts, n2, "t_test_2_moments");
    ts = mcstat_var_test_2_moments(m, &my, fabs(v), alt, alpha, &r);
    fz_check_result(ts, &r, MCSTAT_TEST_VAR_2, alt, alpha, 0);
    fz_check_not_enumeric(ts, n2, "var_test_2_moments");

    /* Merges both ways and with itself: counts add (or the merge is refused
     * with MCSTAT_ETOOBIG, unchanged, when the sum would pass 2^64 - 1),
     * extremes combine, and the merged accumulator is again one that
     * serializes and deserializes. */
    mcstat_moments c[3] = {*m, my, *m};
    const mcstat_moments before[3] = {*m, my, *m};
    int mst[3];
    mst[0] = mcstat_moments_merge(&c[0], &my);
    mst[1] = mcstat_moments_merge(&c[1], m);
    mst[2] = mcstat_moments_merge(&c[2], &c[2]);
    for (int i = 0; i < 3; i++) {
        uint64_t add = i == 0 ? my.n : m->n, had = before[i].n;
        if (add > UINT64_MAX - had) {
            FZ_ASSERT(mst[i] == MCSTAT_ETOOBIG, "merge %d past 2^64 - 1: status %d", i, mst[i]);
            FZ_ASSERT(memcmp(&c[i], &before[i], sizeof c[i]) == 0, "refused merge %d changed dst", i);
            continue;
        }
        FZ_ASSERT(mst[i] == MCSTAT_OK, "merge %d: status %d", i, mst[i]);
        FZ_ASSERT(c[i].n == had + add, "merged n %llu, want %llu", (unsigned long long)c[i].n,
                  (unsigned long long)(had + add));
        unsigned char b[NB];
        mcstat_moments back;
        FZ_ASSERT(mcstat_moments_to_bytes(&c[i], b, NB) == MCSTAT_OK, "to_bytes merged");
        /* from_bytes checks necessary conditions (it cannot prove that data
         * exist with these moments), so a record it accepted but no data
         * could produce may merge into one it refuses: here only "refused
         * as corrupt, never crashed or misread".  Accumulators built from
         * data must read back after any merges: fuzz_moments asserts that.
         * (CI found such a pair at n = 1.8e19; each stricter rule only moved
         * the hole.) */
        int back_st = mcstat_moments_from_bytes(b, NB, &back);
        FZ_ASSERT(back_st == MCSTAT_OK || back_st == MCSTAT_ECORRUPT, "merged %d read back: status %d", i, back_st);
        fz_check_result(mcstat_t_test_1_moments(&c[i], v, alt, alpha, &r), &r, MCSTAT_TEST_T_1, alt, alpha, 0);
    }
    /* One more value, and the stream built on it. */
    mcstat_moments d = *m;
    int st = mcstat_moments_add(&d, v);
    fz_check_status(st);
    if (st == MCSTAT_OK)
        FZ_ASSERT(d.n == m->n + 1, "add: n");
    if (m->n == UINT64_MAX && isfinite(v))
        FZ_ASSERT(st == MCSTAT_ETOOBIG && memcmp(&d, m, sizeof d) == 0, "add past 2^64 - 1: status %d", st);
    mcstat_stream s;
    mcstat_stream_init(&s);
    s.moments = *m;
    for (size_t i = 0; i < ny; i++)
        mcstat_stream_add(&s, y[i]);
    fz_check_status(mcstat_stream_check_mean(&s, v, 0.0, alpha, &r));
    fz_check_status(mcstat_stream_check_var(&s, fabs(v), alpha, &r));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    uint8_t mode = fz_u8(&in);
    unsigned char b[NB + 8];
    size_t nb = fz_bytes(&in, b, NB);
    if (mode & 1) {
        if (nb < NB)
            memset(b + nb, 0, NB - nb);
        nb = NB;
        memcpy(b, "MCSM", 4);
        b[4] = 1, b[5] = b[6] = b[7] = 0;
        if (mode & 2) /* the reserved bytes zero, as the format requires */
            memset(b + 20, 0, 4), memset(b + 80, 0, 8);
        put_u64(b + 88, fnv1a(b, 88));
    }
    mcstat_moments m, keep;
    memset(&m, 0x77, sizeof m);
    keep = m;
    size_t len = (mode & 4) ? (size_t)(mode >> 3) + NB - 16 : nb; /* wrong lengths too */
    int st = mcstat_moments_from_bytes(b, len, &m);
    fz_check_status(st);
    if (st != MCSTAT_OK) {
        FZ_ASSERT(st == MCSTAT_ECORRUPT, "from_bytes: status %d", st);
        FZ_ASSERT(memcmp(&m, &keep, sizeof m) == 0, "refused bytes changed *m");
        return 0;
    }
    FZ_ASSERT(len == NB, "accepted %zu bytes", len);
    unsigned char b2[NB];
    FZ_ASSERT(mcstat_moments_to_bytes(&m, b2, NB) == MCSTAT_OK, "to_bytes");
    FZ_ASSERT(memcmp(b, b2, NB) == 0, "accepted bytes do not round-trip");
    FZ_ASSERT(mcstat_moments_to_bytes(&m, b2, NB - 1) == MCSTAT_EBUFSIZE, "short buffer");
    if (fz_verbose())
        fprintf(stderr, "n %llu scale %d mean %a mean_lo %a m2 %a m3 %a m4 %a min %a max %a\n",
                (unsigned long long)m.n, m.scale, m.mean, m.mean_lo, m.m2, m.m3, m.m4, m.min, m.max);
    use_moments(&m, &in);
    return 0;
}
