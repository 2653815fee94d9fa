# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Estimated run time of the studies' steps, for the progress bars only.

A bar that counts steps is wrong when steps differ by orders of magnitude:
in 3.2 the first K-S test at n = 1e5 simulates the null distribution
(seconds; the later runs at that size reuse it from the cache), so a bar
counting (size, run) steps stood at 94% with most of the time still to go.
Each study gives its bar the sum of its steps' estimates and advances it by
each step's estimate.

The constants are seconds on one core of the development machine (x86-64,
2 cores), measured once with ``time.perf_counter`` around the calls; only
their ratios matter.  Nothing but the bars reads them: results never depend
on them, and a wrong constant only makes a bar uneven.
"""
from __future__ import annotations

# A primary irradiance estimate (the timing study's wall time per estimate).
ESTIMATE = {"U": 53e-9, "C": 53e-9, "A": 20e-9, "S": 49e-9}
ESTIMATE_DEFAULT = 50e-9

# One direction from a BRDF's sampler plus one from the exact rejection
# sampler and both Morton keys (Ward: 195 + 328 + 2 x 27 ns; Ashikhmin-Shirley
# about the same).
DIRECTION_PAIR = 0.6e-6
# One direction and its key, the sampler alone (3.2+: a variant and the reference).
DIRECTION = 0.25e-6
# One direction binned into the chi-squared cells (direction_gof), and the
# equal-probability cells of one depth (direction_cells: 35-100 ms).
GOF = 0.05e-6
CELLS = 0.07
# What every step costs besides its samples: Python calls, small arrays.
STEP = 1e-4

# One look of a sequential test (SequentialTest.push of 100 + 100 values), and
# one look of the peeked fixed-n test per run (MomentsArray pushes, batch Welch).
SEQ_LOOK = 2.2e-6
NAIVE_LOOK = 1.6e-6

# K-S (Canner): the p-value method `method="auto"` picks, MCSTAT_KS_AUTO_EXACT_WORK
# in mcstat.h: exact when (min(nx, ny) + 1)(nx + ny + 1) is at most this.
KS_AUTO_EXACT_WORK = 1.6e7
KS_EXACT = 1.4e-10      # per unit of that work: the p-value
KS_EXACT_CRITICAL = 6e-9  # the same with the critical value (critical=True)
KS_STATISTIC = 5e-8     # per value: sorting, the statistic, a cached p-value
KS_REPLICATE = 6.5e-10  # per value and simulated replicate, up to N = 6e4 values
KS_REPLICATE_N = 6e4    # beyond, per replicate cost grows as N^2 (caches):
#                         8.9 s for 20000 replicates at 1e5 + 1e5 against 0.77 s at 3e4 + 3e4


def estimates(kind: str, n: float) -> float:
    """n primary estimates of the irradiance estimator `kind`."""
    return n * ESTIMATE.get(kind, ESTIMATE_DEFAULT)


def ks(nx: int, ny: int, n_sim: int, *, simulate_null: bool = True, method: str = "auto",
       critical: bool = True) -> float:
    """One two-sample K-S test with Canner's weight.  With a simulated
    p-value, `simulate_null` says whether this test simulates the null
    distribution (False: a KSCache already holds it for these sizes)."""
    big = nx + ny
    work = (min(nx, ny) + 1.0) * (big + 1.0)
    if method == "exact" or (method == "auto" and work <= KS_AUTO_EXACT_WORK):
        return STEP + (KS_EXACT_CRITICAL if critical else KS_EXACT) * work
    t = STEP + KS_STATISTIC * big
    if simulate_null:
        t += n_sim * big * KS_REPLICATE * max(1.0, big / KS_REPLICATE_N)
    return t
