/*
 * test_outputs_on_failure.c - the header's rule, call by call: a call that
 * gives one answer writes it only on success, so that a caller's output
 * keeps its bytes (sentinel-filled here) through every failure; and the
 * stated exceptions (element-wise and text calls) behave as stated.
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "mcstat.h"
#include <string.h>

static const double good[5] = {1.0, 2.5, 3.0, 4.5, 2.0};
static const double same[4] = {7.0, 7.0, 7.0, 7.0};

/* UNTOUCHED(obj, call): call fails and obj (sentinel-filled) keeps its bytes */
#define UNTOUCHED(obj, call)                                                            \
    do {                                                                                \
        unsigned char before_[sizeof(obj)];                                             \
        memset(&(obj), 0xAB, sizeof(obj));                                              \
        memcpy(before_, &(obj), sizeof(obj));                                           \
        int st_ = (call);                                                               \
        CHECK_MSG(st_ != MCSTAT_OK, "%s: succeeded", #call);                            \
        CHECK_MSG(!memcmp(before_, &(obj), sizeof(obj)), "%s (status %d): output written on failure", #call, st_); \
    } while (0)

int main(void)
{
    mcstat_result r;
    mcstat_moments m, mg, mc;
    double d, d2[2], arr[5];
    int dec;
    uint64_t u;
    mcstat_moments_init(&mg);
    mcstat_moments_add_array(&mg, good, 5);
    mcstat_moments_init(&mc);
    mcstat_moments_add_array(&mc, same, 4);

    UNTOUCHED(m, mcstat_moments_from_summary(3, NAN, 1.0, &m));
    UNTOUCHED(m, mcstat_moments_from_summary(1, 1.0, 2.0, &m));
    UNTOUCHED(r, mcstat_t_test_1(good, 5, 0.0, 0, 2.0, &r));
    UNTOUCHED(r, mcstat_t_test_1(same, 4, 0.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_t_test_1_moments(&mc, 0.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_t_test_2(good, 5, same, 4, 0.0, 0, NAN, &r));
    UNTOUCHED(r, mcstat_t_test_2_moments(&mc, &mc, 0.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_t_test_2_pooled(same, 4, same, 4, 0.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_t_test_2_pooled_moments(&mg, &mc, 0.0, 9, 0.05, &r));
    UNTOUCHED(r, mcstat_t_test_paired(same, same, 4, 0.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_var_test_1(good, 5, -1.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_var_test_1(same, 4, 1.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_var_test_1_moments(&mc, 1.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_var_test_2(good, 5, same, 4, 1.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_var_test_2_moments(&mg, &mc, 1.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_efficiency_test(&mg, &mg, &mc, &mc, -1.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_efficiency_test(&mc, &mg, &mg, &mg, 1.0, 0, 0.05, &r));
    UNTOUCHED(r, mcstat_ks_test_2(good, 5, same, 0, 0, 0.05, NULL, &r));
    UNTOUCHED(r, mcstat_equivalence_test_1(good, 5, 0.0, 1.0, -1.0, 0.05, &r));
    UNTOUCHED(r, mcstat_equivalence_test_1(same, 4, 7.0, -1.0, 1.0, 0.05, &r));
    UNTOUCHED(r, mcstat_equivalence_test_1_moments(&mc, 7.0, -1.0, 1.0, 0.05, &r));
    UNTOUCHED(r, mcstat_equivalence_test_2(same, 4, same, 4, -1.0, 1.0, 0.05, &r));
    UNTOUCHED(r, mcstat_equivalence_test_2_moments(&mc, &mc, -1.0, 1.0, 0.05, &r));
    UNTOUCHED(d, mcstat_t_cdf(1.0, -1.0, 0, &d));
    UNTOUCHED(d, mcstat_t_cdf(NAN, 3.0, 0, &d));
    UNTOUCHED(d, mcstat_t_logcdf(1.0, 0.0, 0, &d));
    UNTOUCHED(d, mcstat_t_quantile(1.5, 3.0, 0, &d));
    UNTOUCHED(d, mcstat_chisq_cdf(1.0, -1.0, 0, &d));
    UNTOUCHED(d, mcstat_chisq_logcdf(1.0, NAN, 0, &d));
    UNTOUCHED(d, mcstat_chisq_quantile(-0.5, 3.0, 0, &d));
    UNTOUCHED(d, mcstat_f_cdf(1.0, 0.0, 3.0, 0, &d));
    UNTOUCHED(d, mcstat_f_logcdf(1.0, 3.0, -2.0, 0, &d));
    UNTOUCHED(d, mcstat_f_quantile(2.0, 3.0, 3.0, 0, &d));
    {
        /* element-wise: the failing element is NaN, the others computed */
        double dfs[3] = {3.0, -1.0, 5.0}, q[3];
        UNTOUCHED(q, mcstat_t_quantiles(1.5, dfs, 3, 0, q));
        CHECK_INT(mcstat_t_quantiles(0.25, dfs, 3, 0, q), MCSTAT_EINVAL);
        CHECK(q[0] < 0 && isnan(q[1]) && q[2] < 0);
    }
    {
        /* text: a NUL-terminated prefix and the full length */
        mcstat_t_test_1(good, 5, 0.0, 0, 0.05, &r);
        char small[8];
        size_t len = 0;
        CHECK_INT(mcstat_result_format(&r, NULL, NULL, small, sizeof small, &len), MCSTAT_EBUFSIZE);
        CHECK(strlen(small) == sizeof small - 1 && len > sizeof small);
    }
    UNTOUCHED(arr, mcstat_p_adjust((const double[]){0.1, 0.2, 1.5, 0.3, 0.4}, 5, MCSTAT_P_ADJUST_BH, NULL, 0, arr));
    UNTOUCHED(arr, mcstat_p_adjust((const double[]){0.1, 0.2, 0.5, 0.3, 0.4}, 5, 99, NULL, 0, arr));
    UNTOUCHED(arr, mcstat_e_bh((const double[]){1.0, 2.0, -1.0, 3.0, 4.0}, 5, NULL, 0, arr));
    {
        mcstat_escalation e;
        UNTOUCHED(e, mcstat_escalation_design(2.0, 0.5, 0.1, &e));
        mcstat_escalation_design(0.01, 0.5, 0.1, &e);
        UNTOUCHED(dec, mcstat_escalation_decide(&e, 1.5, 0.5, &dec));
    }
    UNTOUCHED(d2, mcstat_result_conf_int(&r, 2.0, d2));
    UNTOUCHED(d, mcstat_result_log_p_value(NULL, &d));
#ifndef MCSTAT_NO_EXPERIMENTAL
    {
        mcstat_power_options po = MCSTAT_POWER_OPTIONS_INIT, out;
        po.n = 10;
        po.effect = 0.5;
        po.alpha = 2.0;
        UNTOUCHED(d, mcstat_power_compute(&po, &d));
        UNTOUCHED(out, mcstat_power_solve(&po, 99, &out));
        mcstat_diagnostics dg;
        UNTOUCHED(dg, mcstat_diag_compute(same, 4, NULL, &dg));
        UNTOUCHED(d2, mcstat_diag_tail_index(good, 5, 10, d2));
        UNTOUCHED(d2, mcstat_diag_t_size(0.0, 3.0, 0, 10, 0.05, d2));
        UNTOUCHED(u, mcstat_diag_batch_size(0.0, 3.0, 10, 2.0, 0.01, &u));
        UNTOUCHED(r, mcstat_gof_chisq_test((const double[]){1, 2, 3}, (const double[]){0.5, 0.5, -1}, 3, NULL, 0.05, &r));
        UNTOUCHED(r, mcstat_binom_test(5, 3, 0.5, 0, 0.05, &r));
        UNTOUCHED(r, mcstat_battery_test(5, 10, 1.5, 0, 0.05, &r));
        UNTOUCHED(r, mcstat_battery_test_pvalues((const double[]){0.1, NAN}, 2, 0.05, 0, 0.05, &r));
        mcstat_seq s;
        UNTOUCHED(s, mcstat_seq_init(&s, 99, 0.0, NULL));
        mcstat_seq_init(&s, MCSTAT_SEQ_MEAN_1, 0.0, NULL);
        UNTOUCHED(r, mcstat_seq_result(NULL, &r));
        UNTOUCHED(r, mcstat_seq_finish(NULL, &r));
        mcstat_seq keep = s;
        CHECK(mcstat_seq_push_array(&s, (const double[]){1.0, NAN, 2.0}, 3) != MCSTAT_OK);
        CHECK(!memcmp(&s, &keep, sizeof s));
        CHECK(mcstat_seq_push_moments(&s, &mc) == MCSTAT_OK || !memcmp(&s, &keep, sizeof s));
    }
#endif
    {
        /* an accumulator is the output of the calls that add to it */
        double nanmid[5] = {1.0, 2.0, NAN, 3.0, 4.0};
        mcstat_moments keep = mg, bad;
        memset(&bad, 0x5A, sizeof bad);
        m = keep;
        CHECK(mcstat_moments_add_array(&m, nanmid, 5) != MCSTAT_OK && !memcmp(&m, &keep, sizeof m));
        m = keep;
        CHECK(mcstat_moments_add(&m, INFINITY) != MCSTAT_OK && !memcmp(&m, &keep, sizeof m));
        m = keep;
        CHECK(mcstat_moments_merge(&m, &bad) != MCSTAT_OK && !memcmp(&m, &keep, sizeof m));
        unsigned char bytes[256] = {0};
        UNTOUCHED(m, mcstat_moments_from_bytes(bytes, mcstat_sizeof_moments_bytes(), &m));
        UNTOUCHED(m, mcstat_moments_from_bytes(bytes, 3, &m));
    }
    {
        mcstat_stream st;
        mcstat_stream_init(&st);
        UNTOUCHED(m, mcstat_stream_moments(NULL, &m));
        UNTOUCHED(r, mcstat_stream_check_mean(&st, 0.0, 0.1, 0.05, &r));
        UNTOUCHED(r, mcstat_stream_check_var(&st, 1.0, 0.05, &r));
    }
    return h_report("test_outputs_on_failure");
}
