// chisq.cpp - chisq_gof: Pearson's chi-squared goodness of fit (libmcstat's
// mcstat_chisq_gof); arguments in, a TestResult out.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cmath>
#include <string>

namespace mcs {

namespace {

const char *CHISQ_DOC = R"doc(chisq_gof(observed, expected, *, expected_kind="probabilities", pool=True, min_expected=5.0, n_estimated=0, rescale=False, alpha=0.05)

Pearson's chi-squared goodness-of-fit test of cell counts.

Parameters
----------
observed : array_like, shape (k,)
    Counts of the k cells (finite, >= 0; need not be integers).
expected : array_like, shape (k,)
    Cell probabilities (``expected_kind="probabilities"``, summing to 1)
    or expected counts (``"counts"``, summing to ``observed.sum()``), both
    to within sqrt(machine epsilon) relative, as R's ``chisq.test``
    requires, unless ``rescale=True``.
pool : bool
    Pool cells of low expectation: walking the cells in the given order,
    consecutive cells are merged until the expected count reaches
    `min_expected`; a short last group joins the group before it.  Order
    the cells so that neighbours in the array are neighbours in space.
    ``pool=False`` is R's ``chisq.test(x, p = p)`` (every expectation must
    then be > 0).
min_expected : float
    The pooling threshold on expected counts (Cochran's 5 by default).
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
    Negative counts or expectations, sums that do not match, a zero
    expectation without pooling, alpha outside (0, 1), mismatched sizes.
NonFiniteError
    NaN or infinity in either array.
TooFewObservationsError
    Fewer than 2 cells, no observations, or df < 1 after pooling.
)doc";

py::object chisq_gof(py::object observed, py::object expected, const std::string &kind, bool pool,
                     double min_expected, int n_estimated, bool rescale, double alpha)
{
    py::array o = as_contiguous_array(observed, "observed"), e = as_contiguous_array(expected, "expected");
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
    else
        throw_invalid("expected_kind must be 'probabilities' or 'counts', got '" + kind + "'");
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
    if (st)
        throw_status(st, "chisq_gof");
    return make_result(r);
}

} // namespace

void register_chisq(py::module_ &mod)
{
    mod.def("chisq_gof", &chisq_gof, py::arg("observed"), py::arg("expected"), py::kw_only(),
            py::arg("expected_kind") = "probabilities", py::arg("pool") = true,
            py::arg("min_expected") = mcstat_gof_default_min_expected(), py::arg("n_estimated") = 0,
            py::arg("rescale") = false, py::arg("alpha") = 0.05, CHISQ_DOC);
}

} // namespace mcs
