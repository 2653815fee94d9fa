"""Row-wise tests on N-D input (the per-pixel case)."""
import numpy as np
import pytest
import scipy.stats as st

import mcstat
from pixel_bounds import assert_var_close, assert_welch_close


@pytest.fixture(autouse=True)
def restore_threads():
    yield
    mcstat.set_num_threads(0)


def test_rows_agree_with_scipy(rng):
    X = rng.normal(size=(500, 16))
    Y = rng.normal(0.2, 2, size=(500, 24))
    for alt in ("two-sided", "less", "greater"):
        b = mcstat.t_test(X, Y, alternative=alt)
        s = st.ttest_ind(X, Y, axis=1, equal_var=False, alternative=alt)
        np.testing.assert_allclose(b.statistic, s.statistic, rtol=1e-12)
        np.testing.assert_allclose(b.pvalue, s.pvalue, rtol=1e-12)
        np.testing.assert_allclose(b.df, s.df, rtol=1e-12)
        ci = s.confidence_interval()
        np.testing.assert_allclose(b.conf_int[:, 0], ci.low, rtol=1e-12)
        np.testing.assert_allclose(b.conf_int[:, 1], ci.high, rtol=1e-12)
        b1 = mcstat.t_test(X, mu=0.1, alternative=alt)
        s1 = st.ttest_1samp(X, 0.1, axis=1, alternative=alt)
        np.testing.assert_allclose(b1.pvalue, s1.pvalue, rtol=1e-12)


@pytest.mark.parametrize("func,kw", [(mcstat.t_test, {}), (mcstat.t_test, {"mu": 0.3}),
                                     (mcstat.var_test, {"sigma2": 1.5}), (mcstat.var_test, {"ratio": 0.7})])
def test_each_row_is_the_single_call(rng, func, kw):
    two = "sigma2" not in kw and "mu" not in kw
    X = rng.normal(size=(37, 12))
    Y = rng.normal(size=(37, 9)) if two else None
    b = func(X, Y, **kw) if two else func(X, **kw)
    welch = func is mcstat.t_test and two
    for i in range(37):
        r = func(X[i], Y[i], **kw) if two else func(X[i], **kw)
        if welch:  # the block paths, to the bounds of mcstat.h
            assert_welch_close(b[i], r)
            continue
        if func is mcstat.var_test:
            assert_var_close(b[i], r)
            continue
        assert b[i]._raw() == r._raw()
        assert b.statistic[i] == r.statistic and b.pvalue[i] == r.pvalue
        assert b.decision[i] == r.decision and b.reject[i] == r.reject
    assert b.shape == (37,) and len(b) == 37


def test_fields_shapes(rng):
    X, Y = rng.normal(size=(3, 4, 10)), rng.normal(size=(3, 4, 8))
    b = mcstat.t_test(X, Y)
    assert b.statistic.shape == (3, 4) and b.conf_int.shape == (3, 4, 2) and b.estimate.shape == (3, 4, 2)
    assert b.critical_values.shape == (3, 4, 2) and b.df.shape == (3, 4) and b.nobs.shape == (3, 4, 2)
    assert b.decision.dtype.kind == "U" and b.reject.dtype == bool and b.pvalue_se.shape == (3, 4)
    f = mcstat.var_test(X, Y)
    assert f.df.shape == (3, 4, 2) and f.estimate.shape == (3, 4)
    assert (f.df[..., 0] == 9).all() and (f.df[..., 1] == 7).all()
    assert_welch_close(b[1, 2], mcstat.t_test(X[1, 2], Y[1, 2]))
    # one index of a 2-D batch: the sub-batch of that row of tests (as NumPy)
    assert b[1].shape == (4,) and b[1][2]._raw() == b[1, 2]._raw()
    with pytest.raises(IndexError):
        b[1, 2, 0]
    assert "Welch Two Sample t-test" in str(b) and "failed" in repr(b)


def test_axis_and_layouts_are_read_correctly(rng):
    base = rng.normal(size=(20, 30))
    ref = mcstat.t_test(base, mu=0.05)
    variants = [
        mcstat.t_test(np.asfortranarray(base), mu=0.05),          # rows strided
        mcstat.t_test(base.T.copy(), mu=0.05, axis=0),             # tests along axis 0
        mcstat.t_test(np.ascontiguousarray(base.T), mu=0.05, axis=-2),
        mcstat.t_test(np.repeat(base, 2, axis=1)[:, ::2], mu=0.05),  # values strided
        mcstat.t_test(base.astype(np.float32).astype(np.float64), mu=0.05),
    ]
    for v in variants[:4]:
        np.testing.assert_array_equal(v.statistic, ref.statistic)
        np.testing.assert_array_equal(v.conf_int, ref.conf_int)
    cube = rng.normal(size=(4, 5, 6))
    b = mcstat.t_test(cube, axis=1)
    assert b.shape == (4, 6)
    assert b[2, 3]._raw() == mcstat.t_test(cube[2, :, 3])._raw()


def test_results_do_not_depend_on_threads(rng):
    X, Y = rng.normal(size=(5000, 8)), rng.normal(size=(5000, 11))
    X[123, 4] = np.nan
    out = []
    for t in (1, 2, 3):
        mcstat.set_num_threads(t)
        assert mcstat.get_num_threads() == t
        b = mcstat.t_test(X, Y, on_error="nan")
        out.append(np.concatenate([b.statistic, b.pvalue, b.conf_int.ravel(), b.df]))
    np.testing.assert_array_equal(out[0], out[1])
    np.testing.assert_array_equal(out[0], out[2])


def test_bad_rows_are_named(rng):
    X = rng.normal(size=(100, 10))
    X[[3, 50, 51, 52, 60, 61, 99], 2] = np.nan
    X[70] = 4.0  # constant
    with pytest.raises(mcstat.NonFiniteError) as e:
        mcstat.t_test(X)
    msg = str(e.value)
    assert "8 of 100 rows failed" in msg and "rows 3, 50, 51, 52, 60 and 3 more" in msg
    assert "1 of them failed for another reason" in msg and "on_error='nan'" in msg
    assert list(e.value.rows) == [3, 50, 51, 52, 60, 61, 70, 99]
    b = mcstat.t_test(X, on_error="nan")
    assert np.isnan(b.pvalue[3]) and not b.reject[3] and b.decision[3] == "" and b.status[3] == 3
    assert b.status[70] == 4 and not b.ok[70] and b.ok.sum() == 92
    assert np.isfinite(b.pvalue[b.ok]).all()
    with pytest.raises(mcstat.NonFiniteError):
        b[3]
    # omit drops the NaN values; the constant row still fails
    with pytest.raises(mcstat.DegenerateDataError) as e:
        mcstat.t_test(X, nan_policy="omit")
    assert list(e.value.rows) == [70]
    X3 = rng.normal(size=(2, 3, 5))
    X3[1, 2, 0] = np.inf
    with pytest.raises(mcstat.NonFiniteError, match=r"rows \(1, 2\)") as e:
        mcstat.t_test(X3)
    assert e.value.rows.tolist() == [[1, 2]]


def test_shape_errors(rng):
    with pytest.raises(mcstat.InvalidArgumentError, match="same shape except along axis"):
        mcstat.t_test(rng.normal(size=(4, 5)), rng.normal(size=(3, 5)))
    with pytest.raises(mcstat.InvalidArgumentError, match="same number of dimensions"):
        mcstat.t_test(rng.normal(size=(4, 5)), rng.normal(size=5))
    with pytest.raises(mcstat.InvalidArgumentError, match="axis 2 is out of range"):
        mcstat.t_test(rng.normal(size=(4, 5)), axis=2)
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.t_test(np.zeros((3, 1)) + np.arange(3)[:, None])
    empty = mcstat.t_test(np.zeros((0, 5)))
    assert empty.shape == (0,)


def test_intervals_false_rows(rng):
    X = rng.normal(size=(50, 20))
    a, b = mcstat.t_test(X), mcstat.t_test(X, intervals=False)
    np.testing.assert_array_equal(a.pvalue, b.pvalue)
    assert np.isnan(b.conf_int).all() and np.isnan(b.critical_values).all()


def test_batch_iterates_like_an_array():
    rng = np.random.default_rng(11)
    x = rng.standard_normal((4, 3, 12)) + 0.2
    b = mcstat.t_test(x, mu=0.0)
    assert b.shape == (4, 3) and len(b) == 4
    subs = list(b)
    assert len(subs) == len(b) == 4
    for i, sub in enumerate(subs):
        assert sub.shape == (3,) and len(list(sub)) == 3
        np.testing.assert_array_equal(sub.pvalue, b.pvalue[i])
        for j, r in enumerate(sub):
            want = mcstat.t_test(x[i, j], mu=0.0)
            assert r.pvalue == want.pvalue == b[i, j].pvalue
            assert r.conf_int == b[i, j].conf_int
    flat = list(b.ravel())
    assert len(flat) == 12 and b.ravel().shape == (12,)
    assert [r.statistic for r in flat] == list(b.statistic.ravel())
    assert b[-1].shape == (3,) and b[-1, -1].pvalue == b.pvalue[3, 2]
    # 1-D: TestResults, as before
    one = mcstat.t_test(x.reshape(12, 12), mu=0.0)
    assert [r.pvalue for r in one] == list(one.pvalue)
    with pytest.raises(IndexError):
        b[4]
    with pytest.raises(IndexError):
        b[0, 3]
    with pytest.raises(IndexError):
        b[0, 0, 0]
    # pairs (conf_int, two-sample estimate) keep their trailing axis
    y = rng.standard_normal((4, 3, 9))
    w = mcstat.t_test(x, y)
    assert w[1].conf_int.shape == (3, 2) and w.ravel().estimate.shape == (12, 2)
    assert w[1][2].estimate == w[1, 2].estimate
