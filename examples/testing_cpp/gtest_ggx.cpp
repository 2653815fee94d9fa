// gtest_ggx.cpp - mcstat's checks as GoogleTest assertions (mcstat_testing.h)
// under one budget for the run: the correct GGX at three angles, the warp
// and an estimator pass; the planted pdf bug fails (ctest expects that of
// the Planted test alone, CMakeLists.txt); a BSDF whose heavy-tailed
// weights leave the check inconclusive fails, and passes where the test
// allows it.
#include <gtest/gtest.h>

#include "mcstat_testing.h"

#include "ggx_checks.hpp"

TEST(Ggx, ConsistentAt20Degrees)
{
    example::Bsdf b;
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(20), 50000);
}

TEST(Ggx, ConsistentAt60Degrees)
{
    example::Bsdf b;
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(60), 50000);
}

TEST(Ggx, TwoChecksDeclared)
{
    MCSTAT_TEST_CHECKS(2);
    example::Bsdf b;
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(35), 50000);
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(75), 50000);
}

TEST(Warp, CosineHemisphere) { MCSTAT_ASSERT_WARP_CONSISTENT(example::cosine_warp(), 50000); }

TEST(Phase, Isotropic) { MCSTAT_EXPECT_PHASE_CONSISTENT(example::isotropic_phase(), example::incident(30), 50000); }

TEST(Medium, HomogeneousFlights) { MCSTAT_EXPECT_MEDIUM_CONSISTENT(example::homogeneous_medium(), 2.0, 50000); }

TEST(Estimator, CosineIntegralIsPi)
{
    std::vector<double> v = example::cosine_estimates(20000, 7);
    MCSTAT_EXPECT_UNBIASED(v.data(), v.size(), example::kPi);
}

TEST(Planted, PdfBugIsCaught)
{
    example::Bsdf b(ggx::Bug::Pdf);
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(35), 50000);
}

TEST(Inconclusive, WrongCosineFails)
{
    MCSTAT_EXPECT_BSDF_CONSISTENT(example::wrong_cosine_bsdf(), example::incident(0), 50000);
}

TEST(Inconclusive, WrongCosineAllowed)
{
    MCSTAT_ALLOW_INCONCLUSIVE();
    MCSTAT_EXPECT_BSDF_CONSISTENT(example::wrong_cosine_bsdf(), example::incident(0), 50000);
}
