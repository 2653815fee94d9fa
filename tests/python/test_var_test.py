"""var_test against SciPy's distributions and the 50-digit references."""
import numpy as np
import pytest
import scipy.stats as st

import mcstat
from conftest import rel_err
from refdata import (CASES, STIFF_DOMAIN, TOL_CONF_INT, TOL_CRITICAL, TOL_DF, TOL_ESTIMATE, TOL_STATISTIC,
                     accuracy_bound, values)

ALTS = ["two-sided", "less", "greater"]


def pvalue(cdf, sf, alternative):
    if alternative == "less":
        return cdf
    if alternative == "greater":
        return sf
    return min(1.0, 2 * min(cdf, sf))


@pytest.mark.parametrize("alternative", ALTS)
@pytest.mark.parametrize("n", [2, 3, 10, 97, 2000])
def test_chisq_agrees_with_scipy(rng, n, alternative):
    for alpha in (0.05, 0.01, 0.2):
        x = rng.normal(0, rng.uniform(0.2, 3), size=n)
        sigma2 = float(rng.uniform(0.5, 2))
        r = mcstat.var_test(x, sigma2=sigma2, alternative=alternative, alpha=alpha)
        df = n - 1
        stat = df * x.var(ddof=1) / sigma2
        assert rel_err(r.statistic, stat) <= 1e-13
        assert r.df == df
        p = pvalue(st.chi2.cdf(stat, df), st.chi2.sf(stat, df), alternative)
        assert rel_err(r.pvalue, p) <= 1e-11
        a = alpha / 2 if alternative == "two-sided" else alpha
        lo = st.chi2.ppf(a, df) if alternative != "greater" else 0.0
        hi = st.chi2.isf(a, df) if alternative != "less" else np.inf
        assert rel_err(r.critical_values[0], lo) <= 1e-11
        assert rel_err(r.critical_values[1], hi) <= 1e-11
        m2 = df * x.var(ddof=1)
        assert rel_err(r.conf_int[0], m2 / hi if np.isfinite(hi) else 0.0) <= 1e-11
        assert rel_err(r.conf_int[1], m2 / lo if lo > 0 else np.inf) <= 1e-11
        assert r.estimate == pytest.approx(x.var(ddof=1), rel=1e-13)


@pytest.mark.parametrize("alternative", ALTS)
@pytest.mark.parametrize("nx,ny", [(2, 2), (3, 30), (25, 31), (400, 90)])
def test_f_agrees_with_scipy(rng, nx, ny, alternative):
    for alpha in (0.05, 0.01):
        x = rng.normal(0, rng.uniform(0.2, 3), size=nx)
        y = rng.normal(5, rng.uniform(0.2, 3), size=ny)
        ratio = float(rng.uniform(0.5, 2))
        r = mcstat.var_test(x, y, ratio=ratio, alternative=alternative, alpha=alpha)
        est = x.var(ddof=1) / y.var(ddof=1)
        f = est / ratio
        d1, d2 = nx - 1, ny - 1
        assert rel_err(r.statistic, f) <= 1e-13
        assert r.df == (d1, d2)
        p = pvalue(st.f.cdf(f, d1, d2), st.f.sf(f, d1, d2), alternative)
        assert rel_err(r.pvalue, p) <= 1e-10
        a = alpha / 2 if alternative == "two-sided" else alpha
        lo = st.f.ppf(a, d1, d2) if alternative != "greater" else 0.0
        hi = st.f.isf(a, d1, d2) if alternative != "less" else np.inf
        assert rel_err(r.critical_values[0], lo) <= 1e-10
        assert rel_err(r.critical_values[1], hi) <= 1e-10
        assert rel_err(r.estimate, est) <= 1e-13
        assert r.nobs == (nx, ny)


def test_arguments():
    x = np.arange(10.0)
    with pytest.raises(mcstat.InvalidArgumentError, match="sigma2"):
        mcstat.var_test(x)
    with pytest.raises(mcstat.InvalidArgumentError, match="sigma2"):
        mcstat.var_test(x, sigma2=0.0)
    with pytest.raises(mcstat.InvalidArgumentError, match="sigma2"):
        mcstat.var_test(x, sigma2=-1.0)
    with pytest.raises(mcstat.InvalidArgumentError, match="ratio"):
        mcstat.var_test(x, x[::-1] ** 2, ratio=0.0)
    with pytest.raises(mcstat.InvalidArgumentError, match="ratio"):
        mcstat.var_test(x, ratio=2.0, sigma2=1.0)
    with pytest.raises(mcstat.InvalidArgumentError, match="sigma2"):
        mcstat.var_test(x, x ** 2, sigma2=1.0)
    with pytest.raises(mcstat.DegenerateDataError):
        mcstat.var_test(x, np.ones(5))
    with pytest.raises(TypeError):
        mcstat.t_test(x, mu=1.0, sigma2=2.0)  # sigma2 is var_test's


@pytest.mark.parametrize("case", [c for c in CASES if c["kind"] in ("VAR_1", "VAR_2")],
                         ids=lambda c: f'{c["kind"]}-{c["x"]}-{c["y"]}')
def test_stiff_references(case):
    x = values(case["x"])
    alt = ALTS[case["alternative"]]
    if case["kind"] == "VAR_1":
        r = mcstat.var_test(x, sigma2=case["null_value"], alternative=alt, alpha=case["alpha"])
        df = (r.df,)
    else:
        r = mcstat.var_test(x, values(case["y"]), ratio=case["null_value"], alternative=alt, alpha=case["alpha"])
        df = r.df
        assert rel_err(df[1], case["df1"]) <= TOL_DF
    # the p-value to the accuracy table's bound, the rest as test_reference.c
    p_tol = accuracy_bound("var_test_1" if case["kind"] == "VAR_1" else "var_test_2", STIFF_DOMAIN)
    for got, key, tol in [(r.statistic, "statistic", TOL_STATISTIC), (df[0], "df0", TOL_DF), (r.pvalue, "p", p_tol),
                          (r.critical_values[0], "c0", TOL_CRITICAL), (r.critical_values[1], "c1", TOL_CRITICAL),
                          (r.conf_int[0], "ci0", TOL_CONF_INT), (r.conf_int[1], "ci1", TOL_CONF_INT),
                          (r.estimate, "e0", TOL_ESTIMATE)]:
        assert rel_err(got, case[key]) <= tol, (key, got, case[key])
    assert r.reject == (case["p"] <= case["alpha"])
