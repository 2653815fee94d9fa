// result.cpp - TestResult: one test's mcstat_result, read through properties.
//
// Creating it copies the 224-byte struct and nothing else; tuples, strings
// and the R-style text are made only when asked for, so a call that wants
// only `pvalue` pays for nothing more.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace mcs {

namespace {

bool is_ks(const mcstat_result &r) { return r.test == MCSTAT_TEST_KS_2; }

// The test's name as the first line of the R-style block has it.
std::string method_name(const mcstat_result &r)
{
    switch (r.test) {
    case MCSTAT_TEST_T_1: return "One Sample t-test";
    case MCSTAT_TEST_T_2: return "Welch Two Sample t-test";
    case MCSTAT_TEST_T_2_POOLED: return "Two Sample t-test";
    case MCSTAT_TEST_T_PAIRED: return "Paired t-test";
    case MCSTAT_TEST_VAR_1: return "One Sample Chi-squared test on variance";
    case MCSTAT_TEST_VAR_2: return "F test to compare two variances";
    case MCSTAT_TEST_CHISQ_GOF: return "Chi-squared test for given probabilities";
    case MCSTAT_TEST_KS_2:
    case MCSTAT_TEST_SEQ_MEAN_1:
    case MCSTAT_TEST_SEQ_MEAN_2:
    case MCSTAT_TEST_SEQ_VAR_1:
    case MCSTAT_TEST_SEQ_VAR_2: {
        // libmcstat's formatter owns the wording: take its title line
        char buf[256];
        size_t len = 0;
        int st = mcstat_result_format(&r, "x", "y", buf, sizeof buf, &len);
        if (st != MCSTAT_OK && st != MCSTAT_EBUFSIZE)
            return is_ks(r) ? "two-sample Kolmogorov-Smirnov test" : "sequential test";
        std::string t(buf);
        size_t a = t.find('\t'), b = t.find('\n', a == std::string::npos ? 0 : a);
        return a == std::string::npos ? t : t.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
    }
    case MCSTAT_TEST_BINOM: return "Exact binomial test";
    case MCSTAT_TEST_EFFICIENCY: return "Efficiency ratio test (delta method)";
    default: return "unknown";
    }
}

const char *pvalue_method_name(int method)
{
    switch (method) {
    case MCSTAT_METHOD_ANALYTIC: return "analytic";
    case MCSTAT_METHOD_EXACT: return "exact";
    case MCSTAT_METHOD_SIMULATE: return "simulate";
    case MCSTAT_METHOD_ASYMPTOTIC: return "asymptotic";
    default: return "unknown";
    }
}

bool two_estimates(const mcstat_result &r)
{
    return r.test == MCSTAT_TEST_T_2 || r.test == MCSTAT_TEST_T_2_POOLED || r.test == MCSTAT_TEST_SEQ_MEAN_2;
}
bool is_seq(const mcstat_result &r) { return r.test >= MCSTAT_TEST_SEQ_MEAN_1 && r.test <= MCSTAT_TEST_SEQ_VAR_2; }
bool two_df(const mcstat_result &r) { return r.test == MCSTAT_TEST_VAR_2; }
// (the paired test counts pairs: one number)
bool two_samples(const mcstat_result &r)
{
    return r.test == MCSTAT_TEST_T_2 || r.test == MCSTAT_TEST_T_2_POOLED || r.test == MCSTAT_TEST_VAR_2 ||
           r.test == MCSTAT_TEST_KS_2 || r.test == MCSTAT_TEST_SEQ_MEAN_2 || r.test == MCSTAT_TEST_SEQ_VAR_2 ||
           r.test == MCSTAT_TEST_EFFICIENCY;
}

// nan_policy="propagate" on data with NaN: every field NaN (tests.cpp).
bool is_nan_result(const mcstat_result &r) { return std::isnan(r.p_value); }

double log_pvalue(const mcstat_result &r)
{
    double lp;
    return mcstat_result_log_p_value(&r, &lp) == MCSTAT_OK ? lp : NAN;
}

py::object confidence_interval(const mcstat_result &r, PyObject *level_obj)
{
    static py::object make = py::module_::import("mcstat._result").attr("ConfidenceInterval");
    double level = get_double(level_obj, "confidence_level");
    if (!(level > 0.0 && level < 1.0))
        throw_invalid("confidence_level must be in (0, 1), got " + repr(level_obj));
    if (is_nan_result(r))
        return make(NAN, NAN);
    if (r.test == MCSTAT_TEST_KS_2 || r.test == MCSTAT_TEST_CHISQ_GOF)
        throw_invalid(std::string("the ") + (r.test == MCSTAT_TEST_KS_2 ? "Kolmogorov-Smirnov" : "chi-squared goodness-of-fit") +
                      " test has no confidence interval (it estimates no parameter)");
    double ci[2];
    int st = mcstat_result_conf_int(&r, level, ci);
    if (st)
        throw_status(st, "confidence_interval");
    return make(ci[0], ci[1]);
}

std::string format(const mcstat_result &r, const char *x_name, const char *y_name)
{
    char buf[1024];
    size_t len = 0;
    std::string text;
    int st = mcstat_result_format(&r, x_name, y_name, buf, sizeof buf, &len);
    if (st == MCSTAT_OK) {
        text.assign(buf, len);
    } else {
        if (st != MCSTAT_EBUFSIZE)
            throw_status(st, "formatting a result");
        std::vector<char> big(len + 1);
        st = mcstat_result_format(&r, x_name, y_name, big.data(), big.size(), &len);
        if (st)
            throw_status(st, "formatting a result");
        text.assign(big.data(), len);
    }
    if (is_nan_result(r)) { // no decision was made: say so instead of "equal"
        size_t d = text.find("decision at alpha");
        size_t c = d == std::string::npos ? d : text.find(": ", d);
        size_t e = c == std::string::npos ? c : text.find('\n', c);
        if (e != std::string::npos)
            text.replace(c + 2, e - c - 2, "none (NaN in the data, nan_policy='propagate')");
    }
    return text;
}

py::object pair(double a, double b) { return py::make_tuple(a, b); }

std::string short_num(double v)
{
    char b[40];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

} // namespace

py::object make_result(const mcstat_result &r)
{
    Result s;
    s.r = r;
    return py::cast(s);
}

py::object make_result(const Result &r)
{
    return py::cast(r);
}

void register_result(py::module_ &mod)
{
    py::class_<Result>(mod, "TestResult", R"doc(
The outcome of one hypothesis test (returned by `t_test`, `var_test` and
`ks_test`).

Attributes
----------
statistic : float
    t, X-squared or F; for `ks_test` D = ``sup |F - G|`` (weight "none") or
    Canner's D2 (weight "canner"), one-sided versions for "less" and
    "greater"; for `binom_test` the number of successes.
df : float or tuple of float
    Degrees of freedom; ``(num, denom)`` for the F test.
pvalue : float
    p-value for `alternative`.
log_pvalue : float
    Its natural logarithm, computed by libmcstat from the statistic's log
    tail (`binom_test`: directly), so it stays finite where `pvalue`
    underflows to 0 (t, chi-squared, F, TOST, asymptotic K-S; an exact or
    simulated K-S p-value is its log).
conf_int : tuple of float
    ``(low, high)`` confidence interval at level ``1 - alpha`` for the
    tested parameter (mean, difference in means, variance or ratio of
    variances); one-sided alternatives have an infinite end.  NaN when the
    test ran with ``intervals=False``.
estimate : float or tuple of float
    Mean of x; ``(mean of x, mean of y)`` for Welch; variance of x;
    ratio of variances.
null_value : float
    mu, sigma2 or ratio under H0.
alternative : str
    ``"two-sided"``, ``"less"`` or ``"greater"``.
method : str
    The test's name as R prints it, e.g. ``"Welch Two Sample t-test"``
    or ``"Monte-Carlo two-sample Kolmogorov-Smirnov test with Canner's
    weight"``.
pvalue_method : str
    How the p-value was obtained: ``"analytic"`` (t, chi-squared, F),
    ``"exact"``, ``"simulate"`` or ``"asymptotic"`` (K-S; Pearson's
    X-squared in `chisq_gof`).
alpha : float
    Significance level used for `reject`, `decision`, `critical_values`
    and `conf_int`.
reject : bool
    H0 rejected at level `alpha` against `alternative`.
decision : str
    The paper's three-way outcome: ``"less"``, ``"equal"`` or ``"greater"``.
critical_values : tuple of float
    Reject when `statistic` is below the first or above the second (K-S:
    ``(-inf, c)``; NaN when the test ran with ``critical=False``).
critical_se : float
    Monte Carlo standard error of the upper critical value when it was
    simulated (K-S "simulate"), else 0.0.
pvalue_se : float
    Monte Carlo standard error of `pvalue` when it was simulated, else 0.0.
n_sim : int
    Replicates simulated (0 unless the p-value was simulated).
seed : int or None
    The seed the simulation used (None unless the p-value was
    simulated): passing it back as ``seed=`` reproduces the result.
weight : str or None
    K-S: ``"none"`` or ``"canner"``; None for the other tests.
cells : int or None
    `chisq_gof`: the number of cells after pooling; None for the other
    tests.
std_error : float
    Standard error of the estimate (t tests; `efficiency_test`: of the
    log of the ratio; NaN otherwise).
efficiency : dict or None
    `efficiency_test`: the factors of the ratio and their errors,
    ``var_ratio`` (s_y^2 / s_x^2), ``time_ratio`` (mean time of y / of
    x), ``se_log_var_x``, ``se_log_var_y``, ``se_log_time_x``,
    ``se_log_time_y`` (delta-method standard errors of the four logs),
    ``batches_x``, ``batches_y`` (timed batches); None for the other tests.
nobs : int or tuple of int
    Sample size(s) used (after NaNs were omitted).

Notes
-----
A TestResult unpacks like SciPy's results: ``t, p = mcstat.t_test(x, y)``
(``result[0]`` is `statistic`, ``result[1]`` `pvalue`).

``str(result)`` is the R-style block (R's ``print.htest`` layout plus a
decision line) with data names "x" and "y"; ``result.format(x_name,
y_name)`` names them.
)doc")
        .def_property_readonly("statistic", [](const Result &s) { return s.r.statistic; })
        .def_property_readonly("df", [](const Result &s) -> py::object {
            return two_df(s.r) ? pair(s.r.df[0], s.r.df[1]) : py::float_(s.r.df[0]);
        })
        .def_property_readonly("pvalue", [](const Result &s) { return s.r.p_value; })
        // libmcstat's, from the statistic's log tail: finite where pvalue underflows
        .def_property_readonly("log_pvalue", [](const Result &s) { return log_pvalue(s.r); })
        .def_property_readonly("conf_int", [](const Result &s) { return pair(s.r.conf_int[0], s.r.conf_int[1]); })
        .def_property_readonly("estimate", [](const Result &s) -> py::object {
            return two_estimates(s.r) ? pair(s.r.estimate[0], s.r.estimate[1]) : py::float_(s.r.estimate[0]);
        })
        .def_property_readonly("null_value", [](const Result &s) { return s.r.null_value; })
        .def_property_readonly("alternative",
                               [](const Result &s) { return py::str(mcstat_alternative_name(s.r.alternative)); })
        .def_property_readonly("method", [](const Result &s) { return py::str(method_name(s.r)); })
        .def_property_readonly("pvalue_method", [](const Result &s) { return py::str(pvalue_method_name(s.r.method)); })
        .def_property_readonly("critical_se",
                               [](const Result &s) { return is_ks(s.r) ? s.r.ks_critical_se : 0.0; })
        .def_property_readonly("n_sim", [](const Result &s) {
            return is_ks(s.r) ? static_cast<int64_t>(s.r.ks_n_sim) : int64_t{0};
        })
        .def_property_readonly("seed", [](const Result &s) -> py::object {
            return s.has_seed ? py::object(py::int_(s.seed)) : py::object(py::none());
        })
        .def_property_readonly("weight", [](const Result &s) -> py::object {
            if (!is_ks(s.r))
                return py::none();
            return py::str(s.r.ks_weight == MCSTAT_KS_WEIGHT_CANNER ? "canner" : "none");
        })
        // chi-squared goodness of fit: cells after pooling, None for other tests
        .def_property_readonly("cells", [](const Result &s) -> py::object {
            if (s.r.test != MCSTAT_TEST_CHISQ_GOF)
                return py::none();
            return py::int_(s.r.chisq_cells);
        })
        .def_property_readonly("efficiency", [](const Result &s) -> py::object {
            if (s.r.test != MCSTAT_TEST_EFFICIENCY)
                return py::none();
            py::dict d;
            d["var_ratio"] = s.r.eff_var_ratio;
            d["time_ratio"] = s.r.eff_time_ratio;
            d["se_log_var_x"] = s.r.eff_se_log_var_x;
            d["se_log_var_y"] = s.r.eff_se_log_var_y;
            d["se_log_time_x"] = s.r.eff_se_log_time_x;
            d["se_log_time_y"] = s.r.eff_se_log_time_y;
            d["batches_x"] = s.r.eff_batches_x;
            d["batches_y"] = s.r.eff_batches_y;
            return std::move(d);
        })
        .def_property_readonly("alpha", [](const Result &s) { return s.r.alpha; })
        .def_property_readonly("reject", [](const Result &s) { return s.r.reject != 0; })
        .def_property_readonly("decision", [](const Result &s) {
            // a sequential test that has not decided yet is neither "equal" nor anything else
            if (is_seq(s.r) && s.r.seq_state != MCSTAT_SEQ_DECIDED)
                return py::str("continue");
            return py::str(is_nan_result(s.r) ? "" : mcstat_decision_name(s.r.decision));
        })
        .def_property_readonly("critical_values",
                               [](const Result &s) { return pair(s.r.critical[0], s.r.critical[1]); })
        .def_property_readonly("pvalue_se", [](const Result &s) { return s.r.p_value_se; })
        .def_property_readonly("std_error", [](const Result &s) { return s.r.std_error; })
        .def_property_readonly("nobs", [](const Result &s) -> py::object {
            if (two_samples(s.r))
                return py::make_tuple(s.r.n[0], s.r.n[1]);
            return py::int_(s.r.n[0]);
        })
        .def(
            "confidence_interval",
            [](const Result &s, py::handle level) { return confidence_interval(s.r, level.ptr()); },
            py::arg("confidence_level") = 0.95, R"doc(
The confidence interval for the tested parameter at `confidence_level`
(default 0.95, as SciPy's; `conf_int` is the one at ``1 - alpha``), for the
test's alternative (one-sided ones keep an infinite end).  Returns a
named tuple ``ConfidenceInterval(low, high)`` like SciPy's.  t tests:
estimate -+ t quantile * std_error; variance and F tests from their
statistics; TOST: the two-sided t interval; binomial: Clopper-Pearson.
NaN for a result of ``nan_policy="propagate"``.

Raises
------
InvalidArgumentError
    confidence_level outside (0, 1); the K-S and chi-squared
    goodness-of-fit tests (no parameter, no interval).
)doc")
        // unpacks like SciPy's results: t, p = mcstat.t_test(x, y)
        .def("__len__", [](const Result &) { return 2; })
        .def("__iter__", [](const Result &s) {
            return py::iter(py::make_tuple(s.r.statistic, s.r.p_value));
        })
        .def("__getitem__", [](const Result &s, py::ssize_t i) {
            if (i < -2 || i > 1)
                throw py::index_error("TestResult index out of range (it unpacks as statistic, pvalue)");
            return (i == 0 || i == -2) ? s.r.statistic : s.r.p_value;
        })
        .def(
            "format",
            [](const Result &s, const std::string &x_name, const std::string &y_name) {
                return format(s.r, x_name.c_str(), y_name.c_str());
            },
            py::arg("x_name") = "x", py::arg("y_name") = "y",
            "The R-style text block with the data named `x_name` (and `y_name`).")
        .def("__str__", [](const Result &s) { return format(s.r, nullptr, nullptr); })
        .def("__repr__", [](const Result &s) {
            const mcstat_result &r = s.r;
            std::string df = short_num(r.df[0]);
            if (two_df(r))
                df = "(" + df + ", " + short_num(r.df[1]) + ")";
            if (is_ks(r)) {
                std::string t = std::string("<TestResult ") + method_name(r) + ": statistic=" + short_num(r.statistic) +
                                ", pvalue=" + short_num(r.p_value);
                if (r.method == MCSTAT_METHOD_SIMULATE)
                    t += " (se " + short_num(r.p_value_se) + ", n_sim=" + short_num(r.ks_n_sim) + ")";
                return t + ", alternative='" + mcstat_alternative_name(r.alternative) + "', decision='" +
                       (is_nan_result(r) ? "" : mcstat_decision_name(r.decision)) + "' at alpha=" + short_num(r.alpha) +
                       ">";
            }
            return std::string("<TestResult ") + method_name(r) + ": statistic=" + short_num(r.statistic) +
                   ", df=" + df + ", pvalue=" + short_num(r.p_value) + ", alternative='" +
                   mcstat_alternative_name(r.alternative) + "', decision='" +
                   (is_nan_result(r) ? "" : mcstat_decision_name(r.decision)) + "' at alpha=" + short_num(r.alpha) +
                   ">";
        })
        .def("__reduce__", [](py::object self) {
            const Result &s = self.cast<const Result &>();
            py::object seed = s.has_seed ? py::object(py::int_(s.seed)) : py::object(py::none());
            return py::make_tuple(py::module_::import("mcstat._core").attr("_result_from_bytes"),
                                  py::make_tuple(py::bytes(reinterpret_cast<const char *>(&s.r), sizeof s.r), seed));
        })
        .def("_raw", [](const Result &s) {
            return py::bytes(reinterpret_cast<const char *>(&s.r), sizeof s.r);
        }, "The mcstat_result struct's bytes (for tests).");
}

void register_result_helpers(py::module_ &mod)
{
    // One row of a BatchResult as a TestResult (mcstat._result.BatchResult.__getitem__).
    mod.def("_result_from_fields", [](const std::string &kind, const std::string &alternative, double alpha,
                                      double null_value, py::dict f) {
        mcstat_result r;
        std::memset(&r, 0, sizeof r);
        r.test = kind == "t_1" ? MCSTAT_TEST_T_1 : kind == "t_2" ? MCSTAT_TEST_T_2
               : kind == "t_2_pooled" ? MCSTAT_TEST_T_2_POOLED : kind == "t_paired" ? MCSTAT_TEST_T_PAIRED
               : kind == "var_1" ? MCSTAT_TEST_VAR_1 : MCSTAT_TEST_VAR_2;
        r.method = MCSTAT_METHOD_ANALYTIC;
        if (mcstat_alternative_parse(alternative.c_str(), &r.alternative))
            throw_invalid("alternative");
        r.alpha = alpha;
        r.null_value = null_value;
        auto vec = [&](const char *k) {
            py::array_t<double, py::array::forcecast> a(f[k]);
            return std::vector<double>(a.data(), a.data() + a.size());
        };
        std::vector<double> df = vec("df"), ci = vec("conf_int"), est = vec("estimate"), cr = vec("critical_values");
        r.statistic = f["statistic"].cast<double>();
        r.df[0] = df[0];
        r.df[1] = df.size() > 1 ? df[1] : NAN;
        r.p_value = f["pvalue"].cast<double>();
        r.p_value_se = 0.0;
        r.conf_int[0] = ci[0];
        r.conf_int[1] = ci[1];
        r.estimate[0] = est[0];
        r.estimate[1] = est.size() > 1 ? est[1] : NAN;
        r.critical[0] = cr[0];
        r.critical[1] = cr[1];
        r.std_error = f["std_error"].cast<double>();
        r.reject = f["reject"].cast<bool>() ? 1 : 0;
        r.decision = f["decision_code"].cast<int>();
        py::array_t<int64_t, py::array::forcecast> n(f["nobs"]);
        r.n[0] = static_cast<uint64_t>(n.data()[0]);
        r.n[1] = n.size() > 1 ? static_cast<uint64_t>(n.data()[1]) : 0;
        if (kind == "t_paired") // one size, the pairs: the single call's n[1] = n[0]
            r.n[1] = r.n[0];
        return make_result(r);
    });
    mod.def("_result_from_bytes", [](py::bytes b, py::object seed) {
        std::string s = b;
        if (s.size() != sizeof(mcstat_result))
            throw_status(MCSTAT_ECORRUPT, "a pickled TestResult from another build of mcstat");
        Result res;
        std::memcpy(&res.r, s.data(), sizeof res.r);
        if (!seed.is_none()) {
            res.seed = seed.cast<uint64_t>();
            res.has_seed = true;
        }
        return make_result(res);
    }, py::arg("raw"), py::arg("seed") = py::none());
}

} // namespace mcs
