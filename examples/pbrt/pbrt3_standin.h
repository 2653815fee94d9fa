// pbrt3_standin.h - NOT pbrt: BxDFs behind pbrt-v3's virtual interface
// (f, Sample_f with out-pointers, Pdf, the member `type`), written here so
// that the pbrt-v3 test builds without pbrt, in C++14.  No line of pbrt is
// copied; the formulas are the published ones:
//   Lambert's law, sampled by Malley's method (the base class's default
//     sampler, as in pbrt-v3);
//   the Beckmann distribution D(m) = exp(-tan^2 / a^2) / (pi a^2 cos^4),
//     its normals sampled in proportion to D(m) cos(m) (tan^2 = -a^2
//     log(1 - u)), Smith's exact Lambda = (erf(c) - 1) / 2 + exp(-c^2) /
//     (2 c sqrt(pi)), c = 1 / (a tan) (Walter et al. 2007, eqs. 25-28, 33),
//     G = 1 / (1 + Lambda(wo) + Lambda(wi)), and f = R D F G / (4 cos_o cos_i);
//   Schlick's Fresnel approximation F0 + (1 - F0)(1 - cos)^5;
//   a mirror of reflectance R, whose Sample_f sets no sampledType (pbrt-v3's
//     BSDF sets it to the BxDF's type first).
#ifndef MCSTAT_EXAMPLE_PBRT3_STANDIN_H
#define MCSTAT_EXAMPLE_PBRT3_STANDIN_H

#include <algorithm>
#include <cmath>

namespace pbrt3 {

typedef float Float;
constexpr Float Pi = 3.14159265358979323846f;

struct Vector3f {
    Float x, y, z;
    Vector3f() : x(0), y(0), z(0) {}
    Vector3f(Float x, Float y, Float z) : x(x), y(y), z(z) {}
    Vector3f operator+(const Vector3f &v) const { return Vector3f(x + v.x, y + v.y, z + v.z); }
    Vector3f operator-() const { return Vector3f(-x, -y, -z); }
    Vector3f operator*(Float s) const { return Vector3f(s * x, s * y, s * z); }
};
inline Float Dot(const Vector3f &a, const Vector3f &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vector3f Normalize(const Vector3f &v) { return v * (1 / std::sqrt(Dot(v, v))); }
inline Float AbsCosTheta(const Vector3f &w) { return std::abs(w.z); }
inline bool SameHemisphere(const Vector3f &a, const Vector3f &b) { return a.z * b.z > 0; }
inline Vector3f Reflect(const Vector3f &wo, const Vector3f &n) { return -wo + n * (2 * Dot(wo, n)); }

struct Point2f {
    Float x, y;
    Point2f() : x(0), y(0) {}
    Point2f(Float x, Float y) : x(x), y(y) {}
    Float operator[](int i) const { return i == 0 ? x : y; }
};

// Three channels, with pbrt-v3's nSamples and operator[].
class RGBSpectrum {
public:
    static const int nSamples = 3;
    explicit RGBSpectrum(Float v = 0) { c[0] = c[1] = c[2] = v; }
    RGBSpectrum(Float r, Float g, Float b) { c[0] = r, c[1] = g, c[2] = b; }
    Float operator[](int i) const { return c[i]; }
    RGBSpectrum operator*(const RGBSpectrum &s) const { return RGBSpectrum(c[0] * s[0], c[1] * s[1], c[2] * s[2]); }
    RGBSpectrum operator*(Float a) const { return RGBSpectrum(c[0] * a, c[1] * a, c[2] * a); }
    RGBSpectrum operator+(const RGBSpectrum &s) const { return RGBSpectrum(c[0] + s[0], c[1] + s[1], c[2] + s[2]); }

private:
    Float c[3];
};
typedef RGBSpectrum Spectrum;

enum BxDFType {
    BSDF_REFLECTION = 1 << 0,
    BSDF_TRANSMISSION = 1 << 1,
    BSDF_DIFFUSE = 1 << 2,
    BSDF_GLOSSY = 1 << 3,
    BSDF_SPECULAR = 1 << 4,
};
inline BxDFType operator|(BxDFType a, BxDFType b) { return BxDFType(int(a) | int(b)); }

class BxDF {
public:
    explicit BxDF(BxDFType type) : type(type) {}
    virtual ~BxDF() {}
    virtual Spectrum f(const Vector3f &wo, const Vector3f &wi) const = 0;
    // The default: cosine-weighted directions on wo's side (Malley's method).
    virtual Spectrum Sample_f(const Vector3f &wo, Vector3f *wi, const Point2f &u, Float *pdf,
                              BxDFType * /*sampledType*/ = nullptr) const
    {
        Float r = std::sqrt(u.x), phi = 2 * Pi * u.y;
        *wi = Vector3f(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max<Float>(0, 1 - u.x)));
        if (wo.z < 0)
            wi->z = -wi->z;
        *pdf = Pdf(wo, *wi);
        return f(wo, *wi);
    }
    virtual Float Pdf(const Vector3f &wo, const Vector3f &wi) const
    {
        return SameHemisphere(wo, wi) ? AbsCosTheta(wi) / Pi : 0;
    }
    const BxDFType type;
};

// f = R / pi on both sides: pbrt-v3's BSDF, not the BxDF, keeps it to
// reflection.
class LambertianReflection : public BxDF {
public:
    explicit LambertianReflection(const Spectrum &R) : BxDF(BSDF_REFLECTION | BSDF_DIFFUSE), R(R) {}
    Spectrum f(const Vector3f &, const Vector3f &) const override { return R * (1 / Pi); }

private:
    Spectrum R;
};

class BeckmannDistribution {
public:
    explicit BeckmannDistribution(Float alpha) : a(alpha) {}
    Float D(const Vector3f &m) const
    {
        Float c2 = m.z * m.z;
        if (c2 == 0)
            return 0;
        Float t2 = (1 - c2) / c2;
        return std::exp(-t2 / (a * a)) / (Pi * a * a * c2 * c2);
    }
    Float Lambda(const Vector3f &w) const
    {
        Float t = std::sqrt(std::max<Float>(0, 1 - w.z * w.z)) / std::abs(w.z);
        if (t == 0)
            return 0;
        Float c = 1 / (a * t);
        return (std::erf(c) - 1) / 2 + std::exp(-c * c) / (2 * c * std::sqrt(Pi));
    }
    Float G(const Vector3f &wo, const Vector3f &wi) const { return 1 / (1 + Lambda(wo) + Lambda(wi)); }
    // A normal in proportion to D(m) |cos m|, on wo's side.
    Vector3f Sample_wh(const Vector3f &wo, const Point2f &u) const
    {
        Float t2 = -a * a * std::log1p(-u.x), phi = 2 * Pi * u.y;
        Float c = 1 / std::sqrt(1 + t2), s = std::sqrt(std::max<Float>(0, 1 - c * c));
        Vector3f m(s * std::cos(phi), s * std::sin(phi), c);
        return SameHemisphere(wo, m) ? m : -m;
    }
    Float Pdf(const Vector3f &, const Vector3f &wh) const { return D(wh) * AbsCosTheta(wh); }

private:
    Float a;
};

class FresnelSchlick {
public:
    explicit FresnelSchlick(const Spectrum &F0) : F0(F0) {}
    Spectrum Evaluate(Float c) const
    {
        Float k = 1 - std::abs(c), k5 = k * k * k * k * k;
        return F0 * (1 - k5) + Spectrum(k5);
    }

private:
    Spectrum F0;
};

class MicrofacetReflection : public BxDF {
public:
    MicrofacetReflection(const Spectrum &R, const BeckmannDistribution *distribution, const FresnelSchlick *fresnel)
        : BxDF(BSDF_REFLECTION | BSDF_GLOSSY), R(R), distribution(distribution), fresnel(fresnel)
    {
    }
    Spectrum f(const Vector3f &wo, const Vector3f &wi) const override
    {
        Float co = AbsCosTheta(wo), ci = AbsCosTheta(wi);
        Vector3f wh = wi + wo;
        if (co == 0 || ci == 0 || Dot(wh, wh) == 0)
            return Spectrum(0);
        wh = Normalize(wh);
        return R * fresnel->Evaluate(Dot(wi, wh)) * (distribution->D(wh) * distribution->G(wo, wi) / (4 * ci * co));
    }
    Spectrum Sample_f(const Vector3f &wo, Vector3f *wi, const Point2f &u, Float *pdf,
                      BxDFType * /*sampledType*/) const override
    {
        if (wo.z == 0)
            return Spectrum(0);
        Vector3f wh = distribution->Sample_wh(wo, u);
        if (Dot(wo, wh) <= 0)
            return Spectrum(0);
        *wi = Reflect(wo, wh);
        if (!SameHemisphere(wo, *wi))
            return Spectrum(0); // *pdf stays 0: a failed sample
        *pdf = distribution->Pdf(wo, wh) / (4 * Dot(wo, wh));
        return f(wo, *wi);
    }
    Float Pdf(const Vector3f &wo, const Vector3f &wi) const override
    {
        if (!SameHemisphere(wo, wi))
            return 0;
        Vector3f wh = Normalize(wo + wi);
        return distribution->Pdf(wo, wh) / (4 * std::abs(Dot(wo, wh)));
    }

private:
    Spectrum R;
    const BeckmannDistribution *distribution;
    const FresnelSchlick *fresnel;
};

// A mirror of reflectance R: all light in the mirror direction (pdf 1, the
// probability of the lobe), f() and Pdf() 0 everywhere else.
class SpecularReflection : public BxDF {
public:
    explicit SpecularReflection(const Spectrum &R) : BxDF(BSDF_REFLECTION | BSDF_SPECULAR), R(R) {}
    Spectrum f(const Vector3f &, const Vector3f &) const override { return Spectrum(0); }
    Spectrum Sample_f(const Vector3f &wo, Vector3f *wi, const Point2f &, Float *pdf,
                      BxDFType * /*sampledType*/) const override
    {
        *wi = Vector3f(-wo.x, -wo.y, wo.z);
        *pdf = 1;
        return R * (1 / AbsCosTheta(*wi));
    }
    Float Pdf(const Vector3f &, const Vector3f &) const override { return 0; }

private:
    Spectrum R;
};

} // namespace pbrt3

#endif
