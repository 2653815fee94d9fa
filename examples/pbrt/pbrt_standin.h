// pbrt_standin.h - NOT pbrt: the few types and BxDFs that the pbrt
// examples name, written here behind pbrt-v4's signatures so that the
// tests build without pbrt.  No line of pbrt is copied; the formulas are
// the published ones:
//   Lambert's law, sampled by Malley's method (cosine-weighted directions
//     from a uniform point of the disk, polar mapping);
//   the anisotropic Trowbridge-Reitz (GGX) distribution D, Smith's Lambda
//     and the height-correlated G = 1 / (1 + Lambda(wo) + Lambda(wi))
//     (Heitz 2014, "Understanding the Masking-Shadowing Function", eqs.
//     85-86), and its visible normals sampled as in Heitz 2018, "Sampling
//     the GGX Distribution of Visible Normals", JCGT 7(4), listing 1,
//     with density D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z (eq. 3);
//   the microfacet conductor f = D F G / (4 |cos_o| |cos_i|) with the
//     Jacobian 1 / (4 |wo.m|) of reflection (Walter et al. 2007, eq. 14);
//   Fresnel's equations for a complex index eta + i k (Born & Wolf,
//     "Principles of Optics", 14.2), evaluated in std::complex.
// In pbrt's tree the same test includes <pbrt/bxdfs.h> instead.
#ifndef MCSTAT_EXAMPLE_PBRT_STANDIN_H
#define MCSTAT_EXAMPLE_PBRT_STANDIN_H

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <optional>

namespace pbrt {

using Float = float;
constexpr Float Pi = 3.14159265358979323846f;

struct Vector3f {
    Float x = 0, y = 0, z = 0;
    Vector3f() = default;
    Vector3f(Float x, Float y, Float z) : x(x), y(y), z(z) {}
    Vector3f operator+(const Vector3f &v) const { return {x + v.x, y + v.y, z + v.z}; }
    Vector3f operator-(const Vector3f &v) const { return {x - v.x, y - v.y, z - v.z}; }
    Vector3f operator-() const { return {-x, -y, -z}; }
    Vector3f operator*(Float s) const { return {s * x, s * y, s * z}; }
};
inline Vector3f operator*(Float s, const Vector3f &v) { return v * s; }
inline Float Dot(const Vector3f &a, const Vector3f &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Float AbsDot(const Vector3f &a, const Vector3f &b) { return std::abs(Dot(a, b)); }
inline Float LengthSquared(const Vector3f &v) { return Dot(v, v); }
inline Vector3f Normalize(const Vector3f &v) { return v * (1 / std::sqrt(LengthSquared(v))); }
inline Vector3f Cross(const Vector3f &a, const Vector3f &b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

struct Point2f {
    Float x = 0, y = 0;
    Point2f() = default;
    Point2f(Float x, Float y) : x(x), y(y) {}
    Float operator[](int i) const { return i == 0 ? x : y; }
};

// A few wavelengths' values, as pbrt-v4's SampledSpectrum holds them.
constexpr int NSpectrumSamples = 4;
class SampledSpectrum {
public:
    SampledSpectrum() { v.fill(0); }
    explicit SampledSpectrum(Float c) { v.fill(c); }
    explicit SampledSpectrum(const std::array<Float, NSpectrumSamples> &values) : v(values) {}
    Float operator[](int i) const { return v[size_t(i)]; }
    Float &operator[](int i) { return v[size_t(i)]; }
    explicit operator bool() const
    {
        return std::any_of(v.begin(), v.end(), [](Float c) { return c != 0; });
    }
    SampledSpectrum operator*(const SampledSpectrum &s) const
    {
        SampledSpectrum r;
        for (int i = 0; i < NSpectrumSamples; i++)
            r[i] = (*this)[i] * s[i];
        return r;
    }
    SampledSpectrum operator*(Float a) const
    {
        SampledSpectrum r;
        for (int i = 0; i < NSpectrumSamples; i++)
            r[i] = (*this)[i] * a;
        return r;
    }
    SampledSpectrum operator/(Float a) const { return *this * (1 / a); }
    Float Average() const
    {
        Float s = 0;
        for (Float c : v)
            s += c;
        return s / NSpectrumSamples;
    }

private:
    std::array<Float, NSpectrumSamples> v;
};
inline SampledSpectrum operator*(Float a, const SampledSpectrum &s) { return s * a; }

enum class TransportMode { Radiance, Importance };
enum class BxDFReflTransFlags {
    Unset = 0,
    Reflection = 1 << 0,
    Transmission = 1 << 1,
    All = Reflection | Transmission
};
inline int operator&(BxDFReflTransFlags a, BxDFReflTransFlags b) { return int(a) & int(b); }
enum BxDFFlags {
    Unset = 0,
    Reflection = 1 << 0,
    Transmission = 1 << 1,
    Diffuse = 1 << 2,
    Glossy = 1 << 3,
    Specular = 1 << 4,
    DiffuseReflection = Diffuse | Reflection,
    GlossyReflection = Glossy | Reflection,
    SpecularReflection = Specular | Reflection,
};

struct BSDFSample {
    BSDFSample() = default;
    BSDFSample(SampledSpectrum f, Vector3f wi, Float pdf, BxDFFlags flags, Float eta = 1,
               bool pdfIsProportional = false)
        : f(f), wi(wi), pdf(pdf), flags(flags), eta(eta), pdfIsProportional(pdfIsProportional)
    {
    }
    SampledSpectrum f;
    Vector3f wi;
    Float pdf = 0;
    BxDFFlags flags = Unset;
    Float eta = 1;
    bool pdfIsProportional = false;
};

inline Float AbsCosTheta(const Vector3f &w) { return std::abs(w.z); }
inline bool SameHemisphere(const Vector3f &a, const Vector3f &b) { return a.z * b.z > 0; }
inline Vector3f Reflect(const Vector3f &wo, const Vector3f &n) { return -wo + 2 * Dot(wo, n) * n; }

// Malley's method: a uniform point of the disk (polar map) lifted to the hemisphere.
inline Vector3f SampleCosineHemisphere(Point2f u)
{
    Float r = std::sqrt(u.x), phi = 2 * Pi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max<Float>(0, 1 - u.x))};
}

// Reflectance of a conductor of complex index eta + i k at incidence cos_i:
// the mean of s and p reflectances of Fresnel's equations (cos_t complex).
inline Float FrComplex(Float cos_i, Float eta, Float k)
{
    using C = std::complex<Float>;
    C n(eta, k);
    Float c = std::clamp<Float>(cos_i, 0, 1), sin2 = 1 - c * c;
    C cos_t = std::sqrt(C(1) - sin2 / (n * n));
    C rs = (C(c) - n * cos_t) / (C(c) + n * cos_t);
    C rp = (n * c - cos_t) / (n * c + cos_t);
    return (std::norm(rs) + std::norm(rp)) / 2;
}
inline SampledSpectrum FrComplex(Float cos_i, const SampledSpectrum &eta, const SampledSpectrum &k)
{
    SampledSpectrum r;
    for (int i = 0; i < NSpectrumSamples; i++)
        r[i] = FrComplex(cos_i, eta[i], k[i]);
    return r;
}

class TrowbridgeReitzDistribution {
public:
    TrowbridgeReitzDistribution(Float alpha_x, Float alpha_y) : ax(alpha_x), ay(alpha_y) {}
    // Below this roughness pbrt treats the surface as a mirror (a delta lobe).
    bool EffectivelySmooth() const { return std::max(ax, ay) < 1e-3f; }

    Float D(const Vector3f &m) const
    {
        if (m.z <= 0)
            return 0;
        Float s = m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay) + m.z * m.z;
        return 1 / (Pi * ax * ay * s * s);
    }
    Float Lambda(const Vector3f &w) const
    {
        Float z2 = w.z * w.z;
        if (z2 == 0)
            return INFINITY;
        Float t2 = (ax * ax * w.x * w.x + ay * ay * w.y * w.y) / z2;
        return t2 / (2 * (1 + std::sqrt(1 + t2))); // (sqrt(1 + t2) - 1) / 2 without cancellation
    }
    Float G1(const Vector3f &w) const { return 1 / (1 + Lambda(w)); }
    Float G(const Vector3f &wo, const Vector3f &wi) const { return 1 / (1 + Lambda(wo) + Lambda(wi)); }
    // The density of visible normals m seen from w (w.z > 0 taken as is, else mirrored).
    Float PDF(const Vector3f &w, const Vector3f &m) const
    {
        Float cw = AbsCosTheta(w);
        Float wm = w.z < 0 ? -Dot(w, m) : Dot(w, m);
        return wm > 0 && cw > 0 ? G1(w) * wm * D(m) / cw : 0;
    }
    // A visible normal for w (Heitz 2018, listing 1), mirrored to w's side.
    Vector3f Sample_wm(Vector3f w, Point2f u) const
    {
        if (w.z < 0)
            w = -w;
        Vector3f vh = Normalize(Vector3f(ax * w.x, ay * w.y, w.z));
        Float len2 = vh.x * vh.x + vh.y * vh.y;
        Vector3f t1 = len2 > 0 ? Vector3f(-vh.y, vh.x, 0) * (1 / std::sqrt(len2)) : Vector3f(1, 0, 0);
        Vector3f t2 = Cross(vh, t1);
        Float r = std::sqrt(u.x), phi = 2 * Pi * u.y;
        Float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
        Float s = (1 + vh.z) / 2;
        p2 = (1 - s) * std::sqrt(std::max<Float>(0, 1 - p1 * p1)) + s * p2;
        Float p3 = std::sqrt(std::max<Float>(0, 1 - p1 * p1 - p2 * p2));
        Vector3f nh = p1 * t1 + p2 * t2 + p3 * vh;
        return Normalize(Vector3f(ax * nh.x, ay * nh.y, std::max<Float>(0, nh.z)));
    }

private:
    Float ax, ay;
};

// Lambertian reflection of albedo R.
class DiffuseBxDF {
public:
    explicit DiffuseBxDF(SampledSpectrum R) : R(R) {}
    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode) const
    {
        return SameHemisphere(wo, wi) ? R * (1 / Pi) : SampledSpectrum(0);
    }
    std::optional<BSDFSample> Sample_f(Vector3f wo, Float, Point2f u, TransportMode mode,
                                       BxDFReflTransFlags flags = BxDFReflTransFlags::All) const
    {
        if (!(flags & BxDFReflTransFlags::Reflection) || wo.z == 0)
            return {};
        Vector3f wi = SampleCosineHemisphere(u);
        if (wo.z < 0)
            wi.z = -wi.z;
        return BSDFSample(f(wo, wi, mode), wi, AbsCosTheta(wi) / Pi, DiffuseReflection);
    }
    Float PDF(Vector3f wo, Vector3f wi, TransportMode, BxDFReflTransFlags flags = BxDFReflTransFlags::All) const
    {
        if (!(flags & BxDFReflTransFlags::Reflection) || !SameHemisphere(wo, wi))
            return 0;
        return AbsCosTheta(wi) / Pi;
    }
    BxDFFlags Flags() const { return R ? DiffuseReflection : Unset; }

private:
    SampledSpectrum R;
};

// A rough conductor (Trowbridge-Reitz microfacets, visible normals sampled),
// a mirror below pbrt's smoothness threshold.  Works from either side
// (wo.z < 0 mirrors the frame).
class ConductorBxDF {
public:
    ConductorBxDF(const TrowbridgeReitzDistribution &distrib, SampledSpectrum eta, SampledSpectrum k)
        : distrib(distrib), eta(eta), k(k)
    {
    }
    BxDFFlags Flags() const { return distrib.EffectivelySmooth() ? SpecularReflection : GlossyReflection; }

    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode) const
    {
        if (!SameHemisphere(wo, wi) || distrib.EffectivelySmooth())
            return {};
        Float co = AbsCosTheta(wo), ci = AbsCosTheta(wi);
        Vector3f m = wo + wi;
        if (co == 0 || ci == 0 || LengthSquared(m) == 0)
            return {};
        m = Normalize(m);
        if (m.z < 0)
            m = -m;
        return distrib.D(m) * FrComplex(AbsDot(wo, m), eta, k) * distrib.G(up(wo), up(wi)) / (4 * ci * co);
    }
    std::optional<BSDFSample> Sample_f(Vector3f wo, Float, Point2f u, TransportMode,
                                       BxDFReflTransFlags flags = BxDFReflTransFlags::All) const
    {
        if (!(flags & BxDFReflTransFlags::Reflection) || wo.z == 0)
            return {};
        if (distrib.EffectivelySmooth()) {
            Vector3f wi(-wo.x, -wo.y, wo.z); // all of the light, in the mirror direction
            return BSDFSample(FrComplex(AbsCosTheta(wi), eta, k) / AbsCosTheta(wi), wi, 1, SpecularReflection);
        }
        Vector3f m = distrib.Sample_wm(wo, u);
        if (wo.z < 0)
            m = -m; // the normal on wo's side, so that the reflection stays there
        Vector3f wi = Reflect(wo, m);
        if (!SameHemisphere(wo, wi))
            return {};
        Float co = AbsCosTheta(wo), ci = AbsCosTheta(wi);
        if (ci == 0)
            return {};
        Vector3f mu = m.z < 0 ? -m : m;
        Float pdf = distrib.PDF(wo, mu) / (4 * AbsDot(wo, m));
        SampledSpectrum fv = distrib.D(mu) * FrComplex(AbsDot(wo, m), eta, k) * distrib.G(up(wo), up(wi)) /
                             (4 * ci * co);
        return BSDFSample(fv, wi, pdf, GlossyReflection);
    }
    Float PDF(Vector3f wo, Vector3f wi, TransportMode, BxDFReflTransFlags flags = BxDFReflTransFlags::All) const
    {
        if (!(flags & BxDFReflTransFlags::Reflection) || !SameHemisphere(wo, wi) || distrib.EffectivelySmooth())
            return 0;
        Vector3f m = wo + wi;
        if (LengthSquared(m) == 0)
            return 0;
        m = Normalize(m);
        if (m.z < 0)
            m = -m;
        return distrib.PDF(wo, m) / (4 * AbsDot(wo, m));
    }

private:
    static Vector3f up(const Vector3f &w) { return w.z < 0 ? -w : w; }
    TrowbridgeReitzDistribution distrib;
    SampledSpectrum eta, k;
};

} // namespace pbrt

#endif
