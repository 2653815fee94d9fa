/*
 * ks_simulate.c - the null distribution of the K-S statistic by simulation.
 *
 * Under H0 with the tie pattern fixed only the order of the labels matters
 * (ERRATA 3), so a replicate is a random arrangement of nx x-labels and ny
 * y-labels over the N pooled positions: no reals are drawn or sorted.  The
 * arrangement is drawn sequentially, as the exact recursion reads it: with
 * s - 1 labels placed and `left` x-labels still to place, the label moving
 * the path to point s is x with probability left/(N - s + 1), decided by one
 * 32-bit random integer r as hi32(r (N - s + 1)) < left (Lemire's
 * multiply-shift bounded integer, without rejection: the probability is off
 * by less than 2^-32, so a replicate's law is within N 2^-32 of the exact
 * one in total variation: 5e-7 at N = 2000).  The statistic is updated on
 * the fly at the end of each tie block: O(N) per replicate, N - 1 random
 * 32-bit integers, no division.
 *
 * Reproducibility: replicate k's generator is seeded from (seed, k) alone,
 * so its key is a pure function of (data, seed, k), whatever the number of
 * threads and whichever kernel computes it.  Threads take fixed blocks of
 * BLOCK replicates and write their own slots.
 *
 * Kernels: a scalar one (any size, any machine) and, on x86-64 with AVX2
 * (checked at run time) when nx ny < 2^31, one that runs 8 replicates in
 * the 32-bit lanes of AVX2 registers, 8 xoshiro256++ streams alongside.
 * Both compute the same integers and the same IEEE products in the same
 * order, so their keys are bit-identical (tests/c/test_ks.c checks it).
 * Generator: xoshiro256++ (Blackman & Vigna 2019), state seeded by
 * splitmix64; its 64-bit outputs serve two labels each, low half first.
 * GSL's taus2 (scalar) is compiled only into the benchmark's own copy of
 * this file (bench/CMakeLists.txt defines MCSTAT_KS_BENCH_TAUS2), for its
 * comparison of generators; the library has no use for it.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <pthread.h>
#ifdef MCSTAT_KS_BENCH_TAUS2
#include <gsl/gsl_rng.h>
#endif
#include <stdlib.h>

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define MCSTAT_KS_AVX2 1
#include <immintrin.h>
#else
#define MCSTAT_KS_AVX2 0
#endif

#define BLOCK 256 /* replicates per unit of work handed to a thread */
#define LANES 8   /* replicates per AVX2 group */

typedef struct {
    const mcstat__ks_data *d;
    int64_t n_sim;
    uint64_t seed;
    int rng;             /* MCSTAT__KS_RNG_* */
    int simd;            /* the AVX2 kernel applies */
    double *keys;
    const double *w;     /* Canner: sg/(s (N - s)) at tie-block ends with 0 < s < N, else 0, where
                            sg = -1 for LESS (the claimed deviation is -u), else +1 */
    const int64_t *mask; /* -1 at block ends with 0 < s < N, else 0 */
    const int32_t *mask32;
    pthread_mutex_t lock;
    int64_t next_block, n_blocks;
    int status;
} sim_job;

static uint64_t splitmix64(uint64_t z)
{
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

typedef struct {
    uint64_t s[4];
} xoshiro;

static inline uint64_t rotl(uint64_t x, int k)
{
    return (x << k) | (x >> (64 - k));
}

static inline uint64_t xoshiro_next(xoshiro *x)
{
    uint64_t *s = x->s;
    const uint64_t r = rotl(s[0] + s[3], 23) + s[0], t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return r;
}

/* Replicate k's state: 256 bits from splitmix64 started at a hash of (seed, k). */
static void seed_replicate(xoshiro *x, uint64_t seed, int64_t k)
{
    uint64_t z = splitmix64(seed ^ splitmix64((uint64_t)k));
    for (int j = 0; j < 4; j++)
        x->s[j] = z = splitmix64(z);
}

/* The key of a replicate from its extremes (NONE) or its best point (Canner). */
static double finish_none(const mcstat__ks_data *d, int64_t umax, int64_t umin)
{
    if (d->alternative == MCSTAT_GREATER)
        return (double)umax;
    if (d->alternative == MCSTAT_LESS)
        return (double)-umin;
    return (double)(umax > -umin ? umax : -umin);
}

static double finish_canner(const mcstat__ks_data *d, double best, int64_t best_u, uint64_t best_s)
{
    if (best == 0.0)
        return 0.0;
    uint64_t au = (uint64_t)(best_u < 0 ? -best_u : best_u);
    return mcstat__ks_key(d->weight, au, best_s * (d->N - best_s));
}

/* ---- the scalar kernel --------------------------------------------------------- */

/* 64 random bits: xoshiro256++, or (benchmark build) two outputs of GSL's
 * taus2. */
typedef struct {
#ifdef MCSTAT_KS_BENCH_TAUS2
    int taus2;
    gsl_rng *gsl;
#endif
    xoshiro xo;
} source;

static inline uint64_t source_next(source *src)
{
#ifdef MCSTAT_KS_BENCH_TAUS2
    if (src->taus2) {
        uint64_t a = (uint64_t)gsl_rng_get(src->gsl);
        return a | (uint64_t)gsl_rng_get(src->gsl) << 32;
    }
#endif
    return xoshiro_next(&src->xo);
}

static double replicate_scalar(const sim_job *job, source *src)
{
    const mcstat__ks_data *d = job->d;
    const uint64_t N = d->N;
    const int64_t n1 = (int64_t)d->n1, NN = (int64_t)N;
    uint64_t left = d->n1; /* x-labels not yet placed */
    int64_t u = 0;         /* i n2 - j n1 = i N - s n1 */
    uint64_t v = 0;
    if (d->weight == MCSTAT_KS_WEIGHT_NONE) {
        const int64_t *mask = job->mask;
        int64_t umax = 0, umin = 0;
        for (uint64_t s = 1; s < N; s++) {
            v = (s & 1) ? source_next(src) : v >> 32;
            const uint64_t isx = (((v & 0xffffffffu) * (N - s + 1)) >> 32) < left;
            left -= isx;
            u += (int64_t)isx * NN - n1;
            const int64_t m = u & mask[s];
            umax = m > umax ? m : umax;
            umin = m < umin ? m : umin;
        }
        return finish_none(d, umax, umin);
    }
    const double *w = job->w;
    const int two = d->alternative == MCSTAT_TWO_SIDED;
    double best = 0.0;
    int64_t best_u = 0;
    uint64_t best_s = 1;
    for (uint64_t s = 1; s < N; s++) {
        v = (s & 1) ? source_next(src) : v >> 32;
        const uint64_t isx = (((v & 0xffffffffu) * (N - s + 1)) >> 32) < left;
        left -= isx;
        u += (int64_t)isx * NN - n1;
        /* (sg u) |sg u| w = (u |u|)(sg w) exactly: a sign change is exact */
        const double du = (double)u;
        const double key = (two ? du * du : du * fabs(du)) * w[s];
        if (key > best) {
            best = key;
            best_u = u;
            best_s = s;
        }
    }
    return finish_canner(d, best, best_u, best_s);
}

/* ---- the AVX2 kernel: 8 replicates in lockstep ---------------------------------- */
#if MCSTAT_KS_AVX2

#define AVX2 __attribute__((target("avx2")))

static AVX2 inline __m256i rotl4(__m256i x, int k)
{
    return _mm256_or_si256(_mm256_slli_epi64(x, k), _mm256_srli_epi64(x, 64 - k));
}

/* xoshiro256++ on four streams at once; returns their outputs. */
#define XO_STEP(s0, s1, s2, s3, out)                                                    \
    do {                                                                                \
        out = _mm256_add_epi64(rotl4(_mm256_add_epi64(s0, s3), 23), s0);                \
        const __m256i t_ = _mm256_slli_epi64(s1, 17);                                   \
        s2 = _mm256_xor_si256(s2, s0);                                                  \
        s3 = _mm256_xor_si256(s3, s1);                                                  \
        s1 = _mm256_xor_si256(s1, s2);                                                  \
        s0 = _mm256_xor_si256(s0, s3);                                                  \
        s2 = _mm256_xor_si256(s2, t_);                                                  \
        s3 = rotl4(s3, 45);                                                             \
    } while (0)

/* hi32(r * rem) < left, lane by lane, for eight 32-bit lanes (r unsigned). */
#define LABEL_STEP(r, remv, left, isx)                                                  \
    do {                                                                                \
        const __m256i ev_ = _mm256_mul_epu32(r, remv);                                  \
        const __m256i od_ = _mm256_mul_epu32(_mm256_srli_epi64(r, 32), remv);           \
        const __m256i hi_ = _mm256_blend_epi32(_mm256_srli_epi64(ev_, 32), od_, 0xAA); \
        isx = _mm256_cmpgt_epi32(left, hi_);                                            \
        left = _mm256_add_epi32(left, isx);                                             \
    } while (0)

/*
 * Lane layout: 32-bit lane 2i is replicate i, lane 2i + 1 is replicate 4 + i
 * (i < 4); streams A hold replicates 0-3, B replicates 4-7, one per 64-bit
 * lane.  At odd s a replicate uses the low half of its next output, at even
 * s the high half, as the scalar kernel does.
 */
static AVX2 void group_avx2(const sim_job *job, int64_t k0, double *out)
{
    const mcstat__ks_data *d = job->d;
    const int32_t N = (int32_t)d->N, n1 = (int32_t)d->n1;
    uint64_t st[4][LANES];
    for (int r = 0; r < LANES; r++) {
        xoshiro x;
        seed_replicate(&x, job->seed, k0 + r);
        for (int j = 0; j < 4; j++)
            st[j][r] = x.s[j];
    }
    __m256i a0 = _mm256_loadu_si256((const __m256i *)st[0]), a1 = _mm256_loadu_si256((const __m256i *)st[1]);
    __m256i a2 = _mm256_loadu_si256((const __m256i *)st[2]), a3 = _mm256_loadu_si256((const __m256i *)st[3]);
    __m256i b0 = _mm256_loadu_si256((const __m256i *)(st[0] + 4)), b1 = _mm256_loadu_si256((const __m256i *)(st[1] + 4));
    __m256i b2 = _mm256_loadu_si256((const __m256i *)(st[2] + 4)), b3 = _mm256_loadu_si256((const __m256i *)(st[3] + 4));
    __m256i left = _mm256_set1_epi32(n1), u = _mm256_setzero_si256();
    const __m256i n2v = _mm256_set1_epi32(N - n1), n1v = _mm256_set1_epi32(n1);
    __m256i ra = _mm256_setzero_si256(), rb = _mm256_setzero_si256(), isx;
    double res[LANES];

    if (d->weight == MCSTAT_KS_WEIGHT_NONE) {
        const int32_t *mask = job->mask32;
        __m256i umax = _mm256_setzero_si256(), umin = _mm256_setzero_si256();
        for (int32_t s = 1; s < N; s++) {
            __m256i r;
            if (s & 1) {
                XO_STEP(a0, a1, a2, a3, ra);
                XO_STEP(b0, b1, b2, b3, rb);
                r = _mm256_blend_epi32(ra, _mm256_slli_epi64(rb, 32), 0xAA);
            } else {
                r = _mm256_blend_epi32(_mm256_srli_epi64(ra, 32), rb, 0xAA);
            }
            LABEL_STEP(r, _mm256_set1_epi32(N - s + 1), left, isx);
            /* u += isx ? n2 : -n1 */
            u = _mm256_add_epi32(u, _mm256_sub_epi32(_mm256_and_si256(isx, _mm256_add_epi32(n2v, n1v)), n1v));
            const __m256i m = _mm256_and_si256(u, _mm256_set1_epi32(mask[s]));
            umax = _mm256_max_epi32(umax, m);
            umin = _mm256_min_epi32(umin, m);
        }
        int32_t mx[LANES], mn[LANES];
        _mm256_storeu_si256((__m256i *)mx, umax);
        _mm256_storeu_si256((__m256i *)mn, umin);
        for (int l = 0; l < LANES; l++)
            res[l] = finish_none(d, mx[l], mn[l]);
    } else {
        const double *w = job->w;
        const int two = d->alternative == MCSTAT_TWO_SIDED;
        const __m256d absmask = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
        __m256d best_lo = _mm256_setzero_pd(), best_hi = _mm256_setzero_pd();
        __m256d bs_lo = _mm256_set1_pd(1.0), bs_hi = _mm256_set1_pd(1.0), sv = _mm256_set1_pd(1.0);
        const __m256d one = _mm256_set1_pd(1.0);
        for (int32_t s = 1; s < N; s++, sv = _mm256_add_pd(sv, one)) { /* sv = s, exactly */
            __m256i r;
            if (s & 1) {
                XO_STEP(a0, a1, a2, a3, ra);
                XO_STEP(b0, b1, b2, b3, rb);
                r = _mm256_blend_epi32(ra, _mm256_slli_epi64(rb, 32), 0xAA);
            } else {
                r = _mm256_blend_epi32(_mm256_srli_epi64(ra, 32), rb, 0xAA);
            }
            LABEL_STEP(r, _mm256_set1_epi32(N - s + 1), left, isx);
            u = _mm256_add_epi32(u, _mm256_sub_epi32(_mm256_and_si256(isx, _mm256_add_epi32(n2v, n1v)), n1v));
            const __m256d wv = _mm256_set1_pd(w[s]);
            const __m256d dlo = _mm256_cvtepi32_pd(_mm256_castsi256_si128(u));
            const __m256d dhi = _mm256_cvtepi32_pd(_mm256_extracti128_si256(u, 1));
            /* (du * du or du * |du|) * w, the scalar kernel's products in its order */
            const __m256d klo = _mm256_mul_pd(_mm256_mul_pd(dlo, two ? dlo : _mm256_and_pd(dlo, absmask)), wv);
            const __m256d khi = _mm256_mul_pd(_mm256_mul_pd(dhi, two ? dhi : _mm256_and_pd(dhi, absmask)), wv);
            const __m256d glo = _mm256_cmp_pd(klo, best_lo, _CMP_GT_OQ), ghi = _mm256_cmp_pd(khi, best_hi, _CMP_GT_OQ);
            best_lo = _mm256_blendv_pd(best_lo, klo, glo);
            best_hi = _mm256_blendv_pd(best_hi, khi, ghi);
            bs_lo = _mm256_blendv_pd(bs_lo, sv, glo);
            bs_hi = _mm256_blendv_pd(bs_hi, sv, ghi);
        }
        double b[LANES], bs[LANES];
        _mm256_storeu_pd(b, best_lo);
        _mm256_storeu_pd(b + 4, best_hi);
        _mm256_storeu_pd(bs, bs_lo);
        _mm256_storeu_pd(bs + 4, bs_hi);
        for (int l = 0; l < LANES; l++) {
            /* |u| at the best point, from its key: best = u^2 w(s) to a few
             * ulps, so sqrt(best s (N - s)) is within 1e-6 of |u| < 2^31 and
             * rounds to it (cheaper than carrying u through every blend) */
            const uint64_t q = (uint64_t)bs[l] * (d->N - (uint64_t)bs[l]);
            res[l] = finish_canner(d, b[l], (int64_t)llround(sqrt(b[l] * (double)q)), (uint64_t)bs[l]);
        }
    }
    for (int i = 0; i < 4; i++) { /* lanes 2i, 2i+1 are replicates i, 4+i */
        out[i] = res[2 * i];
        out[4 + i] = res[2 * i + 1];
    }
}

static int have_avx2(void)
{
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2");
}
#endif

/* ---- threads ----------------------------------------------------------------------- */

static void *worker(void *arg)
{
    sim_job *job = arg;
#ifdef MCSTAT_KS_BENCH_TAUS2
    source src = {job->rng == MCSTAT__KS_RNG_TAUS2, NULL, {{0, 0, 0, 0}}};
    if (src.taus2 && !(src.gsl = gsl_rng_alloc(gsl_rng_taus2))) {
        pthread_mutex_lock(&job->lock);
        job->status = MCSTAT_ENOMEM;
        pthread_mutex_unlock(&job->lock);
        return NULL;
    }
#else
    source src = {{{0, 0, 0, 0}}};
#endif
    for (;;) {
        pthread_mutex_lock(&job->lock);
        int64_t b = job->status ? job->n_blocks : job->next_block++;
        pthread_mutex_unlock(&job->lock);
        if (b >= job->n_blocks)
            break;
        int64_t k = b * BLOCK, last = k + BLOCK < job->n_sim ? k + BLOCK : job->n_sim;
#if MCSTAT_KS_AVX2
        if (job->simd)
            for (; k + LANES <= last; k += LANES)
                group_avx2(job, k, job->keys + k);
#endif
        for (; k < last; k++) {
#ifdef MCSTAT_KS_BENCH_TAUS2
            if (src.taus2) {
                uint64_t z = splitmix64(job->seed ^ splitmix64((uint64_t)k));
                gsl_rng_set(src.gsl, (unsigned long)(z & 0xffffffffu));
                job->keys[k] = replicate_scalar(job, &src);
                continue;
            }
#endif
            seed_replicate(&src.xo, job->seed, k);
            job->keys[k] = replicate_scalar(job, &src);
        }
    }
#ifdef MCSTAT_KS_BENCH_TAUS2
    if (src.gsl)
        gsl_rng_free(src.gsl);
#endif
    return NULL;
}

int mcstat__ks_simulate_rng(const mcstat__ks_data *d, int64_t n_sim, uint64_t seed, int threads, int rng,
                             double *keys)
{
    const uint64_t N = d->N;
#ifndef MCSTAT_KS_BENCH_TAUS2
    if (rng == MCSTAT__KS_RNG_TAUS2) /* the benchmark's build only */
        return MCSTAT_EINVAL;
#endif
    if (N > UINT32_MAX) /* the 32-bit label draw needs N - s < 2^32 */
        return MCSTAT_ETOOBIG;
    if ((uint64_t)n_sim > SIZE_MAX / (2 * sizeof(uint64_t)))
        return MCSTAT_ETOOBIG;
    /* Everything is allocated before the simulation starts: a sort buffer
     * refused after minutes of simulating wastes them all. */
    uint64_t *k = malloc(2 * (size_t)n_sim * sizeof *k);
    if (!k)
        return MCSTAT_ENOMEM;
    sim_job job;
    job.d = d;
    job.n_sim = n_sim;
    job.seed = seed;
    job.rng = rng;
    job.keys = keys;
    job.next_block = 0;
    job.n_blocks = (n_sim + BLOCK - 1) / BLOCK;
    job.status = MCSTAT_OK;
    /* the AVX2 kernel keeps u = i n2 - j n1 and N in int32 lanes */
    job.simd = 0;
#if MCSTAT_KS_AVX2
    job.simd = rng == MCSTAT__KS_RNG_XOSHIRO && d->n1 * d->n2 < (UINT64_C(1) << 31) && N < (UINT64_C(1) << 31) &&
               have_avx2();
#endif
    /* w and mask are indexed by the point s; the statistic is looked at only
     * at the end of a tie block (all points when there are no ties) */
    double *w = malloc((N + 1) * (sizeof *w + sizeof(int64_t) + sizeof(int32_t)));
    if (!w) {
        free(k);
        return MCSTAT_ENOMEM;
    }
    int64_t *mask = (int64_t *)(w + N + 1);
    int32_t *mask32 = (int32_t *)(mask + N + 1);
    for (uint64_t s = 0; s <= N; s++) {
        mask[s] = (s > 0 && s < N && !d->ends) ? -1 : 0;
        w[s] = 0.0;
    }
    for (size_t k = 0; d->ends && k < d->nblocks; k++)
        if (d->ends[k] < N)
            mask[d->ends[k]] = -1;
    for (uint64_t s = 0; s <= N; s++) {
        mask32[s] = (int32_t)mask[s];
        if (mask[s])
            w[s] = (d->alternative == MCSTAT_LESS ? -1.0 : 1.0) / ((double)s * (double)(N - s));
    }
    job.w = w;
    job.mask = mask;
    job.mask32 = mask32;
    pthread_mutex_init(&job.lock, NULL);
    pthread_t th[64];
    int started = 0;
    if (threads > job.n_blocks)
        threads = (int)job.n_blocks;
    for (int t = 1; t < threads; t++) {
        if (pthread_create(&th[started], NULL, worker, &job) != 0)
            break; /* fewer threads: same result, later */
        started++;
    }
    worker(&job);
    for (int t = 0; t < started; t++)
        pthread_join(th[t], NULL);
    pthread_mutex_destroy(&job.lock);
    free(w);
    if (job.status) {
        free(k);
        return job.status;
    }

    /* sort the keys (non-negative doubles: their order keys sort alike) */
    for (int64_t i = 0; i < n_sim; i++)
        k[i] = mcstat__order_key(keys[i]);
    int st = mcstat__radix_sort_u64(k, (size_t)n_sim, k + n_sim);
    for (int64_t i = 0; i < n_sim; i++)
        keys[i] = mcstat__key_double(k[i]);
    free(k);
    return st;
}

int mcstat__ks_simulate(const mcstat__ks_data *d, int64_t n_sim, uint64_t seed, int threads, double *keys)
{
    return mcstat__ks_simulate_rng(d, n_sim, seed, threads, MCSTAT__KS_RNG_DEFAULT, keys);
}
