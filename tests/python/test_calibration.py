"""Calibration: under H0 every test rejects at its size (marker ``stats``).

Each check counts the rejections among R independent replicates under H0
(fixed seeds) and requires the count to lie inside the exact two-sided
binomial acceptance region of Bin(R, size) at the per-check level 1e-4 /
2000 = 5e-8: the suite (this file and test_stats_power.py: 392 checks in this
version, at most 2000, counted by ``stats_oracle.BUDGET``, which fails the
run beyond that) fails by chance with probability at most 1e-4
(Bonferroni).  Where an attainable K-S p-value equals alpha (3 + 3,
one-sided: 1/20) the floating-point comparison may go either way, and
either size is accepted.

The size each count is compared with:

- one-sample t, chi-square variance test, F test: alpha exactly (normal
  data, exact distributions), at n = 2, 3, 5, 30 and pairs down to 2 + 2;
  the two-sided test's rejections split alpha/2 + alpha/2 between its tails;
- Welch's t: its true size for normal data, which is not alpha (the
  Welch-Satterthwaite df is an approximation: 0.0122 at alpha 0.01 for
  12 + 7 values with a 7x variance ratio), computed by quadrature
  (``stats_oracle.welch_rejection``);
- two-sample K-S, weight none and Canner, each alternative, methods exact,
  simulate and (weight none) asymptotic, at 2+2 ... 40+40: the statistic is
  discrete, so the exact size of each procedure, computed from the exact
  permutation distribution by lattice-path counting (``stats_oracle.KSNull``;
  never above alpha for exact and simulate), at sizes where no p-value can
  reach alpha the count must be 0.

The row-wise API (2-D input, one test per row) makes the t and variance
tests cheap: 40000 replicates per call.  K-S has no row-wise call, so it
gets 10000 replicates per configuration.  Confidence intervals are checked to
be the inversion of the test (an interval misses the null value exactly in
the rows that reject).
"""
import zlib

import numpy as np
import pytest

import mcstat
from stats_oracle import BUDGET, KSNull, welch_rejection

pytestmark = pytest.mark.stats

ROWS = 40000
KS_ROWS = 10000
ALPHAS = (0.05, 0.01)
ALTS = ("two-sided", "less", "greater")


def seeded(*key):
    """A stable generator per configuration (hash() is randomised per process)."""
    return np.random.default_rng(zlib.crc32(repr(key).encode()))


def check(k, n, size, what):
    assert BUDGET.accept(k, n, size), (
        f"{what}: {k} rejections of {n} ({k / n:.5f}); expected size {size}, "
        f"acceptance region {BUDGET.region(n, size)}")


def check_batch(b, R, size_of, null, what):
    """The rejection count of each alternative; for two-sided also each tail."""
    for alt in ALTS:
        r = b[alt]
        k = int(r.reject.sum())
        check(k, R, size_of(alt), f"{what} {alt}")
        lo, hi = r.conf_int[..., 0], r.conf_int[..., 1]
        miss = (null < lo) | (null > hi)
        assert np.array_equal(miss, r.reject), f"{what} {alt}: the interval is not the test's inversion"
        if alt == "two-sided":
            below = int((r.decision_code < 0).sum())
            check(below, R, size_of("less-tail"), f"{what} two-sided, lower tail")
            check(k - below, R, size_of("greater-tail"), f"{what} two-sided, upper tail")


def exact_size(alpha):
    return lambda alt: alpha / 2 if alt.endswith("tail") else alpha


@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("n", [2, 3, 5, 30])
def test_one_sample_t(n, alpha):
    X = seeded("t1", n, alpha).normal(2.0, 1.5, size=(ROWS, n))
    b = {alt: mcstat.t_test(X, mu=2.0, alternative=alt, alpha=alpha) for alt in ALTS}
    check_batch(b, ROWS, exact_size(alpha), 2.0, f"t_1 n={n} alpha={alpha}")


@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("n", [2, 3, 5, 30])
def test_one_sample_variance(n, alpha):
    X = seeded("var1", n, alpha).normal(-1.0, 1.5, size=(ROWS, n))
    b = {alt: mcstat.var_test(X, sigma2=2.25, alternative=alt, alpha=alpha) for alt in ALTS}
    check_batch(b, ROWS, exact_size(alpha), 2.25, f"var_1 n={n} alpha={alpha}")


@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("n1,n2,sd2", [(2, 2, 1.5), (2, 3, 1.5), (3, 3, 1.5), (5, 8, 1.5), (30, 20, 1.5),
                                       (7, 4, 3.0)])
def test_f_test(n1, n2, sd2, alpha):
    g = seeded("var2", n1, n2, sd2, alpha)
    X = g.normal(2.0, 1.5, size=(ROWS, n1))
    Y = g.normal(-3.0, sd2, size=(ROWS, n2))
    ratio = 1.5**2 / sd2**2
    b = {alt: mcstat.var_test(X, Y, ratio=ratio, alternative=alt, alpha=alpha) for alt in ALTS}
    check_batch(b, ROWS, exact_size(alpha), ratio, f"var_2 {n1}+{n2} ratio={ratio} alpha={alpha}")


@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("n1,n2,sd1,sd2", [(2, 2, 1.0, 1.0), (2, 3, 1.0, 1.0), (3, 3, 1.0, 2.0),
                                           (5, 8, 1.0, 1.0), (12, 7, 1.5, 4.0), (30, 20, 1.0, 3.0)])
def test_welch(n1, n2, sd1, sd2, alpha):
    g = seeded("t2", n1, n2, sd1, sd2, alpha)
    X = g.normal(2.0, sd1, size=(ROWS, n1))
    Y = g.normal(2.0, sd2, size=(ROWS, n2))
    b = {alt: mcstat.t_test(X, Y, alternative=alt, alpha=alpha) for alt in ALTS}

    # under H0 the statistic is symmetric: each tail at level a has the
    # same probability, and the two-sided test is two tails at alpha / 2
    one = welch_rejection(n1, n2, sd1, sd2, 0.0, "less", alpha)
    half = welch_rejection(n1, n2, sd1, sd2, 0.0, "less", alpha / 2)

    def size(alt):
        return {"less": one, "greater": one, "two-sided": 2 * half}.get(alt, half)

    check_batch(b, ROWS, size, 0.0, f"t_2 {n1}+{n2} sd {sd1}/{sd2} alpha={alpha}")


def test_welch_size_oracle_against_known_values():
    """The quadrature reproduces the size that the previous version of this
    file measured by 1e6 replicates (12 vs 7 values, sd 1.5 vs 4), and alpha
    where Welch's statistic is an exact t: as sd1 -> 0 it becomes the
    one-sample t of y, with df n2 - 1."""
    assert abs(welch_rejection(12, 7, 1.5, 4.0, 0.0, "two-sided", 0.01) - 0.0122) < 3e-4
    assert abs(welch_rejection(12, 7, 1.5, 4.0, 0.0, "two-sided", 0.05) - 0.0528) < 6e-4
    # sd1 -> 0: T is the one-sample t of y with df -> n2 - 1, size -> alpha
    assert abs(welch_rejection(6, 6, 1e-6, 1.0, 0.0, "greater", 0.05) - 0.05) < 1e-4


# ---- two-sample Kolmogorov-Smirnov ---------------------------------------------
KS_SIZES = [(2, 2), (2, 3), (3, 3), (5, 7), (10, 10), (20, 15), (40, 40)]
KS_ALPHA = 0.05
N_SIM = 250  # alpha (n_sim + 1) = 12.55: no p-value sits on alpha


@pytest.mark.parametrize("weight", ["none", "canner"])
@pytest.mark.parametrize("n1,n2", KS_SIZES)
def test_ks(n1, n2, weight):
    g = seeded("ks", n1, n2, weight)
    X = g.normal(size=(KS_ROWS, n1))
    Y = g.normal(size=(KS_ROWS, n2))
    methods = ["exact", "simulate"] + (["asymptotic"] if weight == "none" else [])
    for alt in ALTS:
        null = KSNull(n1, n2, weight, alt)
        for method in methods:
            if method == "exact":
                size = null.size_exact(KS_ALPHA)
            elif method == "simulate":
                size = null.size_simulate(KS_ALPHA, N_SIM)
            else:
                size = null.size_asymptotic(KS_ALPHA)
            if method != "asymptotic":
                assert size[1] <= KS_ALPHA + 1e-12  # valid by construction
            k = 0
            for i in range(KS_ROWS):
                # n_sim and seed apply to the simulation only (ks_test refuses them elsewhere)
                sim = {"n_sim": N_SIM, "seed": i} if method == "simulate" else {}
                r = mcstat.ks_test(X[i], Y[i], weight=weight, alternative=alt, alpha=KS_ALPHA,
                                   method=method, threads=1, critical=False, **sim)
                k += bool(r.reject)
            check(k, KS_ROWS, size, f"ks {weight} {method} {n1}+{n2} {alt}")


def test_ks_exact_sizes_at_tiny_sizes():
    """The oracle against hand-checkable closed forms: with 2 + 2 values no
    arrangement is rarer than 1/6, so nothing rejects at 0.05; with n + n
    values the one-sided unweighted statistic has P(D+ >= k/n) =
    C(2n, n - k) / C(2n, n) (the reflection principle)."""
    from math import comb
    for alt in ALTS:
        assert KSNull(2, 2, "none", alt).size_exact(0.05) == (0.0, 0.0)
    null = KSNull(5, 5, "none", "less")
    for k in range(1, 6):
        kk = int(np.searchsorted(null.values, k / 5 - 1e-12))
        assert abs(null.tail(kk) - comb(10, 5 - k) / comb(10, 5)) < 1e-15
