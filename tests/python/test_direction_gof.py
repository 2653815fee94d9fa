# The chi-squared route for direction samplers: equal-probability cells
# (estimators.direction_cells), planted sampler bugs (BRDFPlan.sample_bug)
# and estimators.direction_gof.
import numpy as np
import pytest
from scipy import stats

import mcstat
from mcstat import estimators as est


def wo_of(theta, phi):
    t, p = np.radians(theta), np.radians(phi)
    return [np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)]


# the paper scene's BRDFs (mcstat_app.reproduce.scene.PAPER_SCENE) and a mixture
PLANS = {
    "ward": lambda: est.ward(0.0, 0.6, 0.2, 0.05).plan(wo_of(70, 40)),
    "ashikhmin_shirley": lambda: est.ashikhmin_shirley(0.0, 0.2, 50, 500).plan(wo_of(30, 40)),
    "ward_mixture": lambda: est.ward(0.3, 0.5, 0.3, 0.1).plan(wo_of(45, 10)),
}


@pytest.fixture(scope="module")
def cells():
    return {name: (make(), est.direction_cells(make(), 6)) for name, make in PLANS.items()}


def test_cells_cosine_closed_form():
    # rho_s = 0: the sampler is cosine-weighted, P(cell) = 4 dt [s - s^2] on s <= 1/2
    plan = est.ward(0.5, 0.0, 0.3, 0.3).plan([0.3, 0.2, 0.9])
    c = est.direction_cells(plan, 5, rel_tol=1e-10)
    b = c.bounds()
    s0, s1 = np.minimum(b[:, 0], 0.5), np.minimum(b[:, 1], 0.5)
    exact = 4 * (b[:, 3] - b[:, 2]) * ((s1 - s1**2) - (s0 - s0**2))
    assert np.max(np.abs(c.prob - exact)) < 1e-12
    assert np.all(np.abs(c.prob * 32 - 1) < 0.3)


@pytest.mark.parametrize("name", list(PLANS))
def test_cells_sum_and_partition(cells, name):
    plan, c = cells[name]
    assert abs(c.prob.sum() - 1) < 1e-7
    assert np.all(np.abs(c.prob * 64 - 1) < 0.3)
    b = c.bounds()
    assert abs(((b[:, 1] - b[:, 0]) * (b[:, 3] - b[:, 2])).sum() - 1) < 1e-12
    w = plan.sample(3000, seed=5).directions
    loc = c.locate(w)
    st = est.direction_square(w)
    r = b[loc]
    assert np.all((st[:, 0] >= r[:, 0]) & (st[:, 0] <= r[:, 1]) & (st[:, 1] >= r[:, 2]) & (st[:, 1] <= r[:, 3]))
    assert np.array_equal(c.counts(w), np.bincount(loc, minlength=64).astype(float))


@pytest.mark.parametrize("name", list(PLANS))
def test_cells_against_monte_carlo(cells, name):
    # an independent check of the cubature: frequencies of 400000 directions
    # from the correct sampler, cell by cell, within 5 binomial sd
    plan, c = cells[name]
    n = 400000
    f = c.counts(plan.sample(n, seed=77).directions) / n
    sd = np.sqrt(c.prob * (1 - c.prob) / n)
    assert np.all(np.abs(f - c.prob) < 5 * sd + 1e-12)


@pytest.mark.parametrize("name", list(PLANS))
def test_calibration(cells, name):
    plan, c = cells[name]
    runs, n = 300, 2000
    rej = sum(est.direction_gof(plan.sample(n, seed=1000 + r).directions, cells=c).reject for r in range(runs))
    lo, hi = stats.binom.ppf([0.0005, 0.9995], runs, 0.05)
    assert lo <= rej <= hi, rej


@pytest.mark.parametrize("name", list(PLANS))
@pytest.mark.parametrize("bug", est.SAMPLER_BUGS)
def test_bugs_caught(cells, name, bug):
    plan, c = cells[name]
    rej = sum(est.direction_gof(plan.sample_bug(20000, bug, seed=r).directions, cells=c, alpha=0.01).reject
              for r in range(10))
    assert rej >= 9


def test_sample_bug_none_is_sample():
    plan = PLANS["ward"]()
    a = plan.sample_bug(100, None, seed=3, first_index=5)
    b = plan.sample(100, seed=3, first_index=5)
    assert np.array_equal(a.directions, b.directions)
    assert np.allclose(a.pdf, b.pdf, rtol=1e-13, atol=0)  # pdf of the renormalised direction
    assert np.array_equal(a.keys, b.keys)
    # threads never change the numbers
    x = plan.sample_bug(20000, "jacobian", seed=3, threads=1)
    y = plan.sample_bug(20000, "jacobian", seed=3, threads=2)
    assert np.array_equal(x.directions, y.directions)
    # the pdf reported is the claimed (correct) density
    assert np.allclose(x.pdf, plan.pdf(x.directions), rtol=0, atol=0)


def test_direction_gof_defaults():
    plan = PLANS["ashikhmin_shirley"]()
    w = plan.sample(5000, seed=9).directions
    r = est.direction_gof(w, plan)
    assert r.method == "Chi-squared test for given probabilities"
    assert r.nobs == 5000
    assert 2 ** est.default_depth(5000) >= r.cells
    assert est.default_depth(10) == 2 and est.default_depth(10**9) == 12
    assert est.default_depth(5000) == 6


def test_bad_input():
    plan = PLANS["ward"]()
    with pytest.raises(est.InvalidEstimatorArgument):
        plan.sample_bug(10, "nope")
    with pytest.raises(TypeError):
        plan.sample_bug(10, 3)
    with pytest.raises(est.InvalidEstimatorArgument):
        est.direction_cells(plan, 0)
    with pytest.raises(est.InvalidEstimatorArgument):
        est.direction_cells(plan, 13)
    with pytest.raises(est.InvalidEstimatorArgument):
        est.direction_cells(plan, 4, rel_tol=0.5)
    c = est.direction_cells(plan, 3)
    with pytest.raises(est.InvalidEstimatorArgument):
        c.counts([[0.0, 0.0, 0.0]])
    with pytest.raises(est.InvalidEstimatorArgument):
        c.counts([[np.nan, 0.0, 1.0]])
    with pytest.raises(est.InvalidEstimatorArgument):
        c.counts([[0.0, 1.0]])
    with pytest.raises(est.InvalidEstimatorArgument):
        est.cells_count(c.split[:-1], 3, [[0.0, 0.0, 1.0]])
    with pytest.raises(est.InvalidEstimatorArgument):
        est.direction_gof([[0.0, 0.0, 1.0]])
    with pytest.raises(mcstat.TooFewObservationsError):
        est.direction_gof(np.zeros((0, 3)), cells=c)
    with pytest.raises(mcstat.InvalidArgumentError):
        est.direction_gof(plan.sample(100).directions, cells=c, alpha=2.0)
