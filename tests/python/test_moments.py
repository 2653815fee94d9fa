"""mcstat.Moments and mcstat.batch_means."""
import copy
import math
import pickle

import numpy as np
import pytest
import scipy.stats as st

import mcstat


def test_moments_values(rng):
    x = rng.normal(3, 2, size=1001)
    m = mcstat.Moments(x)
    assert m.n == 1001
    assert m.mean == pytest.approx(x.mean(), rel=1e-15)
    assert m.var == pytest.approx(x.var(ddof=1), rel=1e-14)
    assert m.sd == pytest.approx(x.std(ddof=1), rel=1e-14) and m.std == m.sd
    assert m.skewness == pytest.approx(st.skew(x), rel=1e-12)
    assert m.kurtosis == pytest.approx(st.kurtosis(x), rel=1e-12)
    assert (m.min, m.max) == (x.min(), x.max())


def test_empty_and_single():
    m = mcstat.Moments()
    assert m.n == 0 and np.isnan(m.mean) and np.isnan(m.var) and np.isnan(m.min) and np.isnan(m.max)
    m.push(2.5)
    assert m.n == 1 and m.mean == 2.5 and np.isnan(m.var) and m.min == m.max == 2.5
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.t_test(m)


def test_push_merge_add(rng):
    x = rng.normal(size=5000)
    whole = mcstat.Moments(x)
    parts = [mcstat.Moments(p) for p in np.array_split(x, 7)]
    merged = mcstat.Moments()
    for p in parts:
        merged.merge(p)
    total = parts[0] + parts[1]
    for p in parts[2:]:
        total += p
    pushed = mcstat.Moments()
    assert pushed.push(x[:10]) is pushed
    for v in x[10:20]:
        pushed.push(float(v))
    pushed.push(x[20:].reshape(-1, 10))  # any shape
    for m in (merged, total, pushed):
        assert m.n == 5000
        assert m.mean == pytest.approx(whole.mean, rel=1e-15)
        assert m.var == pytest.approx(whole.var, rel=1e-14)
    assert parts[0].n == len(np.array_split(x, 7)[0])  # + made a new object


def test_push_errors_leave_state_unchanged():
    m = mcstat.Moments([1.0, 2.0, 3.0])
    before = m.to_bytes()
    with pytest.raises(mcstat.NonFiniteError, match="NaN or infinite"):
        m.push([4.0, np.nan])
    with pytest.raises(mcstat.NonFiniteError):
        m.push(np.inf)
    with pytest.raises(mcstat.NonFiniteError):
        m.push([5.0, np.inf], nan_policy="omit")
    assert m.to_bytes() == before
    m.push([4.0, np.nan], nan_policy="omit")
    m.push(float("nan"), nan_policy="omit")
    assert m.n == 4
    with pytest.raises(mcstat.InvalidArgumentError, match="nan_policy"):
        m.push([1.0], nan_policy="drop")
    with pytest.raises(TypeError):
        m.push(None)
    with pytest.raises(TypeError):
        m.merge([1.0, 2.0])


def test_bytes_round_trip_and_pickle(rng):
    m = mcstat.Moments(rng.normal(1e9, 1e-3, size=999))
    b = m.to_bytes()
    assert isinstance(b, bytes) and len(b) == 96 and b[:4] == b"MCSM"
    m2 = mcstat.Moments.from_bytes(b)
    assert m2 == m and m2.to_bytes() == b
    assert mcstat.Moments.from_bytes(bytearray(b)) == m
    assert mcstat.Moments.from_bytes(memoryview(b)) == m
    assert pickle.loads(pickle.dumps(m)) == m
    assert copy.copy(m) == m and copy.deepcopy(m) == m and m.copy() == m
    c = m.copy()
    c.push(1e9)
    assert c != m and c.n == m.n + 1
    assert mcstat.Moments.from_bytes(mcstat.Moments().to_bytes()).n == 0


@pytest.mark.parametrize("damage", ["truncated", "longer", "flipped", "version", "empty"])
def test_from_bytes_rejects_damage(rng, damage):
    b = bytearray(mcstat.Moments(rng.normal(size=10)).to_bytes())
    if damage == "truncated":
        b = b[:95]
    elif damage == "longer":
        b = b + b"\0"
    elif damage == "flipped":
        b[40] ^= 0x10
    elif damage == "version":
        b[4] = 2
    else:
        b = b""
    with pytest.raises(mcstat.CorruptDataError, match="truncated, corrupt"):
        mcstat.Moments.from_bytes(bytes(b))
    assert issubclass(mcstat.CorruptDataError, ValueError)


def test_repr_and_eq():
    m = mcstat.Moments([1.0, 2.0, 4.0])
    assert repr(m) == "Moments(n=3, mean=2.33333, sd=1.52753)"
    assert (m == 3) is False
    with pytest.raises(TypeError):
        hash(m)


def test_batch_means(rng):
    x = rng.normal(size=1003)
    b = mcstat.batch_means(x, 10)
    assert b.shape == (100,)
    exact = [math.fsum(r) / 10 for r in x[:1000].reshape(100, 10)]
    np.testing.assert_allclose(b, exact, rtol=1e-15, atol=1e-16)  # data of spread 1
    with pytest.raises(mcstat.InvalidArgumentError, match="do not split"):
        mcstat.batch_means(x, 10, remainder="raise")
    assert mcstat.batch_means(x[:1000], 10, remainder="raise").shape == (100,)
    assert mcstat.batch_means(x, 1)[5] == x[5]
    assert mcstat.batch_means(x[:5], 10).shape == (0,)
    img = rng.normal(size=(4, 6, 64))
    bm = mcstat.batch_means(img, 16)
    assert bm.shape == (4, 6, 4)
    np.testing.assert_allclose(bm, img.reshape(4, 6, 4, 16).mean(axis=-1), rtol=1e-12, atol=1e-16)
    bm0 = mcstat.batch_means(np.moveaxis(img, -1, 0), 16, axis=0)
    np.testing.assert_array_equal(bm0, np.moveaxis(bm, -1, 0))
    with pytest.raises(mcstat.InvalidArgumentError, match="k must be"):
        mcstat.batch_means(x, 0)
    with pytest.raises(mcstat.InvalidArgumentError, match="axis"):
        mcstat.batch_means(x, 2, axis=1)
    with pytest.raises(mcstat.NonFiniteError):
        mcstat.batch_means([1.0, np.nan, 2.0, 3.0], 2)
    with pytest.raises(TypeError):
        mcstat.batch_means(None, 2)
