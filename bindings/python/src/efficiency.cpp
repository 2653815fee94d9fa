// efficiency.cpp - efficiency_test: the ratio of two estimators' efficiencies
// (libmcstat's mcstat_efficiency_test); arrays or Moments in, a TestResult out.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cfloat>
#include <cmath>
#include <string>

namespace mcs {

namespace {

const char *EFFICIENCY_DOC = R"doc(efficiency_test(x, y, time_x, time_y, *, ratio=1.0, alternative="two-sided", alpha=0.05)

Is estimator x more efficient than estimator y?  Efficiency is 1 /
(variance per sample x time per sample) (Kalos & Whitlock); the test is
on rho = eff(x) / eff(y) = (var_y tau_y) / (var_x tau_x).

The standard error of log rho comes from the delta method without
assuming normal data (the sample kurtosis enters the variance of each
log s^2), plus the spread of the timed batches; the statistic is referred
to a t on Satterthwaite's degrees of freedom.  Asymptotic: it needs
samples with finite fourth moments, independent samples and batches, and
for mostly-zero estimators hundreds of non-zero values (libmcstat's
header gives the measured calibration).

Parameters
----------
x, y : array_like (1-D) or Moments
    The two estimators' samples (primary estimates), or their
    accumulators.
time_x, time_y : array_like (1-D) or Moments
    Time per sample of k >= 2 timed batches each (a batch's wall time
    divided by its size), preferably interleaved so that machine load
    affects both; `compare_efficiency` does the timing.  Equal values (an
    exact cost) are accepted and add no error.
ratio : float
    rho under H0 (> 0, finite); 1 by default.
alternative : {"two-sided", "less", "greater"}
    "greater": x is more efficient than `ratio` times y.
alpha : float
    Significance level in (0, 1).

Returns
-------
TestResult
    ``statistic`` (t), ``df``, ``pvalue``, ``conf_int`` for rho,
    ``estimate`` rho_hat, ``std_error`` of log rho_hat, ``efficiency``
    (the variance and time factors and their errors), ``decision``.

Raises
------
InvalidArgumentError
    alpha outside (0, 1), ratio <= 0 or not finite, a negative time.
TooFewObservationsError
    Fewer than 2 values in x or y, fewer than 2 timed batches.
DegenerateDataError
    x or y constant, or every batch of a timing timed as 0.
NonFiniteError
    NaN or infinity in an array.
)doc";

// The accumulator of a Moments, or of a 1-D array (named in errors).
const mcstat_moments *moments_arg(py::handle obj, const char *name, mcstat_moments *store)
{
    if (obj.is_none())
        throw py::type_error(std::string("efficiency_test(): ") + name +
                             " must be array-like or an mcstat.Moments, not None");
    if (const mcstat_moments *m = as_moments(obj))
        return m;
    if (as_moments_array(obj))
        throw py::type_error(std::string("efficiency_test(): ") + name +
                             " must be a 1-D array or an mcstat.Moments, not an mcstat.MomentsArray (one test "
                             "compares two estimators: pass one pixel's accumulator, a[i])");
    py::array a = as_contiguous_array(obj, name);
    if (a.ndim() != 1)
        throw_invalid(std::string(name) + " must be 1-D (or an mcstat.Moments), got " + std::to_string(a.ndim()) +
                      "-D");
    mcstat_moments_init(store);
    int st = mcstat_moments_add_array(store, static_cast<const double *>(a.data()), static_cast<size_t>(a.size()));
    if (st)
        throw_status(st, name);
    return store;
}

bool constant(const mcstat_moments *m)
{
    double sd = mcstat_moments_sd(m);
    return !(sd > 0.0) || sd < 10.0 * DBL_EPSILON * std::fabs(mcstat_moments_mean(m));
}

// Which argument libmcstat refused, and why, in the arguments' names: the
// checks mcstat_efficiency_test makes, repeated only to word the message.
[[noreturn]] void explain(int st, const mcstat_moments *const m[4])
{
    static const char *names[] = {"x", "y", "time_x", "time_y"};
    for (int k = 0; k < 4; k++) {
        std::string name = names[k];
        bool time = k >= 2;
        if (st == MCSTAT_ETOOFEW && m[k]->n < 2)
            throw_status(st, time ? name + " has " + std::to_string(m[k]->n) + " timed batch(es), need at least 2"
                                  : name + " has " + std::to_string(m[k]->n) + " value(s), need at least 2");
        if (st == MCSTAT_EDEGENERATE && !time && constant(m[k]))
            throw_status(st, name + " is constant: its variance is 0");
        if (st == MCSTAT_EDEGENERATE && time && !(mcstat_moments_mean(m[k]) > 0.0))
            throw_status(st, "every batch of " + name + " was timed as 0 (a timer too coarse for the batch size)");
        if (st == MCSTAT_EINVAL && time && m[k]->n > 0 && m[k]->min < 0.0)
            throw_invalid(name + " contains a negative time (" + repr(py::float_(m[k]->min).ptr()) + ")");
    }
    throw_status(st);
}

py::object efficiency_test(py::object x, py::object y, py::object time_x, py::object time_y, py::handle ratio_obj,
                           py::handle alternative, py::handle alpha_obj)
{
    double ratio = get_double(ratio_obj.ptr(), "ratio");
    if (!(ratio > 0.0) || !std::isfinite(ratio))
        throw_invalid("ratio must be finite and > 0, got " + repr(ratio_obj.ptr()));
    double alpha = get_double(alpha_obj.ptr(), "alpha");
    if (!(alpha > 0.0 && alpha < 1.0))
        throw_invalid("alpha must be in (0, 1), got " + repr(alpha_obj.ptr()));
    int alt = parse_alternative(alternative.ptr());
    mcstat_moments store[4];
    const mcstat_moments *m[4] = {moments_arg(x, "x", &store[0]), moments_arg(y, "y", &store[1]),
                                  moments_arg(time_x, "time_x", &store[2]), moments_arg(time_y, "time_y", &store[3])};
    mcstat_result r;
    int st = mcstat_efficiency_test(m[0], m[1], m[2], m[3], ratio, alt, alpha, &r);
    if (st)
        explain(st, m);
    return make_result(r);
}

} // namespace

void register_efficiency(py::module_ &mod)
{
    mod.def("efficiency_test", &efficiency_test, py::arg("x"), py::arg("y"), py::arg("time_x"), py::arg("time_y"),
            py::kw_only(), py::arg("ratio") = 1.0, py::arg("alternative") = "two-sided", py::arg("alpha") = 0.05,
            EFFICIENCY_DOC);
}

} // namespace mcs
