"""bench/bench_power.py's referees, checked small: the re-implemented chi2
tests of Mitsuba 3 (chi2.py) and pbrt-v4 (bsdfs_test.cpp) hold their level
on a correct Henyey-Greenstein sampler and reject one whose g is 5% high;
the likelihood-ratio oracle's critical value holds its level under H0 and
its power at the analytic n90 is near 0.9; and the bench's --quick run
finds the oracle no worse than mcstat's check (a check that beat the
Neyman-Pearson test would mean a wrong oracle).

Fixed seeds throughout: the counts are deterministic.  Bounds: a test at
alpha = 0.01 run 20 times rejects Binomial(20, <= 0.01) times, at most 3 at
a meta-level of 0.001.
"""
import os
import sys

import numpy as np
import pytest
from scipy.stats import binom

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "bench"))
import bench_power as bp  # noqa: E402

pytestmark = pytest.mark.stats

SEEDS = 20
BOUND = int(binom.ppf(0.999, SEEDS, 0.01))
WI = bp.direction(30.0)


def _draws(model, n, seed):
    return model.draw(np.random.default_rng([seed, 5]).random((n, 3)))


def test_chi2_peers_hold_their_level_and_see_a_sampler_bug():
    hg, bug = bp.HG(0.7, WI), bp.HG(0.735, WI)
    mt, pt = bp.MitsubaChi2(hg), bp.PbrtChi2(hg)
    n = 50_000
    false_mi = sum(mt.reject(*_draws(hg, n, s), n) for s in range(SEEDS))
    false_pb = sum(pt.reject_run(*_draws(hg, n, s), n) for s in range(SEEDS))
    assert false_mi <= BOUND and false_pb <= BOUND, (false_mi, false_pb)
    assert sum(mt.reject(*_draws(bug, n, s), n) for s in range(SEEDS)) >= 18
    assert sum(pt.reject_run(*_draws(bug, n, s), n) for s in range(SEEDS)) >= 18


def test_lr_oracle_level_and_power():
    hg, bug = bp.HG(0.7, WI), bp.HG(0.735, WI)
    o = bp.LROracle(bug, hg, 400_000)
    o.claim_sampler = hg
    n = int(round(o.n90()))
    assert 300 < n < 3000, n
    assert sum(o.reject(n, s, null=True) for s in range(200)) <= int(binom.ppf(0.999, 200, 0.01))
    k = sum(o.reject(n, s) for s in range(200))
    assert 0.8 * 200 <= k <= 0.97 * 200, k


def test_quick_run_oracle_is_no_worse_than_the_check():
    rows = bp.main(["--quick", "--only", "HG g=0.7 / sampler g x1.05", "--no-chi2"])
    (case, res, *_), = rows
    m, o = res["mcstat"]["n90"], res["oracle"]["n90"]
    assert o is not None and (m is None or o <= m), (m, o)
