"""mcstat.Stream: libmcstat's buffered per-thread accumulator and its checks."""
import numpy as np
import pytest

import mcstat


def test_moments_are_those_of_push(rng):
    x = rng.normal(3.0, 2.0, 5000)
    s = mcstat.Stream()
    for chunk in np.array_split(x, 7):  # crosses the 492-value buffer many times
        s.push(chunk)
    m = s.moments()
    want = mcstat.Moments(x)
    assert s.n == 5000 and m.n == 5000
    assert (m.min, m.max) == (want.min, want.max)
    for k in ("mean", "var", "skewness", "kurtosis"):
        assert getattr(m, k) == pytest.approx(getattr(want, k), rel=1e-13, abs=1e-15), k
    assert s.flush().moments().to_bytes() == m.to_bytes()  # flushing changes nothing


def test_merge_and_scalars(rng):
    x, y = rng.normal(size=300), rng.normal(size=1000)
    a, b = mcstat.Stream().push(x), mcstat.Stream()
    for v in y:
        b.push(float(v))
    assert a.merge(b) is a and a.n == 1300
    assert a.moments().mean == pytest.approx(np.concatenate([x, y]).mean(), rel=1e-14)


def test_check_mean_is_the_t_test(rng):
    x = rng.normal(0.1, 1.0, 2000)
    s = mcstat.Stream().push(x)
    r = s.check_mean(0.0)
    t = mcstat.t_test(x, mu=0.0)
    assert r.statistic == t.statistic and r.pvalue == t.pvalue and r.reject == t.reject
    # a tolerance wider than the bias passes; the result names the bound crossed otherwise
    assert not s.check_mean(0.0, tolerance=0.5).reject
    r = mcstat.Stream().push(x + 1.0).check_mean(0.0, tolerance=0.5)
    assert r.reject and r.alpha == 0.025


def test_check_var(rng):
    x = rng.normal(0.0, 2.0, 3000)
    s = mcstat.Stream().push(x)
    assert s.check_var(1.0).reject
    assert not s.check_var(9.0).reject
    v = mcstat.var_test(x, sigma2=1.0, alternative="greater")
    assert s.check_var(1.0).statistic == pytest.approx(v.statistic, rel=1e-15)


def test_nonfinite_values_are_counted_then_refused_by_the_checks():
    s = mcstat.Stream().push([1.0, np.nan, 2.0, np.inf, 3.0])
    assert s.n == 3 and s.n_nonfinite == 2 and s.n_overflow == 0
    assert s.moments().n == 3
    with pytest.raises(mcstat.NonFiniteError, match="has seen NaN or infinite values"):
        s.check_mean(2.0)
    with pytest.raises(mcstat.NonFiniteError):
        s.check_var(1.0)


def test_bad_arguments():
    s = mcstat.Stream().push([1.0, 2.0, 4.0])
    with pytest.raises(mcstat.InvalidArgumentError, match="tolerance=-1.0"):
        s.check_mean(0.0, tolerance=-1.0)
    with pytest.raises(mcstat.InvalidArgumentError, match="bound=0.0"):
        s.check_var(0.0)
    with pytest.raises(mcstat.TooFewObservationsError):
        mcstat.Stream().push([1.0]).check_mean(0.0)
    with pytest.raises(TypeError, match="values must hold real numbers"):
        s.push(np.array([1j]))
    with pytest.raises(TypeError):
        s.merge(mcstat.Moments([1.0, 2.0]))
