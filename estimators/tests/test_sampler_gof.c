/*
 * test_sampler_gof.c - equal-probability direction cells (mcest_brdf_cells)
 * and the planted sampler bugs (mcest_brdf_sample_bug), through
 * mcstat_chisq_gof:
 *   - cell probabilities against the closed form for a cosine-weighted
 *     sampler, and summing to 1 for the paper scene's lobes;
 *   - the cells are a partition: locate agrees with the bounds;
 *   - calibration: the correct samplers are rejected at rate ~alpha over
 *     seeds (binomial bounds);
 *   - every planted bug is rejected in (nearly) every run at n = 20000.
 */
#define MCSTAT_EXPERIMENTAL /* power, diagnostics, goodness of fit */
#include "harness.h"
#include "internal.h"
#include "mcest.h"
#include "mcstat.h"

#include <stdlib.h>
#include <string.h>

#define DEPTH 6
#define CELLS (1 << DEPTH)

static double work[2 << (DEPTH + 8)];

static void wo_of(double theta_deg, double phi_deg, double *wo)
{
    double t = theta_deg * M_PI / 180.0, p = phi_deg * M_PI / 180.0;
    wo[0] = sin(t) * cos(p), wo[1] = sin(t) * sin(p), wo[2] = cos(t);
}

/* The paper scene's BRDFs (programs/mcstat_app/reproduce/scene.py) and a mixture. */
static void plans(mcest_brdf_plan *p)
{
    mcest_brdf b;
    double wo[3];
    mcest_brdf_ward(0.0, 0.6, 0.2, 0.05, &b);
    wo_of(70, 40, wo);
    CHECK_INT(mcest_brdf_plan_init(&b, wo, &p[0]), MCEST_OK);
    mcest_brdf_ashikhmin_shirley(0.0, 0.2, 50, 500, &b);
    wo_of(30, 40, wo);
    CHECK_INT(mcest_brdf_plan_init(&b, wo, &p[1]), MCEST_OK);
    mcest_brdf_ward(0.3, 0.5, 0.3, 0.1, &b);
    wo_of(45, 10, wo);
    CHECK_INT(mcest_brdf_plan_init(&b, wo, &p[2]), MCEST_OK);
}

static void test_cells_exact(void)
{
    /* Ward with rho_s = 0: the sampler is cosine-weighted, p = z/pi on the
     * upper hemisphere, so a cell's probability is
     * 4 (t1 - t0) [s - s^2] from s0 to s1 (clipped to s <= 1/2). */
    mcest_brdf b;
    mcest_brdf_plan p;
    double wo[3] = {0.3, 0.2, 0.9};
    CHECK_INT(mcest_brdf_ward(0.5, 0.0, 0.3, 0.3, &b), MCEST_OK);
    CHECK_INT(mcest_brdf_plan_init(&b, wo, &p), MCEST_OK);
    double split[CELLS - 1], prob[CELLS], bounds[4 * CELLS], err;
    CHECK_INT(mcest_brdf_cells(&p, DEPTH, 1e-9, work, split, prob, &err), MCEST_OK);
    CHECK_INT(mcest_cells_bounds(split, DEPTH, bounds), MCEST_OK);
    double worst = 0.0, sum = 0.0;
    for (int c = 0; c < CELLS; c++) {
        double *r = bounds + 4 * c;
        double s0 = fmin(r[0], 0.5), s1 = fmin(r[1], 0.5);
        double exact = 4.0 * (r[3] - r[2]) * ((s1 - s1 * s1) - (s0 - s0 * s0));
        worst = fmax(worst, fabs(prob[c] - exact));
        sum += prob[c];
        /* nearly equal probabilities (medians of 256 pilot directions a cell) */
        CHECK_MSG(fabs(prob[c] * CELLS - 1.0) < 0.3, "cell %d: %g", c, prob[c]);
    }
    printf("cosine cells: max |error| %.3g, sum - 1 = %.3g, reported error %.3g\n", worst, sum - 1.0, err);
    CHECK_MSG(worst < 1e-11, "worst %g", worst);
    CHECK(fabs(sum - 1.0) < 1e-10);
}

/* Deep trees put cells next to the density's singular point wi = -wo
 * (direction_cells.c): the probabilities still sum to 1. */
static void test_cells_deep(const mcest_brdf_plan *p)
{
    for (int depth = 8; depth <= 12; depth += 4) {
        size_t cells = (size_t)1 << depth;
        double *wk = malloc(mcest_cells_work_size(depth) * sizeof *wk), *split = malloc(cells * sizeof *split),
               *prob = malloc(cells * sizeof *prob), err, sum = 0.0;
        CHECK_INT(mcest_brdf_cells(p, depth, 1e-8, wk, split, prob, &err), MCEST_OK);
        for (size_t c = 0; c < cells; c++)
            sum += prob[c];
        printf("depth %d: sum - 1 = %.3g (reported error %.3g)\n", depth, sum - 1.0, err);
        CHECK_MSG(fabs(sum - 1.0) < 1e-6, "depth %d: sum %.17g", depth, sum);
        free(wk);
        free(split);
        free(prob);
    }
}

static void test_cells_partition(const mcest_brdf_plan *p, const char *name)
{
    double split[CELLS - 1], prob[CELLS], bounds[4 * CELLS], err;
    int st = mcest_brdf_cells(p, DEPTH, 1e-8, work, split, prob, &err);
    CHECK_MSG(st == MCEST_OK, "%s: status %d", name, st);
    double sum = 0.0, area = 0.0;
    int near_equal = 0;
    CHECK_INT(mcest_cells_bounds(split, DEPTH, bounds), MCEST_OK);
    for (int c = 0; c < CELLS; c++) {
        sum += prob[c];
        area += (bounds[4 * c + 1] - bounds[4 * c]) * (bounds[4 * c + 3] - bounds[4 * c + 2]);
        near_equal += fabs(prob[c] * CELLS - 1.0) < 0.2;
        CHECK(prob[c] >= 0.0);
    }
    printf("%s cells: sum - 1 = %.3g (reported error %.3g), %d of %d within 20%% of 1/%d\n", name, sum - 1.0,
           err, near_equal, CELLS, CELLS);
    CHECK_MSG(fabs(sum - 1.0) < 1e-9, "%s: sum %.17g", name, sum);
    CHECK(fabs(area - 1.0) < 1e-12);
    CHECK_MSG(near_equal >= CELLS * 9 / 10, "%s: only %d near-equal cells", name, near_equal);
    /* every direction lands in the cell whose rectangle holds it */
    enum { N = 2000 };
    static double w[3 * N], st2[2 * N];
    uint32_t cell[N];
    CHECK_INT(mcest_brdf_sample(p, 99, 0, N, w, NULL), MCEST_OK);
    CHECK_INT(mcest_cells_locate(split, DEPTH, w, N, cell), MCEST_OK);
    CHECK_INT(mcest_direction_square(w, N, st2), MCEST_OK);
    int bad = 0;
    for (int k = 0; k < N; k++) {
        const double *r = bounds + 4 * cell[k];
        bad += !(st2[2 * k] >= r[0] && st2[2 * k] <= r[1] && st2[2 * k + 1] >= r[2] && st2[2 * k + 1] <= r[3]);
    }
    CHECK_INT(bad, 0);
}

/* Rejection rate of the chi-squared test over `runs` seeds. */
static int rejections(const mcest_brdf_plan *p, const double *split, const double *prob, int bug, size_t n,
                      int runs, double alpha)
{
    double *w = malloc(3 * n * sizeof *w), counts[CELLS];
    int rej = 0;
    for (int r = 0; r < runs; r++) {
        CHECK_INT(mcest_brdf_sample_bug(p, bug, 1000 + (uint64_t)r, 0, n, w), MCEST_OK);
        CHECK_INT(mcest_cells_count(split, DEPTH, w, n, counts), MCEST_OK);
        mcstat_result res;
        CHECK_INT(mcstat_gof_chisq_test(counts, prob, CELLS, NULL, alpha, &res), MCSTAT_OK);
        rej += res.reject;
    }
    free(w);
    return rej;
}

static void test_calibration_and_bugs(const mcest_brdf_plan *p, const char *name)
{
    double split[CELLS - 1], prob[CELLS];
    CHECK_INT(mcest_brdf_cells(p, DEPTH, 1e-8, work, split, prob, NULL), MCEST_OK);
    /* H0: 400 runs of n = 2000 at alpha = 0.05: sd 0.011, bounds +- 4 sd */
    const int runs = 400;
    int rej = rejections(p, split, prob, MCEST_SAMPLER_BUG_NONE, 2000, runs, 0.05);
    double rate = (double)rej / runs;
    printf("%s: correct sampler rejected %d/%d\n", name, rej, runs);
    CHECK_MSG(fabs(rate - 0.05) < 4.0 * sqrt(0.05 * 0.95 / runs), "%s: rate %g", name, rate);
    for (int bug = 1; bug <= MCEST_SAMPLER_BUG_JACOBIAN; bug++) {
        int rb = rejections(p, split, prob, bug, 20000, 20, 0.01);
        printf("%s: bug %s rejected %d/20 at n = 20000\n", name, mcest_sampler_bug_name(bug), rb);
        CHECK_MSG(rb >= 19, "%s: bug %s rejected only %d/20", name, mcest_sampler_bug_name(bug), rb);
    }
}

static void test_bad_input(const mcest_brdf_plan *p)
{
    double split[CELLS - 1], prob[CELLS], w[3] = {0, 0, 1}, counts[CELLS];
    uint32_t c;
    mcest_brdf_plan bad;
    memset(&bad, 0, sizeof bad);
    CHECK_INT(mcest_brdf_cells(&bad, DEPTH, 1e-8, work, split, prob, NULL), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_cells(p, 0, 1e-8, work, split, prob, NULL), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_cells(p, MCEST_CELLS_MAX_DEPTH + 1, 1e-8, work, split, prob, NULL), MCEST_EINVAL);
    CHECK(mcest_cells_work_size(DEPTH) == sizeof work / sizeof work[0]);
    CHECK(mcest_cells_work_size(0) == 0);
    CHECK_INT(mcest_brdf_cells(p, DEPTH, 0.5, work, split, prob, NULL), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_cells(p, DEPTH, NAN, work, split, prob, NULL), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_cells(p, DEPTH, 1e-8, work, NULL, prob, NULL), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_cells(p, 2, 1e-8, work, split, prob, NULL), MCEST_OK);
    CHECK_INT(mcest_cells_locate(split, 2, w, 1, &c), MCEST_OK);
    double wz[3] = {0, 0, 0}, wn[3] = {NAN, 0, 1};
    CHECK_INT(mcest_cells_locate(split, 2, wz, 1, &c), MCEST_EINVAL);
    CHECK_INT(mcest_cells_locate(split, 2, wn, 1, &c), MCEST_EINVAL);
    CHECK_INT(mcest_cells_count(split, 2, wn, 1, counts), MCEST_EINVAL);
    CHECK_INT(mcest_cells_count(split, 0, w, 1, counts), MCEST_EINVAL);
    CHECK_INT(mcest_cells_bounds(NULL, 2, counts), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_sample_bug(p, 5, 0, 0, 1, w), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_sample_bug(p, -1, 0, 0, 1, w), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_sample_bug(&bad, 1, 0, 0, 1, w), MCEST_EINVAL);
    CHECK_INT(mcest_brdf_sample_bug(p, 1, 0, 0, 1, NULL), MCEST_EINVAL);
    int bug;
    CHECK_INT(mcest_sampler_bug_parse("phi_half", &bug), MCEST_OK);
    CHECK_INT(bug, MCEST_SAMPLER_BUG_PHI_HALF);
    CHECK_INT(mcest_sampler_bug_parse("nope", &bug), MCEST_EINVAL);
    CHECK_INT(mcest_sampler_bug_parse(NULL, &bug), MCEST_OK);
    CHECK_INT(bug, MCEST_SAMPLER_BUG_NONE);
    CHECK(mcest_sampler_bug_name(9) == NULL);
    CHECK(strcmp(mcest_sampler_bug_name(MCEST_SAMPLER_BUG_JACOBIAN), "jacobian") == 0);
    /* NONE is the BRDF's own sampler, bit for bit */
    double a[30], b2[30];
    CHECK_INT(mcest_brdf_sample_bug(p, MCEST_SAMPLER_BUG_NONE, 5, 7, 10, a), MCEST_OK);
    CHECK_INT(mcest_brdf_sample(p, 5, 7, 10, b2, NULL), MCEST_OK);
    CHECK(memcmp(a, b2, sizeof a) == 0);
}

int main(void)
{
    mcest_brdf_plan p[3];
    const char *names[3] = {"ward", "ashikhmin_shirley", "ward_mixture"};
    plans(p);
    test_cells_exact();
    for (int i = 0; i < 3; i++)
        test_cells_partition(&p[i], names[i]);
    test_cells_deep(&p[0]);
    for (int i = 0; i < 3; i++)
        test_calibration_and_bugs(&p[i], names[i]);
    test_bad_input(&p[0]);
    return h_report("test_sampler_gof");
}
