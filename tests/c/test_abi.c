/*
 * test_abi.c - linked against the shared library: the sizes, versions and
 * constants an FFI caller reads at run time agree with the header, and a
 * program built against 0.1.0's header (its options structs, its entry
 * points, its result fields) still works.
 */
/* a 0.1.0 program calls the names of 0.1.0, some deprecated since */
#define MCSTAT_DISABLE_DEPRECATE_WARNINGS
#include "harness.h"
#include "mcstat.h"

#include <stddef.h>
#include <string.h>

/* ---- a consumer compiled against 0.1.0's mcstat.h -------------------------
 * The options structs as 0.1.0 declared them.  A library that has grown a
 * struct must still accept these (their size is MCSTAT_*_OPTIONS_SIZE_0_1)
 * with defaults for the fields appended since. */
typedef struct {
    uint32_t size;
    int32_t weight, method, threads;
    int64_t n_sim;
    uint64_t seed;
    mcstat_ks_cache *cache;
    int32_t critical, reserved;
} ks_options_0_1;
typedef struct {
    uint32_t size;
    int32_t test, alternative, strict;
    double n, n_ratio, sd_ratio, effect, alpha, power;
    double reserved[4];
} power_options_0_1;
typedef struct {
    uint32_t size;
    int32_t reserved_i;
    uint64_t k, m, tail_k;
    double alpha, tolerance, tail_threshold;
    double reserved[4];
} diag_options_0_1;
typedef struct {
    uint32_t size;
    int32_t expected, pool, rescale;
    double min_expected;
    int32_t n_estimated, reserved;
} chisq_options_0_1;
_Static_assert(sizeof(ks_options_0_1) == MCSTAT_KS_OPTIONS_SIZE_0_1, "0.1.0 layout");
_Static_assert(sizeof(power_options_0_1) == MCSTAT_POWER_OPTIONS_SIZE_0_1, "0.1.0 layout");
_Static_assert(sizeof(diag_options_0_1) == MCSTAT_DIAG_OPTIONS_SIZE_0_1, "0.1.0 layout");
_Static_assert(sizeof(chisq_options_0_1) == MCSTAT_CHISQ_OPTIONS_SIZE_0_1, "0.1.0 layout");

/* A caller's struct at the start of a poisoned buffer, to see how much an
 * initialiser writes. */
static unsigned char buf[512];
static void poison(void) { memset(buf, 0xAB, sizeof buf); }
static size_t written(void)
{
    size_t n = sizeof buf;
    while (n > 0 && buf[n - 1] == 0xAB)
        n--;
    return n;
}

/* 0.1.0's initialisers (the exported names, called as an old binary does:
 * the parentheses bypass the header's macros) write 0.1.0's size only, and
 * what they write is what the current defaults give. */
static void test_old_initialisers(void)
{
    poison();
    CHECK_INT((mcstat_ks_options_init)((mcstat_ks_options *)buf), MCSTAT_OK);
    CHECK_INT(written(), MCSTAT_KS_OPTIONS_SIZE_0_1);
    ks_options_0_1 k;
    memcpy(&k, buf, sizeof k);
    CHECK(k.size == sizeof k && k.weight == MCSTAT_KS_WEIGHT_CANNER && k.method == MCSTAT_METHOD_AUTO &&
          k.threads == 1 && k.n_sim == MCSTAT_KS_DEFAULT_N_SIM && k.critical == 1);

    poison();
    CHECK_INT((mcstat_power_options_init)((mcstat_power_options *)buf), MCSTAT_OK);
    CHECK_INT(written(), MCSTAT_POWER_OPTIONS_SIZE_0_1);
    power_options_0_1 p;
    memcpy(&p, buf, sizeof p);
    CHECK(p.size == sizeof p && p.test == MCSTAT_POWER_T_1 && p.alpha == 0.05 && p.strict == 1);

    poison();
    CHECK_INT((mcstat_diag_options_init)((mcstat_diag_options *)buf), MCSTAT_OK);
    CHECK_INT(written(), MCSTAT_DIAG_OPTIONS_SIZE_0_1);
    diag_options_0_1 d;
    memcpy(&d, buf, sizeof d);
    CHECK(d.size == sizeof d && d.alpha == 0.05 && d.tolerance == 0.2 && d.tail_threshold == 2.2);

    poison();
    CHECK_INT((mcstat_chisq_options_init)((mcstat_chisq_options *)buf), MCSTAT_OK);
    CHECK_INT(written(), MCSTAT_CHISQ_OPTIONS_SIZE_0_1);
    chisq_options_0_1 c;
    memcpy(&c, buf, sizeof c);
    CHECK(c.size == sizeof c && c.pool == 1 && c.min_expected == MCSTAT_CHISQ_DEFAULT_MIN_EXPECTED);
}

/* The sized initialisers write exactly the size asked for, refuse sizes no
 * release had (writing nothing), and the header's macro passes sizeof. */
static void test_sized_initialisers(void)
{
    const size_t known[4] = {MCSTAT_KS_OPTIONS_SIZE_0_1, MCSTAT_POWER_OPTIONS_SIZE_0_1,
                             MCSTAT_DIAG_OPTIONS_SIZE_0_1, MCSTAT_CHISQ_OPTIONS_SIZE_0_1};
    const size_t current[4] = {sizeof(mcstat_ks_options), sizeof(mcstat_power_options),
                               sizeof(mcstat_diag_options), sizeof(mcstat_chisq_options)};
    for (int i = 0; i < 4; i++) {
        const size_t sizes[] = {known[i], current[i], current[i] + 8, known[i] - 4, 4, 0};
        for (size_t j = 0; j < sizeof sizes / sizeof *sizes; j++) {
            size_t sz = sizes[j];
            int ok = sz == known[i] || sz == current[i];
            poison();
            int st = i == 0   ? mcstat_ks_options_init_size((mcstat_ks_options *)buf, sz)
                     : i == 1 ? mcstat_power_options_init_size((mcstat_power_options *)buf, sz)
                     : i == 2 ? mcstat_diag_options_init_size((mcstat_diag_options *)buf, sz)
                              : mcstat_chisq_options_init_size((mcstat_chisq_options *)buf, sz);
            CHECK_MSG(st == (ok ? MCSTAT_OK : MCSTAT_EINVAL), "struct %d size %zu: status %d", i, sz, st);
            CHECK_MSG(written() == (ok ? sz : 0), "struct %d size %zu: wrote %zu bytes", i, sz, written());
            uint32_t field;
            memcpy(&field, buf, sizeof field);
            CHECK(!ok || field == sz);
        }
    }
    mcstat_ks_options o;
    memset(&o, 0, sizeof o);
    CHECK_INT(mcstat_ks_options_init(&o), MCSTAT_OK);
    mcstat_ks_options want = MCSTAT_KS_OPTIONS_INIT;
    CHECK(!memcmp(&o, &want, sizeof o));
    CHECK_INT(mcstat_ks_options_init_size(NULL, sizeof o), MCSTAT_EINVAL);
    /* no thread is started unless the caller asks */
    CHECK_INT(o.threads, 1);
}

/* A 0.1.0 consumer's options go through every function taking them, with
 * the results of the current struct; sizes no release had are refused. */
static void test_old_structs_accepted(void)
{
    const double x[12] = {0.1, 0.5, 0.2, 0.9, 0.3, 0.7, 1.4, 0.8, 1.1, 0.05, 0.6, 1.3};
    const double y[10] = {1.2, 0.8, 1.9, 1.5, 1.1, 2.4, 0.95, 1.7, 1.3, 2.0};
    mcstat_result a, b;

    ks_options_0_1 k;
    CHECK_INT((mcstat_ks_options_init)((mcstat_ks_options *)&k), MCSTAT_OK);
    k.weight = MCSTAT_KS_WEIGHT_NONE;
    k.method = MCSTAT_METHOD_SIMULATE;
    k.n_sim = 500;
    k.seed = 7;
    mcstat_ks_options kc = MCSTAT_KS_OPTIONS_INIT;
    kc.weight = MCSTAT_KS_WEIGHT_NONE;
    kc.method = MCSTAT_METHOD_SIMULATE;
    kc.n_sim = 500;
    kc.seed = 7;
    CHECK_INT(mcstat_ks_test_2(x, 12, y, 10, MCSTAT_TWO_SIDED, 0.05, (const mcstat_ks_options *)&k, &a), MCSTAT_OK);
    CHECK_INT(mcstat_ks_test_2(x, 12, y, 10, MCSTAT_TWO_SIDED, 0.05, &kc, &b), MCSTAT_OK);
    CHECK(!memcmp(&a, &b, sizeof a) && a.method == MCSTAT_METHOD_SIMULATE && a.ks_n_sim == 500);

    power_options_0_1 p;
    CHECK_INT((mcstat_power_options_init)((mcstat_power_options *)&p), MCSTAT_OK);
    p.n = 20;
    p.effect = 0.5;
    double pw0, pw1;
    mcstat_power_options pc = MCSTAT_POWER_OPTIONS_INIT;
    pc.n = 20;
    pc.effect = 0.5;
    CHECK_INT(mcstat_power_compute((const mcstat_power_options *)&p, &pw0), MCSTAT_OK);
    CHECK_INT(mcstat_power_compute(&pc, &pw1), MCSTAT_OK);
    CHECK(pw0 == pw1 && pw0 > 0.5 && pw0 < 0.6);
    /* solve writes the caller's version of the struct back, nothing more */
    poison();
    CHECK_INT(mcstat_power_solve((const mcstat_power_options *)&p, MCSTAT_POWER_SOLVE_POWER,
                                 (mcstat_power_options *)buf), MCSTAT_OK);
    CHECK_INT(written(), sizeof p);
    power_options_0_1 ps;
    memcpy(&ps, buf, sizeof ps);
    CHECK(ps.size == sizeof ps && ps.power == pw0 && ps.n == 20);
    char text[512];
    CHECK_INT(mcstat_power_format((const mcstat_power_options *)&ps, text, sizeof text, NULL), MCSTAT_OK);

    diag_options_0_1 d;
    CHECK_INT((mcstat_diag_options_init)((mcstat_diag_options *)&d), MCSTAT_OK);
    double z[40];
    for (int i = 0; i < 40; i++)
        z[i] = (double)((i * 37) % 41) / 41.0;
    mcstat_diagnostics da, db;
    CHECK_INT(mcstat_diagnose(z, 40, (const mcstat_diag_options *)&d, &da), MCSTAT_OK);
    CHECK_INT(mcstat_diagnose(z, 40, NULL, &db), MCSTAT_OK);
    CHECK(!memcmp(&da, &db, sizeof da));

    chisq_options_0_1 c;
    CHECK_INT((mcstat_chisq_options_init)((mcstat_chisq_options *)&c), MCSTAT_OK);
    const double obs[4] = {12, 30, 28, 10}, pr[4] = {0.25, 0.25, 0.25, 0.25};
    CHECK_INT(mcstat_chisq_gof(obs, pr, 4, (const mcstat_chisq_options *)&c, 0.05, &a), MCSTAT_OK);
    CHECK_INT(mcstat_chisq_gof(obs, pr, 4, NULL, 0.05, &b), MCSTAT_OK);
    CHECK(!memcmp(&a, &b, sizeof a) && a.chisq_cells == 4);

    /* a header newer than this library (a larger size), or a struct cut
     * short: MCSTAT_EINVAL from every function */
    unsigned char big[sizeof(mcstat_power_options) + 16];
    const uint32_t bad[] = {0, 4, MCSTAT_KS_OPTIONS_SIZE_0_1 - 8, (uint32_t)sizeof(mcstat_ks_options) + 8};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        memset(big, 0, sizeof big);
        memcpy(big, &kc, sizeof kc);
        memcpy(big, &bad[i], sizeof bad[i]);
        CHECK_INT(mcstat_ks_test_2(x, 12, y, 10, MCSTAT_TWO_SIDED, 0.05, (const mcstat_ks_options *)big, &a),
                  MCSTAT_EINVAL);
    }
    const uint32_t bad_power[] = {0, MCSTAT_POWER_OPTIONS_SIZE_0_1 - 8, (uint32_t)sizeof(mcstat_power_options) + 8};
    for (size_t i = 0; i < sizeof bad_power / sizeof *bad_power; i++) {
        memset(big, 0, sizeof big);
        memcpy(big, &pc, sizeof pc);
        memcpy(big, &bad_power[i], sizeof bad_power[i]);
        CHECK_INT(mcstat_power_compute((const mcstat_power_options *)big, &pw0), MCSTAT_EINVAL);
        CHECK_INT(mcstat_power_solve((const mcstat_power_options *)big, MCSTAT_POWER_SOLVE_POWER, &pc), MCSTAT_EINVAL);
        CHECK_INT(mcstat_power_format((const mcstat_power_options *)big, text, sizeof text, NULL), MCSTAT_EINVAL);
    }
    mcstat_diag_options dc = MCSTAT_DIAG_OPTIONS_INIT;
    dc.size += 8;
    CHECK_INT(mcstat_diagnose(z, 40, &dc, &da), MCSTAT_EINVAL);
    dc.size = MCSTAT_DIAG_OPTIONS_SIZE_0_1 - 8;
    CHECK_INT(mcstat_diagnose(z, 40, &dc, &da), MCSTAT_EINVAL);
    mcstat_chisq_options cc = MCSTAT_CHISQ_OPTIONS_INIT;
    cc.size += 8;
    CHECK_INT(mcstat_chisq_gof(obs, pr, 4, &cc, 0.05, &a), MCSTAT_EINVAL);
    cc.size = MCSTAT_CHISQ_OPTIONS_SIZE_0_1 - 4;
    CHECK_INT(mcstat_chisq_gof(obs, pr, 4, &cc, 0.05, &a), MCSTAT_EINVAL);
}

/* The per-test result fields are 0.1.0's reserved storage under names: a
 * 0.1.0 binary reading reserved[i] sees what the library writes. */
static void test_result_layout(void)
{
    CHECK_INT(sizeof(mcstat_result), 216);
    CHECK_INT(offsetof(mcstat_result, reserved_i), 20);
    CHECK_INT(offsetof(mcstat_result, reserved), 160);
    const size_t ri = offsetof(mcstat_result, reserved_i), rd = offsetof(mcstat_result, reserved);
    CHECK_INT(offsetof(mcstat_result, ks_weight), ri);
    CHECK_INT(offsetof(mcstat_result, chisq_cells), ri + 4);
    CHECK_INT(offsetof(mcstat_result, chisq_n_estimated), ri + 8);
    CHECK_INT(offsetof(mcstat_result, ks_critical_se), rd);
    CHECK_INT(offsetof(mcstat_result, ks_n_sim), rd + 8);
    CHECK_INT(offsetof(mcstat_result, tost_t_lower), rd);
    CHECK_INT(offsetof(mcstat_result, tost_p_lower), rd + 16);
    CHECK_INT(offsetof(mcstat_result, tost_upper), rd + 40);
    CHECK_INT(offsetof(mcstat_result, binom_log_p_value), rd + 16);
    CHECK_INT(offsetof(mcstat_result, chisq_cells_given), rd + 16);
    CHECK_INT(offsetof(mcstat_result, chisq_min_expected), rd + 24);
    CHECK_INT(offsetof(mcstat_result, chisq_pool_below), rd + 32);
    /* the stream's overflow count lives in 0.1.0's reserved storage */
    CHECK_INT(offsetof(mcstat_stream, n_overflow), offsetof(mcstat_stream, reserved));
    CHECK_INT(offsetof(mcstat_stream, reserved_1), offsetof(mcstat_stream, reserved) + 8);
    CHECK_INT(offsetof(mcstat_stream, buf), offsetof(mcstat_stream, reserved) + 16);
    /* the deprecated accessors still name the same storage */
    mcstat_result r;
    memset(&r, 0, sizeof r);
    MCSTAT_RESULT_N_SIM(&r) = 3.0;
    MCSTAT_RESULT_CHISQ_ESTIMATED(&r) = 2;
    MCSTAT_RESULT_LOG_P_VALUE(&r) = -5.0;
    CHECK(r.reserved[1] == 3.0 && r.reserved_i[2] == 2 && r.reserved[2] == -5.0);
    /* a binomial test's log p-value lands where 0.1.0 read it */
    CHECK_INT(mcstat_binom_test(0, 2000, 0.5, MCSTAT_LESS, 0.05, &r), MCSTAT_OK);
    CHECK(r.p_value == 0.0 && r.reserved[2] == r.binom_log_p_value && r.binom_log_p_value < -1300.0);
    /* decision values */
    CHECK_INT(MCSTAT_DECISION_LESS, -1);
    CHECK_INT(MCSTAT_DECISION_EQUAL, 0);
    CHECK_INT(MCSTAT_DECISION_GREATER, 1);
    CHECK(!strcmp(mcstat_decision_name(MCSTAT_DECISION_LESS), "less"));
    CHECK(!strcmp(mcstat_decision_name(MCSTAT_DECISION_GREATER), "greater"));
}

int main(void)
{
    test_old_initialisers();
    test_sized_initialisers();
    test_old_structs_accepted();
    test_result_layout();

    CHECK_INT(mcstat_version_number(), MCSTAT_VERSION_NUMBER);
    char v[32];
    snprintf(v, sizeof v, "%d.%d.%d", MCSTAT_VERSION_MAJOR, MCSTAT_VERSION_MINOR, MCSTAT_VERSION_PATCH);
    CHECK(!strcmp(mcstat_version(), v));
    CHECK_INT(mcstat_sizeof_moments(), sizeof(mcstat_moments));
    CHECK_INT(mcstat_sizeof_result(), sizeof(mcstat_result));
    CHECK_INT(mcstat_moments_bytes(), MCSTAT_MOMENTS_BYTES);
    /* the documented, fixed layout of the accumulator (FFI callers mirror it) */
    CHECK_INT(sizeof(mcstat_moments), 128);
    CHECK_INT(offsetof(mcstat_moments, n), 0);
    CHECK_INT(offsetof(mcstat_moments, scale), 8);
    CHECK_INT(offsetof(mcstat_moments, mean), 16);
    CHECK_INT(offsetof(mcstat_moments, m2), 32);
    CHECK_INT(offsetof(mcstat_moments, max), 64);
    CHECK_INT(offsetof(mcstat_result, n), 32);
    CHECK_INT(offsetof(mcstat_result, statistic), 48);
    /* the embedded-check accumulator: a fixed 4096-byte layout */
    CHECK_INT(mcstat_sizeof_stream(), sizeof(mcstat_stream));
    CHECK_INT(sizeof(mcstat_stream), MCSTAT_STREAM_BYTES);
    CHECK_INT(offsetof(mcstat_stream, count), 128);
    CHECK_INT(offsetof(mcstat_stream, buf), 160);
    /* enum values are part of the ABI */
    CHECK_INT(MCSTAT_TWO_SIDED, 0);
    CHECK_INT(MCSTAT_LESS, 1);
    CHECK_INT(MCSTAT_GREATER, 2);
    CHECK_INT(MCSTAT_EINVAL, 1);
    CHECK_INT(MCSTAT_ECORRUPT, 8);
    /* one call through the shared library */
    const double x[4] = {1.0, 2.0, 3.0, 5.0};
    mcstat_result r;
    CHECK_INT(mcstat_t_test_1(x, 4, 0.0, MCSTAT_TWO_SIDED, 0.05, &r), MCSTAT_OK);
    CHECK_INT(r.test, MCSTAT_TEST_T_1);
    return h_report("test_abi");
}
