"""mcstat reproduce's study of sequential tests on the planted bugs (3.4+):
its stopping times, fixed-n comparison and H0 rates against direct
recomputations from the same seed streams, its planner rule and
reproducibility."""
import copy

import numpy as np
import pytest

import mcstat
from mcstat_app.reproduce import PAPER_SCENE, Plan, parse_scene
from mcstat_app.reproduce import results as R
from mcstat_app.reproduce import sequential
from mcstat_app.reproduce.context import Context
from mcstat_app.reproduce.irradiance import ReceiverEstimators

SMALL = {"runs": 6, "h0_runs": 30, "batch": 50, "max_n": 1000, "pilot": 20000}


def small_plan(**extra):
    doc = copy.deepcopy(PAPER_SCENE)
    doc["studies"] = {"sequential": dict(SMALL, **extra)}
    return Plan(parse_scene(doc, "test"))


@pytest.fixture(scope="module")
def small():
    plan = small_plan()
    ctx = Context(7, progress=False, out=open("/dev/null", "w"))
    return plan, ctx, sequential.run(ctx, plan)


def _test_of(x, y, batch, p):
    s = mcstat.SequentialTest("mean2", alpha=p["alpha"], t_opt=p["t_opt"], min_n=sequential.MIN_N)
    for j in range(0, x.size, batch):
        s.push(x[j:j + batch], y[j:j + batch])
        if s.decided:
            break
    return s


def test_stopping_times_match_a_direct_recomputation(small):
    plan, ctx, res = small
    p = plan.params["sequential"]
    B, nmax = res["batch"], res["max_n"]
    assert (B, nmax, res["looks"]) == (50, 1000, 20)
    rec = ReceiverEstimators(Context(7, progress=False), plan, 0, "sequential")
    S = rec.primaries("S", 3 * nmax, 0).reshape(3, nmax)
    for v in res["bugs"]:
        s = res["per_bug"][v]
        assert len(s["stops"]) == 6 and sum(s["decisions"].values()) == 6
        assert s["decided"] == sum(x is not None for x in s["stops"])
        for t in s["stops"]:
            assert t is None or (t % B == 0 and sequential.MIN_N <= t <= nmax)
        A = rec.primaries("A", 3 * nmax, 0, v).reshape(3, nmax)
        for i in range(3):  # run i draws [i max_n, (i + 1) max_n) of each estimator
            t = _test_of(A[i], S[i], B, p)
            assert s["stops"][i] == (t.n_decided if t.decided else None)
        # the bugs of the paper scene are decided, in the direction of the pilot's difference
        assert s["decided"] == 6 and s["correct"] == 6
        assert s["median"] == sorted(s["stops"])[2]  # inverted-cdf median of 6 values: the 3rd


def test_fixed_n_is_mcstat_power_at_the_pilot_effect(small):
    plan, _, res = small
    for v in res["bugs"]:
        pil, f = res["pilot"]["bugs"][v], res["per_bug"][v]["fixed"]
        want = mcstat.power("welch", n=None, effect=abs(pil["effect"]), alpha=res["alpha"], power=0.9,
                            sd_ratio=pil["sd_ratio"]).n
        assert f["n"] == max(2, want) and f["check"]["tests"] == 30
        assert f["check"]["rejections"] == f["check"]["decided"][pil["direction"]]
        assert res["per_bug"][v]["median_over_fixed"] == res["per_bug"][v]["median"] / f["n"]
    assert res["pilot"]["bugs"]["no_cosine"]["direction"] == "greater"
    assert res["pilot"]["bugs"]["barycentric"]["direction"] == "less"


def test_h0_first_rejections_match_a_direct_recomputation(small):
    plan, _, res = small
    p = plan.params["sequential"]
    B, nmax, looks = res["batch"], res["max_n"], res["looks"]
    rec = ReceiverEstimators(Context(7, progress=False), plan, 0, "sequential")
    R_ = res["h0_runs"]
    A = rec.primaries("A", R_ * nmax, 0).reshape(R_, nmax)
    S = rec.primaries("S", R_ * nmax, 0).reshape(R_, nmax)
    h = res["h0"]
    for i in range(R_):
        # the naive test: Welch's test of the cumulative samples at every look, first p <= alpha
        naive = next((j for j in range(looks)
                      if mcstat.t_test(A[i, :(j + 1) * B], S[i, :(j + 1) * B], alpha=res["alpha"]).reject), -1)
        assert h["naive"]["first_look"][i] == naive, i
        t = _test_of(A[i], S[i], B, p)
        assert h["sequential"]["first_look"][i] == (t.n_decided // B - 1 if t.decided else -1), i
    for name in ("sequential", "naive"):
        first = np.array(h[name]["first_look"])
        assert h[name]["rejections"] == int(np.sum(first >= 0)) and h[name]["tests"] == R_
        curve = np.array(h[name]["curve"])
        assert curve.size == looks and np.all(np.diff(curve) >= 0)
        assert curve[-1] == pytest.approx(h[name]["rate"])
    # looking at every batch, the fixed-n test rejects a true H0 at least as often as the sequential one
    assert h["naive"]["rejections"] >= h["sequential"]["rejections"]


def test_reproducible_and_written(small):
    plan, _, res = small
    again = sequential.run(Context(7, progress=False, out=open("/dev/null", "w")), plan)
    assert R.dumps(res) == R.dumps(again)
    other = sequential.run(Context(8, progress=False, out=open("/dev/null", "w")), plan)
    assert other["pilot"] != res["pilot"]
    text = "\n".join(sequential.findings(res))
    assert text.count("3.4+ at origin") == 5 and "under H0" in text


def test_plan_rule():
    doc = copy.deepcopy(PAPER_SCENE)
    doc["estimators"], doc["trusted"] = ["C", "S"], "S"
    plan = Plan(parse_scene(doc))
    assert not plan.runs("sequential")
    assert any(s["study"] == "sequential" and "estimator A" in s["reason"] for s in plan.left_out)
    doc = copy.deepcopy(PAPER_SCENE)
    doc["studies"] = {"sequential": {"enabled": False}}
    assert not Plan(parse_scene(doc)).runs("sequential")
    quick = Plan(parse_scene(copy.deepcopy(PAPER_SCENE)), quick=True).params["sequential"]
    assert (quick["runs"], quick["h0_runs"], quick["pilot"]) == (40, 500, 200000)
    # a budget below one batch is one batch
    plan = small_plan(max_n=20)
    assert "up to 50," in next(s["what"] for s in plan.steps if s["study"] == "sequential")
