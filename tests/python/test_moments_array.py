"""mcstat.MomentsArray: one accumulator per pixel (the render-farm case).

Every pixel must be bit for bit the `Moments` that received the same values
(the C library's add_rows is "add_array on a fresh accumulator, then merge",
which is what Moments.push does), merging arrays built on different
"machines" must reproduce one machine's pushes bit for bit in a fixed order
and to rounding otherwise, and the per-pixel tests must be the single tests
on each pixel's accumulator, bit for bit.  NumPy on the raw data is the
independent oracle for means and variances."""
import copy
import pickle

import numpy as np
import pytest
import scipy.stats as st

import mcstat
from pixel_bounds import assert_pvalues_close

SHAPE = (5, 7)


def stack(rng, k, shape=SHAPE, loc=0.0, scale=1.0):
    grid = np.arange(int(np.prod(shape)), dtype=float).reshape(shape)
    return loc + 0.1 * grid + scale * rng.normal(size=(k,) + shape)


def pixel_moments(batches, idx):
    """The single-accumulator way: one Moments per pixel, same pushes."""
    m = mcstat.Moments()
    for b in batches:
        m.push(np.ascontiguousarray(b[(slice(None),) + idx]) if b.ndim > len(idx) else np.array([b[idx]]))
    return m


def test_push_stacks_and_images_bit_identical_to_moments(rng):
    batches = [stack(rng, 13), stack(rng, 1)[0], stack(rng, 8)]  # a stack, one image, a stack
    acc = mcstat.MomentsArray(SHAPE)
    for b in batches:
        assert acc.push(b) is acc
    assert acc.shape == SHAPE and acc.size == 35 and acc.ndim == 2 and len(acc) == 5
    assert (acc.n == 22).all() and acc.n.dtype == np.int64
    for idx in np.ndindex(*SHAPE):
        ref = pixel_moments(batches, idx)
        assert acc[idx] == ref  # 96-byte records equal
        assert acc.mean[idx] == ref.mean and acc.var[idx] == ref.var and acc.sd[idx] == ref.sd
        assert acc.min[idx] == ref.min and acc.max[idx] == ref.max
    assert acc[-1, -1] == acc[4, 6]


def test_against_numpy_on_raw_data(rng):
    data = stack(rng, 40, shape=(6, 4, 3), loc=2.0, scale=0.5)
    acc = mcstat.MomentsArray((6, 4, 3)).push(data[:25]).push(data[25:])
    np.testing.assert_allclose(acc.mean, data.mean(axis=0), rtol=1e-14)
    np.testing.assert_allclose(acc.var, data.var(axis=0, ddof=1), rtol=1e-12)
    np.testing.assert_array_equal(acc.min, data.min(axis=0))
    np.testing.assert_array_equal(acc.max, data.max(axis=0))
    # a 1-D "image" and a non-contiguous stack are read correctly
    flat = mcstat.MomentsArray(12).push(data[:, :, :, 0].reshape(40, 24)[:, ::2])
    np.testing.assert_allclose(flat.mean, data[:, :, :, 0].reshape(40, 24)[:, ::2].mean(axis=0), rtol=1e-14)


def test_distributed_merge_equals_single_machine(rng):
    batches = [stack(rng, 10) for _ in range(8)]
    one = mcstat.MomentsArray(SHAPE)
    for b in batches:
        one.push(b)
    # per-batch accumulators on "workers", folded left in batch order: bit for bit
    fold = mcstat.MomentsArray(SHAPE)
    for b in batches:
        fold.merge(mcstat.MomentsArray(SHAPE).push(b))
    assert fold == one
    # a tree ((0+1)+(2+3)) + ... and shipped through bytes: equal to rounding
    parts = [mcstat.MomentsArray.from_bytes(mcstat.MomentsArray(SHAPE).push(b).to_bytes(), SHAPE) for b in batches]
    while len(parts) > 1:
        parts = [parts[i] + parts[i + 1] for i in range(0, len(parts), 2)]
    tree = parts[0]
    assert (tree.n == one.n).all()
    np.testing.assert_allclose(tree.mean, one.mean, rtol=1e-15, atol=0)
    np.testing.assert_allclose(tree.var, one.var, rtol=1e-13, atol=0)


def test_offset_data_survives_merging(rng):
    """1e9 + noise of 1e-3: the spread is 1e-12 of the values.  Merged over
    many small batches the variance must still match the exact one (NumPy
    on the noise alone, computed without the offset)."""
    noise = rng.normal(scale=1e-3, size=(64, 3, 4))
    data = 1e9 + noise
    noise_exact = data - 1e9  # the values actually stored (exact subtraction)
    parts = [mcstat.MomentsArray((3, 4)).push(data[i:i + 4]) for i in range(0, 64, 4)]
    while len(parts) > 1:
        parts = [parts[i] + parts[i + 1] for i in range(0, len(parts), 2)]
    acc = parts[0]
    np.testing.assert_allclose(acc.var, noise_exact.var(axis=0, ddof=1), rtol=1e-12)
    # the mean's offset from 1e9 is kept to double-double precision, so a t
    # test against 1e9 + the exact noise mean does not reject on rounding
    r = mcstat.t_test(acc, mu=1e9)
    ref = st.ttest_1samp(noise_exact, 0.0, axis=0)
    np.testing.assert_allclose(r.statistic, ref.statistic, rtol=1e-12)


@pytest.mark.parametrize("func,kw", [(mcstat.t_test, {"mu": 0.3}), (mcstat.t_test, {}),
                                     (mcstat.var_test, {"sigma2": 1.5}), (mcstat.var_test, {"ratio": 0.7})])
@pytest.mark.parametrize("alternative", ["two-sided", "less", "greater"])
def test_per_pixel_tests_are_the_single_calls(rng, func, kw, alternative):
    two = "sigma2" not in kw and "mu" not in kw
    x = mcstat.MomentsArray(SHAPE).push(stack(rng, 12))
    y = mcstat.MomentsArray(SHAPE).push(stack(rng, 9, loc=0.1, scale=1.3))
    b = func(x, y, alternative=alternative, **kw) if two else func(x, alternative=alternative, **kw)
    assert isinstance(b, mcstat.BatchResult) and b.shape == SHAPE
    for idx in np.ndindex(*SHAPE):
        r = func(x[idx], y[idx], alternative=alternative, **kw) if two else func(x[idx], alternative=alternative, **kw)
        assert b[idx]._raw() == r._raw()
        assert b.pvalue[idx] == r.pvalue and b.reject[idx] == r.reject and b.decision[idx] == r.decision
    # and the same as the row-wise test on the raw arrays when the pushes were one stack each
    if two:
        X, Y = stack(rng, 12), stack(rng, 9)
        bx = func(mcstat.MomentsArray(SHAPE).push(X), mcstat.MomentsArray(SHAPE).push(Y), **kw)
        ba = func(np.moveaxis(X, 0, -1), np.moveaxis(Y, 0, -1), **kw)
        # both two-sample tests here (Welch, F) run on block paths: the bounds of mcstat.h
        assert_pvalues_close(ba.pvalue, bx.pvalue)
        np.testing.assert_allclose(ba.statistic, bx.statistic, rtol=1e-14, atol=1e-14)


def test_welch_against_scipy_and_broadcast_reference(rng):
    X, Y = stack(rng, 30), stack(rng, 20, loc=0.05)
    x, y = mcstat.MomentsArray(SHAPE).push(X), mcstat.MomentsArray(SHAPE).push(Y)
    b = mcstat.t_test(x, y, alternative="less")
    s = st.ttest_ind(X, Y, axis=0, equal_var=False, alternative="less")
    np.testing.assert_allclose(b.statistic, s.statistic, rtol=1e-12)
    np.testing.assert_allclose(b.pvalue, s.pvalue, rtol=1e-12)
    # one reference accumulator against every pixel
    ref = mcstat.Moments(Y[:, 2, 3])
    c = mcstat.t_test(x, ref)
    for idx in [(0, 0), (2, 3), (4, 6)]:
        assert c[idx]._raw() == mcstat.t_test(x[idx], ref)._raw()
    d = mcstat.var_test(ref, x)
    assert d[1, 1]._raw() == mcstat.var_test(ref, x[1, 1])._raw()


def test_intervals_false_and_failed_pixels(rng):
    x = mcstat.MomentsArray(SHAPE).push(stack(rng, 6))
    x.push(np.full(SHAPE, 1.0))
    b = mcstat.t_test(x, intervals=False)
    assert np.isnan(b.conf_int).all() and np.isfinite(b.pvalue).all()
    # pixels with too few values fail: raise naming them, or NaN on request
    sparse = mcstat.MomentsArray((2, 2)).push(np.ones((2, 2)))
    sparse.push(np.array([[2.0, np.nan], [3.0, np.nan]]), nan_policy="omit")
    with pytest.raises(mcstat.TooFewObservationsError, match="2 of 4 rows"):
        mcstat.t_test(sparse)
    r = mcstat.t_test(sparse, on_error="nan")
    assert r.ok.tolist() == [[True, False], [True, False]] and np.isnan(r.pvalue[0, 1])
    assert sparse.n.tolist() == [[2, 1], [2, 1]]


def test_bytes_and_pickle(rng):
    acc = mcstat.MomentsArray((3, 4)).push(stack(rng, 5, shape=(3, 4), loc=1e6))
    b = acc.to_bytes()
    assert len(b) == 12 * 96
    assert b[96 * 5:96 * 6] == acc[1, 1].to_bytes()  # C order, the single record
    assert mcstat.MomentsArray.from_bytes(b, (3, 4)) == acc
    flat = mcstat.MomentsArray.from_bytes(b)
    assert flat.shape == (12,) and flat.to_bytes() == b
    for copied in (pickle.loads(pickle.dumps(acc)), copy.deepcopy(acc), acc.copy()):
        assert copied == acc and copied is not acc
    c = acc.copy().push(np.zeros((3, 4)))
    assert c != acc and (acc.n == 5).all()  # copies are independent
    assert mcstat.MomentsArray.from_bytes(mcstat.MomentsArray((0,)).to_bytes(), (0,)).size == 0
    assert "shape=(3, 4)" in repr(acc) and "n=5" in repr(acc)


def test_bad_input():
    acc = mcstat.MomentsArray((2, 3)).push(np.ones((4, 2, 3)))
    before = acc.to_bytes()
    bad = np.ones((2, 2, 3))
    bad[1, 0, 2] = np.nan
    with pytest.raises(mcstat.NonFiniteError, match="unchanged"):
        acc.push(bad)
    bad[1, 0, 2] = np.inf
    with pytest.raises(mcstat.NonFiniteError):
        acc.push(bad, nan_policy="omit")
    assert acc.to_bytes() == before  # atomic: nothing was added
    with pytest.raises(mcstat.InvalidArgumentError, match="shape"):
        acc.push(np.ones((3, 2)))
    with pytest.raises(mcstat.InvalidArgumentError, match="nan_policy"):
        acc.push(np.ones((2, 3)), nan_policy="ignore")
    with pytest.raises(TypeError):
        acc.push(None)
    with pytest.raises(mcstat.InvalidArgumentError, match="shapes differ"):
        acc.merge(mcstat.MomentsArray((3, 2)))
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.MomentsArray((-1, 2))
    with pytest.raises(TypeError):
        mcstat.MomentsArray("abc")
    corrupt = bytearray(before)
    corrupt[100] ^= 0xFF
    with pytest.raises(mcstat.CorruptDataError):
        mcstat.MomentsArray.from_bytes(bytes(corrupt), (2, 3))
    with pytest.raises(mcstat.CorruptDataError, match="bytes given"):
        mcstat.MomentsArray.from_bytes(before[:-1], (2, 3))
    with pytest.raises(mcstat.CorruptDataError):
        mcstat.MomentsArray.from_bytes(before, (3, 3))
    with pytest.raises(IndexError):
        acc[2, 0]
    with pytest.raises(IndexError):
        acc[0]
    # tests: a MomentsArray beside a raw array, mismatched shapes, bad alpha
    with pytest.raises(mcstat.InvalidArgumentError, match="MomentsArray"):
        mcstat.t_test(acc, np.ones(5))
    with pytest.raises(mcstat.InvalidArgumentError, match="same shape"):
        mcstat.t_test(acc, mcstat.MomentsArray((3, 2)).push(np.ones((3, 3, 2))))
    with pytest.raises(mcstat.InvalidArgumentError, match="alpha"):
        mcstat.t_test(acc, alpha=1.5)
    with pytest.raises(mcstat.DegenerateDataError):  # every pixel constant
        mcstat.t_test(acc)


@pytest.mark.parametrize("func,kw", [(mcstat.t_test, {"mu": 1.0}), (mcstat.t_test, {}),
                                     (mcstat.var_test, {"sigma2": 4.0}), (mcstat.var_test, {})])
def test_merged_arrays_are_calibrated(func, kw):
    """Under H0, pixels whose samples were pushed on four "machines" and
    merged reject at rate alpha (99.9% binomial bounds over 4000 pixels)."""
    rng = np.random.default_rng(99)
    shape, alpha = (40, 100), 0.05
    two = not kw

    def farm():
        parts = [mcstat.MomentsArray(shape).push(rng.normal(1.0, 2.0, size=(int(k),) + shape)) for k in (3, 5, 4, 6)]
        return (parts[0] + parts[1]) + (parts[2] + parts[3])

    x = farm()
    r = func(x, farm(), alpha=alpha) if two else func(x, alpha=alpha, **kw)
    lo, hi = st.binom.ppf([0.0005, 0.9995], x.size, alpha)
    assert lo <= r.reject.sum() <= hi, (int(r.reject.sum()), lo, hi)
    # and a shifted mean / inflated variance is found (power)
    y = mcstat.MomentsArray(shape).push(rng.normal(3.5, 4.0, size=(30,) + shape))
    p = func(x, y, alpha=alpha) if two else func(y, alpha=alpha, **kw)
    assert p.reject.mean() > 0.5
