# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Beyond the paper: the exact binomial test, the battery
meta-test, and diagnostics of an estimator's primary estimates.

The numbers are libmcstat's (``mcstat_binom_test``, ``mcstat_battery_test``,
``mcstat_diag_compute``, documented in mcstat.h); this module converts
arguments and adds the normality tests of the batch means, which come from
SciPy (D'Agostino-Pearson ``normaltest`` and Shapiro-Wilk ``shapiro``).
"""
from __future__ import annotations

import math
import operator
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from . import _core
from ._errors import InvalidArgumentError
from ._core import TestResult
from ._power import _real

__all__ = ["binom_test", "battery_test", "diagnose", "Diagnostics", "t_size_edgeworth", "batch_size_recommend",
           "tail_index"]


def binom_test(x: int, n: int, p: float = 0.5, *, alternative: str = "two-sided",
               alpha: float = 0.05) -> TestResult:
    """Exact binomial test of H0: P(success) = p, as R's ``binom.test``.

    Experimental (libmcstat's mcstat/gof.h): its name and options may change before 1.0; a
    renamed function stays as a deprecated alias for one release.

    Parameters
    ----------
    x, n : int
        Successes and trials (0 <= x <= n, 1 <= n <= 2**53).
    p : float
        Probability of success under H0, in [0, 1].
    alternative : {"two-sided", "less", "greater"}
        "two-sided" uses R's rule: the p-value sums the probabilities of all
        outcomes no more likely than x (relative tolerance 1e-7).
    alpha : float
        Level for `reject`, `decision`, `critical_values` and the
        Clopper-Pearson `conf_int` (level 1 - alpha; one-sided for a
        one-sided alternative, as R).

    Returns
    -------
    TestResult
        ``statistic`` = x, ``estimate`` = x/n, ``null_value`` = p,
        ``critical_values`` = the counts accepted, ``[c0, c1]`` (reject
        when x < c0 or x > c1), ``log_pvalue`` finite far below 1e-308;
        ``str()`` is R's block plus the decision line.
    """
    return _core._binom_test(operator.index(x), operator.index(n), _real(p, "p"), alternative, _real(alpha, "alpha"))


def battery_test(tests: Any, alpha: float = 0.05, *, n: Optional[int] = None, alternative: str = "two-sided",
                 meta_alpha: float = 0.05) -> TestResult:
    """The meta-test of a battery: is its number of rejections consistent
    with the level `alpha` of its tests?

    Experimental (libmcstat's mcstat/gof.h): its name and options may change before 1.0; a
    renamed function stays as a deprecated alias for one release.

    Under every null hypothesis, k independent tests at level alpha reject
    Binomial(k, alpha) times; this is the exact binomial test of the count
    against alpha (`binom_test`).

    Parameters
    ----------
    tests : array_like of bool, array_like of float, or int
        The battery's reject flags (bool), its p-values (float; a test
        rejects when p <= alpha), or the number of rejections (int, with
        `n` the number of tests).
    alpha : float
        The level of the battery's tests, in (0, 1).
    n : int, optional
        Number of tests, when `tests` is a count.
    alternative : {"two-sided", "less", "greater"}
        "greater": too many rejections (an anti-conservative test or a real
        effect); "less": too few (a conservative test); default both.
    meta_alpha : float
        The meta-test's own level.

    Returns
    -------
    TestResult of the binomial test (``statistic`` = rejections).
    """
    alpha, meta_alpha = _real(alpha, "alpha"), _real(meta_alpha, "meta_alpha")
    if isinstance(tests, (int, np.integer)) and not isinstance(tests, (bool, np.bool_)):
        if n is None:
            raise TypeError("battery_test: n (the number of tests) is required with a count of rejections")
        if not (0.0 < alpha < 1.0):
            raise InvalidArgumentError(f"battery_test: alpha must be in (0, 1), got {alpha!r}")
        return _core._battery_test(operator.index(tests), operator.index(n), alpha, alternative, meta_alpha)
    if n is not None:
        raise TypeError("battery_test: n is only for a count of rejections")
    a = _core._real_array(tests, "tests")
    if a.dtype == np.bool_:
        flags = a.ravel()
        if not (0.0 < alpha < 1.0):
            raise InvalidArgumentError(f"battery_test: alpha must be in (0, 1), got {alpha!r}")
        return _core._battery_test(int(flags.sum()), flags.size, alpha, alternative, meta_alpha)
    if a.dtype.kind in "iu":
        # 0/1 integers are ambiguous: flags (1 = rejected) or p-values (0 = rejected)?
        raise TypeError("battery_test: pass reject flags as bool and p-values as float, not integers")
    return _core._battery_test_pvalues(a.ravel(), alpha, alternative, meta_alpha)


def tail_index(x: Any, tail_k: Optional[int] = None) -> Tuple[float, float]:
    """Hill's tail index of each tail of `x` (1-D): ``(lower, upper)``.

    Each from the `tail_k` most extreme values on its side of the median
    (default max(10, min(4 sqrt(n), n // 25)); fewer when fewer values lie
    beyond the median).  inf means no Pareto tail; below about 2 the
    variance is infinite ("fireflies": sample variances, t and F tests are
    unreliable).  The same estimate `diagnose` reports, without the rest.
    Raises `TooFewObservationsError` for n < 2 tail_k + 2 and
    `NonFiniteError` for NaN or infinite values.
    """
    if tail_k is not None and operator.index(tail_k) < 1:
        raise InvalidArgumentError(f"tail_index: tail_k must be >= 1, got {tail_k!r}")
    lo, up = _core._tail_index(_core._float_array(x, "x"), 0 if tail_k is None else operator.index(tail_k))
    return float(lo), float(up)


def t_size_edgeworth(skewness: float, kurtosis: float, k: int, m: int, alpha: float = 0.05) -> Tuple[float, float]:
    """Predicted rejection rates (lower tail "less", upper tail "greater") of
    the two-sided t test at `alpha` on m batch means of k values of the given
    skewness and excess kurtosis (Hall's Edgeworth expansion; each is
    alpha/2 for normal data).  See mcstat.h, "Estimator diagnostics"."""
    return _core._t_size_edgeworth(_real(skewness, "skewness"), _real(kurtosis, "kurtosis"), int(k), int(m),
                                   _real(alpha, "alpha"))


def batch_size_recommend(skewness: float, kurtosis: float, m: int, alpha: float = 0.05,
                         tolerance: float = 0.2) -> int:
    """The smallest batch size k whose `t_size_edgeworth` tails are both
    within tolerance * alpha/2 of alpha/2, for m batch means."""
    return _core._batch_size_recommend(_real(skewness, "skewness"), _real(kurtosis, "kurtosis"), int(m),
                                       _real(alpha, "alpha"), _real(tolerance, "tolerance"))


@dataclass
class Diagnostics:
    """The result of `diagnose` (fields as in mcstat.h's mcstat_diagnostics).

    Attributes
    ----------
    n, mean, sd : primary estimates, their mean and standard deviation
    skewness, skewness_se, kurtosis, kurtosis_se : g1 and excess g2 with
        their standard errors under normality
    tail_index : (lower, upper) Hill estimates from `tail_k` order
        statistics each (inf: no Pareto tail); tail_index_se their errors
    heavy_tail : bool, a tail index below `tail_threshold` (2.2): infinite
        or nearly infinite variance ("fireflies")
    max_share : the largest single share of the sum of squares
    k, m : batch size and number of batch means `t_size` refers to
    t_size : predicted (less, greater) rejection rates of the two-sided t
        test at alpha on m batch means of k (alpha/2 each if normal)
    recommended_k : the batch size rule's k for m batch means
    batch_k, batch_m : the batch size and count the normality tests used
    normaltest_pvalue, shapiro_pvalue : SciPy's tests of normality of those
        batch means (None when there were too few: normaltest needs 20,
        Shapiro-Wilk 3, both at most 5000 means are used)
    warnings : human-readable warnings
    """

    n: int
    mean: float
    sd: float
    skewness: float
    skewness_se: float
    kurtosis: float
    kurtosis_se: float
    tail_k: int
    tail_index: Tuple[float, float]
    tail_index_se: Tuple[float, float]
    max_share: float
    heavy_tail: bool
    k: int
    m: int
    t_size: Tuple[float, float]
    recommended_k: int
    alpha: float
    tolerance: float
    batch_k: int = 0
    batch_m: int = 0
    normaltest_pvalue: Optional[float] = None
    shapiro_pvalue: Optional[float] = None
    warnings: List[str] = field(default_factory=list)

    def to_dict(self) -> Dict[str, Any]:
        return dict(self.__dict__)

    def __str__(self) -> str:
        def f(v: float) -> str:
            return "inf" if math.isinf(v) else f"{v:.3g}"
        lines = [f"diagnostics of {self.n} primary estimates: mean {self.mean:.6g}, sd {self.sd:.4g}",
                 f"skewness {self.skewness:.3g} (se {self.skewness_se:.2g}), excess kurtosis {self.kurtosis:.3g} "
                 f"(se {self.kurtosis_se:.2g})",
                 f"tail index (Hill, {self.tail_k} order statistics): lower {f(self.tail_index[0])}, upper "
                 f"{f(self.tail_index[1])}; largest share of the sum of squares {self.max_share:.2g}",
                 f"t test at alpha = {self.alpha:g} on {self.m} batch means of {self.k}: predicted rejection rates "
                 f"less {self.t_size[0]:.4f}, greater {self.t_size[1]:.4f} (nominal {self.alpha / 2:g} each)",
                 f"recommended batch size for {self.m} batch means: k = {self.recommended_k}"]
        if self.batch_m:
            nt = "n/a" if self.normaltest_pvalue is None else f"{self.normaltest_pvalue:.3g}"
            sw = "n/a" if self.shapiro_pvalue is None else f"{self.shapiro_pvalue:.3g}"
            lines.append(f"normality of {self.batch_m} batch means of {self.batch_k}: D'Agostino-Pearson p = {nt}, "
                         f"Shapiro-Wilk p = {sw}")
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def _normality(x: np.ndarray, k: int) -> Tuple[int, Optional[float], Optional[float]]:
    m = x.size // k
    if m < 3:
        return m, None, None
    from scipy import stats  # a maintained implementation of both tests

    means = x[: m * k].reshape(m, k).mean(axis=1)
    if np.ptp(means) == 0.0:
        return m, None, None
    means = means[:5000]  # Shapiro-Wilk's p-value is documented up to 5000
    nt = float(stats.normaltest(means).pvalue) if means.size >= 20 else None
    sw = float(stats.shapiro(means).pvalue)
    return m, nt, sw


def diagnose(x: Any, *, k: Optional[int] = None, m: Optional[int] = None, alpha: float = 0.05,
             tolerance: float = 0.2, tail_k: Optional[int] = None, tail_threshold: float = 2.2,
             normality: bool = True) -> Diagnostics:
    """Diagnostics of an estimator's primary estimates `x` (1-D).

    Experimental (libmcstat's mcstat/diagnostics.h): its name and options may change before 1.0;
    a renamed function stays as a deprecated alias for one release.

    Reports the shape (skewness, excess kurtosis, standard errors), the
    tails (Hill's tail index of each tail; `heavy_tail` when one is below
    `tail_threshold`: infinite variance or close to it), the t test's
    predicted rejection rates on batch means, the recommended batch size,
    and SciPy's normality tests of the batch means.  See mcstat.h,
    "Estimator diagnostics", for the rules and their measured error rates.

    Parameters
    ----------
    x : array_like
        Primary estimates, in the order they were drawn (batches are
        consecutive runs of k).
    k : int, optional
        The batch size in use; the normality tests and `t_size` use it
        (default: the recommended k for the tests, 1 for `t_size`).
    m : int, optional
        The number of batch means the t test will see (default n // k with
        `k`, else 30): the recommended k is for m batch means.
    alpha, tolerance : float
        The t test's level and the allowed relative error of each tail's
        rejection rate (0.2: 0.025 +- 0.005 at alpha = 0.05).
    tail_k : int, optional
        Order statistics per tail for Hill's estimate (default
        max(10, min(4 sqrt(n), n // 25)); fewer when fewer values lie
        beyond the median).
    tail_threshold : float
        heavy_tail below this tail index.
    normality : bool
        Run the normality tests of the batch means (needs SciPy).
    """
    a = _core._float_array(x, "x")
    if k is not None and operator.index(k) < 1:
        raise InvalidArgumentError(f"diagnose: k must be >= 1, got {k!r}")
    if m is not None and operator.index(m) < 2:
        raise InvalidArgumentError(f"diagnose: m must be >= 2, got {m!r}")
    if tail_k is not None and operator.index(tail_k) < 1:
        raise InvalidArgumentError(f"diagnose: tail_k must be >= 1, got {tail_k!r}")
    alpha, tolerance = _real(alpha, "alpha"), _real(tolerance, "tolerance")
    d = _core._diagnose(a, int(k or 0), int(m or 0), alpha, tolerance, int(tail_k or 0),
                        _real(tail_threshold, "tail_threshold"))
    out = Diagnostics(**d)
    if out.heavy_tail:
        out.warnings.append(
            f"heavy tail: Hill tail index {min(out.tail_index):.2f} < {tail_threshold:g} (variance infinite or nearly "
            "so: rare huge estimates, 'fireflies'); sample variances, t and F tests are unreliable")
    half = alpha / 2
    if max(abs(out.t_size[0] - half), abs(out.t_size[1] - half)) > tolerance * half:
        out.warnings.append(
            f"batch means of {out.k} are too skewed for the t test on {out.m} of them: predicted rejection rates "
            f"{out.t_size[0]:.4f} / {out.t_size[1]:.4f} instead of {half:g}; use k >= {out.recommended_k}")
    if normality:
        bk = int(k) if k is not None else out.recommended_k
        out.batch_k = bk
        out.batch_m, out.normaltest_pvalue, out.shapiro_pvalue = _normality(a, bk)
    return out
