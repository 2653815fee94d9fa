# The render guards of mcstat.image.compare (libmcstat's MCSTAT_PIXELS_RENDER):
# the per-image false alarm on render-shaped unbiased pairs against a binomial
# bound, the floor's numbers against closed forms computed here, power on a
# planted change.  Fixed seeds only: every number below is deterministic.
import os
import sys

import numpy as np
import pytest
from scipy import stats

import mcstat.image as mi
from mcstat import _core

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "bench"))
from bench_pixels_null import generate  # noqa: E402

ALPHA = 0.05
MIX = (0.10, 0.40, 0.35, 0.15, 0.0)  # dark, sparse, smooth, firefly (no hidden: see the bench)


def _flags(ref, cand, **kw):
    r = mi.compare(ref, cand, seed_axis=0, **kw)
    return np.asarray(r.decision)[..., 0] != 0


@pytest.mark.parametrize("k", [4, 16])
def test_false_alarm_within_binomial_bound(k):
    # 40 images of 64 x 64 per K: the guards' per-image false alarms must be
    # consistent with a rate <= alpha: at most the 99.9% quantile of
    # Binomial(40, alpha) (meta-level 0.001 for a rate exactly alpha).  At
    # K = 16 the plain Welch test on the same images exceeds it (the defect).
    n = 40
    bound = int(stats.binom.ppf(0.999, n, ALPHA))
    after = before = 0
    for i in range(n):
        ref, cand, _, _ = generate(np.random.default_rng(7_000_000 + 1000 * k + i), k, classes=MIX)
        after += bool(_flags(ref, cand).any())
        before += bool(_flags(ref, cand, render_guards=False).any())
    assert after <= bound, (after, bound)
    if k == 16:
        assert before > bound, (before, bound)


def test_floor_against_closed_form():
    rng = np.random.default_rng(3)
    k = 8
    y = rng.gamma(4.0, 0.25, (k, 3, 3)).astype(np.float32)
    x = np.zeros_like(y)
    x[2, 1, 1] = 4.0  # one nonzero value: floored as a constant side
    x[:, 2, 2] = 0.5
    y[:, 2, 2] = 0.75  # both constant, different
    r = _core._t_test_2_pixels(x, y, None, 0, 0.05, render=True)
    pi = 1.0 - 0.05 ** (1.0 / k)
    for idx in [(0, 0), (1, 1)]:
        xs, ys = x[(slice(None),) + idx].astype(np.float64), y[(slice(None),) + idx].astype(np.float64)
        d = xs.mean() - ys.mean()
        vx = max(xs.var(ddof=1), d * d * (1 - pi) / pi)
        t = d / np.sqrt(vx / k + ys.var(ddof=1) / k)
        assert r["statistic"][idx] == pytest.approx(t, rel=1e-12)
        assert r["df"][idx] == k - 1
        assert r["pvalue"][idx] == pytest.approx(2 * stats.t.sf(abs(t), k - 1), rel=1e-9)
        assert abs(t) <= np.sqrt(k * pi / (1 - pi)) * (1 + 1e-12)
    # both constant and different (0.5 and 0.75 in every seed): not taken for
    # a deterministic difference; both sides floored, t = d / sqrt(2 d^2 r / k)
    r3 = (1 - pi) / pi
    assert r["statistic"][2, 2] == pytest.approx(-1.0 / np.sqrt(2 * r3 / k), rel=1e-12)
    assert r["pvalue"][2, 2] > 0.05
    # without the guards the zero side is a one-sample test of y
    plain = _core._t_test_2_pixels(x, y, None, 0, 0.05)
    assert plain["pvalue"][0, 0] < 0.01 < 0.05 < r["pvalue"][0, 0]
    assert plain["status"][2, 2] != 0
    # the numerical floor: float32 resolution, stated on the result
    res = mi.compare(y, x, seed_axis=0)
    assert res.resolution == _core.RESOLUTION_FLOAT32 == 2.0 ** -18
    assert res.rejections == 0
    assert mi.compare(y.astype(np.float64), x.astype(np.float64), seed_axis=0).resolution == 2.0 ** -47


def test_numerical_floor_spread_at_rounding_is_constant():
    # y constant at 1; x at 1 with one value 1 ulp above (float32): within
    # the floor both sides are constant and equal, so the pixel is not
    # tested; with a stated resolution below the ulp it is a tested (floored) side
    k = 8
    y = np.ones((k, 1, 1), np.float32)
    x = y.copy()
    x[0] = np.nextafter(np.float32(1), np.float32(2))
    r = _core._t_test_2_pixels(x, y, None, 0, 0.05, render=True)
    assert r["status"][0, 0] == 4  # MCSTAT_EDEGENERATE
    r = _core._t_test_2_pixels(x, y, None, 0, 0.05, render=True, resolution=1e-9)
    assert r["status"][0, 0] == 0 and r["pvalue"][0, 0] > 0.05


def test_power_on_a_planted_change():
    # x1.05 on a 16 x 16 region at K = 16: the guards flag changed pixels
    # and nothing else on these fixed images
    hit = tot = false = 0
    for i in range(4):
        ref, cand, ch, _ = generate(np.random.default_rng(9_000 + i), 16, classes=MIX,
                                    change=(1.05, np.s_[24:40, 24:40]))
        f = _flags(ref, cand)
        hit += int(np.count_nonzero(f & ch))
        tot += int(np.count_nonzero(ch))
        false += int(np.count_nonzero(f & ~ch))
    assert hit >= 0.1 * tot, (hit, tot)
    assert false <= 0.05 * max(1, hit)
