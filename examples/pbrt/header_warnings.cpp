// header_warnings.cpp - mcstat_pbrt.h adds no warning to its caller's
// code under the strict flags mcstat/embedded.h is held to (ctest
// testing_pbrt_header_warnings compiles this file with them and -Werror
// as C++14; it is not run): every template of the adapter instantiated
// for a minimal pbrt-v4-like and pbrt-v3-like BxDF, with lobes and a
// custom reducer.
#include "mcstat_pbrt.h"

#include <vector>

namespace {

struct Vec {
    float x, y, z;
    Vec(float a, float b, float c) : x(a), y(b), z(c) {}
};
struct Pt {
    float x, y;
    Pt(float a, float b) : x(a), y(b) {}
};
struct Spectrum {
    float v[2];
    float Average() const { return (v[0] + v[1]) / 2; }
    float operator[](int i) const { return v[i]; }
};
enum class Mode { Radiance, Importance };
enum class SampleFlags { Unset, Reflection, Transmission, All };
enum BxDFFlags { Reflection = 1, Glossy = 8, GlossyReflection = 9 };
struct Sample {
    Spectrum f;
    Vec wi;
    float pdf;
    BxDFFlags flags;
    bool pdfIsProportional;
};
struct Optional {
    bool ok;
    Sample s;
    explicit operator bool() const { return ok; }
    const Sample *operator->() const { return &s; }
    const Sample &operator*() const { return s; }
};

struct V4 {
    Spectrum f(Vec, Vec, Mode) const { return Spectrum{{0.5f, 0.25f}}; }
    Optional Sample_f(Vec wo, float, Pt, Mode, SampleFlags) const
    {
        return Optional{true, Sample{Spectrum{{1.0f, 1.0f}}, Vec(-wo.x, -wo.y, wo.z), 0.5f, GlossyReflection, false}};
    }
    float PDF(Vec, Vec, Mode, SampleFlags) const { return 0.5f; }
    BxDFFlags Flags() const { return GlossyReflection; }
};

enum BxDFType { BSDF_REFLECTION = 1 };
struct V3 {
    BxDFType type = BSDF_REFLECTION;
    double f(const Vec &, const Vec &) const { return 0.5; }
    double Sample_f(const Vec &wo, Vec *wi, const Pt &, float *pdf, BxDFType *) const
    {
        *wi = Vec(-wo.x, -wo.y, wo.z);
        *pdf = 1;
        return 0.5;
    }
    float Pdf(const Vec &, const Vec &) const { return 1; }
};

template <class A> int exercise(A &a)
{
    a.lobes([](const double *wo) { return std::vector<mcstat_pbrt::Lobe>{{{-wo[0], -wo[1], wo[2]}, 0.5, 0.5}}; });
    mcstat_check_model m = a.model();
    const double u[3] = {0.25, 0.5, 0.75}, x[3] = {0.0, 0.6, 0.8};
    double out[3], w, p, lx[3 * MCSTAT_CHECK_MAX_LOBES], mass[MCSTAT_CHECK_MAX_LOBES], value[MCSTAT_CHECK_MAX_LOBES];
    size_t count = 0;
    return m.sample(m.user, a.wo(), u, 1, out, &w, &p) + m.pdf(m.user, a.wo(), x, 1, &p) +
           m.eval(m.user, a.wo(), x, 1, &w) + m.lobes(m.user, a.wo(), lx, mass, value, &count) +
           static_cast<int>(a.error().size()) + (a.exception() ? 1 : 0) + a.domain();
}

} // namespace

int main()
{
    V4 b4;
    V3 b3;
    auto a4 = mcstat_pbrt::adapt(b4, {0.0, 0.6, 0.8});
    auto c4 = mcstat_pbrt::adapt(b4, {0.0, 0.6, 0.8}, mcstat_pbrt::channel{1});
    auto a3 = mcstat_pbrt::adapt(b3, {0.0, 0.6, -0.8});
    a4.api().mode = Mode::Importance;
    a4.stochastic(true).domain(MCSTAT_CHECK_DOMAIN_SPHERE);
    return exercise(a4) + exercise(c4) + exercise(a3);
}
