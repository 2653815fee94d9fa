# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Counts of decisions: the battery meta-test and Clopper-Pearson intervals.

The studies count rejections over repeated tests; whether such a count is
consistent with the level alpha (a false-rejection rate, section 3.1; the
fraction of equal means, section 3.3) is the meta-test of a battery: R's
exact ``binom.test`` of the count against alpha.  The numbers are
libmcstat's (``mcstat.binom_test`` / ``mcstat.battery_test``: R's two-sided
rule, Clopper-Pearson interval, exact tails from the library's incomplete
beta); this module keeps the dict form the report and results.json use.
"""
from __future__ import annotations

from typing import Any, Dict, Tuple

import mcstat


def clopper_pearson(x: int, n: int, conf: float = 0.95) -> Tuple[float, float]:
    """Exact (Clopper-Pearson) confidence interval of a binomial proportion."""
    if n <= 0:
        return (0.0, 1.0)
    lo, hi = mcstat.binom_test(x, n, 0.5, alpha=1.0 - conf).conf_int
    return (float(lo), float(hi))


def binom_test(x: int, n: int, p: float, conf: float = 0.95) -> Dict[str, Any]:
    """Two-sided exact binomial test of H0: P(success) = p (R's binom.test).

    Returns a dict: x, n, p0, estimate, pvalue, log_pvalue, conf_int
    (Clopper-Pearson), conf_level, accepted (the counts not rejected at
    1 - conf_level).
    """
    r = mcstat.binom_test(int(x), int(n), float(p), alpha=1.0 - conf)
    return dict(x=int(x), n=int(n), p0=float(p), estimate=x / n, pvalue=float(r.pvalue),
                log_pvalue=float(r.log_pvalue), conf_int=[float(c) for c in r.conf_int], conf_level=conf,
                accepted=[int(c) for c in r.critical_values])


def format_binom(res: Dict[str, Any], x_name: str, n_name: str) -> str:
    """The result laid out as R prints binom.test (libmcstat's formatter),
    plus mcstat's decision line."""
    r = mcstat.binom_test(res["x"], res["n"], res["p0"], alpha=1.0 - res["conf_level"])
    return r.format(x_name, n_name)


def rate_summary(x: int, n: int, alpha: float) -> Dict[str, Any]:
    """A count of rejections among n tests at level alpha: the rate, its 95%
    Clopper-Pearson interval and the battery meta-test of rate = alpha
    (None for all three when no test succeeded)."""
    if n == 0:
        return dict(rejections=0, tests=0, rate=None, ci95=[None, None], alpha=alpha, binom_pvalue=None)
    t = mcstat.battery_test(int(x), alpha, n=int(n))
    return dict(rejections=int(x), tests=int(n), rate=x / n, ci95=[float(c) for c in t.conf_int], alpha=alpha,
                binom_pvalue=float(t.pvalue))


def rate_of_counts(c: Dict[str, int], alpha: float) -> Dict[str, Any]:
    """rate_summary of decision counts (less / equal / greater / failed):
    rejections among the tests that ran; failed tests are counted apart."""
    return dict(rate_summary(c["less"] + c["greater"], c["less"] + c["equal"] + c["greater"], alpha),
                failed=c["failed"])
