/*
 * bench_estimators.c - throughput of libmcest's batch calls: estimates per
 * second per core for U, C, A, S on the paper-like scene (and S on a
 * straddling and a tiny emitter), and directions per second for the BRDF
 * samplers.  Single thread; the median of `reps` runs (at most 64) of `n`
 * estimates filled in batches of `batch`.  Prints one line per case: name,
 * Mest/s, ns/est (medians), and the range of Mest/s over the runs.
 *
 * Usage: bench_estimators [n] [batch] [reps]
 */
#include "mcest.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static volatile double sink;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median and range of the run times t[0..reps-1] (sorted in place). */
static void report(const char *name, double *t, int reps, size_t n)
{
    qsort(t, (size_t)reps, sizeof *t, cmp_double);
    double med = reps % 2 ? t[reps / 2] : 0.5 * (t[reps / 2 - 1] + t[reps / 2]);
    printf("%-28s %8.1f Mest/s %8.2f ns/est  (median of %d, range %.1f-%.1f Mest/s)\n", name, n / med / 1e6,
           med / n * 1e9, reps, n / t[reps - 1] / 1e6, n / t[0] / 1e6);
}

int main(int argc, char **argv)
{
    size_t n = argc > 1 ? strtoull(argv[1], NULL, 10) : 20000000;
    size_t batch = argc > 2 ? strtoull(argv[2], NULL, 10) : 1 << 16;
    int reps = argc > 3 ? atoi(argv[3]) : 3;
    if (reps < 1)
        reps = 1;
    if (reps > 64)
        reps = 64;
    double ts[64];
    double *out = malloc(batch * sizeof(double) * 3);
    if (!out)
        return 1;
    mcest_scene scenes[3];
    const char *snames[3] = {"paper", "straddle", "tiny"};
    mcest_scene_paper(&scenes[0]);
    mcest_scene st = {{-1.0, 0.2, -0.5, 1.2, -0.3, 0.8, 0.1, 1.1, 0.6}, {0, 0, 0}, {0, 0, 1}, 1};
    mcest_scene ti = {{0.3, 0.2, 1.0, 0.300015, 0.2, 1.000002, 0.300003, 0.200014, 0.999999},
                      {0, 0, 0}, {0, 0, 1}, 1};
    scenes[1] = st, scenes[2] = ti;
    for (int s = 0; s < 3; s++) {
        mcest_irradiance_plan P;
        mcest_irradiance_plan_init(&scenes[s], &P);
        for (int m = MCEST_U; m <= MCEST_S; m++) {
            if (s > 0 && m != MCEST_S && m != MCEST_A)
                continue;
            for (int r = 0; r < reps; r++) {
                double t0 = now(), acc = 0;
                for (size_t i = 0; i < n; i += batch) {
                    size_t k = n - i < batch ? n - i : batch;
                    mcest_irradiance_estimates(&P, m, 0, 1, i, k, out);
                    acc += out[k - 1];
                }
                sink = acc;
                ts[r] = now() - t0;
            }
            char name[64];
            snprintf(name, sizeof name, "irradiance %s %s", mcest_method_name(m), snames[s]);
            report(name, ts, reps, n);
        }
    }
    /* BRDF samplers and the exact samplers (fewer: they cost more) */
    mcest_brdf b[2];
    mcest_brdf_ward(0.0, 0.6, 0.1, 0.3, &b[0]);
    mcest_brdf_ashikhmin_shirley(0.0, 0.1, 100, 1000, &b[1]);
    double wo[3] = {0.4, 0.2, 0.894427191};
    size_t nb = n / 10;
    for (int k = 0; k < 2; k++) {
        mcest_brdf_plan P;
        mcest_brdf_plan_init(&b[k], wo, &P);
        const char *nm = k ? "A-S" : "Ward";
        for (int exact = 0; exact < 2; exact++) {
            for (int r = 0; r < reps; r++) {
                double t0 = now();
                for (size_t i = 0; i < nb; i += batch) {
                    size_t c = nb - i < batch ? nb - i : batch;
                    if (exact)
                        mcest_brdf_sample_exact(&P, 1, i, c, 0, out, NULL);
                    else
                        mcest_brdf_sample(&P, 1, i, c, out, NULL);
                }
                ts[r] = now() - t0;
            }
            char name[64];
            snprintf(name, sizeof name, "%s %s", nm, exact ? "exact sampler" : "sampler");
            report(name, ts, reps, nb);
        }
    }
    free(out);
    return 0;
}
