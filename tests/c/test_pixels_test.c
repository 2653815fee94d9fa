/*
 * test_pixels_test.c - mcstat_pixels_test (pixels_test.c): every test, in
 * seeds-major, row and weighted-RGB layouts, float32 and double, every
 * alternative, with and without intervals and NaN omission, every output
 * array against the single call on the pixel's own values (bit for bit
 * but for Welch's test, whose block path is held to the bounds of
 * mcstat.h); results independent of the number of threads; the structs'
 * sizes and initialisers; bad arguments, nothing written.
 */
#include "harness.h"
#include "mcstat.h"
#include "internal.h" /* mcstat__pixels_baseline_only */

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define P 700 /* pixels */
#define NX 8
#define NY 7  /* y's values in the unpaired tests (paired: NX) */
#define CH 3
#define PAD 3 /* the rows layout leaves PAD unused elements after each row */

static const double RGB[CH] = {0.2126, 0.7152, 0.0722};

enum { SEEDS_MAJOR, ROWS, RGB_SEEDS_MAJOR, N_LAYOUTS };

static double urand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1p-53;
}

/* value s of pixel i of side `side`, before the layout: pixel kinds by
 * i mod 50 (a NaN, an Inf, a constant sample, a large offset, different
 * scales), else noise */
static double truth(int side, size_t s, size_t i, size_t c)
{
    unsigned long long st = (i * 131u + s * 7u + (unsigned)side * 100003u + c * 17u) * 2654435761u + 1u;
    for (int k = 0; k < 3; k++)
        urand(&st);
    double u = urand(&st) - 0.5;
    size_t kind = i % 50;
    if (kind == 3 && s == 2 && side == 0)
        return NAN;
    if (kind == 7 && s == 1 && side == 1)
        return NAN;
    if (kind == 11 && s == 0)
        return INFINITY;
    if (kind == 13)
        return 0.25; /* constant */
    if (kind == 17)
        return 1e8 + u;
    return (1.0 + (double)(i % 5)) * u + (side ? 0.05 * (double)(i % 3) : 0.0) + 0.5;
}

static double xd[N_LAYOUTS][NX * P * CH + P * PAD], yd[N_LAYOUTS][NX * P * CH + P * PAD];
static float xf[N_LAYOUTS][NX * P * CH + P * PAD], yf[N_LAYOUTS][NX * P * CH + P * PAD];

static void fill(void)
{
    for (int L = 0; L < N_LAYOUTS; L++)
        for (int side = 0; side < 2; side++) {
            double *d = side ? yd[L] : xd[L];
            float *f = side ? yf[L] : xf[L];
            for (size_t i = 0; i < P; i++)
                for (size_t s = 0; s < NX; s++)
                    for (size_t c = 0; c < (L == RGB_SEEDS_MAJOR ? CH : 1); c++) {
                        double v = truth(side, s, i, c);
                        size_t k = L == ROWS ? i * (NX + PAD) + s : L == SEEDS_MAJOR ? s * P + i : s * P * CH + i * CH + c;
                        d[k] = v;
                        f[k] = (float)v;
                    }
        }
}

static mcstat_pixels_in side_in(int L, int f32, int side, size_t n)
{
    mcstat_pixels_in in = MCSTAT_PIXELS_IN_INIT;
    in.type = f32 ? MCSTAT_VALUE_FLOAT32 : MCSTAT_VALUE_FLOAT64;
    in.data = f32 ? (const void *)(side ? yf[L] : xf[L]) : (const void *)(side ? yd[L] : xd[L]);
    in.n = n;
    in.value_stride = L == ROWS ? 1 : L == SEEDS_MAJOR ? P : P * CH;
    in.pixel_stride = L == ROWS ? NX + PAD : L == SEEDS_MAJOR ? 1 : CH;
    in.channels = L == RGB_SEEDS_MAJOR ? CH : 1;
    in.weights = L == RGB_SEEDS_MAJOR ? RGB : NULL;
    return in;
}

/* pixel i's values as the call forms them */
static void values(const mcstat_pixels_in *in, size_t i, double *v)
{
    for (size_t s = 0; s < in->n; s++) {
        size_t k = s * in->value_stride + i * in->pixel_stride;
        if (!in->weights) {
            v[s] = in->type ? (double)((const float *)in->data)[k] : ((const double *)in->data)[k];
            continue;
        }
        double a = 0.0;
        for (size_t c = 0; c < in->channels; c++)
            a += in->weights[c] * (in->type ? (double)((const float *)in->data)[k + c] : ((const double *)in->data)[k + c]);
        v[s] = a;
    }
}

typedef struct {
    double p[P], t[P], df[P], df2[P], e[P], e2[P], se[P], lo[P], hi[P], c0[P], c1[P];
    int32_t st[P];
    int8_t dec[P];
    uint64_t nx[P], ny[P];
} outs;

static mcstat_pixels_out view(outs *o)
{
    mcstat_pixels_out v = MCSTAT_PIXELS_OUT_INIT;
    v.p_value = o->p;
    v.statistic = o->t;
    v.df = o->df;
    v.df2 = o->df2;
    v.estimate = o->e;
    v.estimate2 = o->e2;
    v.std_error = o->se;
    v.conf_lo = o->lo;
    v.conf_hi = o->hi;
    v.critical_lo = o->c0;
    v.critical_hi = o->c1;
    v.status = o->st;
    v.decision = o->dec;
    v.n_x = o->nx;
    v.n_y = o->ny;
    return v;
}

static int same(double a, double b)
{
    return (isnan(a) && isnan(b)) || memcmp(&a, &b, sizeof a) == 0;
}

/* the single call on pixel i's values */
static int reference(int test, const mcstat_pixels_in *x, const mcstat_pixels_in *y, size_t i, double null_value,
                     int alt, unsigned flags, mcstat_result *r)
{
    double vx[NX], vy[NX];
    values(x, i, vx);
    if (y)
        values(y, i, vy);
    int32_t st = MCSTAT_OK;
    mcstat_moments mx, my;
    switch (test) {
    case MCSTAT_TEST_T_1:
        mcstat_t_test_1_matrix(vx, x->n, 0, 1, null_value, alt, 0.05, flags, r, &st);
        return st;
    case MCSTAT_TEST_VAR_1:
        mcstat_var_test_1_matrix(vx, x->n, 0, 1, null_value, alt, 0.05, flags, r, &st);
        return st;
    case MCSTAT_TEST_T_2:
        mcstat_t_test_2_matrix(vx, x->n, 0, vy, y->n, 0, 1, null_value, alt, 0.05, flags, r, &st);
        return st;
    case MCSTAT_TEST_VAR_2:
        mcstat_var_test_2_matrix(vx, x->n, 0, vy, y->n, 0, 1, null_value, alt, 0.05, flags, r, &st);
        return st;
    case MCSTAT_TEST_T_2_POOLED:
        mcstat_moments_init(&mx);
        mcstat_moments_init(&my);
        st = (flags & MCSTAT_ROWS_OMIT_NAN) ? mcstat_moments_add_array_omit_nan(&mx, vx, x->n, NULL)
                                            : mcstat_moments_add_array(&mx, vx, x->n);
        if (!st)
            st = (flags & MCSTAT_ROWS_OMIT_NAN) ? mcstat_moments_add_array_omit_nan(&my, vy, y->n, NULL)
                                                : mcstat_moments_add_array(&my, vy, y->n);
        return st ? st : mcstat_t_test_2_pooled_moments(&mx, &my, null_value, alt, 0.05, r);
    default: { /* paired */
        size_t n = 0;
        for (size_t s = 0; s < x->n; s++)
            if (!(flags & MCSTAT_ROWS_OMIT_NAN) || (!isnan(vx[s]) && !isnan(vy[s]))) {
                vx[n] = vx[s];
                vy[n] = vy[s];
                n++;
            }
        return mcstat_t_test_paired(vx, vy, n, null_value, alt, 0.05, r);
    }
    }
}

/* |a - b| within tol relative to max(|b|, scale), or both the same */
static int near(double a, double b, double tol, double scale)
{
    return same(a, b) || fabs(a - b) <= tol * fmax(fabs(b), scale);
}

static double max_p_err; /* the variance tests' largest p-value error / bound */

static void check_case(int test, int L, int f32, int alt, unsigned flags)
{
    static outs o;
    memset(&o, 0xff, sizeof o);
    const int two = test != MCSTAT_TEST_T_1 && test != MCSTAT_TEST_VAR_1;
    const int welch = test == MCSTAT_TEST_T_2, var = test == MCSTAT_TEST_VAR_1 || test == MCSTAT_TEST_VAR_2;
    const int block = welch || var; /* the block paths: to the bounds of mcstat.h, not bit for bit */
    const double null_value = var ? 1.5 : 0.1;
    mcstat_pixels_in x = side_in(L, f32, 0, NX), y = side_in(L, f32, 1, test == MCSTAT_TEST_T_PAIRED ? NX : NY);
    mcstat_pixels_options opt = MCSTAT_PIXELS_OPTIONS_INIT;
    opt.flags = flags;
    mcstat_pixels_out v = view(&o);
    int ret = mcstat_pixels_test(test, &x, two ? &y : NULL, 0, P, null_value, alt, 0.05, &opt, &v);
    int first = MCSTAT_OK, ok_pixels = 0, mism = 0;
    const int iv = !(flags & MCSTAT_ROWS_NO_INTERVALS);
    for (size_t i = 0; i < P; i++) {
        mcstat_result r;
        int want = reference(test, &x, two ? &y : NULL, i, null_value, alt, flags,
                             &r);
        if (want && first == MCSTAT_OK)
            first = want;
        int bad = o.st[i] != want;
        if (want) {
            bad |= !(isnan(o.p[i]) && isnan(o.t[i]) && isnan(o.df[i]) && isnan(o.e[i]) && isnan(o.lo[i]) &&
                     isnan(o.c0[i]) && o.dec[i] == 0 && o.nx[i] == 0 && o.ny[i] == 0);
        } else {
            ok_pixels++;
            double rlo = iv ? r.conf_int[0] : NAN, rhi = iv ? r.conf_int[1] : NAN;
            double rc0 = iv ? r.critical[0] : NAN, rc1 = iv ? r.critical[1] : NAN;
            double rdf2 = test == MCSTAT_TEST_VAR_2 ? r.df[1] : NAN;
            double re2 = test == MCSTAT_TEST_T_2 || test == MCSTAT_TEST_T_2_POOLED ? r.estimate[1] : NAN;
            bad |= o.nx[i] != r.n[0] || o.ny[i] != (two ? r.n[1] : 0);
            if (!block) {
                bad |= !same(o.p[i], r.p_value) || !same(o.t[i], r.statistic) || !same(o.df[i], r.df[0]) ||
                       !same(o.df2[i], rdf2) || !same(o.e[i], r.estimate[0]) || !same(o.e2[i], re2) ||
                       !same(o.se[i], r.std_error) || !same(o.lo[i], rlo) || !same(o.hi[i], rhi) ||
                       !same(o.c0[i], rc0) || !same(o.c1[i], rc1) || o.dec[i] != r.decision;
            } else {
                /* mcstat.h: each within the bound of the exact tail, so twice it apart */
                double tol_p = 2.0 * (3e-14 + 4e-16 * fabs(log(fmax(r.p_value, DBL_MIN))));
                double hw = isfinite(rhi - rlo) ? fabs(rhi - rlo) : fabs(r.std_error);
                double scale = welch ? 4.0 * r.std_error * sqrt((double)NX) : 0.0;
                double ctol = welch ? 3e-13 : 0.0; /* the variance tests' are the single call's */
                bad |= !near(o.p[i], r.p_value, tol_p, 0.0) || !near(o.t[i], r.statistic, 1e-14, welch ? 1.0 : 0.0) ||
                       !near(o.df[i], r.df[0], 1e-14, 0.0) || !same(o.df2[i], rdf2) ||
                       !near(o.e[i], r.estimate[0], 8 * DBL_EPSILON, scale) ||
                       !near(o.e2[i], re2, 8 * DBL_EPSILON, scale) || !near(o.se[i], r.std_error, 1e-14, 0.0) ||
                       !near(o.lo[i], rlo, 1e-14, welch ? hw : 0.0) || !near(o.hi[i], rhi, 1e-14, welch ? hw : 0.0) ||
                       !near(o.c0[i], rc0, ctol, 0.0) || !near(o.c1[i], rc1, ctol, 0.0);
                if (var) {
                    double e = fabs(o.p[i] - r.p_value) / r.p_value / tol_p;
                    max_p_err = e > max_p_err ? e : max_p_err;
                }
                /* the decision may differ only where p is within its bound of alpha */
                if (o.dec[i] != r.decision && fabs(r.p_value - 0.05) > 1e-12)
                    bad = 1;
            }
        }
        if (bad && mism++ < 3)
            fprintf(stderr, "test %d layout %d f32 %d alt %d flags %u: pixel %zu differs (status %d, want %d)\n",
                    test, L, f32, alt, flags, i, (int)o.st[i], want);
        h_checks++;
        h_failures += bad;
    }
    CHECK_INT(ret, first);
    CHECK(first != MCSTAT_OK && ok_pixels > P / 2); /* both kinds of pixel were there */
}

static void test_every_case(void)
{
    const int tests[] = {MCSTAT_TEST_T_1,      MCSTAT_TEST_T_2,   MCSTAT_TEST_T_2_POOLED,
                         MCSTAT_TEST_T_PAIRED, MCSTAT_TEST_VAR_1, MCSTAT_TEST_VAR_2};
    const int alts[] = {MCSTAT_TWO_SIDED, MCSTAT_LESS, MCSTAT_GREATER};
    const unsigned flags[] = {0u, MCSTAT_ROWS_NO_INTERVALS, MCSTAT_ROWS_OMIT_NAN};
    for (size_t t = 0; t < 6; t++)
        for (int L = 0; L < N_LAYOUTS; L++)
            for (int f32 = 0; f32 < 2; f32++)
                for (size_t a = 0; a < 3; a++)
                    for (size_t f = 0; f < 3; f++)
                        check_case(tests[t], L, f32, alts[a], flags[f]);
    printf("variance tests per pixel: max p-value error / bound %.3f\n", max_p_err);
}

/* The same bytes whatever the number of threads (P2 pixels: ranges of at
 * least 4096). */
#define P2 40000
static double bx[4 * P2], by[4 * P2];
static double r1[2][P2], r3[2][P2];
static int32_t s1[P2], s3[P2];

static void test_threads(void)
{
    unsigned long long st = 7;
    for (size_t k = 0; k < 4 * P2; k++) {
        bx[k] = urand(&st);
        by[k] = urand(&st) * 1.1;
    }
    const int tests[] = {MCSTAT_TEST_T_2, MCSTAT_TEST_VAR_2, MCSTAT_TEST_T_PAIRED};
    /* round 0: pixel 5 fails (a NaN); round 1: pixels 21000 (constant on
     * both sides) and 35000 (a NaN) fail, in different chunks: the call
     * returns the status of the lower index whichever thread took it */
    for (int round = 0; round < 2; round++) {
        if (round == 0) {
            bx[5 * 4 + 1] = NAN;
        } else {
            bx[5 * 4 + 1] = 0.5;
            for (size_t s = 0; s < 4; s++) {
                bx[21000 * 4 + s] = 1.0;
                by[21000 * 4 + s] = 2.0;
            }
            by[35000 * 4 + 2] = NAN;
        }
        const int want = round == 0 ? MCSTAT_ENONFINITE : MCSTAT_EDEGENERATE;
        for (size_t t = 0; t < 3; t++)
            for (int threads = 2; threads <= 8; threads *= 4) {
                mcstat_pixels_in x = MCSTAT_PIXELS_IN_INIT, y = MCSTAT_PIXELS_IN_INIT;
                x.data = bx;
                y.data = by;
                x.n = y.n = 4;
                x.value_stride = y.value_stride = 1;
                x.pixel_stride = y.pixel_stride = 4;
                mcstat_pixels_options o1 = MCSTAT_PIXELS_OPTIONS_INIT, o3 = MCSTAT_PIXELS_OPTIONS_INIT;
                o3.threads = threads;
                mcstat_pixels_out v1 = MCSTAT_PIXELS_OUT_INIT, v3 = MCSTAT_PIXELS_OUT_INIT;
                memset(r3, 0, sizeof r3);
                memset(s3, 0, sizeof s3);
                v1.p_value = r1[0];
                v1.conf_lo = r1[1];
                v1.status = s1;
                v3.p_value = r3[0];
                v3.conf_lo = r3[1];
                v3.status = s3;
                double nv = tests[t] == MCSTAT_TEST_VAR_2 ? 1.0 : 0.0;
                int a = mcstat_pixels_test(tests[t], &x, &y, 0, P2, nv, MCSTAT_TWO_SIDED, 0.05, &o1, &v1);
                int b = mcstat_pixels_test(tests[t], &x, &y, 0, P2, nv, MCSTAT_TWO_SIDED, 0.05, &o3, &v3);
                CHECK_MSG(a == want, "test %d round %d: status %d, want %d", tests[t], round, a, want);
                CHECK_INT(b, a);
                CHECK(memcmp(r1, r3, sizeof r1) == 0 && memcmp(s1, s3, sizeof s1) == 0);
                CHECK(s1[round == 0 ? 5 : 35000] == MCSTAT_ENONFINITE && (round == 0 || s1[21000] == MCSTAT_EDEGENERATE));
            }
    }
}

static void test_structs(void)
{
    CHECK_INT(mcstat_sizeof_pixels_in(), MCSTAT_PIXELS_IN_SIZE_0_2);
    CHECK_INT(mcstat_sizeof_pixels_options(), MCSTAT_PIXELS_OPTIONS_SIZE_0_3);
    mcstat_pixels_options old = MCSTAT_PIXELS_OPTIONS_INIT; /* 0.2's size stays a known one */
    CHECK_INT(mcstat_pixels_options_init_size(&old, MCSTAT_PIXELS_OPTIONS_SIZE_0_2), MCSTAT_OK);
    CHECK_INT(mcstat_sizeof_pixels_out(), MCSTAT_PIXELS_OUT_SIZE_0_2);
    mcstat_pixels_in in;
    mcstat_pixels_options op;
    mcstat_pixels_out ou;
    memset(&in, 0x55, sizeof in);
    memset(&op, 0x55, sizeof op);
    memset(&ou, 0x55, sizeof ou);
    CHECK_INT(mcstat_pixels_in_init_size(&in, sizeof in), MCSTAT_OK);
    CHECK_INT(mcstat_pixels_options_init_size(&op, sizeof op), MCSTAT_OK);
    CHECK_INT(mcstat_pixels_out_init_size(&ou, sizeof ou), MCSTAT_OK);
    const mcstat_pixels_in din = MCSTAT_PIXELS_IN_INIT;
    const mcstat_pixels_options dop = MCSTAT_PIXELS_OPTIONS_INIT;
    const mcstat_pixels_out dou = MCSTAT_PIXELS_OUT_INIT;
    CHECK(memcmp(&in, &din, sizeof in) == 0 && memcmp(&op, &dop, sizeof op) == 0 &&
          memcmp(&ou, &dou, sizeof ou) == 0);
    CHECK_INT(mcstat_pixels_in_init_size(&in, 12), MCSTAT_EINVAL);
    CHECK_INT(mcstat_pixels_options_init_size(NULL, sizeof op), MCSTAT_EINVAL);
    CHECK_INT(mcstat_pixels_out_init_size(&ou, sizeof ou + 8), MCSTAT_EINVAL);
}

static void test_bad_arguments(void)
{
    static double p[4] = {-1, -1, -1, -1};
    static int32_t st[4] = {-1, -1, -1, -1};
    mcstat_pixels_out o = MCSTAT_PIXELS_OUT_INIT;
    o.p_value = p;
    o.status = st;
    double d[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 17};
    mcstat_pixels_in x = MCSTAT_PIXELS_IN_INIT, y;
    x.data = d;
    x.n = 4;
    x.value_stride = 1;
    x.pixel_stride = 4;
    y = x;
    mcstat_pixels_options opt = MCSTAT_PIXELS_OPTIONS_INIT;
#define BAD(call, want) CHECK_INT(call, want)
    BAD(mcstat_pixels_test(99, &x, &y, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_2, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, &y, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, NULL, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, NULL), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 2, 1, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, NAN, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_VAR_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_VAR_2, &x, &y, 0, 2, -1.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, 5, 0.05, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 1.0, NULL, &o), MCSTAT_EINVAL);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, NAN, NULL, &o), MCSTAT_EINVAL);
    opt.flags = 8u;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, &opt, &o), MCSTAT_EINVAL);
    opt.flags = 0u;
    opt.threads = 0;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, &opt, &o), MCSTAT_EINVAL);
    opt.threads = 65;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, &opt, &o), MCSTAT_EINVAL);
    opt.threads = 1;
    opt.size = 3;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, &opt, &o), MCSTAT_EINVAL);
    mcstat_pixels_in z = x;
    z.size = 0;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z = x;
    z.type = 2;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z = x;
    z.channels = 0;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z.channels = 2; /* without weights */
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    const double wnan[2] = {1.0, NAN}, w2[2] = {0.5, 0.5};
    z.weights = wnan;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z.weights = w2; /* x weighted, y not */
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_2, &z, &y, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z = x;
    z.type = MCSTAT_VALUE_FLOAT32; /* x float, y double */
    BAD(mcstat_pixels_test(MCSTAT_TEST_VAR_2, &z, &y, 0, 2, 1.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z = x;
    z.n = 3; /* paired, unequal */
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_PAIRED, &z, &y, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z = x;
    z.data = NULL;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_EINVAL);
    z = x;
    z.value_stride = SIZE_MAX / 2;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_ETOOBIG);
    z = x;
    z.pixel_stride = SIZE_MAX / 4;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_2, &x, &z, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_ETOOBIG);
    mcstat_pixels_out bo = o;
    bo.size = 8;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &bo), MCSTAT_EINVAL);
    bo = o;
    bo.reserved = 1;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &bo), MCSTAT_EINVAL);
    CHECK(p[0] == -1.0 && st[0] == -1); /* nothing was written */
    /* an empty range with NULL data, then a good call */
    z = x;
    z.data = NULL;
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &z, NULL, 1, 1, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_OK);
    BAD(mcstat_pixels_test(MCSTAT_TEST_T_1, &x, NULL, 0, 2, 0.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_OK);
    CHECK(st[0] == MCSTAT_OK && st[1] == MCSTAT_OK && p[0] > 0.0 && p[0] < 1.0 && st[2] == -1);
    /* too few values: each pixel's status */
    z = x;
    z.n = 1;
    BAD(mcstat_pixels_test(MCSTAT_TEST_VAR_1, &z, NULL, 0, 2, 1.0, MCSTAT_TWO_SIDED, 0.05, NULL, &o), MCSTAT_ETOOFEW);
    CHECK(st[0] == MCSTAT_ETOOFEW && st[1] == MCSTAT_ETOOFEW && isnan(p[0]));
#undef BAD
}

/* The variance tests' tails (pixels_var.c's table) over a wide range of
 * statistics and df against the single call: each pixel's values are a
 * fixed zero-mean pattern scaled to give the statistic wanted (log-uniform
 * over 24 decades about the centre). */
static void scaled_pattern(double *v, size_t n, size_t stride, double c)
{
    for (size_t s = 0; s < n; s++)
        v[s * stride] = c * (s % 2 ? 1.0 : -1.0) * (1.0 + 0.25 * (double)(s % 3));
}

static void test_variance_tails(void)
{
    const size_t sizes[][2] = {{2, 2}, {2, 6}, {3, 3}, {4, 8}, {8, 8}, {16, 4}, {64, 64}, {201, 51}, {1001, 3}};
    const int alts[] = {MCSTAT_TWO_SIDED, MCSTAT_LESS, MCSTAT_GREATER};
    double worst = 0.0;
    for (size_t c = 0; c < sizeof sizes / sizeof *sizes; c++) {
        size_t nx = sizes[c][0], ny = sizes[c][1], m = nx > 100 ? 2000 : 6000;
        double *x = malloc(nx * m * sizeof *x), *y = malloc(ny * m * sizeof *y), *p = malloc(m * sizeof *p);
        int32_t *st = malloc(m * sizeof *st);
        double *vx = malloc(nx * sizeof *vx), *vy = malloc(ny * sizeof *vy);
        for (int two = 0; two < 2; two++) {
            for (size_t i = 0; i < m; i++) { /* pixel i: value s at s * m + i */
                double u = -12.0 + 24.0 * (double)i / (double)(m - 1); /* log10 of the statistic / centre */
                scaled_pattern(x + i, nx, m, 1.0);
                double m2 = 0.0, mean = 0.0;
                for (size_t s = 0; s < nx; s++)
                    mean += x[s * m + i] / (double)nx;
                for (size_t s = 0; s < nx; s++)
                    m2 += (x[s * m + i] - mean) * (x[s * m + i] - mean);
                double target = pow(10.0, u) * (two ? 1.0 : (double)(nx - 1));
                /* chi-squared: M2 / sigma2 with sigma2 = 1; F: var(x) / var(y) with var(y) = 1 */
                double want_m2 = two ? target * (double)(nx - 1) : target;
                scaled_pattern(x + i, nx, m, sqrt(want_m2 / m2));
                if (two) {
                    scaled_pattern(y + i, ny, m, 1.0);
                    double my = 0.0, m2y = 0.0;
                    for (size_t s = 0; s < ny; s++)
                        my += y[s * m + i] / (double)ny;
                    for (size_t s = 0; s < ny; s++)
                        m2y += (y[s * m + i] - my) * (y[s * m + i] - my);
                    scaled_pattern(y + i, ny, m, sqrt((double)(ny - 1) / m2y));
                }
            }
            mcstat_pixels_in in_x = MCSTAT_PIXELS_IN_INIT, in_y = MCSTAT_PIXELS_IN_INIT;
            in_x.data = x;
            in_x.n = nx;
            in_x.value_stride = m;
            in_x.pixel_stride = 1;
            in_y = in_x;
            in_y.data = y;
            in_y.n = ny;
            mcstat_pixels_out o = MCSTAT_PIXELS_OUT_INIT;
            o.p_value = p;
            o.status = st;
            for (size_t a = 0; a < 3; a++) {
                int test = two ? MCSTAT_TEST_VAR_2 : MCSTAT_TEST_VAR_1;
                CHECK_INT(mcstat_pixels_test(test, &in_x, two ? &in_y : NULL, 0, m, 1.0, alts[a], 0.05, NULL, &o),
                          MCSTAT_OK);
                for (size_t i = 0; i < m; i++) {
                    mcstat_result r;
                    for (size_t s = 0; s < nx; s++)
                        vx[s] = x[s * m + i];
                    for (size_t s = 0; two && s < ny; s++)
                        vy[s] = y[s * m + i];
                    int want = two ? mcstat_var_test_2(vx, nx, vy, ny, 1.0, alts[a], 0.05, &r)
                                   : mcstat_var_test_1(vx, nx, 1.0, alts[a], 0.05, &r);
                    CHECK_INT(st[i], want);
                    if (want != MCSTAT_OK || r.p_value < DBL_MIN)
                        continue;
                    /* mcstat.h: twice Welch's bound (the table interpolates the general
                     * routine's own tails, whose errors it carries) */
                    double tol = 6e-14 + 8e-16 * fabs(log(r.p_value));
                    double e = fabs(p[i] - r.p_value) / r.p_value / tol;
                    worst = e > worst ? e : worst;
                    CHECK_MSG(e <= 1.0, "var test %d, n %zu + %zu, alt %d, pixel %zu: p %.17g, single call %.17g",
                              test, nx, ny, alts[a], i, p[i], r.p_value);
                }
            }
        }
        free(x);
        free(y);
        free(p);
        free(st);
        free(vx);
        free(vy);
    }
    printf("variance tails over 24 decades of the statistic: max p-value error / bound %.3f\n", worst);
}

/* The layouts read the same values: every block path gives the same bytes
 * for the seeds-major stack and the rows (the rows transposed into the
 * tile loop, pixels.c). */
static void test_layouts_agree(void)
{
    static outs a, b;
    const int tests[] = {MCSTAT_TEST_T_2, MCSTAT_TEST_VAR_2, MCSTAT_TEST_VAR_1};
    for (size_t t = 0; t < 3; t++)
        for (int f32 = 0; f32 < 2; f32++) {
            int two = tests[t] != MCSTAT_TEST_VAR_1;
            mcstat_pixels_in xs = side_in(SEEDS_MAJOR, f32, 0, NX), ys = side_in(SEEDS_MAJOR, f32, 1, NY);
            mcstat_pixels_in xr = side_in(ROWS, f32, 0, NX), yr = side_in(ROWS, f32, 1, NY);
            memset(&a, 0, sizeof a);
            memset(&b, 0, sizeof b);
            mcstat_pixels_out va = view(&a), vb = view(&b);
            double nv = tests[t] == MCSTAT_TEST_T_2 ? 0.0 : 1.0;
            mcstat_pixels_test(tests[t], &xs, two ? &ys : NULL, 0, P, nv, MCSTAT_TWO_SIDED, 0.05, NULL, &va);
            mcstat_pixels_test(tests[t], &xr, two ? &yr : NULL, 0, P, nv, MCSTAT_TWO_SIDED, 0.05, NULL, &vb);
            CHECK_MSG(memcmp(&a, &b, sizeof a) == 0, "test %d f32 %d: layouts differ", tests[t], f32);
        }
}

/* Rows of every length the row path treats apart (4 values of 8 rows at a
 * time, the last n mod 4 one by one, the last k mod 8 rows through the
 * buffer, rows longer than the buffer) give the bytes of the seeds-major
 * path on the same values, in the AVX2 and the baseline builds; the
 * pixels include a NaN and an Inf at the last value, magnitudes outside
 * the fast range and a constant row. */
#define PL 53 /* pixels: 6 tiles of 8 and 5 */
#define NL_MAX 300
static double ld_s[NL_MAX * PL], ld_r[NL_MAX * PL + PL], ld_y[NL_MAX * PL], ld_yr[NL_MAX * PL + PL];
static float lf_s[NL_MAX * PL], lf_r[NL_MAX * PL + PL], lf_y[NL_MAX * PL], lf_yr[NL_MAX * PL + PL];

static double row_value(int side, size_t s, size_t n, size_t i)
{
    unsigned long long st = (i * 7919u + s * 31u + (unsigned)side * 65537u) * 2654435761u + 3u;
    double u = urand(&st) - 0.5;
    switch (i % 13) {
    case 2: return s == n - 1 && !side ? NAN : u;
    case 5: return s == n - 1 ? INFINITY : u;
    case 6: return 1e250 * u; /* above the fast range: the single call's code */
    case 9: return 1e-250 * u;
    case 10: return -0.0;
    default: return (1.0 + (double)(i % 3)) * u + 0.01 * (double)side;
    }
}

/* the float rows: the extreme magnitudes brought into float's range */
static float to_float(double v, size_t i)
{
    return (float)(i % 13 == 6 ? v * 1e-220 : i % 13 == 9 ? v * 1e220 : v);
}

static void test_row_lengths(void)
{
    static outs a, b, c;
    const size_t lens[] = {2, 3, 4, 5, 7, 9, 16, 31, 64, 255, 256, 257, 300};
    const int tests[] = {MCSTAT_TEST_T_2, MCSTAT_TEST_T_2_POOLED, MCSTAT_TEST_VAR_1, MCSTAT_TEST_VAR_2};
    for (size_t li = 0; li < sizeof lens / sizeof lens[0]; li++) {
        const size_t n = lens[li], ps = n + 1; /* odd row starts */
        for (size_t i = 0; i < PL; i++)
            for (size_t s = 0; s < n; s++) {
                double vx = row_value(0, s, n, i), vy = row_value(1, s, n, i);
                ld_s[s * PL + i] = vx;
                ld_r[i * ps + s] = vx;
                ld_y[s * PL + i] = vy;
                ld_yr[i * ps + s] = vy;
                lf_s[s * PL + i] = to_float(vx, i);
                lf_r[i * ps + s] = lf_s[s * PL + i];
                lf_y[s * PL + i] = to_float(vy, i);
                lf_yr[i * ps + s] = lf_y[s * PL + i];
            }
        for (int f32 = 0; f32 < 2; f32++)
            for (size_t t = 0; t < sizeof tests / sizeof tests[0]; t++) {
                const int two = tests[t] != MCSTAT_TEST_VAR_1;
                mcstat_pixels_in xs = MCSTAT_PIXELS_IN_INIT, ys, xr, yr;
                xs.type = f32 ? MCSTAT_VALUE_FLOAT32 : MCSTAT_VALUE_FLOAT64;
                xs.n = n;
                xs.value_stride = PL;
                xs.pixel_stride = 1;
                ys = xs;
                xs.data = f32 ? (const void *)lf_s : (const void *)ld_s;
                ys.data = f32 ? (const void *)lf_y : (const void *)ld_y;
                xr = xs;
                xr.value_stride = 1;
                xr.pixel_stride = ps;
                yr = xr;
                xr.data = f32 ? (const void *)lf_r : (const void *)ld_r;
                yr.data = f32 ? (const void *)lf_yr : (const void *)ld_yr;
                memset(&a, 0, sizeof a);
                memset(&b, 0, sizeof b);
                memset(&c, 0, sizeof c);
                mcstat_pixels_out va = view(&a), vb = view(&b), vc = view(&c);
                double nv = tests[t] == MCSTAT_TEST_VAR_1 ? 0.1 : tests[t] == MCSTAT_TEST_VAR_2 ? 1.0 : 0.0;
                int sa = mcstat_pixels_test(tests[t], &xs, two ? &ys : NULL, 0, PL, nv, MCSTAT_TWO_SIDED, 0.05, NULL, &va);
                int sb = mcstat_pixels_test(tests[t], &xr, two ? &yr : NULL, 0, PL, nv, MCSTAT_TWO_SIDED, 0.05, NULL, &vb);
                mcstat__pixels_baseline_only(1);
                int sc = mcstat_pixels_test(tests[t], &xr, two ? &yr : NULL, 0, PL, nv, MCSTAT_TWO_SIDED, 0.05, NULL, &vc);
                mcstat__pixels_baseline_only(0);
                CHECK_INT(sb, sa);
                CHECK_INT(sc, sa);
                CHECK_MSG(memcmp(&a, &b, sizeof a) == 0, "n %zu test %d f32 %d: rows differ from seeds-major", n,
                          tests[t], f32);
                CHECK_MSG(memcmp(&b, &c, sizeof b) == 0, "n %zu test %d f32 %d: AVX2 rows differ from baseline", n,
                          tests[t], f32);
                /* most pixels took the block path (the others' kinds are 4 of 13) */
                size_t ok = 0;
                for (size_t i = 0; i < PL; i++)
                    ok += a.st[i] == MCSTAT_OK;
                CHECK_MSG(ok >= PL / 2, "n %zu: %zu pixels succeeded", n, ok);
            }
    }
}

/* MCSTAT_PIXELS_RENDER against closed forms computed here: a side of zeros
 * (rule-of-three variance), a side with one nonzero value, both sides
 * constant (equal: untested; different: p = 0), smooth pixels (Hsu's df);
 * block path (many pixels) and single call (a pixel with a NaN, omitted)
 * alike, AVX2 and baseline bit for bit; refused outside Welch's test. */
#define RP 300
#define RK 8
static void test_render_guards(void)
{
    static float x[RK * RP], y[RK * RP];
    uint64_t state = 12345;
    for (size_t i = 0; i < RP; i++)
        for (size_t s = 0; s < RK; s++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            double u = (double)(state >> 11) * 0x1p-53;
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            double v = (double)(state >> 11) * 0x1p-53;
            x[s * RP + i] = (float)(1.0 + 0.2 * u);
            y[s * RP + i] = (float)(1.1 + 0.05 * v);
        }
    for (size_t s = 0; s < RK; s++) {
        x[s * RP + 0] = 0.0f;                         /* a side of zeros */
        x[s * RP + 1] = s == 3 ? 5.0f : 0.0f;         /* one nonzero value */
        x[s * RP + 2] = 0.5f, y[s * RP + 2] = 0.75f;  /* both constant, different */
        x[s * RP + 3] = y[s * RP + 3] = 0.25f;        /* both constant, equal */
        x[s * RP + 4] = s == 0 ? NAN : 0.0f;          /* zeros and a NaN: the single call */
    }
    x[0 * RP + 5] = nextafterf(0.25f, 1.0f);          /* within the floor of y's 0.25 */
    for (size_t s = 0; s < RK; s++)
        y[s * RP + 5] = 0.25f, x[s * RP + 5] = s == 0 ? x[5] : 0.25f;
    mcstat_pixels_in px = MCSTAT_PIXELS_IN_INIT, py;
    px.type = MCSTAT_VALUE_FLOAT32;
    px.n = RK;
    px.value_stride = RP;
    px.pixel_stride = 1;
    py = px;
    px.data = x;
    py.data = y;
    mcstat_pixels_options o = MCSTAT_PIXELS_OPTIONS_INIT;
    o.flags = MCSTAT_PIXELS_RENDER | MCSTAT_ROWS_OMIT_NAN;
    static double p[2][RP], t[2][RP], df[2][RP], se[2][RP];
    static int32_t st[2][RP];
    for (int base = 0; base < 2; base++) {
        mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
        out.p_value = p[base];
        out.statistic = t[base];
        out.df = df[base];
        out.std_error = se[base];
        out.status = st[base];
        mcstat__pixels_baseline_only(base);
        mcstat_pixels_test(MCSTAT_TEST_T_2, &px, &py, 0, RP, 0.0, MCSTAT_TWO_SIDED, 0.05, &o, &out);
        mcstat__pixels_baseline_only(0);
    }
    CHECK(memcmp(p[0], p[1], sizeof p[0]) == 0 && memcmp(t[0], t[1], sizeof t[0]) == 0 &&
          memcmp(df[0], df[1], sizeof df[0]) == 0);
    const double eps = MCSTAT_RESOLUTION_FLOAT64;
    /* pixel 0: x = 0 constant; its variance d^2 (1 - pi) / pi, pi = 1 - 0.05^(1/K) */
    for (int i = 0; i < 2; i++) {
        size_t j = i == 0 ? 0 : 4;
        size_t nx = i == 0 ? RK : RK - 1;
        double my = 0.0, vy = 0.0;
        for (size_t s = 0; s < RK; s++)
            my += y[s * RP + j];
        my /= RK;
        for (size_t s = 0; s < RK; s++)
            vy += (y[s * RP + j] - my) * (y[s * RP + j] - my);
        vy /= RK - 1;
        double pi = 1.0 - pow(0.05, 1.0 / (double)nx);
        double vx = my * my * (1.0 - pi) / pi;
        double tt = -my / sqrt(vx / (double)nx + vy / RK), want_df = (double)(nx < RK ? nx : RK) - 1.0, pt;
        mcstat_t_cdf(tt, want_df, 0, &pt);
        CHECK_INT(st[0][j], MCSTAT_OK);
        CHECK_REL(t[0][j], tt, 1e-12, "pixel %zu", j);
        CHECK_REL(df[0][j], want_df, 0.0, "pixel %zu", j);
        CHECK_REL(p[0][j], 2.0 * pt, 1e-10, "pixel %zu", j);
        /* the bound: never significant alone */
        CHECK(fabs(t[0][j]) <= sqrt((double)nx * pi / (1.0 - pi)) * (1.0 + 1e-12));
    }
    /* pixel 1: one nonzero value, floored as a constant side: t = d / sqrt(d^2 r / K + vy / K) */
    {
        double mx = 5.0 / RK, my = 0.0, vy = 0.0, vx = 0.0;
        for (size_t s = 0; s < RK; s++)
            my += y[s * RP + 1];
        my /= RK;
        for (size_t s = 0; s < RK; s++) {
            vy += (y[s * RP + 1] - my) * (y[s * RP + 1] - my);
            vx += (x[s * RP + 1] - mx) * (x[s * RP + 1] - mx);
        }
        vy /= RK - 1;
        vx /= RK - 1;
        double pi = 1.0 - pow(0.05, 1.0 / RK), d = mx - my, fl = d * d * (1.0 - pi) / pi;
        double tt = d / sqrt((fl > vx ? fl : vx) / RK + vy / RK);
        CHECK_REL(t[0][1], tt, 1e-12, "pixel 1");
        CHECK_REL(df[0][1], RK - 1.0, 0.0, "pixel 1");
    }
    /* pixel 2: both sides constant and different: not a deterministic
     * difference (a light's edge at a few spp gives every seed the same
     * count by chance), both sides floored: t = d / sqrt(2 d^2 r / K),
     * never significant alone; 3 and 5: equal within the floor */
    {
        double mx = 0.0, my = 0.0;
        for (size_t s = 0; s < RK; s++)
            mx += x[s * RP + 2], my += y[s * RP + 2];
        double pi = 1.0 - pow(0.05, 1.0 / RK), r = (1.0 - pi) / pi, d = (mx - my) / RK;
        CHECK_INT(st[0][2], MCSTAT_OK);
        CHECK_REL(t[0][2], (d > 0 ? 1.0 : -1.0) / sqrt(2.0 * r / RK), 1e-12, "pixel 2");
        CHECK(p[0][2] > 0.05);
    }
    CHECK_INT(st[0][3], MCSTAT_EDEGENERATE);
    CHECK_MSG(st[0][5] == MCSTAT_EDEGENERATE, "pixel 5: status %d (x differs from y by one float ulp, eps %g)",
              st[0][5], eps);
    /* smooth pixels: Welch's t with Hsu's df K - 1 */
    for (size_t j = 6; j < RP; j++) {
        double mx = 0, my = 0, vx = 0, vy = 0;
        for (size_t s = 0; s < RK; s++)
            mx += x[s * RP + j], my += y[s * RP + j];
        mx /= RK, my /= RK;
        for (size_t s = 0; s < RK; s++)
            vx += (x[s * RP + j] - mx) * (x[s * RP + j] - mx), vy += (y[s * RP + j] - my) * (y[s * RP + j] - my);
        double tt = (mx - my) / sqrt(vx / (RK - 1) / RK + vy / (RK - 1) / RK), pt;
        mcstat_t_cdf(-fabs(tt), RK - 1.0, 0, &pt);
        CHECK_REL(t[0][j], tt, 1e-11, "pixel %zu", j);
        CHECK_REL(df[0][j], RK - 1.0, 0.0, "pixel %zu", j);
        CHECK_REL(p[0][j], 2.0 * pt, 1e-9, "pixel %zu", j);
    }
    /* without the flag: the plain Welch test (x = 0 constant is a one-sample test of y) */
    o.flags = MCSTAT_ROWS_OMIT_NAN;
    mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
    out.p_value = p[1];
    out.status = st[1];
    mcstat_pixels_test(MCSTAT_TEST_T_2, &px, &py, 0, RP, 0.0, MCSTAT_TWO_SIDED, 0.05, &o, &out);
    CHECK(p[1][0] < 1e-6 && p[0][0] > 0.05 && st[1][2] == MCSTAT_EDEGENERATE);
    o.flags = MCSTAT_PIXELS_RENDER;
    CHECK_INT(mcstat_pixels_test(MCSTAT_TEST_T_2_POOLED, &px, &py, 0, RP, 0.0, MCSTAT_TWO_SIDED, 0.05, &o, &out),
              MCSTAT_EINVAL);
    o.resolution = 1.0;
    CHECK_INT(mcstat_pixels_test(MCSTAT_TEST_T_2, &px, &py, 0, RP, 0.0, MCSTAT_TWO_SIDED, 0.05, &o, &out),
              MCSTAT_EINVAL);
}

/* The guards at the ends of the exponent range: a floor of (shift)^2 that
 * overflows unscaled, here against mu0 = -2e303.  Pixel 0: sides constant
 * at 1e-296 and 1e-149 (the statistic was inf/inf, a NaN p-value with
 * status OK; found by tests/fuzz/fuzz_pixels): t = 1 / sqrt(2 r / K)
 * whatever the scale.  Pixel 1: one nonzero value against a smooth side
 * (the fast path's floor overflowed to an infinite standard error, t = 0):
 * the same t, df and p as the data and mu0 scaled by 2^-1000. */
static void test_render_guards_extreme(void)
{
    enum { K = 4, EP = 2 };
    const double mu0 = -2e303;
    double x[K * EP], y[K * EP], xs[K * EP], ys[K * EP];
    for (size_t s = 0; s < K; s++) {
        x[s * EP + 0] = 1e-296, y[s * EP + 0] = 1e-149;
        x[s * EP + 1] = s == 2 ? 5.0 : 0.0, y[s * EP + 1] = 1.0 + 0.125 * (double)s;
    }
    for (size_t i = 0; i < K * EP; i++)
        xs[i] = ldexp(x[i], -1000), ys[i] = ldexp(y[i], -1000);
    mcstat_pixels_in px = MCSTAT_PIXELS_IN_INIT, py;
    px.type = MCSTAT_VALUE_FLOAT64;
    px.n = K;
    px.value_stride = EP;
    px.pixel_stride = 1;
    py = px;
    mcstat_pixels_options o = MCSTAT_PIXELS_OPTIONS_INIT;
    o.flags = MCSTAT_PIXELS_RENDER;
    double p[2][EP], t[2][EP], df[2][EP];
    int32_t st[2][EP];
    for (int c = 0; c < 2; c++) {
        px.data = c ? xs : x;
        py.data = c ? ys : y;
        mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
        out.p_value = p[c];
        out.statistic = t[c];
        out.df = df[c];
        out.status = st[c];
        mcstat_pixels_test(MCSTAT_TEST_T_2, &px, &py, 0, EP, c ? ldexp(mu0, -1000) : mu0, MCSTAT_TWO_SIDED, 0.05,
                           &o, &out);
    }
    double pi = 1.0 - pow(0.05, 1.0 / K), r = (1.0 - pi) / pi;
    CHECK_INT(st[0][0], MCSTAT_OK);
    CHECK_REL(t[0][0], 1.0 / sqrt(2.0 * r / K), 1e-12, "pixel 0");
    CHECK(p[0][0] > 0.05 && p[0][0] <= 1.0);
    CHECK_INT(st[0][1], MCSTAT_OK);
    CHECK_INT(st[1][1], MCSTAT_OK);
    CHECK_REL(t[0][1], t[1][1], 1e-12, "pixel 1");
    CHECK_REL(df[0][1], df[1][1], 0.0, "pixel 1");
    CHECK_REL(p[0][1], p[1][1], 1e-10, "pixel 1");
    CHECK(t[0][1] > 1.0);
}

/* The paired test under the guards, against closed forms: pixel 0 equal
 * in every seed (untested); 1 a side of zeros against a varying side (the
 * rule-of-three floor); 2 a constant nonzero difference (the same floor:
 * t = sqrt(K / r)); 3 ordinary pairs (the plain paired test, bit for bit);
 * 4 differences zero but in 3 seeds (df 2, t unchanged); 5 differences
 * within the numerical floor of values near 1e6 (untested); 6 the same as
 * 1 scaled by 2^-1000 (the same t); 7 a side zero in one seed where the
 * other is not (the rule-of-three floor). */
static void test_render_guards_paired(void)
{
    enum { K = 6, EP = 8 };
    double x[K * EP], y[K * EP];
    for (size_t s = 0; s < K; s++) {
        double u = 0.3 + 0.17 * (double)s + 0.05 * (double)(s * s % 5), w = 1.0 + 0.21 * (double)((s * 7) % 6);
        double *xs = x + s * EP, *ys = y + s * EP;
        xs[0] = ys[0] = u;
        xs[1] = u, ys[1] = 0.0;
        xs[2] = w + 0.5, ys[2] = w;
        xs[3] = w + 0.1 * u, ys[3] = u;
        xs[4] = w + (s == 1 || s == 3 || s == 4 ? 0.2 * u : 0.0), ys[4] = w;
        xs[5] = 1e6 + 1e-12 * u, ys[5] = 1e6;
        xs[6] = ldexp(u, -1000), ys[6] = 0.0;
        xs[7] = s == 0 ? 0.0 : w + 0.3, ys[7] = s == 0 ? 0.01 : w;
    }
    mcstat_pixels_in px = MCSTAT_PIXELS_IN_INIT, py;
    px.type = MCSTAT_VALUE_FLOAT64;
    px.n = K;
    px.value_stride = EP;
    px.pixel_stride = 1;
    py = px;
    px.data = x;
    py.data = y;
    mcstat_pixels_options o = MCSTAT_PIXELS_OPTIONS_INIT;
    o.flags = MCSTAT_PIXELS_RENDER;
    double p[EP], t[EP], df[EP];
    int32_t st[EP];
    mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
    out.p_value = p;
    out.statistic = t;
    out.df = df;
    out.status = st;
    /* the first failed pixel's status: pixel 0's */
    CHECK_INT(mcstat_pixels_test(MCSTAT_TEST_T_PAIRED, &px, &py, 0, EP, 0.0, MCSTAT_TWO_SIDED, 0.05, &o, &out),
              MCSTAT_EDEGENERATE);
    double pi = 1.0 - pow(0.05, 1.0 / K), r = (1.0 - pi) / pi;
    CHECK_INT(st[0], MCSTAT_EDEGENERATE);
    CHECK_INT(st[5], MCSTAT_EDEGENERATE);
    /* pixel 1: d = x; its variance floored at mean^2 r */
    double d[K], m = 0.0, v = 0.0;
    for (size_t s = 0; s < K; s++)
        m += (d[s] = x[s * EP + 1]) / K;
    for (size_t s = 0; s < K; s++)
        v += (d[s] - m) * (d[s] - m) / (K - 1);
    CHECK(m * m * r > v); /* the floor is what acts */
    CHECK_INT(st[1], MCSTAT_OK);
    CHECK_REL(t[1], m / sqrt(fmax(v, m * m * r) / K), 1e-12, "pixel 1");
    CHECK_REL(df[1], K - 1.0, 0.0, "pixel 1 df");
    CHECK_INT(st[6], MCSTAT_OK);
    CHECK_REL(t[6], t[1], 1e-12, "pixel 6");
    m = v = 0.0;
    for (size_t s = 0; s < K; s++)
        m += (d[s] = x[s * EP + 7] - y[s * EP + 7]) / K;
    for (size_t s = 0; s < K; s++)
        v += (d[s] - m) * (d[s] - m) / (K - 1);
    CHECK(m * m * r > v);
    CHECK_INT(st[7], MCSTAT_OK);
    CHECK_REL(t[7], m / sqrt(fmax(v, m * m * r) / K), 1e-12, "pixel 7");
    CHECK_INT(st[2], MCSTAT_OK);
    CHECK_REL(t[2], sqrt(K / r), 1e-12, "pixel 2");
    CHECK(p[2] > 0.05);
    /* pixels 3 and 4 against the plain paired test on their own values */
    for (size_t i = 3; i <= 4; i++) {
        double a[K], b[K];
        for (size_t s = 0; s < K; s++)
            a[s] = x[s * EP + i], b[s] = y[s * EP + i];
        mcstat_result rr;
        CHECK_INT(mcstat_t_test_paired(a, b, K, 0.0, MCSTAT_TWO_SIDED, 0.05, &rr), MCSTAT_OK);
        CHECK_INT(st[i], MCSTAT_OK);
        CHECK_REL(t[i], rr.statistic, 0.0, "pixel %zu t", i);
        CHECK_REL(df[i], i == 3 ? K - 1.0 : 2.0, 0.0, "pixel %zu df", i);
        if (i == 3)
            CHECK_REL(p[i], rr.p_value, 0.0, "pixel 3 p");
        else
            CHECK(p[i] > rr.p_value); /* fewer df: a wider null */
    }
    /* the guards stay refused by the one-sample and pooled tests */
    CHECK_INT(mcstat_pixels_test(MCSTAT_TEST_T_1, &px, NULL, 0, EP, 0.0, MCSTAT_TWO_SIDED, 0.05, &o, &out),
              MCSTAT_EINVAL);
}

int main(void)
{
    fill();
    test_structs();
    test_every_case();
    test_layouts_agree();
    test_row_lengths();
    test_variance_tails();
    test_threads();
    test_bad_arguments();
    test_render_guards();
    test_render_guards_extreme();
    test_render_guards_paired();
    return h_report("test_pixels_test");
}
