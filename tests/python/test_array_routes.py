"""The Python calls that reach libmcstat's array functions, tail index,
battery test on counts, power at given n, and the version number: each
agrees with the route it stands beside."""
import numpy as np
import pytest

import mcstat
from pixel_bounds import assert_welch_close
from mcstat import diagnostics


def _fields(r):
    # repr: equal strings are equal bits (NaN included)
    return repr((r.statistic, r.df, r.pvalue, r.conf_int, r.estimate, r.critical_values, r.std_error, r.reject,
            r.decision))


@pytest.mark.parametrize("test,kw", [(mcstat.t_test, {"mu": 0.1}), (mcstat.var_test, {"sigma2": 1.3})])
def test_one_dimensional_input_matches_a_row(rng, test, kw):
    # 1-D input goes through mcstat_t_test_1 / var_test_1 (and _2); a row of
    # 2-D input through the matrix functions: rows.c promises the same bits
    x, y = rng.standard_gamma(2.0, 37), rng.standard_gamma(2.0, 53)
    one = test(x, **kw)
    row = test(x[None, :], **kw)
    assert one.statistic == row.statistic[0] and one.pvalue == row.pvalue[0]
    assert one.conf_int == tuple(row.conf_int[0])
    two_kw = {} if test is mcstat.t_test else {"ratio": 0.8}
    one2 = test(x, y, **two_kw)
    row2 = test(x[None, :], y[None, :], **two_kw)
    if test is mcstat.t_test:  # Welch's block path: to the bounds of mcstat.h
        assert_welch_close(row2[0], one2)
    else:
        assert one2.statistic == row2.statistic[0] and one2.pvalue == row2.pvalue[0]
    # and the moments route gives the same numbers again
    m = test(mcstat.Moments(x), mcstat.Moments(y), **two_kw)
    assert _fields(m) == _fields(one2)


def test_equivalence_arrays_match_moments(rng):
    x, y = rng.normal(0.01, 1.0, 400), rng.normal(0.0, 1.0, 300)
    for args in ((x,), (x, y)):
        a = mcstat.equivalence_test(*args, margin=0.3)
        m = mcstat.equivalence_test(*(mcstat.Moments(v) for v in args), margin=0.3)
        assert (a.statistics, a.pvalues, a.conf_int, a.df, a.reject) == (m.statistics, m.pvalues, m.conf_int, m.df,
                                                                          m.reject)


def test_tail_index_is_diagnose_s(rng):
    x = rng.pareto(1.5, 4000) * rng.choice([-1.0, 1.0], 4000)
    lo, up = diagnostics.tail_index(x)
    d = mcstat.diagnose(x, normality=False)
    assert (lo, up) == d.tail_index
    assert 1.2 < up < 1.8 and 1.2 < lo < 1.8
    assert diagnostics.tail_index(x, tail_k=50) != (lo, up)
    with pytest.raises(mcstat.TooFewObservationsError):
        diagnostics.tail_index(x[:20], tail_k=10)
    with pytest.raises(mcstat.InvalidArgumentError, match="tail_k must be >= 1"):
        diagnostics.tail_index(x, tail_k=0)
    with pytest.raises(mcstat.InvalidArgumentError, match="one-dimensional"):
        diagnostics.tail_index(x.reshape(40, 100))


def test_battery_test_on_counts_is_the_binomial_test():
    r = mcstat.battery_test(9, 0.05, n=100, alternative="greater")
    b = mcstat.binom_test(9, 100, 0.05, alternative="greater")
    assert (r.statistic, r.pvalue, r.conf_int) == (b.statistic, b.pvalue, b.conf_int)
    flags = np.zeros(100, bool)
    flags[:9] = True
    assert mcstat.battery_test(flags, 0.05, alternative="greater").pvalue == r.pvalue
    with pytest.raises(mcstat.InvalidArgumentError):
        mcstat.battery_test(101, 0.05, n=100)


def test_power_at_given_n():
    # mcstat_power_compute; statsmodels counts both tails, as strict=True
    from statsmodels.stats.power import TTestPower

    p = mcstat.power("t", n=20, effect=0.5, alpha=0.05)
    assert p.solved_for == "power"
    assert p.power == pytest.approx(TTestPower().power(effect_size=0.5, nobs=20, alpha=0.05), rel=1e-9)
    assert mcstat.power("t", effect=0.5, alpha=0.05, power=p.power * (1 - 1e-9)).n == 20


def test_p_adjust_names_its_methods():
    with pytest.raises(mcstat.InvalidArgumentError) as e:
        mcstat.p_adjust([0.1], method="sidak")
    # every method the library has, by R's name (from libmcstat's own list)
    for name in ("none", "bonferroni", "holm", "hochberg", "hommel", "BH", "BY"):
        assert mcstat._core._p_adjust_method_name(name) == name
        assert f"'{name}'" in str(e.value)


def test_version_number():
    major, minor, patch = (int(v) for v in mcstat.__libmcstat_version__.split("."))
    assert mcstat.__libmcstat_version_number__ == major * 10000 + minor * 100 + patch
