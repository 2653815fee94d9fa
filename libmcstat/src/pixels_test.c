/*
 * pixels_test.c - mcstat_pixels_test: one test per pixel of an image stack
 * (mcstat.h, section "Per-pixel tests"), its structs' sizes and initialisers, and the 0.2
 * seeds-major Welch calls on top of it.
 *
 * The arguments are checked here, once; the pixels are then split into
 * contiguous ranges, one per thread (threads.c), and each range goes to
 *   - Welch's test: the block kernel of pixels.c;
 *   - the variance tests: the block path of pixels_var.c (a per-call table
 *     of the tails, the df being the same for every pixel);
 *   - the other tests: each pixel's values gathered into a buffer and run
 *     through the single call's own code (the accumulator, the test on it,
 *     a quantile cache shared by the range, so that equal df solve their
 *     critical values once), bit for bit the _matrix call on that row.
 * Every pixel's work is a function of its own values only, so results do
 * not depend on the number of threads.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"
#include "options.h"

#include <stdlib.h>

static const uint32_t IN_SIZES[] = {MCSTAT_PIXELS_IN_SIZE_0_2};
static const uint32_t OPT_SIZES[] = {MCSTAT_PIXELS_OPTIONS_SIZE_0_2, MCSTAT_PIXELS_OPTIONS_SIZE_0_3};
static const uint32_t OUT_SIZES[] = {MCSTAT_PIXELS_OUT_SIZE_0_2};
_Static_assert(sizeof(mcstat_pixels_in) == MCSTAT_PIXELS_IN_SIZE_0_2,
               "a grown mcstat_pixels_in needs its size appended to IN_SIZES");
_Static_assert(sizeof(mcstat_pixels_options) == MCSTAT_PIXELS_OPTIONS_SIZE_0_3,
               "a grown mcstat_pixels_options needs its size appended to OPT_SIZES");
_Static_assert(sizeof(mcstat_pixels_out) == MCSTAT_PIXELS_OUT_SIZE_0_2,
               "a grown mcstat_pixels_out needs its size appended to OUT_SIZES");
#define N_OF(a) (sizeof(a) / sizeof *(a))

#define MAX_THREADS 64
/* Below this many pixels a thread costs more than it saves. */
#define MIN_PIXELS_PER_THREAD 4096
/* the threads take the pixels by chunks of a multiple of this many: the
 * block paths' blocks */
#define PIXEL_GRANULE 256

size_t mcstat_sizeof_pixels_in(void)
{
    return sizeof(mcstat_pixels_in);
}

size_t mcstat_sizeof_pixels_options(void)
{
    return sizeof(mcstat_pixels_options);
}

size_t mcstat_sizeof_pixels_out(void)
{
    return sizeof(mcstat_pixels_out);
}

int mcstat_pixels_in_init_size(mcstat_pixels_in *in, size_t size)
{
    const mcstat_pixels_in d = MCSTAT_PIXELS_IN_INIT;
    return mcstat__options_init(in, size, &d, sizeof d, IN_SIZES, N_OF(IN_SIZES));
}

int mcstat_pixels_options_init_size(mcstat_pixels_options *opt, size_t size)
{
    const mcstat_pixels_options d = MCSTAT_PIXELS_OPTIONS_INIT;
    return mcstat__options_init(opt, size, &d, sizeof d, OPT_SIZES, N_OF(OPT_SIZES));
}

int mcstat_pixels_out_init_size(mcstat_pixels_out *out, size_t size)
{
    const mcstat_pixels_out d = MCSTAT_PIXELS_OUT_INIT;
    return mcstat__options_init(out, size, &d, sizeof d, OUT_SIZES, N_OF(OUT_SIZES));
}

/* ---- arguments ----------------------------------------------------------- */

static int two_sample(int test)
{
    return test == MCSTAT_TEST_T_2 || test == MCSTAT_TEST_T_2_POOLED || test == MCSTAT_TEST_T_PAIRED ||
           test == MCSTAT_TEST_VAR_2;
}

/* One side's input: known type, channels and weights; every element of
 * pixels [0, end) addressable (when [begin, end) is not empty): (n-1) vs + (end-1) ps + channels - 1 fits. */
static int check_side(const mcstat_pixels_in *p, size_t begin, size_t end)
{
    if (p->type != MCSTAT_VALUE_FLOAT64 && p->type != MCSTAT_VALUE_FLOAT32)
        return MCSTAT_EINVAL;
    if (p->channels == 0 || (p->channels > 1 && !p->weights) || (end > begin && p->n > 0 && !p->data))
        return MCSTAT_EINVAL;
    if (p->weights)
        for (size_t c = 0; c < p->channels; c++)
            if (!isfinite(p->weights[c]))
                return MCSTAT_EINVAL;
    if (end == begin || p->n == 0)
        return MCSTAT_OK;
    size_t last = p->channels - 1, a, b;
    if (__builtin_mul_overflow(p->n - 1, p->value_stride, &a) ||
        __builtin_mul_overflow(end - 1, p->pixel_stride, &b) || __builtin_add_overflow(a, b, &a) ||
        __builtin_add_overflow(a, last, &a) || a > SIZE_MAX / 8)
        return MCSTAT_ETOOBIG;
    return MCSTAT_OK;
}

static int same_weighting(const mcstat_pixels_in *x, const mcstat_pixels_in *y)
{
    if (x->type != y->type || x->channels != y->channels || !x->weights != !y->weights)
        return 0;
    for (size_t c = 0; x->weights && c < x->channels; c++)
        if (x->weights[c] != y->weights[c])
            return 0;
    return 1;
}

/* ---- one range of pixels --------------------------------------------------- */

typedef struct {
    int test, alternative;
    unsigned flags;
    double null_value, alpha;
    double eps; /* MCSTAT_PIXELS_RENDER's, resolved from the type */
    mcstat_pixels_in x, y;
    mcstat_pixels_out out;
} job;

/* Value s of pixel i: the element, or the weighted sum of its channels
 * formed in double (pixels.c's value, whose Welch path is the same). */
static double value(const mcstat_pixels_in *p, size_t s, size_t i)
{
    size_t k = s * p->value_stride + i * p->pixel_stride;
    const float *f = p->type == MCSTAT_VALUE_FLOAT32 ? p->data : NULL;
    const double *d = f ? NULL : p->data;
    if (!p->weights)
        return f ? (double)f[k] : d[k];
    double v = 0.0;
    for (size_t c = 0; c < p->channels; c++)
        v += p->weights[c] * (f ? (double)f[k + c] : d[k + c]);
    return v;
}

static void gather(const mcstat_pixels_in *p, size_t i, double *buf)
{
    for (size_t s = 0; s < p->n; s++)
        buf[s] = value(p, s, i);
}

static int sample_moments(const double *v, size_t n, unsigned flags, mcstat_moments *m)
{
    mcstat_moments_init(m);
    return (flags & MCSTAT_ROWS_OMIT_NAN) ? mcstat_moments_add_array_omit_nan(m, v, n, NULL)
                                          : mcstat_moments_add_array(m, v, n);
}

/* Leaves out the pairs with a NaN on either side; returns their number. */
static size_t complete_pairs(double *x, double *y, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (!isnan(x[i]) && !isnan(y[i])) {
            x[k] = x[i];
            y[k] = y[i];
            k++;
        }
    return k;
}

static void put(const job *jb, size_t i, int st, const mcstat_result *r)
{
    const mcstat_pixels_out *o = &jb->out;
    const int ok = st == MCSTAT_OK, two = two_sample(jb->test);
    const int iv = ok && !(jb->flags & MCSTAT_ROWS_NO_INTERVALS);
#define PUT(field, v)                                                                                              \
    do {                                                                                                           \
        if (o->field)                                                                                              \
            o->field[i] = (v);                                                                                     \
    } while (0)
    PUT(p_value, ok ? r->p_value : NAN);
    PUT(statistic, ok ? r->statistic : NAN);
    PUT(df, ok ? r->df[0] : NAN);
    PUT(df2, ok && jb->test == MCSTAT_TEST_VAR_2 ? r->df[1] : NAN);
    PUT(estimate, ok ? r->estimate[0] : NAN);
    PUT(estimate2, ok && (jb->test == MCSTAT_TEST_T_2 || jb->test == MCSTAT_TEST_T_2_POOLED) ? r->estimate[1] : NAN);
    PUT(std_error, ok ? r->std_error : NAN);
    PUT(conf_lo, iv ? r->conf_int[0] : NAN);
    PUT(conf_hi, iv ? r->conf_int[1] : NAN);
    PUT(critical_lo, iv ? r->critical[0] : NAN);
    PUT(critical_hi, iv ? r->critical[1] : NAN);
    PUT(status, st);
    PUT(decision, (int8_t)(ok ? r->decision : 0));
    PUT(n_x, ok ? r->n[0] : 0);
    PUT(n_y, ok && two ? r->n[1] : 0);
#undef PUT
}

/* One pixel through the single call's code: its values gathered into the
 * range's buffers, the accumulators, the test on them with the range's
 * quantile cache (so equal df solve their critical values once). */
typedef struct {
    const job *jb;
    double *bx, *by;
    mcstat_qcache qc;
} single_ctx;

static int single_pixel(void *vctx, size_t i)
{
    single_ctx *sc = vctx;
    const job *jb = sc->jb;
    const size_t nx = jb->x.n, ny = jb->y.n;
    mcstat_qcache *q = (jb->flags & MCSTAT_ROWS_NO_INTERVALS) ? NULL : &sc->qc;
    mcstat_moments mx, my;
    mcstat_result r;
    int st;
    gather(&jb->x, i, sc->bx);
    if (two_sample(jb->test))
        gather(&jb->y, i, sc->by);
    switch (jb->test) {
    case MCSTAT_TEST_T_PAIRED: {
        size_t n = (jb->flags & MCSTAT_ROWS_OMIT_NAN) ? complete_pairs(sc->bx, sc->by, nx) : nx;
        st = (jb->flags & MCSTAT_PIXELS_RENDER)
                 ? mcstat__t_test_paired_render(sc->bx, sc->by, n, jb->eps, jb->null_value, jb->alternative,
                                                jb->alpha, q, &r)
                 : mcstat__t_test_paired(sc->bx, sc->by, n, jb->null_value, jb->alternative, jb->alpha, q, &r);
        break;
    }
    case MCSTAT_TEST_T_1:
    case MCSTAT_TEST_VAR_1:
        st = sample_moments(sc->bx, nx, jb->flags, &mx);
        if (!st)
            st = (jb->test == MCSTAT_TEST_T_1 ? mcstat__t_test_1 : mcstat__var_test_1)(
                &mx, jb->null_value, jb->alternative, jb->alpha, q, &r);
        break;
    default: /* T_2 (Welch's pixels its block path leaves), T_2_POOLED, VAR_2 */
        st = sample_moments(sc->bx, nx, jb->flags, &mx);
        if (!st)
            st = sample_moments(sc->by, ny, jb->flags, &my);
        if (!st)
            st = (jb->test == MCSTAT_TEST_T_2_POOLED ? mcstat__t_test_2_pooled : mcstat__var_test_2)(
                &mx, &my, jb->null_value, jb->alternative, jb->alpha, q, &r);
        break;
    }
    put(jb, i, st, &r);
    return st;
}

/* The tests but Welch's on the chunks this thread takes: the variance tests
 * by blocks (pixels_var.c), the others pixel by pixel through the single
 * call. */
static int single_call_work(const job *jb, mcstat__work *wk, size_t *first_index)
{
    const int two = two_sample(jb->test);
    const size_t nx = jb->x.n, ny = two ? jb->y.n : 0;
    single_ctx sc;
    sc.jb = jb;
    sc.bx = malloc((nx ? nx : 1) * sizeof *sc.bx);
    sc.by = two ? malloc((ny ? ny : 1) * sizeof *sc.by) : NULL;
    mcstat__qcache_init(&sc.qc);
    int first = MCSTAT_OK;
    size_t begin, end;
    if (!sc.bx || (two && !sc.by)) {
        while (mcstat__work_take(wk, &begin, &end))
            for (size_t i = begin; i < end; i++) {
                put(jb, i, MCSTAT_ENOMEM, NULL);
                if (first == MCSTAT_OK) {
                    first = MCSTAT_ENOMEM;
                    *first_index = i;
                }
            }
    } else if (jb->test == MCSTAT_TEST_VAR_1 || jb->test == MCSTAT_TEST_VAR_2) {
        first = mcstat__pixels_var(jb->test, &jb->x, two ? &jb->y : NULL, wk, first_index, jb->null_value,
                                   jb->alternative, jb->alpha, jb->flags, &jb->out, single_pixel, &sc);
    } else {
        while (mcstat__work_take(wk, &begin, &end))
            for (size_t i = begin; i < end; i++) {
                int st = single_pixel(&sc, i);
                if (st && first == MCSTAT_OK) {
                    first = st;
                    *first_index = i;
                }
            }
    }
    free(sc.bx);
    free(sc.by);
    return first;
}

static int run_work(void *ctx, mcstat__work *wk, size_t *first_index)
{
    MCSTAT_IEEE_SCOPE(); /* a started thread's environment is the process default */
    const job *jb = ctx;
    if (jb->test == MCSTAT_TEST_T_2)
        return mcstat__pixels_welch(&jb->x, &jb->y, wk, first_index, jb->null_value, jb->alternative, jb->alpha,
                                    jb->flags, jb->eps, &jb->out);
    return single_call_work(jb, wk, first_index);
}

/* ---- the entry point ---------------------------------------------------------- */

int mcstat_pixels_test(int test, const mcstat_pixels_in *x, const mcstat_pixels_in *y, size_t begin, size_t end,
                       double null_value, int alternative, double alpha, const mcstat_pixels_options *opt,
                       const mcstat_pixels_out *out)
{
    MCSTAT_IEEE_SCOPE();
    job jb;
    memset(&jb, 0, sizeof jb);
    const int is_var = test == MCSTAT_TEST_VAR_1 || test == MCSTAT_TEST_VAR_2;
    if (test != MCSTAT_TEST_T_1 && test != MCSTAT_TEST_T_2 && test != MCSTAT_TEST_T_2_POOLED &&
        test != MCSTAT_TEST_T_PAIRED && !is_var)
        return MCSTAT_EINVAL;
    const int two = two_sample(test);
    if (!x || !out || (two ? !y : y != NULL) || end < begin)
        return MCSTAT_EINVAL;
    mcstat_pixels_options o = MCSTAT_PIXELS_OPTIONS_INIT;
    if (opt && mcstat__options_read(&o, sizeof o, opt, OPT_SIZES, N_OF(OPT_SIZES)))
        return MCSTAT_EINVAL;
    if ((o.flags & ~(uint32_t)(MCSTAT_ROWS_NO_INTERVALS | MCSTAT_ROWS_OMIT_NAN | MCSTAT_PIXELS_RENDER)) ||
        o.threads < 1 || o.threads > MAX_THREADS || o.reserved != 0 || !(o.resolution >= 0.0 && o.resolution < 1.0) ||
        ((o.flags & MCSTAT_PIXELS_RENDER) && test != MCSTAT_TEST_T_2 && test != MCSTAT_TEST_T_PAIRED))
        return MCSTAT_EINVAL;
    const mcstat_pixels_in none = MCSTAT_PIXELS_IN_INIT;
    jb.x = none;
    jb.y = none;
    jb.out = (mcstat_pixels_out)MCSTAT_PIXELS_OUT_INIT;
    if (mcstat__options_read(&jb.x, sizeof jb.x, x, IN_SIZES, N_OF(IN_SIZES)) ||
        (two && mcstat__options_read(&jb.y, sizeof jb.y, y, IN_SIZES, N_OF(IN_SIZES))) ||
        mcstat__options_read(&jb.out, sizeof jb.out, out, OUT_SIZES, N_OF(OUT_SIZES)) || jb.out.reserved != 0)
        return MCSTAT_EINVAL;
    if (!isfinite(null_value) || (is_var && !(null_value > 0.0)) || !valid_alternative(alternative) ||
        !valid_alpha(alpha))
        return MCSTAT_EINVAL;
    int st = check_side(&jb.x, begin, end);
    if (!st && two)
        st = check_side(&jb.y, begin, end);
    if (st)
        return st;
    if (two && !same_weighting(&jb.x, &jb.y))
        return MCSTAT_EINVAL;
    if (test == MCSTAT_TEST_T_PAIRED && jb.x.n != jb.y.n)
        return MCSTAT_EINVAL;
    const mcstat_pixels_out *po = &jb.out;
    jb.test = test;
    jb.alternative = alternative;
    jb.alpha = alpha;
    jb.null_value = null_value;
    jb.flags = o.flags;
    jb.eps = o.resolution > 0.0                    ? o.resolution
             : jb.x.type == MCSTAT_VALUE_FLOAT32 ? MCSTAT_RESOLUTION_FLOAT32
                                                 : MCSTAT_RESOLUTION_FLOAT64;
    if (!po->conf_lo && !po->conf_hi && !po->critical_lo && !po->critical_hi)
        jb.flags |= MCSTAT_ROWS_NO_INTERVALS; /* nothing asks for them */
    return mcstat__run_work(begin, end, o.threads, MIN_PIXELS_PER_THREAD, PIXEL_GRANULE, run_work, &jb);
}

/* ---- the seeds-major Welch calls ---------------------------------------------- */

static int seeds_major(int type, const void *x, size_t nx, size_t xs, const void *y, size_t ny, size_t ys,
                       size_t channels, const double *w, size_t begin, size_t end, double mu0, int alternative,
                       double alpha, unsigned flags, const mcstat_pixels_out *out)
{
    mcstat_pixels_in px = {sizeof px, type, x, nx, xs, channels, channels, w};
    mcstat_pixels_in py = {sizeof py, type, y, ny, ys, channels, channels, w};
    mcstat_pixels_options o = MCSTAT_PIXELS_OPTIONS_INIT;
    o.flags = flags;
    if (end > begin && (!x || !y))
        return MCSTAT_EINVAL;
    return mcstat_pixels_test(MCSTAT_TEST_T_2, &px, &py, begin, end, mu0, alternative, alpha, &o, out);
}

int mcstat_t_test_2_pixels(const double *x, size_t nx, size_t x_seed_stride, const double *y, size_t ny,
                           size_t y_seed_stride, size_t channels, const double *weights, size_t begin, size_t end,
                           double mu0, int alternative, double alpha, unsigned flags, const mcstat_pixels_out *out)
{
    return seeds_major(MCSTAT_VALUE_FLOAT64, x, nx, x_seed_stride, y, ny, y_seed_stride, channels, weights, begin,
                       end, mu0, alternative, alpha, flags, out);
}

int mcstat_t_test_2_pixels_f32(const float *x, size_t nx, size_t x_seed_stride, const float *y, size_t ny,
                               size_t y_seed_stride, size_t channels, const double *weights, size_t begin,
                               size_t end, double mu0, int alternative, double alpha, unsigned flags,
                               const mcstat_pixels_out *out)
{
    return seeds_major(MCSTAT_VALUE_FLOAT32, x, nx, x_seed_stride, y, ny, y_seed_stride, channels, weights, begin,
                       end, mu0, alternative, alpha, flags, out);
}
