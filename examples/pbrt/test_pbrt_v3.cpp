// test_pbrt_v3.cpp - mcstat_pbrt.h on BxDFs behind pbrt-v3's virtual
// interface (pbrt3_standin.h), built as C++14: the interface recognised
// from Sample_f's out-pointers, two uniforms, *sampledType started from the
// BxDF's type, f() kept to its side as pbrt-v3's BSDF keeps it; correct
// BxDFs pass mcstat_testing.h's assertion, and planted bugs (overrides, as
// a pbrt-v3 bug would be) are rejected at a fixed seed by their route:
//   PdfHighOnHalf      Pdf() 10% high where wi.x > 0: pdf_value;
//   CosineInSampledF   Sample_f returns f |cos theta_i| (the integrand, as
//                      Mitsuba's sampler would) where pbrt wants f: weight;
//   WeightHigh         Sample_f's value 10% high: weight (also on the mirror).
// And a blind spot, pinned: f() multiplied by |cos theta_i| in a BxDF whose
// Sample_f returns f() (pbrt-v3's default sampler, by virtual call) is a
// consistent BxDF, only not the intended one; no consistency check can
// tell, a reference albedo can (it is 2/3 of R here).
#include <gtest/gtest.h>

#include "mcstat_pbrt.h"
#include "mcstat_testing.h"

#include "pbrt3_standin.h"

#include <cmath>
#include <cstdio>
#include <string>

using namespace pbrt3;

namespace {

constexpr size_t kN = 100000;
constexpr uint64_t kSeed = 20260521;
constexpr double kAlpha = 0.01;
constexpr double kPi = 3.14159265358979323846;

struct Dir {
    double v[3];
    Dir(double theta, double phi = 30.0)
    {
        double t = theta * kPi / 180, p = phi * kPi / 180;
        v[0] = std::sin(t) * std::cos(p), v[1] = std::sin(t) * std::sin(p), v[2] = std::cos(t);
    }
};

const Spectrum kAlbedo(0.9f, 0.5f, 0.2f);
const BeckmannDistribution kBeckmann(0.25f);
const FresnelSchlick kSchlick(Spectrum(0.95f, 0.64f, 0.54f)); // copper-like F0

struct PdfHighOnHalf : MicrofacetReflection {
    PdfHighOnHalf() : MicrofacetReflection(kAlbedo, &kBeckmann, &kSchlick) {}
    Float Pdf(const Vector3f &wo, const Vector3f &wi) const override
    {
        Float p = MicrofacetReflection::Pdf(wo, wi);
        return wi.x > 0 ? 1.1f * p : p;
    }
};

struct CosineInF : LambertianReflection {
    CosineInF() : LambertianReflection(kAlbedo) {}
    Spectrum f(const Vector3f &wo, const Vector3f &wi) const override
    {
        return LambertianReflection::f(wo, wi) * AbsCosTheta(wi);
    }
};

template <class B> struct CosineInSampledF : B {
    using B::B;
    Spectrum Sample_f(const Vector3f &wo, Vector3f *wi, const Point2f &u, Float *pdf,
                      BxDFType *sampledType) const override
    {
        Spectrum f = B::Sample_f(wo, wi, u, pdf, sampledType);
        return f * AbsCosTheta(*wi);
    }
};

template <class B> struct WeightHigh : B {
    using B::B;
    Spectrum Sample_f(const Vector3f &wo, Vector3f *wi, const Point2f &u, Float *pdf,
                      BxDFType *sampledType) const override
    {
        return B::Sample_f(wo, wi, u, pdf, sampledType) * 1.1f;
    }
};

std::vector<mcstat_pbrt::Lobe> mirror_lobe(const double *wo)
{
    return {{{-wo[0], -wo[1], wo[2]}, 1.0, (0.9 + 0.5 + 0.2) / 3}};
}

std::string routes_rejecting(const mcstat_check_report &r)
{
    std::string s;
    for (int k = 0; k < MCSTAT_CHECK_ROUTE_COUNT; k++)
        if (r.route[k].state == MCSTAT_CHECK_STATE_RAN && r.route[k].reject)
            s += std::string(s.empty() ? "" : ", ") + mcstat_check_route_name(k);
    return s.empty() ? "none" : s;
}

template <class A> void expect_rejected_by(A &check, int route, const char *what)
{
    mcstat_check_model m = check.model();
    mcstat_check_report r;
    ASSERT_EQ(mcstat_check_bsdf(&m, check.wo(), kN, kSeed, kAlpha, nullptr, nullptr, 0, &r), MCSTAT_OK) << r.message;
    std::printf("%-44s %s (p = %.3g; rejecting: %s)\n", what, r.reject ? "REJECTED" : "passed", r.p_value,
                routes_rejecting(r).c_str());
    EXPECT_TRUE(r.reject) << mcstat_testing::check_text(r);
    EXPECT_TRUE(r.route[route].state == MCSTAT_CHECK_STATE_RAN && r.route[route].reject)
        << mcstat_check_route_name(route) << " did not reject\n"
        << mcstat_testing::check_text(r);
}

// Records what the adapter hands Sample_f; writes no sampledType.
struct Probe : BxDF {
    mutable Point2f u;
    Probe() : BxDF(BSDF_REFLECTION | BSDF_SPECULAR) {}
    Spectrum f(const Vector3f &, const Vector3f &) const override { return Spectrum(0.5f); }
    Spectrum Sample_f(const Vector3f &wo, Vector3f *wi, const Point2f &u_, Float *pdf, BxDFType *) const override
    {
        u = u_;
        *wi = Vector3f(-wo.x, -wo.y, wo.z);
        *pdf = 1;
        return Spectrum(0.5f);
    }
};

} // namespace

TEST(Adapter, Pbrt3Interface)
{
    Probe p;
    auto check = mcstat_pbrt::adapt(p, {0.0, 0.0, 1.0});
    mcstat_check_model m = check.model();
    EXPECT_EQ(m.n_uniforms, 2);
    EXPECT_EQ(m.weight, MCSTAT_CHECK_WEIGHT_VALUE);
    EXPECT_EQ(m.domain, MCSTAT_CHECK_DOMAIN_HEMISPHERE);
    const double top = 1.0 - std::ldexp(1.0, -53), u[2] = {top, 0.25};
    double x[3], w, pdf;
    // the BxDF's type made the sample specular, and no lobes were given: refused
    EXPECT_EQ(m.sample(m.user, check.wo(), u, 1, x, &w, &pdf), 2);
    EXPECT_NE(check.error().find("specular"), std::string::npos);
    EXPECT_EQ(p.u.x, std::nextafter(1.0f, 0.0f));
    EXPECT_EQ(p.u.y, 0.25f);
}

TEST(Adapter, Pbrt3SideOfF)
{
    // LambertianReflection::f is R/pi on both sides; pbrt-v3's BSDF counts it on wo's side only
    LambertianReflection b(kAlbedo);
    auto check = mcstat_pbrt::adapt(b, {0.0, 0.0, -1.0});
    EXPECT_EQ(check.domain(), MCSTAT_CHECK_DOMAIN_SPHERE);
    mcstat_check_model m = check.model();
    const double above[3] = {0.0, 0.6, 0.8}, below[3] = {0.0, 0.6, -0.8};
    double out[2];
    ASSERT_EQ(m.eval(m.user, check.wo(), above, 1, &out[0]), 0);
    ASSERT_EQ(m.eval(m.user, check.wo(), below, 1, &out[1]), 0);
    EXPECT_EQ(out[0], 0.0);
    EXPECT_FLOAT_EQ(float(out[1]), float(kAlbedo[0] + kAlbedo[1] + kAlbedo[2]) / 3 / float(kPi) * 0.8f);
}

TEST(Correct, Lambertian)
{
    LambertianReflection b(kAlbedo);
    auto c = mcstat_pbrt::adapt(b, Dir(30).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, LambertianFromBelow)
{
    LambertianReflection b(kAlbedo);
    auto c = mcstat_pbrt::adapt(b, Dir(150).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, BeckmannAt30Degrees)
{
    MicrofacetReflection b(kAlbedo, &kBeckmann, &kSchlick);
    auto c = mcstat_pbrt::adapt(b, Dir(30).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, BeckmannAt70DegreesFromBelow)
{
    MicrofacetReflection b(kAlbedo, &kBeckmann, &kSchlick);
    auto c = mcstat_pbrt::adapt(b, Dir(110).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, MirrorWithItsLobe)
{
    SpecularReflection b(kAlbedo);
    auto c = mcstat_pbrt::adapt(b, Dir(40).v);
    c.lobes(mirror_lobe);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Planted, PdfHighOnHalfOfTheDomain)
{
    PdfHighOnHalf b;
    auto c = mcstat_pbrt::adapt(b, Dir(30).v);
    expect_rejected_by(c, MCSTAT_CHECK_ROUTE_PDF_VALUE, "v3 Beckmann, Pdf() 10% high where wi.x > 0");
}

TEST(Planted, CosineInTheSampledValue)
{
    CosineInSampledF<LambertianReflection> b(kAlbedo);
    auto c = mcstat_pbrt::adapt(b, Dir(30).v);
    expect_rejected_by(c, MCSTAT_CHECK_ROUTE_WEIGHT, "v3 Lambertian, Sample_f returns f |cos|");
    CosineInSampledF<MicrofacetReflection> g(kAlbedo, &kBeckmann, &kSchlick);
    auto cg = mcstat_pbrt::adapt(g, Dir(30).v);
    expect_rejected_by(cg, MCSTAT_CHECK_ROUTE_WEIGHT, "v3 Beckmann, Sample_f returns f |cos|");
}

TEST(BlindSpot, CosineInFAndSoInItsSampler)
{
    CosineInF b;
    auto c = mcstat_pbrt::adapt(b, Dir(30).v);
    mcstat_check_model m = c.model();
    mcstat_check_report r;
    ASSERT_EQ(mcstat_check_bsdf(&m, c.wo(), kN, kSeed, kAlpha, nullptr, nullptr, 0, &r), MCSTAT_OK);
    EXPECT_FALSE(r.reject) << mcstat_testing::check_text(r);
    double rho = (0.9 + 0.5 + 0.2) / 3; // the albedo it should have; cos^2 / pi integrates to 2/3
    EXPECT_NEAR(r.albedo, 2.0 / 3.0 * rho, 5 * r.albedo_se);
}

TEST(Planted, SampleWeightTenPercentHigh)
{
    WeightHigh<MicrofacetReflection> b(kAlbedo, &kBeckmann, &kSchlick);
    auto c = mcstat_pbrt::adapt(b, Dir(30).v);
    expect_rejected_by(c, MCSTAT_CHECK_ROUTE_WEIGHT, "v3 Beckmann, Sample_f's value 10% high");
    WeightHigh<SpecularReflection> mirror(kAlbedo);
    auto cm = mcstat_pbrt::adapt(mirror, Dir(40).v);
    cm.lobes(mirror_lobe);
    expect_rejected_by(cm, MCSTAT_CHECK_ROUTE_WEIGHT, "v3 mirror, Sample_f's value 10% high");
}
