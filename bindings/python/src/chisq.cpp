// chisq.cpp - chisq_gof: Pearson's chi-squared goodness of fit (libmcstat's
// mcstat_chisq_gof); arguments in, a TestResult out.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <string>

namespace mcs {

namespace {

const char *CHISQ_DOC = R"doc(chisq_gof(observed, expected=None, *, expected_kind="auto", pool=True, min_expected=None, n_estimated=0, rescale=False, alpha=0.05)

Pearson's chi-squared goodness-of-fit test of cell counts.

Experimental (libmcstat's mcstat/gof.h): its name and options may change
before 1.0; a renamed function stays as a deprecated alias for one release.

Parameters
----------
observed : array_like, shape (k,)
    Counts of the k cells (finite, >= 0; need not be integers).
expected : array_like, shape (k,), optional
    None (the default, as SciPy's ``chisquare(f_obs)`` and R's
    ``chisq.test(x)``): equal probabilities.  Else cell probabilities (``expected_kind="probabilities"``, summing to 1,
    as R's ``chisq.test(x, p = p)``) or expected counts (``"counts"``,
    summing to ``observed.sum()``, as SciPy's ``chisquare(f_obs, f_exp)``),
    both to within sqrt(machine epsilon) relative, unless ``rescale=True``.
    ``"auto"`` (the default) takes probabilities when `expected` sums to 1
    and counts otherwise (when ``observed.sum()`` is 1 the two readings are
    the same test).
pool : bool
    Pool cells of low expectation: walking the cells in the given order,
    consecutive cells are merged until the expected count reaches
    `min_expected`; a short last group joins the group before it.  Order
    the cells so that neighbours in the array are neighbours in space.
    ``pool=False`` is R's ``chisq.test(x, p = p)`` (every expectation must
    then be > 0).
min_expected : float
    The pooling threshold on expected counts (Cochran's 5 by default);
    with ``pool=False`` it does not apply, and giving it raises.
n_estimated : int
    Parameters of the expected probabilities estimated from these counts:
    df = (cells after pooling) - 1 - n_estimated.
alpha : float
    Significance level in (0, 1).

Returns
-------
TestResult
    ``statistic`` X-squared, ``df``, ``pvalue`` (the chi-squared upper
    tail, accurate deep into the tail), ``reject``, ``decision``
    ("greater" when rejected, else "equal"), ``critical_values``
    ``(-inf, c)``, ``cells`` (after pooling), ``nobs`` (the total count).

Raises
------
InvalidArgumentError
    Negative counts or expectations, sums that do not match (the message
    gives both sums), a zero expectation without pooling, alpha outside
    (0, 1), mismatched sizes.
NonFiniteError
    NaN or infinity in either array.
TooFewObservationsError
    Fewer than 2 cells, no observations, or df < 1 after pooling.
)doc";

std::string num(double v)
{
    return repr(py::float_(v).ptr());
}

// What libmcstat refused (MCSTAT_EINVAL), in the arguments' names: the
// checks mcstat_gof_chisq_test makes, repeated only to word the message.
std::string explain_invalid(const double *o, const double *e, size_t k, const mcstat_gof_options &opt)
{
    double so = 0.0, se = 0.0;
    for (size_t i = 0; i < k; i++) {
        if (o[i] < 0.0)
            return "observed counts must be >= 0, got " + num(o[i]) + " at index " + std::to_string(i);
        if (e[i] < 0.0)
            return "expected must be >= 0, got " + num(e[i]) + " at index " + std::to_string(i);
        if (!opt.pool && !(e[i] > 0.0))
            return "expected is 0 at index " + std::to_string(i) +
                   ": without pooling (pool=False) every cell needs a positive expectation";
        so += o[i];
        se += e[i];
    }
    if (!std::isfinite(so) || !std::isfinite(se))
        return "the sums of observed and expected overflow";
    if (!(se > 0.0))
        return "expected sums to 0";
    std::string sums = "expected sums to " + num(se) + " and observed to " + num(so);
    switch (opt.expected) {
    case MCSTAT_GOF_PROBABILITIES:
        return sums + ": as probabilities (expected_kind='probabilities') expected must sum to 1; "
                      "pass expected_kind='counts' for expected counts, or rescale=True to scale it";
    case MCSTAT_GOF_COUNTS:
        return sums + ": as expected counts (expected_kind='counts') the sums must agree; "
                      "pass rescale=True to scale expected to observed's total";
    default:
        return sums + ": expected must be probabilities (summing to 1) or expected counts (summing to "
                      "observed's total), to a relative 1.5e-8; pass rescale=True to scale it";
    }
}

py::object chisq_gof(py::object observed, py::object expected, const std::string &kind, bool pool,
                     py::object min_expected_arg, int n_estimated, bool rescale, double alpha)
{
    if (!min_expected_arg.is_none() && !pool)
        throw_invalid("min_expected applies to pooling, not pool=False (where every cell is tested as given)");
    double min_expected =
        min_expected_arg.is_none() ? mcstat_gof_default_min_expected() : get_double(min_expected_arg.ptr(), "min_expected");
    py::array o = as_contiguous_array(observed, "observed");
    if (expected.is_none()) {
        if (o.ndim() != 1)
            throw_invalid("observed must be a 1-D array");
        py::ssize_t k = o.size();
        py::array_t<double> uniform(k);
        double *d = uniform.mutable_data();
        for (py::ssize_t i = 0; i < k; i++)
            d[i] = 1.0 / static_cast<double>(k);
        expected = uniform;
        if (kind == "counts")
            throw_invalid("expected_kind='counts' needs expected counts; without expected the cells are "
                          "equally likely");
    }
    py::array e = as_contiguous_array(expected, "expected");
    if (o.ndim() != 1 || e.ndim() != 1)
        throw_invalid("observed and expected must be 1-D arrays");
    if (o.size() != e.size())
        throw_invalid("observed and expected must have the same length, got " + std::to_string(o.size()) +
                      " and " + std::to_string(e.size()));
    mcstat_gof_options opt;
    mcstat_gof_options_init(&opt);
    if (kind == "probabilities")
        opt.expected = MCSTAT_GOF_PROBABILITIES;
    else if (kind == "counts")
        opt.expected = MCSTAT_GOF_COUNTS;
    else if (kind == "auto")
        opt.expected = MCSTAT_GOF_AUTO;
    else
        throw_invalid("expected_kind must be 'auto', 'probabilities' or 'counts', got " +
                      repr(py::str(kind).ptr()));
    if (!(min_expected >= 0.0) || !std::isfinite(min_expected))
        throw_invalid("min_expected must be finite and >= 0");
    if (n_estimated < 0)
        throw_invalid("n_estimated must be >= 0");
    if (!(alpha > 0.0 && alpha < 1.0))
        throw_invalid("alpha must be in (0, 1), got " + std::to_string(alpha));
    opt.pool = pool ? 1 : 0;
    opt.min_expected = min_expected;
    opt.n_estimated = n_estimated;
    opt.rescale = rescale ? 1 : 0;
    mcstat_result r;
    const double *od = static_cast<const double *>(o.data()), *ed = static_cast<const double *>(e.data());
    size_t k = static_cast<size_t>(o.size());
    int st;
    {
        py::gil_scoped_release nogil;
        st = mcstat_gof_chisq_test(od, ed, k, &opt, alpha, &r);
    }
    if (st == MCSTAT_EINVAL)
        throw_invalid(explain_invalid(od, ed, k, opt));
    if (st == MCSTAT_ETOOFEW)
        throw_status(st, k < 2 ? "chisq_gof needs at least 2 cells, got " + std::to_string(k)
                               : "no observations, or df < 1 after pooling and n_estimated");
    if (st)
        throw_status(st);
    return make_result(r);
}

} // namespace

void register_chisq(py::module_ &mod)
{
    mod.def("chisq_gof", &chisq_gof, py::arg("observed"), py::arg("expected") = py::none(), py::kw_only(),
            py::arg("expected_kind") = "auto", py::arg("pool") = true,
            py::arg("min_expected") = py::none(), py::arg("n_estimated") = 0,
            py::arg("rescale") = false, py::arg("alpha") = 0.05, CHISQ_DOC);
}

} // namespace mcs
