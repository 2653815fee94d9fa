# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Exact binomial test and Clopper-Pearson interval, for counts of decisions.

The studies count rejections over repeated tests; whether such a count is
consistent with the level alpha (a false-rejection rate, section 3.1; the
fraction of equal means, section 3.3) is a binomial question that
libmcstat's five tests do not cover.  This is R's ``binom.test``: the
two-sided p-value sums the probabilities of all outcomes no more likely
than the observed one (with R's relative tolerance 1e-7), and the interval
is Clopper and Pearson's, found by bisection on the exact tails.  Sums run
over the whole support in log space (log-factorials by cumulative sums),
which is exact enough (relative ~1e-12) and cheap for the counts here
(n up to ~1e6).  tests/python/test_reproduce_binomial.py checks it against
SciPy's ``binomtest``.
"""
from __future__ import annotations

import math
from typing import Dict, Tuple

import numpy as np


def _logpmf(n: int, p: float) -> np.ndarray:
    k = np.arange(n + 1, dtype=float)
    lf = np.concatenate([[0.0], np.cumsum(np.log(np.arange(1, n + 1, dtype=float)))])
    lc = lf[n] - lf - lf[::-1]
    if p == 0.0:
        out = np.full(n + 1, -np.inf)
        out[0] = 0.0
        return out
    if p == 1.0:
        out = np.full(n + 1, -np.inf)
        out[n] = 0.0
        return out
    return lc + k * math.log(p) + (n - k) * math.log1p(-p)


def _cdf_upper(x: int, n: int, p: float) -> float:
    """P(X >= x)."""
    return float(np.exp(_logpmf(n, p)[x:]).sum())


def _cdf_lower(x: int, n: int, p: float) -> float:
    """P(X <= x)."""
    return float(np.exp(_logpmf(n, p)[: x + 1]).sum())


def _bisect(f, target: float) -> float:
    """p in (0, 1) with f(p) = target, f increasing in p."""
    lo, hi = 0.0, 1.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if f(mid) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def clopper_pearson(x: int, n: int, conf: float = 0.95) -> Tuple[float, float]:
    """Exact (Clopper-Pearson) confidence interval of a binomial proportion."""
    if n <= 0:
        return (0.0, 1.0)
    a = (1.0 - conf) / 2.0
    lo = 0.0 if x == 0 else _bisect(lambda p: _cdf_upper(x, n, p), a)
    hi = 1.0 if x == n else _bisect(lambda p: -_cdf_lower(x, n, p), -a)
    return (lo, hi)


def binom_test(x: int, n: int, p: float, conf: float = 0.95) -> Dict[str, float]:
    """Two-sided exact binomial test of H0: P(success) = p (R's binom.test).

    Returns a dict: x, n, p0, estimate, pvalue, conf_int (Clopper-Pearson).
    """
    if not (0 <= x <= n and n >= 1 and 0.0 <= p <= 1.0):
        raise ValueError(f"binom_test: need 0 <= x <= n, n >= 1 and p in [0, 1], got x={x}, n={n}, p={p}")
    lp = _logpmf(n, p)
    d = lp[x]
    # outcomes no more likely than the observed one (R's relErr = 1 + 1e-7)
    pv = float(np.exp(lp[lp <= d + math.log1p(1e-7)]).sum())
    return dict(x=int(x), n=int(n), p0=float(p), estimate=x / n, pvalue=min(1.0, pv),
                conf_int=list(clopper_pearson(x, n, conf)), conf_level=conf)


def format_binom(res: Dict[str, float], x_name: str, n_name: str) -> str:
    """The result laid out as R prints binom.test."""
    pv = res["pvalue"]
    pv_text = "< 2.2e-16" if pv < 2.2e-16 else f"= {pv:.4g}"
    lo, hi = res["conf_int"]
    return (f"\n\tExact binomial test\n\n"
            f"data:  {x_name} and {n_name}\n"
            f"number of successes = {res['x']}, number of trials = {res['n']}, p-value {pv_text}\n"
            f"alternative hypothesis: true probability of success is not equal to {res['p0']:g}\n"
            f"{round(100 * res['conf_level'])} percent confidence interval:\n"
            f" {lo:.7g} {hi:.7g}\n"
            f"sample estimates:\n"
            f"probability of success \n"
            f"{res['estimate']:>22.7g} \n")


def rate_summary(x: int, n: int, alpha: float) -> Dict[str, float]:
    """A count of rejections among n tests at level alpha: the rate, its 95%
    Clopper-Pearson interval and the binomial test of rate = alpha (None
    for all three when no test succeeded)."""
    if n == 0:
        return dict(rejections=0, tests=0, rate=None, ci95=[None, None], alpha=alpha, binom_pvalue=None)
    t = binom_test(x, n, alpha)
    return dict(rejections=int(x), tests=int(n), rate=x / n, ci95=t["conf_int"], alpha=alpha,
                binom_pvalue=t["pvalue"])


def rate_of_counts(c: Dict[str, int], alpha: float) -> Dict[str, float]:
    """rate_summary of decision counts (less / equal / greater / failed):
    rejections among the tests that ran; failed tests are counted apart."""
    return dict(rate_summary(c["less"] + c["greater"], c["less"] + c["equal"] + c["greater"], alpha),
                failed=c["failed"])
