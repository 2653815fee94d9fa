/*
 * fuzz_rows.c - the row-wise tests (mcstat_*_test_*_rows).
 *
 * Input: a selector byte, rows (0..6), row lengths (0..12), strides (the
 * length plus 0..3), a flags byte (unknown bits sometimes), the matrices'
 * values (fz_doubles, padded with small integers), the null value, the
 * alternative, alpha.  Invariants: row i's status and result are bit for
 * bit the single-sample call on row i (NaN removed first under
 * MCSTAT_ROWS_OMIT_NAN; without intervals, the same p-value, statistic,
 * reject and decision, and NaN critical values and intervals); a failed
 * row holds NaN fields; the return value is the first failing row's
 * status; unknown flags are refused with nothing written.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "fuzz_check.h"
#include "fuzz_input.h"

#define MAXROWS 6
#define MAXLEN 12
#define MAXSTRIDE (MAXLEN + 3)

static const int TEST_KIND[4] = {MCSTAT_TEST_T_1, MCSTAT_TEST_T_2, MCSTAT_TEST_VAR_1, MCSTAT_TEST_VAR_2};

static void fill(fz_input *in, double *m, size_t count)
{
    size_t k = fz_doubles(in, m, count);
    for (size_t i = k; i < count; i++)
        m[i] = (double)(i % 7);
}

/* The row without its NaN when asked; returns its length. */
static size_t row_copy(const double *row, size_t n, unsigned flags, double *dst)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (!((flags & MCSTAT_ROWS_OMIT_NAN) && isnan(row[i])))
            dst[k++] = row[i];
    return k;
}

static int single(int which, const double *x, size_t nx, const double *y, size_t ny, double v, int alt,
                  double alpha, mcstat_result *r)
{
    mcstat_moments mx, my;
    mcstat_moments_init(&mx);
    mcstat_moments_init(&my);
    int st = mcstat_moments_add_array(&mx, x, nx);
    if (!st && (which & 1))
        st = mcstat_moments_add_array(&my, y, ny);
    if (st)
        return st;
    switch (which) {
    case 0: return mcstat_t_test_1_moments(&mx, v, alt, alpha, r);
    case 1: return mcstat_t_test_2_moments(&mx, &my, v, alt, alpha, r);
    case 2: return mcstat_var_test_1_moments(&mx, v, alt, alpha, r);
    default: return mcstat_var_test_2_moments(&mx, &my, v, alt, alpha, r);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fz_input in = fz_make(data, size);
    static double x[MAXROWS * MAXSTRIDE], y[MAXROWS * MAXSTRIDE];
    int which = fz_u8(&in) % 4;
    size_t rows = (size_t)fz_range(&in, 0, MAXROWS);
    size_t nx = (size_t)fz_range(&in, 0, MAXLEN), ny = (size_t)fz_range(&in, 0, MAXLEN);
    size_t sx = nx + (size_t)fz_range(&in, 0, 3), sy = ny + (size_t)fz_range(&in, 0, 3);
    uint8_t fb = fz_u8(&in);
    unsigned flags = fb < 240 ? fb % 4 : fz_u32(&in);
    fill(&in, x, rows * sx);
    fill(&in, y, rows * sy);
    double v = fz_double(&in);
    int alt = fz_alternative(&in);
    double alpha = fz_alpha(&in);
    int with_status = fz_bool(&in);
    if (fz_verbose()) {
        fz_print_doubles("x", x, rows * sx);
        fz_print_doubles("y", y, rows * sy);
        fprintf(stderr, "which %d rows %zu nx %zu sx %zu ny %zu sy %zu flags %u null %a alt %d alpha %a\n", which,
                rows, nx, sx, ny, sy, flags, v, alt, alpha);
    }

    mcstat_result out[MAXROWS], keep[MAXROWS];
    int32_t status[MAXROWS];
    memset(out, 0x3c, sizeof out);
    memcpy(keep, out, sizeof out);
    for (size_t i = 0; i < MAXROWS; i++)
        status[i] = -7;
    int32_t *sp = with_status ? status : NULL;
    int st;
    switch (which) {
    case 0: st = mcstat_t_test_1_matrix(x, nx, sx, rows, v, alt, alpha, flags, out, sp); break;
    case 1: st = mcstat_t_test_2_matrix(x, nx, sx, y, ny, sy, rows, v, alt, alpha, flags, out, sp); break;
    case 2: st = mcstat_var_test_1_matrix(x, nx, sx, rows, v, alt, alpha, flags, out, sp); break;
    default: st = mcstat_var_test_2_matrix(x, nx, sx, y, ny, sy, rows, v, alt, alpha, flags, out, sp); break;
    }
    fz_check_status(st);
    if (flags & ~(MCSTAT_ROWS_NO_INTERVALS | MCSTAT_ROWS_OMIT_NAN)) {
        FZ_ASSERT(st == MCSTAT_EINVAL, "unknown flags %#x: status %d", flags, st);
        FZ_ASSERT(memcmp(out, keep, sizeof out) == 0, "unknown flags: out written");
        return 0;
    }
    int first = MCSTAT_OK;
    unsigned cflags = (flags & MCSTAT_ROWS_NO_INTERVALS) ? FZ_NO_INTERVALS : 0;
    for (size_t i = 0; i < rows; i++) {
        double rx[MAXLEN], ry[MAXLEN];
        size_t kx = row_copy(x + i * sx, nx, flags, rx), ky = row_copy(y + i * sy, ny, flags, ry);
        mcstat_result r;
        int si = single(which, rx, kx, ry, ky, v, alt, alpha, &r);
        if (first == MCSTAT_OK)
            first = si;
        if (with_status)
            FZ_ASSERT(status[i] == si, "row %zu: status %d, single call %d", i, status[i], si);
        fz_check_result(si, &out[i], TEST_KIND[which], alt, alpha, cflags);
        fz_check_not_enumeric(si, (double)(kx + ky), "row test");
        if (si != MCSTAT_OK) {
            FZ_ASSERT(isnan(out[i].p_value) && isnan(out[i].statistic), "row %zu failed but p %.17g", i,
                      out[i].p_value);
            continue;
        }
        if (!(flags & MCSTAT_ROWS_NO_INTERVALS)) {
            FZ_ASSERT(memcmp(&out[i], &r, sizeof r) == 0, "row %zu differs from the single call", i);
        } else {
            FZ_ASSERT(out[i].p_value == r.p_value && out[i].reject == r.reject && out[i].decision == r.decision &&
                          memcmp(&out[i].statistic, &r.statistic, sizeof r.statistic) == 0,
                      "row %zu (no intervals): p %.17g, single %.17g", i, out[i].p_value, r.p_value);
            FZ_ASSERT(isnan(out[i].critical[0]) && isnan(out[i].critical[1]) && isnan(out[i].conf_int[0]) &&
                          isnan(out[i].conf_int[1]),
                      "row %zu: intervals computed without being asked", i);
        }
    }
    FZ_ASSERT(st == first, "status %d, first failing row %d", st, first);
    for (size_t i = rows; i < MAXROWS; i++)
        FZ_ASSERT(memcmp(&out[i], &keep[i], sizeof out[i]) == 0 && status[i] == -7, "row %zu beyond rows written",
                  i);
    return 0;
}
