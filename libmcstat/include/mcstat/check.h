/*
 * mcstat/check.h - renderer checks: do a BSDF's, an emitter's or a warp's
 * sample(), pdf(), eval() and sample weight agree?
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_CHECK_FAMILY_H
#define MCSTAT_CHECK_FAMILY_H

#include "tests.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 9. Renderer checks.                                                    */
/* Do a BSDF's sample(), pdf(), eval() and sample weight agree?  The        */
/* renderer hands over its routines as callbacks; mcstat feeds them its own  */
/* uniform numbers, runs a battery of checks ("routes") and controls the     */
/* battery's error rate.  Emitters (sampling directions from a reference    */
/* point) and warps (square, disk, interval) are checked the same way.      */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* The model a renderer hands over.                                          */
/* Points live in a domain:                                                  */
/*   SPHERE       unit directions (x, y, z): BSDFs with transmission,        */
/*                emitters;                                                  */
/*   HEMISPHERE   unit directions with z >= 0 (the shading normal is +z):    */
/*                reflection-only BSDFs;                                     */
/*   SQUARE       (x, y) in [0, 1]^2;  DISK  (x, y), x^2 + y^2 <= 1;         */
/*   INTERVAL     x in [0, 1].                                               */
/* Densities are with respect to solid angle (directions) or area/length.   */
/* Callbacks (each returns 0 on success, anything else to stop the check:   */
/* MCSTAT_ECALLBACK then names it), called only from the calling thread,    */
/* n points at a time (n <= the options' batch):                             */
/*   sample(user, wi, u, n, x, weight, pdf): for k < n, from the uniforms    */
/*     u[k*n_uniforms ..] in [0, 1) (multiples of 2^-53: a float renderer    */
/*     that converts them must clamp, as those above 1 - 2^-25 round to      */
/*     1.0f, outside [0, 1): min(u, nextafterf(1, 0)) keeps its contract),   */
/*     point x[k*dims ..], the sample weight                                 */
/*     weight[k] and the density pdf[k] the renderer's sampler reports.  A   */
/*     sample that failed (the renderer's "invalid sample") has pdf 0 and    */
/*     weight 0; x is then ignored.  With MCSTAT_CHECK_WEIGHT_OVER_PDF       */
/*     (Mitsuba's BSDFSample weight) weight = eval/pdf; with                 */
/*     MCSTAT_CHECK_WEIGHT_VALUE (pbrt's Sample_f times |cos|) weight =      */
/*     eval.                                                                 */
/*   pdf(user, wi, x, n, out): out[k] the density at x[k*dims ..].           */
/*   eval(user, wi, x, n, out): out[k] the integrand the sampler is built    */
/*     for: f(wi, x) |cos(x)| for a BSDF (Mitsuba's eval includes the        */
/*     cosine), the radiance arriving along x for an emitter.  NULL for a   */
/*     warp (no integrand: only the sampler and its density are checked).   */
/* wi is the fixed direction given to mcstat_check_bsdf (NULL for emitters   */
/* and warps; an emitter's reference point lives in `user`).  Callbacks run */
/* under IEEE defaults (see the conventions above): a renderer built to     */
/* flush subnormals sees them kept inside the check.                         */
/* ------------------------------------------------------------------------ */
enum mcstat_check_domain {
    MCSTAT_CHECK_DOMAIN_SPHERE = 0,
    MCSTAT_CHECK_DOMAIN_HEMISPHERE = 1,
    MCSTAT_CHECK_DOMAIN_SQUARE = 2,
    MCSTAT_CHECK_DOMAIN_DISK = 3,
    MCSTAT_CHECK_DOMAIN_INTERVAL = 4,
    /* the names before 0.3 (mcstat/deprecated.h) */
    MCSTAT_DOMAIN_SPHERE MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_DOMAIN_SPHERE") = 0,
    MCSTAT_DOMAIN_HEMISPHERE MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_DOMAIN_HEMISPHERE") = 1,
    MCSTAT_DOMAIN_SQUARE MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_DOMAIN_SQUARE") = 2,
    MCSTAT_DOMAIN_DISK MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_DOMAIN_DISK") = 3,
    MCSTAT_DOMAIN_INTERVAL MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_DOMAIN_INTERVAL") = 4
};

enum mcstat_check_weight {
    MCSTAT_CHECK_WEIGHT_OVER_PDF = 0, /* weight = eval / pdf (Mitsuba, most path tracers) */
    MCSTAT_CHECK_WEIGHT_VALUE = 1,    /* weight = eval (the sampled value, not divided) */
    /* the names before 0.3 (mcstat/deprecated.h) */
    MCSTAT_WEIGHT_OVER_PDF MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_WEIGHT_OVER_PDF") = 0,
    MCSTAT_WEIGHT_VALUE MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_WEIGHT_VALUE") = 1
};

#define MCSTAT_CHECK_MAX_UNIFORMS 8

typedef int (*mcstat_check_sample_fn)(void *user, const double *wi, const double *u, size_t n, double *x,
                                      double *weight, double *pdf);
typedef int (*mcstat_check_density_fn)(void *user, const double *wi, const double *x, size_t n,
                                       double *out);

/* Discrete lobes (specular reflection and refraction: a BSDF whose sample()
 * returns a direction with a probability, not a density).  pdf() and
 * eval() then describe the smooth part only (as Mitsuba's and pbrt's do),
 * and lobes(user, wi, x, mass, value, count) describes the rest for the
 * check's wi: *count <= MCSTAT_CHECK_MAX_LOBES lobes (x, mass and value
 * have room for that many, no more), lobe k with its
 * direction x[3k ..] (unit length, in the domain), the probability
 * mass[k] in [0, 1] with which sample() returns it (what sample()
 * reports as its pdf there), and value[k] >= 0, the integral of
 * f |cos| over the lobe (its albedo: Fresnel's R for a mirror-like
 * reflection), so that its weight is value/mass (MCSTAT_CHECK_WEIGHT_VALUE:
 * value).  A sample within MCSTAT_CHECK_LOBE_TOLERANCE (chord length) of
 * a lobe's direction is that lobe's sample; lobes must lie further apart
 * than twice that.  Called once per check (mcstat_check_bsdf only). */
#define MCSTAT_CHECK_MAX_LOBES 4
#define MCSTAT_CHECK_LOBE_TOLERANCE 1e-4
typedef int (*mcstat_check_lobes_fn)(void *user, const double *wi, double *x, double *mass, double *value,
                                     size_t *count);

typedef struct mcstat_check_model {
    int32_t domain;            /* enum mcstat_check_domain */
    int32_t n_uniforms;        /* uniforms per sample, 1..MCSTAT_CHECK_MAX_UNIFORMS (Mitsuba's BSDFs: 3) */
    int32_t weight;            /* enum mcstat_check_weight */
    int32_t sample_reports;    /* 1: sample() writes weight and pdf (BSDFs, emitters); 0: only x
                                  (warps: every sample succeeds, pdf() gives its density) */
    void *user;                /* passed to every callback */
    mcstat_check_sample_fn sample;
    mcstat_check_density_fn pdf;
    mcstat_check_density_fn eval; /* NULL: no integrand (warps) */
    MCSTAT_ANONYMOUS union {
        double reserved[4];    /* zero */
        MCSTAT_ANONYMOUS struct {
            mcstat_check_lobes_fn lobes; /* NULL: no discrete lobes (0.2.0's zeros) */
            double reserved_rest[3];     /* zero */
        };
    };
} mcstat_check_model;

/* Coordinates per point of a domain (3, 3, 2, 2, 1); 0 for a bad domain. */
MCSTAT_API int mcstat_check_domain_dims(int domain);
/* "sphere", "hemisphere", "square", "disk", "interval" and back. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_domain_parse(const char *name, int *domain);
MCSTAT_API const char *mcstat_check_domain_name(int domain); /* NULL if invalid */

/* ------------------------------------------------------------------------ */
/* The routes.                                                               */
/* Each route checks one claim, and names what it cannot see:              */
/*   CELLS        sample() draws from the density pdf() claims: Pearson's    */
/*                chi-squared of the successful samples' counts in cells of  */
/*                (nearly) equal probability.  Cells: a k-d tree over the    */
/*                domain's equal-area square (directions: s = (1 - z)/2,     */
/*                t = phi/(2 pi)), split at medians of an independent pilot  */
/*                sample until each leaf holds 32 pilot points (the sphere   */
/*                is cut at the horizon first); each cell's probability is   */
/*                the integral of pdf() over it by adaptive cubature (Genz-  */
/*                Malik 7/5, splitting where the rules disagree) to 5% of    */
/*                the cell count's sampling sd.  A rectangle where pdf() is  */
/*                0 at some of its 17 points and 4 corner probes and not at  */
/*                others holds the support's edge: its error is then bounded */
/*                by the estimate's distance to area times the least or the  */
/*                largest value seen, and it is halved across the edge; when */
/*                the rectangles run out, the largest errors are halved      */
/*                first.  Rectangles on a pole of the sphere (the disk's     */
/*                centre: lines of the square) start as layers shrinking by  */
/*                4 toward it, so that a narrow peak there is integrated.    */
/*                Consecutive cells are pooled until the expected            */
/*                count is 5, and the remaining cubature error enters each   */
/*                cell's variance, so an integration that falls short costs  */
/*                power, never the level.                                    */
/*                df = pooled cells - 1.  Beside this fine level, a coarse   */
/*                one pools the same cells, in the same order, into about    */
/*                16 groups (where the fine level has more than 32): a      */
/*                smooth error (a parameter a few percent off) moves         */
/*                probability between large regions, which hundreds of      */
/*                cells dilute.  The p-value is twice the smaller of the     */
/*                two (Bonferroni); statistic and df are the deciding        */
/*                level's.  Blind to: pdf() scaled by a constant,            */
/*                everything about weights and eval.                         */
/*   MASS         the fraction of samples that succeed equals the integral   */
/*                of pdf() over the domain.  Two estimates: the cubature's  */
/*                integral C (error e) and the mean M of pdf/table at the   */
/*                n_eval points of a table of the cubature's rectangles     */
/*                (each weighing its integral and its error, plus its share */
/*                of a cell's significant excess of pilot points over the   */
/*                cell's integral; unbiased, standard error s).  When M's   */
/*                values                                                    */
/*                are not heavy-tailed (Hill index >= 2.5) and either the   */
/*                two disagree (|C - M| > 4e + 3s) or M is the more precise  */
/*                (3s < 4e), a two-sided z test against M; otherwise the    */
/*                exact binomial test, conservative over the interval that  */
/*                spans both C +- 4e and M +- 3s (it holds the true integral */
/*                when either error statement does); p = 0 only when both   */
/*                ends are above 1.  With discrete lobes, the                */
/*                smooth successes are tested so, and each lobe's count by  */
/*                the exact binomial test against n mass[k]; the route's    */
/*                p-value is the smallest times (lobes + 1) (Bonferroni),   */
/*                where/value the lobe furthest off (its direction, share    */
/*                and mass).  mcstat_check_medium with escape_transmittance */
/*                adds the escapes' weights (a t test, in the same         */
/*                Bonferroni; value: their mean and T(tmax)).  Catches      */
/*                pdf() scaled by a constant, samples                        */
/*                lost, a lobe chosen at a rate other than its pdf says.    */
/*   PDF_VALUE    the pdf sample() reports equals pdf() at the sampled point */
/*                (deterministic: relative tolerance rtol at every sample); */
/*                on a discrete lobe, its mass.  A point whose coordinates  */
/*                are float32 values (a float renderer's) passes when the   */
/*                difference is within rtol plus 4 ulps' worth of pdf()'s   */
/*                change at the point's float32 neighbours: rounding where  */
/*                pdf() is ill-conditioned (grazing half vectors).  WEIGHT   */
/*                likewise.                                                  */
/*   WEIGHT       the weight equals eval/pdf (deterministic, as PDF_VALUE);  */
/*                a failed sample has weight 0; on a discrete lobe, value/   */
/*                mass.                                                      */
/*   SUPPORT      eval > 0 only where pdf > 0, at the sampled points and at  */
/*                the eval-only estimator's points (a region the sampler     */
/*                never reaches biases every estimate using it); a discrete */
/*                lobe with value > 0 has mass > 0.  pdf > 0 where eval = 0  */
/*                is counted (wasted samples), not a failure.                */
/*   INTEGRALS    eval against the sampler, end to end: the integrals of     */
/*                eval over up to 16 regions (consecutive runs of cells),    */
/*                estimated from the sample weights and from an estimator    */
/*                that uses only eval (points from a table of the cells'     */
/*                probabilities, mixed 9:1 with uniform points so that every */
/*                region is reached), compared by a Wald test (chi-squared   */
/*                on the regions, covariances estimated).  The statistical   */
/*                form of WEIGHT: it is what checks a stochastic BSDF.       */
/*   ENERGY       albedo <= 1: one-sided t test of the mean weight (BSDFs;   */
/*                discrete lobes' weights included).                        */
/* CELLS, INTEGRALS, KS and RECIPROCITY see the smooth part only: samples   */
/* on a discrete lobe are left out of them (INTEGRALS: weight 0 there).    */
/*   RECIPROCITY  eval(wi, x)/|x.z| == eval(x, wi)/|wi.z| at up to 1000     */
/*                sampled points (deterministic; only when asked: BSDFs      */
/*                with refraction are not reciprocal in radiance).           */
/*   KS           the sampler's weighted distribution against eval's, point  */
/*                by point rather than by region: the sampled points kept    */
/*                with probability weight/W (W twice the pilot's largest    */
/*                weight: importance resampling, so that the kept points     */
/*                follow eval if the weights are right) against points drawn */
/*                from eval by rejection from the eval-only estimator's      */
/*                table (the envelope twice the largest eval/table of the   */
/*                first half of its points; the second half are proposals), */
/*                by the two-sample K-S test with Canner's weight on Morton     */
/*                keys of the equal-area square, at most 20000 points a     */
/*                side (the exact p-value's cost).  An envelope exceeded    */
/*                makes the route INVALID (the report says which).          */
/* Heavy tails: INTEGRALS and ENERGY need finite variance.  When the Hill   */
/* tail index of the weights (or of the eval-only estimates) is below 2,    */
/* those routes are INVALID (not run) and the report says why.              */
/* The verdict: deterministic routes reject when more than the tolerated    */
/* share of points (option `tolerated`) differ beyond rtol;                 */
/* the statistical routes' p-values are adjusted across routes (Holm), and  */
/* the check rejects when any adjusted p-value is <= alpha: a correct model */
/* is rejected with probability at most alpha (the cubature and the         */
/* asymptotic tests being approximations; measured: tests/python/           */
/* test_check_calibration.py and bench/).  A check that did not reject but  */
/* needed a route that could not answer is inconclusive, not consistent    */
/* (mcstat_check_verdict, below the report).                                */
/* The numerical floor: differences at the resolution of the caller's       */
/* arithmetic are not evidence.  The statistical routes add the options'    */
/* resolution (derived from the values by default: float32 or float64) as a */
/* relative error of what they compare (CELLS: of each cell's probability; */
/* MASS: of the mass; INTEGRALS: a common and a per-region error; ENERGY: */
/* of the albedo), and report it.                                           */
/* ------------------------------------------------------------------------ */
enum mcstat_check_route {
    MCSTAT_CHECK_ROUTE_CELLS = 0,
    MCSTAT_CHECK_ROUTE_MASS = 1,
    MCSTAT_CHECK_ROUTE_PDF_VALUE = 2,
    MCSTAT_CHECK_ROUTE_WEIGHT = 3,
    MCSTAT_CHECK_ROUTE_SUPPORT = 4,
    MCSTAT_CHECK_ROUTE_INTEGRALS = 5,
    MCSTAT_CHECK_ROUTE_ENERGY = 6,
    MCSTAT_CHECK_ROUTE_RECIPROCITY = 7,
    MCSTAT_CHECK_ROUTE_KS = 8,
    MCSTAT_CHECK_ROUTE_COUNT = 9 /* number of routes */
};

/* "cells", "mass", "pdf_value", "weight", "support", "integrals", "energy",
 * "reciprocity", "ks" and back. */
MCSTAT_API const char *mcstat_check_route_name(int route); /* NULL if invalid */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_route_parse(const char *name, int *route);

enum mcstat_check_state {
    MCSTAT_CHECK_STATE_RAN = 0,
    MCSTAT_CHECK_STATE_SKIPPED = 1, /* not asked for, or not applicable to this model */
    MCSTAT_CHECK_STATE_INVALID = 2, /* an assumption failed (heavy tails, too few samples): no answer */
    /* the names before 0.3 (mcstat/deprecated.h) */
    MCSTAT_ROUTE_RAN MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_STATE_RAN") = 0,
    MCSTAT_ROUTE_SKIPPED MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_STATE_SKIPPED") = 1,
    MCSTAT_ROUTE_INVALID MCSTAT_DEPRECATED_ENUMERATOR("MCSTAT_CHECK_STATE_INVALID") = 2
};

/* Why a route could not answer (its state INVALID): the report's `why`.
 * mcstat_check_why_text gives the reason and what would let it answer. */
enum mcstat_check_why {
    MCSTAT_CHECK_WHY_NONE = 0,        /* it answered (or was skipped) */
    MCSTAT_CHECK_WHY_HEAVY_TAIL = 1,  /* a tail index below 2: the mean it tests has no finite variance */
    MCSTAT_CHECK_WHY_TOO_FEW = 2,     /* too few samples, cells, regions or kept points */
    MCSTAT_CHECK_WHY_ENVELOPE = 3,    /* KS: a ratio beyond the resampling envelope */
    MCSTAT_CHECK_WHY_NOTHING = 4,     /* nothing to compare: eval() and the weights are 0 wherever looked,
                                         or no smooth part is claimed or sampled (a purely discrete BSDF) */
    MCSTAT_CHECK_WHY_NUMERIC = 5,     /* a numerical step failed */
    MCSTAT_CHECK_WHY_INTEGRATION = 6  /* the integral of pdf() is not known well enough to test against */
};
/* A sentence: the reason a route could not answer and what would let it
 * answer; "" for MCSTAT_CHECK_WHY_NONE, NULL for an invalid value. */
MCSTAT_API const char *mcstat_check_why_text(int why);


/* ------------------------------------------------------------------------ */
/* Options; grows by appending fields ("Conventions"), so always start     */
/* from the initialiser.                                                    */
/* ------------------------------------------------------------------------ */
typedef struct mcstat_check_options {
    uint32_t size;         /* sizeof(mcstat_check_options): set by the initialiser */
    uint32_t routes;       /* bit (1u << route) for each route to run; default all
                              (routes that do not apply to the model are skipped) */
    int32_t stochastic;    /* 1: weight and pdf are estimates (layered BSDFs): PDF_VALUE and
                              WEIGHT are skipped, INTEGRALS checks them; default 0 */
    int32_t reciprocal;    /* 1: run RECIPROCITY; default 0 */
    int32_t cells;         /* target cells for CELLS, 0 or 2..2^20; 0 (default): 2 n^0.4 within
                              [8, 8192]; the tree gives within a factor 1.4 of it */
    int32_t reserved_i;    /* zero */
    uint64_t n_pilot;      /* pilot samples for the cells, 0 or >= 64 (at most 2^40); 0
                              (default): 32 per target cell */
    uint64_t n_eval;       /* points of the eval-only estimator, 0 or >= 1000; 0 (default): n */
    uint64_t batch;        /* points per callback call, 64..2^32; default 65536 */
    double rtol;           /* relative tolerance of the deterministic routes, in (0, 1); default
                              1e-3 (renderers computing in float32 differ at ~1e-6) */
    double tolerated;      /* share of checked points a deterministic route lets differ beyond
                              rtol, in [0, 1); default 1e-4: float32 renderers miss a light's rim
                              on a retraced point, or lose digits at grazing angles, in about 1e-5
                              of samples (measured on Mitsuba 3); a real bug of a region of
                              probability 1e-3 is still seen at n = 1e5 */
    double reserved[4];    /* zero */
    /* since 0.3 (MCSTAT_CHECK_OPTIONS_SIZE_0_3): */
    double escape_transmittance; /* mcstat_check_medium: < 0 (default -1): a flight that passes the
                              surface is a failed sample, weight 0, its weight not checked; in
                              [0, 1]: T(tmax), the transmittance to the surface, and such a flight
                              reports pdf 0 and the weight it carries on (1 for analog tracking,
                              T(tmax)/P(escape) when the distances follow another density): MASS
                              also tests that the mean over the n flights of the escapes' weights
                              (0 for a scattering) equals T(tmax), by a two-sided t test.  Needs
                              MCSTAT_CHECK_WEIGHT_OVER_PDF */
    double resolution;     /* the relative resolution of the caller's arithmetic: differences of
                              integrals at that scale are rounding, not evidence.  The statistical
                              routes add it as an error of what they compare (INTEGRALS: a
                              relative error common to all regions and one of each region, of
                              this size each, in the variance of the difference; ENERGY: one of
                              the albedo; MASS and CELLS: one of the mass and of each cell's
                              probability), and each route reports it.  0 (default): derived from the values the callbacks return,
                              MCSTAT_RESOLUTION_FLOAT32 when every pdf, weight and eval value
                              is a float32 (a renderer computing in float), else
                              MCSTAT_RESOLUTION_FLOAT64; > 0: that value, below 0.01 */
    /* routes must not be 0; reserved fields and the model's must be zero
     * (later releases may give them a meaning): MCSTAT_EINVAL otherwise. */
} mcstat_check_options;

#define MCSTAT_CHECK_ROUTE_ALL ((1u << MCSTAT_CHECK_ROUTE_COUNT) - 1u)
#define MCSTAT_CHECK_OPTIONS_INIT \
    {sizeof(mcstat_check_options), MCSTAT_CHECK_ROUTE_ALL, 0, 0, 0, 0, 0, 0, 65536, 1e-3, 1e-4, {0, 0, 0, 0}, -1.0, 0.0}


/* sizeof(mcstat_check_options) in each release that changed it. */
#define MCSTAT_CHECK_OPTIONS_SIZE_0_2 96u
#define MCSTAT_CHECK_OPTIONS_SIZE_0_3 112u
/* Sets the first `size` bytes of *opt to MCSTAT_CHECK_OPTIONS_INIT, with
 * opt->size = size (as mcstat_gof_options_init_size). */
MCSTAT_API int mcstat_check_options_init_size(mcstat_check_options *opt, size_t size);
#define mcstat_check_options_init(opt) mcstat_check_options_init_size((opt), sizeof *(opt))
MCSTAT_API size_t mcstat_sizeof_check_options(void);
MCSTAT_API size_t mcstat_sizeof_check_model(void);
MCSTAT_API size_t mcstat_sizeof_check_report(void);

/* ------------------------------------------------------------------------ */
/* The report.                                                               */
/* Per route: its state, whether it is deterministic, its verdict, and      */
/*   statistic, df, p_value, p_adjusted   (statistical routes; NaN otherwise) */
/*   effect       the departure measured: CELLS Cohen's w = sqrt(X^2/N);     */
/*                MASS and INTEGRALS and ENERGY the relative difference of   */
/*                the two sides; deterministic routes the largest relative   */
/*                difference seen                                            */
/*   detectable   the smallest departure of the same kind this run detects  */
/*                with probability 0.8 at alpha (normal approximations);    */
/*                deterministic routes: the smallest probability of a       */
/*                region where any error above rtol is caught with          */
/*                probability 0.8, -ln(0.2)/checked                         */
/*   n_for_1pct   samples the route needs to detect a 1% departure with     */
/*                probability 0.8 (CELLS: w = 0.01; MASS, INTEGRALS, ENERGY: */
/*                1% relative; deterministic: a region of probability 1%)   */
/*   checked, count  points checked and points beyond tolerance (CELLS:      */
/*                samples and pooled cells)                                  */
/*   where, value[2]  deterministic routes: the point of the largest         */
/*                difference and the two values that differ there           */
/* ------------------------------------------------------------------------ */
typedef struct mcstat_check_route_result {
    int32_t state;         /* enum mcstat_check_state */
    int32_t deterministic; /* 1: a tolerance check, not a test */
    int32_t reject;
    MCSTAT_ANONYMOUS union {
        int32_t reserved_i; /* 0.2.0's name of this storage */
        int32_t why;        /* state INVALID: enum mcstat_check_why; else 0 */
    };
    double statistic, df, p_value, p_adjusted;
    double effect, detectable, n_for_1pct;
    uint64_t checked, count;
    double where[3];
    double value[2];
    MCSTAT_ANONYMOUS union {
        double reserved[3]; /* 0.2.0's name of this storage */
        MCSTAT_ANONYMOUS struct {
            /* statistical routes: the numerical floor they applied, relative
               (options' resolution); NaN for the deterministic ones */
            double resolution;
            double reserved_2[2]; /* zero */
        };
    };
} mcstat_check_route_result;

enum mcstat_check_kind {
    MCSTAT_CHECK_KIND_BSDF = 0,
    MCSTAT_CHECK_KIND_EMITTER = 1,
    MCSTAT_CHECK_KIND_WARP = 2,
    MCSTAT_CHECK_KIND_PHASE = 3, /* mcstat_check_phase */
    MCSTAT_CHECK_KIND_MEDIUM = 4 /* mcstat_check_medium */
};

typedef struct mcstat_check_report {
    int32_t kind;          /* enum mcstat_check_kind */
    int32_t domain;
    int32_t reject;        /* 1: some route rejected */
    int32_t heavy_tailed;  /* 1: a tail index below 2 made routes INVALID */
    double alpha;
    double p_value;        /* smallest adjusted p-value (0 when a deterministic route failed) */
    double wi[3];          /* BSDFs: the direction checked (NaN otherwise) */
    uint64_t n, n_failed;  /* samples drawn for the test, and how many failed */
    uint64_t n_pilot, n_eval;
    uint64_t cells;        /* cells of the tree (before pooling) */
    uint64_t calls;        /* callback calls */
    uint64_t pdf_without_eval; /* points where pdf() > 0 but eval() = 0: samples wasted, not an error */
    double mass;           /* integral of pdf() over the domain (cubature) */
    double mass_error;     /* its estimated absolute error: sum over the cells */
    double mass_sampled, mass_sampled_se; /* the same by Monte Carlo at the table points */
    double albedo, albedo_se;        /* mean weight and its standard error */
    double albedo_eval, albedo_eval_se; /* the eval-only estimate of the same integral */
    double tail_index[2];  /* Hill's upper tail index of the weights, of the eval-only estimates */
    MCSTAT_ANONYMOUS union {
        double reserved[8];
        MCSTAT_ANONYMOUS struct {
            /* samples with weight 0 where the reported pdf and eval() are > 0: counted
               as successes.  A sampler that marks a failed sample by its weight alone
               (Mitsuba and pbrt mark it by pdf 0) shows here; the text says so when
               they are 1% of n or more */
            uint64_t zero_weight;
            /* mcstat_check_medium: the sigma_ref of the map of distances (0 otherwise) */
            double sigma_ref;
            MCSTAT_ANONYMOUS union {
                double reserved_rest[6];
                MCSTAT_ANONYMOUS struct {
                    /* discrete lobes (model->lobes): how many, the samples on them, the
                       sum of their masses and of their values (the discrete part of the
                       albedo; the albedo fields above are the smooth part's); 0 without */
                    uint64_t lobes, n_lobe;
                    double lobe_mass, lobe_albedo;
                    /* mcstat_check_medium with escape_transmittance >= 0: the mean over
                       the n flights of the escapes' weights and its standard error (NaN
                       otherwise, and the se with fewer than 2 escapes) */
                    double escape_weight, escape_weight_se;
                };
            };
        };
    };
    mcstat_check_route_result route[MCSTAT_CHECK_ROUTE_COUNT];
    char message[256];     /* MCSTAT_ECALLBACK: what went wrong, naming the callback, the point
                              and the value; otherwise empty */
} mcstat_check_report;

/* The three verdicts of a check.  INCONCLUSIVE: no route rejected, but a
 * route the check needed could not answer (state INVALID for a reason other
 * than MCSTAT_CHECK_WHY_NOTHING; KS only when INTEGRALS did not answer
 * either, as both check eval() against the sampler), so "consistent" would
 * claim an error rate the battery did not have. */
enum mcstat_check_verdict {
    MCSTAT_CHECK_CONSISTENT = 0,
    MCSTAT_CHECK_INCONSISTENT = 1, /* report->reject */
    MCSTAT_CHECK_INCONCLUSIVE = 2
};
/* *verdict <- the report's verdict; *unanswered (may be NULL) <- bit
 * (1u << route) for each route that could not answer and counts toward
 * INCONCLUSIVE.  MCSTAT_EINVAL for NULL report or verdict, or a report
 * whose states are not those of a check. */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_verdict(const mcstat_check_report *report, int *verdict, uint32_t *unanswered);
MCSTAT_API const char *mcstat_check_verdict_name(int verdict); /* "consistent", ...; NULL if invalid */

/* ------------------------------------------------------------------------ */
/* The checks.                                                               */
/* n samples from model->sample (n >= 1000), the uniforms a pure function of */
/* (seed, stream, index), so a check is reproducible and its stream of       */
/* uniforms does not depend on batch; alpha in (0, 1) is the level of the   */
/* whole battery; opt may be NULL (the defaults).                            */
/* Scratch: work of work_bytes >= mcstat_check_work_size(...) bytes, aligned */
/* to 16, or work NULL (allocated and freed inside the call).  About 16 n + */
/* 12 n_eval + 16 n_pilot + 12 KB per target cell + (76 + 16 dims +         */
/* 8 n_uniforms) per batch point: 15 MB at n = 1e5 with the defaults, 44 MB */
/* at 1e6 (most of it the batch and the cubature's rectangles).             */
/*   mcstat_check_bsdf     wi a direction (normalised inside; wi.z may be   */
/*                         negative: light arriving from below); ENERGY,     */
/*                         RECIPROCITY apply; model->lobes may be given;     */
/*   mcstat_check_emitter  directions from a reference point: domain SPHERE */
/*                         or HEMISPHERE, no ENERGY, no RECIPROCITY;         */
/*   mcstat_check_warp     eval ignored (CELLS, MASS, and PDF_VALUE when     */
/*                         sample_reports);                                  */
/*   mcstat_check_phase    a phase function p(wi, wo) of a medium: as       */
/*                         mcstat_check_bsdf on domain SPHERE (required),    */
/*                         eval = p itself (no cosine), weight p/pdf; ENERGY */
/*                         tests albedo == 1 (two-sided: a phase function    */
/*                         integrates to 1 over the sphere; constant weights */
/*                         within rtol), RECIPROCITY (when asked) p(wi, wo)  */
/*                         == p(wo, wi).  mcstat_check_bsdf on the same      */
/*                         model runs the same routes but only sees albedo   */
/*                         above 1, and divides reciprocity by cosines;      */
/*   mcstat_check_medium   distance sampling along a ray: the callbacks'     */
/*                         points are distances t >= 0 (domain INTERVAL,     */
/*                         one coordinate, n_uniforms as the sampler needs), */
/*                         mapped inside to x = 1 - exp(-sigma_ref t) in     */
/*                         [0, 1] (pdf and eval divided by dx/dt, so that    */
/*                         weights are unchanged; pdf() and eval() may be    */
/*                         asked at t = +inf, x = 1).  sample() reports the  */
/*                         density in t of a scattering at t, e.g. sigma_t   */
/*                         exp(-sigma_t t); a flight that passes the surface */
/*                         at tmax is a failed sample (pdf 0, weight 0), so  */
/*                         MASS compares the share of flights stopping       */
/*                         before tmax with the integral of pdf() (1 -       */
/*                         exp(-sigma_t tmax)): pdf() must be 0 beyond tmax; */
/*                         with options' escape_transmittance, an escape's  */
/*                         weight is checked too.                            */
/*                         eval(t) is the integrand the weight estimates,    */
/*                         sigma_s T(t) (the weight sigma_s T / pdf);        */
/*                         ENERGY: albedo <= 1.  sigma_ref >                 */
/*                         0 finite (MCSTAT_EINVAL otherwise): near the      */
/*                         medium's sigma_t the points are nearly uniform;   */
/*                         far below it they crowd at x = 0 (cells still     */
/*                         adapt), above it pdf(x) is unbounded at x = 1.    */
/*                         The report's points (where) are x, not t.         */
/* Cost: the callbacks are called about n + n_pilot times for samples,      */
/* n + n_eval times each for eval and pdf, and pdf 21 times per cubature    */
/* rectangle (2 to 40 per cell); the check's own work is O(1) per sample   */
/* besides sorting for KS (figures: bench/RESULTS.md).                      */
/* Statuses: MCSTAT_EINVAL (NULL model, callbacks or out, a bad domain,      */
/* n_uniforms or weight, lobes given to a check other than mcstat_check_bsdf, */
/* escape_transmittance NaN or above 1, or at least 0 for a check other     */
/* than mcstat_check_medium or with MCSTAT_CHECK_WEIGHT_VALUE,                     */
/* a BSDF, emitter, phase function or medium without */
/* eval or with sample_reports 0, a phase function off SPHERE, a medium    */
/* off INTERVAL or sigma_ref not > 0 finite, n < 1000, alpha outside       */
/* (0, 1), an options size this library does not know, a bad option, work too small or misaligned,  */
/* wi zero or not finite), MCSTAT_ETOOBIG (n beyond 2^48 or sizes whose     */
/* scratch overflows), MCSTAT_ENOMEM, MCSTAT_ECALLBACK (a callback returned */
/* non-zero, or NaN, Inf, a negative density or weight, a point outside the */
/* domain or a direction not of unit length within 1e-4, lobes() giving     */
/* more than MCSTAT_CHECK_MAX_LOBES lobes, a mass outside [0, 1] or lobes  */
/* closer than twice MCSTAT_CHECK_LOBE_TOLERANCE: out->message says       */
/* which callback, the index, point and value; nothing else in *out is      */
/* meaningful).  A sampler whose samples all fail is not an error: the      */
/* report's routes that need samples say "no answer", and MASS compares     */
/* the failures with the mass of pdf().                                     */
/* ------------------------------------------------------------------------ */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_work_size(const mcstat_check_model *model, size_t n, const mcstat_check_options *opt,
                                      size_t *bytes);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_bsdf(const mcstat_check_model *model, const double wi[3], size_t n, uint64_t seed,
                                 double alpha, const mcstat_check_options *opt, void *work, size_t work_bytes,
                                 mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_emitter(const mcstat_check_model *model, size_t n, uint64_t seed, double alpha,
                                    const mcstat_check_options *opt, void *work, size_t work_bytes,
                                    mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_warp(const mcstat_check_model *model, size_t n, uint64_t seed, double alpha,
                                 const mcstat_check_options *opt, void *work, size_t work_bytes,
                                 mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_phase(const mcstat_check_model *model, const double wi[3], size_t n, uint64_t seed,
                                  double alpha, const mcstat_check_options *opt, void *work, size_t work_bytes,
                                  mcstat_check_report *out);
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_medium(const mcstat_check_model *model, double sigma_ref, size_t n, uint64_t seed,
                                   double alpha, const mcstat_check_options *opt, void *work, size_t work_bytes,
                                   mcstat_check_report *out);

/* Writes the report as a text block (R's layout: one line per route with
 * its statistic, df and p-values, then what a pass means and the budget a
 * 1% error needs) into buf; *length (may be NULL) receives the full
 * length.  MCSTAT_EINVAL, MCSTAT_EBUFSIZE (buf holds a NUL-terminated
 * prefix). */
MCSTAT_NODISCARD MCSTAT_API int mcstat_check_format(const mcstat_check_report *r, char *buf, size_t size, size_t *length);
/* One sentence saying what route `route` checks (static storage; NULL if
 * invalid), and one saying what it cannot see. */
MCSTAT_API const char *mcstat_check_route_meaning(int route);
MCSTAT_API const char *mcstat_check_route_blind_spot(int route);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_CHECK_FAMILY_H */
