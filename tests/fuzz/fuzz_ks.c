/*
 * fuzz_ks.c - the two-sample Kolmogorov-Smirnov test with its options, and
 * the cache of simulated null distributions.
 *
 * Input: x and y (fz_doubles, up to 40 values each, so the exact recursion
 * and a simulation of at most 256 replicates stay fast), the alternative,
 * alpha, then the options: a byte whose bits choose NULL options, an odd
 * options size, and a cache; weight, method, threads, n_sim, seed,
 * critical; the cache's byte budget.
 * Beyond fz_check_result: results are bit-identical for 1 and 2 threads and
 * with or without a cache (documented), a cache hit repeats the result, the
 * exact method's answer does not depend on which sample is called x (with
 * the alternative mirrored), and a failed call leaves *out untouched.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#define MAXN 40

static int32_t pick(fz_input *in, int32_t valid_count)
{
    uint8_t b = fz_u8(in);
    return b < 240 ? b % valid_count : (int32_t)fz_u32(in);
}

static int mirror(int alt)
{
    return alt == MCSTAT_LESS ? MCSTAT_GREATER : alt == MCSTAT_GREATER ? MCSTAT_LESS : alt;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    static double x[MAXN], y[MAXN];
    size_t nx = fz_doubles(&in, x, MAXN), ny = fz_doubles(&in, y, MAXN);
    int alt = fz_alternative(&in);
    double alpha = fz_alpha(&in);
    uint8_t flags = fz_u8(&in);

    mcstat_ks_options o;
    FZ_ASSERT(mcstat_ks_options_init(&o) == MCSTAT_OK, "options_init");
    o.weight = pick(&in, 2);
    o.method = pick(&in, 5);
    o.threads = pick(&in, 3); /* 0 is invalid, 1 and 2 are not */
    uint8_t b = fz_u8(&in);
    o.n_sim = b < 250 ? 1 + b : (int64_t)fz_u64(&in);
    if (o.n_sim > 256 && o.method != MCSTAT_METHOD_EXACT && o.method != MCSTAT_METHOD_ASYMPTOTIC)
        o.n_sim = 256; /* keep one input fast; large values only reach the argument check */
    o.seed = fz_u64(&in);
    o.critical = fz_bool(&in);
    if (flags & 2)
        o.size = (uint32_t)fz_range(&in, 0, 2 * sizeof o);
    size_t cache_bytes = (size_t)fz_range(&in, 0, 1 << 20);

    const mcstat_ks_options *opt = (flags & 1) ? NULL : &o;
    if (fz_verbose()) {
        fz_print_doubles("x", x, nx);
        fz_print_doubles("y", y, ny);
        fprintf(stderr, "alt %d alpha %a opt %s weight %d method %d threads %d n_sim %lld seed %llu critical %d size %u\n",
                alt, alpha, opt ? "set" : "NULL", o.weight, o.method, o.threads, (long long)o.n_sim,
                (unsigned long long)o.seed, o.critical, o.size);
    }

    mcstat_result r, keep;
    memset(&r, 0xa5, sizeof r);
    keep = r;
    int st = mcstat_ks_test_2(x, nx, y, ny, alt, alpha, opt, &r);
    fz_check_result(st, &r, MCSTAT_TEST_KS_2, alt, alpha, 0);
    if (st != MCSTAT_OK) {
        FZ_ASSERT(memcmp(&r, &keep, sizeof r) == 0, "status %d but *out written", st);
        return 0;
    }
    if (opt && o.method != MCSTAT_METHOD_AUTO)
        FZ_ASSERT(r.method == o.method, "method %d, asked %d", r.method, o.method);
    if (opt && !o.critical)
        FZ_ASSERT(isnan(r.critical[1]), "critical %.17g not asked for", r.critical[1]);
    if (!opt)
        return 0;

    /* The other thread count: bit-identical. */
    mcstat_ks_options o2 = o;
    o2.threads = o.threads == 1 ? 2 : 1;
    mcstat_result r2;
    st = mcstat_ks_test_2(x, nx, y, ny, alt, alpha, &o2, &r2);
    FZ_ASSERT(st == MCSTAT_OK, "threads %d: status %d", o2.threads, st);
    FZ_ASSERT(memcmp(&r, &r2, sizeof r) == 0, "threads %d and %d differ: p %.17g %.17g", o.threads, o2.threads,
              r.p_value, r2.p_value);

    /* Through a cache, twice: the same result both times. */
    if (flags & 4) {
        mcstat_ks_cache *cache = NULL;
        st = mcstat_ks_cache_new(cache_bytes, &cache);
        FZ_ASSERT(st == MCSTAT_OK || st == MCSTAT_ENOMEM, "cache_new: status %d", st);
        if (st == MCSTAT_OK) {
            o2 = o;
            o2.cache = cache;
            for (int k = 0; k < 2; k++) {
                st = mcstat_ks_test_2(x, nx, y, ny, alt, alpha, &o2, &r2);
                FZ_ASSERT(st == MCSTAT_OK, "cached call %d: status %d", k, st);
                FZ_ASSERT(memcmp(&r, &r2, sizeof r) == 0, "cached call %d differs: p %.17g %.17g", k, r.p_value,
                          r2.p_value);
            }
            uint64_t hits = 99, misses = 99, entries = 99;
            FZ_ASSERT(mcstat_ks_cache_stats(cache, &hits, &misses, &entries) == MCSTAT_OK, "cache_stats");
            FZ_ASSERT(hits <= 2 && misses <= 2 && entries <= 1, "cache stats %llu %llu %llu",
                      (unsigned long long)hits, (unsigned long long)misses, (unsigned long long)entries);
            FZ_ASSERT(mcstat_ks_cache_stats(cache, NULL, NULL, NULL) == MCSTAT_OK, "cache_stats NULLs");
            mcstat_ks_cache_free(cache);
        }
    }

    /* Exact: x and y swapped, the alternative mirrored, give the same statistic
     * and the same p-value (the permutation distribution does not care). */
    if (r.method == MCSTAT_METHOD_EXACT) {
        st = mcstat_ks_test_2(y, ny, x, nx, mirror(alt), alpha, &o, &r2);
        FZ_ASSERT(st == MCSTAT_OK, "swapped: status %d", st);
        FZ_ASSERT(r2.statistic == r.statistic, "swapped: statistic %.17g, was %.17g", r2.statistic, r.statistic);
        FZ_ASSERT(fabs(r2.p_value - r.p_value) <= 1e-10 * r.p_value + 1e-300, "swapped: p %.17g, was %.17g",
                  r2.p_value, r.p_value);
    }
    return 0;
}
