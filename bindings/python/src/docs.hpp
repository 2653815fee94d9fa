// docs.hpp - the docstrings of t_test and var_test (NumPy style).
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#pragma once

namespace mcs {

inline constexpr const char T_TEST_DOC[] = R"doc(t_test($module, /, x, y=None, *, mu=0.0, alternative='two-sided', alpha=0.05, axis=-1, nan_policy='raise', intervals=True, on_error='raise')
--

Student's one-sample t test, or Welch's two-sample t test.

One sample (``y`` is None): H0 mean(x) = mu (paper, section 2.1).  Two
samples: H0 mean(x) - mean(y) = mu, with Welch-Satterthwaite degrees of
freedom (section 2.3).

Parameters
----------
x, y : array_like or Moments
    Samples.  Anything NumPy converts to float64; C-contiguous float64 is
    read in place, anything else is converted once.  A `Moments`
    accumulator may stand in for either sample (an array beside it must
    then be 1-D).  With N-D input, one test per row along `axis`.
mu : float, optional
    Mean (difference of means) under H0.
alternative : {"two-sided", "less", "greater"}, optional
    A claim about the first sample: "less" means mean(x) < mu (or
    mean(x) - mean(y) < mu).
alpha : float, optional
    Significance level in (0, 1), for `reject`, `decision`, the critical
    values and the 1 - alpha confidence interval.
axis : int, optional
    The axis holding each sample in N-D input (default: the last).  x and
    y must then have the same shape except along `axis` (no broadcasting).
nan_policy : {"raise", "omit"}, optional
    NaN raises `NonFiniteError`, or is omitted from its sample (row).
    Infinities always raise.
intervals : bool, optional
    False skips the critical values and the confidence interval (NaN):
    the cheap path when only p-values and decisions are wanted.
on_error : {"raise", "nan"}, optional
    Row-wise tests only: a failed row raises (the exception's ``rows``
    names them), or gets NaN fields, ``reject`` False and a non-zero
    ``status``.  A single test always raises.

Returns
-------
TestResult or BatchResult
    One result, or arrays of results for N-D input.

Raises
------
TooFewObservationsError
    A sample with fewer than 2 values (also empty input).
NonFiniteError
    NaN or infinity in the data.
DegenerateDataError
    Constant data (Welch: both samples constant).
InvalidArgumentError
    alpha outside (0, 1), non-finite mu, unknown alternative, nan_policy or
    on_error, axis out of range, scalar input, mismatched shapes.
TypeError
    x is None, or an option of the wrong type.

Examples
--------
>>> r = mcstat.t_test(new, trusted, alpha=0.01)
>>> r.pvalue, r.decision
>>> print(r.format("new", "trusted"))   # R's print.htest layout
)doc";

inline constexpr const char VAR_TEST_DOC[] = R"doc(var_test($module, /, x, y=None, *, sigma2=None, ratio=1.0, alternative='two-sided', alpha=0.05, axis=-1, nan_policy='raise', intervals=True, on_error='raise')
--

Chi-squared test of one variance, or the F test of two.

One sample (``y`` is None): H0 var(x) = sigma2, statistic (n-1) s^2 /
sigma2 on n-1 degrees of freedom (section 2.2).  Two samples: H0
var(x)/var(y) = ratio, statistic (s_x^2 / s_y^2) / ratio on (nx-1, ny-1)
degrees of freedom (section 2.4).

Parameters
----------
x, y : array_like or Moments
    Samples, as for `t_test`.
sigma2 : float
    Variance under H0 (required for one sample, positive).
ratio : float, optional
    Ratio of variances under H0 (two samples, positive).
alternative : {"two-sided", "less", "greater"}, optional
    A claim about the first sample: "less" means var(x) < sigma2 (or
    var(x)/var(y) < ratio): the new estimator has the lower variance
    (ERRATA 4).
alpha, axis, nan_policy, intervals, on_error
    As for `t_test`.

Returns
-------
TestResult or BatchResult

Raises
------
TooFewObservationsError, NonFiniteError, DegenerateDataError,
InvalidArgumentError, TypeError
    As for `t_test`; DegenerateDataError for either sample constant;
    InvalidArgumentError also for a missing or non-positive sigma2, a
    non-positive ratio, sigma2 with two samples or ratio with one.
)doc";

} // namespace mcs
