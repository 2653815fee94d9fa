/*
 * test_rng_morton.c - the counter-based generator against NumPy's Philox
 * (ref_philox.h, made by reference/make_philox_reference.py), and Morton
 * keys of directions: bit layout, equal-area map (chi^2 of uniform
 * directions), no ties, order along the polar angle.
 */
#include "est_stats.h"
#include "harness.h"
#include "internal.h"
#include "mcest.h"
#include "ref_philox.h"

#include <string.h>

static void test_philox(void)
{
    int n = (int)(sizeof ref_philox / sizeof ref_philox[0]);
    for (int i = 0; i < n; i++) {
        mcest_u64x4 r = mcest_random_block(ref_philox[i].seed, ref_philox[i].tag,
                                           ref_philox[i].index, ref_philox[i].block);
        for (int k = 0; k < 4; k++)
            CHECK_MSG(r.v[k] == ref_philox[i].out[k], "case %d word %d", i, k);
    }
    CHECK(u01(0) == 0.0);
    CHECK(u01(UINT64_MAX) == 1.0 - 0x1.0p-53);
    /* uniform words: chi^2 of 1e6 uniforms in 1000 bins */
    static double obs[1000], prob[1000];
    for (int b = 0; b < 1000; b++)
        prob[b] = 1e-3;
    for (uint64_t i = 0; i < 250000; i++) {
        mcest_u64x4 r = mcest_random_block(3, 4, i, 0);
        for (int k = 0; k < 4; k++)
            obs[(int)(u01(r.v[k]) * 1000)] += 1;
    }
    int df;
    double p = chisq_gof(obs, prob, 1000, 0, 1e6, &df);
    printf("  uniforms: chi^2 p = %.3g (df %d)\n", p, df);
    CHECK(p > 1e-4);
}

static void uniform_dir(uint64_t i, double *w)
{
    mcest_u64x4 r = mcest_random_block(9, 9, i, 0);
    double z = 2 * u01(r.v[0]) - 1, phi = 2 * M_PI * u01(r.v[1]), s = sqrt(1 - z * z);
    w[0] = s * cos(phi), w[1] = s * sin(phi), w[2] = z;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static void test_morton(void)
{
    /* layout: s = (1 - z)/2, t = phi/2pi; s's bits on odd positions */
    double w[3] = {1.0, 0.0, 0.0}; /* s = 1/2, t = 0 */
    uint64_t key;
    CHECK_INT(mcest_direction_key(w, 1, &key), MCEST_OK);
    CHECK(key == (1ULL << 63));
    double up[3] = {0, 0, 1}, down[3] = {0, 0, -1}, west[3] = {0, 1, 0};
    mcest_direction_key(up, 1, &key);
    CHECK(key == 0);
    mcest_direction_key(down, 1, &key);
    CHECK(key == 0xAAAAAAAAAAAAAAAAULL); /* s = 1 saturates at 2^32 - 1, t = 0 */
    mcest_direction_key(west, 1, &key); /* s = 1/2, t = 1/4 */
    CHECK(key == ((1ULL << 63) | (1ULL << 60)));
    double st[2];
    mcest_direction_square(west, 1, st);
    CHECK(st[0] == 0.5 && st[1] == 0.25);
    /* equal area: uniform directions give uniform (s, t) */
    enum { N = 400000, G = 20 };
    static double obs[G * G], prob[G * G];
    static double dirs[3 * N];
    static uint64_t keys[N];
    for (int c = 0; c < G * G; c++)
        prob[c] = 1.0 / (G * G);
    for (uint64_t i = 0; i < N; i++)
        uniform_dir(i, dirs + 3 * i);
    for (uint64_t i = 0; i < N; i++) {
        mcest_direction_square(dirs + 3 * i, 1, st);
        obs[(int)(st[0] * G) * G + (int)(st[1] * G)] += 1;
    }
    int df;
    double p = chisq_gof(obs, prob, G * G, 0, N, &df);
    printf("  equal-area map: chi^2 p = %.3g (df %d)\n", p, df);
    CHECK(p > 1e-4);
    /* keys: no ties among 4e5 random directions */
    CHECK_INT(mcest_direction_key(dirs, N, keys), MCEST_OK);
    qsort(keys, N, sizeof keys[0], cmp_u64);
    size_t ties = 0;
    for (size_t i = 1; i < N; i++)
        ties += keys[i] == keys[i - 1];
    CHECK_INT(ties, 0);
    /* the key orders by polar angle first: upper hemisphere below 2^63 */
    for (uint64_t i = 0; i < 1000; i++) {
        mcest_direction_key(dirs + 3 * i, 1, &key);
        CHECK((dirs[3 * i + 2] > 0) == (key < (1ULL << 63)));
    }
    double bad[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 1};
    CHECK_INT(mcest_direction_key(bad, 1, &key), MCEST_EINVAL);
    CHECK_INT(mcest_direction_key(nan3, 1, &key), MCEST_EINVAL);
    CHECK_INT(mcest_direction_key(NULL, 0, NULL), MCEST_OK);
}

static void test_misc(void)
{
    char v[32]; /* the header's version: its one source */
    snprintf(v, sizeof v, "%d.%d.%d", MCEST_VERSION_MAJOR, MCEST_VERSION_MINOR, MCEST_VERSION_PATCH);
    CHECK(!strcmp(mcest_version(), v));
    CHECK_INT(mcest_version_number(), MCEST_VERSION_NUMBER);
    CHECK(mcest_sizeof_irradiance_plan() == sizeof(mcest_irradiance_plan));
    CHECK(mcest_sizeof_brdf_plan() == sizeof(mcest_brdf_plan));
    CHECK(mcest_sizeof_scene() == sizeof(mcest_scene));
    CHECK(mcest_sizeof_brdf() == sizeof(mcest_brdf));
    for (int s = 0; s <= 6; s++)
        CHECK(mcest_strerror(s) != NULL);
    CHECK(strstr(mcest_strerror(99), "unknown") != NULL);
}

int main(void)
{
    test_philox();
    test_morton();
    test_misc();
    return h_report("test_rng_morton");
}
