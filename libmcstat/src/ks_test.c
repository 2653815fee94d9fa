/*
 * ks_test.c - the two-sample Kolmogorov-Smirnov test (section 2.5, ERRATA
 * 1-3, 7): arguments, the statistic, and which method computes the p-value.
 *
 * The statistic is computed on integers: after s = i + j pooled values the
 * lattice point is u = i*ny - j*nx = (F - G) nx ny and q = s (N - s) =
 * z (1 - z) N^2, so D = |u| / (nx ny) and D2 = sqrt(N u^2 / (nx ny q)).
 * Which point is the supremum is decided exactly on (u, q); R's cumulative
 * sums of 1/nx - 1/ny leave rounding noise instead (its D^- of identical
 * samples can print as -3.5e-17).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <pthread.h>
#include <stdlib.h>

#define PARALLEL_SORT_MIN 65536 /* below this a second thread costs more than it saves */

/* Every size mcstat_ks_options has had, oldest first (options.c). */
static const uint32_t KS_SIZES[] = {MCSTAT_KS_OPTIONS_SIZE_0_1};
_Static_assert(sizeof(mcstat_ks_options) == MCSTAT_KS_OPTIONS_SIZE_0_1,
               "a grown mcstat_ks_options needs its size appended to KS_SIZES");

int mcstat_ks_options_init_size(mcstat_ks_options *opt, size_t size)
{
    const mcstat_ks_options d = MCSTAT_KS_OPTIONS_INIT;
    return mcstat__options_init(opt, size, &d, sizeof d, KS_SIZES, sizeof KS_SIZES / sizeof *KS_SIZES);
}

/* 0.1.0's entry point: its callers' structs are 0.1.0's size (the name is
 * parenthesised against the header's macro). */
int(mcstat_ks_options_init)(mcstat_ks_options *opt)
{
    return mcstat_ks_options_init_size(opt, MCSTAT_KS_OPTIONS_SIZE_0_1);
}


double mcstat__ks_key_statistic(const mcstat__ks_data *d, double key)
{
    double n12 = (double)d->n1 * (double)d->n2;
    if (d->weight == MCSTAT_KS_WEIGHT_NONE)
        return key / n12;
    return sqrt(key * (double)d->N / n12);
}

static int bits(uint64_t v)
{
    return v ? 64 - __builtin_clzll(v) : 0;
}

/* u^2 q exactly, as hi * 2^64 + lo (below 2^192 for any 64-bit u and q) */
static void square_times(uint64_t u, uint64_t q, unsigned __int128 *hi, uint64_t *lo)
{
    unsigned __int128 s = (unsigned __int128)u * u;
    unsigned __int128 p0 = (unsigned __int128)(uint64_t)s * q, p1 = (s >> 64) * q;
    *lo = (uint64_t)p0;
    *hi = p1 + (p0 >> 64);
}

int mcstat__ks_point_cmp(int weight, mcstat__ks_point a, mcstat__ks_point b)
{
    if (weight == MCSTAT_KS_WEIGHT_NONE)
        return (a.u > b.u) - (a.u < b.u);
    /* a.u^2 / a.q against b.u^2 / b.q: cross-multiplied */
    if (2 * bits(a.u) + bits(b.q) <= 128 && 2 * bits(b.u) + bits(a.q) <= 128) {
        unsigned __int128 l = (unsigned __int128)a.u * a.u;
        unsigned __int128 r = (unsigned __int128)b.u * b.u;
        unsigned __int128 lq = l * b.q, rq = r * a.q;
        return (lq > rq) - (lq < rq);
    }
    unsigned __int128 lh, rh;
    uint64_t ll, rl;
    square_times(a.u, b.q, &lh, &ll);
    square_times(b.u, a.q, &rh, &rl);
    if (lh != rh)
        return lh > rh ? 1 : -1;
    return (ll > rl) - (ll < rl);
}

typedef struct {
    const double *x;
    size_t n;
    uint64_t *keys, *tmp;
    int status;
} sort_job;

static void *sort_run(void *arg)
{
    sort_job *j = arg;
    j->status = mcstat__sort_double_keys(j->x, j->n, j->keys, j->tmp);
    return NULL;
}

/* NaN check and order keys of both samples, sorted (two threads when big),
 * each followed by the sentinel UINT64_MAX (above every key: NaN has none). */
static int sorted_keys(const double *x, size_t nx, const double *y, size_t ny, int threads, uint64_t *kx,
                       uint64_t *ky, uint64_t *tmp)
{
    sort_job jx = {x, nx, kx, tmp, 0}, jy = {y, ny, ky, tmp + nx, 0};
    pthread_t th;
    if (threads > 1 && nx + ny >= PARALLEL_SORT_MIN && pthread_create(&th, NULL, sort_run, &jy) == 0) {
        sort_run(&jx);
        pthread_join(th, NULL);
    } else {
        sort_run(&jx);
        sort_run(&jy);
    }
    kx[nx] = ky[ny] = UINT64_MAX;
    return jx.status ? jx.status : jy.status;
}

/* Weight NONE: the pass over the merged samples without a branch on the
 * data (the merge's x-or-y choice is a coin flip that mispredicts half the
 * time: 9 ms of 1e6 + 1e6, 3.6 ms without; bench/RESULTS_ks.md).  Each step
 * takes the next value (x's on equal keys), and the point counts only when
 * the following value differs (the end of a tie block).  Keeps the first
 * points of the largest and smallest u, which decide the sign of a
 * two-sided supremum as the general scan does.  Big inputs are scanned in
 * two halves on two threads, split where the merge has taken N/2 values. */
typedef struct {
    const uint64_t *kx, *ky;
    int64_t a, b;           /* n2, n1 */
    uint64_t s0, s1;        /* points s0 + 1 .. s1 */
    size_t ix, iy;          /* values taken before */
    int64_t umax, umin;     /* results: extremes of u at block ends (with 0) */
    uint64_t smax, smin, nb;/* their first points; block ends seen */
} none_part;

static void *scan_none_part(void *arg)
{
    none_part *p = arg;
    const uint64_t *kx = p->kx, *ky = p->ky;
    const int64_t a = p->a, b = p->b;
    size_t ix = p->ix, iy = p->iy;
    int64_t u = (int64_t)ix * a - (int64_t)iy * b, umax = 0, umin = 0;
    uint64_t smax = 0, smin = 0, nb = 0;
    uint64_t vx = kx[ix], vy = ky[iy];
    for (uint64_t s = p->s0 + 1; s <= p->s1; s++) {
        const int tx = vx <= vy;
        const uint64_t v = tx ? vx : vy;
        ix += (size_t)tx;
        iy += (size_t)(1 - tx);
        u += tx ? a : -b;
        vx = kx[ix];
        vy = ky[iy];
        const int end = (vx < vy ? vx : vy) != v;
        nb += (uint64_t)end;
        const int64_t m = end ? u : 0;
        smax = m > umax ? s : smax;
        umax = m > umax ? m : umax;
        smin = m < umin ? s : smin;
        umin = m < umin ? m : umin;
    }
    p->umax = umax;
    p->umin = umin;
    p->smax = smax;
    p->smin = smin;
    p->nb = nb;
    return NULL;
}

static int scan_none(const uint64_t *kx, const uint64_t *ky, int threads, mcstat__ks_data *d, uint64_t **ends_out)
{
    const uint64_t N = d->N, n1 = d->n1, n2 = d->n2;
    none_part part[2] = {{kx, ky, (int64_t)n2, (int64_t)n1, 0, N, 0, 0, 0, 0, 0, 0, 0}};
    int two = threads > 1 && N >= PARALLEL_SORT_MIN;
    pthread_t th;
    if (two) {
        /* the merge path at S: ix = #x among the S first values, x[m] among
         * them iff kx[m] <= ky[S - m - 1] (x first on ties) */
        const uint64_t S = N / 2;
        uint64_t lo = S > n2 ? S - n2 : 0, hi = S < n1 ? S : n1;
        while (lo < hi) {
            uint64_t mid = lo + (hi - lo) / 2;
            if (kx[mid] <= ky[S - mid - 1])
                lo = mid + 1;
            else
                hi = mid;
        }
        part[1] = part[0];
        part[0].s1 = part[1].s0 = S;
        part[1].ix = (size_t)lo;
        part[1].iy = (size_t)(S - lo);
        two = pthread_create(&th, NULL, scan_none_part, &part[1]) == 0;
        if (!two)
            part[0].s1 = N;
    }
    scan_none_part(&part[0]);
    if (two) {
        pthread_join(th, NULL);
        none_part *q = &part[1];
        if (q->umax > part[0].umax) { /* on equal values the first half's point comes first */
            part[0].umax = q->umax;
            part[0].smax = q->smax;
        }
        if (q->umin < part[0].umin) {
            part[0].umin = q->umin;
            part[0].smin = q->smin;
        }
        part[0].nb += q->nb;
    }
    const int64_t umax = part[0].umax, umin = part[0].umin;
    const uint64_t smax = part[0].smax, smin = part[0].smin;
    size_t nb = (size_t)part[0].nb, ix, iy;
    uint64_t vx, vy;
    uint64_t *ends = NULL;
    if (nb < N) { /* ties: the ends of the blocks, for the exact and simulated methods */
        ends = malloc(nb * sizeof *ends);
        if (!ends)
            return MCSTAT_ENOMEM;
        size_t j = 0;
        ix = iy = 0;
        vx = kx[0];
        vy = ky[0];
        for (uint64_t s = 1; s <= N; s++) {
            const int tx = vx <= vy;
            const uint64_t v = tx ? vx : vy;
            ix += (size_t)tx;
            iy += (size_t)(1 - tx);
            vx = kx[ix];
            vy = ky[iy];
            ends[j] = s; /* j < nb until the last end */
            j += (vx < vy ? vx : vy) != v;
        }
    }
    int64_t best;
    int sign;
    if (d->alternative == MCSTAT_GREATER) {
        best = umax;
        sign = umax > 0;
    } else if (d->alternative == MCSTAT_LESS) {
        best = -umin;
        sign = -(umin < 0);
    } else if (umax != -umin) {
        best = umax > -umin ? umax : -umin;
        sign = umax > -umin ? 1 : -1;
    } else {
        best = umax;
        sign = umax == 0 ? 0 : smax < smin ? 1 : -1;
    }
    d->nblocks = nb;
    d->ends = ends;
    *ends_out = ends;
    d->obs.u = (uint64_t)best;
    d->obs.q = 1;
    d->key = (double)best;
    d->sign = sign;
    return MCSTAT_OK;
}

/* One pass over the two sorted samples: the tie blocks and the supremum. */
static int scan(const uint64_t *kx, const uint64_t *ky, mcstat__ks_data *d, uint64_t **ends_out)
{
    const uint64_t n1 = d->n1, n2 = d->n2, N = d->N;
    const int canner = d->weight == MCSTAT_KS_WEIGHT_CANNER;
    size_t ix = 0, iy = 0, nb = 0;
    mcstat__ks_point best = {0, 1};
    double best_key = 0.0;
    int best_sign = 0;
    uint64_t *ends = NULL;
    for (int pass = 0; pass < 2; pass++) {
        ix = iy = nb = 0;
        while (ix < n1 || iy < n2) {
            uint64_t v = ix < n1 ? kx[ix] : UINT64_MAX;
            if (iy < n2 && ky[iy] < v)
                v = ky[iy];
            while (ix < n1 && kx[ix] == v)
                ix++;
            while (iy < n2 && ky[iy] == v)
                iy++;
            uint64_t s = ix + iy;
            if (pass == 1) {
                ends[nb++] = s;
                continue;
            }
            nb++;
            if (s == N)
                break;
            int64_t u = (int64_t)ix * (int64_t)n2 - (int64_t)iy * (int64_t)n1;
            int sg = u > 0 ? 1 : u < 0 ? -1 : 0;
            if (d->alternative == MCSTAT_GREATER && sg < 0)
                continue;
            if (d->alternative == MCSTAT_LESS && sg > 0)
                continue;
            mcstat__ks_point p = {(uint64_t)(u < 0 ? -u : u), canner ? s * (N - s) : 1};
            double key = mcstat__ks_key(d->weight, p.u, p.q);
            if (key < best_key)
                continue;
            if (key == best_key && mcstat__ks_point_cmp(d->weight, p, best) <= 0)
                continue;
            best = p;
            best_key = key;
            best_sign = sg;
        }
        if (pass == 0) {
            if (nb == N) /* no ties */
                break;
            ends = malloc(nb * sizeof *ends);
            if (!ends)
                return MCSTAT_ENOMEM;
        }
    }
    d->nblocks = nb;
    d->ends = ends;
    *ends_out = ends;
    d->obs = best;
    d->key = best_key;
    d->sign = best_sign;
    return MCSTAT_OK;
}

static int check_options(const mcstat_ks_options *o)
{
    if (o->weight != MCSTAT_KS_WEIGHT_NONE && o->weight != MCSTAT_KS_WEIGHT_CANNER)
        return 0;
    if (o->method != MCSTAT_METHOD_AUTO && o->method != MCSTAT_METHOD_EXACT &&
        o->method != MCSTAT_METHOD_SIMULATE && o->method != MCSTAT_METHOD_ASYMPTOTIC)
        return 0;
    if (o->method == MCSTAT_METHOD_ASYMPTOTIC && o->weight == MCSTAT_KS_WEIGHT_CANNER)
        return 0;
    if (o->threads < 1 || o->threads > 64 || o->n_sim < 1 || (o->critical != 0 && o->critical != 1))
        return 0;
    return 1;
}

static double exact_work(uint64_t n1, uint64_t n2)
{
    double m = (double)(n1 < n2 ? n1 : n2);
    return (m + 1.0) * ((double)n1 + (double)n2 + 1.0);
}

static int finish_simulated(const mcstat__ks_data *d, const double *keys, int64_t n_sim, int critical,
                            mcstat_result *r)
{
    /* #{key* >= key}: keys are sorted ascending; binary search for the first >= */
    size_t lo = 0, hi = (size_t)n_sim;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (keys[mid] < d->key)
            lo = mid + 1;
        else
            hi = mid;
    }
    double B = (double)n_sim, ge = (double)((size_t)n_sim - lo);
    double p = (1.0 + ge) / (B + 1.0);
    r->p_value = p;
    r->p_value_se = sqrt(p * (1.0 - p) / B);
    r->ks_n_sim = B;
    if (!critical)
        return MCSTAT_OK;
    /* p <= alpha  <=>  #{key* >= key} <= m = floor(alpha (B + 1) - 1)  <=>  key > the
     * (B - m)-th smallest simulated key: that order statistic is critical[1]. */
    double mf = floor(r->alpha * (B + 1.0) - 1.0);
    if (mf < 0.0) { /* even the largest statistic gives p = 1/(B+1) > alpha */
        r->critical[1] = INFINITY;
        r->ks_critical_se = NAN;
        return MCSTAT_OK;
    }
    size_t k = (size_t)n_sim - 1 - (size_t)mf; /* 0-based index of the (B-m)-th smallest */
    r->critical[1] = mcstat__ks_key_statistic(d, keys[k]);
    /* Its Monte Carlo error: the order statistics one binomial standard
     * deviation, sqrt(B a (1-a)), either side bracket it with ~68% confidence. */
    double a = 1.0 - ((double)k + 1.0) / B;
    size_t delta = (size_t)ceil(sqrt(B * a * (1.0 - a)));
    size_t klo = k > delta ? k - delta : 0, khi = k + delta < (size_t)n_sim ? k + delta : (size_t)n_sim - 1;
    r->ks_critical_se =
        0.5 * (mcstat__ks_key_statistic(d, keys[khi]) - mcstat__ks_key_statistic(d, keys[klo]));
    return MCSTAT_OK;
}

static int run_simulation(const mcstat__ks_data *d, const mcstat_ks_options *o, mcstat_result *r)
{
    if ((uint64_t)o->n_sim > SIZE_MAX / sizeof(double) / 2)
        return MCSTAT_ETOOBIG;
    double *keys = malloc((size_t)o->n_sim * sizeof *keys);
    if (!keys)
        return MCSTAT_ENOMEM;
    int st = MCSTAT_OK;
    int hit = o->cache && mcstat__ks_cache_get(o->cache, d, o->n_sim, o->seed, keys) == MCSTAT_OK;
    if (!hit) {
        st = mcstat__ks_simulate(d, o->n_sim, o->seed, o->threads, keys);
        if (!st && o->cache)
            mcstat__ks_cache_put(o->cache, d, o->n_sim, o->seed, keys); /* ENOMEM there only costs a re-run */
    }
    if (!st)
        st = finish_simulated(d, keys, o->n_sim, o->critical, r);
    free(keys);
    return st;
}

int mcstat_ks_test_2(const double *x, size_t nx, const double *y, size_t ny, int alternative, double alpha,
                     const mcstat_ks_options *opt, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
    if (opt && mcstat__options_read(&o, sizeof o, opt, KS_SIZES, sizeof KS_SIZES / sizeof *KS_SIZES))
        return MCSTAT_EINVAL;
    if (!x || !y || !out || !valid_alternative(alternative) || !valid_alpha(alpha) || !check_options(&o))
        return MCSTAT_EINVAL;
    if (nx == 0 || ny == 0)
        return MCSTAT_ETOOFEW;
    /* u = i ny - j nx must fit in an int64, and 2 N keys in memory */
    if ((uint64_t)nx > ((UINT64_C(1) << 62) - 1) / (uint64_t)ny || nx > SIZE_MAX / 32 || ny > SIZE_MAX / 32)
        return MCSTAT_ETOOBIG;

    int method = o.method;
    double work = exact_work(nx, ny);
    if (method == MCSTAT_METHOD_AUTO)
        method = work <= MCSTAT_KS_AUTO_EXACT_WORK ? MCSTAT_METHOD_EXACT : MCSTAT_METHOD_SIMULATE;
    if (method == MCSTAT_METHOD_EXACT && work > MCSTAT_KS_EXACT_MAX_WORK)
        return MCSTAT_ETOOBIG;

    mcstat__ks_data d = {0};
    d.n1 = nx;
    d.n2 = ny;
    d.N = (uint64_t)nx + ny;
    d.weight = o.weight;
    d.alternative = mcstat__ks_cdf_alternative(alternative); /* the CDF sense, as R */

    uint64_t *kx = malloc((2 * (nx + ny) + 2) * sizeof *kx), *ends = NULL;
    if (!kx)
        return MCSTAT_ENOMEM;
    int st = sorted_keys(x, nx, y, ny, o.threads, kx, kx + nx + 1, kx + nx + ny + 2);
    if (!st)
        st = d.weight == MCSTAT_KS_WEIGHT_NONE ? scan_none(kx, kx + nx + 1, o.threads, &d, &ends)
                                               : scan(kx, kx + nx + 1, &d, &ends);
    free(kx);
    if (st)
        return st;

    /* auto: the unweighted test goes to Kolmogorov's limit when the data have
     * no ties; with ties that limit is conservative, so it simulates. */
    if (o.method == MCSTAT_METHOD_AUTO && method == MCSTAT_METHOD_SIMULATE &&
        d.weight == MCSTAT_KS_WEIGHT_NONE && d.nblocks == d.N)
        method = MCSTAT_METHOD_ASYMPTOTIC;

    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = MCSTAT_TEST_KS_2;
    r.method = method;
    r.alternative = alternative;
    r.alpha = alpha;
    r.n[0] = nx;
    r.n[1] = ny;
    r.statistic = mcstat__ks_key_statistic(&d, d.key);
    r.critical[0] = -INFINITY;
    r.ks_weight = d.weight;
    r.ks_critical_se = 0.0;
    r.ks_n_sim = 0.0;
    r.p_value_se = 0.0;

    if (d.obs.u == 0 && method != MCSTAT_METHOD_ASYMPTOTIC) {
        r.p_value = 1.0; /* every arrangement has a statistic >= 0 */
    }
    switch (method) {
    case MCSTAT_METHOD_EXACT:
        if ((st = mcstat__ks_exact_check(&d)))
            break;
        if (d.obs.u > 0)
            st = mcstat__ks_exact_sf(&d, d.obs, &r.p_value);
        if (!st && o.critical) {
            double ck;
            if (!(st = mcstat__ks_exact_critical(&d, alpha, &ck)))
                r.critical[1] = mcstat__ks_key_statistic(&d, ck);
        }
        break;
    case MCSTAT_METHOD_SIMULATE:
        st = run_simulation(&d, &o, &r);
        break;
    default: /* asymptotic, unweighted */
        r.p_value = mcstat__ks_asymp_sf(nx, ny, alternative == MCSTAT_TWO_SIDED, r.statistic);
        if (o.critical)
            r.critical[1] = mcstat__ks_asymp_critical(nx, ny, alternative == MCSTAT_TWO_SIDED, alpha);
        break;
    }
    free(ends);
    if (st)
        return st;
    r.reject = r.p_value <= alpha;
    /* the first sample is "less" where its CDF lies above (d.sign = +1) */
    int sign = alternative == MCSTAT_GREATER ? 1 : alternative == MCSTAT_LESS ? -1 : -d.sign;
    r.decision = r.reject ? sign : 0;
    *out = r;
    return MCSTAT_OK;
}
