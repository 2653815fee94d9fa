"""mcstat.image: what a pass means (detectable bias and the per-test level
of each adjustment), block tests, verdicts and `image-test`'s exit statuses
per verdict, and the maps' colour keys.  Independent checks: SciPy's
noncentral t for the power at the computed bias, R's definitions of the
adjustments through mcstat.p_adjust for the per-test levels, mcstat.t_test
on block means computed here for the block tests."""
import json

import numpy as np
import pytest
from PIL import Image
from scipy import integrate, optimize, stats

import mcstat
from mcstat import image as mi
from mcstat_app import image as app_image
from mcstat_app import errors as E
from cli_run import run_cli


def stacks(seed, k=8, h=32, w=40, c=1, bias=0.0, box=None, sigma=1.0):
    rng = np.random.default_rng(seed)
    base = 2.0 + np.linspace(0, 1, w)[None, :, None] + np.zeros((h, w, c))
    ref = base + sigma * rng.standard_normal((k, h, w, c))
    cand = base + sigma * rng.standard_normal((k, h, w, c))
    if box is not None:
        y0, y1, x0, x1 = box
        cand[:, y0:y1, x0:x1] += bias
    return ref, cand


# ---- detectable bias ---------------------------------------------------------------
@pytest.mark.parametrize("df", [4.0, 6.5, 11.0, 40.0])
@pytest.mark.parametrize("level", [0.05, 1e-4, 1e-6])
@pytest.mark.parametrize("power", [0.5, 0.8])
def test_detectable_bias_has_its_power_under_the_noncentral_t(df, level, power):
    se = 0.37
    delta = float(mi.detectable_bias(se, df, level, power=power))
    c = stats.t.isf(level / 2, df)
    got = nct_power(c, df, delta / se)
    want = stats.nct.sf(c, df, delta / se) + stats.nct.cdf(-c, df, delta / se)
    if np.isfinite(want):  # SciPy's nct (Boost) returns NaN in the far tails
        assert got == pytest.approx(want, rel=1e-6, abs=1e-9)
    else:
        assert level < 0.05
    # the Johnson-Welch approximation errs on the safe side: at least the
    # target power, at most 0.025 above it for df >= 4 (the module's doc)
    assert power - 1e-3 <= got <= power + 0.025, got
    exact = optimize.brentq(lambda d: nct_power(c, df, d) - power, 0.0, 20 * c) * se
    assert 0 <= delta / exact - 1 <= 0.025


def nct_power(c, df, ncp):
    """P(|T'| > c), T' = (Z + ncp) / sqrt(V / df), V ~ chi2(df): the integral
    over V of the normal tails (an independent route to the noncentral t)."""
    f = lambda v: (stats.norm.sf(c * np.sqrt(v / df) - ncp) + stats.norm.cdf(-c * np.sqrt(v / df) - ncp)) \
        * stats.chi2.pdf(v, df)
    return integrate.quad(f, 0, np.inf, epsabs=1e-12, epsrel=1e-10, limit=200)[0]


def test_detectable_bias_one_sided_uses_the_one_sided_critical_value():
    d2 = float(mi.detectable_bias(1.0, 10.0, 0.02, power=0.5, alternative="two-sided"))
    d1 = float(mi.detectable_bias(1.0, 10.0, 0.01, power=0.5, alternative="greater"))
    assert d1 == pytest.approx(d2, rel=1e-12)
    assert d2 == pytest.approx(stats.t.isf(0.01, 10.0) * (1 - 1 / 40), rel=1e-9)


def test_t_quantile_interpolation_matches_exact():
    rng = np.random.default_rng(3)
    df = rng.uniform(1.1, 200.0, 200_000)
    df[:5] = [np.nan, -1.0, 0.0, np.inf, 3.0]
    for q in (0.025, 3e-9, 0.6):
        got = mi._t_upper_quantile(q, df)
        assert np.isnan(got[:4]).all()
        want = stats.t.isf(q, df[4:])
        np.testing.assert_allclose(got[4:], want, rtol=1e-13)


def test_per_test_levels_closed_form():
    m, a = 1000, 0.05
    assert mi.per_test_level("BH", a, m, 0) == pytest.approx(a / m)
    assert mi.per_test_level("fdr_bh", a, m, 9) == pytest.approx(a * 10 / m)
    hm = sum(1.0 / k for k in range(1, m + 1))
    assert mi.per_test_level("BY", a, m, 0) == pytest.approx(a / (m * hm))
    assert mi.per_test_level("e-BH", a, m, 0) == pytest.approx((0.1 * a / m) ** (1 / 0.9))
    assert mi.per_test_level("holm", a, m, 3) == pytest.approx(a / (m - 3))
    assert mi.per_test_level("hochberg", a, m, 0) == pytest.approx(a / m)
    assert mi.per_test_level("bonferroni", a, m, 7) == pytest.approx(a / m)
    assert mi.per_test_level("none", a, m, 7) == a
    # the harmonic number's asymptotic series above 1e6 terms
    assert mi._harmonic(2_000_000) == pytest.approx(float(np.sum(1.0 / np.arange(2_000_000, 0, -1))), rel=1e-14)


@pytest.mark.parametrize("method", ["BH", "BY", "e-BH", "holm", "hochberg", "hommel", "bonferroni", "none"])
def test_per_test_level_rejects_one_more(method):
    """A not-rejected p-value set just below the level is rejected by the
    adjustment itself (the others held fixed); for Holm and Bonferroni the
    level is the largest such one (just above: not rejected)."""
    rng = np.random.default_rng(5)
    m, a = 400, 0.1
    p = rng.uniform(size=m)
    p[:12] = rng.uniform(0, 1e-5, 12)  # some discoveries
    r = int((mcstat.p_adjust(p, method=method) <= a).sum())
    assert 0 < r < m
    lv = mi.per_test_level(method, a, m, r)
    out = np.flatnonzero(mcstat.p_adjust(p, method=method) > a)
    j = out[np.argmax(p[out])]  # the largest not-rejected p: others stay where they were
    q = p.copy()
    q[j] = lv * (1 - 1e-9)
    assert mcstat.p_adjust(q, method=method)[j] <= a
    if method in ("holm", "bonferroni"):
        q[j] = lv * (1 + 1e-6)
        assert mcstat.p_adjust(q, method=method)[j] > a


def test_compare_detectable_bias_from_summaries_equals_from_samples():
    ref, cand = stacks(1, k=6, h=10, w=12, c=3)
    a = mi.compare(ref, cand, channels="rgb", render_guards=False)
    summ = [mi.Summary(np.full(s.shape[1:], float(s.shape[0])), s.mean(axis=0),
                       ((s - s.mean(axis=0)) ** 2).sum(axis=0), ["R", "G", "B"]) for s in (ref, cand)]
    b = mi.compare(summ[0], summ[1], channels="rgb")
    assert a.level == b.level == pytest.approx(0.05 / (10 * 12 * 3))
    np.testing.assert_allclose(a.detectable_bias, b.detectable_bias, rtol=1e-10)
    # the same numbers as detectable_bias on SciPy-free Welch se and df computed here
    vx, vy = cand.var(axis=0, ddof=1) / 6, ref.var(axis=0, ddof=1) / 6
    df = (vx + vy) ** 2 / (vx ** 2 / 5 + vy ** 2 / 5)
    np.testing.assert_allclose(a.detectable_bias, mi.detectable_bias(np.sqrt(vx + vy), df, a.level), rtol=1e-9)


def test_detectable_bias_falls_with_the_seeds():
    med = []
    for k in (4, 8, 16, 32):
        ref, cand = stacks(2, k=k, h=24, w=24)
        res = mi.compare(ref, cand)
        med.append(res.bias_statistics()["absolute"]["median"])
    assert all(a > b for a, b in zip(med, med[1:])), med
    # about 1/sqrt(n) once the critical value settles
    assert med[2] / med[3] == pytest.approx(np.sqrt(2), rel=0.2)


def test_summary_and_text_say_what_a_pass_means():
    ref, cand = stacks(4)
    res = mi.compare(ref, cand)
    s = res.summary()
    b = s["detectable_bias"]
    assert s["verdict"] == "equal" and b["power"] == 0.8 and b["level"] == pytest.approx(0.05 / (32 * 40))
    vals = res.detectable_bias[res.tested]
    assert b["absolute"]["median"] == pytest.approx(np.median(vals))
    assert b["absolute"]["p90"] == pytest.approx(np.quantile(vals, 0.9))
    assert b["absolute"]["p99"] == pytest.approx(np.quantile(vals, 0.99))
    rel = vals / np.abs(res.mean_reference[res.tested])
    assert b["relative"]["median"] == pytest.approx(np.median(rel))
    json.dumps(s, allow_nan=False)
    t = res.text()
    assert "no differences found; a bias smaller than" in t and "could have hidden" in t
    assert "verdict: equal" in t


# ---- verdicts ---------------------------------------------------------------------
def test_verdicts():
    ref, cand = stacks(6, box=(4, 20, 4, 20), bias=4.0)
    assert mi.compare(ref, cand).verdict == "different"
    ref, cand = stacks(6)
    res = mi.compare(ref, cand)
    assert res.verdict == "equal"
    p90 = res.bias_statistics()["absolute"]["p90"]
    assert mi.compare(ref, cand, max_detectable_bias=p90 * 1.01).verdict == "equal"
    res = mi.compare(ref, cand, max_detectable_bias=p90 * 0.99)
    assert res.verdict == "inconclusive" and "could have hidden" in res.verdict_reason()[1]
    rel90 = res.bias_statistics()["relative"]["p90"]
    assert mi.compare(ref, cand, max_relative_detectable_bias=rel90 * 0.99).verdict == "inconclusive"
    assert mi.compare(ref, cand, max_relative_detectable_bias=rel90 * 1.01).verdict == "equal"
    # the median instead of the 90th percentile
    assert mi.compare(ref, cand, max_detectable_bias=p90 * 0.99, bias_quantile=0.5).verdict == "equal"
    # nothing testable: constant in both inputs
    const = np.ones((4, 8, 8))
    res = mi.compare(const, const)
    assert not res.tested.any() and res.verdict == "inconclusive"
    assert res.summary()["verdict"] == "inconclusive"
    json.dumps(res.summary(), allow_nan=False)  # strict JSON when nothing was tested
    assert "verdict: inconclusive" in res.text()
    for bad in (dict(max_detectable_bias=0.0), dict(max_relative_detectable_bias=-1.0),
                dict(detect_power=1.0), dict(bias_quantile=1.5), dict(block=0), dict(block=2.5)):
        with pytest.raises(mcstat.InvalidArgumentError):
            mi.compare(ref, cand, **bad)


def test_exit_status_per_verdict(tmp_path):
    ref, cand = stacks(7, box=(4, 20, 4, 20), bias=4.0)
    _, null = stacks(8)
    np.save(tmp_path / "ref.npy", ref)
    np.save(tmp_path / "cand.npy", cand)
    np.save(tmp_path / "null.npy", null)
    np.save(tmp_path / "const.npy", np.ones((4, 8, 8)))
    base = ("image-test", "-r", tmp_path / "ref.npy", "--quiet", "--fail-on-reject")
    assert run_cli(*base, "-c", tmp_path / "cand.npy")[0] == E.EXIT_REJECTED == 1
    assert run_cli(*base, "-c", tmp_path / "null.npy")[0] == E.EXIT_OK == 0
    code, _, err = run_cli(*base, "-c", tmp_path / "null.npy", "--max-detectable-bias", "1e-3")
    assert code == E.EXIT_INCONCLUSIVE == 6, err
    code, _, err = run_cli(*base, "-c", tmp_path / "null.npy", "--max-relative-detectable-bias", "1e-4")
    assert code == 6, err
    assert run_cli(*base, "-c", tmp_path / "null.npy", "--max-detectable-bias", "1e3")[0] == 0
    code, _, err = run_cli("image-test", "-r", tmp_path / "const.npy", "-c", tmp_path / "const.npy", "--quiet",
                           "--fail-on-reject")
    assert code == 6, err
    # without --fail-on-reject every verdict exits 0
    assert run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy", "--quiet")[0] == 0
    assert run_cli("image-test", "-r", tmp_path / "const.npy", "-c", tmp_path / "const.npy", "--quiet")[0] == 0
    code, _, err = run_cli(*base, "-c", tmp_path / "null.npy", "--max-detectable-bias", "-1")
    assert code == E.EXIT_USAGE and "--max-detectable-bias" in err
    # the JSON carries the verdict; --help documents status 6
    js = tmp_path / "s.json"
    run_cli(*base, "-c", tmp_path / "null.npy", "--max-detectable-bias", "1e-3", "--json", js)
    assert json.loads(js.read_text())["verdict"] == "inconclusive"
    _, out, _ = run_cli("--help")
    assert "  6    image-test --fail-on-reject: inconclusive" in out
    _, out, _ = run_cli("image-test", "--help")
    assert "6 inconclusive" in out and "--max-detectable-bias" in out and "--block" in out


# ---- block tests ------------------------------------------------------------------
def block_means_here(a, n):
    k, h, w, c = a.shape
    out = np.empty((k, -(-h // n), -(-w // n), c))
    for by in range(out.shape[1]):
        for bx in range(out.shape[2]):
            out[:, by, bx] = a[:, by * n:(by + 1) * n, bx * n:(bx + 1) * n].mean(axis=(1, 2))
    return out


def test_block_tests_are_welch_on_block_means():
    ref, cand = stacks(9, k=6, h=21, w=27, c=3, box=(0, 8, 0, 8), bias=0.5)
    res = mi.compare(ref, cand, block=8, channels="rgb", render_guards=False)
    assert res.block == 8 and res.image_shape == (21, 27) and res.shape == (3, 4, 3)
    bc, br = block_means_here(cand, 8), block_means_here(ref, 8)   # edge blocks 5 x 3 pixels and so on
    want = mcstat.t_test(np.moveaxis(bc, 0, -1), np.moveaxis(br, 0, -1), axis=-1)
    np.testing.assert_allclose(res.pvalue, want.pvalue, rtol=1e-12)
    np.testing.assert_allclose(res.statistic, want.statistic, rtol=1e-12)
    sp = stats.ttest_ind(bc, br, axis=0, equal_var=False)
    np.testing.assert_allclose(res.pvalue, sp.pvalue, rtol=1e-9)
    np.testing.assert_allclose(res.padjusted, mcstat.p_adjust(want.pvalue, method="BH"), rtol=1e-12)
    np.testing.assert_allclose(res.detectable_bias,
                               mi.detectable_bias(want.std_error, want.df, res.level), rtol=1e-9)
    # the map is drawn at the image's size, each block one colour
    rgb = app_image.map_rgb(res)
    assert rgb.shape == (21, 27, 3)
    s = res.summary()
    assert s["block"]["size"] == 8 and s["block"]["grid"] == [3, 4] and s["block"]["image"] == [21, 27]
    assert "Block Welch" in res.text() and "edge blocks smaller" in res.text()


def test_block_tests_find_a_small_regional_bias_per_pixel_tests_miss():
    ref, cand = stacks(10, k=8, h=48, w=48, box=(16, 32, 16, 32), bias=0.3)
    px = mi.compare(ref, cand)
    assert px.rejections == 0 and px.verdict == "equal"
    bl = mi.compare(ref, cand, block=8)
    d = bl.pixel_decision()
    assert (d[2:4, 2:4] == 1).all()          # the four blocks inside the box
    assert (d != 0).sum() <= 5 and bl.verdict == "different"


def test_block_tests_refuse_summaries_and_handle_non_finite():
    ref, cand = stacks(11, k=4, h=16, w=16)
    summ = mi.Summary(np.full((16, 16, 1), 4.0), ref.mean(axis=0), ref.var(axis=0, ddof=1) * 3, ["Y"])
    with pytest.raises(mi.ImageInputError, match="covariances"):
        mi.compare(summ, summ, block=4)
    cand[2, 5, 9, 0] = np.nan
    with pytest.raises(mcstat.NonFiniteError, match="x=9, y=5"):
        mi.compare(ref, cand, block=4)
    res = mi.compare(ref, cand, block=4, nan_policy="omit")
    assert not res.tested[1, 2, 0] and res.tested.sum() == 15
    assert np.isnan(res.pvalue[1, 2, 0]) and np.isnan(res.detectable_bias[1, 2, 0])
    assert app_image.map_rgb(res)[4:8, 8:12].tolist() == [[list(mi.COLOR_KEY["not tested"])] * 4] * 4


def test_cli_block(tmp_path):
    ref, cand = stacks(10, k=8, h=48, w=48, box=(16, 32, 16, 32), bias=0.3)
    np.save(tmp_path / "ref.npy", ref[..., 0])
    np.save(tmp_path / "cand.npy", cand[..., 0])
    code, out, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy", "--block", "8",
                             "--fail-on-reject", "--png", tmp_path / "m.png")
    assert code == 1, err
    assert "8 x 8 block means" in out
    img = np.asarray(Image.open(tmp_path / "m.png").convert("RGB"))[:48, :48]
    assert (img[16:32, 16:32] == mi.COLOR_KEY["greater"]).all()


# ---- the maps' keys ---------------------------------------------------------------
def _has_colour(a, col):
    return bool(np.all(a == np.asarray(col, dtype=np.uint8), axis=-1).any())


def test_significance_map_carries_its_key(tmp_path):
    ref, cand = stacks(12, h=40, w=56, box=(4, 20, 4, 20), bias=4.0)
    res = mi.compare(ref, cand)
    app_image.write_map(res, str(tmp_path / "m.png"))
    im = Image.open(tmp_path / "m.png")
    assert im.mode == "P"   # a palette PNG: greys and the key colours
    img = np.asarray(im.convert("RGB"))
    assert img.shape[0] > 40 and img.shape[1] >= 56
    np.testing.assert_array_equal(img[:40, :56], app_image.map_rgb(res))   # the map itself unchanged
    band = img[40:]
    for name in ("greater", "less", "mixed", "not tested"):
        assert _has_colour(band, mi.COLOR_KEY[name]), name
    for g in (60, 130, 200):   # the grey scale's swatches
        assert _has_colour(band, (g, g, g))
    # text drawn: light pixels in the band beyond the swatches
    assert (band[:, 40:].max(axis=-1) > 200).sum() > 500


def test_significance_map_legend_scales_with_the_image():
    res = mi.compare(*stacks(13, k=3, h=8, w=2500))
    leg = app_image.legend_rgb(res, 2500)
    assert leg.shape[1] >= 2500 and leg.shape[0] >= 2 * 90


def test_bias_map_has_its_colour_bar(tmp_path):
    ref, cand = stacks(14, h=30, w=50)
    ref[:, :, :25] *= 3.0   # noisier on the left: larger detectable bias there
    res = mi.compare(ref, cand)
    code, out, err = run_cli("image-test", "-r", _save(tmp_path, "r.npy", ref), "-c", _save(tmp_path, "c.npy", cand),
                             "--bias-png", tmp_path / "b.png")
    assert code == 0 and "detectable-bias map" in out, err
    im = Image.open(tmp_path / "b.png")
    assert im.mode == "P"
    img = np.asarray(im.convert("RGB"))
    assert img.shape[0] > 30
    np.testing.assert_array_equal(img[:30, :50], app_image.bias_map_rgb(res))
    band = img[30:]
    assert _has_colour(band, app_image._VIRIDIS[0]) and _has_colour(band, app_image._VIRIDIS[-1])
    # brighter (yellower) where the detectable bias is larger
    m = app_image.bias_map_rgb(res).astype(float).sum(axis=-1)
    assert m[:, :25].mean() > m[:, 25:].mean()


def _save(d, name, a):
    np.save(d / name, a)
    return d / name


def test_blocks_of_rgb_luminance_are_one_test_per_block():
    # luminance of an RGB stack is formed by the per-pixel test from the
    # channels; the block means must keep those weights (one test per block,
    # the same as blocks of the luminance stack itself), NaN handling included
    rng = np.random.default_rng(41)
    ref = rng.normal(1.0, 0.3, (8, 16, 12, 3))
    cand = rng.normal(1.0, 0.3, (8, 16, 12, 3))
    cand[:, :4, :4, 0] += 0.5
    w = np.asarray(mcstat.image.LUMINANCE_WEIGHTS)
    got = mcstat.image.compare(ref, cand, block=4, seed_axis=0)
    want = mcstat.image.compare(ref @ w, cand @ w, block=4, seed_axis=0)
    assert got.pvalue.shape == (4, 3, 1)
    np.testing.assert_allclose(got.pvalue, want.pvalue, rtol=1e-12)
    cand[3, 9, 5, 2] = np.nan
    with pytest.raises(mcstat.NonFiniteError, match="x=5, y=9"):
        mcstat.image.compare(ref, cand, block=4, seed_axis=0)
    got = mcstat.image.compare(ref, cand, block=4, seed_axis=0, nan_policy="omit")
    assert not got.tested[2, 1, 0] and int(got.tested.sum()) == 11
