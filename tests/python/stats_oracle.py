"""Independent oracles and binomial bounds for the calibration and power
suite (tests marked ``stats``: test_calibration.py, test_stats_power.py).

Nothing here calls mcstat: every prediction comes from SciPy's
distributions, a closed form, numerical integration or a lattice-path
count written from the definitions in mcstat.h (ERRATA 1-3), so that a
mistake in libmcstat cannot agree with itself.

- `Budget`: exact binomial acceptance regions at a per-check level chosen
  so that the whole suite's false-failure probability is at most 1e-4
  (Bonferroni); it counts the checks it makes and refuses to make more
  than it was sized for.
- `welch_rejection`: the exact rejection probability of Welch's test on
  normal data (any sizes, variances and true difference), by quadrature
  over the two sample variances.
- `KSNull`: the exact permutation distribution of the two-sample K-S
  statistic (weight none or Canner, each alternative) for continuous data,
  by counting lattice paths with Python integers; from it the exact size of
  the exact, simulated and asymptotic tests.
- `ks_statistic_rows`: the statistic itself, vectorised over rows (NumPy),
  for power checks row by row.
"""
import math

import numpy as np
from scipy import stats


# ---- binomial bounds under a Bonferroni budget ------------------------------
class Budget:
    """Per-check level = total / max_checks.  `accept(k, n, p)` says whether
    k rejections out of n are inside the exact two-sided binomial acceptance
    region of Bin(n, p) at that level; `p` may be an interval (lo, hi) of
    admissible rates, for tests whose size is ambiguous at a boundary."""

    def __init__(self, total=1e-4, max_checks=2000):
        self.total = total
        self.max_checks = max_checks
        self.level = total / max_checks
        self.used = 0

    def region(self, n, p):
        lo_p, hi_p = (p, p) if np.isscalar(p) else p
        lo = stats.binom.ppf(self.level / 2, n, lo_p) if lo_p > 0 else 0
        hi = stats.binom.isf(self.level / 2, n, hi_p) if hi_p < 1 else n
        return int(lo), int(hi)

    def accept(self, k, n, p):
        self.used += 1
        assert self.used <= self.max_checks, "the suite makes more checks than its budget was sized for"
        lo, hi = self.region(n, p)
        return lo <= k <= hi

    def half_width(self, n, p):
        """Half-width of the acceptance region, as a rate."""
        lo, hi = self.region(n, p)
        return (hi - lo) / (2.0 * n)


# ---- Welch's test on normal data: exact rejection probability ---------------
def welch_rejection(n1, n2, sd1, sd2, delta, alternative, alpha, m=400):
    """P(Welch's test rejects) for X ~ N(mu1, sd1^2) (n1 values), Y ~ N(mu2,
    sd2^2) (n2 values), delta = mu1 - mu2 - (null difference).

    X-bar - Y-bar ~ N(delta, se^2) is independent of the two sample
    variances; given them, the test rejects when a normal variable crosses
    c * se_hat (c the t quantile at the Welch-Satterthwaite df), which has a
    closed form.  What remains is an expectation over two independent
    scaled chi-squares, done by the midpoint rule in probability (m x m
    points; the integrand is bounded: against m = 1600 the difference is
    below 3e-5 at m = 400 for sizes 2+2 ... 30+20, a tenth of the binomial
    noise of the checks)."""
    u = (np.arange(m) + 0.5) / m
    a = sd1**2 / n1 * stats.chi2.ppf(u, n1 - 1) / (n1 - 1)  # s1^2 / n1
    b = sd2**2 / n2 * stats.chi2.ppf(u, n2 - 1) / (n2 - 1)  # s2^2 / n2
    A, B = np.meshgrid(a, b, indexing="ij")
    se_hat = np.sqrt(A + B)
    nu = (A + B) ** 2 / (A**2 / (n1 - 1) + B**2 / (n2 - 1))
    se = math.sqrt(sd1**2 / n1 + sd2**2 / n2)
    one = alpha if alternative != "two-sided" else alpha / 2
    c = stats.t.isf(one, nu)
    p = 0.0
    if alternative in ("greater", "two-sided"):
        p = p + stats.norm.sf((c * se_hat - delta) / se)
    if alternative in ("less", "two-sided"):
        p = p + stats.norm.cdf((-c * se_hat - delta) / se)
    return float(np.mean(p))


# ---- the two-sample K-S statistic: exact null distribution -----------------
def _point_values(n1, n2, weight, alternative):
    """The statistic's contribution at every lattice point (i, j): after i
    values of x and j of y (continuous data: every point is a pooled jump
    point).  Points that do not take part are -inf."""
    i = np.arange(n1 + 1)[:, None].astype(float)
    j = np.arange(n2 + 1)[None, :].astype(float)
    N = n1 + n2
    diff = i / n1 - j / n2  # F - G
    if alternative == "two-sided":
        d = np.abs(diff)
    elif alternative == "less":  # x smaller: its CDF above, sup (F - G)
        d = diff
    else:
        d = -diff
    if weight == "none":
        return d
    z = (i + j) / N
    with np.errstate(divide="ignore", invalid="ignore"):
        v = math.sqrt(n1 * n2 / N) * d / np.sqrt(z * (1 - z))
    v[(z <= 0) | (z >= 1)] = -np.inf  # Canner's weight: only 0 < z < 1
    return v


class KSNull:
    """Exact null distribution of the K-S statistic for continuous data:
    all C(n1+n2, n1) label orders equally likely.  The statistic of an order
    is the maximum of the point values along its lattice path (one-sided
    ones at least 0: the end point where F = G counts)."""

    REL = 1e-11  # values closer than this (relative) are the same value

    def __init__(self, n1, n2, weight, alternative):
        self.n1, self.n2 = n1, n2
        self.weight, self.alternative = weight, alternative
        self.pv = _point_values(n1, n2, weight, alternative)
        vals = np.sort(self.pv[np.isfinite(self.pv)].ravel())
        if alternative != "two-sided":
            vals = np.concatenate([[0.0], vals[vals > 0]])
        uniq = [vals[0]]
        for v in vals[1:]:
            if v > uniq[-1] + self.REL * max(1.0, abs(uniq[-1])):
                uniq.append(v)
        self.values = np.array(uniq)
        self.total = math.comb(n1 + n2, n1)
        self._tail = {}

    def _count_below(self, v):
        """Number of lattice paths whose every point value is below v."""
        bad = self.pv >= v - self.REL * max(1.0, abs(v))
        n1, n2 = self.n1, self.n2
        row = [0] * (n2 + 1)
        for i in range(n1 + 1):
            new = [0] * (n2 + 1)
            for j in range(n2 + 1):
                if bad[i, j]:
                    continue
                if i == 0 and j == 0:
                    new[j] = 1
                else:
                    new[j] = (row[j] if i > 0 else 0) + (new[j - 1] if j > 0 else 0)
            row = new
        return row[n2]

    def tail(self, k):
        """P(D >= values[k]) as an exact fraction's float."""
        if k not in self._tail:
            v = self.values[k]
            if self.alternative != "two-sided" and v <= 0:
                self._tail[k] = 1.0
            else:
                self._tail[k] = 1.0 - self._count_below(v) / self.total
        return self._tail[k]

    def pmf(self):
        t = np.array([self.tail(k) for k in range(len(self.values))] + [0.0])
        return t[:-1] - t[1:]

    def _size(self, reject_prob):
        """Size of a test rejecting with probability reject_prob(k) when D =
        values[k]; reject_prob returns (lo, hi) for boundary cases."""
        pm = self.pmf()
        lo = hi = 0.0
        for k, w in enumerate(pm):
            a, b = reject_prob(k)
            lo += w * a
            hi += w * b
        return lo, hi

    @staticmethod
    def _le(p, alpha, tol=1e-9):
        """p <= alpha as (lo, hi): (0, 1) when p is within tol of alpha, where
        a floating-point p-value may fall on either side."""
        if abs(p - alpha) <= tol * alpha:
            return 0.0, 1.0
        return (1.0, 1.0) if p <= alpha else (0.0, 0.0)

    def critical_index(self, alpha):
        """Smallest k with P(D >= values[k]) <= alpha (the exact test rejects
        at D >= values[k]); bisection, the tail being decreasing in k."""
        lo, hi = 0, len(self.values)  # tail(hi) := 0 <= alpha
        while lo < hi:
            mid = (lo + hi) // 2
            if self.tail(mid) <= alpha:
                hi = mid
            else:
                lo = mid + 1
        return lo

    def size_exact(self, alpha):
        """(lo, hi) size of the exact test, p = P(D* >= D) <= alpha; lo == hi
        unless an attainable p-value sits on alpha."""
        k = self.critical_index(alpha)
        hi = self.tail(k) if k < len(self.values) else 0.0
        lo = hi
        if k < len(self.values) and abs(self.tail(k) - alpha) <= 1e-9 * alpha:
            lo = self.tail(k + 1) if k + 1 < len(self.values) else 0.0
        if k > 0 and abs(self.tail(k - 1) - alpha) <= 1e-9 * alpha:
            hi = self.tail(k - 1)
        return lo, hi

    def size_simulate(self, alpha, n_sim):
        """Size of the simulated test, p = (1 + #{D* >= D}) / (n_sim + 1):
        given D = values[k] the count is Binomial(n_sim, tail(k))."""
        top = alpha * (n_sim + 1) - 1  # reject iff count <= top
        assert abs(top - round(top)) > 1e-6, "choose n_sim so that alpha (n_sim + 1) is not an integer"
        m = math.floor(top)

        def rp(k):
            r = float(stats.binom.cdf(m, n_sim, self.tail(k))) if m >= 0 else 0.0
            return r, r

        return self._size(rp)

    def asymptotic_pvalue(self, d):
        """Kolmogorov's limit at sqrt(ne) d, one-sided exp(-2 ne d^2)."""
        ne = self.n1 * self.n2 / (self.n1 + self.n2)
        if self.alternative == "two-sided":
            return float(stats.kstwobign.sf(math.sqrt(ne) * d))
        return min(1.0, math.exp(-2.0 * ne * d * d))

    def size_asymptotic(self, alpha):
        assert self.weight == "none"
        return self._size(lambda k: self._le(self.asymptotic_pvalue(self.values[k]), alpha))


def ks_statistic_rows(x, y, weight, alternative):
    """The K-S statistic of every row pair (continuous data), NumPy: sort
    the pooled row, walk the labels, take the maximum point value."""
    x, y = np.atleast_2d(x), np.atleast_2d(y)
    n1, n2 = x.shape[1], y.shape[1]
    N = n1 + n2
    pooled = np.concatenate([x, y], axis=1)
    order = np.argsort(pooled, axis=1, kind="stable")
    is_x = order < n1
    i = np.cumsum(is_x, axis=1)
    j = np.arange(1, N + 1)[None, :] - i
    diff = i / n1 - j / n2
    d = np.abs(diff) if alternative == "two-sided" else (diff if alternative == "less" else -diff)
    if weight == "canner":
        z = np.arange(1, N + 1)[None, :] / N
        with np.errstate(divide="ignore", invalid="ignore"):
            d = math.sqrt(n1 * n2 / N) * d / np.sqrt(z * (1 - z))
        d = d[:, :-1]  # z = 1 at the last point
    s = d.max(axis=1)
    return np.maximum(s, 0.0) if alternative != "two-sided" else s


# The one budget of the whole stats suite (test_calibration.py, test_stats_power.py).
BUDGET = Budget(total=1e-4, max_checks=2000)
