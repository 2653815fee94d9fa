/*
 * mcstat_testing.h - mcstat's statistical checks as assertions of a C++
 * test framework (GoogleTest or Catch2 v2), under one error budget for the
 * whole suite, with escalation instead of reruns and reproducible seeds.
 * Header-only C++14 over libmcstat; the same rules as Python's
 * mcstat.testing, so a seed printed by either means the same draw.
 *
 *     #include <gtest/gtest.h>
 *     #include <mcstat_testing.h>
 *
 *     TEST(Lambert, Consistent) {                   // run: MCSTAT_SUITE_ALPHA=1e-3 ./tests
 *         mcstat_check_model model = {};            // the BSDF's callbacks (mcstat.h, "Renderer checks")
 *         model.domain = MCSTAT_CHECK_DOMAIN_HEMISPHERE;
 *         model.n_uniforms = 3;
 *         model.weight = MCSTAT_CHECK_WEIGHT_OVER_PDF;
 *         model.sample_reports = 1;
 *         model.sample = lambert_sample, model.pdf = lambert_pdf, model.eval = lambert_eval;
 *         const double wi[3] = {0.48, 0.0, 0.88};
 *         MCSTAT_EXPECT_BSDF_CONSISTENT(model, wi, 100000);
 *     }
 *
 * (the README's GoogleTest quickstart defines the three callbacks; it is
 * built and run as written by the project's checks).
 *
 * Include the framework's header first (gtest/gtest.h, or catch2/catch.hpp);
 * MCSTAT_TESTING_GTEST or MCSTAT_TESTING_CATCH2 defined to 1 forces one.
 *
 * The checks.  Each expands to a statement; the EXPECT forms record a
 * failure and go on, the ASSERT forms (REQUIRE in Catch2) end the test:
 *   MCSTAT_EXPECT_BSDF_CONSISTENT(model, wi, n)     mcstat_check_bsdf
 *   MCSTAT_EXPECT_EMITTER_CONSISTENT(model, n)      mcstat_check_emitter
 *   MCSTAT_EXPECT_WARP_CONSISTENT(model, n)         mcstat_check_warp
 *   MCSTAT_EXPECT_PHASE_CONSISTENT(model, wi, n)    mcstat_check_phase
 *   MCSTAT_EXPECT_MEDIUM_CONSISTENT(model, sigma_ref, n)  mcstat_check_medium
 *   MCSTAT_EXPECT_UNBIASED(values, count, expected) two-sided one-sample t test
 *   MCSTAT_EXPECT_SAME_DISTRIBUTION(x, nx, y, ny)   two-sample Kolmogorov-Smirnov
 *                                                   (unweighted: exact or asymptotic
 *                                                   p-values reach small shares)
 * and MCSTAT_ASSERT_... for each.  A failure's message holds the deciding
 * stage's report (mcstat's text block), the alpha spent, the stages'
 * p-values, the seed and how to rerun exactly that test.  A renderer check
 * whose verdict is inconclusive (mcstat_check_verdict: a route it needed
 * could not answer) fails too, naming the routes and why, unless the test
 * called MCSTAT_ALLOW_INCONCLUSIVE() before it.
 *
 * The budget.  MCSTAT_SUITE_ALPHA (default 1e-3) is the probability that a
 * run in which every checked component is correct fails at all.  It is
 * split evenly over the m statistical tests of the run: MCSTAT_SUITE_TESTS
 * if set, else the number of tests selected to run (GoogleTest's
 * test_to_run_count(), Catch2's tests matching the command line), which is
 * conservative when some of them are not statistical.  A test with k checks
 * declares them first, MCSTAT_TEST_CHECKS(k), and each gets 1/k of the
 * test's share; a check beyond the declared count fails rather than
 * overspend.  By Bonferroni's inequality the run's false-failure
 * probability is at most the budget, whatever the dependence.
 *
 * Seeds.  MCSTAT_SEED (default 0) is the master seed; check j (0, 1, ...) of
 * the test named N ("Suite.Name" in GoogleTest, the test case's name in
 * Catch2) draws from splitmix64(master ^ fnv1a64(N + "#" + j)), and stage 2
 * of an escalated check from splitmix64(seed + 1).  A test's own data (an
 * estimator's samples it draws before MCSTAT_EXPECT_UNBIASED) seeds from
 * MCSTAT_DATA_SEED("label"): splitmix64(master ^ fnv1a64(N + "#data:" +
 * label)), so a failure's rerun line draws the same data again.
 *
 * Escalation (the check_* forms, which draw their own uniforms).  Stage 1
 * runs at n and decides with mcstat_escalation_design(share, 1/2, alpha0):
 * reject at p <= share/2, pass above alpha0 (MCSTAT_ESCALATE_ALPHA0,
 * default 0.05, raised to the smallest band the design allows), and in
 * between run stage 2 at MCSTAT_ESCALATE_FACTOR x n (default 4; 0: no
 * escalation, one stage at the whole share) on fresh uniforms, deciding on
 * p1 p2 (mcstat.h, "Escalation instead of reruns").  The check keeps its
 * level; a correct component escalates with probability about alpha0.
 *
 * The summary: when the process ends, stderr gets one line of what ran
 * (checks, alpha spent of the budget, samples, escalations, failures), if
 * any check ran.  Counters are guarded by a mutex; checks may run on several
 * threads, but a test's own checks are counted in the order they run.
 */
#ifndef MCSTAT_TESTING_H
#define MCSTAT_TESTING_H

#include "mcstat.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <mutex>
#include <string>
#include <vector>
#if defined(__linux__)
#include <unistd.h>
#endif

#if !defined(MCSTAT_TESTING_GTEST) && !defined(MCSTAT_TESTING_CATCH2)
#  if defined(GTEST_INCLUDE_GTEST_GTEST_H_) || defined(GOOGLETEST_INCLUDE_GTEST_GTEST_H_)
#    define MCSTAT_TESTING_GTEST 1
#  elif defined(TWOBLUECUBES_SINGLE_INCLUDE_CATCH_HPP_INCLUDED) || defined(TWOBLUECUBES_CATCH_HPP_INCLUDED)
#    define MCSTAT_TESTING_CATCH2 1
#  else
#    error "mcstat_testing.h: include gtest/gtest.h or catch2/catch.hpp first (or define MCSTAT_TESTING_GTEST / MCSTAT_TESTING_CATCH2)"
#  endif
#endif

namespace mcstat_testing {

// ---- seeds: the same derivation as mcstat.testing (Python) ---------------------
inline uint64_t fnv1a64(const std::string &s)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : s)
        h = (h ^ c) * 0x100000001b3ull;
    return h;
}

inline uint64_t splitmix64(uint64_t x)
{
    uint64_t z = x + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

inline uint64_t check_seed(uint64_t master, const std::string &name, unsigned index)
{
    return splitmix64(master ^ fnv1a64(name + "#" + std::to_string(index)));
}

inline uint64_t stage2_seed(uint64_t seed) { return splitmix64(seed + 1); }

// The seed of a test's own data (what it draws itself, apart from the
// checks' uniforms), `label` naming the draw: never a check's seed (their
// keys end in a number, these in "#data:label"); mcstat.testing's
// Scope.data_seed gives the same for the same master seed and test name.
inline uint64_t data_seed(uint64_t master, const std::string &name, const std::string &label)
{
    return splitmix64(master ^ fnv1a64(name + "#data:" + label));
}

// ---- the run's settings, from the environment ---------------------------------------
struct Settings {
    double alpha = 1e-3, escalate = 4.0, alpha0 = 0.05;
    uint64_t master = 0;
    long tests = 0; // 0: the framework's count
    std::string error; // a bad variable: every check fails with this
};

inline bool env_double(const char *name, double *v, std::string *error)
{
    const char *s = std::getenv(name);
    if (!s || !*s)
        return true;
    char *end = nullptr;
    double d = std::strtod(s, &end);
    if (*end != '\0' || !std::isfinite(d)) {
        *error = std::string(name) + " must be a number, got '" + s + "'";
        return false;
    }
    *v = d;
    return true;
}

inline Settings read_settings()
{
    Settings st;
    if (!env_double("MCSTAT_SUITE_ALPHA", &st.alpha, &st.error) || !(st.alpha > 0 && st.alpha < 1)) {
        if (st.error.empty())
            st.error = "MCSTAT_SUITE_ALPHA must be in (0, 1)";
        return st;
    }
    if (!env_double("MCSTAT_ESCALATE_FACTOR", &st.escalate, &st.error) ||
        !(st.escalate == 0 || st.escalate >= 1)) {
        if (st.error.empty())
            st.error = "MCSTAT_ESCALATE_FACTOR must be 0 (off) or >= 1";
        return st;
    }
    if (!env_double("MCSTAT_ESCALATE_ALPHA0", &st.alpha0, &st.error) || !(st.alpha0 > 0 && st.alpha0 <= 1)) {
        if (st.error.empty())
            st.error = "MCSTAT_ESCALATE_ALPHA0 must be in (0, 1]";
        return st;
    }
    if (const char *s = std::getenv("MCSTAT_SEED")) {
        char *end = nullptr;
        unsigned long long v = std::strtoull(s, &end, 10);
        if (!*s || *end != '\0' || *s == '-') {
            st.error = std::string("MCSTAT_SEED must be a decimal integer in [0, 2^64), got '") + s + "'";
            return st;
        }
        st.master = v;
    }
    if (const char *s = std::getenv("MCSTAT_SUITE_TESTS")) {
        char *end = nullptr;
        long v = std::strtol(s, &end, 10);
        if (!*s || *end != '\0' || v < 1) {
            st.error = std::string("MCSTAT_SUITE_TESTS must be an integer >= 1, got '") + s + "'";
            return st;
        }
        st.tests = v;
    }
    return st;
}

// ---- the running suite: counters, the current test's checks, the summary ----------
struct Suite {
    Settings settings = read_settings();
    std::mutex mu;
    std::string test;       // the test whose checks are being counted
    unsigned used = 0;      // its checks so far
    unsigned declared = 1;  // MCSTAT_TEST_CHECKS
    bool allow_inconclusive = false; // MCSTAT_ALLOW_INCONCLUSIVE
    unsigned long checks = 0, escalated = 0, failed = 0;
    unsigned long long samples = 0;
    double spent = 0;

    ~Suite()
    {
        if (checks)
            std::fprintf(stderr,
                         "mcstat: %lu statistical check(s); alpha spent %.3g of the suite's %.3g, master seed %llu; "
                         "samples %llu; escalated %lu; failed %lu\n",
                         checks, spent, settings.alpha, (unsigned long long)settings.master, samples, escalated,
                         failed);
    }
};

inline Suite &suite()
{
    static Suite s;
    return s;
}

// The framework's view: the running test's name and the run's test count.
inline std::string current_test_name();
inline long framework_test_count();

struct Plan {
    bool ok = false;
    std::string error, name;
    unsigned index = 0;
    double alpha = 0;
    uint64_t seed = 0;
    bool allow_inconclusive = false;
};

inline Plan next_check(const char *kind)
{
    Suite &s = suite();
    Plan p;
    std::lock_guard<std::mutex> lock(s.mu);
    if (!s.settings.error.empty()) {
        p.error = s.settings.error;
        return p;
    }
    p.name = current_test_name();
    if (p.name != s.test) {
        s.test = p.name;
        s.used = 0;
        s.declared = 1;
        s.allow_inconclusive = false;
    }
    long m = s.settings.tests ? s.settings.tests : framework_test_count();
    if (m < 1) {
        p.error = "the number of statistical tests is unknown: set MCSTAT_SUITE_TESTS";
        return p;
    }
    if (s.used >= s.declared) {
        p.error = p.name + ": check " + std::to_string(s.used + 1) + " (" + kind + ") is one more than the " +
                  std::to_string(s.declared) + " the test declared; declare them first with MCSTAT_TEST_CHECKS(" +
                  std::to_string(s.used + 1) + ") so that the suite's budget is split before they run";
        s.used++;
        return p;
    }
    p.index = s.used++;
    p.alpha = s.settings.alpha / (double)m / (double)s.declared;
    p.seed = check_seed(s.settings.master, p.name, p.index);
    p.allow_inconclusive = s.allow_inconclusive;
    p.ok = true;
    return p;
}

inline void declare_checks(unsigned k)
{
    Suite &s = suite();
    std::lock_guard<std::mutex> lock(s.mu);
    s.test = current_test_name();
    s.used = 0;
    s.declared = k < 1 ? 1 : k;
    s.allow_inconclusive = false;
}

// The running test's data seed under the run's MCSTAT_SEED (MCSTAT_DATA_SEED).
inline uint64_t test_data_seed(const char *label)
{
    return data_seed(suite().settings.master, current_test_name(), label ? label : "");
}

// The running test's renderer checks pass when their verdict is
// inconclusive (a route they needed could not answer) instead of failing.
inline void allow_inconclusive()
{
    Suite &s = suite();
    std::lock_guard<std::mutex> lock(s.mu);
    std::string name = current_test_name();
    if (name != s.test) {
        s.test = name;
        s.used = 0;
        s.declared = 1;
    }
    s.allow_inconclusive = true;
}

struct Outcome {
    bool ok;
    std::string message;
};

inline std::string g(double v)
{
    char b[40];
    std::snprintf(b, sizeof b, "%.3g", v);
    return b;
}

inline Outcome failed(const std::string &m)
{
    std::lock_guard<std::mutex> lock(suite().mu);
    suite().failed++;
    return {false, "mcstat: " + m};
}

// The running test program, as a command that works from any folder.
inline std::string program_path()
{
#if defined(__linux__)
    char buf[4096];
    ssize_t k = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (k > 0) {
        buf[k] = '\0';
        return "'" + std::string(buf) + "'";
    }
#endif
    return "./the-test-program";
}

inline std::string reproduce(const Plan &p)
{
    const Settings &st = suite().settings;
    std::string filter =
#if MCSTAT_TESTING_GTEST
        "--gtest_filter='" + p.name + "'";
#else
        "'" + p.name + "'";
#endif
    return "reproduce: MCSTAT_SUITE_ALPHA=" + g(st.alpha) + " MCSTAT_SEED=" + std::to_string(st.master) +
           " MCSTAT_SUITE_TESTS=" + std::to_string(st.tests ? st.tests : framework_test_count()) + " " +
           program_path() + " " + filter + " (the same seeds and shares)";
}

struct Stage {
    int status = MCSTAT_OK;
    double p = 1;
    std::string text;
    unsigned long long samples = 0;
    std::string inconclusive; // a check's verdict "inconclusive": the routes and why
};

// One statistical check: `run(n, seed, alpha)` is a stage; escalatable ones
// (the check_* forms) may get a second.
inline Outcome decide(const char *kind, size_t n, bool escalatable,
                      const std::function<Stage(size_t, uint64_t, double)> &run)
{
    Plan p = next_check(kind);
    if (!p.ok)
        return failed(p.error);
    const Settings &st = suite().settings;
    std::string lines;
    Stage last;
    int decision;
    int stages = 1;
    if (escalatable && st.escalate > 0) {
        mcstat_escalation d;
        double lo = std::fmin(1.0, std::exp(1.0) * p.alpha); // the smallest band the design allows, doubled
        if (mcstat_escalation_design(p.alpha, 0.5, std::fmax(st.alpha0, lo), &d) != MCSTAT_OK)
            return failed(std::string(kind) + ": no escalation design at alpha " + g(p.alpha));
        last = run(n, p.seed, d.alpha1);
        if (last.status != MCSTAT_OK)
            return failed(std::string(kind) + ": " + mcstat_strerror(last.status) + "\n" + last.text);
        unsigned long long total = last.samples;
        if (mcstat_escalation_decide(&d, last.p, NAN, &decision) != MCSTAT_OK)
            return failed(std::string(kind) + ": stage 1's p-value " + g(last.p) + " cannot be decided on");
        lines += "  stage 1: n " + std::to_string(n) + ", seed " + std::to_string(p.seed) + ": p " + g(last.p) +
                 " (rejects at <= " + g(d.alpha1) + ", passes above " + g(d.alpha0) + ")\n";
        if (decision == MCSTAT_ESCALATION_CONTINUE) {
            double p1 = last.p;
            size_t n2 = (size_t)std::llround(st.escalate * (double)n);
            uint64_t s2 = stage2_seed(p.seed);
            last = run(n2, s2, std::fmin(d.c / p1, 0.5));
            if (last.status != MCSTAT_OK)
                return failed(std::string(kind) + ": " + mcstat_strerror(last.status) + "\n" + last.text);
            total += last.samples;
            if (mcstat_escalation_decide(&d, p1, last.p, &decision) != MCSTAT_OK)
                return failed(std::string(kind) + ": stage 2's p-value " + g(last.p) + " cannot be decided on");
            stages = 2;
            lines += "  stage 2 (escalated): n " + std::to_string(n2) + ", seed " + std::to_string(s2) + ": p " +
                     g(last.p) + "; p1 p2 = " + g(p1 * last.p) +
                     (decision == MCSTAT_ESCALATION_REJECT ? " <= c = " : " > c = ") + g(d.c) + "\n";
        }
        last.samples = total;
    } else {
        last = run(n, p.seed, p.alpha);
        if (last.status != MCSTAT_OK)
            return failed(std::string(kind) + ": " + mcstat_strerror(last.status) + "\n" + last.text);
        decision = last.p <= p.alpha ? MCSTAT_ESCALATION_REJECT : MCSTAT_ESCALATION_PASS;
        lines += "  one stage: n " + std::to_string(n) + ", seed " + std::to_string(p.seed) + ": p " + g(last.p) +
                 " (rejects at <= " + g(p.alpha) + ")\n";
    }
    {
        std::lock_guard<std::mutex> lock(suite().mu);
        Suite &s = suite();
        s.checks++;
        s.spent += p.alpha;
        s.samples += last.samples;
        s.escalated += stages > 1;
    }
    if (decision != MCSTAT_ESCALATION_REJECT && !last.inconclusive.empty() && !p.allow_inconclusive)
        return failed(std::string(kind) + " inconclusive at alpha " + g(p.alpha) + ": no route rejected, but " +
                      last.inconclusive + " (MCSTAT_ALLOW_INCONCLUSIVE() lets the test pass so)\n" + lines +
                      last.text + "\n" + reproduce(p));
    if (decision != MCSTAT_ESCALATION_REJECT)
        return {true, std::string(kind) + " passed at alpha " + g(p.alpha) + " (seed " + std::to_string(p.seed) + ")"};
    return failed(std::string(kind) + " rejected at alpha " + g(p.alpha) + " (this check's share of the suite's " +
                  g(st.alpha) + ")\n" + lines + last.text + "\n" + reproduce(p));
}

// ---- the checks ------------------------------------------------------------------
inline std::string check_text(const mcstat_check_report &r)
{
    size_t len = 0;
    (void)mcstat_check_format(&r, nullptr, 0, &len); // MCSTAT_EBUFSIZE, and the length
    std::string t(len + 1, '\0');
    int st = mcstat_check_format(&r, &t[0], t.size(), nullptr);
    if (st != MCSTAT_OK)
        return std::string("(the report could not be formatted: ") + mcstat_strerror(st) + ")";
    t.resize(len);
    return t;
}

// kind: MCSTAT_CHECK_KIND_*; wi for BSDFs and phase functions, sigma_ref for media
inline Outcome check(int kind, const mcstat_check_model &model, const double *wi, double sigma_ref, size_t n)
{
    const char *name = kind == MCSTAT_CHECK_KIND_BSDF      ? "check_bsdf"
                       : kind == MCSTAT_CHECK_KIND_EMITTER ? "check_emitter"
                       : kind == MCSTAT_CHECK_KIND_PHASE   ? "check_phase"
                       : kind == MCSTAT_CHECK_KIND_MEDIUM  ? "check_medium"
                                                           : "check_warp";
    return decide(name, n, true, [&](size_t k, uint64_t seed, double a) {
        Stage st;
        mcstat_check_report r;
        switch (kind) {
        case MCSTAT_CHECK_KIND_BSDF: st.status = mcstat_check_bsdf(&model, wi, k, seed, a, nullptr, nullptr, 0, &r); break;
        case MCSTAT_CHECK_KIND_EMITTER:
            st.status = mcstat_check_emitter(&model, k, seed, a, nullptr, nullptr, 0, &r);
            break;
        case MCSTAT_CHECK_KIND_PHASE: st.status = mcstat_check_phase(&model, wi, k, seed, a, nullptr, nullptr, 0, &r); break;
        case MCSTAT_CHECK_KIND_MEDIUM:
            st.status = mcstat_check_medium(&model, sigma_ref, k, seed, a, nullptr, nullptr, 0, &r);
            break;
        default: st.status = mcstat_check_warp(&model, k, seed, a, nullptr, nullptr, 0, &r); break;
        }
        if (st.status == MCSTAT_ECALLBACK) {
            st.text = r.message;
            return st;
        }
        if (st.status != MCSTAT_OK)
            return st;
        st.p = r.p_value;
        st.text = check_text(r);
        st.samples = r.n + r.n_pilot + r.n_eval;
        int verdict;
        uint32_t open = 0;
        if (mcstat_check_verdict(&r, &verdict, &open) == MCSTAT_OK && verdict == MCSTAT_CHECK_INCONCLUSIVE)
            for (int i = 0; i < MCSTAT_CHECK_ROUTE_COUNT; i++)
                if (open & (1u << i))
                    st.inconclusive += std::string(st.inconclusive.empty() ? "" : "; ") + mcstat_check_route_name(i) +
                                       " could not answer: " + mcstat_check_why_text(r.route[i].why);
        return st;
    });
}

inline std::string result_text(const mcstat_result &r)
{
    size_t len = 0;
    (void)mcstat_result_format(&r, nullptr, nullptr, nullptr, 0, &len); // MCSTAT_EBUFSIZE, and the length
    std::string t(len + 1, '\0');
    int st = mcstat_result_format(&r, nullptr, nullptr, &t[0], t.size(), nullptr);
    if (st != MCSTAT_OK)
        return std::string("(the result could not be formatted: ") + mcstat_strerror(st) + ")";
    t.resize(len);
    return t;
}

inline Outcome unbiased(const double *x, size_t n, double expected)
{
    return decide("unbiased", n, false, [&](size_t, uint64_t, double a) {
        Stage st;
        mcstat_result r;
        st.status = mcstat_t_test_1(x, n, expected, MCSTAT_TWO_SIDED, a, &r);
        if (st.status == MCSTAT_OK) {
            st.p = r.p_value;
            st.text = result_text(r);
            st.samples = n;
        }
        return st;
    });
}

inline Outcome same_distribution(const double *x, size_t nx, const double *y, size_t ny)
{
    return decide("same_distribution", nx, false, [&](size_t, uint64_t, double a) {
        Stage st;
        mcstat_ks_options o;
        mcstat_ks_options_init(&o);
        o.weight = MCSTAT_KS_WEIGHT_NONE;
        mcstat_result r;
        st.status = mcstat_ks_test_2(x, nx, y, ny, MCSTAT_TWO_SIDED, a, &o, &r);
        if (st.status == MCSTAT_OK) {
            st.p = r.p_value;
            st.text = result_text(r);
            st.samples = nx + ny;
        }
        return st;
    });
}

// ---- the frameworks ----------------------------------------------------------------
#if MCSTAT_TESTING_GTEST
inline std::string current_test_name()
{
    const ::testing::TestInfo *t = ::testing::UnitTest::GetInstance()->current_test_info();
    return t ? std::string(t->test_suite_name()) + "." + t->name() : std::string("(no test)");
}
inline long framework_test_count() { return ::testing::UnitTest::GetInstance()->test_to_run_count(); }
#  define MCSTAT_TESTING_FAIL_(o, fatal)                                                                       \
    do {                                                                                                       \
        ::mcstat_testing::Outcome mcstat_o_ = (o);                                                             \
        if (!mcstat_o_.ok) {                                                                                   \
            if (fatal)                                                                                         \
                GTEST_FATAL_FAILURE_(mcstat_o_.message.c_str());                                               \
            else                                                                                               \
                ADD_FAILURE() << mcstat_o_.message;                                                            \
        }                                                                                                      \
    } while (0)
#else
inline std::string current_test_name() { return Catch::getResultCapture().getCurrentTestName(); }
inline long framework_test_count()
{
    Catch::IConfigPtr cfg = Catch::getCurrentContext().getConfig();
    if (!cfg)
        return 0;
    return (long)Catch::filterTests(Catch::getAllTestCasesSorted(*cfg), cfg->testSpec(), *cfg).size();
}
#  define MCSTAT_TESTING_FAIL_(o, fatal)                                                                       \
    do {                                                                                                       \
        ::mcstat_testing::Outcome mcstat_o_ = (o);                                                             \
        if (!mcstat_o_.ok) {                                                                                   \
            if (fatal)                                                                                         \
                FAIL(mcstat_o_.message);                                                                       \
            else                                                                                               \
                FAIL_CHECK(mcstat_o_.message);                                                                 \
        } else {                                                                                               \
            SUCCEED(mcstat_o_.message); /* an assertion, so that -w NoAssertions sees the check */             \
        }                                                                                                      \
    } while (0)
#endif

} // namespace mcstat_testing

#define MCSTAT_TEST_CHECKS(k) ::mcstat_testing::declare_checks(k)
#define MCSTAT_ALLOW_INCONCLUSIVE() ::mcstat_testing::allow_inconclusive()
#define MCSTAT_DATA_SEED(label) ::mcstat_testing::test_data_seed(label)

#define MCSTAT_EXPECT_BSDF_CONSISTENT(model, wi, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_BSDF, (model), (wi), 0.0, (n)), false)
#define MCSTAT_ASSERT_BSDF_CONSISTENT(model, wi, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_BSDF, (model), (wi), 0.0, (n)), true)
#define MCSTAT_EXPECT_EMITTER_CONSISTENT(model, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_EMITTER, (model), nullptr, 0.0, (n)), false)
#define MCSTAT_ASSERT_EMITTER_CONSISTENT(model, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_EMITTER, (model), nullptr, 0.0, (n)), true)
#define MCSTAT_EXPECT_WARP_CONSISTENT(model, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_WARP, (model), nullptr, 0.0, (n)), false)
#define MCSTAT_ASSERT_WARP_CONSISTENT(model, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_WARP, (model), nullptr, 0.0, (n)), true)
#define MCSTAT_EXPECT_PHASE_CONSISTENT(model, wi, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_PHASE, (model), (wi), 0.0, (n)), false)
#define MCSTAT_ASSERT_PHASE_CONSISTENT(model, wi, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_PHASE, (model), (wi), 0.0, (n)), true)
#define MCSTAT_EXPECT_MEDIUM_CONSISTENT(model, sigma_ref, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_MEDIUM, (model), nullptr, (sigma_ref), (n)), false)
#define MCSTAT_ASSERT_MEDIUM_CONSISTENT(model, sigma_ref, n) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::check(MCSTAT_CHECK_KIND_MEDIUM, (model), nullptr, (sigma_ref), (n)), true)
#define MCSTAT_EXPECT_UNBIASED(values, count, expected) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::unbiased((values), (count), (expected)), false)
#define MCSTAT_ASSERT_UNBIASED(values, count, expected) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::unbiased((values), (count), (expected)), true)
#define MCSTAT_EXPECT_SAME_DISTRIBUTION(x, nx, y, ny) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::same_distribution((x), (nx), (y), (ny)), false)
#define MCSTAT_ASSERT_SAME_DISTRIBUTION(x, nx, y, ny) \
    MCSTAT_TESTING_FAIL_(::mcstat_testing::same_distribution((x), (nx), (y), (ny)), true)

#endif
