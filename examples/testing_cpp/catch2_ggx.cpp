// catch2_ggx.cpp - the same checks as gtest_ggx.cpp as Catch2 (v2) test
// cases; the planted one is tagged [planted].
#define CATCH_CONFIG_MAIN
#include <catch2/catch.hpp>

#include "mcstat_testing.h"

#include "ggx_checks.hpp"

TEST_CASE("ggx is consistent at 20 and 60 degrees")
{
    MCSTAT_TEST_CHECKS(2);
    example::Bsdf b;
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(20), 50000);
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(60), 50000);
}

TEST_CASE("the cosine warp draws its density") { MCSTAT_ASSERT_WARP_CONSISTENT(example::cosine_warp(), 50000); }

TEST_CASE("the cosine integral estimator is unbiased")
{
    std::vector<double> v = example::cosine_estimates(20000, 7);
    MCSTAT_EXPECT_UNBIASED(v.data(), v.size(), example::kPi);
}

TEST_CASE("a planted pdf bug is caught", "[planted]")
{
    example::Bsdf b(ggx::Bug::Pdf);
    MCSTAT_EXPECT_BSDF_CONSISTENT(b.model(), example::incident(35), 50000);
}
