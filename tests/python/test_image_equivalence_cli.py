"""mcstat.image.equivalence's nan_policy and `mcstat image-test
--equivalence`: the verdict and exit status on an equal pair and on a 10%
change, the NaN rules (raise names the value; omit leaves it out of its
pixel's and its block's sample), the summary JSON, and the options that
belong to the difference test refused.  Fixed seeds: nothing by chance."""
import json

import numpy as np
import pytest

import mcstat
import mcstat.image as mi
from cli_run import run_cli


def _stacks(scale=1.0, seed=0):
    rng = np.random.default_rng(seed)
    base = rng.gamma(4.0, 0.25, (1, 32, 32, 3))
    a = base * rng.gamma(50, 1 / 50, (16, 32, 32, 3))
    b = scale * base * rng.gamma(50, 1 / 50, (16, 32, 32, 3))
    return a.astype(np.float32), b.astype(np.float32)


def test_nan_raises_naming_the_value():
    a, b = _stacks()
    b[3, 5, 7, 1] = np.nan
    with pytest.raises(mcstat.NonFiniteError, match=r"candidate holds NaN at seed 3, x=7, y=5 \(G\).*nan_policy='omit'"):
        mi.equivalence(a, b, margin=0.05, seed_axis=0, block=16)


def test_infinity_is_refused_even_with_omit():
    a, b = _stacks()
    a[0, 1, 2, 0] = np.inf
    with pytest.raises(mcstat.NonFiniteError, match="reference holds an infinity at seed 0, x=2, y=1"):
        mi.equivalence(a, b, margin=0.05, seed_axis=0, block=16, nan_policy="omit")


def test_bad_nan_policy_is_refused():
    a, b = _stacks()
    with pytest.raises(mcstat.InvalidArgumentError, match="nan_policy"):
        mi.equivalence(a, b, margin=0.05, seed_axis=0, nan_policy="ignore")


def test_omit_leaves_the_nan_out_of_its_pixel_and_block():
    """A NaN at seed 3 of one pixel: that pixel's p-value is the test of
    the other 15 values of its side, and its block's p-value the test of
    the other 15 seeds' block means (an oracle from the arrays with those
    values removed)."""
    a, b = _stacks()
    b[3, 5, 7, 1] = np.nan
    e = mi.equivalence(a, b, margin=0.05, seed_axis=0, block=16, nan_policy="omit", channels="rgb")
    keep = np.arange(16) != 3
    # the pixel, by the TOST on its values without the NaN
    ref_px, cand_px = a[:, 5, 7, 1].astype(np.float64), b[keep, 5, 7, 1].astype(np.float64)
    lo = mcstat.t_test(cand_px, 0.95 * ref_px, alternative="greater")
    hi = mcstat.t_test(cand_px, 1.05 * ref_px, alternative="less")
    assert e.pixel_pvalue[5, 7, 1] == pytest.approx(max(lo.pvalue, hi.pvalue), rel=1e-12)
    # the block (0, 0), by the TOST on the block means of the other seeds
    rb = a[:, :16, :16, 1].astype(np.float64).mean(axis=(1, 2))
    cb = b[keep, :16, :16, 1].astype(np.float64).mean(axis=(1, 2))
    lo = mcstat.t_test(cb, 0.95 * rb, alternative="greater")
    hi = mcstat.t_test(cb, 1.05 * rb, alternative="less")
    assert e.block_pvalue[0, 0, 1] == pytest.approx(max(lo.pvalue, hi.pvalue), rel=1e-9)
    assert e.equivalent and e.nan_policy == "omit"


def test_a_block_left_with_too_few_seeds_is_untestable():
    a, b = _stacks()
    b[1:, 0, 0, 0] = np.nan  # one seed left in the candidate's block (0, 0)
    e = mi.equivalence(a, b, margin=0.05, seed_axis=0, block=16, nan_policy="omit", channels="rgb")
    assert np.isnan(e.block_pvalue[0, 0, 0]) and e.blocks_untestable >= 1 and not e.equivalent


def _save(tmp_path, scale):
    a, b = _stacks(scale)
    np.save(tmp_path / "ref.npy", a)
    np.save(tmp_path / "cand.npy", b)


def test_cli_equal_pair_is_equivalent(tmp_path):
    _save(tmp_path, 1.0)
    js = tmp_path / "eq.json"
    code, out, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy",
                             "--equivalence", "0.05", "--json", js, "--fail-on-reject")
    assert code == 0, err
    assert "verdict: equivalent" in out
    s = json.loads(js.read_text())
    assert s["test"] == "equivalence" and s["verdict"] == "equivalent" and s["margin"] == 0.05
    assert s["blocks"] == s["blocks_shown"] == 1 and s["margin_shown"] < 0.05


def test_cli_ten_percent_change_is_not_shown_equivalent(tmp_path):
    _save(tmp_path, 1.1)
    code, out, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy",
                             "--equivalence", "0.05", "--block", "8", "--fail-on-reject")
    assert code == 1, err
    assert "verdict: not shown equivalent" in out and "blocks furthest from equivalence" in out
    # without --fail-on-reject the verdict is printed and the status is 0
    code, out, _ = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy",
                           "--equivalence", "0.05")
    assert code == 0 and "not shown equivalent" in out


def test_cli_nan_rules(tmp_path):
    a, b = _stacks()
    b[2, 3, 4, 0] = np.nan
    np.save(tmp_path / "ref.npy", a)
    np.save(tmp_path / "cand.npy", b)
    code, _, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy",
                           "--equivalence", "0.05")
    assert code == 3 and "NaN at seed 2, x=4, y=3" in err and "--nan omit" in err
    code, out, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy",
                             "--equivalence", "0.05", "--nan", "omit", "--fail-on-reject")
    assert code == 0, err


@pytest.mark.parametrize("extra,word", [(["--png", "x.png"], "--png"), (["--alternative", "less"], "--alternative"),
                                        (["--adjust", "BY"], "--adjust"),
                                        (["--max-detectable-bias", "0.1"], "--max-detectable-bias")])
def test_cli_refuses_the_difference_tests_options(tmp_path, extra, word):
    _save(tmp_path, 1.0)
    code, _, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy",
                           "--equivalence", "0.05", *extra)
    assert code == 2 and word in err


@pytest.mark.parametrize("margin,atol,word", [("1.5", "0", "--equivalence"), ("0", "0", "--atol"),
                                              ("0.05", "-1", "--atol")])
def test_cli_refuses_bad_margins(tmp_path, margin, atol, word):
    _save(tmp_path, 1.0)
    code, _, err = run_cli("image-test", "-r", tmp_path / "ref.npy", "-c", tmp_path / "cand.npy",
                           "--equivalence", margin, "--atol", atol)
    assert code == 2 and word in err
