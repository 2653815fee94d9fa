"""The exact binomial test and Clopper-Pearson intervals of mcstat_app.reproduce
(now libmcstat's, through mcstat.binom_test) against SciPy's binomtest."""
import pytest
from scipy import stats

from mcstat_app.reproduce.binomial import binom_test, clopper_pearson, format_binom

CASES = [(14, 1000, 0.01), (0, 100, 0.05), (100, 100, 0.05), (3, 100, 0.05), (10, 1000, 0.01), (7, 20, 0.3),
         (50, 100, 0.5), (1, 5000, 0.001), (990, 1000, 0.99), (13, 40, 0.5), (0, 1, 0.5), (1, 1, 0.01),
         (37, 200, 0.05), (0, 200000, 1e-6)]


@pytest.mark.parametrize("x,n,p", CASES)
def test_against_scipy(x, n, p):
    ours = binom_test(x, n, p)
    ref = stats.binomtest(x, n, p)
    ci = ref.proportion_ci(method="exact")
    assert ours["pvalue"] == pytest.approx(ref.pvalue, rel=1e-9, abs=1e-300)
    assert ours["conf_int"][0] == pytest.approx(ci.low, abs=1e-10)
    assert ours["conf_int"][1] == pytest.approx(ci.high, abs=1e-10)
    assert ours["estimate"] == x / n


def test_interval_levels_and_errors():
    lo90, hi90 = clopper_pearson(5, 50, 0.90)
    lo99, hi99 = clopper_pearson(5, 50, 0.99)
    assert lo99 < lo90 < 0.1 < hi90 < hi99
    with pytest.raises(ValueError):
        binom_test(5, 4, 0.5)


def test_format_like_r():
    text = format_binom(binom_test(14, 1000, 0.01), "14", "1000")
    assert "\tExact binomial test" in text
    assert "number of successes = 14, number of trials = 1000, p-value = 0.2006" in text
    assert "true probability of success is not equal to 0.01" in text
    # R prints the interval's two ends with a common number of decimals
    assert "95 percent confidence interval:\n 0.007674502 0.023378156" in text
    assert "decision at alpha = 0.05: equal" in text
