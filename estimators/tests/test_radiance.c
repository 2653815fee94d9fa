/*
 * test_radiance.c - reflected radiance (section 3.3): BRDF sampling with
 * the true density and the rejection estimators, each against the
 * cubature reference, and the paper's experiment: for many outgoing
 * directions, Welch's test of sampling against rejection at alpha = 0.01,
 * m = 50 estimates each, reports "equal" about 99% of the time.
 */
#include "est_stats.h"
#include "harness.h"
#include "mcest.h"

#include <math.h>

#define NR 100000
static double a[NR], b[NR];

static void test_against_reference(void)
{
    mcest_brdf brdfs[4];
    mcest_brdf_ward(0.0, 0.7, 0.1, 0.3, &brdfs[0]);
    mcest_brdf_ward(0.2, 0.5, 0.02, 0.02, &brdfs[1]);
    mcest_brdf_ashikhmin_shirley(0.0, 0.2, 50, 500, &brdfs[2]);
    mcest_brdf_ashikhmin_shirley(0.5, 0.05, 20, 20, &brdfs[3]);
    double thetas[3] = {0.1, 0.8, 1.4};
    for (int k = 0; k < 4; k++)
        for (int t = 0; t < 3; t++) {
            double wo[3] = {sin(thetas[t]) * cos(1.0), sin(thetas[t]) * sin(1.0), cos(thetas[t])};
            mcest_brdf_plan P;
            mcest_brdf_plan_init(&brdfs[k], wo, &P);
            mcest_brdf_plan_albedo(&P, 1e-6);
            double Lr;
            mcest_reflected_radiance_reference(&P, 1e-7, &Lr);
            printf("  model %d (%g, %g) theta_o %.1f: Lr = %.8f;", P.brdf.model, P.brdf.rough_x,
                   P.brdf.rough_y, thetas[t], Lr);
            for (int m = MCEST_RR_SAMPLING; m <= MCEST_RR_REJECTION_UNBIASED; m++) {
                CHECK_INT(mcest_reflected_radiance(&P, m, 100 + t, 0, NR, 0, a), MCEST_OK);
                est_summary s = summarize(a, NR);
                double z = (s.mean - Lr) / s.se;
                printf("  z[%d] = %5.2f (sd %.3f)", m, z, s.sd);
                CHECK_MSG(fabs(z) < 5, "model %d theta %g method %d: z = %g", P.brdf.model,
                          thetas[t], m, z);
            }
            printf("\n");
        }
}

static void test_paper_experiment(void)
{
    mcest_brdf ward;
    mcest_brdf_ward(0.0, 0.6, 0.15, 0.05, &ward);
    const int dirs = 400, m = 50;
    int equal = 0;
    for (int d = 0; d < dirs; d++) {
        /* outgoing directions uniform over the hemisphere (stratified in z) */
        double z = (d + 0.5) / dirs, phi = 2.399963229728653 * d, s = sqrt(1 - z * z);
        double wo[3] = {s * cos(phi), s * sin(phi), z};
        mcest_brdf_plan P;
        mcest_brdf_plan_init(&ward, wo, &P);
        mcest_brdf_plan_albedo(&P, 1e-5);
        mcest_reflected_radiance(&P, MCEST_RR_SAMPLING, 7, (uint64_t)d * m, m, 0, a);
        mcest_reflected_radiance(&P, MCEST_RR_REJECTION, 8, (uint64_t)d * m, m, 0, b);
        mcstat_result r;
        if (mcstat_t_test_2(a, m, b, m, 0.0, MCSTAT_TWO_SIDED, 0.01, &r) == MCSTAT_OK)
            equal += r.decision == 0;
    }
    double frac = (double)equal / dirs;
    printf("  section 3.3: %d of %d outgoing directions report equal means (%.1f%%) at alpha = 0.01\n",
           equal, dirs, 100 * frac);
    /* Expected about 99% (primary estimates are skewed, so a little less);
     * 0.95 is 5 binomial standard deviations below. */
    CHECK(frac > 0.95);
}

int main(void)
{
    test_against_reference();
    test_paper_experiment();
    return h_report("test_radiance");
}
