/*
 * ks_simulate.c - the null distribution of the K-S statistic by simulation.
 *
 * Under H0 with the tie pattern fixed only the order of the labels matters
 * (ERRATA 3), so a replicate is a random arrangement of nx x-labels and ny
 * y-labels over the N pooled positions: no reals are drawn or sorted.  The
 * arrangement is drawn sequentially, as the exact recursion reads it: the
 * label at position s is x with probability (x-labels left)/(N - s), decided
 * by one 32-bit random integer r as r (N - s) < left 2^32 (the probability is
 * then off by less than 2^-32, so a replicate's law is within N 2^-32 of the
 * exact one in total variation: 5e-7 at N = 2000).  The statistic is updated
 * on the fly at the end of each tie block: O(N) per replicate.
 *
 * Reproducibility: replicates come in fixed blocks of BLOCK, block b drawn by
 * its own generator seeded from (seed, b), and written to its own slots, so
 * the result is bit-identical for any number of threads.  Generator: GSL's
 * taus2 (a maximally equidistributed combined Tausworthe generator, 32-bit
 * output), the fastest of GSL's good generators here (bench/RESULTS_ks.md).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <gsl/gsl_rng.h>
#include <pthread.h>
#include <stdlib.h>

#define BLOCK 256  /* replicates per generator */
#define CHUNK 4096 /* random numbers drawn ahead, per refill */

typedef struct {
    const mcstat__ks_data *d;
    int64_t n_sim;
    uint64_t seed;
    int rng;          /* MCSTAT__KS_RNG_* */
    double *keys;
    const double *w;  /* 1/(s (N - s)) at tie-block ends with 0 < s < N, else 0 (Canner) */
    const int64_t *mask; /* -1 at block ends with 0 < s < N, else 0 */
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

/* xoshiro256++ (Blackman & Vigna 2019): 64 good bits in ~1 ns, two draws. */
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

/* The random source of one block: GSL's taus2 or xoshiro256++. */
typedef struct {
    int kind;
    gsl_rng *gsl;
    xoshiro xo;
} source;

static void source_seed(source *src, uint64_t seed, int64_t block)
{
    uint64_t z = splitmix64(seed ^ splitmix64((uint64_t)block));
    if (src->kind == MCSTAT__KS_RNG_TAUS2) {
        gsl_rng_set(src->gsl, (unsigned long)(z & 0xffffffffu));
    } else {
        for (int k = 0; k < 4; k++)
            src->xo.s[k] = z = splitmix64(z);
    }
}

/* n 32-bit random integers. */
static void source_fill(source *src, uint32_t *r, size_t n)
{
    if (src->kind == MCSTAT__KS_RNG_TAUS2) {
        gsl_rng *g = src->gsl;
        for (size_t i = 0; i < n; i++)
            r[i] = (uint32_t)gsl_rng_get(g);
        return;
    }
    xoshiro x = src->xo;
    size_t i = 0;
    for (; i + 1 < n; i += 2) {
        uint64_t v = xoshiro_next(&x);
        r[i] = (uint32_t)(v >> 32);
        r[i + 1] = (uint32_t)v;
    }
    if (i < n)
        r[i] = (uint32_t)(xoshiro_next(&x) >> 32);
    src->xo = x;
}

/* One replicate's key.  buf holds CHUNK random numbers and CHUNK u's. */
static double replicate(const sim_job *job, source *src, uint32_t *rbuf, int64_t *ubuf)
{
    const mcstat__ks_data *d = job->d;
    const uint64_t N = d->N;
    const int64_t n1 = (int64_t)d->n1, NN = (int64_t)N;
    const int alt = d->alternative;
    const int canner = d->weight == MCSTAT_KS_WEIGHT_CANNER;
    uint64_t left = d->n1; /* x-labels not yet placed */
    int64_t u = 0;         /* i n2 - j n1 = i N - s n1 */
    int64_t umax = 0, umin = 0;
    double best = 0.0;
    int64_t best_u = 0;
    uint64_t best_s = 1;
    const double sg = alt == MCSTAT_LESS ? -1.0 : 1.0;
    /* points s = 1 .. N-1: the label at position s - 1 moves the path to s */
    for (uint64_t s0 = 1; s0 < N; s0 += CHUNK) {
        const uint64_t len = N - s0 < CHUNK ? N - s0 : CHUNK;
        source_fill(src, rbuf, (size_t)len);
        if (!canner) {
            const int64_t *mask = job->mask + s0;
            for (uint64_t k = 0; k < len; k++) {
                const uint64_t s = s0 + k - 1; /* labels placed before this one */
                const uint64_t isx = (uint64_t)rbuf[k] * (N - s) < (left << 32);
                left -= isx;
                u += (int64_t)isx * NN - n1;
                const int64_t v = u & mask[k];
                umax = v > umax ? v : umax;
                umin = v < umin ? v : umin;
            }
            continue;
        }
        const double *w = job->w + s0;
        double cbest = 0.0;
        for (uint64_t k = 0; k < len; k++) {
            const uint64_t s = s0 + k - 1;
            const uint64_t isx = (uint64_t)rbuf[k] * (N - s) < (left << 32);
            left -= isx;
            u += (int64_t)isx * NN - n1;
            ubuf[k] = u;
            const double du = sg * (double)u;
            const double key = (alt == MCSTAT_TWO_SIDED ? du * du : du * fabs(du)) * w[k];
            cbest = key > cbest ? key : cbest;
        }
        if (cbest > best) {
            /* find the winner and keep its (u, s): its key is recomputed exactly */
            for (uint64_t k = 0; k < len; k++) {
                const double du = sg * (double)ubuf[k];
                const double key = (alt == MCSTAT_TWO_SIDED ? du * du : du * fabs(du)) * w[k];
                if (key == cbest) {
                    best_u = ubuf[k];
                    best_s = s0 + k;
                    break;
                }
            }
            best = cbest;
        }
    }
    if (!canner) {
        if (alt == MCSTAT_GREATER)
            return (double)umax;
        if (alt == MCSTAT_LESS)
            return (double)-umin;
        return (double)(umax > -umin ? umax : -umin);
    }
    if (best == 0.0)
        return 0.0;
    uint64_t au = (uint64_t)(best_u < 0 ? -best_u : best_u);
    return mcstat__ks_key(d->weight, au, best_s * (N - best_s));
}

static void *worker(void *arg)
{
    sim_job *job = arg;
    source src = {job->rng, NULL, {{0, 0, 0, 0}}};
    uint32_t *rbuf = malloc(CHUNK * (sizeof *rbuf + sizeof(int64_t)));
    if (job->rng == MCSTAT__KS_RNG_TAUS2)
        src.gsl = gsl_rng_alloc(gsl_rng_taus2);
    if (!rbuf || (job->rng == MCSTAT__KS_RNG_TAUS2 && !src.gsl)) {
        pthread_mutex_lock(&job->lock);
        job->status = MCSTAT_ENOMEM;
        pthread_mutex_unlock(&job->lock);
        free(rbuf);
        if (src.gsl)
            gsl_rng_free(src.gsl);
        return NULL;
    }
    int64_t *ubuf = (int64_t *)(rbuf + CHUNK);
    for (;;) {
        pthread_mutex_lock(&job->lock);
        int64_t b = job->status ? job->n_blocks : job->next_block++;
        pthread_mutex_unlock(&job->lock);
        if (b >= job->n_blocks)
            break;
        source_seed(&src, job->seed, b);
        int64_t first = b * BLOCK, last = first + BLOCK < job->n_sim ? first + BLOCK : job->n_sim;
        for (int64_t k = first; k < last; k++)
            job->keys[k] = replicate(job, &src, rbuf, ubuf);
    }
    free(rbuf);
    if (src.gsl)
        gsl_rng_free(src.gsl);
    return NULL;
}

int mcstat__ks_simulate_rng(const mcstat__ks_data *d, int64_t n_sim, uint64_t seed, int threads, int rng,
                             double *keys)
{
    const uint64_t N = d->N;
    if (N > UINT32_MAX) /* the 32-bit label draw needs N - s < 2^32 */
        return MCSTAT_ETOOBIG;
    sim_job job;
    job.d = d;
    job.n_sim = n_sim;
    job.seed = seed;
    job.rng = rng;
    job.keys = keys;
    job.next_block = 0;
    job.n_blocks = (n_sim + BLOCK - 1) / BLOCK;
    job.status = MCSTAT_OK;
    /* w and mask are indexed by the point s; the statistic is looked at only
     * at the end of a tie block (all points when there are no ties) */
    double *w = malloc((N + 1) * (sizeof *w + sizeof(int64_t)));
    if (!w)
        return MCSTAT_ENOMEM;
    int64_t *mask = (int64_t *)(w + N + 1);
    for (uint64_t s = 0; s <= N; s++) {
        mask[s] = (s > 0 && s < N && !d->ends) ? -1 : 0;
        w[s] = 0.0;
    }
    for (size_t k = 0; d->ends && k < d->nblocks; k++)
        if (d->ends[k] < N)
            mask[d->ends[k]] = -1;
    for (uint64_t s = 1; s < N; s++)
        if (mask[s])
            w[s] = 1.0 / ((double)s * (double)(N - s));
    job.w = w;
    job.mask = mask;
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
    if (job.status)
        return job.status;

    /* sort the keys (non-negative doubles: their order keys sort alike) */
    uint64_t *k = malloc(2 * (size_t)n_sim * sizeof *k);
    if (!k)
        return MCSTAT_ENOMEM;
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
