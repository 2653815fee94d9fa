// test_pbrt_bsdf.cpp - a pbrt-v4 BxDF checked by mcstat in one GoogleTest assertion: does
// Sample_f draw what PDF() claims, with the f that f() returns?  Drop it into pbrt's tests
// (link libmcstat); outside pbrt's tree, pbrt_standin.h supplies the names.
#include <gtest/gtest.h>
#include <mcstat_pbrt.h>
#include <mcstat_testing.h>
#if __has_include(<pbrt/bxdfs.h>)
#include <pbrt/bxdfs.h>
#else
#include "pbrt_standin.h"
#endif

TEST(PbrtBxDF, RoughConductorIsConsistent)  // run: MCSTAT_SUITE_ALPHA=1e-3 MCSTAT_SEED=0 ./test
{
    pbrt::ConductorBxDF bxdf(pbrt::TrowbridgeReitzDistribution(0.3f, 0.15f), pbrt::SampledSpectrum(0.2f),
                             pbrt::SampledSpectrum(3.9f));                  // gold-like eta, k
    auto check = mcstat_pbrt::adapt(bxdf, {0.5, 0.3, 0.8});               // pbrt's wo: mcstat's wi
    MCSTAT_EXPECT_BSDF_CONSISTENT(check.model(), check.wo(), 100000);
}
