// ggx.hpp - a GGX (Trowbridge-Reitz) microfacet conductor, written the way
// a renderer writes its BSDFs, and its adapter to mcstat's C callbacks.
//
// The BSDF (local shading frame, normal +z, reflection only):
//   D(m)    = 1 / (pi ax ay (mx^2/ax^2 + my^2/ay^2 + mz^2)^2)   anisotropic GGX
//   Lambda  = (-1 + sqrt(1 + (ax^2 wx^2 + ay^2 wy^2) / wz^2)) / 2
//   G1(w)   = 1 / (1 + Lambda(w)),  G2 = 1 / (1 + Lambda(wi) + Lambda(wo))
//             (height-correlated Smith masking-shadowing)
//   F(c)    = F0 + (1 - F0)(1 - c)^5                             Schlick
//   eval    = f(wi, wo) |wo.z| = F(wi.m) D(m) G2 / (4 wi.z),     m = half vector
//   sampling: visible normals (Heitz 2018, "Sampling the GGX Distribution
//   of Visible Normals", JCGT 7(4)), pdf = G1(wi) D(m) / (4 wi.z)
//   weight  = eval / pdf = F G2 / G1(wi), computed in that simplified form,
//             as Mitsuba's and pbrt's samplers do, not by dividing.
// Templated on the arithmetic: Ggx<float> is a GPU renderer's CPU
// reference path, Ggx<double> an offline renderer's.
//
// Planted bugs (Bug), each about 10%, one per class of mistake:
//   Sampler  sample() draws visible normals for alpha * 1.1, but reports
//            the true pdf and weight of the direction it drew;
//   Pdf      pdf() evaluates D with alpha * 1.1 (sample() reports the
//            right pdf);
//   Eval     eval() uses F0 * 0.9 (a parameter read twice, differently),
//            while sample()'s weight uses F0;
//   Weight   sample()'s weight is 10% high;
// and Throws: eval() throws, to show that the exception stops the check
// (MCSTAT_ECALLBACK) without crossing the C boundary.
#ifndef MCSTAT_EXAMPLE_GGX_HPP
#define MCSTAT_EXAMPLE_GGX_HPP

#include "mcstat.h"

#include <cmath>
#include <cstddef>
#include <exception>
#include <new>

namespace ggx {

constexpr double pi = 3.14159265358979323846;

template <class Real> struct Vec3 {
    Real x, y, z;
};

template <class Real> inline Real dot(const Vec3<Real> &a, const Vec3<Real> &b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class Real> inline Vec3<Real> normalize(const Vec3<Real> &v)
{
    Real inv = Real(1) / std::sqrt(dot(v, v));
    return {v.x * inv, v.y * inv, v.z * inv};
}

enum class Bug { None, Sampler, Pdf, Eval, Weight, Throws };

inline const char *bug_name(Bug b)
{
    switch (b) {
    case Bug::None: return "correct";
    case Bug::Sampler: return "sampler (visible normals of alpha*1.1)";
    case Bug::Pdf: return "pdf (D of alpha*1.1 in pdf())";
    case Bug::Eval: return "eval (F0*0.9 in eval())";
    case Bug::Weight: return "weight (10% high)";
    case Bug::Throws: return "throws (eval() runs out of memory)";
    }
    return "?";
}

struct SampleOut {
    double x[3];
    double weight, pdf;
};

template <class Real> class Ggx {
public:
    using real_type = Real;

    Ggx(Real alpha_x, Real alpha_y, Real f0, Bug bug = Bug::None)
        : ax_(alpha_x), ay_(alpha_y), f0_(f0), bug_(bug)
    {
    }

    // The microfacet distribution.
    static Real D(const Vec3<Real> &m, Real ax, Real ay)
    {
        if (m.z <= Real(0))
            return Real(0);
        Real s = m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z;
        return Real(1) / (Real(pi) * ax * ay * s * s);
    }

    Real lambda(const Vec3<Real> &w) const
    {
        Real z2 = w.z * w.z;
        Real t2 = (ax_ * ax_ * w.x * w.x + ay_ * ay_ * w.y * w.y) / z2;
        // (-1 + sqrt(1 + t2)) / 2 without the cancellation at small t2
        return t2 / (Real(2) * (Real(1) + std::sqrt(Real(1) + t2)));
    }

    Real g1(const Vec3<Real> &w) const { return Real(1) / (Real(1) + lambda(w)); }

    static Real schlick(Real f0, Real c)
    {
        Real k = Real(1) - c, k2 = k * k;
        return f0 + (Real(1) - f0) * k2 * k2 * k;
    }

    // A visible normal for wi (Heitz 2018, listing 1) at roughness (ax, ay).
    static Vec3<Real> sample_vndf(const Vec3<Real> &wi, Real ax, Real ay, Real u1, Real u2)
    {
        Vec3<Real> vh = normalize(Vec3<Real>{ax * wi.x, ay * wi.y, wi.z});
        Real lensq = vh.x * vh.x + vh.y * vh.y;
        Vec3<Real> t1 = lensq > Real(0) ? Vec3<Real>{-vh.y / std::sqrt(lensq), vh.x / std::sqrt(lensq), Real(0)}
                                        : Vec3<Real>{Real(1), Real(0), Real(0)};
        Vec3<Real> t2{vh.y * t1.z - vh.z * t1.y, vh.z * t1.x - vh.x * t1.z, vh.x * t1.y - vh.y * t1.x};
        Real r = std::sqrt(u1), phi = Real(2 * pi) * u2;
        Real p1 = r * std::cos(phi), p2 = r * std::sin(phi);
        Real s = Real(0.5) * (Real(1) + vh.z);
        p2 = (Real(1) - s) * std::sqrt(std::fmax(Real(0), Real(1) - p1 * p1)) + s * p2;
        Real p3 = std::sqrt(std::fmax(Real(0), Real(1) - p1 * p1 - p2 * p2));
        Vec3<Real> nh{p1 * t1.x + p2 * t2.x + p3 * vh.x, p1 * t1.y + p2 * t2.y + p3 * vh.y,
                      p1 * t1.z + p2 * t2.z + p3 * vh.z};
        return normalize(Vec3<Real>{ax * nh.x, ay * nh.y, std::fmax(Real(0), nh.z)});
    }

    // The density of visible normals of wi, per solid angle of wo = reflect(wi, m).
    Real pdf_of_m(const Vec3<Real> &wi, const Vec3<Real> &m, Real ax, Real ay) const
    {
        Real wim = dot(wi, m);
        if (wim <= Real(0))
            return Real(0);
        return g1(wi) * D(m, ax, ay) / (Real(4) * wi.z);
    }

    // sample(): one direction from uniforms u1, u2.  A failed sample (wo
    // below the horizon) has pdf 0 and weight 0, as in a renderer.
    SampleOut sample(const Vec3<Real> &wi, Real u1, Real u2) const
    {
        SampleOut s{};
        if (wi.z <= Real(0))
            return s; // light from below: a reflection-only BSDF has nothing to sample
        Real sx = bug_ == Bug::Sampler ? ax_ * Real(1.1) : ax_;
        Real sy = bug_ == Bug::Sampler ? ay_ * Real(1.1) : ay_;
        Vec3<Real> m = sample_vndf(wi, sx, sy, u1, u2);
        Real wim = dot(wi, m);
        Vec3<Real> wo{Real(2) * wim * m.x - wi.x, Real(2) * wim * m.y - wi.y, Real(2) * wim * m.z - wi.z};
        s.x[0] = wo.x, s.x[1] = wo.y, s.x[2] = wo.z;
        if (wo.z <= Real(0) || wim <= Real(0)) {
            s.weight = s.pdf = 0.0;
            return s;
        }
        // the density of the true distribution at the drawn direction: the
        // Sampler bug draws from another one but reports this.
        Real pdf = pdf_of_m(wi, m, ax_, ay_);
        Real g2 = Real(1) / (Real(1) + lambda(wi) + lambda(wo));
        Real weight = schlick(f0_, wim) * g2 / g1(wi);
        if (bug_ == Bug::Weight)
            weight *= Real(1.1);
        s.pdf = double(pdf);
        s.weight = double(weight);
        return s;
    }

    Real pdf(const Vec3<Real> &wi, const Vec3<Real> &wo) const
    {
        if (wi.z <= Real(0) || wo.z <= Real(0))
            return Real(0);
        Vec3<Real> m = normalize(Vec3<Real>{wi.x + wo.x, wi.y + wo.y, wi.z + wo.z});
        Real s = bug_ == Bug::Pdf ? Real(1.1) : Real(1);
        return pdf_of_m(wi, m, ax_ * s, ay_ * s);
    }

    // f(wi, wo) |wo.z| (the cosine included, as Mitsuba's eval).
    Real eval(const Vec3<Real> &wi, const Vec3<Real> &wo) const
    {
        if (wi.z <= Real(0) || wo.z <= Real(0))
            return Real(0);
        Vec3<Real> m = normalize(Vec3<Real>{wi.x + wo.x, wi.y + wo.y, wi.z + wo.z});
        if (bug_ == Bug::Throws)
            throw std::bad_alloc(); // e.g. a texture lookup that allocates
        Real f0 = bug_ == Bug::Eval ? f0_ * Real(0.9) : f0_;
        Real g2 = Real(1) / (Real(1) + lambda(wi) + lambda(wo));
        return schlick(f0, dot(wi, m)) * D(m, ax_, ay_) * g2 / (Real(4) * wi.z);
    }

private:
    Real ax_, ay_, f0_;
    Bug bug_;
};

// ---- the C callbacks --------------------------------------------------------
// mcstat calls these with `user` = the BSDF, n points at a time.  Good
// practice at a C boundary: no exception may cross it (catch everything and
// return non-zero: mcstat then stops with MCSTAT_ECALLBACK naming the
// callback; the exception is kept, for the caller to rethrow after mcstat
// has returned), convert the batch once, and keep the per-point loop free of
// allocation and virtual calls.  The counters let a benchmark see how many
// points each callback was asked for.
template <class Bsdf> struct Callbacks {
    const Bsdf *bsdf;
    unsigned long long sample_points = 0, pdf_points = 0, eval_points = 0;
    unsigned long long sample_calls = 0, pdf_calls = 0, eval_calls = 0;
    std::exception_ptr error; // what a callback caught: rethrow it once mcstat has returned

    Callbacks(const Bsdf *b) : bsdf(b) {}

    template <class R> static Vec3<R> vec(const double *p) { return {R(p[0]), R(p[1]), R(p[2])}; }

    static int sample(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                      double *pdf) noexcept
    {
        auto *self = static_cast<Callbacks *>(user);
        try {
            self->sample_calls++;
            self->sample_points += n;
            auto w = vec<typename Bsdf::real_type>(wi);
            for (size_t k = 0; k < n; k++) {
                SampleOut s = self->bsdf->sample(w, typename Bsdf::real_type(u[2 * k]),
                                                 typename Bsdf::real_type(u[2 * k + 1]));
                x[3 * k] = s.x[0], x[3 * k + 1] = s.x[1], x[3 * k + 2] = s.x[2];
                weight[k] = s.weight;
                pdf[k] = s.pdf;
            }
            return 0;
        } catch (...) {
            self->error = std::current_exception();
            return 1;
        }
    }

    static int pdf(void *user, const double *wi, const double *x, size_t n, double *out) noexcept
    {
        auto *self = static_cast<Callbacks *>(user);
        try {
            self->pdf_calls++;
            self->pdf_points += n;
            auto w = vec<typename Bsdf::real_type>(wi);
            for (size_t k = 0; k < n; k++)
                out[k] = double(self->bsdf->pdf(w, vec<typename Bsdf::real_type>(x + 3 * k)));
            return 0;
        } catch (...) {
            self->error = std::current_exception();
            return 1;
        }
    }

    static int eval(void *user, const double *wi, const double *x, size_t n, double *out) noexcept
    {
        auto *self = static_cast<Callbacks *>(user);
        try {
            self->eval_calls++;
            self->eval_points += n;
            auto w = vec<typename Bsdf::real_type>(wi);
            for (size_t k = 0; k < n; k++)
                out[k] = double(self->bsdf->eval(w, vec<typename Bsdf::real_type>(x + 3 * k)));
            return 0;
        } catch (...) {
            self->error = std::current_exception();
            return 1;
        }
    }

    // The model mcstat checks: a reflection-only BSDF on the upper
    // hemisphere, two uniforms per sample, Mitsuba's weight = eval / pdf.
    mcstat_check_model model()
    {
        mcstat_check_model m{};
        m.domain = MCSTAT_CHECK_DOMAIN_HEMISPHERE;
        m.n_uniforms = 2;
        m.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
        m.sample_reports = 1;
        m.user = this;
        m.sample = &Callbacks::sample;
        m.pdf = &Callbacks::pdf;
        m.eval = &Callbacks::eval;
        return m;
    }
};

} // namespace ggx

#endif
