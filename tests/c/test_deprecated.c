/*
 * test_deprecated.c - the names this release replaced still link against the
 * shared library (as a binary built against 0.1.0 sees it) and give results
 * bit for bit those of their replacements.
 */
#define MCSTAT_DISABLE_DEPRECATE_WARNINGS /* this test calls them on purpose */
#include "harness.h"
#include "mcstat.h"

#include <string.h>

#define ROWS 6
#define N 9
#define STRIDE 11

static double urand(unsigned long long *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1p-53;
}

static int same_results(const mcstat_result *a, const mcstat_result *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

/* The renderer checks' constants under their old names: the same values. */
static void test_check_constants(void)
{
    CHECK(MCSTAT_DOMAIN_SPHERE == MCSTAT_CHECK_DOMAIN_SPHERE && MCSTAT_DOMAIN_HEMISPHERE == MCSTAT_CHECK_DOMAIN_HEMISPHERE);
    CHECK(MCSTAT_DOMAIN_SQUARE == MCSTAT_CHECK_DOMAIN_SQUARE && MCSTAT_DOMAIN_DISK == MCSTAT_CHECK_DOMAIN_DISK);
    CHECK(MCSTAT_DOMAIN_INTERVAL == MCSTAT_CHECK_DOMAIN_INTERVAL);
    CHECK(MCSTAT_WEIGHT_OVER_PDF == MCSTAT_CHECK_WEIGHT_OVER_PDF && MCSTAT_WEIGHT_VALUE == MCSTAT_CHECK_WEIGHT_VALUE);
    CHECK(MCSTAT_ROUTE_RAN == MCSTAT_CHECK_STATE_RAN && MCSTAT_ROUTE_SKIPPED == MCSTAT_CHECK_STATE_SKIPPED);
    CHECK(MCSTAT_ROUTE_INVALID == MCSTAT_CHECK_STATE_INVALID);
}

static void test_sizes(void)
{
    /* 0.1.0's options name, as typedef and as struct tag (source code of
     * either form still compiles) */
    struct mcstat_chisq_options tagged;
    mcstat_chisq_options typed;
    CHECK(sizeof tagged == sizeof(mcstat_gof_options) && sizeof typed == sizeof(mcstat_gof_options));
    CHECK(mcstat_moments_bytes() == mcstat_sizeof_moments_bytes());
    CHECK(mcstat_sizeof_moments_bytes() == MCSTAT_MOMENTS_BYTES);
    CHECK(mcstat_sizeof_chisq_options() == mcstat_sizeof_gof_options());
    CHECK(mcstat_chisq_default_min_expected() == mcstat_gof_default_min_expected());
}

static void test_diag(void)
{
    static double x[500];
    unsigned long long s = 7;
    for (int i = 0; i < 500; i++)
        x[i] = -log(urand(&s) + 1e-300);
    mcstat_diagnostics a, b;
    memset(&a, 0x55, sizeof a);
    memset(&b, 0x55, sizeof b);
    CHECK_INT(mcstat_diagnose(x, 500, NULL, &a), MCSTAT_OK);
    CHECK_INT(mcstat_diag_compute(x, 500, NULL, &b), MCSTAT_OK);
    CHECK(memcmp(&a, &b, sizeof a) == 0);
    double ia[2], ib[2], sa[2], sb[2];
    CHECK_INT(mcstat_tail_index(x, 500, 0, ia), MCSTAT_OK);
    CHECK_INT(mcstat_diag_tail_index(x, 500, 0, ib), MCSTAT_OK);
    CHECK(memcmp(ia, ib, sizeof ia) == 0);
    CHECK_INT(mcstat_t_size_edgeworth(2.0, 6.0, 4, 30, 0.05, sa), MCSTAT_OK);
    CHECK_INT(mcstat_diag_t_size(2.0, 6.0, 4, 30, 0.05, sb), MCSTAT_OK);
    CHECK(memcmp(sa, sb, sizeof sa) == 0);
    uint64_t ka = 0, kb = 1;
    CHECK_INT(mcstat_batch_size_recommend(2.0, 6.0, 30, 0.05, 0.2, &ka), MCSTAT_OK);
    CHECK_INT(mcstat_diag_batch_size(2.0, 6.0, 30, 0.05, 0.2, &kb), MCSTAT_OK);
    CHECK(ka == kb);
    /* a statuses too */
    CHECK_INT(mcstat_diagnose(NULL, 500, NULL, &a), mcstat_diag_compute(NULL, 500, NULL, &b));
}

static void test_gof(void)
{
    const double obs[5] = {12, 30, 18, 25, 15}, p[5] = {0.1, 0.3, 0.2, 0.25, 0.15};
    mcstat_chisq_options oo;
    mcstat_gof_options no;
    CHECK_INT(mcstat_chisq_options_init_size(&oo, sizeof oo), MCSTAT_OK);
    CHECK_INT(mcstat_gof_options_init_size(&no, sizeof no), MCSTAT_OK);
    CHECK(memcmp(&oo, &no, sizeof oo) == 0);
    CHECK_INT((mcstat_chisq_options_init)(NULL), MCSTAT_EINVAL);
    CHECK_INT((mcstat_chisq_options_init)(&oo), MCSTAT_OK);
    CHECK(memcmp(&oo, &no, MCSTAT_GOF_OPTIONS_SIZE_0_1) == 0);
    mcstat_result a, b;
    CHECK_INT(mcstat_chisq_gof(obs, p, 5, &oo, 0.05, &a), MCSTAT_OK);
    CHECK_INT(mcstat_gof_chisq_test(obs, p, 5, &no, 0.05, &b), MCSTAT_OK);
    CHECK(same_results(&a, &b, 1));
    CHECK(a.test == MCSTAT_TEST_CHISQ_GOF && a.p_value > 0.0 && a.p_value < 1.0);
}

static void test_seq(void)
{
    const double x[5] = {1.0, 2.5, 3.0, 4.5, 2.0}, y[4] = {0.5, 1.5, 1.0, 2.0};
    mcstat_seq a, b;
    mcstat_result ra, rb;
    mcstat_moments mx, my;
    mcstat_moments_init(&mx);
    mcstat_moments_init(&my);
    mcstat_moments_add_array(&mx, x, 5);
    mcstat_moments_add_array(&my, y, 4);
    CHECK_INT(mcstat_seq_init(&a, MCSTAT_SEQ_MEAN_2, 0.0, NULL), MCSTAT_OK);
    b = a;
    CHECK_INT(mcstat_seq_push_array_2(&a, x, 5, y, 4), MCSTAT_OK);
    CHECK_INT(mcstat_seq_push_2_array(&b, x, 5, y, 4), MCSTAT_OK);
    CHECK_INT(mcstat_seq_push_moments_2(&a, &mx, &my), MCSTAT_OK);
    CHECK_INT(mcstat_seq_push_2_moments(&b, &mx, &my), MCSTAT_OK);
    CHECK_INT(mcstat_seq_result(&a, &ra), MCSTAT_OK);
    CHECK_INT(mcstat_seq_result(&b, &rb), MCSTAT_OK);
    CHECK(same_results(&ra, &rb, 1) && ra.n[0] == 10 && ra.n[1] == 8);
    CHECK_INT(mcstat_seq_push_moments_2(&a, &mx, NULL), MCSTAT_EINVAL);
}

static void test_rows(void)
{
    static double x[ROWS * STRIDE], y[ROWS * STRIDE];
    unsigned long long s = 99;
    for (int i = 0; i < ROWS * STRIDE; i++) {
        x[i] = urand(&s) + 0.1 * (i / STRIDE);
        y[i] = 2.0 * urand(&s);
    }
    mcstat_result a[ROWS], b[ROWS];
    int32_t sa[ROWS], sb[ROWS];
    for (int alt = 0; alt < 3; alt++) {
        CHECK_INT(mcstat_t_test_1_rows(x, ROWS, N, STRIDE, 0.5, alt, 0.05, 0, a, sa), MCSTAT_OK);
        CHECK_INT(mcstat_t_test_1_matrix(x, N, STRIDE, ROWS, 0.5, alt, 0.05, 0, b, sb), MCSTAT_OK);
        CHECK(same_results(a, b, ROWS) && memcmp(sa, sb, sizeof sa) == 0);
        CHECK_INT(mcstat_var_test_1_rows(x, ROWS, N, STRIDE, 0.1, alt, 0.05, 0, a, sa), MCSTAT_OK);
        CHECK_INT(mcstat_var_test_1_matrix(x, N, STRIDE, ROWS, 0.1, alt, 0.05, 0, b, sb), MCSTAT_OK);
        CHECK(same_results(a, b, ROWS) && memcmp(sa, sb, sizeof sa) == 0);
        CHECK_INT(mcstat_t_test_2_rows(x, N, STRIDE, y, N - 2, STRIDE, ROWS, 0.0, alt, 0.05, 0, a, sa), MCSTAT_OK);
        CHECK_INT(mcstat_t_test_2_matrix(x, N, STRIDE, y, N - 2, STRIDE, ROWS, 0.0, alt, 0.05, 0, b, sb),
                  MCSTAT_OK);
        CHECK(same_results(a, b, ROWS) && memcmp(sa, sb, sizeof sa) == 0);
        CHECK_INT(mcstat_var_test_2_rows(x, N, STRIDE, y, N - 2, STRIDE, ROWS, 1.0, alt, 0.05, 0, a, sa),
                  MCSTAT_OK);
        CHECK_INT(mcstat_var_test_2_matrix(x, N, STRIDE, y, N - 2, STRIDE, ROWS, 1.0, alt, 0.05, 0, b, sb),
                  MCSTAT_OK);
        CHECK(same_results(a, b, ROWS) && memcmp(sa, sb, sizeof sa) == 0);
    }
    /* the new order: row 2 of the matrix is the single test on x + 2 STRIDE */
    mcstat_result one;
    CHECK_INT(mcstat_t_test_1(x + 2 * STRIDE, N, 0.5, MCSTAT_TWO_SIDED, 0.05, &one), MCSTAT_OK);
    CHECK_INT(mcstat_t_test_1_matrix(x, N, STRIDE, ROWS, 0.5, MCSTAT_TWO_SIDED, 0.05, 0, b, sb), MCSTAT_OK);
    CHECK(same_results(&b[2], &one, 1));
}

int main(void)
{
    test_sizes();
    test_check_constants();
    test_diag();
    test_gof();
    test_seq();
    test_rows();
    return h_report("test_deprecated");
}
