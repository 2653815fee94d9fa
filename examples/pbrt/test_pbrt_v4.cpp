// test_pbrt_v4.cpp - mcstat_pbrt.h on BxDFs behind pbrt-v4's signatures
// (pbrt_standin.h): what the adapter converts, checked point by point; the
// correct BxDFs pass the assertion of mcstat_testing.h; and each planted
// bug is rejected, at a fixed seed, by the route that should see it.
//
// The planted bugs wrap a correct BxDF and change one routine, as a
// renderer's bug would:
//   PdfHighOnHalf  PDF() 10% high where wi.x > 0 (Sample_f reports the
//                  right pdf): pdf_value;
//   CosineInF      f() returns f |cos theta_i|, the value Mitsuba's eval
//                  returns, while Sample_f's f is pbrt's: weight;
//   WeightHigh     Sample_f's f 10% high: weight;
//   SamplerWide    Sample_f draws from roughness x 1.1 but reports the true
//                  f and pdf of the direction it drew: cells (no
//                  deterministic route can see it).
#include <gtest/gtest.h>
#include <gtest/gtest-spi.h>

#include "mcstat_pbrt.h"
#include "mcstat_testing.h"

#include "pbrt_standin.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

using namespace pbrt;

namespace {

constexpr size_t kN = 100000;
constexpr uint64_t kSeed = 20260521;
constexpr double kAlpha = 0.01;
constexpr double kPi = 3.14159265358979323846;

// A direction theta degrees off the normal, at azimuth phi degrees.
struct Dir {
    double v[3];
    Dir(double theta, double phi = 30.0)
    {
        double t = theta * kPi / 180, p = phi * kPi / 180;
        v[0] = std::sin(t) * std::cos(p), v[1] = std::sin(t) * std::sin(p), v[2] = std::cos(t);
    }
};

DiffuseBxDF diffuse() { return DiffuseBxDF(SampledSpectrum({0.9f, 0.6f, 0.4f, 0.2f})); }

// gold-like, anisotropic
ConductorBxDF conductor(Float roughness = 1.0f)
{
    return ConductorBxDF(TrowbridgeReitzDistribution(0.3f * roughness, 0.15f * roughness),
                         SampledSpectrum({0.2f, 0.4f, 0.9f, 1.3f}), SampledSpectrum({3.9f, 2.6f, 2.0f, 1.8f}));
}

// ---- the planted bugs ---------------------------------------------------------------
template <class B> struct Forward {
    B b;
    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode m) const { return b.f(wo, wi, m); }
    std::optional<BSDFSample> Sample_f(Vector3f wo, Float uc, Point2f u, TransportMode m,
                                       BxDFReflTransFlags fl) const
    {
        return b.Sample_f(wo, uc, u, m, fl);
    }
    Float PDF(Vector3f wo, Vector3f wi, TransportMode m, BxDFReflTransFlags fl) const { return b.PDF(wo, wi, m, fl); }
    BxDFFlags Flags() const { return b.Flags(); }
};

template <class B> struct PdfHighOnHalf : Forward<B> {
    Float PDF(Vector3f wo, Vector3f wi, TransportMode m, BxDFReflTransFlags fl) const
    {
        Float p = this->b.PDF(wo, wi, m, fl);
        return wi.x > 0 ? 1.1f * p : p;
    }
};

template <class B> struct CosineInF : Forward<B> {
    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode m) const
    {
        return this->b.f(wo, wi, m) * AbsCosTheta(wi);
    }
};

template <class B> struct WeightHigh : Forward<B> {
    std::optional<BSDFSample> Sample_f(Vector3f wo, Float uc, Point2f u, TransportMode m,
                                       BxDFReflTransFlags fl) const
    {
        std::optional<BSDFSample> bs = this->b.Sample_f(wo, uc, u, m, fl);
        if (bs)
            bs->f = bs->f * 1.1f;
        return bs;
    }
};

struct SamplerWide : Forward<ConductorBxDF> {
    ConductorBxDF wide = conductor(1.1f);
    std::optional<BSDFSample> Sample_f(Vector3f wo, Float uc, Point2f u, TransportMode m,
                                       BxDFReflTransFlags fl) const
    {
        std::optional<BSDFSample> bs = wide.Sample_f(wo, uc, u, m, fl);
        if (bs) {
            bs->pdf = b.PDF(wo, bs->wi, m, fl);
            bs->f = b.f(wo, bs->wi, m);
        }
        return bs;
    }
};

// The conductor's reflectance by the real-arithmetic closed form (a^2 + b^2
// and a of the complex cos_t; Born & Wolf 14.2), independent of the
// std::complex form in pbrt_standin.h, for the mirror's lobe.
double fresnel_conductor(double c, double eta, double k)
{
    double s2 = 1 - c * c, t = eta * eta - k * k - s2;
    double a2b2 = std::sqrt(t * t + 4 * eta * eta * k * k), a = std::sqrt((a2b2 + t) / 2);
    double rs = (a2b2 - 2 * a * c + c * c) / (a2b2 + 2 * a * c + c * c);
    double rp = rs * (c * c * a2b2 - 2 * a * c * s2 + s2 * s2) / (c * c * a2b2 + 2 * a * c * s2 + s2 * s2);
    return (rs + rp) / 2;
}

// The smooth conductor's one lobe: the mirror direction, always chosen,
// carrying the channels' mean reflectance.
std::vector<mcstat_pbrt::Lobe> mirror_lobe(const double *wo)
{
    const double eta[4] = {0.2, 0.4, 0.9, 1.3}, k[4] = {3.9, 2.6, 2.0, 1.8};
    double c = std::abs(wo[2]), r = 0;
    for (int i = 0; i < 4; i++)
        r += fresnel_conductor(c, eta[i], k[i]) / 4;
    return {{{-wo[0], -wo[1], wo[2]}, 1.0, r}};
}

std::string routes_rejecting(const mcstat_check_report &r)
{
    std::string s;
    for (int k = 0; k < MCSTAT_CHECK_ROUTE_COUNT; k++)
        if (r.route[k].state == MCSTAT_CHECK_STATE_RAN && r.route[k].reject)
            s += std::string(s.empty() ? "" : ", ") + mcstat_check_route_name(k);
    return s.empty() ? "none" : s;
}

// One check at the fixed seed; prints a line for the log.
template <class A> mcstat_check_report run(A &check, const char *what, int *status)
{
    mcstat_check_model m = check.model();
    mcstat_check_report r;
    *status = mcstat_check_bsdf(&m, check.wo(), kN, kSeed, kAlpha, nullptr, nullptr, 0, &r);
    if (*status == MCSTAT_OK)
        std::printf("%-44s %s (p = %.3g; rejecting: %s)\n", what, r.reject ? "REJECTED" : "passed", r.p_value,
                    routes_rejecting(r).c_str());
    return r;
}

template <class A> void expect_rejected_by(A &check, int route, const char *what)
{
    int status;
    mcstat_check_report r = run(check, what, &status);
    ASSERT_EQ(status, MCSTAT_OK) << r.message;
    EXPECT_TRUE(r.reject) << mcstat_testing::check_text(r);
    EXPECT_EQ(r.route[route].state, MCSTAT_CHECK_STATE_RAN);
    EXPECT_TRUE(r.route[route].reject) << mcstat_check_route_name(route) << " did not reject\n"
                                       << mcstat_testing::check_text(r);
}

// Sample_f's f and pdf scaled alike by a random factor: estimates whose
// ratio is right, flagged as pbrt-v4's layered BxDFs flag theirs.
struct Proportional : Forward<DiffuseBxDF> {
    std::optional<BSDFSample> Sample_f(Vector3f wo, Float uc, Point2f u, TransportMode m,
                                       BxDFReflTransFlags fl) const
    {
        std::optional<BSDFSample> bs = b.Sample_f(wo, uc, u, m, fl);
        if (bs) {
            Float s = 0.5f + uc;
            bs->f = bs->f * s, bs->pdf *= s, bs->pdfIsProportional = true;
        }
        return bs;
    }
};

// ---- a probe: records what the adapter hands the BxDF -----------------------------
struct Probe {
    mutable Vector3f f_wo, f_wi;
    mutable Float uc = -1;
    mutable Point2f u{-1, -1};
    enum Mode { Ok, Empty, ZeroPdf, Throws } mode = Ok;
    SampledSpectrum f(Vector3f wo, Vector3f wi, TransportMode) const
    {
        if (mode == Throws)
            throw std::runtime_error("texture lookup failed");
        f_wo = wo, f_wi = wi;
        return SampledSpectrum({0.1f, 0.2f, 0.3f, 0.4f});
    }
    std::optional<BSDFSample> Sample_f(Vector3f, Float uc_, Point2f u_, TransportMode, BxDFReflTransFlags) const
    {
        uc = uc_, u = u_;
        if (mode == Empty)
            return {};
        Vector3f wi(0.6f, 0.0f, 0.8f);
        return BSDFSample(SampledSpectrum(0.5f), wi, mode == ZeroPdf ? 0.0f : 0.25f, GlossyReflection);
    }
    Float PDF(Vector3f, Vector3f wi, TransportMode, BxDFReflTransFlags) const { return wi.z; }
    BxDFFlags Flags() const { return GlossyReflection; }
};

} // namespace

// ---- the conventions, point by point --------------------------------------------------
TEST(Adapter, NamesCosineAndWeight)
{
    Probe p;
    auto check = mcstat_pbrt::adapt(p, {0.0, 0.0, 2.0});
    mcstat_check_model m = check.model();
    EXPECT_EQ(m.n_uniforms, 3);
    EXPECT_EQ(m.weight, MCSTAT_CHECK_WEIGHT_VALUE);
    EXPECT_EQ(m.domain, MCSTAT_CHECK_DOMAIN_HEMISPHERE); // reflection only, wo above
    EXPECT_EQ(check.wo()[2], 1.0);                 // normalised
    const double wi[3] = {0.0, 0.6, 0.8}, x[3] = {0.8, 0.0, 0.6};
    double out = -1;
    ASSERT_EQ(m.eval(m.user, wi, x, 1, &out), 0);
    // pbrt's f(wo, wi) got mcstat's wi as wo and the point as wi ...
    EXPECT_FLOAT_EQ(p.f_wo.y, 0.6f);
    EXPECT_FLOAT_EQ(p.f_wi.x, 0.8f);
    // ... and eval is the channels' mean times |cos theta_i|, in float
    EXPECT_EQ(out, double(0.25f * 0.6f));
    ASSERT_EQ(m.pdf(m.user, wi, x, 1, &out), 0);
    EXPECT_EQ(out, double(0.6f));
    // the sample's weight is f |cos| (MCSTAT_CHECK_WEIGHT_VALUE), its pdf Sample_f's
    const double u[3] = {0.1, 0.2, 0.3};
    double xs[3], w, pdf;
    ASSERT_EQ(m.sample(m.user, wi, u, 1, xs, &w, &pdf), 0);
    EXPECT_EQ(w, double(0.5f * 0.8f));
    EXPECT_EQ(pdf, 0.25);
    EXPECT_EQ(xs[0], double(0.6f));
    EXPECT_FLOAT_EQ(p.uc, 0.1f);
    EXPECT_FLOAT_EQ(p.u.x, 0.2f);
    EXPECT_FLOAT_EQ(p.u.y, 0.3f);
}

TEST(Adapter, UniformsStayBelowOneInFloat)
{
    Probe p;
    auto check = mcstat_pbrt::adapt(p, {0.0, 0.0, 1.0});
    mcstat_check_model m = check.model();
    const double top = 1.0 - std::ldexp(1.0, -53); // mcstat's largest uniform: 1.0f as a float
    ASSERT_EQ(float(top), 1.0f);
    const double u[3] = {top, top, 1.0 - std::ldexp(1.0, -26)};
    double x[3], w, pdf;
    ASSERT_EQ(m.sample(m.user, check.wo(), u, 1, x, &w, &pdf), 0);
    const float below_one = std::nextafter(1.0f, 0.0f);
    EXPECT_EQ(p.uc, below_one);
    EXPECT_EQ(p.u.x, below_one);
    EXPECT_EQ(p.u.y, below_one);
}

TEST(Adapter, FailedSamples)
{
    Probe p;
    auto check = mcstat_pbrt::adapt(p, {0.0, 0.0, 1.0});
    mcstat_check_model m = check.model();
    const double u[3] = {0.5, 0.5, 0.5};
    for (Probe::Mode mode : {Probe::Empty, Probe::ZeroPdf}) {
        p.mode = mode;
        double x[3], w = -1, pdf = -1;
        ASSERT_EQ(m.sample(m.user, check.wo(), u, 1, x, &w, &pdf), 0);
        EXPECT_EQ(pdf, 0.0);
        EXPECT_EQ(w, 0.0);
    }
}

TEST(Adapter, ExceptionsStopTheCheckAtTheBoundary)
{
    Probe p;
    p.mode = Probe::Throws;
    auto check = mcstat_pbrt::adapt(p, {0.0, 0.0, 1.0});
    mcstat_check_model m = check.model();
    mcstat_check_report r;
    EXPECT_EQ(mcstat_check_bsdf(&m, check.wo(), 1000, 1, 0.01, nullptr, nullptr, 0, &r), MCSTAT_ECALLBACK);
    EXPECT_NE(std::string(r.message).find("eval() returned status 1"), std::string::npos) << r.message;
    EXPECT_EQ(check.error(), "f threw: texture lookup failed");
    EXPECT_THROW(std::rethrow_exception(check.exception()), std::runtime_error);
}

TEST(Adapter, DomainFromFlagsAndSide)
{
    DiffuseBxDF d = diffuse();
    EXPECT_EQ(mcstat_pbrt::adapt(d, {0.3, 0.0, 0.9}).domain(), MCSTAT_CHECK_DOMAIN_HEMISPHERE);
    EXPECT_EQ(mcstat_pbrt::adapt(d, {0.3, 0.0, -0.9}).domain(), MCSTAT_CHECK_DOMAIN_SPHERE);
}

TEST(Adapter, ReducersOfASpectrum)
{
    SampledSpectrum s({1.0f, 2.0f, 3.0f, 6.0f});
    EXPECT_EQ(mcstat_pbrt::average()(s), 3.0);
    EXPECT_EQ(mcstat_pbrt::channel{2}(s), 3.0);
    EXPECT_EQ(mcstat_pbrt::average()(0.5f), 0.5);
}

// A specular sample without lobes is refused, clearly; with pdfIsProportional, too.
TEST(Adapter, DeltaLobeWithoutLobesIsRefused)
{
    ConductorBxDF mirror = conductor(0.0f);
    auto check = mcstat_pbrt::adapt(mirror, Dir(40).v);
    mcstat_check_model m = check.model();
    mcstat_check_report r;
    EXPECT_EQ(mcstat_check_bsdf(&m, check.wo(), 1000, 1, 0.01, nullptr, nullptr, 0, &r), MCSTAT_ECALLBACK);
    EXPECT_NE(check.error().find("Sample_f returned a specular sample"), std::string::npos) << check.error();
}

TEST(Adapter, ProportionalPdfNeedsTheStochasticOption)
{
    Proportional b{{diffuse()}};
    auto check = mcstat_pbrt::adapt(b, Dir(30).v);
    mcstat_check_model m = check.model();
    mcstat_check_report r;
    EXPECT_EQ(mcstat_check_bsdf(&m, check.wo(), 1000, 1, 0.01, nullptr, nullptr, 0, &r), MCSTAT_ECALLBACK);
    EXPECT_NE(check.error().find("pdfIsProportional"), std::string::npos) << check.error();
    // told, with options.stochastic: the statistical routes judge it
    auto told = mcstat_pbrt::adapt(b, Dir(30).v);
    told.stochastic(true);
    mcstat_check_model mt = told.model();
    mcstat_check_options o;
    mcstat_check_options_init(&o);
    o.stochastic = 1;
    ASSERT_EQ(mcstat_check_bsdf(&mt, told.wo(), kN, kSeed, kAlpha, &o, nullptr, 0, &r), MCSTAT_OK) << r.message;
    EXPECT_FALSE(r.reject) << mcstat_testing::check_text(r);
}

// ---- correct BxDFs pass mcstat_testing.h's assertion ---------------------------------
TEST(Correct, DiffuseAbove)
{
    DiffuseBxDF b = diffuse();
    auto c = mcstat_pbrt::adapt(b, Dir(30).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, DiffuseFromBelow)
{
    DiffuseBxDF b = diffuse();
    auto c = mcstat_pbrt::adapt(b, {0.3, -0.2, -0.9}); // light arriving from below: the sphere
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, ConductorAt20Degrees)
{
    ConductorBxDF b = conductor();
    auto c = mcstat_pbrt::adapt(b, Dir(20).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, ConductorAt75Degrees)
{
    ConductorBxDF b = conductor();
    auto c = mcstat_pbrt::adapt(b, Dir(75, 110).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, ConductorFromBelow)
{
    ConductorBxDF b = conductor();
    auto c = mcstat_pbrt::adapt(b, Dir(140).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, ConductorOneChannel)
{
    ConductorBxDF b = conductor();
    auto c = mcstat_pbrt::adapt(b, Dir(45).v, mcstat_pbrt::channel{3});
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Correct, MirrorWithItsLobe)
{
    ConductorBxDF b = conductor(0.0f);
    auto c = mcstat_pbrt::adapt(b, Dir(50).v);
    c.lobes(mirror_lobe);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

// ---- planted bugs: rejected, by the route that sees them -------------------------------
TEST(Planted, PdfHighOnHalfOfTheDomain)
{
    PdfHighOnHalf<DiffuseBxDF> d{{diffuse()}};
    auto cd = mcstat_pbrt::adapt(d, Dir(30).v);
    expect_rejected_by(cd, MCSTAT_CHECK_ROUTE_PDF_VALUE, "diffuse, PDF() 10% high where wi.x > 0");
    PdfHighOnHalf<ConductorBxDF> g{{conductor()}};
    auto cg = mcstat_pbrt::adapt(g, Dir(30).v);
    expect_rejected_by(cg, MCSTAT_CHECK_ROUTE_PDF_VALUE, "conductor, PDF() 10% high where wi.x > 0");
}

TEST(Planted, CosineFoldedIntoF)
{
    CosineInF<DiffuseBxDF> d{{diffuse()}};
    auto cd = mcstat_pbrt::adapt(d, Dir(30).v);
    expect_rejected_by(cd, MCSTAT_CHECK_ROUTE_WEIGHT, "diffuse, f() includes |cos theta_i|");
    CosineInF<ConductorBxDF> g{{conductor()}};
    auto cg = mcstat_pbrt::adapt(g, Dir(30).v);
    expect_rejected_by(cg, MCSTAT_CHECK_ROUTE_WEIGHT, "conductor, f() includes |cos theta_i|");
}

TEST(Planted, SampleWeightTenPercentHigh)
{
    WeightHigh<DiffuseBxDF> d{{diffuse()}};
    auto cd = mcstat_pbrt::adapt(d, Dir(30).v);
    expect_rejected_by(cd, MCSTAT_CHECK_ROUTE_WEIGHT, "diffuse, Sample_f's f 10% high");
    WeightHigh<ConductorBxDF> g{{conductor()}};
    auto cg = mcstat_pbrt::adapt(g, Dir(30).v);
    expect_rejected_by(cg, MCSTAT_CHECK_ROUTE_WEIGHT, "conductor, Sample_f's f 10% high");
    WeightHigh<ConductorBxDF> mirror{{conductor(0.0f)}};
    auto cm = mcstat_pbrt::adapt(mirror, Dir(50).v);
    cm.lobes(mirror_lobe);
    expect_rejected_by(cm, MCSTAT_CHECK_ROUTE_WEIGHT, "mirror, Sample_f's f 10% high");
}

TEST(Planted, SamplerOfAnotherRoughness)
{
    SamplerWide s{{conductor()}};
    auto c = mcstat_pbrt::adapt(s, Dir(30).v);
    expect_rejected_by(c, MCSTAT_CHECK_ROUTE_CELLS, "conductor, Sample_f draws roughness x 1.1");
}

// The assertion itself fails on a planted bug, with mcstat's report.
static void assert_weight_high_consistent()
{
    WeightHigh<ConductorBxDF> g{{conductor()}};
    auto c = mcstat_pbrt::adapt(g, Dir(30).v);
    MCSTAT_EXPECT_BSDF_CONSISTENT(c.model(), c.wo(), kN);
}

TEST(Planted, TheAssertionFails)
{
    EXPECT_NONFATAL_FAILURE(assert_weight_high_consistent(), "check_bsdf rejected");
}
