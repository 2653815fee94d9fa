"""mcstat.image and `mcstat image-test`: per-pixel Welch tests with FDR
control.  p-values against SciPy's Welch test; a planted biased region is
found with the false discovery proportion controlled; on null images the
fraction of runs with any discovery stays within binomial bounds of alpha;
the CLI round trip (.npy, PFM, EXR, .npz summaries in; PNG and JSON out);
clear errors for bad input."""
import json
import os
import sys

import numpy as np
import pytest
from PIL import Image
from scipy import stats

import mcstat
from mcstat import image as mi
from mcstat_app import image as app_image
from cli_run import run_cli


def planted(rng, k=8, h=48, w=64, c=3, bias=2.0, box=(10, 26, 20, 44), sigma=1.0):
    """Reference and candidate stacks (k, h, w, c): a smooth image plus noise,
    the candidate `bias` brighter inside box (y0, y1, x0, x1)."""
    yy, xx = np.mgrid[0:h, 0:w]
    base = 2.0 + np.sin(xx / 9.0)[..., None] * np.array([1.0, 0.5, 0.2]) [:c] + yy[..., None] / h
    ref = base + sigma * rng.standard_normal((k, h, w, c))
    cand = base + sigma * rng.standard_normal((k, h, w, c))
    y0, y1, x0, x1 = box
    cand[:, y0:y1, x0:x1, :] += bias
    mask = np.zeros((h, w), bool)
    mask[y0:y1, x0:x1] = True
    return ref, cand, mask


def test_pvalues_match_scipy(rng):
    ref, cand, _ = planted(rng, k=5, h=12, w=10)
    res = mi.compare(ref, cand, channels="rgb", render_guards=False)
    want = stats.ttest_ind(cand, ref, axis=0, equal_var=False)
    np.testing.assert_allclose(res.pvalue, want.pvalue, rtol=1e-9)
    np.testing.assert_allclose(res.statistic, want.statistic, rtol=1e-12)
    np.testing.assert_allclose(res.padjusted, mcstat.p_adjust(want.pvalue, method="BH"), rtol=1e-9)
    lum = ref @ np.array(mi.LUMINANCE_WEIGHTS)
    lumc = cand @ np.array(mi.LUMINANCE_WEIGHTS)
    res_y = mi.compare(ref, cand, render_guards=False)  # luminance is the default
    np.testing.assert_allclose(res_y.pvalue[..., 0], stats.ttest_ind(lumc, lum, axis=0, equal_var=False).pvalue,
                               rtol=1e-9)


def test_planted_region_found_with_fdr_controlled():
    rng = np.random.default_rng(11)
    fdp, power = [], []
    for _ in range(20):
        ref, cand, mask = planted(rng, h=64, w=64, c=1, bias=3.0, box=(8, 24, 30, 46))
        res = mi.compare(ref, cand, alpha=0.05)
        d = res.pixel_decision()
        found = d != 0
        assert np.all(d[mask] >= 0)  # never "less" in the brighter box
        fdp.append((found & ~mask).sum() / max(found.sum(), 1))
        power.append((found & mask).mean() / mask.mean())
    # BH with independent tests: E[FDP] = alpha m0 / m = 0.047 here; the mean
    # of 20 FDPs (~250 discoveries each, sd of one FDP ~0.014) stays below
    # 0.047 + 4 sd / sqrt(20).
    assert np.mean(fdp) < 0.065, fdp
    assert np.mean(power) > 0.5, power
    # without adjustment the same data give far more false positives
    res_none = mi.compare(ref, cand, alpha=0.05, method="none")
    fp_none = ((res_none.pixel_decision() != 0) & ~mask).sum()
    assert fp_none > 100  # ~0.05 * 3840


def test_null_images_calibrated():
    """Null images: the fraction of runs with any discovery is at most alpha
    (binomial bound).  It is below alpha here, not equal: with 6 + 6 seeds
    Welch's p-values are conservative far in the tail where BH's first
    threshold alpha / m lies (Satterthwaite's df < the pooled 10)."""
    rng = np.random.default_rng(5)
    runs, alpha = 300, 0.1
    any_bh = any_holm = 0
    for _ in range(runs):
        ref = rng.standard_normal((6, 24, 24)) * 2 + 1
        cand = rng.standard_normal((6, 24, 24)) * 2 + 1
        res = mi.compare(ref, cand, alpha=alpha)
        any_bh += bool((res.padjusted <= alpha).any())
        any_holm += bool((mcstat.p_adjust(res.pvalue, method="holm") <= alpha).any())
    hi = stats.binom.ppf(0.9995, runs, alpha)
    assert any_bh <= hi, (any_bh, hi)
    assert any_holm <= hi, (any_holm, hi)


def test_bh_exact_calibration_on_uniform_pvalues():
    """With exactly uniform null p-values BH's FDR is exactly alpha m0 / m:
    under the complete null P(any discovery) = alpha, within binomial bounds
    (two-sided, 99.9%); with planted signals the mean FDP is alpha m0 / m
    to within 4 standard errors."""
    rng = np.random.default_rng(21)
    runs, m, alpha = 2000, 500, 0.1
    p = rng.uniform(size=(runs, m))
    anyd = sum(bool((mcstat.p_adjust(row, method="BH") <= alpha).any()) for row in p)
    lo, hi = stats.binom.ppf([0.0005, 0.9995], runs, alpha)
    assert lo <= anyd <= hi, (anyd, lo, hi)
    m1 = 100
    fdp = []
    for row in p[:1000]:
        row = row.copy()
        row[:m1] = rng.beta(0.02, 1.0, size=m1)  # signals
        rej = mcstat.p_adjust(row, method="BH") <= alpha
        fdp.append(rej[m1:].sum() / max(rej.sum(), 1))
    want = alpha * (m - m1) / m
    se = np.std(fdp) / np.sqrt(len(fdp))
    assert abs(np.mean(fdp) - want) < 4 * se + 1e-3, (np.mean(fdp), want, se)


def test_summary_input_matches_samples(rng, tmp_path):
    ref, cand, _ = planted(rng, k=6, h=16, w=20)
    def summ(a, path, var=False):
        n = np.full(a.shape[1:], a.shape[0], dtype=np.int64)
        mean = a.mean(axis=0)
        m2 = ((a - mean) ** 2).sum(axis=0)
        if var:
            np.savez(path, n=a.shape[0], mean=mean, var=m2 / (a.shape[0] - 1))
        else:
            np.savez(path, n=n, mean=mean, M2=m2)
        return str(path)
    pr, pc = summ(ref, tmp_path / "r.npz"), summ(cand, tmp_path / "c.npz", var=True)
    a = app_image.compare(pr, pc, channels="rgb")
    b = mi.compare(ref, cand, channels="rgb", render_guards=False)
    np.testing.assert_allclose(a.pvalue, b.pvalue, rtol=1e-10)
    np.testing.assert_array_equal(a.decision, b.decision)
    with pytest.raises(mi.ImageInputError, match="covariances"):
        app_image.compare(pr, pc)  # luminance of per-channel summaries


def test_accumulator_input_matches_samples(rng, tmp_path):
    """A render farm's merged per-pixel accumulators (MomentsArray, pushed in
    two batches as two workers would) give the tests the seed stacks give,
    from Python and from the CLI (.npz of 96-byte records)."""
    ref, cand, mask = planted(rng, k=8, h=16, w=20, bias=3.0, box=(2, 10, 4, 12))

    def farm(a):  # (seeds, H, W, C): two workers, merged
        w1, w2 = mcstat.MomentsArray(a.shape[1:]), mcstat.MomentsArray(a.shape[1:])
        w1.push(a[:3])
        w2.push(a[3:])
        return w1 + w2

    ar, ac = farm(ref), farm(cand)
    a = mi.compare(ar, ac, channels="rgb")
    b = mi.compare(ref, cand, channels="rgb", render_guards=False)
    np.testing.assert_allclose(a.pvalue, b.pvalue, rtol=1e-10)
    np.testing.assert_array_equal(a.decision, b.decision)
    mi.save_moments(tmp_path / "r.npz", ar)
    mi.save_moments(tmp_path / "c.npz", ac)
    js = tmp_path / "s.json"
    code, out, err = run_cli("image-test", "-r", tmp_path / "r.npz", "-c", tmp_path / "c.npz", "--channels", "rgb",
                             "--json", js, "--quiet")
    assert code == 0, err
    with open(js) as f:
        s = json.load(f)
    assert s["rejections_adjusted"] == int((b.padjusted <= 0.05).sum()) > 0
    # a corrupt record is refused, naming the file
    bad = np.load(tmp_path / "c.npz")["moments"].copy()
    bad[3, 4, 0, 10] ^= 1
    np.savez(tmp_path / "bad.npz", moments=bad)
    with pytest.raises(mi.ImageInputError, match="bad.npz"):
        app_image.compare(str(tmp_path / "r.npz"), str(tmp_path / "bad.npz"))


def _write_pfm(path, img):
    h, w = img.shape[:2]
    kind = b"PF" if img.ndim == 3 else b"Pf"
    with open(path, "wb") as f:
        f.write(kind + b"\n%d %d\n-1.0\n" % (w, h))
        f.write(np.ascontiguousarray(img[::-1], dtype="<f4").tobytes())


def test_cli_round_trip(tmp_path):
    rng = np.random.default_rng(7)
    ref, cand, mask = planted(rng, k=8, h=40, w=56, bias=3.0, box=(5, 20, 10, 30))
    np.save(tmp_path / "ref.npy", ref)
    cfiles = []
    for i in range(cand.shape[0]):
        p = tmp_path / f"cand_{i}.pfm"
        _write_pfm(p, cand[i].astype(np.float32))
        cfiles.append(p)
    png, js = tmp_path / "map.png", tmp_path / "summary.json"
    code, out, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", *cfiles, "--png", png, "--json", js,
                             "--channels", "rgb")
    assert code == 0, err
    assert "rejections after adjustment" in out and "smallest p-values" in out
    img = np.asarray(Image.open(png).convert("RGB"))
    # the map on top, its colour key in a band below (as wide as the key needs)
    assert img.shape[0] > 40 and img.shape[1] >= 56 and img.dtype == np.uint8
    img = img[:40, :56]
    red = np.all(img == mi.COLOR_KEY["greater"], axis=-1)
    assert red[mask].mean() > 0.9 and red[~mask].mean() < 0.05
    with open(js) as f:
        s = json.load(f, parse_constant=lambda c: pytest.fail(f"non-finite {c} in the JSON"))
    # the same numbers as the API on the same (float32-rounded) data
    api = mi.compare(ref, cand.astype(np.float32).astype(np.float64), channels="rgb")
    assert s["tests"] == 40 * 56 * 3 and s["tested"] == s["tests"]
    assert s["rejections_adjusted"] == int((api.padjusted <= 0.05).sum())
    assert s["rejections_unadjusted"] == int((api.pvalue <= 0.05).sum())
    assert s["rejections_adjusted"] == s["rejected_greater"] + s["rejected_less"]
    assert s["expected_false_discoveries_bound"] == pytest.approx(0.05 * s["rejections_adjusted"])
    assert len(s["worst"]) == 10 and all(mask[w["y"], w["x"]] for w in s["worst"])
    assert s["worst"][0]["pvalue"] == pytest.approx(np.nanmin(api.pvalue), rel=1e-12)
    # --fail-on-reject
    code, _, _ = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", *cfiles, "--quiet", "--fail-on-reject")
    assert code == 1


def test_exr_input(tmp_path):
    OpenEXR = pytest.importorskip("OpenEXR")
    rng = np.random.default_rng(8)
    ref, cand, mask = planted(rng, k=4, h=20, w=24, bias=4.0, box=(4, 12, 4, 16))
    files = {}
    for side, data in (("r", ref), ("c", cand)):
        files[side] = []
        for i, im in enumerate(data.astype(np.float32)):
            p = str(tmp_path / f"{side}{i}.exr")
            with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage},
                              {"RGB": im}) as f:
                f.write(p)
            files[side].append(p)
    res = app_image.compare(files["r"], files["c"])
    want = mi.compare(ref.astype(np.float32), cand.astype(np.float32))
    np.testing.assert_array_equal(res.pvalue, want.pvalue)
    assert (res.pixel_decision()[mask] == 1).mean() > 0.8


def test_exr_without_package(tmp_path, monkeypatch):
    p = tmp_path / "a.exr"
    p.write_bytes(b"\x76\x2f\x31\x01")
    monkeypatch.setitem(sys.modules, "OpenEXR", None)
    with pytest.raises(mi.ImageInputError, match="pip install OpenEXR"):
        app_image.read_image(str(p))


def test_constant_pixels_not_tested(rng):
    ref, cand, _ = planted(rng, k=5, h=8, w=8, c=1)
    ref[:, 0, 0, 0] = cand[:, 0, 0, 0] = 0.0  # black background in both
    res = mi.compare(ref, cand)
    assert np.isnan(res.pvalue[0, 0, 0]) and not res.tested[0, 0, 0]
    s = res.summary()
    assert s["not_tested"] == 1 and s["tested"] == 63
    assert res.pixel_decision()[0, 0] == -2
    # n of the adjustment counts the tested pixels only
    ok = res.tested
    np.testing.assert_array_equal(res.padjusted[ok], mcstat.p_adjust(res.pvalue[ok], method="BH"))


def test_bad_inputs(tmp_path, rng):
    ref, cand, _ = planted(rng, k=4, h=8, w=8)
    with pytest.raises(mi.ImageInputError, match="8 x 8 pixels.*9 x 8 pixels"):
        mi.compare(ref, np.concatenate([cand, cand[:, :, :1]], axis=2))
    with pytest.raises(mcstat.TooFewObservationsError, match="1 seed"):
        mi.compare(ref, cand[:1])
    bad = cand.copy()
    bad[2, 3, 5, 1] = np.nan
    with pytest.raises(mcstat.NonFiniteError, match="x=5, y=3"):
        mi.compare(ref, bad, channels="rgb")
    res = mi.compare(ref, bad, channels="rgb", nan_policy="omit")
    assert res.tested.all()
    with pytest.raises(mcstat.InvalidArgumentError, match="alpha"):
        mi.compare(ref, cand, alpha=1.5)
    with pytest.raises(mcstat.InvalidArgumentError, match="channels"):
        mi.compare(ref, cand, channels="hsv")
    # the CLI: a clear message and exit status 3 (bad input)
    np.save(tmp_path / "r.npy", ref)
    np.save(tmp_path / "c.npy", cand[:, :7])
    code, _, err = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "c.npy")
    assert code == 3 and "ImageInputError" in err and "8 x 7 pixels" in err
    np.save(tmp_path / "one.npy", cand[:1])
    code, _, err = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "one.npy")
    assert code == 3 and "1 seed" in err
    code, _, err = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "missing.exr")
    assert code == 3 and "no such file" in err
    (tmp_path / "x.png").write_bytes(b"")
    code, _, err = run_cli("image-test", "-r", tmp_path / "x.png", tmp_path / "x.png", "-c", tmp_path / "x.png",
                           tmp_path / "x.png")
    assert code == 3 and "unknown image format" in err
    (tmp_path / "t.pfm").write_bytes(b"PF\n4 4\n-1.0\n" + b"\0" * 20)
    with pytest.raises(mi.ImageInputError, match="PFM data"):
        app_image.read_image(str(tmp_path / "t.pfm"))


# ---- the seeds axis ----------------------------------------------------------------

def _hw_seeds(rng, k=16, n=32):
    """Reference and candidate as (H, W, seeds) arrays (grey), the candidate
    brighter in a box, and the seeds-first originals."""
    ref, cand, mask = planted(rng, k=k, h=n, w=n, c=1, bias=3.0)
    ref, cand = ref[..., 0], cand[..., 0]
    return np.moveaxis(ref, 0, -1), np.moveaxis(cand, 0, -1), ref, cand, mask


def test_seeds_last_stack_is_refused_not_misread(rng):
    ref_l, cand_l, ref, cand, mask = _hw_seeds(rng)
    assert ref_l.shape == (32, 32, 16)
    want = mi.compare(ref, cand)  # seeds first: clear from the shape
    assert want.summary()["rejections_adjusted"] > 0.8 * mask.sum()
    # (32, 32, 16) reads as 32 seeds of 32 x 16 too: refused, saying how to say which
    with pytest.raises(ValueError, match=r"seed_axis=-1 if it is \(H, W, seeds\)"):
        mi.compare(ref_l, cand_l)
    got = mi.compare(ref_l, cand_l, seed_axis=-1)
    np.testing.assert_array_equal(got.pvalue, want.pvalue)
    assert got.summary()["rejections_adjusted"] == want.summary()["rejections_adjusted"]
    np.testing.assert_array_equal(mi.compare(ref_l, cand_l, seed_axis=2).pvalue, want.pvalue)


def test_seeds_axis_from_the_two_shapes(rng):
    ref_l, cand_l, ref, cand, _ = _hw_seeds(rng)
    # different numbers of seeds on the last axis: that axis
    got = mi.compare(ref_l, cand_l[..., :12])
    np.testing.assert_array_equal(got.pvalue, mi.compare(ref, cand[:12]).pvalue)
    # a stack against Samples of the other side: the axis whose removal leaves its image
    s = mi.Samples(ref[..., None], ["Y"])
    got = mi.compare(s, cand_l)
    np.testing.assert_array_equal(got.pvalue, mi.compare(s, cand).pvalue)
    # clear layouts keep the documented default (seeds first)
    assert mi._infer_seed_axis(np.zeros((16, 480, 640)), np.zeros((16, 480, 640))) == 0
    assert mi._infer_seed_axis(np.zeros((1000, 32, 32)), np.zeros((1000, 32, 32))) == 0
    assert mi._infer_seed_axis(np.zeros((8, 48, 64, 3)), np.zeros((8, 48, 64, 3))) == 0
    for shape in [(32, 32, 16), (16, 16, 64), (8, 16, 8), (8, 8, 8), (48, 64, 3, 8), (48, 64, 8, 3)]:
        with pytest.raises(mi.ImageInputError, match="cannot tell which axis"):
            mi._infer_seed_axis(np.zeros(shape), np.zeros(shape))
    with pytest.raises(mi.ImageInputError, match="out of range"):
        mi.compare(ref_l, cand_l, seed_axis=3)


def test_cli_seed_axis(rng, tmp_path):
    ref_l, cand_l, ref, cand, mask = _hw_seeds(rng)
    np.save(tmp_path / "r.npy", ref_l)
    np.save(tmp_path / "c.npy", cand_l)
    code, _, err = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "c.npy", "--quiet")
    assert code != 0 and "seed_axis" in err
    js = tmp_path / "s.json"
    code, _, err = run_cli("image-test", "-r", tmp_path / "r.npy", "-c", tmp_path / "c.npy", "--seed-axis", "-1",
                           "--json", js, "--quiet")
    assert code == 0, err
    assert json.loads(js.read_text())["rejections_adjusted"] == mi.compare(ref, cand).summary()["rejections_adjusted"]
    # load_side alone: the shape must settle it
    with pytest.raises(mi.ImageInputError, match="cannot tell"):
        app_image.load_side(str(tmp_path / "r.npy"))
    assert app_image.load_side(str(tmp_path / "r.npy"), seed_axis=-1).data.shape == (16, 32, 32, 1)


def test_statsmodels_method_names_in_the_summary(rng):
    ref, cand, _ = planted(rng, k=5, h=8, w=8, c=1)
    res = mi.compare(ref, cand, method="fdr_bh")
    assert res.method == "BH" and res.summary()["controls"] == "false discovery rate"
    np.testing.assert_array_equal(res.padjusted, mi.compare(ref, cand, method="BH").padjusted)
