# The per-pixel Welch test on seeds-major stacks (_core._t_test_2_pixels,
# libmcstat's mcstat_t_test_2_pixels), which mcstat.image.compare runs on
# per-seed renders: each pixel against mcstat.t_test on its two samples and
# against SciPy, float32 read in place, luminance weights, thread counts,
# NaN omission, the statuses of pixels that cannot be tested.
import tracemalloc

import numpy as np
import pytest
from scipy import stats

import mcstat
import mcstat.image as mi
from mcstat import _core

W = np.array(mi.LUMINANCE_WEIGHTS)
# the p-value bound of tests/c/test_pixels.c at p >= 1e-30: 3e-14 + 4e-16 |log p|
P_RTOL = 6e-14


def stacks(rng, k=8, m=9, shape=(6, 7), c=None, dtype=np.float64):
    s = shape + ((c,) if c else ())
    x = rng.normal(1.0, 0.2, (k,) + s) + 0.3 * rng.standard_normal(s)
    y = rng.normal(1.0, 0.3, (m,) + s)
    return x.astype(dtype), y.astype(dtype)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("alternative", ["two-sided", "less", "greater"])
def test_each_pixel_is_the_single_call(rng, dtype, alternative):
    x, y = stacks(rng, dtype=dtype)
    code = _core._alternative_code(alternative)
    r = _core._t_test_2_pixels(x, y, None, code, 0.05, intervals=True)
    for i in np.ndindex(x.shape[1:]):
        one = mcstat.t_test(x[(slice(None),) + i].astype(np.float64), y[(slice(None),) + i].astype(np.float64),
                            alternative=alternative)
        assert r["status"][i] == 0
        assert r["pvalue"][i] == pytest.approx(one.pvalue, rel=P_RTOL)
        assert r["statistic"][i] == pytest.approx(one.statistic, rel=1e-13, abs=1e-14)
        assert r["df"][i] == pytest.approx(one.df, rel=1e-13)
        assert r["mean_x"][i] == pytest.approx(one.estimate[0], rel=1e-14, abs=1e-15)
        assert r["conf_lo"][i] == pytest.approx(one.conf_int[0], rel=1e-13, abs=1e-14)
        assert r["conf_hi"][i] == pytest.approx(one.conf_int[1], rel=1e-13, abs=1e-14)


def test_luminance_weights_and_scipy(rng):
    x, y = stacks(rng, c=4, dtype=np.float32)  # RGBA: alpha weighted 0
    w = tuple(W) + (0.0,)
    r = _core._t_test_2_pixels(x, y, w, 0, 0.05)
    lx, ly = x.astype(np.float64) @ np.array(w), y.astype(np.float64) @ np.array(w)
    want = stats.ttest_ind(lx, ly, axis=0, equal_var=False)
    np.testing.assert_allclose(r["pvalue"], want.pvalue, rtol=1e-11)
    np.testing.assert_allclose(r["statistic"], want.statistic, rtol=1e-11)
    for i in [(0, 0), (3, 5), (5, 6)]:
        one = mcstat.t_test(lx[(slice(None),) + i], ly[(slice(None),) + i])
        assert r["pvalue"][i] == pytest.approx(one.pvalue, rel=P_RTOL)


def test_float32_is_read_in_place():
    rng = np.random.default_rng(5)
    x = rng.standard_normal((8, 60000, 3)).astype(np.float32)
    y = rng.standard_normal((8, 60000, 3)).astype(np.float32)
    tracemalloc.start()
    try:
        _core._t_test_2_pixels(x, y, tuple(W), 0, 0.05)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    outputs = 60000 * (5 * 8 + 4)
    # a float64 copy of one side alone would be 11.5 MB, a luminance stack 3.8 MB
    assert peak < outputs + 1_000_000, peak


def test_results_do_not_depend_on_the_thread_count(rng):
    x, y = stacks(rng, shape=(100, 123), dtype=np.float32)
    before = mcstat.get_num_threads()
    try:
        runs = []
        for t in (1, 2, 3):
            mcstat.set_num_threads(t)
            runs.append(_core._t_test_2_pixels(x, y, None, 0, 0.05, intervals=True))
    finally:
        mcstat.set_num_threads(before)
    for r in runs[1:]:
        for k in runs[0]:
            np.testing.assert_array_equal(r[k], runs[0][k])


def test_image_scale_outputs_are_ordinary_arrays(rng):
    # 2^19 pixels: each float64 output is 4 MiB, allocated apart from
    # NumPy's allocator (output_array.hpp); the same numbers as the pixels
    # computed in small pieces, writable, and alive as long as a view is
    x, y = stacks(rng, k=2, m=3, shape=(512, 1024), dtype=np.float32)
    r = _core._t_test_2_pixels(x, y, None, 0, 0.05, intervals=True)
    views = {k: v[::7, 3:] for k, v in r.items()}
    rows = [_core._t_test_2_pixels(np.ascontiguousarray(x[:, i:i + 8]), np.ascontiguousarray(y[:, i:i + 8]), None,
                                   0, 0.05, intervals=True)
            for i in range(0, 512, 8)]
    for k, v in r.items():
        assert v.flags.writeable and v.flags.c_contiguous and v.shape == (512, 1024)
        np.testing.assert_array_equal(v, np.concatenate([piece[k] for piece in rows]))
    adjusted = mcstat.p_adjust(r["pvalue"])
    np.testing.assert_array_equal(adjusted, mcstat.p_adjust(r["pvalue"].tolist()))
    want = {k: v[::7, 3:].copy() for k, v in r.items()}
    del r, rows
    _ = [np.ones(1 << 20) for _ in range(8)]  # memory freed too early would be reused here
    for k, v in views.items():
        np.testing.assert_array_equal(v, want[k])
        v[0, 0] = 0


def test_pixels_that_cannot_be_tested(rng):
    x, y = stacks(rng)
    x[:, 0, 0] = 3.0
    y[:, 0, 0] = 3.0  # constant in both: not tested
    x[:, 0, 1] = 3.0  # constant in one: tested, as in R
    x[2, 1, 1] = np.nan
    y[4, 2, 2] = np.inf
    r = _core._t_test_2_pixels(x, y, None, 0, 0.05, intervals=True)
    assert r["status"][0, 0] == mcstat.DegenerateDataError.status
    assert r["status"][0, 1] == 0
    assert r["status"][1, 1] == mcstat.NonFiniteError.status
    assert r["status"][2, 2] == mcstat.NonFiniteError.status
    for k in ("pvalue", "statistic", "df", "mean_x", "mean_y", "conf_lo", "conf_hi"):
        assert np.isnan(r[k][0, 0]) and np.isnan(r[k][1, 1]) and np.isnan(r[k][2, 2])
    om = _core._t_test_2_pixels(x, y, None, 0, 0.05, omit_nan=True)
    one = mcstat.t_test(np.delete(x[:, 1, 1], 2), y[:, 1, 1])
    assert om["status"][1, 1] == 0
    assert om["pvalue"][1, 1] == pytest.approx(one.pvalue, rel=P_RTOL)
    assert om["status"][2, 2] == mcstat.NonFiniteError.status  # Inf stays an error
    few = _core._t_test_2_pixels(x[:1], y, None, 0, 0.05)["status"]
    assert few[2, 2] == mcstat.NonFiniteError.status  # the data are read before the count is judged
    few[2, 2] = mcstat.TooFewObservationsError.status
    assert (few == mcstat.TooFewObservationsError.status).all()


def test_bad_arguments(rng):
    x, y = stacks(rng, dtype=np.float32)
    with pytest.raises(mcstat.InvalidArgumentError):
        _core._t_test_2_pixels(x, y.astype(np.float64), None, 0, 0.05)
    with pytest.raises(mcstat.InvalidArgumentError):
        _core._t_test_2_pixels(x.astype(np.int32), y.astype(np.int32), None, 0, 0.05)
    with pytest.raises(mcstat.InvalidArgumentError):
        _core._t_test_2_pixels(np.moveaxis(x, 0, -1), np.moveaxis(y, 0, -1), None, 0, 0.05)
    with pytest.raises(mcstat.InvalidArgumentError):
        _core._t_test_2_pixels(x, y, (0.5, 0.5), 0, 0.05)  # 7 channels, 2 weights
    with pytest.raises(mcstat.InvalidArgumentError):
        _core._t_test_2_pixels(x, y, None, 0, 1.5)
    with pytest.raises(mcstat.InvalidArgumentError):
        _core._t_test_2_pixels(x, y, None, 9, 0.05)


def test_compare_omit_nan_and_luminance(rng):
    ref, cand = stacks(rng, c=3, dtype=np.float32)
    cand[3, 2, 4, 1] = np.nan
    with pytest.raises(mcstat.NonFiniteError):
        mi.compare(ref, cand)
    res = mi.compare(ref, cand, nan_policy="omit", render_guards=False)
    lc, lr = cand.astype(np.float64) @ W, ref.astype(np.float64) @ W
    for i in [(2, 4), (0, 0), (5, 6)]:
        a, b = lc[(slice(None),) + i], lr[(slice(None),) + i]
        one = mcstat.t_test(a[~np.isnan(a)], b)
        assert res.pvalue[i + (0,)] == pytest.approx(one.pvalue, rel=P_RTOL)
        assert res.statistic[i + (0,)] == pytest.approx(one.statistic, rel=1e-13)
    assert res.pvalue.shape == ref.shape[1:3] + (1,)


def test_handed_over_sides_are_released_after_the_tests(rng, monkeypatch):
    """mcstat_app hands its loaded renders over (Owned): compare gives the
    same results and holds no reference to them by the time it adjusts
    the p-values, so their memory is gone before the adjustment's."""
    import gc
    import weakref

    x = rng.normal(1.0, 0.1, (6, 20, 30, 3)).astype(np.float32)
    y = rng.normal(1.0, 0.1, (6, 20, 30, 3)).astype(np.float32)
    kept = mi.compare(y, x)
    bx, by = mi.Owned(x.copy()), mi.Owned(y.copy())
    gone = [weakref.ref(bx.value), weakref.ref(by.value)]
    alive_at_adjust = []
    adjust = _core.p_adjust

    def watching(*a, **k):
        gc.collect()
        work = k.get("work")
        # the one render still held is the adjustment's workspace
        alive_at_adjust.append([w() is not None and not (work is not None and np.shares_memory(work, w()))
                                for w in gone])
        alive_at_adjust.append(work is not None)
        return adjust(*a, **k)

    monkeypatch.setattr(mi._core, "p_adjust", watching)
    res = mi.compare(by, bx)
    assert alive_at_adjust == [[False, False], True]
    gc.collect()
    assert all(w() is None for w in gone)
    assert bx.value is None and by.value is None
    for name in ("pvalue", "padjusted", "statistic", "mean_candidate", "mean_reference", "detectable_bias"):
        np.testing.assert_array_equal(getattr(res, name), getattr(kept, name))
    # sides not handed over are the caller's: left as they are
    mi.compare(y, x)
    assert x.shape == (6, 20, 30, 3)


@pytest.mark.parametrize("channels", ["luminance", "rgb"])
def test_map_background_is_the_reference_mean_luminance(rng, channels):
    """The map's grey background comes from the means the tests computed
    (the luminance's, or the channels' weighted): the reference's mean
    luminance, as a separate pass over the renders would give it."""
    x = rng.normal(1.0, 0.3, (5, 12, 17, 3)).astype(np.float32)
    y = rng.normal(2.0, 0.3, (5, 12, 17, 3)).astype(np.float32)
    res = mi.compare(y, x, channels=channels)
    want = np.einsum("...c,c->...", y.astype(np.float64).mean(axis=0), np.asarray(mi.LUMINANCE_WEIGHTS))
    np.testing.assert_allclose(res.reference_luminance, want, rtol=1e-14)
    assert res.reference_luminance.shape == (12, 17)


def test_app_compare_leaves_the_callers_sides_alone(rng, tmp_path):
    """mcstat_app.image.compare hands over only what it loaded from files:
    a caller's own Samples keep their data; file sides give the same
    result."""
    from mcstat_app import image as app

    x = rng.normal(1.0, 0.1, (6, 10, 14, 3)).astype(np.float32)
    y = rng.normal(1.0, 0.1, (6, 10, 14, 3)).astype(np.float32)
    sx, sy = mi.Samples(x, ["R", "G", "B"]), mi.Samples(y, ["R", "G", "B"])
    res = app.compare(sy, sx)
    assert sx.data is x and sy.data is y
    np.save(tmp_path / "ref.npy", y)
    res_files = app.compare(str(tmp_path / "ref.npy"), sx)
    assert sx.data is x
    np.testing.assert_array_equal(res_files.pvalue, res.pvalue)
    np.testing.assert_array_equal(res_files.detectable_bias, res.detectable_bias)
