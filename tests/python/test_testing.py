"""mcstat.testing: seeds, the suite budget, escalation, the assertions and
image equivalence, against closed forms and by calibration (fixed seeds
throughout: every outcome below is deterministic)."""
import math

import numpy as np
import pytest

import mcstat
from mcstat import testing as mt
from mcstat.image import equivalence
from mcstat.testing import _seeds

# 4.5 binomial standard deviations: a correct test fails its seed once in ~3e5
Z = 4.5


def within(k, n, p):
    return abs(k - n * p) <= Z * math.sqrt(n * p * (1 - p))


# ---- seeds: the published constants of FNV-1a and SplitMix64 --------------------------
def test_fnv1a64_known_values():
    assert _seeds.fnv1a64(b"") == 0xCBF29CE484222325
    assert _seeds.fnv1a64(b"a") == 0xAF63DC4C8601EC8C
    assert _seeds.fnv1a64(b"foobar") == 0x85944171F73967E8


def test_splitmix64_known_values():
    # the first outputs of SplitMix64 from state 0 (state advances by the gamma each step)
    g = 0x9E3779B97F4A7C15
    assert _seeds.splitmix64(0) == 0xE220A8397B1DCDAF
    assert _seeds.splitmix64(g) == 0x6E789E6AA1B965F4
    assert _seeds.splitmix64(2 * g % 2**64) == 0x06C45D188009454F


def test_data_seed_same_as_cpp_and_apart_from_the_checks():
    # examples/testing_cpp/gtest_header.cpp holds the same two values
    assert _seeds.data_seed(7, "Seeds.DataSeedSameAsPython", "estimates") == 0xD289FAD8DEAAF501
    assert _seeds.data_seed(7, "Seeds.DataSeedSameAsPython", "") == 0x7C029715620F6239
    assert _seeds.data_seed(7, "n", "a") == _seeds.splitmix64(7 ^ _seeds.fnv1a64(b"n#data:a"))
    sc = mt.Scope(name="t.py::test_x", alpha=0.01, master_seed=5)
    assert sc.data_seed("a") == _seeds.data_seed(5, "t.py::test_x", "a") != sc.data_seed("b")
    assert sc.data_seed() not in {mt.check_seed(5, "t.py::test_x", j) for j in range(16)}
    assert sc.rng("a").random() == sc.rng("a").random()


def test_check_seed_is_a_function_of_master_name_index():
    s = mt.check_seed(7, "t.py::test_x[1]", 0)
    assert s == _seeds.splitmix64(7 ^ _seeds.fnv1a64(b"t.py::test_x[1]#0"))
    assert s == mt.check_seed(7, "t.py::test_x[1]", 0)
    assert len({mt.check_seed(m, n, j) for m in (0, 1) for n in ("a", "b") for j in (0, 1)}) == 8
    assert mt.stage2_seed(s) == _seeds.splitmix64(s + 1)
    with pytest.raises(ValueError, match="master seed"):
        mt.check_seed(-1, "a", 0)


# ---- the budget --------------------------------------------------------------------
def test_shares_split_alpha_by_weight_and_checks():
    s = mt.Suite(alpha=1e-3)
    s.allocate([("a", 1.0, 1), ("b", 2.0, 4), ("c", 1.0, 1)])
    assert s.shares["a"] == pytest.approx(2.5e-4, rel=1e-15)
    assert s.shares["b"] == pytest.approx(5e-4, rel=1e-15)
    assert math.fsum(s.shares.values()) == pytest.approx(1e-3, rel=1e-15)
    sc = s.scope("b")
    alphas = [sc.next_check("k")[1] for _ in range(4)]
    assert alphas == [pytest.approx(1.25e-4, rel=1e-15)] * 4
    with pytest.raises(mt.BudgetError, match="one more than the 4"):
        sc.next_check("k")
    with pytest.raises(mt.BudgetError, match="not one of the suite"):
        s.scope("d")


@pytest.mark.parametrize("kw, what", [({"alpha": 0}, "alpha"), ({"alpha": 1.5}, "alpha"),
                                      ({"alpha": 0.01, "master_seed": -1}, "master seed"),
                                      ({"alpha": 0.01, "escalate": 0.5}, "escalate"),
                                      ({"alpha": 0.01, "alpha0": 0}, "alpha0")])
def test_suite_refuses_bad_settings(kw, what):
    with pytest.raises(mcstat.InvalidArgumentError, match=what):
        mt.Suite(**kw)


def test_assertion_outside_a_budget_needs_alpha():
    with pytest.raises(mt.BudgetError, match="pass alpha="):
        mt.assert_unbiased(np.ones(10), 1.0)


def test_explicit_alpha_may_not_exceed_the_share():
    with mt.scope("x", alpha=1e-4):
        with pytest.raises(mt.BudgetError, match="exceeds"):
            mt.assert_unbiased(np.random.default_rng(1).normal(size=100), 0.0, alpha=1e-3)


# ---- escalation (the C design through Python) ------------------------------------------------
def test_escalation_design_numbers():
    e = mcstat.Escalation(0.05, 0.5, 0.5)
    assert e.alpha1 == 0.025 and e.alpha0 == 0.5
    assert e.c == pytest.approx(0.025 / math.log(20.0), rel=1e-15)
    assert e.decide(0.025) == "reject" and e.decide(0.5) == "continue" and e.decide(0.6) == "pass"
    assert e.decide(0.1, 0.9 * e.c / 0.1) == "reject" and e.decide(0.1, 1.1 * e.c / 0.1) == "pass"


@pytest.mark.parametrize("args, what", [((0.0,), "alpha"), ((0.05, 1.0), "share1"), ((0.05, 0.5, 0.01), "alpha0"),
                                        ((0.5, 0.5, 0.3), "too narrow")])
def test_escalation_refusals_name_the_argument(args, what):
    with pytest.raises(mcstat.InvalidArgumentError, match=what):
        mcstat.Escalation(*args)


def test_escalation_decide_refusals():
    e = mcstat.Escalation(0.01)
    for p1, p2, what in [(float("nan"), None, "p1"), (1.5, None, "p1"), (0.03, 2.0, "p2"), (0.9, 0.1, "decided")]:
        with pytest.raises(mcstat.InvalidArgumentError, match=what):
            e.decide(p1, p2)


def _normal_draw(mu):
    def draw(n, seed):
        return np.random.default_rng(seed).normal(mu, 1.0, n)
    return draw


def test_escalated_unbiased_is_calibrated_and_escalates_at_the_band_rate():
    """H0 true, exact t p-values: the two-stage check rejects at alpha and
    escalates with probability alpha0 - alpha1 (binomial bounds, 4000 seeds)."""
    alpha, runs = 0.05, 4000
    rej = esc = 0
    for seed in range(runs):
        with mt.scope("calibration", alpha=alpha, master_seed=seed) as sc:
            try:
                mt.assert_unbiased(_normal_draw(0.0), 0.0, n=50)
            except mt.StatisticalAssertionError:
                rej += 1
            esc += sc.records[0].stages == 2
    d = mcstat.Escalation(alpha, 0.5, max(0.05, math.e * alpha / 2 * 2))
    assert within(rej, runs, alpha), rej
    assert within(esc, runs, d.alpha0 - d.alpha1), esc


def test_escalation_finds_a_borderline_bias_that_one_stage_misses():
    """A bias whose stage-1 p-value falls in the band is confirmed on stage 2:
    at the same alpha, the two-stage check rejects more often than the
    one-stage check on stage 1's samples (200 seeds, deterministic)."""
    alpha, n, runs = 1e-4, 400, 200
    two = one = 0
    for seed in range(runs):
        with mt.scope("power", alpha=alpha, master_seed=seed):
            try:
                mt.assert_unbiased(_normal_draw(0.15), 0.0, n=n)
            except mt.StatisticalAssertionError:
                two += 1
        with mt.scope("power", alpha=alpha, master_seed=seed, escalate=0):
            try:
                mt.assert_unbiased(_normal_draw(0.15), 0.0, n=n)
            except mt.StatisticalAssertionError:
                one += 1
    # one stage: P(|t| > t_{1-alpha/2}) at a noncentrality of 3, about 0.2; two:
    # P(p1 <= alpha0), about 0.85, as stage 2 (noncentrality 6) then rejects
    assert one < 0.4 * runs and two > 0.7 * runs, (one, two)


def test_failure_message_names_stages_seed_and_reproduction():
    with mt.scope("msg", alpha=1e-3, master_seed=3):
        with pytest.raises(mt.StatisticalAssertionError) as ei:
            mt.assert_unbiased(_normal_draw(0.3), 0.0, n=1000)
    m = str(ei.value)
    assert "rejected at alpha 0.001" in m and "stage 1: n 1000, seed " in m
    assert "One Sample t-test" in m and "reproduce" in m
    assert ei.value.record.decision == "reject" and ei.value.record.seed == mt.check_seed(3, "msg", 0)


def test_pass_records_the_bias_it_could_have_missed():
    with mt.scope("hide", alpha=1e-3) as sc:
        r = mt.assert_unbiased(_normal_draw(0.0), 0.0, n=10_000)
    rec = sc.records[0]
    assert rec.decision == "pass" and "a bias in [" in rec.could_hide
    lo, hi = r.conf_int
    assert lo < 0.0 < hi and hi - lo < 0.15  # t_{1 - alpha1/2} 2 / sqrt(n): about 0.09


def test_draw_returning_the_wrong_count_is_named():
    with pytest.raises(mcstat.InvalidArgumentError, match="draw.*returned 3 values; 100"):
        mt.assert_unbiased(lambda n, s: np.zeros(3), 0.0, n=100, alpha=0.01)


def test_same_distribution_rejects_and_passes():
    def a(n, s):
        return np.random.default_rng(s).exponential(1.0, n)

    def b(n, s):
        return np.random.default_rng(s).gamma(1.2, 1 / 1.2, n)
    with mt.scope("ks", alpha=1e-4, checks=2):
        mt.assert_same_distribution(a, a, n=5000)
        with pytest.raises(mt.StatisticalAssertionError, match="Kolmogorov"):
            mt.assert_same_distribution(a, b, n=5000)


def test_simulated_ks_too_coarse_for_its_level_is_inconclusive():
    x = np.random.default_rng(1).normal(size=5000)
    with pytest.raises(mt.StatisticalAssertionError, match="inconclusive.*simulated p-value cannot go below"):
        mt.assert_same_distribution(x, x + 0.001, alpha=1e-5, weight="canner")


def test_warp_assertion_escalates_and_catches_a_planted_warp():
    good = (lambda u: np.sqrt(u[:, 0]), lambda x: 2.0 * x)
    bad = (lambda u: u[:, 0] ** 0.53, lambda x: 2.0 * x)  # the inverse cdf off by 6% in the exponent
    with mt.scope("warp", alpha=1e-3, checks=2):
        mt.assert_warp_consistent(*good, domain="interval", n=20_000)
        with pytest.raises(mt.StatisticalAssertionError, match="check_warp"):
            mt.assert_warp_consistent(*bad, domain="interval", n=20_000)


# ---- image equivalence ----------------------------------------------------------------
def _stacks(rng, ratio, seeds=12, h=16, w=16, c=1, sd=0.5):
    mu = rng.uniform(1.0, 2.0, (h, w, c))
    r = mu[None] + sd * rng.standard_normal((seeds, h, w, c))
    k = ratio * mu[None] + sd * rng.standard_normal((seeds, h, w, c))
    return r, k


def test_equivalence_false_claims_at_the_margin_are_at_most_alpha():
    """True ratio exactly 1 + margin in one block: "equivalent" is claimed at
    rate alpha at most (TOST's size; binomial bounds over 2000 seeds)."""
    rng = np.random.default_rng(20261206)
    alpha, margin, runs, k = 0.05, 0.02, 2000, 0
    for _ in range(runs):
        r, c = _stacks(rng, 1.0 + margin, h=8, w=8)
        # one 8 x 8 block: its true ratio is the boundary 1 + margin exactly
        k += equivalence(r, c, margin=margin, block=8, alpha=alpha).equivalent
    assert k <= runs * alpha + Z * math.sqrt(runs * alpha * (1 - alpha)), k


def test_equivalence_shows_equal_renders_and_refuses_a_2_percent_change():
    rng = np.random.default_rng(5)
    r, c = _stacks(rng, 1.0, seeds=64, h=32, w=32, sd=0.2)
    e = equivalence(r, c, margin=0.01, block=16, alpha=1e-3)
    assert e.equivalent and e.margin_shown < 0.01
    r, c = _stacks(rng, 1.02, seeds=64, h=32, w=32, sd=0.2)
    e = equivalence(r, c, margin=0.01, block=16, alpha=1e-3)
    assert not e.equivalent and e.blocks_shown == 0
    assert all(abs(b["relative_difference"] - 0.02) < 0.005 for b in e.worst(3))
    assert "not shown equivalent" in e.text()


def test_equivalence_constant_units_are_decided_exactly():
    r = np.zeros((4, 8, 8))
    r[:, :4] = np.random.default_rng(1).normal(1.0, 0.01, (4, 4, 8))
    c = r.copy()
    c[:, :4] += np.random.default_rng(2).normal(0.0, 0.001, (4, 4, 8))
    e = equivalence(r, c, margin=0.05, atol=1e-6, block=4, alpha=0.01)
    assert e.equivalent  # the black half: equal constants, inside atol
    c[:, 4:] = 1e-3
    assert not equivalence(r, c, margin=0.05, atol=1e-6, block=4, alpha=0.01).equivalent


@pytest.mark.parametrize("kw, what", [({"margin": -0.1}, "margin"), ({"margin": 1.0}, "margin"),
                                      ({"margin": 0.0}, "both 0"), ({"margin": 0.1, "atol": -1}, "atol"),
                                      ({"margin": 0.1, "alpha": 0.6}, "alpha"), ({"margin": 0.1, "block": 0}, "block")])
def test_equivalence_refusals_name_the_argument(kw, what):
    r = np.random.default_rng(1).normal(size=(4, 8, 8))
    with pytest.raises(mcstat.InvalidArgumentError, match=what):
        equivalence(r, r + 0.1, **kw)


def test_equivalence_needs_two_seeds_and_equal_shapes():
    r = np.random.default_rng(1).normal(size=(4, 8, 8))
    with pytest.raises(mcstat.InvalidArgumentError, match="differ in shape"):
        equivalence(r, r[:, :4], margin=0.1, seed_axis=0)
    with pytest.raises(mcstat.InvalidArgumentError, match="at least 2 seeds"):
        equivalence(r[:1], r[:1], margin=0.1, seed_axis=0)


def test_images_equivalent_assertion_spends_its_share():
    rng = np.random.default_rng(9)
    r, c = _stacks(rng, 1.0, seeds=64, h=32, w=32, sd=0.2)
    with mt.scope("img", alpha=1e-3) as sc:
        mt.assert_images_equivalent(r, c, margin=0.01, block=16, alpha=1e-3)
        r2, c2 = _stacks(rng, 1.02, seeds=64, h=32, w=32, sd=0.2)
        with pytest.raises(mt.StatisticalAssertionError, match="not shown to render"):
            mt.assert_images_equivalent(r2, c2, margin=0.01, block=16, alpha=1e-3)
        # equivalence spends none of the false-failure budget: the one check left is still there
        mt.assert_unbiased(_normal_draw(0.0), 0.0, n=100)
    assert [rec.decision for rec in sc.records] == ["pass", "reject", "pass"]
    assert [rec.spends_budget for rec in sc.records] == [False, False, True]


def test_a_failed_check_says_what_failed_in_a_few_lines(tmp_path):
    """The message keeps the routes that failed and the decision (the
    library's lines); the whole report goes to the artifacts and the
    record."""
    def sample(wi, u):  # the cosine-weighted hemisphere, weights 10% high
        r, phi = np.sqrt(u[:, 0]), 2 * np.pi * u[:, 1]
        wo = np.stack([r * np.cos(phi), r * np.sin(phi), np.sqrt(1 - u[:, 0])], axis=1)
        return wo, np.full(len(u), 0.88), wo[:, 2] / np.pi

    def pdf(wi, wo):
        return np.maximum(wo[:, 2], 0) / np.pi

    def ev(wi, wo):
        return 0.8 * pdf(wi, wo)

    suite = mt.Suite(alpha=0.01, artifacts=str(tmp_path))
    suite.allocate([("t", 1.0, 1)])
    with mt._budget._enter(suite.scope("t")), pytest.raises(mt.StatisticalAssertionError) as e:
        mt.assert_bsdf_consistent(sample, ev, pdf, [0, 0, 1.0], n=20_000, domain="hemisphere")
    msg = str(e.value)
    assert len(msg.splitlines()) <= 15, msg
    assert "weight      FAIL" in msg and "INCONSISTENT" in msg and "smallest departure" not in msg
    assert "the whole report: " + str(tmp_path) in msg
    full = e.value.record.message
    assert "smallest departure each route detects" in full and "weight      FAIL" in full
