"""mcstat.image.compare(paired=True) and image-test --paired: the paired t
test per pixel on same-seed renders, against SciPy's ttest_rel, its render
guards against closed forms, its calibration on same-seed stacks shaped
like renders (float32, zeros in the same seeds, a sampler that carries a
pixel's mean by spikes) and its power beside Welch's."""
import numpy as np
import pytest
import scipy.stats as st

import mcstat
import mcstat.image as mi
from cli_run import run_cli

W = np.array([0.2126, 0.7152, 0.0722])


def test_without_guards_it_is_scipys_paired_test():
    rng = np.random.default_rng(20261208)
    ref = rng.gamma(2.0, 1.0, (8, 12, 10, 3))
    cand = ref + rng.normal(0.02, 0.1, ref.shape)
    r = mi.compare(ref, cand, paired=True, render_guards=False, channels="rgb", method="none")
    want = st.ttest_rel(cand, ref, axis=0)
    np.testing.assert_allclose(r.pvalue, want.pvalue, rtol=1e-12)
    np.testing.assert_allclose(r.statistic, want.statistic, rtol=1e-12)
    np.testing.assert_allclose(r.mean_reference, ref.mean(0), rtol=1e-14)
    np.testing.assert_allclose(r.mean_candidate - r.mean_reference, (cand - ref).mean(0), rtol=1e-9, atol=1e-15)
    # luminance: the paired test of the weighted sums
    r = mi.compare(ref, cand, paired=True, render_guards=False, method="none")
    want = st.ttest_rel(cand @ W, ref @ W, axis=0)
    np.testing.assert_allclose(r.pvalue[..., 0], want.pvalue, rtol=1e-12)
    assert r.summary()["test"] == "paired" and "paired t-tests" in r.text()
    # the default guards leave ordinary pixels as they are
    g = mi.compare(ref, cand, paired=True, method="none")
    np.testing.assert_allclose(g.pvalue, r.pvalue, rtol=1e-13)


def test_guards_on_pixels_renders_make():
    k = 8
    rng = np.random.default_rng(7)
    u = rng.uniform(0.5, 1.0, k)
    ref = np.zeros((k, 1, 4))
    cand = np.zeros((k, 1, 4))
    ref[:, 0, 0] = cand[:, 0, 0] = u                    # equal in every seed: not tested
    ref[:, 0, 1], cand[:, 0, 1] = u, u + 0.5             # a constant difference: the rule-of-three floor
    ref[:, 0, 2], cand[:, 0, 2] = u, np.where(np.arange(k) < 6, 0.0, 4 * u)  # zero where the other is not
    ref[:, 0, 3], cand[:, 0, 3] = u, u + rng.normal(0.3, 0.01, k)            # ordinary
    r = mi.compare(ref, cand, paired=True, method="none", seed_axis=0)
    pi = -np.expm1(np.log(0.05) / k)
    ratio = (1 - pi) / pi
    assert not r.tested[0, 0, 0]
    assert r.statistic[0, 1, 0] == pytest.approx(np.sqrt(k / ratio), rel=1e-12)
    d = cand[:, 0, 2] - ref[:, 0, 2]
    assert r.statistic[0, 2, 0] == pytest.approx(d.mean() / np.sqrt(max(d.var(ddof=1), d.mean() ** 2 * ratio) / k),
                                                 rel=1e-12)
    assert r.pvalue[0, 1, 0] > 0.05 and r.pvalue[0, 2, 0] > 0.05
    assert r.pvalue[0, 3, 0] == pytest.approx(st.ttest_rel(cand[:, 0, 3], ref[:, 0, 3]).pvalue, rel=1e-12)
    assert r.decision[0, 3, 0] == 1


def _same_seed_stacks(rng, k, h, w, change=1.0):
    """Reference and candidate rendered with the same seeds (float32): a
    shared path component per seed and pixel, the candidate's own noise
    on top; zeros in the same seeds on both sides in a band of pixels
    (paths that miss); and in another band a candidate that reaches the
    light through rare spikes (zero in most seeds) while the reference is
    smooth, both with the reference's mean.  `change` scales the
    candidate's smooth part (1: both unbiased)."""
    shared = rng.gamma(4.0, 0.25, (k, h, w))
    ref = shared.copy()
    cand = change * (shared + rng.normal(0.0, 0.002, (k, h, w)))
    miss = rng.random((k, h, w)) < 0.3
    band = slice(0, h // 4)
    ref[:, band][miss[:, band]] = 0.0
    cand[:, band][miss[:, band]] = 0.0
    spiky = slice(h // 4, h // 2)
    p = 0.08
    hit = rng.random((k, h // 2 - h // 4, w)) < p
    cand[:, spiky] = np.where(hit, 1.0 / p, 0.0)
    return ref.astype(np.float32), cand.astype(np.float32)


@pytest.mark.stats
def test_calibrated_on_same_seed_render_stacks():
    """Per-image false alarms (any flag after BH at 0.05) over 200 unbiased
    same-seed pairs at K = 8: within the binomial bound of alpha with the
    guards, far beyond it without (the spiky band), so the test can fail."""
    rng = np.random.default_rng(20261208)
    n, alarms, alarms_plain = 200, 0, 0
    for _ in range(n):
        ref, cand = _same_seed_stacks(rng, 8, 32, 32)
        alarms += mi.compare(ref, cand, paired=True).rejections > 0
        alarms_plain += mi.compare(ref, cand, paired=True, render_guards=False).rejections > 0
    bound = st.binom.ppf(0.999, n, 0.05)
    assert alarms <= bound, (alarms, bound)
    assert alarms_plain > 3 * bound, alarms_plain


@pytest.mark.stats
def test_more_power_than_welch_on_same_seed_pairs():
    """The candidate's smooth part 2% brighter: the paired test finds most
    changed pixels at K = 8, where Welch's on the same renders finds few."""
    rng = np.random.default_rng(11)
    paired, welch = [], []
    for _ in range(10):
        ref, cand = _same_seed_stacks(rng, 8, 32, 32, change=1.02)
        region = np.zeros((32, 32), bool)
        region[16:] = True  # smooth pixels, no zeros
        for out, pr in ((paired, True), (welch, False)):
            r = mi.compare(ref, cand, paired=pr)
            out.append(np.mean(r.decision[..., 0][region] == 1))
    assert np.mean(paired) > 0.5, np.mean(paired)
    assert np.mean(welch) < 0.5 * np.mean(paired), (np.mean(welch), np.mean(paired))


def test_omitted_pairs_leave_both_means():
    """nan_policy="omit" drops a pair with a NaN on either side: the
    reference's mean (the map, the relative bias) is over the kept pairs,
    as the test's mean difference is."""
    rng = np.random.default_rng(8)
    ref = rng.gamma(2.0, 1.0, (6, 3, 4, 3))
    cand = ref + rng.normal(0.05, 0.1, ref.shape)
    cand[2, 1, 1, 0] = np.nan  # a NaN in one channel of the candidate's pixel (1, 1)
    r = mi.compare(ref, cand, paired=True, nan_policy="omit", render_guards=False, method="none", seed_axis=0)
    keep = np.arange(6) != 2
    rl, cl = (ref @ W)[:, 1, 1], (cand @ W)[:, 1, 1]
    assert r.mean_reference[1, 1, 0] == pytest.approx(rl[keep].mean(), rel=1e-12)
    assert r.mean_candidate[1, 1, 0] == pytest.approx(cl[keep].mean(), rel=1e-12)
    assert r.pvalue[1, 1, 0] == pytest.approx(st.ttest_rel(cl[keep], rl[keep]).pvalue, rel=1e-10)


def test_paired_blocks_are_the_paired_test_of_block_means():
    rng = np.random.default_rng(3)
    ref = rng.gamma(2.0, 1.0, (6, 8, 8))
    cand = ref + rng.normal(0.01, 0.05, ref.shape)
    r = mi.compare(ref, cand, paired=True, block=4, render_guards=False, method="none")
    bm = lambda a: a.reshape(6, 2, 4, 2, 4).mean(axis=(2, 4))  # noqa: E731
    want = st.ttest_rel(bm(cand), bm(ref), axis=0)
    np.testing.assert_allclose(r.pvalue[..., 0], want.pvalue, rtol=1e-10)


def test_refusals_name_the_problem():
    rng = np.random.default_rng(5)
    a, b = rng.random((6, 4, 4)), rng.random((5, 4, 4))
    with pytest.raises(mi.ImageInputError, match="same seeds on both sides"):
        mi.compare(a, b, paired=True, seed_axis=0)
    acc = mcstat.MomentsArray((4, 4, 1))
    acc.push(a[..., None])
    s = mi.summary_of_moments(acc)
    with pytest.raises(mi.ImageInputError, match="per-seed renders"):
        mi.compare(s, s, paired=True)


def test_cli_paired(tmp_path):
    rng = np.random.default_rng(9)
    ref = rng.gamma(4.0, 0.25, (8, 16, 16)).astype(np.float32)
    cand = (1.05 * ref + rng.normal(0, 0.01, ref.shape)).astype(np.float32)
    np.save(tmp_path / "r.npy", ref)
    np.save(tmp_path / "c.npy", cand)
    code, out, _ = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "c.npy", "--paired",
                           "--fail-on-reject")
    assert code == 1 and "paired t-tests (same-seed pairs)" in out
    code, out, _ = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "c.npy", "--fail-on-reject")
    assert code == 0 and "Welch" in out  # Welch's test misses the 5% at 8 seeds: the pairing is the power
    code, _, err = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "c.npy", "--paired",
                           "--equivalence", "0.1")
    assert code != 0 and "--paired" in err
