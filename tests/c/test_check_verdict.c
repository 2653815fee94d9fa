/* The renderer checks' numerical floor and verdicts: a float32 isotropic
 * phase function (eval = pdf = (float)(1/(4 pi))) passes with the floor
 * derived from its values and fails without it; the floor's option is
 * read from 0.3's options and defaulted for 0.2's; a BSDF whose weights
 * are heavy-tailed is inconclusive with the routes and why; bad input to
 * mcstat_check_verdict, mcstat_check_why_text and the option. */
#include "harness.h"
#include "mcstat.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static double p32(void) { return (double)(1.0f / (4.0f * 3.14159265f)); }

static int iso_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *w, double *p)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++) {
        double z = 1 - 2 * u[2 * k], r = sqrt(fmax(0, 1 - z * z)), phi = 2 * PI * u[2 * k + 1];
        x[3 * k] = r * cos(phi), x[3 * k + 1] = r * sin(phi), x[3 * k + 2] = z;
        w[k] = 1.0, p[k] = p32();
    }
    return 0;
}
static int iso_density(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi, (void)x;
    for (size_t k = 0; k < n; k++)
        out[k] = p32();
    return 0;
}

/* f |cos| should be rho 3 cos^2/(2 pi), sampled exactly; eval() leaves out
 * the cos^2 and sample() reuses it: weights rho/cos^2, tail index 1.5 */
static double wc_pdf(double c) { return c > 0 ? 3 * c * c / (2 * PI) : 0.0; }
static int wc_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *w, double *p)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++) {
        double c = fmin(fmax(cbrt(1 - u[3 * k]), 1e-12), 1.0), r = sqrt(fmax(0, 1 - c * c)),
               phi = 2 * PI * u[3 * k + 1];
        x[3 * k] = r * cos(phi), x[3 * k + 1] = r * sin(phi), x[3 * k + 2] = c;
        p[k] = wc_pdf(c), w[k] = 0.8 * 3 / (2 * PI) / p[k];
    }
    return 0;
}
static int wc_density(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++)
        out[k] = wc_pdf(x[3 * k + 2]);
    return 0;
}
static int wc_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++)
        out[k] = x[3 * k + 2] > 0 ? 0.8 * 3 / (2 * PI) : 0.0;
    return 0;
}

int main(void)
{
    static mcstat_check_report r;
    const double up[3] = {0, 0, 1};
    mcstat_check_model m = {MCSTAT_CHECK_DOMAIN_SPHERE, 2, MCSTAT_CHECK_WEIGHT_OVER_PDF, 1, NULL, iso_sample, iso_density,
                            iso_density, {{0, 0, 0, 0}}};
    int v = -1;
    uint32_t open = 99;

    /* float32 values: the derived floor, and the verdict */
    CHECK_INT(mcstat_check_phase(&m, up, 100000, 0, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK_MSG(!r.reject, "p = %g", r.p_value);
    CHECK(r.route[MCSTAT_CHECK_ROUTE_INTEGRALS].resolution == MCSTAT_RESOLUTION_FLOAT32);
    CHECK(r.route[MCSTAT_CHECK_ROUTE_ENERGY].resolution == MCSTAT_RESOLUTION_FLOAT32);
    CHECK(isnan(r.route[MCSTAT_CHECK_ROUTE_PDF_VALUE].resolution));
    CHECK_INT(mcstat_check_verdict(&r, &v, &open), MCSTAT_OK);
    CHECK(v == MCSTAT_CHECK_CONSISTENT && open == 0);
    char buf[8192];
    CHECK_INT(mcstat_check_format(&r, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "numerical floor: differences of 3.8e-06 relative") != NULL);

    /* the floor given: float64's shows the rounding as evidence */
    mcstat_check_options o;
    mcstat_check_options_init(&o);
    CHECK(o.size == MCSTAT_CHECK_OPTIONS_SIZE_0_3 && o.resolution == 0.0);
    o.resolution = MCSTAT_RESOLUTION_FLOAT64;
    CHECK_INT(mcstat_check_phase(&m, up, 100000, 0, 0.01, &o, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_INTEGRALS].reject);
    CHECK_INT(mcstat_check_verdict(&r, &v, NULL), MCSTAT_OK);
    CHECK(v == MCSTAT_CHECK_INCONSISTENT);
    /* 0.2's options: the field is beyond the caller's size, never read */
    mcstat_check_options old;
    CHECK_INT(mcstat_check_options_init_size(&old, MCSTAT_CHECK_OPTIONS_SIZE_0_2), MCSTAT_OK);
    old.resolution = 0.5;
    CHECK_INT(mcstat_check_phase(&m, up, 100000, 0, 0.01, &old, NULL, 0, &r), MCSTAT_OK);
    CHECK(!r.reject && r.route[MCSTAT_CHECK_ROUTE_INTEGRALS].resolution == MCSTAT_RESOLUTION_FLOAT32);
    double bad[] = {-1e-9, 0.01, 1.0, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        o.resolution = bad[i];
        CHECK_INT(mcstat_check_phase(&m, up, 100000, 0, 0.01, &o, NULL, 0, &r), MCSTAT_EINVAL);
    }

    /* heavy-tailed weights: inconclusive, the routes and why */
    mcstat_check_model wc = {MCSTAT_CHECK_DOMAIN_HEMISPHERE, 3, MCSTAT_CHECK_WEIGHT_OVER_PDF, 1, NULL, wc_sample, wc_density,
                             wc_eval, {{0, 0, 0, 0}}};
    CHECK_INT(mcstat_check_bsdf(&wc, up, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(!r.reject && r.heavy_tailed);
    CHECK_INT(mcstat_check_verdict(&r, &v, &open), MCSTAT_OK);
    CHECK(v == MCSTAT_CHECK_INCONCLUSIVE);
    CHECK(open & (1u << MCSTAT_CHECK_ROUTE_INTEGRALS) && open & (1u << MCSTAT_CHECK_ROUTE_ENERGY));
    CHECK(!(open & (1u << MCSTAT_CHECK_ROUTE_CELLS)));
    CHECK(r.route[MCSTAT_CHECK_ROUTE_ENERGY].why == MCSTAT_CHECK_WHY_HEAVY_TAIL);
    CHECK(r.route[MCSTAT_CHECK_ROUTE_CELLS].why == MCSTAT_CHECK_WHY_NONE);
    CHECK_INT(mcstat_check_format(&r, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "decision at alpha = 0.01: INCONCLUSIVE: no route rejected, but integrals, energy") != NULL);
    CHECK(strstr(buf, "consistent (no route rejected") == NULL);

    /* the words and bad input */
    CHECK(strcmp(mcstat_check_verdict_name(MCSTAT_CHECK_INCONCLUSIVE), "inconclusive") == 0);
    CHECK(mcstat_check_verdict_name(3) == NULL && mcstat_check_verdict_name(-1) == NULL);
    CHECK(strcmp(mcstat_check_why_text(MCSTAT_CHECK_WHY_NONE), "") == 0);
    for (int w = MCSTAT_CHECK_WHY_HEAVY_TAIL; w <= MCSTAT_CHECK_WHY_INTEGRATION; w++)
        CHECK(mcstat_check_why_text(w) != NULL && strlen(mcstat_check_why_text(w)) > 10);
    CHECK(mcstat_check_why_text(MCSTAT_CHECK_WHY_INTEGRATION + 1) == NULL && mcstat_check_why_text(-1) == NULL);
    v = 7;
    CHECK_INT(mcstat_check_verdict(NULL, &v, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_check_verdict(&r, NULL, NULL), MCSTAT_EINVAL);
    r.route[2].state = 9;
    CHECK_INT(mcstat_check_verdict(&r, &v, NULL), MCSTAT_EINVAL);
    CHECK(v == 7);
    return h_report("test_check_verdict");
}
