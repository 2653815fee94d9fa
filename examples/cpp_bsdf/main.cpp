// main.cpp - mcstat's renderer check on a C++ BSDF (ggx.hpp): the correct
// GGX conductor passes, and each of four planted ~10% bugs is caught.
//
// The BSDF is handed to mcstat_check_bsdf through the C callback API, with
// the BSDF object as the user pointer (ggx::Callbacks).  For each case the
// program prints mcstat's report and a summary line.  Which route should
// catch each bug:
//   sampler  CELLS (the directions drawn do not follow pdf());
//   pdf      PDF_VALUE (pdf() disagrees with the pdf sample() reports);
//   eval     WEIGHT (the weight is not eval / pdf);
//   weight   WEIGHT;
// and an eval() that throws stops the check with MCSTAT_ECALLBACK naming
// eval, the exception rethrown by the caller after mcstat has returned.
// A regression demo with a fixed seed, not a calibration claim: the false
// rejection rate of the check is measured in tests/python and bench/.
//
// usage: mcstat_cpp_bsdf [--n N] [--seed S] [--quiet]
// Exit status 0 when the correct BSDF (float and double) passes and every
// bug is rejected by its route; 1 otherwise; 2 for bad usage.
#include "ggx.hpp"

#include "mcstat.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

namespace {

constexpr int EXPECT_PASS = -1, EXPECT_ECALLBACK = -2;

struct Case {
    const char *real;
    ggx::Bug bug;
    int route; // the route that must reject, or EXPECT_PASS, EXPECT_ECALLBACK
};

struct Outcome {
    int status;
    mcstat_check_report report;
    std::string error; // the exception a callback caught, rethrown here
};

template <class Real> Outcome run_case(ggx::Bug bug, const double wi[3], size_t n, uint64_t seed, double alpha)
{
    // a rough anisotropic conductor (F0 0.8: a gold-like reflectance)
    ggx::Ggx<Real> bsdf(Real(0.3), Real(0.15), Real(0.8), bug);
    ggx::Callbacks<ggx::Ggx<Real>> cb{&bsdf};
    mcstat_check_model model = cb.model();
    mcstat_check_options opt;
    mcstat_check_options_init(&opt);
    Outcome o{};
    o.status = mcstat_check_bsdf(&model, wi, n, seed, alpha, &opt, nullptr, 0, &o.report);
    // the exception a callback kept crosses no C frame: rethrow it here
    if (cb.error) {
        try {
            std::rethrow_exception(cb.error);
        } catch (const std::exception &e) {
            o.error = e.what();
        } catch (...) {
            o.error = "an unknown exception";
        }
    }
    return o;
}

std::string format(const mcstat_check_report &r)
{
    size_t len = 0;
    std::vector<char> buf(4096);
    int st = mcstat_check_format(&r, buf.data(), buf.size(), &len);
    if (st == MCSTAT_EBUFSIZE) {
        buf.resize(len + 1);
        st = mcstat_check_format(&r, buf.data(), buf.size(), &len);
    }
    if (st != MCSTAT_OK)
        return std::string("(mcstat_check_format: ") + mcstat_strerror(st) + ")";
    return std::string(buf.data());
}

std::string rejecting_routes(const mcstat_check_report &r)
{
    std::string s;
    for (int k = 0; k < MCSTAT_CHECK_ROUTE_COUNT; k++)
        if (r.route[k].state == MCSTAT_CHECK_STATE_RAN && r.route[k].reject) {
            if (!s.empty())
                s += ",";
            s += mcstat_check_route_name(k);
        }
    return s.empty() ? "none" : s;
}

int usage()
{
    std::fprintf(stderr, "usage: mcstat_cpp_bsdf [--n N] [--seed S] [--quiet]\n");
    return 2;
}

} // namespace

int main(int argc, char **argv)
{
    size_t n = 100000;
    uint64_t seed = 20261203;
    bool quiet = false;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "--n") && i + 1 < argc) {
            char *end;
            double v = std::strtod(argv[++i], &end);
            if (*end || !(v >= 1000 && v <= 1e9))
                return usage();
            n = size_t(v);
        } else if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) {
            seed = std::strtoull(argv[++i], nullptr, 10);
        } else if (!std::strcmp(argv[i], "--quiet")) {
            quiet = true;
        } else {
            return usage();
        }
    }
    const double alpha = 0.01;
    // light arriving 50 degrees off the normal, between the roughness axes
    const double theta = 50 * ggx::pi / 180, phi = 30 * ggx::pi / 180;
    const double wi[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};

    const Case cases[] = {
        {"float", ggx::Bug::None, EXPECT_PASS},
        {"double", ggx::Bug::None, EXPECT_PASS},
        {"float", ggx::Bug::Sampler, MCSTAT_CHECK_ROUTE_CELLS},
        {"float", ggx::Bug::Pdf, MCSTAT_CHECK_ROUTE_PDF_VALUE},
        {"float", ggx::Bug::Eval, MCSTAT_CHECK_ROUTE_WEIGHT},
        {"float", ggx::Bug::Weight, MCSTAT_CHECK_ROUTE_WEIGHT},
        {"float", ggx::Bug::Throws, EXPECT_ECALLBACK},
    };
    int failures = 0;
    std::vector<std::string> summary;
    for (const Case &c : cases) {
        bool dbl = !std::strcmp(c.real, "double");
        Outcome o = dbl ? run_case<double>(c.bug, wi, n, seed, alpha) : run_case<float>(c.bug, wi, n, seed, alpha);
        char line[512];
        bool ok;
        if (c.route == EXPECT_ECALLBACK || o.status != MCSTAT_OK) {
            // the check stops at the callback's failure and names it
            ok = c.route == EXPECT_ECALLBACK && o.status == MCSTAT_ECALLBACK && !o.error.empty() &&
                 std::strstr(o.report.message, "eval") != nullptr;
            std::snprintf(line, sizeof line, "%-6s %-40s status %d, %s (caught: %s)  %s", c.real,
                          ggx::bug_name(c.bug), o.status,
                          o.status == MCSTAT_ECALLBACK ? o.report.message : mcstat_strerror(o.status),
                          o.error.empty() ? "nothing" : o.error.c_str(), ok ? "ok" : "WRONG");
        } else {
            const mcstat_check_report &r = o.report;
            bool route_rejects = c.route >= 0 && r.route[c.route].state == MCSTAT_CHECK_STATE_RAN && r.route[c.route].reject;
            ok = c.route == EXPECT_PASS ? !r.reject : (r.reject && route_rejects);
            std::snprintf(line, sizeof line, "%-6s %-40s %s (p = %.3g; rejecting: %s; %s)  %s", c.real,
                          ggx::bug_name(c.bug), r.reject ? "REJECTED" : "passed", r.p_value,
                          rejecting_routes(r).c_str(),
                          c.route == EXPECT_PASS ? "expected to pass"
                                      : (std::string("expected: ") + mcstat_check_route_name(c.route)).c_str(),
                          ok ? "ok" : "WRONG");
            if (!quiet)
                std::printf("==== %s, %s ====\n%s\n", c.real, ggx::bug_name(c.bug), format(r).c_str());
        }
        if (!ok)
            failures++;
        summary.push_back(line);
        std::printf("%s\n", line);
        std::fflush(stdout);
    }
    std::printf("\nsummary (n = %zu, seed = %llu, alpha = %g):\n", n, (unsigned long long)seed, alpha);
    for (const std::string &s : summary)
        std::printf("  %s\n", s.c_str());
    std::printf("%s\n", failures ? "FAILED" : "all cases as expected");
    return failures ? 1 : 0;
}
