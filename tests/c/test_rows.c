/*
 * test_rows.c - the row-wise tests: every row bit for bit the single-sample
 * call (with quantiles reused across rows of equal df), failed rows reported
 * and cleared without stopping the others, the flags.
 */
#include "harness.h"
#include "mcstat.h"

#include <stdlib.h>
#include <string.h>

#define ROWS 40
#define NX 17
#define NY 23
#define SX 20 /* row strides larger than the rows */
#define SY 25

static double urand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1p-53;
}

static double x[ROWS * SX], y[ROWS * SY];

static void fill(void)
{
    unsigned long long s = 12345;
    for (int i = 0; i < ROWS * SX; i++)
        x[i] = (urand(&s) - 0.5) * (1 + i / SX % 5) + 1e3 * (i / SX % 3);
    for (int i = 0; i < ROWS * SY; i++)
        y[i] = (urand(&s) - 0.4) * (1 + i / SY % 7);
    /* bad rows: NaN in row 3 of x, constant row 5 of x, Inf in row 7 of y */
    x[3 * SX + 4] = NAN;
    for (int k = 0; k < NX; k++)
        x[5 * SX + k] = 2.5;
    y[7 * SY + 1] = INFINITY;
}

static int same(const mcstat_result *a, const mcstat_result *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

static void test_rows_match_single_calls(void)
{
    static mcstat_result out[ROWS];
    int32_t status[ROWS];
    for (int alt = 0; alt < 3; alt++) {
        /* one-sample t: equal df, so the quantiles are solved once and reused */
        int st = mcstat_t_test_1_matrix(x, NX, SX, ROWS, 0.1, alt, 0.05, 0, out, status);
        CHECK_INT(st, MCSTAT_ENONFINITE); /* the first failing row is row 3 */
        for (int i = 0; i < ROWS; i++) {
            mcstat_result r;
            int s1 = mcstat_t_test_1(x + i * SX, NX, 0.1, alt, 0.05, &r);
            CHECK_INT(status[i], s1);
            if (s1 == MCSTAT_OK)
                CHECK_MSG(same(&out[i], &r), "t_1 row %d alt %d", i, alt);
            else
                CHECK(isnan(out[i].p_value) && isnan(out[i].statistic));
        }
        CHECK_INT(status[5], MCSTAT_EDEGENERATE);

        st = mcstat_t_test_2_matrix(x, NX, SX, y, NY, SY, ROWS, -0.2, alt, 0.1, 0, out, status);
        CHECK_INT(st, MCSTAT_ENONFINITE);
        for (int i = 0; i < ROWS; i++) {
            mcstat_result r;
            int s1 = mcstat_t_test_2(x + i * SX, NX, y + i * SY, NY, -0.2, alt, 0.1, &r);
            CHECK_INT(status[i], s1);
            if (s1 == MCSTAT_OK)
                CHECK_MSG(same(&out[i], &r), "t_2 row %d alt %d", i, alt);
        }
        CHECK_INT(status[5], MCSTAT_OK); /* Welch needs spread in one sample only */
        CHECK_INT(status[7], MCSTAT_ENONFINITE);

        st = mcstat_var_test_1_matrix(x, NX, SX, ROWS, 0.3, alt, 0.05, 0, out, status);
        for (int i = 0; i < ROWS; i++) {
            mcstat_result r;
            int s1 = mcstat_var_test_1(x + i * SX, NX, 0.3, alt, 0.05, &r);
            CHECK_INT(status[i], s1);
            if (s1 == MCSTAT_OK)
                CHECK_MSG(same(&out[i], &r), "var_1 row %d alt %d", i, alt);
        }
        st = mcstat_var_test_2_matrix(x, NX, SX, y, NY, SY, ROWS, 1.5, alt, 0.01, 0, out, status);
        for (int i = 0; i < ROWS; i++) {
            mcstat_result r;
            int s1 = mcstat_var_test_2(x + i * SX, NX, y + i * SY, NY, 1.5, alt, 0.01, &r);
            CHECK_INT(status[i], s1);
            if (s1 == MCSTAT_OK)
                CHECK_MSG(same(&out[i], &r), "var_2 row %d alt %d", i, alt);
        }
    }
}

static void test_flags(void)
{
    static mcstat_result a[ROWS], b[ROWS];
    int32_t status[ROWS];
    mcstat_t_test_2_matrix(x, NX, SX, y, NY, SY, ROWS, 0.0, MCSTAT_TWO_SIDED, 0.05, 0, a, NULL);
    mcstat_t_test_2_matrix(x, NX, SX, y, NY, SY, ROWS, 0.0, MCSTAT_TWO_SIDED, 0.05, MCSTAT_ROWS_NO_INTERVALS, b,
                         status);
    for (int i = 0; i < ROWS; i++) {
        if (status[i])
            continue;
        CHECK(a[i].p_value == b[i].p_value && a[i].statistic == b[i].statistic && a[i].df[0] == b[i].df[0]);
        CHECK(a[i].reject == b[i].reject && a[i].decision == b[i].decision);
        CHECK(isnan(b[i].critical[0]) && isnan(b[i].critical[1]));
        CHECK(isnan(b[i].conf_int[0]) && isnan(b[i].conf_int[1]));
        CHECK(isfinite(a[i].conf_int[0]));
    }
    /* NaN omitted: row 3 becomes a test on its other NX - 1 values */
    mcstat_t_test_1_matrix(x, NX, SX, ROWS, 0.0, MCSTAT_TWO_SIDED, 0.05, MCSTAT_ROWS_OMIT_NAN, a, status);
    CHECK_INT(status[3], MCSTAT_OK);
    CHECK_INT(a[3].n[0], NX - 1);
    double clean[NX];
    int k = 0;
    for (int j = 0; j < NX; j++)
        if (!isnan(x[3 * SX + j]))
            clean[k++] = x[3 * SX + j];
    mcstat_result r;
    mcstat_t_test_1(clean, (size_t)k, 0.0, MCSTAT_TWO_SIDED, 0.05, &r);
    CHECK(same(&a[3], &r));
    /* bad arguments touch nothing */
    CHECK_INT(mcstat_t_test_1_matrix(NULL, NX, SX, 3, 0.0, 0, 0.05, 0, a, status), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_1_matrix(x, NX, SX, 3, 0.0, 0, 0.05, 64u, a, status), MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_1_matrix(x, NX, SX, 0, 0.0, 0, 0.05, 0, NULL, NULL), MCSTAT_OK);
    /* per-row argument errors are row statuses */
    CHECK_INT(mcstat_t_test_1_matrix(x, NX, SX, 2, 0.0, 0, 1.5, 0, a, status), MCSTAT_EINVAL);
    CHECK_INT(status[1], MCSTAT_EINVAL);
    CHECK_INT(mcstat_t_test_1_matrix(x, 1, SX, 2, 0.0, 0, 0.05, 0, a, status), MCSTAT_ETOOFEW);
}

int main(void)
{
    fill();
    test_rows_match_single_calls();
    test_flags();
    return h_report("test_rows");
}
