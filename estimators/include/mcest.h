/*
 * mcest.h - reference Monte Carlo estimators for the case studies of Subr &
 * Arvo, "Statistical Hypothesis Testing for Assessing Monte Carlo
 * Estimators" (sections 3.1-3.4).
 *
 *   - Irradiance at a point from a two-sided Lambertian triangle (3.1):
 *     Lambert's formula (exact, clipped to the receiver's hemisphere) and the
 *     four estimators U, C, A, S, with the three planted bugs of 3.4.
 *   - BRDF sampling (3.2, 3.3): Ward's and Ashikhmin-Shirley's anisotropic
 *     BRDFs, their half-vector samplers and the true densities of the
 *     directions they draw, exact rejection samplers of f*cos, Morton keys of
 *     directions, and reflected radiance under an analytic environment.
 *
 * Conventions, for every function in this header:
 *   - Fallible calls return an int status: MCEST_OK (0) or one of the
 *     MCEST_E* codes; mcest_strerror() gives a sentence.  Results are written
 *     through the pointers given last.  When a batch call fails, the contents
 *     of its output arrays are unspecified.
 *   - No abort(), no exit(), no global state, no allocation: every function
 *     is thread-safe on distinct outputs; plans are read-only once built and
 *     may be shared between threads.
 *   - Randomness is counter-based (Philox4x64-10, Salmon et al. 2011): the
 *     random numbers of estimate number i are a pure function of (seed, the
 *     kind of estimate, i).  A batch call fills out[k] with estimate number
 *     first_index + k, so a run split into batches, or over threads, gives
 *     the same numbers as one call: thread t may compute indices
 *     [t*n/T, (t+1)*n/T) with no coordination.  Different kinds of estimate
 *     (each method, each bug, each sampler) draw from independent streams
 *     even with the same seed, so two samples from two estimators are
 *     independent, as the paper's two-sample tests assume.
 *   - Directions are unit 3-vectors stored as consecutive (x, y, z) triples.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCEST_H
#define MCEST_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32) && defined(MCEST_SHARED_BUILD)
#  define MCEST_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#  define MCEST_API __attribute__((visibility("default")))
#else
#  define MCEST_API
#endif

/* ------------------------------------------------------------------------ */
/* Versions and status codes.                                                */
/* ------------------------------------------------------------------------ */
#define MCEST_VERSION_MAJOR 0
#define MCEST_VERSION_MINOR 1
#define MCEST_VERSION_PATCH 0
#define MCEST_VERSION_NUMBER \
    (MCEST_VERSION_MAJOR * 10000 + MCEST_VERSION_MINOR * 100 + MCEST_VERSION_PATCH)

MCEST_API unsigned mcest_version_number(void);
MCEST_API const char *mcest_version(void); /* "MAJOR.MINOR.PATCH", static storage */

enum mcest_status {
    MCEST_OK = 0,
    MCEST_EINVAL = 1,      /* NULL pointer, unknown enum, non-finite or out-of-domain parameter */
    MCEST_EUNSUPPORTED = 2,/* a valid option that does not apply here (a planted bug on U, C or S) */
    MCEST_ELIMIT = 3,      /* a rejection sampler reached the caller's cap on trials */
    MCEST_ENUMERIC = 4,    /* a numerical method missed its tolerance (quadrature) */
    MCEST_ENOTREADY = 5    /* a plan lacks what the call needs (the albedo: see mcest_brdf_plan_albedo) */
};

/* A sentence describing status (static storage; never NULL). */
MCEST_API const char *mcest_strerror(int status);

/* ------------------------------------------------------------------------ */
/* Irradiance from a triangular Lambertian emitter (section 3.1).            */
/*                                                                           */
/* The emitter is a triangle of uniform radiance L, emitting from both       */
/* faces; the receiver is a point with a normal (any length > 0); nothing    */
/* occludes.  Only the part of the emitter above the receiver's tangent      */
/* plane contributes: E = L * (projected solid angle of that part).          */
/* Geometry may sit anywhere: it is translated to the receiver (computing    */
/* edges from the input coordinates, never from translated vertices) and     */
/* rotated into the receiver's frame before anything else, so 1e6 offsets    */
/* cost nothing beyond the rounding of the inputs themselves.                */
/*                                                                           */
/* Estimators (each returns primary estimates; their mean is E):             */
/*   U  uniform direction on the hemisphere; 2*pi*L*cos if it hits, else 0.  */
/*   C  cosine-weighted direction; pi*L if it hits, else 0.                  */
/*   A  uniform point y on the triangle (b1 = 1 - sqrt(u1), b2 = u2*sqrt(u1) */
/*      on the edges v0v1, v0v2); L*area*cos*cos'/r^2, with the receiver's   */
/*      cosine clamped at 0 (the point is below the horizon).  Computed as   */
/*      L * (area*h) * max(0, z) / r^4, h the distance to the emitter's      */
/*      plane (eq. 6: n_tri.z is the same for every point of the triangle).  */
/*   S  uniform direction in the solid angle of the emitter's visible part;  */
/*      L * Omega * cos.  When the triangle straddles the horizon S samples  */
/*      the clipped polygon (a fan of at most two spherical triangles, one   */
/*      chosen with probability proportional to its solid angle), so no      */
/*      sample is wasted below the horizon.  The sampler is Arvo's (1995)    */
/*      rewritten so that it keeps full precision on tiny, sliver and        */
/*      grazing triangles (see src/spherical.c): the sub-triangle's vertex   */
/*      C' comes from the half-angle tangent of arc AC' in closed form (no   */
/*      acos, no sqrt(1 - q^2)), and the arc B-C' is sampled by its chord.   */
/*                                                                           */
/* Planted bugs (section 3.4, ERRATA 8), on estimator A only (the paper      */
/* plants them there); any other method with a bug is MCEST_EUNSUPPORTED:    */
/*   NO_COSINE    omits the receiver's cosine n.z/|z| of eq. 6 (points below */
/*                the horizon still contribute 0);                           */
/*   BARYCENTRIC  b1 = u1, b2 = (1 - u1)*u2: not area-preserving;            */
/*   NO_JACOBIAN  omits n_tri.z/|z|^3 of eq. 6.                              */
/* ------------------------------------------------------------------------ */
enum mcest_method {
    MCEST_U = 0, /* uniform hemisphere */
    MCEST_C = 1, /* cosine-weighted hemisphere */
    MCEST_A = 2, /* uniform area */
    MCEST_S = 3  /* uniform solid angle */
};

enum mcest_bug {
    MCEST_BUG_NONE = 0,
    MCEST_BUG_NO_COSINE = 1,
    MCEST_BUG_BARYCENTRIC = 2,
    MCEST_BUG_NO_JACOBIAN = 3
};

/* "U", "C", "A", "S" (also lower case) and back. */
MCEST_API int mcest_method_parse(const char *name, int *method);
MCEST_API const char *mcest_method_name(int method); /* NULL if invalid */
/* "none" (or NULL or ""), "no_cosine", "barycentric", "no_jacobian". */
MCEST_API int mcest_bug_parse(const char *name, int *bug);
MCEST_API const char *mcest_bug_name(int bug); /* NULL if invalid */

/* A scene: the emitter triangle (vertex k at triangle[3k..3k+2]), the
 * receiver's point and normal, and the emitted radiance (finite, >= 0). */
typedef struct mcest_scene {
    double triangle[9];
    double point[3];
    double normal[3];
    double radiance;
} mcest_scene;

/* The built-in "paper-like" scene of section 3.1, for `mcstat reproduce`:
 * receiver at the origin facing +z, radiance 1, triangle
 * (-0.6, -0.4, 1.0), (0.9, -0.3, 1.3), (0.1, 0.9, 0.8): area 0.995 at about
 * unit height, tilted and off-centre; E = 0.664537151664300 (solid angle
 * 0.7166 sr).  On it sigma_U > sigma_C > sigma_A > sigma_S (ERRATA 10):
 * about 1.86, 1.28, 0.202, 0.042 per primary estimate, each step shown by
 * the one-sided F test on batch means in tests/test_irradiance_mc.c. */
MCEST_API int mcest_scene_paper(mcest_scene *out);

/* Lambert's formula, E = (L/2) |sum_k Theta_k n.gamma_k|, over the polygon
 * left after clipping the triangle to the receiver's upper half-space.
 * Angles are atan2(|a x b|, a.b); for small polygons the sum is rearranged
 * so that its terms do not cancel (src/lambert.c): within 4e-16 of
 * 60-digit references at solid angles of 1e-10 and 1e-12, for emitters
 * filling nearly the whole hemisphere, and 1e6 from the origin.  Slivers
 * and emitters at grazing elevation keep the cancellation between their
 * long edges: relative error ~ eps * kappa, kappa = sum |terms| / |sum|
 * (a 1e-7-wide needle: 4e-13; an emitter 1e-3 rad above the horizon:
 * 1.3e-11).  A receiver in the emitter's plane, or a degenerate triangle,
 * gives 0.
 * Statuses: MCEST_EINVAL (NULL, non-finite input, zero normal, L < 0). */
MCEST_API int mcest_irradiance_exact(const mcest_scene *scene, double *E);

/* Everything the estimators need, computed once per scene.  A plain,
 * fixed-size struct the caller owns; treat the fields as read-only. */
typedef struct mcest_irradiance_plan {
    uint32_t version;          /* MCEST_IRRADIANCE_PLAN_VERSION once built */
    int32_t n_poly;            /* vertices of the visible polygon: 0, 3 or 4 */
    int32_t n_fan;             /* spherical triangles S samples: 0, 1 or 2 */
    int32_t straddles;         /* 1 if the triangle crosses the receiver's horizon */
    double radiance;
    double exact;              /* Lambert's formula (= mcest_irradiance_exact) */
    double solid_angle;        /* of the visible polygon (steradians) */
    double proj_solid_angle;   /* exact / radiance, when radiance > 0 */
    double area;               /* of the whole triangle */
    double height;             /* distance from the receiver to the emitter's plane */
    double v[3][3];            /* triangle in the receiver's frame (receiver at 0, normal +z) */
    double e01[3], e02[3];     /* its edges, from the input coordinates */
    double edge_n[3][3];       /* inward normals of the cone through the triangle (U, C) */
    double a_coef;             /* L * area * height (estimator A) */
    double la_coef;            /* L * area (estimator A with NO_JACOBIAN) */
    double fan[2][20];         /* per spherical triangle of S: see src/spherical.c */
    double reserved[16];
} mcest_irradiance_plan;

#define MCEST_IRRADIANCE_PLAN_VERSION 1u

/* Builds the plan.  Statuses as mcest_irradiance_exact. */
MCEST_API int mcest_irradiance_plan_init(const mcest_scene *scene, mcest_irradiance_plan *plan);

/* Fills out[k], k < n, with primary estimate number first_index + k of
 * `method` (enum mcest_method) with `bug` (enum mcest_bug), from `seed`.
 * No per-sample overhead: one call fills the whole array.
 * Statuses: MCEST_EINVAL (NULL, bad enum, plan not built),
 * MCEST_EUNSUPPORTED (a bug on a method other than A). */
MCEST_API int mcest_irradiance_estimates(const mcest_irradiance_plan *plan, int method, int bug,
                                         uint64_t seed, uint64_t first_index, size_t n,
                                         double *out);

/* One call: plan the scene, then mcest_irradiance_estimates. */
MCEST_API int mcest_irradiance(const mcest_scene *scene, int method, int bug, uint64_t seed,
                               uint64_t first_index, size_t n, double *out);

/* ------------------------------------------------------------------------ */
/* BRDFs (section 3.2).                                                      */
/*                                                                           */
/* Directions live in the shading frame: normal +z, first tangent +x (the    */
/* direction of alpha_x / n_u).  wo is the fixed ("outgoing") direction,     */
/* with wo.z > 0; wi ranges over the sphere and f = 0 when wi.z <= 0.        */
/* Both BRDFs are a diffuse term plus an anisotropic specular lobe:          */
/*                                                                           */
/* Ward (1992), with Walter's (2005) reading:                                */
/*   f = rho_d/pi + rho_s exp(-(hx^2/ax^2 + hy^2/ay^2)/hz^2)                 */
/*                  / (4 pi ax ay sqrt(cos_i cos_o)),  h = wi + wo.          */
/*   Sampler: h ~ (g ax cos 2pi u2, g ay sin 2pi u2, 1), g = sqrt(-ln u1),   */
/*   wi = reflect(wo, h).  True density (Walter 2005):                       */
/*   p(wi) = exp(-(...)) / (pi ax ay hz^3) / (4 wo.h), h the unit half       */
/*   vector.  Ward's own weights assume another density (ERRATA 9).          */
/*                                                                           */
/* Ashikhmin-Shirley (2000), anisotropic Phong:                              */
/*   f_s = sqrt((nu+1)(nv+1))/(8 pi) hz^e F(wo.h) / (wo.h max(cos_i,cos_o)), */
/*   e = (nu hx^2 + nv hy^2)/(hx^2 + hy^2), F(c) = Rs + (1 - Rs)(1 - c)^5;   */
/*   f_d = 28 Rd/(23 pi) (1 - Rs)(1 - (1 - cos_i/2)^5)(1 - (1 - cos_o/2)^5). */
/*   Sampler: phi from tan phi = sqrt((nu+1)/(nv+1)) tan(2 pi u1),           */
/*   cos theta_h = (1 - u2)^(1/(e+1)); density                               */
/*   p(wi) = sqrt((nu+1)(nv+1))/(2 pi) hz^e / (4 wo.h)  (exact).             */
/*                                                                           */
/* When the diffuse term is not zero, "the BRDF's sampler" is the mixture    */
/* that draws a cosine-weighted direction with probability m and the         */
/* half-vector sampler otherwise, m = Bd/(Bd + Bs) (the envelope constants   */
/* below); its density is the mixture's.  With a zero diffuse term it is     */
/* exactly the model's own sampler, as in the paper.                         */
/*                                                                           */
/* Parameters, accepted ranges (all finite): Ward rho_d, rho_s >= 0,         */
/* alpha in [1e-4, 10] (tested 1e-3 to 1); Ashikhmin-Shirley Rd, Rs in       */
/* [0, 1], exponents in [0, 1e7] (tested 1 to 1e5); wo.z >= 1e-12 after      */
/* normalisation.                                                            */
/* ------------------------------------------------------------------------ */
enum mcest_brdf_model {
    MCEST_WARD = 1,
    MCEST_ASHIKHMIN_SHIRLEY = 2
};

typedef struct mcest_brdf {
    int32_t model;      /* enum mcest_brdf_model */
    int32_t reserved_i;
    double diffuse;     /* Ward rho_d;  Ashikhmin-Shirley Rd */
    double specular;    /* Ward rho_s;  Ashikhmin-Shirley Rs (Fresnel reflectance at normal incidence) */
    double rough_x;     /* Ward alpha_x; Ashikhmin-Shirley n_u */
    double rough_y;     /* Ward alpha_y; Ashikhmin-Shirley n_v */
    double reserved[3];
} mcest_brdf;

/* Fill *out after checking the parameters (MCEST_EINVAL if out of range). */
MCEST_API int mcest_brdf_ward(double rho_d, double rho_s, double alpha_x, double alpha_y,
                              mcest_brdf *out);
MCEST_API int mcest_brdf_ashikhmin_shirley(double rd, double rs, double n_u, double n_v,
                                           mcest_brdf *out);

/* f(wi[k], wo) for k < n. */
MCEST_API int mcest_brdf_eval(const mcest_brdf *brdf, const double wo[3], const double *wi,
                              size_t n, double *f);

/* A BRDF with a fixed wo, and what its samplers need: the mixture weight,
 * the envelope of the rejection sampler, and (once computed) the albedo.
 *   Envelope (a proof, not a fit): with the mixture proposal
 *   q = m p_cos + (1-m) p_spec and f cos = diffuse + specular parts,
 *   f cos / q <= Bd + Bs whenever diffuse <= Bd p_cos and
 *   specular <= Bs p_spec (mediant inequality), with
 *     Ward:  Bd = rho_d;  specular/p_spec = rho_s sqrt(cos_i/cos_o) hz^3 (wo.h),
 *            whose supremum over h lies in the plane of n and wo (it grows
 *            with hz and wo.h) and is found by bisection on the derivative
 *            of its logarithm, which is concave there (src/brdf_plan.c);
 *     A-S:   Bd = 28/23 Rd (1-Rs)(1-(1-cos_o/2)^5) 31/32;
 *            specular/p_spec = F(wo.h) min(1, cos_i/cos_o)
 *            <= F(cos_o/2) = Bs, since cos_i + cos_o = 2 (wo.h) hz.
 *   The expected number of trials per sample is (Bd + Bs)/albedo.  The
 *   sampler also checks the bound at run time. */
typedef struct mcest_brdf_plan {
    uint32_t version;      /* MCEST_BRDF_PLAN_VERSION once built */
    int32_t has_albedo;    /* 1 once mcest_brdf_plan_albedo succeeded */
    mcest_brdf brdf;
    double wo[3];          /* normalised */
    double mix;            /* m: probability of the cosine-weighted component */
    double bound_d, bound_s;/* Bd, Bs */
    double bound;          /* Bd + Bs: f cos / q <= bound */
    double albedo_d;       /* integral of the diffuse part of f cos (closed form) */
    double albedo_s;       /* of the specular part (quadrature; NaN until computed) */
    double albedo;         /* albedo_d + albedo_s */
    double albedo_err;     /* estimated absolute error of albedo */
    double reserved[8];
} mcest_brdf_plan;

#define MCEST_BRDF_PLAN_VERSION 1u

/* Builds the plan (cheap: no albedo).  MCEST_EINVAL for bad input. */
MCEST_API int mcest_brdf_plan_init(const mcest_brdf *brdf, const double wo[3],
                                   mcest_brdf_plan *plan);
/* Computes the albedo (integral of f cos over the hemisphere of wi) by
 * adaptive Gauss-Legendre cubature in the sampler's own unit square, where
 * the integrand f cos / p is bounded; rel_tol in [1e-13, 1e-2]; the kink
 * where wi crosses the horizon limits it to about 1e-6..1e-8 (3000 squares
 * of 65 points at most; ~2e-3 for Ashikhmin-Shirley within 1e-6 rad of
 * grazing, where min(1, cos_i/cos_o) is a near-step).  Takes 10 to 40 ms
 * and 120 KB of stack (a fixed array of squares: no allocation).
 * MCEST_ENUMERIC if the tolerance was not reached (the result is stored). */
MCEST_API int mcest_brdf_plan_albedo(mcest_brdf_plan *plan, double rel_tol);

/* The BRDF's sampler: wi[3k..3k+2] is direction number first_index + k;
 * pdf (may be NULL) receives its true density (solid angle measure).
 * Some directions fall below the horizon (the half-vector reflection does
 * that); they are returned as drawn, f is 0 there. */
MCEST_API int mcest_brdf_sample(const mcest_brdf_plan *plan, uint64_t seed, uint64_t first_index,
                                size_t n, double *wi, double *pdf);
/* Density of the sampler at wi[k], on the whole sphere (integrates to 1). */
MCEST_API int mcest_brdf_pdf(const mcest_brdf_plan *plan, const double *wi, size_t n,
                             double *pdf);

/* Exact sampler: directions with density f(wi, wo) cos_i / albedo on the
 * upper hemisphere, by rejection from the BRDF's sampler with the envelope
 * above.  At most max_trials proposals per direction (0: no cap); past it,
 * MCEST_ELIMIT.  *trials (may be NULL) receives the total number of
 * proposals, so trials / n measures 1 / acceptance.  A proposal whose
 * ratio exceeds the envelope returns MCEST_ENUMERIC (never expected). */
MCEST_API int mcest_brdf_sample_exact(const mcest_brdf_plan *plan, uint64_t seed,
                                      uint64_t first_index, size_t n, uint64_t max_trials,
                                      double *wi, uint64_t *trials);

/* ------------------------------------------------------------------------ */
/* Reflected radiance (section 3.3).                                         */
/*                                                                           */
/* Lr(wo) = integral of f(wi, wo) Lenv(wi) cos_i over the hemisphere, under  */
/* the analytic environment (in the shading frame, w = (x, y, z) unit)       */
/*   Lenv(w) = 1 + 0.5 (x^3 - 3 x y^2) + 0.3 cos(12 y)                       */
/*             + 4 exp(20 (w.d - 1)),  d = (0.3, -0.4, sqrt(0.75)),          */
/* a three-fold azimuthal wave, stripes and a bright spot: smooth, >= 0.2,   */
/* with structure at the scales of the lobes, so that biases show.           */
/* Estimators (primary estimates; mean Lr):                                  */
/*   MCEST_RR_SAMPLING   wi from mcest_brdf_sample: f Lenv cos / p(wi), with */
/*                       p the sampler's true density (0 below horizon).     */
/*   MCEST_RR_REJECTION  wi from mcest_brdf_sample_exact: albedo * Lenv(wi). */
/*       Its mean is Lr only with the true normalisation of f cos, which     */
/*       has no closed form: the plan's albedo, from quadrature, enters as   */
/*       a constant, so the estimator's bias is the quadrature error         */
/*       (relative, below the rel_tol given to mcest_brdf_plan_albedo: 1e-6 */
/*       in the tests, far below what 1e10 samples could resolve).            */
/*       Plans without an albedo give MCEST_ENOTREADY.                       */
/*   MCEST_RR_REJECTION_UNBIASED  the same direction, times an independent  */
/*       unbiased estimate of the albedo, f cos / q at one more proposal    */
/*       from the mixture: E[albedo_hat Lenv(wi)] = albedo E[Lenv(wi)] = Lr  */
/*       exactly, with no quadrature, for more variance.                     */
/* ------------------------------------------------------------------------ */
enum mcest_rr_method {
    MCEST_RR_SAMPLING = 0,
    MCEST_RR_REJECTION = 1,
    MCEST_RR_REJECTION_UNBIASED = 2
};

MCEST_API int mcest_environment_radiance(const double *w, size_t n, double *L);

MCEST_API int mcest_reflected_radiance(const mcest_brdf_plan *plan, int method, uint64_t seed,
                                       uint64_t first_index, size_t n, uint64_t max_trials,
                                       double *out);
/* Lr(wo) by the cubature of mcest_brdf_plan_albedo (rel_tol likewise). */
MCEST_API int mcest_reflected_radiance_reference(const mcest_brdf_plan *plan, double rel_tol,
                                                 double *Lr);

/* ------------------------------------------------------------------------ */
/* Morton keys of directions.                                                */
/* Parameterisation: Lambert's equal-area cylindrical map of the sphere,     */
/*   s = (1 - z)/2 in [0, 1]   (s in [0, 1/2] on the upper hemisphere),      */
/*   t = atan2(y, x)/(2 pi) mod 1,                                           */
/* equal areas of the sphere map to equal areas of the square.  Each is      */
/* quantised to 32 bits, q = min(floor(2^32 s), 2^32 - 1), and the key       */
/* interleaves them, s's bit b at key bit 2b+1, t's bit b at key bit 2b, so  */
/* the polar coordinate is the more significant.  Distinct directions tie    */
/* only within about 2^-32 in both coordinates: for K-S tests the key is an  */
/* essentially continuous variable.                                          */
/* ------------------------------------------------------------------------ */
MCEST_API int mcest_direction_square(const double *w, size_t n, double *st);
MCEST_API int mcest_direction_key(const double *w, size_t n, uint64_t *keys);

/* ------------------------------------------------------------------------ */
/* Planted bugs in the BRDF samplers: what a sampler test must catch.        */
/* Realistic mistakes in the half-vector warps; the density the sampler      */
/* claims (mcest_brdf_pdf) stays the correct one, so a goodness-of-fit test  */
/* of the drawn directions against it should reject.  The cosine-weighted    */
/* component of a mixture has no bug.                                        */
/*   ROUGHNESS     the lobe 10% too wide: Ward alpha_x, alpha_y * 1.1;       */
/*                 Ashikhmin-Shirley n_u, n_v / 1.21 (n ~ 2/alpha^2);        */
/*   AXES_SWAPPED  the anisotropy axes swapped (alpha_x <-> alpha_y,         */
/*                 n_u <-> n_v);                                             */
/*   PHI_HALF      the azimuth drawn over half its range (2 pi u -> pi u);   */
/*   JACOBIAN      the sin(theta) of d(omega) = sin(theta) dtheta dphi       */
/*                 forgotten in the polar warp: the half vector's polar      */
/*                 radius (Ward's slope |tan theta_h|, Ashikhmin-Shirley's    */
/*                 theta_h) has, for a narrow lobe, the half-normal law      */
/*                 that density without sin(theta) gives instead of the     */
/*                 Rayleigh law: the correct radius times |cos(2 pi u3)|,    */
/*                 u3 a further uniform (Box-Muller).                        */
/* A pdf normalisation off by a constant changes weights, not directions:   */
/* no test of the directions alone can see it (the radiance tests do).       */
/* ------------------------------------------------------------------------ */
enum mcest_sampler_bug {
    MCEST_SAMPLER_BUG_NONE = 0,
    MCEST_SAMPLER_BUG_ROUGHNESS = 1,
    MCEST_SAMPLER_BUG_AXES_SWAPPED = 2,
    MCEST_SAMPLER_BUG_PHI_HALF = 3,
    MCEST_SAMPLER_BUG_JACOBIAN = 4
};

/* "none" (or NULL or ""), "roughness", "axes_swapped", "phi_half", "jacobian". */
MCEST_API int mcest_sampler_bug_parse(const char *name, int *bug);
MCEST_API const char *mcest_sampler_bug_name(int bug); /* NULL if invalid */

/* The BRDF's sampler with `bug` (enum mcest_sampler_bug): wi[3k..3k+2] is
 * direction number first_index + k.  MCEST_SAMPLER_BUG_NONE is exactly
 * mcest_brdf_sample; each bug draws from its own stream.  MCEST_EINVAL. */
MCEST_API int mcest_brdf_sample_bug(const mcest_brdf_plan *plan, int bug, uint64_t seed,
                                    uint64_t first_index, size_t n, double *wi);

/* ------------------------------------------------------------------------ */
/* Cells of equal probability for chi-squared tests of a sampler.            */
/* The sphere is mapped to Lambert's equal-area square of the Morton keys    */
/* (s = (1 - z)/2, t = phi/(2 pi), solid angle 4 pi ds dt) and cut by a k-d  */
/* tree of the given depth into 2^depth rectangles: the node at depth d      */
/* splits across s (d even) or t (d odd) at the median of a pilot of         */
/* 2^(depth+8) directions drawn by the plan's own sampler from a fixed       */
/* quasi-random lattice (deterministic; 256 per cell), so cells have nearly  */
/* equal probability and follow the lobe however narrow (a cubature of the   */
/* whole sphere could miss a lobe 0.05 rad wide).  Below-horizon directions  */
/* are cells like any other.  Cells are numbered left to right along the     */
/* leaves, so consecutive cells are neighbours (mcstat_gof_chisq_test pools  */
/* in that order).  split holds the 2^depth - 1 split values in heap order   */
/* (node i's children 2i+1, 2i+2).  Each cell's probability prob[c] under    */
/* the plan's density (mcest_brdf_pdf, on the whole sphere) is then computed */
/* by adaptive cubature (7x7 against 4x4 Gauss-Legendre, splitting the worst */
/* rectangle; a cell straddling the horizon in two parts, the cosine part of */
/* a mixture jumping there) to max(rel_tol prob[c], 1e-3 rel_tol/2^depth);   */
/* *err (may be NULL) receives the sum of the estimated errors.  A half-     */
/* vector sampler's density is singular at wi = -wo (like 1/|wi + wo|, with  */
/* a jump through the point): the cell holding that point, or passing near  */
/* it, is integrated as eight triangles fanning around it by the Duffy      */
/* transform.  Measured on the paper scene's lobes: the probabilities sum   */
/* to 1 within 3e-10 at depths 4-10 (Ward at 70 degrees: within 2e-7 at      */
/* depths 8 and 12, where the error estimate says 4e-9: a kink next to the   */
/* singular point), and 33 million sampled directions agree with every one  */
/* of 4096 cells within 4.5 sd.  The sum of the probabilities checks the     */
/* density's normalisation too.  work: the caller's                          */
/* scratch of mcest_cells_work_size(depth) doubles (2^(depth+9); 16 MB at    */
/* depth 12), so that nothing here allocates.                                */
/* Statuses: MCEST_EINVAL (plan not built, depth outside                     */
/* 1..MCEST_CELLS_MAX_DEPTH, rel_tol outside [1e-12, 1e-2], NULL),           */
/* MCEST_ENUMERIC (the summed error estimate exceeds MCEST_CELLS_MAX_ERROR;  */
/* everything is still stored).                                              */
/* ------------------------------------------------------------------------ */
#define MCEST_CELLS_MAX_DEPTH 12
#define MCEST_CELLS_MAX_ERROR 1e-5

/* Doubles of scratch mcest_brdf_cells needs (0 for a bad depth). */
MCEST_API size_t mcest_cells_work_size(int depth);
MCEST_API int mcest_brdf_cells(const mcest_brdf_plan *plan, int depth, double rel_tol, double *work,
                               double *split, double *prob, double *err);
/* cell[k] <- the cell of direction w[3k..3k+2] (any non-zero length).
 * MCEST_EINVAL (NULL, bad depth, a zero or non-finite direction). */
MCEST_API int mcest_cells_locate(const double *split, int depth, const double *w, size_t n,
                                 uint32_t *cell);
/* counts[c] <- the number of the n directions in cell c (2^depth values). */
MCEST_API int mcest_cells_count(const double *split, int depth, const double *w, size_t n,
                                double *counts);
/* bounds[4c..4c+3] <- s0, s1, t0, t1 of cell c. */
MCEST_API int mcest_cells_bounds(const double *split, int depth, double *bounds);

/* ------------------------------------------------------------------------ */
/* Sizes, for FFI callers that cannot read sizeof.                           */
/* ------------------------------------------------------------------------ */
MCEST_API size_t mcest_sizeof_scene(void);
MCEST_API size_t mcest_sizeof_irradiance_plan(void);
MCEST_API size_t mcest_sizeof_brdf(void);
MCEST_API size_t mcest_sizeof_brdf_plan(void);

#ifdef __cplusplus
}
#endif
#endif /* MCEST_H */
