"""mcstat.t_test / var_test with axis= on image stacks (mcstat_pixels_test):
every test, layout and dtype against the single call on each pixel's
values, threads=, lazily formed fields, nan_policy."""
import numpy as np
import pytest

import mcstat
from mcstat._result import _Lazy
from pixel_bounds import assert_pvalues_close, assert_var_close, assert_welch_close

H, W, N = 5, 7, 8
TESTS = [  # (function, kwargs, two samples)
    (mcstat.t_test, {"mu": 0.2}, False),
    (mcstat.t_test, {}, True),
    (mcstat.t_test, {"equal_var": True, "mu": -0.1}, True),
    (mcstat.t_test, {"paired": True}, True),
    (mcstat.var_test, {"sigma2": 0.8}, False),
    (mcstat.var_test, {"ratio": 1.3}, True),
]


def stacks(rng, dtype):
    x = rng.normal(0.3, 1.0, size=(N, H, W)).astype(dtype)
    y = rng.normal(0.1, 1.4, size=(N, H, W)).astype(dtype)
    x[:, 0, 0] = 2.5  # a constant pixel: a failing pixel in every test
    return x, y


def layouts(x):
    """(array, axis) holding the same per-pixel samples in different memory."""
    return [
        (x, 0),                                       # seeds-major, as renderers write
        (np.ascontiguousarray(np.moveaxis(x, 0, -1)), -1),  # rows of values per pixel
        (np.ascontiguousarray(np.moveaxis(x, 0, 1)), 1),    # seeds in the middle
        (np.moveaxis(x, 0, -1)[:, ::-1], -1),          # a reversed, non-contiguous view
    ]


def pixel_values(a, axis, i, j):
    v = np.moveaxis(a, axis, 0)
    return v[:, i, j] if v.ndim == 3 else v[:, i, j]


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
@pytest.mark.parametrize("func,kw,two", TESTS)
@pytest.mark.parametrize("alternative", ["two-sided", "less", "greater"])
def test_every_pixel_is_the_single_call(rng, dtype, func, kw, two, alternative):
    x, y = stacks(rng, dtype)
    for (a, axis), (b, _) in zip(layouts(x), layouts(y)):
        args = (a, b) if two else (a,)
        res = func(*args, axis=axis, alternative=alternative, on_error="nan", **kw)
        assert res.shape == (H, W)
        for i in range(H):
            for j in range(W):
                xs = pixel_values(a, axis, i, j).astype(np.float64)
                ys = pixel_values(b, axis, i, j).astype(np.float64)
                try:
                    r = func(*((xs, ys) if two else (xs,)), alternative=alternative, **kw)
                except mcstat.McstatError:
                    assert res.status[i, j] != 0 and np.isnan(res.pvalue[i, j]) and not res.reject[i, j]
                    continue
                assert res.status[i, j] == 0
                if func is mcstat.t_test and two and not kw:
                    assert_welch_close(res[i, j], r)
                elif func is mcstat.var_test:
                    assert_var_close(res[i, j], r)
                else:
                    assert res[i, j]._raw() == r._raw()


@pytest.mark.parametrize("func,kw,two", TESTS)
def test_without_intervals_and_with_threads(rng, func, kw, two):
    x, y = rng.normal(size=(6, 300, 40)), rng.normal(size=(6, 300, 40))
    args = (x, y) if two else (x,)
    full = func(*args, axis=0, threads=1, **kw)
    fast = func(*args, axis=0, threads=2, intervals=False, **kw)
    np.testing.assert_array_equal(full.pvalue, fast.pvalue)  # threads change no bit
    np.testing.assert_array_equal(full.statistic, fast.statistic)
    np.testing.assert_array_equal(full.decision_code, fast.decision_code)
    assert np.isnan(fast.conf_int).all() and np.isnan(fast.critical_values).all()
    assert np.isfinite(full.conf_int).all()
    again = func(*args, axis=0, threads=2, **kw)
    np.testing.assert_array_equal(full.conf_int, again.conf_int)


def test_fields_are_formed_when_read(rng):
    x, y = rng.normal(size=(8, 20, 30)), rng.normal(size=(8, 20, 30))
    b = mcstat.t_test(x, y, axis=0)
    raw = dict.__getitem__
    assert all(isinstance(raw(b._f, k), _Lazy) for k in ("conf_int", "estimate", "critical_values", "nobs", "reject"))
    assert b.conf_int.shape == (20, 30, 2) and not isinstance(raw(b._f, "conf_int"), _Lazy)
    assert (b.nobs == 8).all() and b.estimate.shape == (20, 30, 2)


def test_mixed_and_integer_dtypes_read_as_float64(rng):
    x = rng.integers(0, 10, size=(9, 4, 5))
    y = rng.normal(5, 3, size=(9, 4, 5)).astype(np.float32)
    b = mcstat.var_test(x, y, axis=0)
    for i, j in [(0, 0), (3, 4)]:
        r = mcstat.var_test(x[:, i, j].astype(float), y[:, i, j].astype(float))
        assert_var_close(b[i, j], r)
    big = np.moveaxis(rng.normal(size=(4, 6, 8)).astype(">f8"), 0, -1)  # non-native byte order
    assert mcstat.t_test(big, mu=0.0)[2, 3]._raw() == mcstat.t_test(big[2, 3].astype(float))._raw()


def test_nan_policies(rng):
    x, y = rng.normal(size=(8, 3, 4)), rng.normal(size=(8, 3, 4))
    x[2, 1, 1] = np.nan
    with pytest.raises(mcstat.McstatError):
        mcstat.t_test(x, y, axis=0)
    p = mcstat.t_test(x, y, axis=0, nan_policy="propagate")
    assert np.isnan(p.pvalue[1, 1]) and np.isfinite(np.delete(p.pvalue.ravel(), 5)).all()
    o = mcstat.t_test(x, y, axis=0, nan_policy="omit")
    assert tuple(o.nobs[1, 1]) == (7, 8) and (o.nobs[0, 0] == 8).all()
    r = mcstat.t_test(np.delete(x[:, 1, 1], 2), y[:, 1, 1])
    assert_welch_close(o[1, 1], r)
    q = mcstat.t_test(x, y, axis=0, paired=True, nan_policy="omit")
    assert q.nobs[1, 1] == 7
    keep = ~np.isnan(x[:, 1, 1])
    assert q[1, 1]._raw() == mcstat.t_test(x[keep, 1, 1], y[keep, 1, 1], paired=True)._raw()


@pytest.mark.parametrize("bad,err", [(0, ValueError), (65, ValueError), ("2", TypeError), (1.5, TypeError)])
def test_threads_argument(rng, bad, err):
    x = rng.normal(size=(4, 3, 3))
    with pytest.raises(err, match="threads"):
        mcstat.t_test(x, axis=0, threads=bad)


@pytest.mark.parametrize("kw,two", [({"sigma2": 0.8}, False), ({"ratio": 1.3}, True)])
@pytest.mark.parametrize("alternative", ["two-sided", "less", "greater"])
def test_variance_block_path(rng, kw, two, alternative):
    # the variance tests' table (pixels_var.c) over many statistics
    x = rng.normal(0.0, 1.0, size=(6, 180, 100)) * rng.uniform(0.3, 3.0, size=(180, 100))
    y = rng.normal(0.0, 1.0, size=(9, 180, 100))
    args = (x, y) if two else (x,)
    b = mcstat.var_test(*args, axis=0, alternative=alternative, threads=1, **kw)
    sel = [(i, j) for i in range(0, 180, 7) for j in range(0, 100, 3)]
    want = np.array([mcstat.var_test(*((x[:, i, j], y[:, i, j]) if two else (x[:, i, j],)),
                                     alternative=alternative, **kw).pvalue for i, j in sel])
    got = np.array([b.pvalue[i, j] for i, j in sel])
    assert_pvalues_close(got, want)
    for i, j in sel[:50]:
        r = mcstat.var_test(*((x[:, i, j], y[:, i, j]) if two else (x[:, i, j],)), alternative=alternative, **kw)
        assert b.critical_values[i, j].tolist() == list(r.critical_values)
        np.testing.assert_allclose(b.statistic[i, j], r.statistic, rtol=1e-14)
        np.testing.assert_allclose(b.conf_int[i, j], r.conf_int, rtol=1e-14)
        assert b.decision[i, j] == r.decision
