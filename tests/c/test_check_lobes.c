/* Discrete lobes in mcstat_check_bsdf: a coated diffuse BSDF (a specular
 * reflection picked with probability Q, weight F/Q, over a Lambertian base;
 * correct), the same with the specular weight 5% off (weight), the lobe
 * picked more often than its pdf says (mass), the base's weight 5% off
 * (the smooth part, checked as before), a lobe never sampled (support),
 * and lobes() giving garbage (ECALLBACK naming it). */
#include "harness.h"
#include "mcstat.h"

#include <math.h>
#include <string.h>

static const double PI = 3.14159265358979323846;
#define Q 0.3
#define RHO 0.6

typedef struct {
    double spec_weight, pick, base_weight; /* 1: correct */
    int garbage;                           /* lobes(): 0 correct, 1.. a kind of garbage */
} coated;

static double fresnel(double c) { return 0.04 + 0.96 * pow(1 - c, 5); }

static int co_sample(void *user, const double *wi, const double *u, size_t n, double *x, double *w, double *p)
{
    const coated *b = user;
    double F = fresnel(wi[2]);
    for (size_t k = 0; k < n; k++) {
        const double *v = u + 3 * k;
        double *d = x + 3 * k;
        if (v[0] < Q * b->pick) {
            d[0] = -wi[0], d[1] = -wi[1], d[2] = wi[2];
            p[k] = Q, w[k] = F / Q * b->spec_weight;
        } else {
            double r = sqrt(v[1]), phi = 2 * PI * v[2];
            d[0] = r * cos(phi), d[1] = r * sin(phi), d[2] = sqrt(1 - v[1]);
            p[k] = (1 - Q) * d[2] / PI, w[k] = (1 - F) * RHO / (1 - Q) * b->base_weight;
        }
    }
    return 0;
}
static int co_pdf(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user, (void)wi;
    for (size_t k = 0; k < n; k++) out[k] = (1 - Q) * fmax(x[3 * k + 2], 0) / PI;
    return 0;
}
static int co_eval(void *user, const double *wi, const double *x, size_t n, double *out)
{
    (void)user;
    for (size_t k = 0; k < n; k++) out[k] = (1 - fresnel(wi[2])) * RHO * fmax(x[3 * k + 2], 0) / PI;
    return 0;
}
static int co_lobes(void *user, const double *wi, double *x, double *mass, double *value, size_t *count)
{
    const coated *b = user;
    x[0] = -wi[0], x[1] = -wi[1], x[2] = wi[2];
    mass[0] = Q, value[0] = fresnel(wi[2]);
    *count = 1;
    switch (b->garbage) {
    case 1: return 7;                               /* a status */
    case 2: *count = MCSTAT_CHECK_MAX_LOBES + 1; break; /* too many */
    case 3: mass[0] = 1.5; break;                   /* not a probability */
    case 4: x[2] = NAN; break;                      /* not a direction */
    case 5: /* the same lobe twice */
        memcpy(x + 3, x, 3 * sizeof *x), mass[1] = 0, value[1] = 0, *count = 2;
        break;
    case 6: /* a second lobe with energy that sample() never returns */
        x[3] = 0, x[4] = 0, x[5] = 1, mass[1] = 0, value[1] = 0.1, *count = 2;
        break;
    case 7: value[0] = -1; break;                   /* a negative value */
    case 8: *count = (size_t)-1; break;             /* *count left unset */
    }
    return 0;
}

int main(void)
{
    static mcstat_check_report r;
    const double wi[3] = {0.4, 0.1, 0.9};
    coated b = {1, 1, 1, 0};
    mcstat_check_model m = {MCSTAT_CHECK_DOMAIN_HEMISPHERE, 3, MCSTAT_CHECK_WEIGHT_OVER_PDF, 1, &b, co_sample, co_pdf, co_eval,
                            {{0, 0, 0, 0}}};
    m.lobes = co_lobes;
    CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK_MSG(!r.reject, "correct coated BSDF rejected, p = %g", r.p_value);
    CHECK(r.lobes == 1 && r.n_lobe > 5000 && r.n_lobe < 7000 && r.n_failed == 0);
    CHECK_REL(r.lobe_mass, Q, 1e-15, "lobe mass");
    CHECK_REL(r.lobe_albedo, fresnel(0.9 / sqrt(0.98)), 1e-12, "lobe albedo");
    CHECK(r.route[MCSTAT_CHECK_ROUTE_CELLS].state == MCSTAT_CHECK_STATE_RAN);
    CHECK(r.route[MCSTAT_CHECK_ROUTE_PDF_VALUE].checked == 20000); /* smooth and discrete samples */
    /* the smooth albedo from the weights against eval's; the discrete part apart */
    CHECK_REL(r.albedo, (1 - fresnel(0.9 / sqrt(0.98))) * RHO, 0.02, "smooth albedo");
    char buf[4096];
    CHECK_INT(mcstat_check_format(&r, buf, sizeof buf, NULL), MCSTAT_OK);
    CHECK(strstr(buf, "discrete lobes: 1") != NULL);

    /* without lobes(), the same sampler fails: its specular samples have pdf Q where pdf() is a density */
    m.lobes = NULL;
    CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_PDF_VALUE].reject);
    m.lobes = co_lobes;

    b.spec_weight = 1.05;
    CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_WEIGHT].reject && !r.route[MCSTAT_CHECK_ROUTE_PDF_VALUE].reject);
    CHECK_REL(r.route[MCSTAT_CHECK_ROUTE_WEIGHT].effect, 0.05 / 1.05, 1e-9, "weight's largest difference");
    b.spec_weight = 1;

    b.pick = 1.1; /* picked at 0.33, reported 0.3 */
    CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_MASS].reject && !r.route[MCSTAT_CHECK_ROUTE_WEIGHT].reject);
    CHECK_REL(r.route[MCSTAT_CHECK_ROUTE_MASS].value[1], Q, 1e-15, "mass route: the lobe's mass");
    CHECK(fabs(r.route[MCSTAT_CHECK_ROUTE_MASS].value[0] - 0.33) < 0.01);
    CHECK_REL(r.route[MCSTAT_CHECK_ROUTE_MASS].where[0], -wi[0] / sqrt(0.98), 1e-12, "mass route: the lobe");
    b.pick = 1;

    b.base_weight = 1.05; /* the smooth part is checked as before */
    CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_WEIGHT].reject);
    b.base_weight = 1;

    b.garbage = 6;
    CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_OK);
    CHECK(r.reject && r.route[MCSTAT_CHECK_ROUTE_SUPPORT].reject);

    static const char *want[] = {NULL, "status 7", "at most", "mass 1.5", "not in the hemisphere",
                                 "same direction", NULL, "value -1", "without setting *count"};
    for (int g = 1; g <= 8; g++) {
        if (!want[g])
            continue;
        b.garbage = g;
        CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_ECALLBACK);
        CHECK_MSG(strstr(r.message, "lobes()") && strstr(r.message, want[g]), "garbage %d: %s", g, r.message);
    }
    b.garbage = 0;

    /* lobes are for BSDFs; the reserved fields stay zero */
    m.domain = MCSTAT_CHECK_DOMAIN_SPHERE;
    CHECK_INT(mcstat_check_phase(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    CHECK_INT(mcstat_check_emitter(&m, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    m.domain = MCSTAT_CHECK_DOMAIN_HEMISPHERE;
    m.reserved_rest[0] = 1;
    CHECK_INT(mcstat_check_bsdf(&m, wi, 20000, 1, 0.01, NULL, NULL, 0, &r), MCSTAT_EINVAL);
    m.reserved_rest[0] = 0;
    CHECK_INT(mcstat_sizeof_check_model() == 80 || sizeof(void *) != 8, 1); /* 0.2.0's size */
    return h_report("test_check_lobes");
}
