// ggx_checks.hpp - what the GoogleTest and Catch2 examples check: the GGX
// conductor of examples/cpp_bsdf (correct, and with a planted pdf bug), a
// warp (the cosine-weighted hemisphere) and an estimator's mean.
#ifndef MCSTAT_EXAMPLE_GGX_CHECKS_HPP
#define MCSTAT_EXAMPLE_GGX_CHECKS_HPP

#include "../cpp_bsdf/ggx.hpp"
#include "mcstat_testing.h"

#include <cmath>
#include <vector>

namespace example {

constexpr double kPi = 3.14159265358979323846;

// A BSDF with its callbacks, alive as long as the model handed to mcstat.
struct Bsdf {
    ggx::Ggx<double> bsdf;
    ggx::Callbacks<ggx::Ggx<double>> cb{&bsdf};
    explicit Bsdf(ggx::Bug bug = ggx::Bug::None) : bsdf(0.3, 0.15, 0.8, bug) {}
    mcstat_check_model model() { return cb.model(); }
};

inline const double *incident(int degrees)
{
    static double wi[3];
    double t = degrees * kPi / 180.0;
    wi[0] = std::sin(t);
    wi[1] = 0.0;
    wi[2] = std::cos(t);
    return wi;
}

// The cosine-weighted hemisphere (Malley's method) as a warp model.
inline int cosine_sample(void *, const double *, const double *u, size_t n, double *x, double *w, double *p)
{
    for (size_t k = 0; k < n; k++) {
        double r = std::sqrt(u[2 * k]), phi = 2 * kPi * u[2 * k + 1], z = std::sqrt(1 - u[2 * k]);
        x[3 * k] = r * std::cos(phi);
        x[3 * k + 1] = r * std::sin(phi);
        x[3 * k + 2] = z;
        w[k] = 1.0;
        p[k] = z / kPi;
    }
    return 0;
}

inline int cosine_pdf(void *, const double *, const double *x, size_t n, double *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = x[3 * k + 2] > 0 ? x[3 * k + 2] / kPi : 0.0;
    return 0;
}

inline mcstat_check_model cosine_warp()
{
    mcstat_check_model m{};
    m.domain = MCSTAT_CHECK_DOMAIN_HEMISPHERE;
    m.n_uniforms = 2;
    m.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    m.sample_reports = 1;
    m.sample = &cosine_sample;
    m.pdf = &cosine_pdf;
    return m;
}

// The isotropic phase function, sampled uniformly (weights 1).
inline int iso_sample(void *, const double *, const double *u, size_t n, double *x, double *w, double *p)
{
    for (size_t k = 0; k < n; k++) {
        double z = 1 - 2 * u[2 * k], r = std::sqrt(std::fmax(0.0, 1 - z * z)), phi = 2 * kPi * u[2 * k + 1];
        x[3 * k] = r * std::cos(phi);
        x[3 * k + 1] = r * std::sin(phi);
        x[3 * k + 2] = z;
        w[k] = 1.0;
        p[k] = 1 / (4 * kPi);
    }
    return 0;
}

inline int iso_density(void *, const double *, const double *, size_t n, double *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = 1 / (4 * kPi);
    return 0;
}

inline mcstat_check_model isotropic_phase()
{
    mcstat_check_model m{};
    m.domain = MCSTAT_CHECK_DOMAIN_SPHERE;
    m.n_uniforms = 2;
    m.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    m.sample_reports = 1;
    m.sample = &iso_sample;
    m.pdf = &iso_density;
    m.eval = &iso_density;
    return m;
}

// Free flights in a homogeneous medium (sigma_t 2, sigma_s 1.5) up to a
// surface at t = 1: distances t with density sigma_t exp(-sigma_t t), the
// weight sigma_s / sigma_t; a flight past the surface fails (pdf 0).
constexpr double kSigmaT = 2.0, kSigmaS = 1.5, kTmax = 1.0;
inline double flight_density(double t) { return t < kTmax ? kSigmaT * std::exp(-kSigmaT * t) : 0.0; }

inline int flight_sample(void *, const double *, const double *u, size_t n, double *x, double *w, double *p)
{
    for (size_t k = 0; k < n; k++) {
        double t = -std::log1p(-u[k]) / kSigmaT;
        bool inside = t < kTmax;
        x[k] = inside ? t : 0.0;
        p[k] = inside ? flight_density(t) : 0.0;
        w[k] = inside ? kSigmaS / kSigmaT : 0.0;
    }
    return 0;
}

inline int flight_pdf(void *, const double *, const double *x, size_t n, double *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = flight_density(x[k]);
    return 0;
}

inline int flight_eval(void *, const double *, const double *x, size_t n, double *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = kSigmaS / kSigmaT * flight_density(x[k]);
    return 0;
}

inline mcstat_check_model homogeneous_medium()
{
    mcstat_check_model m{};
    m.domain = MCSTAT_CHECK_DOMAIN_INTERVAL;
    m.n_uniforms = 1;
    m.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    m.sample_reports = 1;
    m.sample = &flight_sample;
    m.pdf = &flight_pdf;
    m.eval = &flight_eval;
    return m;
}

// A BSDF with the cosine in the wrong place: f |cos| should be rho 3 cos^2 /
// (2 pi), sampled exactly (pdf 3 cos^2 / (2 pi)), but eval() leaves out the
// cos^2 and sample() reuses it, so the weights rho / cos^2 are heavy-tailed
// (tail index 1.5): the routes that average them cannot answer, and the
// check's verdict is inconclusive.
inline double wrong_cosine_eval(double c) { return c > 0 ? 0.8 * 3 / (2 * kPi) : 0.0; }
inline double wrong_cosine_density(double c) { return c > 0 ? 3 * c * c / (2 * kPi) : 0.0; }

inline int wrong_cosine_sample(void *, const double *, const double *u, size_t n, double *x, double *w, double *p)
{
    for (size_t k = 0; k < n; k++) {
        double c = std::fmin(std::fmax(std::cbrt(1 - u[3 * k]), 1e-12), 1.0);
        double r = std::sqrt(std::fmax(0.0, 1 - c * c)), phi = 2 * kPi * u[3 * k + 1];
        x[3 * k] = r * std::cos(phi);
        x[3 * k + 1] = r * std::sin(phi);
        x[3 * k + 2] = c;
        p[k] = wrong_cosine_density(c);
        w[k] = wrong_cosine_eval(c) / p[k];
    }
    return 0;
}

inline int wrong_cosine_pdf(void *, const double *, const double *x, size_t n, double *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = wrong_cosine_density(x[3 * k + 2]);
    return 0;
}

inline int wrong_cosine_value(void *, const double *, const double *x, size_t n, double *out)
{
    for (size_t k = 0; k < n; k++)
        out[k] = wrong_cosine_eval(x[3 * k + 2]);
    return 0;
}

inline mcstat_check_model wrong_cosine_bsdf()
{
    mcstat_check_model m{};
    m.domain = MCSTAT_CHECK_DOMAIN_HEMISPHERE;
    m.n_uniforms = 3;
    m.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
    m.sample_reports = 1;
    m.sample = &wrong_cosine_sample;
    m.pdf = &wrong_cosine_pdf;
    m.eval = &wrong_cosine_value;
    return m;
}

// n estimates of the integral of cos over the hemisphere (pi) by uniform
// hemisphere sampling, from a fixed generator (splitmix64 of the index).
inline std::vector<double> cosine_estimates(size_t n, uint64_t seed)
{
    std::vector<double> v(n);
    for (size_t i = 0; i < n; i++) {
        double u = (double)(mcstat_testing::splitmix64(seed + i) >> 11) / 9007199254740992.0; // 2^53
        v[i] = 2 * kPi * u; // cos theta uniform on [0, 1): the estimate f / pdf = cos / (1 / 2 pi)
    }
    return v;
}

} // namespace example

#endif
