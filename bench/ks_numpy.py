#!/usr/bin/env python3
"""The Python baselines of bench/RESULTS_ks.md, measured in the same run as
ks_bench: a straightforward NumPy simulation of the two-sample K-S null
distribution (uniforms, argsort, cumulative sums) per replicate at
1000 + 1000, and scipy.stats.ks_2samp(method="asymp") on 1e6 + 1e6 values.
Times are medians [fastest-slowest] (bench/common.py).
Usage: .venv/bin/python bench/ks_numpy.py
"""
import os
import sys

import numpy as np
import scipy
from scipy import stats

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import measure  # noqa: E402


def numpy_replicates(n1, n2, reps, rng):
    N = n1 + n2
    z = np.concatenate([np.full(n1, 1.0 / n1), np.full(n2, -1.0 / n2)])
    z_n = np.sqrt(np.arange(1, N) * (N - np.arange(1, N))) / N  # Canner's sqrt(z(1-z))
    out = np.empty(reps)
    for k in range(reps):
        order = np.argsort(rng.random(N))
        d = np.cumsum(z[order])[:-1]
        out[k] = np.max(np.abs(d) / z_n)
    return out


def best(f, k):
    """Median time of one call of f over k calls."""
    return measure(f, k, 1)


def main():
    rng = np.random.default_rng(1)
    reps = 2000
    t = best(lambda: numpy_replicates(1000, 1000, reps, rng), 3)
    print(f"numpy simulation, 1000+1000: {1e6 * t.median / reps:.1f} us per replicate "
          f"[{1e6 * t.lo / reps:.1f}-{1e6 * t.hi / reps:.1f}] (numpy {np.__version__})")
    x = rng.standard_normal(1000000)
    y = rng.standard_normal(1000000) + 0.002
    t = best(lambda: stats.ks_2samp(x, y, method="asymp"), 3)
    r = stats.ks_2samp(x, y, method="asymp")
    print(f"scipy ks_2samp asymp, 1e6+1e6: {t.fmt('ms')} (D = {r.statistic:.6g}, p = {r.pvalue:.4g}, scipy {scipy.__version__})")


if __name__ == "__main__":
    main()
