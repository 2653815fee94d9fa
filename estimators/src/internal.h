/*
 * internal.h - helpers shared by the estimator library's sources: the
 * counter-based generator, 3-vectors.  Nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCEST_INTERNAL_H
#define MCEST_INTERNAL_H

#include "mcest.h"

#include <math.h>
#include <stdint.h>

#define MCEST_HIDDEN __attribute__((visibility("hidden")))

#ifndef M_PI
#define M_PI 3.14159265358979323846
/* Rectangle (s0, s1, t0, t1) of heap node `node` of a cell tree; returns
 * the node's depth (direction_cells.c). */
MCEST_HIDDEN int mcest_cells_bounds_of(const double *split, int depth, size_t node, double *b);

#endif

/* ---- Philox4x64-10 (Salmon, Moraes, Dror, Shaw, SC'11) ---------------------
 * Why counter-based: estimate i's random numbers are philox(key, (i, block))
 * with nothing carried from estimate i-1, so batches and threads can split
 * a run anywhere and get the same numbers, and a rejection sampler may use
 * as many blocks as it needs for one estimate without shifting the
 * estimates after it.  Philox4x64-10 passes BigCrush, has a 2^256 counter
 * space and a 128-bit key; the key is (seed, stream tag), the tag naming
 * the kind of estimate, so that streams of different estimators never
 * overlap.  It is NumPy's Philox generator (tested against it). */
typedef struct {
    uint64_t v[4];
} mcest_u64x4;

static inline void philox_mul(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
    __uint128_t p = (__uint128_t)a * b;
    *hi = (uint64_t)(p >> 64);
    *lo = (uint64_t)p;
}

static inline mcest_u64x4 philox4x64_10(uint64_t c0, uint64_t c1, uint64_t c2, uint64_t c3,
                                        uint64_t k0, uint64_t k1)
{
    const uint64_t M0 = 0xD2E7470EE14C6C93ULL, M1 = 0xCA5A826395121157ULL;
    const uint64_t W0 = 0x9E3779B97F4A7C15ULL, W1 = 0xBB67AE8584CAA73BULL;
    for (int r = 0; r < 10; r++) {
        uint64_t hi0, lo0, hi1, lo1;
        philox_mul(M0, c0, &hi0, &lo0);
        philox_mul(M1, c2, &hi1, &lo1);
        uint64_t n0 = hi1 ^ c1 ^ k0, n2 = hi0 ^ c3 ^ k1;
        c0 = n0;
        c1 = lo1;
        c2 = n2;
        c3 = lo0;
        k0 += W0;
        k1 += W1;
    }
    mcest_u64x4 out = {{c0, c1, c2, c3}};
    return out;
}

/* Stream tags: (domain << 32) | (method << 8) | bug. */
enum {
    MCEST_DOMAIN_IRRADIANCE = 1,
    MCEST_DOMAIN_BRDF_SAMPLE = 2,
    MCEST_DOMAIN_BRDF_EXACT = 3,
    MCEST_DOMAIN_RR = 4
};

static inline uint64_t mcest_tag(uint64_t domain, uint64_t method, uint64_t bug)
{
    return (domain << 32) | (method << 8) | bug;
}

/* Block `block` of estimate `index`: four 64-bit words. */
static inline mcest_u64x4 mcest_random_block(uint64_t seed, uint64_t tag, uint64_t index,
                                             uint64_t block)
{
    return philox4x64_10(index, block, 0, 0, seed, tag);
}

/* Uniform on [0, 1): the top 53 bits. */
static inline double u01(uint64_t x)
{
    return (double)(x >> 11) * 0x1.0p-53;
}

/* ---- 3-vectors ------------------------------------------------------------ */
static inline double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void cross3(const double *a, const double *b, double *c)
{
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    c[0] = x;
    c[1] = y;
    c[2] = z;
}

static inline double norm3(const double *a)
{
    return sqrt(dot3(a, a));
}

/* |a| without overflow or underflow, scaled by the largest component: for
 * vectors users give at any scale (the receiver normal of length 1e-200 or
 * 1e200 is as good as a unit one).  Inner loops use norm3. */
static inline double norm3_scaled(const double *a)
{
    double m = fmax(fabs(a[0]), fmax(fabs(a[1]), fabs(a[2])));
    if (!(m > 0.0) || isinf(m))
        return m; /* 0, Inf or NaN: the caller rejects it */
    double x = a[0] / m, y = a[1] / m, z = a[2] / m;
    return m * sqrt(x * x + y * y + z * z);
}

static inline int finite3(const double *a)
{
    return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]);
}

/* ---- shared internals ------------------------------------------------------ */

/* A sincos for arguments in [0, 2*pi], accurate to a few ulps (spherical.c). */
MCEST_HIDDEN void mcest_sincos(double x, double *s, double *c);

/* S's spherical triangle precomputation and sampler (spherical.c).
 * a, b, c: unnormalised vertices (receiver at the origin); e_ab = b - a and
 * e_ac = c - a computed accurately.  Fills fan[16]; returns its solid angle. */
MCEST_HIDDEN double mcest_sph_tri_prepare(const double *a, const double *b, const double *c,
                                          const double *e_ab, const double *e_ac, double *fan);
/* The z-component of the sampled direction for a sub-area psi = u1*Omega/2. */
MCEST_HIDDEN double mcest_sph_tri_sample_z(const double *fan, double psi, double u2);
/* The whole sampled direction (tests). */
MCEST_HIDDEN void mcest_sph_tri_sample(const double *fan, double psi, double u2, double *w);

/* BRDF internals (brdf.c). */
MCEST_HIDDEN int mcest_brdf_valid(const mcest_brdf *b);
MCEST_HIDDEN double mcest_brdf_f(const mcest_brdf *b, const double *wo, const double *wi);
MCEST_HIDDEN double mcest_brdf_spec_pdf(const mcest_brdf *b, const double *wo, const double *wi);
MCEST_HIDDEN int mcest_brdf_spec_sample(const mcest_brdf *b, const double *wo, double u1,
                                        double u2, double *wi);
MCEST_HIDDEN double mcest_plan_pdf(const mcest_brdf_plan *p, const double *wi);
MCEST_HIDDEN double mcest_plan_ratio(const mcest_brdf_plan *p, const double *wi);
MCEST_HIDDEN void mcest_plan_propose(const mcest_brdf_plan *p, const uint64_t *r, double *wi);
MCEST_HIDDEN double mcest_env(const double *w);
MCEST_HIDDEN int mcest_plan_ok(const mcest_brdf_plan *p);
MCEST_HIDDEN int mcest_exact_one(const mcest_brdf_plan *p, uint64_t seed, uint64_t tag,
                                 uint64_t index, uint64_t max_trials, double *wi,
                                 uint64_t *trials);

/* Adaptive Gauss-Legendre cubature of f over [0,1]^2 (brdf_plan.c): returns
 * the integral, *err its estimated absolute error; abs_tol is the target. */
typedef double (*mcest_fn2)(void *ctx, double u1, double u2);
MCEST_HIDDEN double mcest_cubature(mcest_fn2 f, void *ctx, double abs_tol, double *err);
/* Integral over the hemisphere of f cos * g(wi) (g = NULL: 1), as the sum of
 * the diffuse part (cosine map) and the specular part (the sampler's map). */
MCEST_HIDDEN int mcest_plan_integrate(const mcest_brdf_plan *p, double (*g)(const double *),
                                      double rel_tol, double *value, double *err);

/* Rectangle (s0, s1, t0, t1) of heap node `node` of a cell tree; returns
 * the node's depth (direction_cells.c). */
MCEST_HIDDEN int mcest_cells_bounds_of(const double *split, int depth, size_t node, double *b);

#endif
