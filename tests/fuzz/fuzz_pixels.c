/*
 * fuzz_pixels.c - Welch's test per pixel on seeds-major images
 * (mcstat_t_test_2_pixels, _f32).
 *
 * Input: a selector byte (float32 or double, weights or not), pixels
 * (0..5), seeds of x and y (0..9), channels (1..3), the weights, a pixel
 * range, a flags byte (unknown bits sometimes), the images' values
 * (fz_doubles, padded with small integers), mu0, the alternative, alpha.
 * Invariants: pixel i's status is the single call's (mcstat_t_test_2 on
 * the pixel's weighted values, NaN removed first under
 * MCSTAT_ROWS_OMIT_NAN); a tested pixel's p-value agrees with it to the
 * accuracy pixels.c claims (loosened tenfold for the fuzzer's extremes),
 * its interval ordered and the single call's to 1e-12 of its scale; a failed pixel holds NaN; the
 * return value is the first failing pixel's status; invalid arguments are
 * refused with nothing written; nothing outside the range is written.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#define MAXPIX 5
#define MAXSEEDS 9
#define MAXCH 3

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    static double xd[MAXSEEDS * MAXPIX * MAXCH], yd[MAXSEEDS * MAXPIX * MAXCH];
    static float xf[MAXSEEDS * MAXPIX * MAXCH], yf[MAXSEEDS * MAXPIX * MAXCH];
    uint8_t sel = fz_u8(&in);
    int f32 = sel & 1, weighted = (sel >> 1) & 1;
    size_t pixels = (size_t)fz_range(&in, 0, MAXPIX);
    size_t nx = (size_t)fz_range(&in, 0, MAXSEEDS), ny = (size_t)fz_range(&in, 0, MAXSEEDS);
    size_t ch = weighted ? (size_t)fz_range(&in, 1, MAXCH) : 1;
    double w[MAXCH];
    for (size_t c = 0; c < ch; c++)
        w[c] = weighted ? fz_double(&in) : 1.0;
    size_t begin = (size_t)fz_range(&in, 0, MAXPIX), end = (size_t)fz_range(&in, 0, MAXPIX);
    if (end > pixels)
        end = pixels;
    uint8_t fb = fz_u8(&in);
    unsigned flags = fb < 240 ? fb % 4 : fz_u32(&in);
    size_t plane = pixels * ch, cx = nx * plane, cy = ny * plane;
    size_t k = fz_doubles(&in, xd, cx);
    for (size_t i = k; i < cx; i++)
        xd[i] = (double)(i % 7);
    k = fz_doubles(&in, yd, cy);
    for (size_t i = k; i < cy; i++)
        yd[i] = (double)(i % 5);
    for (size_t i = 0; i < cx; i++) {
        xf[i] = (float)xd[i]; /* the float images are the doubles rounded */
        if (f32)
            xd[i] = (double)xf[i];
    }
    for (size_t i = 0; i < cy; i++) {
        yf[i] = (float)yd[i];
        if (f32)
            yd[i] = (double)yf[i];
    }
    double mu0 = fz_double(&in);
    int alt = fz_alternative(&in);
    double alpha = fz_alpha(&in);
    if (fz_verbose()) {
        fz_print_doubles("x", xd, cx);
        fz_print_doubles("y", yd, cy);
        fprintf(stderr, "f32 %d weighted %d pixels %zu nx %zu ny %zu ch %zu range %zu..%zu flags %u mu0 %a alt %d "
                        "alpha %a\n", f32, weighted, pixels, nx, ny, ch, begin, end, flags, mu0, alt, alpha);
    }

    double p[MAXPIX], t[MAXPIX], df[MAXPIX], mx[MAXPIX], my[MAXPIX], lo[MAXPIX], hi[MAXPIX], se[MAXPIX];
    int32_t status[MAXPIX];
    double *arrays[8] = {p, t, df, mx, my, lo, hi, se};
    for (int a = 0; a < 8; a++)
        for (size_t i = 0; i < MAXPIX; i++)
            arrays[a][i] = -7.0;
    for (size_t i = 0; i < MAXPIX; i++)
        status[i] = -7;
    mcstat_pixels_out out = MCSTAT_PIXELS_OUT_INIT;
    out.p_value = p;
    out.statistic = t;
    out.df = df;
    out.estimate = mx;
    out.estimate2 = my;
    out.conf_lo = lo;
    out.conf_hi = hi;
    out.status = status;
    out.std_error = se;
    const double *wp = weighted ? w : NULL;
    int st = f32 ? mcstat_t_test_2_pixels_f32(xf, nx, plane, yf, ny, plane, ch, wp, begin, end, mu0, alt, alpha,
                                              flags, &out)
                 : mcstat_t_test_2_pixels(xd, nx, plane, yd, ny, plane, ch, wp, begin, end, mu0, alt, alpha, flags,
                                          &out);
    fz_check_status(st);
    FZ_IEEE_SCOPE(); /* the reference below in the library's arithmetic */
    int bad_w = 0;
    for (size_t c = 0; c < ch && weighted; c++)
        bad_w |= !isfinite(w[c]);
    int invalid = end < begin || bad_w || !isfinite(mu0) || !fz_alpha_valid(alpha) ||
                  (alt != MCSTAT_TWO_SIDED && alt != MCSTAT_LESS && alt != MCSTAT_GREATER) ||
                  (flags & ~(unsigned)(MCSTAT_ROWS_NO_INTERVALS | MCSTAT_ROWS_OMIT_NAN | MCSTAT_PIXELS_RENDER));
    int written = 0;
    for (size_t i = 0; i < MAXPIX; i++)
        written |= status[i] != -7 || p[i] != -7.0;
    if (invalid) {
        FZ_ASSERT(st == MCSTAT_EINVAL, "invalid arguments: status %d", st);
        FZ_ASSERT(!written, "invalid arguments: outputs written");
        return 0;
    }
    if (flags & MCSTAT_PIXELS_RENDER) {
        fz_check_render_pixels(status, p, MAXPIX, begin, end);
        return 0;
    }
    int first = MCSTAT_OK, intervals = !(flags & MCSTAT_ROWS_NO_INTERVALS);
    for (size_t i = 0; i < MAXPIX; i++) {
        if (i < begin || i >= end) {
            FZ_ASSERT(status[i] == -7 && p[i] == -7.0 && lo[i] == -7.0, "pixel %zu outside the range written", i);
            continue;
        }
        double sx[MAXSEEDS], sy[MAXSEEDS];
        size_t kx = 0, ky = 0;
        for (int side = 0; side < 2; side++) {
            const double *img = side ? yd : xd;
            size_t n = side ? ny : nx;
            for (size_t s = 0; s < n; s++) {
                double v;
                if (!weighted) {
                    v = img[s * plane + i];
                } else {
                    v = 0.0;
                    for (size_t c = 0; c < ch; c++)
                        v += w[c] * img[s * plane + i * ch + c];
                }
                if ((flags & MCSTAT_ROWS_OMIT_NAN) && isnan(v))
                    continue;
                if (side)
                    sy[ky++] = v;
                else
                    sx[kx++] = v;
            }
        }
        mcstat_result r;
        int si = mcstat_t_test_2(sx, kx, sy, ky, mu0, alt, alpha, &r);
        if (first == MCSTAT_OK)
            first = si;
        FZ_ASSERT(status[i] == si, "pixel %zu: status %d, single call %d", i, status[i], si);
        if (si != MCSTAT_OK) {
            FZ_ASSERT(isnan(p[i]) && isnan(t[i]) && isnan(df[i]) && isnan(mx[i]) && isnan(lo[i]) && isnan(hi[i]),
                      "pixel %zu failed but p %.17g", i, p[i]);
            continue;
        }
        double tol = 10.0 * (3e-14 + 4e-16 * fabs(log(fmax(r.p_value, DBL_MIN))));
        FZ_ASSERT(fabs(p[i] - r.p_value) <= tol * r.p_value || (r.p_value < 1e-290 && p[i] < 1e-280),
                  "pixel %zu: p %.17g, single call %.17g", i, p[i], r.p_value);
        FZ_ASSERT(p[i] >= 0.0 && p[i] <= 1.0 && df[i] > 0.0, "pixel %zu: p %.17g df %.17g", i, p[i], df[i]);
        if (intervals) {
            FZ_ASSERT(!(lo[i] > hi[i]) && !isnan(lo[i]) && !isnan(hi[i]), "pixel %zu: interval [%.17g, %.17g]", i,
                      lo[i], hi[i]);
            /* the single call's interval, to 1e-12 of its width, its bounds'
             * size or the standard error */
            double a = r.conf_int[0], b = r.conf_int[1];
            double sc = fmax(isfinite(b - a) ? b - a : 0.0, fmax(isfinite(a) ? fabs(a) : 0.0, isfinite(b) ? fabs(b) : 0.0));
            sc = fmax(sc, r.std_error);
            FZ_ASSERT((lo[i] == a || fabs(lo[i] - a) <= 1e-12 * sc) && (hi[i] == b || fabs(hi[i] - b) <= 1e-12 * sc),
                      "pixel %zu: interval [%.17g, %.17g], single call [%.17g, %.17g]", i, lo[i], hi[i], a, b);
        }
        else
            FZ_ASSERT(isnan(lo[i]) && isnan(hi[i]), "pixel %zu: intervals computed without being asked", i);
    }
    FZ_ASSERT(st == first, "status %d, first failing pixel %d", st, first);
    return 0;
}
