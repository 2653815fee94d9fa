"""e-BH (Wang & Ramdas 2022): ``mcstat.e_bh`` on e-values and the
``p_adjust`` method ``"e-BH"`` on calibrated p-values, against a direct
implementation of the k* rule; ``mcstat.image.compare(method="e-BH")`` and
``image-test --adjust e-BH``; and (marker ``stats``) the any-discovery rate
of BH, BY and e-BH on null image pairs whose pixels a reconstruction filter
has correlated."""
import contextlib
import io
import zlib

import numpy as np
import pytest

import mcstat
from mcstat import image as mi
from mcstat_app.cli import main
from stats_oracle import BUDGET


def kstar_reject(e, alpha):
    """Wang & Ramdas' rule itself: reject the k* largest e-values, k* = max{k :
    k e_(k) / m >= 1/alpha}; NaN not counted."""
    e = np.asarray(e, dtype=float)
    ok = ~np.isnan(e)
    s = np.sort(e[ok])[::-1]
    m = s.size
    k = np.arange(1, m + 1)
    hit = np.nonzero(k * s / m >= 1.0 / alpha)[0]
    if hit.size == 0:
        return np.zeros(e.shape, bool)
    return ok & (np.where(ok, e, -1.0) >= s[hit[-1]])


def calibrate(p):
    """e = p^(-9/10) / 10 (inf at p = 0), NaN kept."""
    e = np.where(p > 0, 0.1 * np.power(np.where(p > 0, p, 1.0), -0.9), np.inf)
    return np.where(np.isnan(p), np.nan, e)


def test_e_bh_hand_values():
    np.testing.assert_allclose(mcstat.e_bh([20, 10, 1, 0.5]), [0.2, 0.2, 1, 1], rtol=1e-15)
    got = mcstat.e_bh([[40, 5, 5], [np.nan, 0, np.inf]])
    assert got.shape == (2, 3)
    np.testing.assert_allclose(got, [[5 / 80, 0.25, 0.25], [np.nan, 1, 0]], rtol=1e-15)
    assert mcstat.e_bh([4.0])[0] == 0.25  # one e-value: min(1, 1/e)
    assert mcstat.e_bh([]).shape == (0,)


@pytest.mark.parametrize("seed", range(6))
def test_e_bh_is_the_kstar_rule(seed):
    rng = np.random.default_rng(seed)
    m = int(rng.integers(1, 3000))
    e = 1.0 / rng.uniform(size=m) - 1.0
    if seed % 2:
        e = np.floor(e * 2) / 2  # ties and zeros
    e[rng.uniform(size=m) < 0.05] = np.nan
    adj = mcstat.e_bh(e)
    assert np.array_equal(np.isnan(adj), np.isnan(e))
    for alpha in (0.01, 0.05, 0.1, 0.3):
        np.testing.assert_array_equal(np.nan_to_num(adj, nan=2.0) <= alpha, kstar_reject(e, alpha))


def test_p_adjust_e_bh_is_e_bh_on_calibrated_p():
    rng = np.random.default_rng(3)
    p = rng.uniform(size=500) ** 4
    p[::37] = 0.0
    p[5::41] = 1.0
    p[7::43] = np.nan
    got = mcstat.p_adjust(p, method="e-BH")
    np.testing.assert_allclose(got, mcstat.e_bh(calibrate(p)), rtol=1e-12)
    for name in ("ebh", "e_bh", "E-BH"):
        np.testing.assert_array_equal(mcstat.p_adjust(p, method=name), got)
    ok = ~np.isnan(p)
    assert np.all(got[ok] >= p[ok]) and np.all(got[ok] <= 1)
    # H_m <= 10 (m <= 12366): term by term H m p / k <= 10 m p^0.9 / k, so
    # BY's adjusted values are never larger: e-BH never rejects more
    by = mcstat.p_adjust(p, method="BY")
    assert np.all(by[ok] <= got[ok])
    # one p-value comes back unchanged, as in every method
    assert mcstat.p_adjust([np.nan, 0.003], method="e-BH")[1] == 0.003


def test_e_bh_errors():
    with pytest.raises(mcstat.InvalidArgumentError, match="e-values must be >= 0.*-1.0.*flat index 1"):
        mcstat.e_bh([1.0, -1.0])
    with pytest.raises(mcstat.InvalidArgumentError, match="flat index 0"):
        mcstat.e_bh([-np.inf])
    with pytest.raises(TypeError):
        mcstat.e_bh(None)
    with pytest.raises(mcstat.InvalidArgumentError, match="p-values must lie in"):
        mcstat.p_adjust([0.1, 1.5], method="e-BH")


def test_image_compare_e_bh_and_summary():
    rng = np.random.default_rng(11)
    ref = rng.standard_normal((8, 24, 24))
    cand = rng.standard_normal((8, 24, 24))
    cand[:, 4:10, 4:10] += 4.0
    res = mi.compare(ref, cand, method="ebh", seed_axis=0)
    assert res.method == "e-BH"
    np.testing.assert_array_equal(res.padjusted, mcstat.p_adjust(res.pvalue, method="e-BH"))
    s = res.summary()
    assert s["controls"] == "false discovery rate" and "any dependence" in s["assumes"]
    assert s["expected_false_discoveries_bound"] == pytest.approx(0.05 * s["rejections_adjusted"])
    assert "assumes nothing about the dependence" in res.text()
    bh = mi.compare(ref, cand, method="BH", seed_axis=0)
    assert "PRDS" in bh.summary()["assumes"] and "positively dependent" in bh.text()
    assert "any dependence" in mi.compare(ref, cand, method="BY", seed_axis=0).summary()["assumes"]
    # the planted square is found, and e-BH finds no more than BY does
    assert s["rejections_adjusted"] > 0
    assert s["rejections_adjusted"] <= int((mcstat.p_adjust(res.pvalue, method="BY") <= 0.05).sum())


def test_cli_adjust_e_bh(tmp_path):
    rng = np.random.default_rng(12)
    ref = rng.standard_normal((8, 16, 16))
    cand = rng.standard_normal((8, 16, 16))
    np.save(tmp_path / "r.npy", ref)
    np.save(tmp_path / "c.npy", cand)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        code = main(["image-test", "-r", str(tmp_path / "r.npy"), "-c", str(tmp_path / "c.npy"), "--adjust", "e-BH"])
    assert code == 0
    assert "adjustment: e-BH (controls the false discovery rate; assumes nothing about the dependence" in out.getvalue()


# ---- calibration on filtered null images (marker stats) ----------------------
_K = np.exp(-0.5 * np.arange(-2, 3) ** 2.0)
_K /= _K.sum()


def gaussian_5x5(x):
    """A 5x5 Gaussian reconstruction filter (sigma = 1 pixel) on the last two
    axes, 'valid' (the output is 4 pixels smaller each way): neighbouring
    pixels correlate at about 0.8, pixels two apart at about 0.4."""
    y = sum(_K[i] * x[..., i:i + x.shape[-2] - 4, :] for i in range(5))
    return sum(_K[i] * y[..., i:i + y.shape[-1] - 4] for i in range(5))


@pytest.mark.stats
def test_any_discovery_rate_on_filtered_null_images():
    """Under the global null the FDR is P(any discovery).  800 pairs of 48 x
    48 images, 8 seeds a side, each seed's image white noise through the 5x5
    Gaussian: the count of pairs with any discovery must lie in the binomial
    region of a rate <= alpha for BY and e-BH, which hold under any
    dependence.  BH's is counted and shown, not required (its PRDS
    condition is not guaranteed for two-sided tests of filtered pixels; it
    was 23/800 = 0.029 at alpha = 0.05 with this seed; BY 4/800, e-BH
    1/800).  Unadjusted testing
    must fall outside the region: the check can fail."""
    runs, alpha, h, w, seeds = 800, 0.05, 48, 48, 8
    rng = np.random.default_rng(zlib.crc32(b"e-BH filtered null"))
    count = {"BH": 0, "BY": 0, "e-BH": 0, "none": 0}
    for _ in range(runs):
        x = gaussian_5x5(rng.standard_normal((2, seeds, h + 4, w + 4)))
        for method in count:
            res = mi.compare(x[0], x[1], alpha=alpha, method=method, seed_axis=0)
            count[method] += bool((res.padjusted <= alpha).any())
    rates = {k: v / runs for k, v in count.items()}
    print(f"any-discovery rates over {runs} filtered null pairs at alpha {alpha}: {rates}")
    for method in ("BY", "e-BH"):
        assert BUDGET.accept(count[method], runs, (0.0, alpha)), (
            f"{method}: {count[method]} of {runs} null pairs had a discovery; region for a rate <= {alpha}: "
            f"{BUDGET.region(runs, alpha)}")
    assert not BUDGET.accept(count["none"], runs, (0.0, alpha)), rates
