/*
 * fuzz_pixels_test.c - mcstat_pixels_test: every test, both layouts,
 * float32 or double, channel weights, threads.
 *
 * Input: a selector byte (the test, one of six or an unknown one; float32;
 * rows or seeds-major layout; weighted), pixels (0..5), values of x and y
 * (0..9; the paired test takes x's unless the selector asks for unequal
 * sizes), channels (1..3), the weights, a pixel range, a flags byte
 * (unknown bits sometimes), a threads byte (0 and 65 are invalid), the
 * values (fz_doubles, padded with small integers), the null value, the
 * alternative, alpha.
 * Invariants: invalid arguments are refused with nothing written; pixel i's
 * status is the single call's on its values (NaN left out under
 * MCSTAT_ROWS_OMIT_NAN); a tested pixel's p-value is the single call's bit
 * for bit (every test but Welch's: these small calls never use the
 * variance tests' table), Welch's to ten times the bound of mcstat.h; a
 * failed pixel holds NaN, decision 0; the return value is the first
 * failing pixel's status; nothing outside the range is written.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#define MAXPIX 5
#define MAXN 9
#define MAXCH 3
#define SLOTS (MAXN * MAXPIX * MAXCH)

static const int TESTS[8] = {MCSTAT_TEST_T_1,      MCSTAT_TEST_T_2,   MCSTAT_TEST_T_2_POOLED, MCSTAT_TEST_T_PAIRED,
                             MCSTAT_TEST_VAR_1,    MCSTAT_TEST_VAR_2, 0,                      99};

/* element of value s of pixel i, channel c */
static size_t at(int rows, size_t n, size_t pixels, size_t ch, size_t s, size_t i, size_t c)
{
    return rows ? (i * n + s) * ch + c : (s * pixels + i) * ch + c;
}

static size_t sample(const double *d, int rows, size_t n, size_t pixels, size_t ch, const double *w, size_t i,
                     double *out)
{
    for (size_t s = 0; s < n; s++) {
        double v = 0.0;
        if (!w)
            v = d[at(rows, n, pixels, ch, s, i, 0)];
        else
            for (size_t c = 0; c < ch; c++)
                v += w[c] * d[at(rows, n, pixels, ch, s, i, c)];
        out[s] = v;
    }
    return n;
}

static int reference(int test, double *vx, size_t nx, double *vy, size_t ny, double nv, int alt, double alpha,
                     unsigned flags, mcstat_result *r)
{
    int32_t st = MCSTAT_OK;
    mcstat_moments mx, my;
    int omit = (flags & MCSTAT_ROWS_OMIT_NAN) != 0;
    unsigned f = flags & (MCSTAT_ROWS_NO_INTERVALS | MCSTAT_ROWS_OMIT_NAN);
    switch (test) {
    case MCSTAT_TEST_T_1: (void)mcstat_t_test_1_matrix(vx, nx, 0, 1, nv, alt, alpha, f, r, &st); return st;
    case MCSTAT_TEST_T_2: (void)mcstat_t_test_2_matrix(vx, nx, 0, vy, ny, 0, 1, nv, alt, alpha, f, r, &st); return st;
    case MCSTAT_TEST_VAR_1: (void)mcstat_var_test_1_matrix(vx, nx, 0, 1, nv, alt, alpha, f, r, &st); return st;
    case MCSTAT_TEST_VAR_2: (void)mcstat_var_test_2_matrix(vx, nx, 0, vy, ny, 0, 1, nv, alt, alpha, f, r, &st); return st;
    case MCSTAT_TEST_T_2_POOLED:
        mcstat_moments_init(&mx);
        mcstat_moments_init(&my);
        st = omit ? mcstat_moments_add_array_omit_nan(&mx, vx, nx, NULL) : mcstat_moments_add_array(&mx, vx, nx);
        if (!st)
            st = omit ? mcstat_moments_add_array_omit_nan(&my, vy, ny, NULL) : mcstat_moments_add_array(&my, vy, ny);
        return st ? st : mcstat_t_test_2_pooled_moments(&mx, &my, nv, alt, alpha, r);
    default: {
        size_t k = 0;
        for (size_t s = 0; s < nx; s++)
            if (!omit || (!isnan(vx[s]) && !isnan(vy[s]))) {
                vx[k] = vx[s];
                vy[k] = vy[s];
                k++;
            }
        return mcstat_t_test_paired(vx, vy, k, nv, alt, alpha, r);
    }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    static double xd[SLOTS], yd[SLOTS];
    static float xf[SLOTS], yf[SLOTS];
    uint8_t sel = fz_u8(&in);
    int test = TESTS[sel & 7], f32 = (sel >> 3) & 1, rows = (sel >> 4) & 1, weighted = (sel >> 5) & 1;
    int unequal = (sel >> 6) & 1;
    int two = test == MCSTAT_TEST_T_2 || test == MCSTAT_TEST_T_2_POOLED || test == MCSTAT_TEST_T_PAIRED ||
              test == MCSTAT_TEST_VAR_2;
    size_t pixels = (size_t)fz_range(&in, 0, MAXPIX);
    size_t nx = (size_t)fz_range(&in, 0, MAXN), ny = (size_t)fz_range(&in, 0, MAXN);
    if (test == MCSTAT_TEST_T_PAIRED && !unequal)
        ny = nx;
    size_t ch = weighted ? (size_t)fz_range(&in, 1, MAXCH) : 1;
    double w[MAXCH];
    for (size_t c = 0; c < ch; c++)
        w[c] = weighted ? fz_double(&in) : 1.0;
    size_t begin = (size_t)fz_range(&in, 0, MAXPIX), end = (size_t)fz_range(&in, 0, MAXPIX);
    if (end > pixels)
        end = pixels;
    uint8_t fb = fz_u8(&in);
    unsigned flags = fb < 240 ? fb % 4 : fz_u32(&in);
    uint8_t tb = fz_u8(&in);
    int threads = tb < 250 ? 1 + tb % 3 : tb == 250 ? 0 : 65;
    size_t cx = nx * pixels * ch, cy = ny * pixels * ch;
    size_t k = fz_doubles(&in, xd, cx);
    for (size_t i = k; i < cx; i++)
        xd[i] = (double)(i % 7);
    k = fz_doubles(&in, yd, cy);
    for (size_t i = k; i < cy; i++)
        yd[i] = (double)(i % 5);
    for (size_t i = 0; i < cx; i++) {
        xf[i] = (float)xd[i];
        if (f32)
            xd[i] = (double)xf[i];
    }
    for (size_t i = 0; i < cy; i++) {
        yf[i] = (float)yd[i];
        if (f32)
            yd[i] = (double)yf[i];
    }
    double nv = fz_double(&in);
    int alt = fz_alternative(&in);
    double alpha = fz_alpha(&in);
    if (fz_verbose())
        fprintf(stderr, "test %d f32 %d rows %d weighted %d pixels %zu nx %zu ny %zu ch %zu range %zu..%zu flags %u "
                        "threads %d null %a alt %d alpha %a\n", test, f32, rows, weighted, pixels, nx, ny, ch, begin,
                end, flags, threads, nv, alt, alpha);

    mcstat_pixels_in px = MCSTAT_PIXELS_IN_INIT, py = MCSTAT_PIXELS_IN_INIT;
    px.type = py.type = f32 ? MCSTAT_VALUE_FLOAT32 : MCSTAT_VALUE_FLOAT64;
    px.data = f32 ? (const void *)xf : (const void *)xd;
    py.data = f32 ? (const void *)yf : (const void *)yd;
    px.n = nx;
    py.n = ny;
    px.value_stride = rows ? ch : pixels * ch;
    px.pixel_stride = rows ? nx * ch : ch;
    py.value_stride = rows ? ch : pixels * ch;
    py.pixel_stride = rows ? ny * ch : ch;
    px.channels = py.channels = ch;
    px.weights = py.weights = weighted ? w : NULL;
    mcstat_pixels_options opt = MCSTAT_PIXELS_OPTIONS_INIT;
    opt.flags = flags;
    opt.threads = threads;
    double p[MAXPIX], lo[MAXPIX];
    int32_t status[MAXPIX];
    int8_t dec[MAXPIX];
    for (size_t i = 0; i < MAXPIX; i++) {
        p[i] = lo[i] = -7.0;
        status[i] = -7;
        dec[i] = -7;
    }
    mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
    out.p_value = p;
    out.conf_lo = lo;
    out.status = status;
    out.decision = dec;
    int st = mcstat_pixels_test(test, &px, two ? &py : NULL, begin, end, nv, alt, alpha, &opt, &out);
    fz_check_status(st);
    FZ_IEEE_SCOPE(); /* the reference below in the library's arithmetic */
    int bad_w = 0;
    for (size_t c = 0; c < ch && weighted; c++)
        bad_w |= !isfinite(w[c]);
    int is_var = test == MCSTAT_TEST_VAR_1 || test == MCSTAT_TEST_VAR_2;
    int invalid = test == 0 || test == 99 || end < begin || bad_w || !isfinite(nv) || (is_var && !(nv > 0.0)) ||
                  !fz_alpha_valid(alpha) || (alt != MCSTAT_TWO_SIDED && alt != MCSTAT_LESS && alt != MCSTAT_GREATER) ||
                  (flags & ~(unsigned)(MCSTAT_ROWS_NO_INTERVALS | MCSTAT_ROWS_OMIT_NAN | MCSTAT_PIXELS_RENDER)) ||
                  ((flags & MCSTAT_PIXELS_RENDER) && test != MCSTAT_TEST_T_2 && test != MCSTAT_TEST_T_PAIRED) || threads < 1 || threads > 64 ||
                  (test == MCSTAT_TEST_T_PAIRED && nx != ny);
    int written = 0;
    for (size_t i = 0; i < MAXPIX; i++)
        written |= status[i] != -7 || p[i] != -7.0 || dec[i] != -7;
    if (invalid) {
        FZ_ASSERT(st == MCSTAT_EINVAL, "invalid arguments: status %d", st);
        FZ_ASSERT(!written, "invalid arguments: outputs written");
        return 0;
    }
    if (flags & MCSTAT_PIXELS_RENDER) {
        fz_check_render_pixels(status, p, MAXPIX, begin, end);
        return 0;
    }
    int first = MCSTAT_OK;
    for (size_t i = 0; i < MAXPIX; i++) {
        if (i < begin || i >= end) {
            FZ_ASSERT(status[i] == -7 && p[i] == -7.0 && lo[i] == -7.0, "pixel %zu outside the range written", i);
            continue;
        }
        double vx[MAXN], vy[MAXN];
        sample(xd, rows, nx, pixels, ch, weighted ? w : NULL, i, vx);
        if (two)
            sample(yd, rows, ny, pixels, ch, weighted ? w : NULL, i, vy);
        mcstat_result r;
        int want = reference(test, vx, nx, vy, ny, nv, alt, alpha, flags, &r);
        if (first == MCSTAT_OK)
            first = want;
        FZ_ASSERT(status[i] == want, "pixel %zu: status %d, the single call's %d", i, (int)status[i], want);
        if (want != MCSTAT_OK) {
            FZ_ASSERT(isnan(p[i]) && isnan(lo[i]) && dec[i] == 0, "failed pixel %zu: outputs not NaN", i);
            continue;
        }
        if (test == MCSTAT_TEST_T_2 || is_var) {
            /* the block paths (Welch's, the variance tests' table of tails) are held
             * to the bound of mcstat.h, not to the bit; 10x it leaves room for the
             * harness's extreme inputs */
            double tol = 10.0 * (3e-14 + 4e-16 * fabs(log(fmax(r.p_value, 1e-300))));
            FZ_ASSERT(fabs(p[i] - r.p_value) <= tol * r.p_value || (r.p_value < 1e-300 && p[i] < 1e-290),
                      "pixel %zu: p %a, the single call's %a", i, p[i], r.p_value);
            FZ_ASSERT(dec[i] == r.decision || fabs(r.p_value - alpha) <= tol * alpha,
                      "pixel %zu: decision %d, the single call's %d", i, dec[i], r.decision);
        } else {
            FZ_ASSERT(memcmp(&p[i], &r.p_value, sizeof p[i]) == 0, "pixel %zu: p %a, the single call's %a", i, p[i],
                      r.p_value);
            FZ_ASSERT(dec[i] == r.decision, "pixel %zu: decision %d, the single call's %d", i, dec[i], r.decision);
        }
    }
    FZ_ASSERT(st == first, "returned %d, the first failing pixel's %d", st, first);
    return 0;
}
