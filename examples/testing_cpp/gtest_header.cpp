// gtest_header.cpp - mcstat_testing.h's own rules: its seeds against
// values computed independently (Python's mcstat.testing, the published
// FNV-1a and SplitMix64 constants), the budget split, and a check beyond
// the declared count failing instead of overspending.
#include <gtest/gtest.h>
#include <gtest/gtest-spi.h>

#include "mcstat_testing.h"

#include "ggx_checks.hpp"

TEST(Seeds, PublishedConstants)
{
    EXPECT_EQ(mcstat_testing::fnv1a64(""), 0xcbf29ce484222325ull);
    EXPECT_EQ(mcstat_testing::fnv1a64("a"), 0xaf63dc4c8601ec8cull);
    EXPECT_EQ(mcstat_testing::fnv1a64("foobar"), 0x85944171f73967e8ull);
    EXPECT_EQ(mcstat_testing::splitmix64(0), 0xe220a8397b1dcdafull);
    EXPECT_EQ(mcstat_testing::splitmix64(0x9E3779B97F4A7C15ull), 0x6e789e6aa1b965f4ull);
}

TEST(Seeds, SameAsPython)
{
    // python: mcstat.testing.check_seed(7, "Ggx.ConsistentAt20Degrees", 0), and stage2_seed of it
    EXPECT_EQ(mcstat_testing::check_seed(7, "Ggx.ConsistentAt20Degrees", 0), 0xa1b206793d8b8686ull);
    EXPECT_EQ(mcstat_testing::stage2_seed(mcstat_testing::check_seed(7, "Ggx.ConsistentAt20Degrees", 0)),
              0x551afa00b31cf359ull);
}

TEST(Seeds, DataSeedSameAsPython)
{
    // python: mcstat.testing._seeds.data_seed(7, "Seeds.DataSeedSameAsPython", "estimates") and label ""
    EXPECT_EQ(mcstat_testing::data_seed(7, "Seeds.DataSeedSameAsPython", "estimates"), 0xd289fad8deaaf501ull);
    EXPECT_EQ(mcstat_testing::data_seed(7, "Seeds.DataSeedSameAsPython", ""), 0x7c029715620f6239ull);
    // the running test's, under the run's MCSTAT_SEED, is never one of its checks' seeds
    uint64_t own = MCSTAT_DATA_SEED("estimates");
    EXPECT_EQ(own, mcstat_testing::data_seed(mcstat_testing::suite().settings.master, "Seeds.DataSeedSameAsPython",
                                             "estimates"));
    for (unsigned j = 0; j < 8; j++)
        EXPECT_NE(own, mcstat_testing::check_seed(mcstat_testing::suite().settings.master,
                                                  "Seeds.DataSeedSameAsPython", j));
    EXPECT_NE(own, MCSTAT_DATA_SEED("other"));
}

static void two_checks_one_declared()
{
    std::vector<double> v = example::cosine_estimates(2000, 3);
    MCSTAT_EXPECT_UNBIASED(v.data(), v.size(), example::kPi);
    MCSTAT_EXPECT_UNBIASED(v.data(), v.size(), example::kPi);
}

TEST(Budget, AnUndeclaredCheckFails)
{
    EXPECT_NONFATAL_FAILURE(two_checks_one_declared(), "is one more than the 1 the test declared");
}

TEST(Budget, ShareIsTheSuitesOverTheTestsAndChecks)
{
    // MCSTAT_SUITE_TESTS=8 and MCSTAT_SUITE_ALPHA=0.004 (CMakeLists.txt): 5e-4 a test, 2.5e-4 a check
    MCSTAT_TEST_CHECKS(2);
    mcstat_testing::Plan p = mcstat_testing::next_check("probe");
    ASSERT_TRUE(p.ok) << p.error;
    EXPECT_DOUBLE_EQ(p.alpha, 0.004 / 8 / 2);
    EXPECT_EQ(p.seed, mcstat_testing::check_seed(0, "Budget.ShareIsTheSuitesOverTheTestsAndChecks", 0));
}
