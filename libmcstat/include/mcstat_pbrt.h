/*
 * mcstat_pbrt.h - a pbrt-style BxDF as an mcstat renderer-check model
 * (mcstat.h, "Renderer checks"), so that mcstat_check_bsdf and
 * mcstat_testing.h's assertions check it as the renderer calls it.
 * Header-only C++14 over libmcstat; it includes no pbrt header and reaches
 * the BxDF's types through templates.
 *
 *     #include <gtest/gtest.h>
 *     #include <mcstat_testing.h>
 *     #include <mcstat_pbrt.h>
 *     #include <pbrt/bxdfs.h>
 *
 *     TEST(Conductor, Consistent) {
 *         pbrt::ConductorBxDF bxdf(pbrt::TrowbridgeReitzDistribution(0.3f, 0.15f),
 *                                  pbrt::SampledSpectrum(0.2f), pbrt::SampledSpectrum(3.9f));
 *         auto check = mcstat_pbrt::adapt(bxdf, {0.5, 0.3, 0.8});   // wo, pbrt's fixed direction
 *         MCSTAT_EXPECT_BSDF_CONSISTENT(check.model(), check.wo(), 100000);
 *     }
 *
 * Two interfaces are recognised from the signature of Sample_f (the
 * BxDF's, in its local shading frame, normal +z):
 *   pbrt-v4  SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode)
 *            optional<BSDFSample> Sample_f(Vector3f wo, Float uc, Point2f u,
 *                                          TransportMode, BxDFReflTransFlags)
 *            Float PDF(Vector3f wo, Vector3f wi, TransportMode, BxDFReflTransFlags)
 *            BSDFSample: f, wi, pdf, flags; Flags() (optional) gives the domain;
 *   pbrt-v3  Spectrum f(const Vector3f &wo, const Vector3f &wi)
 *            Spectrum Sample_f(const Vector3f &wo, Vector3f *wi, const Point2f &u,
 *                              Float *pdf, BxDFType *sampledType)
 *            Float Pdf(const Vector3f &wo, const Vector3f &wi)
 *            the member `type` (optional) gives the domain and, as pbrt-v3's
 *            BSDF does, the initial *sampledType and which side f() counts
 *            on (Reflection: wo.z wi.z > 0; Transmission: the other).
 * A class whose Sample_f is overloaded or a template names its interface
 * instead: Adapter<B, v4_api<Vector3f, Float, Point2f, TransportMode,
 * BxDFReflTransFlags>> (or v3_api<Vector3f, Float, Point2f, BxDFType>).
 * Directions are in the shading frame (the cosine is |wi.z|): pbrt's BSDF
 * works in render space, so check its BxDF.
 *
 * What the adapter converts, and why:
 *   - Names.  pbrt's f(wo, wi) keeps wo (towards the camera) fixed and
 *     samples wi; mcstat_check_bsdf keeps "wi" fixed and samples x.  So
 *     mcstat's wi is pbrt's wo (check.wo() is what the check is given) and
 *     mcstat's x is pbrt's wi.
 *   - The cosine.  pbrt's f excludes |cos theta_i|; mcstat's eval is the
 *     integrand f |cos x.z|.  The adapter multiplies it in, in the BxDF's
 *     Float, so that a float renderer's values stay float32 (the check then
 *     applies float32's numerical floor).
 *   - The weight.  pbrt's sampler returns the value f (and the integrator
 *     multiplies by |cos| / pdf): MCSTAT_CHECK_WEIGHT_VALUE, weight = f |cos|.
 *   - Spectra.  mcstat checks a scalar: by default the average of the
 *     channels (Reduce = average: the spectrum's Average(), as pbrt-v4's
 *     SampledSpectrum has, else the mean of s[0 .. S::nSamples), as
 *     pbrt-v3's CoefficientSpectrum has, else the value itself for a
 *     scalar).  The mean is linear, so a consistent BxDF stays consistent;
 *     a bug confined to one channel is diluted by the channel count:
 *     mcstat_pbrt::channel{k} checks channel k alone.  Any functor
 *     double(const Spectrum &) may be given.
 *   - Uniforms.  mcstat's are doubles in [0, 1); converted to float, those
 *     above 1 - 2^-25 round to 1.0f, which pbrt's samplers never produce.
 *     Each is clamped to the largest Float below 1 (pbrt's OneMinusEpsilon).
 *     pbrt-v4: uc = u[0], u = (u[1], u[2]); pbrt-v3: u = (u[0], u[1]).
 *   - Failed samples.  An empty optional (v4) or pdf 0 is mcstat's failed
 *     sample (pdf 0, weight 0).  A sample with pdf > 0 and f = 0 (pbrt's BSDF
 *     wrapper drops it) stays a success of weight 0: the sampler did draw it.
 *   - The domain.  The hemisphere (z >= 0) when the BxDF's flags say
 *     reflection only (no Transmission bit) and wo.z > 0, else the sphere
 *     (pbrt's reflection BxDFs mirror their samples below when wo.z < 0).
 *     .domain(d) overrides it.
 *   - Transport mode (v4): Radiance (the enum's 0); .api().mode = ... sets it.
 *     Sample flags (v4): All (Reflection | Transmission, 3).
 *   - Delta lobes.  A sample whose flags have the Specular bit (16 in both
 *     versions) comes with a probability, not a density, and pbrt's f() and
 *     PDF() are 0 there.  mcstat checks such lobes against a description of
 *     them (model.lobes): give it with .lobes(fn), fn(const double wo[3])
 *     returning std::vector<mcstat_pbrt::Lobe>: each lobe's direction (pbrt's
 *     wi), the probability Sample_f picks it (what it reports as pdf) and its
 *     albedo, the reduced f |cos| it returns (pbrt: F for a mirror), at most
 *     MCSTAT_CHECK_MAX_LOBES; written from the physics, not from Sample_f,
 *     or the check only compares Sample_f with itself.  Without it, a
 *     specular sample stops the check (below): no density can pass for it.
 *   - Estimated pdfs (pbrt-v4's pdfIsProportional, layered BxDFs).  Sample_f's
 *     f and pdf are then estimates, which mcstat checks only with
 *     options.stochastic = 1 (the statistical routes; pdf_value and weight
 *     skipped): call .stochastic(true) and mcstat_check_bsdf with that
 *     option (the mcstat_testing.h macros use the default options).
 *     Without it, such a sample stops the check.  (A PDF() that is itself
 *     an estimate, as LayeredBxDF's, makes the cells' cubature integrate a
 *     noisy function; not tried here.)
 * Exceptions never cross mcstat's C frames: a callback that catches one
 * returns 1, a refusal (a specular or proportional sample the adapter was
 * not told of, too many lobes) 2, and mcstat_check_bsdf then returns
 * MCSTAT_ECALLBACK naming the callback.  The adapter keeps the first reason
 * (error(); the exception itself: exception(), to rethrow once mcstat has
 * returned) and prints it to stderr once, as "mcstat_pbrt: ...", since the
 * check's report can only say that the callback failed.
 *
 * The adapter holds a pointer to the BxDF (a temporary is refused at
 * compile time) and model().user points to the adapter: both must outlive
 * the check, and a copy of the adapter needs its own model().  Not
 * thread-safe (mcstat calls back from the calling thread).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_PBRT_H
#define MCSTAT_PBRT_H

#include "mcstat.h"

#if defined(MCSTAT_NO_EXPERIMENTAL)
#error "mcstat_pbrt.h needs mcstat.h's experimental section \"Renderer checks\" (MCSTAT_NO_EXPERIMENTAL is defined)"
#endif

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mcstat_pbrt {

// The flag bits pbrt-v4's BxDFFlags and pbrt-v3's BxDFType share.
constexpr unsigned kReflection = 1u << 0, kTransmission = 1u << 1, kSpecular = 1u << 4;

namespace detail {
template <class T> struct dependent_false : std::false_type {};
// Overload priority: of the overloads that compile, the highest rank wins.
template <int N> struct rank : rank<N - 1> {};
template <> struct rank<0> {};
} // namespace detail

// ---- the user's types: customisation points -------------------------------------
// A vector built from three Floats and read through .x, .y, .z (pbrt's
// Vector3f); specialise for another layout.
template <class V> struct vector_traits {
    template <class F> static V make(F x, F y, F z) { return V(x, y, z); }
    static void get(const V &v, double out[3])
    {
        out[0] = double(v.x), out[1] = double(v.y), out[2] = double(v.z);
    }
    static auto z(const V &v) -> decltype(v.z) { return v.z; }
};

// A 2D sample built from two Floats (pbrt's Point2f).
template <class P> struct point_traits {
    template <class F> static P make(F a, F b) { return P(a, b); }
};

// A uniform of mcstat's as the BxDF's Float, below 1 (see the header).
template <class F> inline F uniform(double u)
{
    const F below_one = std::nextafter(F(1), F(0));
    F v = F(u);
    return v < below_one ? v : below_one;
}

// ---- spectra to one number -----------------------------------------------------
struct average {
    template <class S> double operator()(const S &s) const { return get(s, detail::rank<3>()); }

private:
    template <class S> static auto get(const S &s, detail::rank<3>) -> decltype(double(s.Average()))
    {
        return double(s.Average());
    }
    template <class S>
    static auto get(const S &s, detail::rank<2>) -> decltype(double(s[0]), double(S::nSamples))
    {
        double sum = 0;
        for (int i = 0; i < int(S::nSamples); i++)
            sum += double(s[i]);
        return sum / double(S::nSamples);
    }
    template <class S>
    static auto get(const S &s, detail::rank<1>) -> typename std::enable_if<std::is_arithmetic<S>::value, double>::type
    {
        return double(s);
    }
    template <class S> static double get(const S &, detail::rank<0>)
    {
        static_assert(detail::dependent_false<S>::value,
                      "mcstat_pbrt::average: the spectrum has no Average(), no nSamples with operator[] and is "
                      "not a number: give the adapter a functor double(const Spectrum &)");
        return 0;
    }
};

// One channel of the spectrum, s[k].
struct channel {
    int k;
    template <class S> double operator()(const S &s) const { return double(s[k]); }
};

// ---- the two interfaces -----------------------------------------------------------
// A sample as mcstat wants it: failed when pdf == 0.
struct sampled {
    double x[3] = {0.0, 0.0, 1.0};
    double weight = 0.0, pdf = 0.0;
    unsigned flags = 0;
    bool proportional = false;
};

namespace detail {
template <class B> auto flags_of(const B &b, rank<2>) -> decltype(long(static_cast<unsigned>(b.Flags())))
{
    return long(static_cast<unsigned>(b.Flags()));
}
template <class B> auto flags_of(const B &b, rank<1>) -> decltype(long(static_cast<unsigned>(b.type)))
{
    return long(static_cast<unsigned>(b.type));
}
template <class B> long flags_of(const B &, rank<0>) { return -1; }

template <class T, class B> auto v3_initial_type(const B &b, rank<1>) -> decltype(static_cast<T>(b.type))
{
    return static_cast<T>(b.type);
}
template <class T, class B> T v3_initial_type(const B &, rank<0>) { return static_cast<T>(0); }

template <class S> auto proportional(const S &s, rank<1>) -> decltype(bool(s.pdfIsProportional))
{
    return bool(s.pdfIsProportional);
}
template <class S> bool proportional(const S &, rank<0>) { return false; }
} // namespace detail

// The BxDF's flags (Flags() in v4, the member type in v3) as bits; -1 when
// it has neither.
template <class B> long bxdf_flags(const B &b) { return detail::flags_of(b, detail::rank<2>()); }

template <class V, class F, class P, class M, class S> struct v4_api {
    using vector_type = V;
    using real_type = F;
    static constexpr int n_uniforms = 3;
    M mode = static_cast<M>(0); // pbrt-v4's TransportMode::Radiance
    static S all() { return static_cast<S>(3); } // BxDFReflTransFlags::All = Reflection | Transmission

    template <class B, class R> sampled sample(const B &b, const V &wo, const double *u, const R &reduce) const
    {
        sampled s;
        F uc = uniform<F>(u[0]);
        P u2 = point_traits<P>::make(uniform<F>(u[1]), uniform<F>(u[2]));
        auto bs = b.Sample_f(wo, uc, u2, mode, all());
        if (!bs || bs->pdf == 0)
            return s;
        vector_traits<V>::get(bs->wi, s.x);
        s.pdf = double(bs->pdf);
        s.weight = double(F(reduce(bs->f)) * F(std::abs(vector_traits<V>::z(bs->wi))));
        s.flags = static_cast<unsigned>(bs->flags);
        s.proportional = detail::proportional(*bs, detail::rank<1>());
        return s;
    }
    template <class B, class R> double eval(const B &b, const V &wo, const V &wi, const R &reduce) const
    {
        return double(F(reduce(b.f(wo, wi, mode))) * F(std::abs(vector_traits<V>::z(wi))));
    }
    template <class B> double pdf(const B &b, const V &wo, const V &wi) const
    {
        return double(b.PDF(wo, wi, mode, all()));
    }
};

template <class V, class F, class P, class T> struct v3_api {
    using vector_type = V;
    using real_type = F;
    static constexpr int n_uniforms = 2;

    template <class B, class R> sampled sample(const B &b, const V &wo, const double *u, const R &reduce) const
    {
        sampled s;
        P u2 = point_traits<P>::make(uniform<F>(u[0]), uniform<F>(u[1]));
        V wi = vector_traits<V>::make(F(0), F(0), F(0));
        F pdf = F(0);
        // pbrt-v3's BSDF sets *sampledType to the BxDF's type before the call
        T type = detail::v3_initial_type<T>(b, detail::rank<1>());
        auto f = b.Sample_f(wo, &wi, u2, &pdf, &type);
        if (pdf == 0)
            return s;
        vector_traits<V>::get(wi, s.x);
        s.pdf = double(pdf);
        s.weight = double(F(reduce(f)) * F(std::abs(vector_traits<V>::z(wi))));
        s.flags = static_cast<unsigned>(type);
        return s;
    }
    // pbrt-v3's BxDFs leave the side to the BSDF (LambertianReflection::f
    // is R/pi below the horizon too): BSDF::f adds a BxDF's f only when its
    // type has Reflection for wo and wi on one side (of the geometric normal,
    // here the shading one), Transmission otherwise.  So does the adapter.
    template <class B, class R> double eval(const B &b, const V &wo, const V &wi, const R &reduce) const
    {
        long type = bxdf_flags(b);
        bool reflect = double(vector_traits<V>::z(wo)) * double(vector_traits<V>::z(wi)) > 0;
        if (type >= 0 && !(unsigned(type) & (reflect ? kReflection : kTransmission)))
            return 0.0;
        return double(F(reduce(b.f(wo, wi))) * F(std::abs(vector_traits<V>::z(wi))));
    }
    template <class B> double pdf(const B &b, const V &wo, const V &wi) const { return double(b.Pdf(wo, wi)); }
};

// The interface of a member function pointer to Sample_f.  v3's pattern is
// the more specialised, so it wins where both match.
template <class Sig> struct api_of {
    static_assert(detail::dependent_false<Sig>::value,
                  "mcstat_pbrt: Sample_f has neither pbrt-v4's signature (wo, uc, u, mode, flags) nor pbrt-v3's "
                  "(wo, wi*, u, pdf*, type*) as a const member: name the interface, Adapter<B, v4_api<...>>");
};
template <class R, class C, class V, class F, class P, class M, class S> struct api_of<R (C::*)(V, F, P, M, S) const> {
    using type = v4_api<typename std::decay<V>::type, typename std::decay<F>::type, typename std::decay<P>::type,
                        typename std::decay<M>::type, typename std::decay<S>::type>;
};
template <class R, class C, class V, class P, class F, class T>
struct api_of<R (C::*)(const V &, V *, const P &, F *, T *) const> {
    using type = v3_api<V, F, P, T>;
};
#if defined(__cpp_noexcept_function_type)
template <class R, class C, class V, class F, class P, class M, class S>
struct api_of<R (C::*)(V, F, P, M, S) const noexcept> : api_of<R (C::*)(V, F, P, M, S) const> {};
template <class R, class C, class V, class P, class F, class T>
struct api_of<R (C::*)(const V &, V *, const P &, F *, T *) const noexcept>
    : api_of<R (C::*)(const V &, V *, const P &, F *, T *) const> {};
#endif

template <class B> using api_for = typename api_of<decltype(&B::Sample_f)>::type;

// ---- delta lobes -----------------------------------------------------------------
struct Lobe {
    double direction[3]; // pbrt's wi of the lobe (unit length)
    double mass;         // the probability Sample_f picks it, the pdf it reports there
    double value;        // its albedo: the reduced f |cos| Sample_f returns there
};
using LobesFn = std::function<std::vector<Lobe>(const double *wo)>;

// ---- the adapter -----------------------------------------------------------------
template <class BxDF, class Api = api_for<BxDF>, class Reduce = average> class Adapter {
public:
    using vector_type = typename Api::vector_type;
    using real_type = typename Api::real_type;

    Adapter(const BxDF &bxdf, const double (&wo)[3], Reduce reduce = Reduce())
        : bxdf_(&bxdf), reduce_(std::move(reduce))
    {
        double len = std::sqrt(wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2]);
        for (int c = 0; c < 3; c++)
            wo_[c] = len > 0 && std::isfinite(len) ? wo[c] / len : wo[c]; // else mcstat refuses it (EINVAL)
        long flags = bxdf_flags(bxdf);
        bool reflection_only = flags >= 0 && !(unsigned(flags) & kTransmission);
        domain_ = reflection_only && wo_[2] > 0 ? MCSTAT_CHECK_DOMAIN_HEMISPHERE : MCSTAT_CHECK_DOMAIN_SPHERE;
    }
    Adapter(const BxDF &&, const double (&)[3], Reduce = Reduce()) = delete; // would dangle

    // pbrt's wo, normalised: the wi to give mcstat_check_bsdf.
    const double *wo() const { return wo_; }
    int domain() const { return domain_; }
    Adapter &domain(int d)
    {
        domain_ = d;
        return *this;
    }
    Adapter &lobes(LobesFn fn)
    {
        lobes_ = std::move(fn);
        return *this;
    }
    Adapter &stochastic(bool on)
    {
        stochastic_ = on;
        return *this;
    }
    Api &api() { return api_; }

    // The model for mcstat_check_bsdf; its user pointer is this adapter.
    mcstat_check_model model()
    {
        mcstat_check_model m{};
        m.domain = domain_;
        m.n_uniforms = Api::n_uniforms;
        m.weight = MCSTAT_CHECK_WEIGHT_VALUE;
        m.sample_reports = 1;
        m.user = this;
        m.sample = &Adapter::sample_cb;
        m.pdf = &Adapter::pdf_cb;
        m.eval = &Adapter::eval_cb;
        if (lobes_)
            m.lobes = &Adapter::lobes_cb;
        return m;
    }

    // Why a callback failed (empty if none did), and the exception it caught.
    const std::string &error() const { return error_; }
    std::exception_ptr exception() const { return exception_; }

private:
    static vector_type vec(const double *p)
    {
        return vector_traits<vector_type>::make(real_type(p[0]), real_type(p[1]), real_type(p[2]));
    }

    // The first failure is kept and printed; mcstat stops at it anyway.
    int fail(int status, const std::string &why) noexcept
    {
        try {
            if (error_.empty()) {
                error_ = why;
                std::fprintf(stderr, "mcstat_pbrt: %s\n", why.c_str());
            }
        } catch (...) {
        }
        return status;
    }

    int caught(const char *where) noexcept
    {
        try {
            if (!exception_)
                exception_ = std::current_exception();
            try {
                throw;
            } catch (const std::exception &e) {
                return fail(1, std::string(where) + " threw: " + e.what());
            } catch (...) {
                return fail(1, std::string(where) + " threw an exception not derived from std::exception");
            }
        } catch (...) {
            return 1;
        }
    }

    static std::string point(const double *x)
    {
        char b[96];
        std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", x[0], x[1], x[2]);
        return b;
    }

    static int sample_cb(void *user, const double *wi, const double *u, size_t n, double *x, double *weight,
                         double *pdf) noexcept
    {
        Adapter *self = static_cast<Adapter *>(user);
        try {
            vector_type wo = vec(wi);
            for (size_t k = 0; k < n; k++) {
                sampled s = self->api_.sample(*self->bxdf_, wo, u + k * size_t(Api::n_uniforms), self->reduce_);
                if (s.pdf != 0 && (s.flags & kSpecular) && !self->lobes_)
                    return self->fail(2, "Sample_f returned a specular sample (flags " + std::to_string(s.flags) +
                                             ", pdf " + std::to_string(s.pdf) + ", wi " + point(s.x) +
                                             "): a delta lobe has a probability, not a density, and f() and "
                                             "PDF() are 0 there; describe the lobes with .lobes(fn) "
                                             "(mcstat_pbrt.h, \"Delta lobes\")");
                if (s.pdf != 0 && s.proportional && !self->stochastic_)
                    return self->fail(2, "Sample_f returned pdfIsProportional: its f and pdf are estimates; "
                                         "call .stochastic(true) and check with options.stochastic = 1");
                x[3 * k] = s.x[0], x[3 * k + 1] = s.x[1], x[3 * k + 2] = s.x[2];
                weight[k] = s.weight;
                pdf[k] = s.pdf;
            }
            return 0;
        } catch (...) {
            return self->caught("Sample_f");
        }
    }

    static int pdf_cb(void *user, const double *wi, const double *x, size_t n, double *out) noexcept
    {
        Adapter *self = static_cast<Adapter *>(user);
        try {
            vector_type wo = vec(wi);
            for (size_t k = 0; k < n; k++)
                out[k] = self->api_.pdf(*self->bxdf_, wo, vec(x + 3 * k));
            return 0;
        } catch (...) {
            return self->caught("PDF");
        }
    }

    static int eval_cb(void *user, const double *wi, const double *x, size_t n, double *out) noexcept
    {
        Adapter *self = static_cast<Adapter *>(user);
        try {
            vector_type wo = vec(wi);
            for (size_t k = 0; k < n; k++)
                out[k] = self->api_.eval(*self->bxdf_, wo, vec(x + 3 * k), self->reduce_);
            return 0;
        } catch (...) {
            return self->caught("f");
        }
    }

    static int lobes_cb(void *user, const double *wi, double *x, double *mass, double *value, size_t *count) noexcept
    {
        Adapter *self = static_cast<Adapter *>(user);
        try {
            std::vector<Lobe> lobes = self->lobes_(wi);
            if (lobes.size() > MCSTAT_CHECK_MAX_LOBES)
                return self->fail(2, "the lobes function gave " + std::to_string(lobes.size()) +
                                         " lobes, more than MCSTAT_CHECK_MAX_LOBES");
            for (size_t k = 0; k < lobes.size(); k++) {
                for (size_t c = 0; c < 3; c++)
                    x[3 * k + c] = lobes[k].direction[c];
                mass[k] = lobes[k].mass;
                value[k] = lobes[k].value;
            }
            *count = lobes.size();
            return 0;
        } catch (...) {
            return self->caught("the lobes function");
        }
    }

    const BxDF *bxdf_;
    Api api_;
    Reduce reduce_;
    double wo_[3];
    int domain_;
    LobesFn lobes_;
    bool stochastic_ = false;
    std::string error_;
    std::exception_ptr exception_;
};

// adapt(bxdf, wo) and adapt(bxdf, wo, reduce): the interface from Sample_f.
template <class BxDF> Adapter<BxDF> adapt(const BxDF &bxdf, const double (&wo)[3])
{
    return Adapter<BxDF>(bxdf, wo);
}
template <class BxDF, class Reduce>
Adapter<BxDF, api_for<BxDF>, Reduce> adapt(const BxDF &bxdf, const double (&wo)[3], Reduce reduce)
{
    return Adapter<BxDF, api_for<BxDF>, Reduce>(bxdf, wo, std::move(reduce));
}
template <class BxDF> void adapt(const BxDF &&, const double (&)[3]) = delete; // would dangle
template <class BxDF, class Reduce> void adapt(const BxDF &&, const double (&)[3], Reduce) = delete;

} // namespace mcstat_pbrt

#endif /* MCSTAT_PBRT_H */
