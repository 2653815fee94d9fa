/* mcstat_check_phase and mcstat_check_medium: an isotropic phase function
 * (correct; eval and weight 0.9 p: caught by energy), homogeneous free
 * flights up to a surface (correct; pdf() with sigma_t 10% off: caught by
 * pdf_value), the escapes' weights against T(tmax) (right, 10% low, and
 * a caller with 0.2's options), and bad arguments. */
#include "harness.h"
#include "mcstat.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

typedef struct { double scale; } phase;

static int iso_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *w, double *p)
{
    (void)wi;
    double s = ((phase *)user)->scale;
    for (size_t k = 0; k < n; k++) {
        double z = 1 - 2 * u[2 * k], r = sqrt(fmax(0, 1 - z * z)), phi = 2 * PI * u[2 * k + 1];
        x[3 * k] = r * cos(phi), x[3 * k + 1] = r * sin(phi), x[3 * k + 2] = z;
        w[k] = s, p[k] = 1 / (4 * PI);
    }
    return 0;
}
static int iso_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi, (void)x;
    for (size_t k = 0; k < n; k++) out[k] = 1 / (4 * PI);
    return 0;
}
static int iso_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)wi, (void)x;
    for (size_t k = 0; k < n; k++) out[k] = ((phase *)user)->scale / (4 * PI);
    return 0;
}

#define ST 2.0
#define SS 1.5
#define TMAX 1.0
typedef struct { double pdf_sigma; } medium;
static double dens(double t, double s) { return t < TMAX ? s * exp(-s * t) : 0.0; }
static int med_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *w, double *p)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++) {
        double t = -log1p(-u[k]) / ST;
        int in = t < TMAX;
        x[k] = in ? t : 0, p[k] = in ? dens(t, ST) : 0, w[k] = in ? SS / ST : 0;
    }
    return 0;
}
/* analog flights whose escapes carry weight esc_weight (1 is right) */
static double esc_weight = 1.0;
static int med_sample_esc(void *user, const double *wi, const double *u, size_t n, double *x, double *w, double *p)
{
    med_sample(user, wi, u, n, x, w, p);
    for (size_t k = 0; k < n; k++)
        if (p[k] == 0) w[k] = esc_weight;
    return 0;
}
static int med_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)wi;
    for (size_t k = 0; k < n; k++) out[k] = dens(x[k], ((medium *)user)->pdf_sigma);
    return 0;
}
static int med_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++) out[k] = SS / ST * dens(x[k], ST);
    return 0;
}

int main(void)
{
    static mcstat_check_report r;
    const double wi[3] = {0, 0.6, 0.8};
    phase ph = {1.0};
    mcstat_check_model m = {MCSTAT_CHECK_DOMAIN_SPHERE, 2, MCSTAT_CHECK_WEIGHT_OVER_PDF, 1, &ph, iso_sample, iso_pdf, iso_eval,
                            {{0, 0, 0, 0}}};
    CHECK_INT(mcstat_check_phase(&m, wi, 5000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(!r.reject && r.kind == MCSTAT_CHECK_KIND_PHASE && r.route[MCSTAT_CHECK_ROUTE_ENERGY].state == MCSTAT_CHECK_STATE_RAN);
    CHECK_REL(r.wi[1], 0.6, 1e-12, "wi");
    ph.scale = 0.9; /* passes the BSDF check (absorption allowed), not the phase check */
    CHECK_INT(mcstat_check_bsdf(&m, wi, 5000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(!r.reject);
    CHECK_INT(mcstat_check_phase(&m, wi, 5000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_ENERGY].reject);
    char buf[4096];
    CHECK_INT(mcstat_check_format(&r, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "Phase function check") != NULL);
    m.domain = MCSTAT_CHECK_DOMAIN_HEMISPHERE;
    CHECK_INT(mcstat_check_phase(&m, wi, 5000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    m.domain = MCSTAT_CHECK_DOMAIN_SPHERE;
    const double zero[3] = {0, 0, 0};
    CHECK_INT(mcstat_check_phase(&m, zero, 5000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);

    medium md = {ST};
    mcstat_check_model d = {MCSTAT_CHECK_DOMAIN_INTERVAL, 1, MCSTAT_CHECK_WEIGHT_OVER_PDF, 1, &md, med_sample, med_pdf, med_eval,
                            {{0, 0, 0, 0}}};
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(!r.reject && r.kind == MCSTAT_CHECK_KIND_MEDIUM && r.sigma_ref == 2.0);
    CHECK_REL(r.mass, 1 - exp(-ST * TMAX), 1e-3, "mass");
    CHECK_INT(mcstat_check_format(&r, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "x = 1 - exp(-2 t)") != NULL);
    md.pdf_sigma = 1.1 * ST;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_PDF_VALUE].reject);
    CHECK_INT(mcstat_check_medium(&d, 0.0, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_check_medium(&d, NAN, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_check_medium(&d, INFINITY, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    /* escapes' weights against T(tmax) (options of 0.3), and a 0.2-sized options struct */
    md.pdf_sigma = ST;
    mcstat_check_options o;
    mcstat_check_options_init(&o);
    CHECK(o.escape_transmittance < 0);
    o.escape_transmittance = exp(-ST * TMAX);
    d.sample = med_sample_esc;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, &o, NULL, 0, &r), MCSTAT_OK);
    CHECK_MSG(!r.reject, "escapes of weight 1: p = %g", r.p_value);
    CHECK_REL(r.escape_weight, (double)r.n_failed / (double)r.n, 1e-12, "analog: the escape share");
    CHECK_REL(r.route[MCSTAT_CHECK_ROUTE_MASS].value[1], exp(-ST * TMAX), 1e-15, "T(tmax)");
    CHECK_INT(mcstat_check_format(&r, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "escape weights") != NULL);
    esc_weight = 0.9;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, &o, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_MASS].reject);
    mcstat_check_options old;
    CHECK_INT(mcstat_check_options_init_size(&old, MCSTAT_CHECK_OPTIONS_SIZE_0_2), MCSTAT_OK);
    old.escape_transmittance = 0.5; /* beyond the caller's size: never read */
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, &old, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_WEIGHT].reject && isnan(r.escape_weight)); /* escapes must weigh 0 */
    esc_weight = 0.0;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, &old, NULL, 0, &r), MCSTAT_OK);
    CHECK(!r.reject);
    o.escape_transmittance = NAN;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, &o, NULL, 0, &r), MCSTAT_EINVAL);
    o.escape_transmittance = 1.5;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, &o, NULL, 0, &r), MCSTAT_EINVAL);
    o.escape_transmittance = 0.5;
    d.weight = MCSTAT_CHECK_WEIGHT_VALUE;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, &o, NULL, 0, &r), MCSTAT_EINVAL);
    d.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    CHECK_INT(mcstat_check_phase(&m, wi, 5000, 1, 0.01, &o, NULL, 0, &r), MCSTAT_EINVAL);
    d.sample = med_sample;
    d.domain = MCSTAT_CHECK_DOMAIN_SQUARE;
    CHECK_INT(mcstat_check_medium(&d, 2.0, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    return h_report("test_check_phase");
}
