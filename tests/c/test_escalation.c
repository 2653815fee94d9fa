/*
 * test_escalation.c - the two-stage escalation (escalation.c): its level
 * against quadrature and against simulation under H0, its power against
 * the closed form for Beta(a, 1) p-values, and its refusals.
 */
#include "harness.h"
#include "mcstat.h"

#include <stdint.h>

static uint64_t rng_state = 20261206;
#include "test_rng.h"

/* P(reject | H0) by midpoint quadrature on log p1 over the escalation band:
 * alpha1 + integral P(p2 <= c / p1) dp1, independent of the closed form. */
static double level_by_quadrature(const mcstat_escalation *d)
{
    const int m = 200000;
    double a = log(d->alpha1), b = log(d->alpha0), h = (b - a) / m, s = 0.0;
    for (int i = 0; i < m; i++) {
        double p1 = exp(a + (i + 0.5) * h);
        s += fmin(1.0, d->c / p1) * p1 * h; /* dp1 = p1 d(log p1) */
    }
    return d->alpha1 + s;
}

static int decide2(const mcstat_escalation *d, double p1, double p2)
{
    int dec = -1;
    if (mcstat_escalation_decide(d, p1, NAN, &dec) != MCSTAT_OK)
        return -1;
    if (dec != MCSTAT_ESCALATION_CONTINUE)
        return dec;
    if (mcstat_escalation_decide(d, p1, p2, &dec) != MCSTAT_OK)
        return -1;
    return dec;
}

/* |k - n p| within 4.5 binomial standard deviations (a false failure once
 * in ~3e5 runs; the seed is fixed, so the outcome is too) */
static int within_binomial(long k, long n, double p)
{
    return fabs((double)k - n * p) <= 4.5 * sqrt(n * p * (1.0 - p));
}

int main(void)
{
    (void)normal;
    /* the design's numbers, by hand: c = (alpha - alpha1) / ln(alpha0 / alpha1) */
    mcstat_escalation d;
    CHECK_INT(mcstat_escalation_design(0.05, 0.5, 0.5, &d), MCSTAT_OK);
    CHECK_REL(d.alpha1, 0.025, 1e-16, "alpha1");
    CHECK_REL(d.alpha0, 0.5, 0.0, "alpha0");
    CHECK_REL(d.c, 0.025 / log(20.0), 1e-15, "c");

    /* the level is alpha, for designs from a suite's tiny shares to 0.2 */
    const double alphas[] = {1e-12, 1e-7, 1e-5, 1e-3, 0.01, 0.05, 0.2};
    const double shares[] = {0.1, 0.5, 0.9};
    const double alpha0s[] = {0.01, 0.05, 0.5, 1.0};
    for (size_t i = 0; i < sizeof alphas / sizeof *alphas; i++)
        for (size_t j = 0; j < sizeof shares / sizeof *shares; j++)
            for (size_t k = 0; k < sizeof alpha0s / sizeof *alpha0s; k++) {
                mcstat_escalation e;
                int st = mcstat_escalation_design(alphas[i], shares[j], alpha0s[k], &e);
                double a1 = alphas[i] * shares[j];
                /* refused exactly where c would exceed alpha1 (or alpha0 <= alpha1) */
                int feasible = alpha0s[k] > a1 && (1.0 - shares[j]) / shares[j] <= log(alpha0s[k] / a1);
                CHECK_MSG((st == MCSTAT_OK) == feasible, "alpha %g share %g alpha0 %g: status %d", alphas[i],
                          shares[j], alpha0s[k], st);
                if (st == MCSTAT_OK)
                    CHECK_REL(level_by_quadrature(&e), alphas[i], 1e-9, "alpha %g share %g alpha0 %g",
                              alphas[i], shares[j], alpha0s[k]);
            }

    /* simulated: H0 (uniform p-values) rejects at alpha; Beta(a, 1)
     * p-values (P(p <= u) = u^a) at alpha1^a + a c^a ln(alpha0 / alpha1) */
    const long n = 2000000;
    CHECK_INT(mcstat_escalation_design(0.05, 0.5, 0.3, &d), MCSTAT_OK);
    const double as[] = {1.0, 0.5, 0.25};
    for (size_t i = 0; i < sizeof as / sizeof *as; i++) {
        double a = as[i];
        long rej = 0, cont = 0;
        for (long t = 0; t < n; t++) {
            double p1 = pow(unif(), 1.0 / a), p2 = pow(unif(), 1.0 / a);
            int dec;
            mcstat_escalation_decide(&d, p1, NAN, &dec);
            cont += dec == MCSTAT_ESCALATION_CONTINUE;
            rej += decide2(&d, p1, p2) == MCSTAT_ESCALATION_REJECT;
        }
        double want = pow(d.alpha1, a) + a * pow(d.c, a) * log(d.alpha0 / d.alpha1);
        double want_cont = pow(d.alpha0, a) - pow(d.alpha1, a);
        CHECK_MSG(within_binomial(rej, n, want), "a %g: %ld rejections of %ld, want %g", a, rej, n, want);
        CHECK_MSG(within_binomial(cont, n, want_cont), "a %g: %ld escalations of %ld, want %g", a, cont, n,
                  want_cont);
        if (a == 1.0)
            CHECK_REL(want, 0.05, 1e-12, "the closed form at a = 1 is alpha");
    }

    /* the boundaries: p1 = alpha1 rejects, p1 = alpha0 escalates, p1 p2 = c rejects */
    int dec = -1;
    CHECK_INT(mcstat_escalation_decide(&d, d.alpha1, NAN, &dec), MCSTAT_OK);
    CHECK_INT(dec, MCSTAT_ESCALATION_REJECT);
    CHECK_INT(mcstat_escalation_decide(&d, d.alpha0, NAN, &dec), MCSTAT_OK);
    CHECK_INT(dec, MCSTAT_ESCALATION_CONTINUE);
    CHECK_INT(mcstat_escalation_decide(&d, nextafter(d.alpha0, 1.0), NAN, &dec), MCSTAT_OK);
    CHECK_INT(dec, MCSTAT_ESCALATION_PASS);
    CHECK_INT(mcstat_escalation_decide(&d, 0.1, d.c / 0.1 * (1 - 1e-15), &dec), MCSTAT_OK);
    CHECK_INT(dec, MCSTAT_ESCALATION_REJECT);
    CHECK_INT(mcstat_escalation_decide(&d, 0.1, d.c / 0.1 * (1 + 1e-12), &dec), MCSTAT_OK);
    CHECK_INT(dec, MCSTAT_ESCALATION_PASS);
    CHECK_INT(mcstat_escalation_decide(&d, 0.0, NAN, &dec), MCSTAT_OK);
    CHECK_INT(dec, MCSTAT_ESCALATION_REJECT);

    /* refusals: nothing written */
    mcstat_escalation z = {-1, -1, -1, -1};
    const double bad[][3] = {{0, .5, .5},   {1, .5, .5},   {NAN, .5, .5}, {.05, 0, .5}, {.05, 1, .5},
                             {.05, NAN, .5}, {.05, .5, .025}, {.05, .5, 1.5}, {.05, .5, NAN},
                             {.5, .5, .3} /* c > alpha1 */, {-.1, .5, .5}, {INFINITY, .5, .5}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        CHECK_INT(mcstat_escalation_design(bad[i][0], bad[i][1], bad[i][2], &z), MCSTAT_EINVAL);
        CHECK(z.alpha == -1 && z.c == -1);
    }
    CHECK_INT(mcstat_escalation_design(0.05, 0.5, 0.5, NULL), MCSTAT_EINVAL);
    dec = 77;
    CHECK_INT(mcstat_escalation_decide(NULL, 0.1, NAN, &dec), MCSTAT_EINVAL);
    CHECK_INT(mcstat_escalation_decide(&d, 0.1, NAN, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_escalation_decide(&d, NAN, NAN, &dec), MCSTAT_EINVAL);
    CHECK_INT(mcstat_escalation_decide(&d, -0.1, NAN, &dec), MCSTAT_EINVAL);
    CHECK_INT(mcstat_escalation_decide(&d, 1.1, NAN, &dec), MCSTAT_EINVAL);
    CHECK_INT(mcstat_escalation_decide(&d, 0.1, 1.5, &dec), MCSTAT_EINVAL);
    CHECK_INT(mcstat_escalation_decide(&d, 0.1, INFINITY, &dec), MCSTAT_EINVAL);
    CHECK_INT(mcstat_escalation_decide(&d, 0.9, 0.1, &dec), MCSTAT_EINVAL);   /* stage 1 passed */
    CHECK_INT(mcstat_escalation_decide(&d, 0.001, 0.1, &dec), MCSTAT_EINVAL); /* stage 1 rejected */
    mcstat_escalation forged = d;
    forged.c = 2 * d.alpha1;
    CHECK_INT(mcstat_escalation_decide(&forged, 0.1, NAN, &dec), MCSTAT_EINVAL);
    forged = d;
    forged.alpha = NAN;
    CHECK_INT(mcstat_escalation_decide(&forged, 0.1, NAN, &dec), MCSTAT_EINVAL);
    CHECK_INT(dec, 77);

    printf("test_escalation: %d checks, %d failures\n", h_checks, h_failures);
    return h_failures != 0;
}
