"""Power: under clear alternatives each test rejects at the predicted rate
(marker ``stats``).

Counts of rejections among R replicates (fixed seeds) must lie in the exact
binomial acceptance region of the predicted rate at the per-check level of
``stats_oracle.BUDGET`` (1e-4 over the whole stats suite, Bonferroni; see
test_calibration.py).  Predictions, none of them from mcstat:

- one-sample t: the noncentral t, scipy.stats.nct (exact for normal data);
- Welch t: exact by quadrature over the two sample variances
  (``stats_oracle.welch_rejection``), any sizes and variances; and, for equal
  sizes and variances, the noncentral t with the pooled 2n - 2 df, which is
  *not* exact for Welch (its estimated df is below 2n - 2, so its power is
  a little lower).  At n = 25 + 25 the quadrature puts that gap below 0.002
  (asserted), so the nct check allows the binomial half-width plus 0.003;
- chi-square variance test: (n - 1) s^2 / sigma0^2 is (sigma^2 / sigma0^2)
  times a central chi-square with n - 1 df;
- F test: s1^2 / s2^2 / ratio0 is (sigma1^2 / sigma2^2 / ratio0) times a
  central F;
- K-S (no closed form under a shift): power rises with the shift and is
  above alpha, and each row's decision is predicted from an independent
  NumPy implementation of the statistic (``stats_oracle.ks_statistic_rows``)
  and the exact null distribution by lattice-path counting
  (``stats_oracle.KSNull``): exact and asymptotic decisions must match row
  for row; the simulated test's count must lie in the binomial region of
  the mean predicted rejection probability (a Poisson-binomial count, whose
  variance the binomial's bounds).
"""
import math
import zlib

import numpy as np
import pytest
from scipy import stats

import mcstat
from stats_oracle import BUDGET, KSNull, ks_statistic_rows, welch_rejection

pytestmark = pytest.mark.stats

ROWS = 40000
ALTS = ("two-sided", "less", "greater")


def seeded(*key):
    return np.random.default_rng(zlib.crc32(repr(key).encode()))


def check(k, n, rate, what):
    assert BUDGET.accept(k, n, rate), (
        f"{what}: {k} rejections of {n} ({k / n:.5f}); predicted {rate:.5f}, "
        f"acceptance region {BUDGET.region(n, rate)}")


def t_power(dist_sf, dist_cdf, crit, alt):
    """Rejection probability of a test whose statistic has survival and
    distribution functions dist_sf, dist_cdf and upper critical value crit(a)."""
    if alt == "greater":
        return dist_sf(crit(ALPHA))
    if alt == "less":
        return dist_cdf(-crit(ALPHA))
    c = crit(ALPHA / 2)
    return dist_sf(c) + dist_cdf(-c)


ALPHA = 0.05


@pytest.mark.parametrize("n,effect", [(2, 3.0), (3, 1.5), (10, 0.6), (50, -0.3)])
def test_one_sample_t_power_is_noncentral_t(n, effect):
    sd = 1.7
    X = seeded("t1", n, effect).normal(effect * sd, sd, size=(ROWS, n))
    df, nc = n - 1, effect * math.sqrt(n)
    for alt in ALTS:
        want = t_power(lambda q: stats.nct.sf(q, df, nc), lambda q: stats.nct.cdf(q, df, nc),
                       lambda a: stats.t.isf(a, df), alt)
        k = int(mcstat.t_test(X, mu=0.0, alternative=alt, alpha=ALPHA).reject.sum())
        check(k, ROWS, want, f"t_1 n={n} effect={effect} {alt}")


@pytest.mark.parametrize("n1,n2,sd1,sd2,delta", [(2, 2, 1.0, 1.0, 4.0), (3, 5, 1.0, 2.0, 2.0),
                                                 (12, 7, 1.5, 4.0, 2.5), (25, 25, 1.0, 1.0, 0.6)])
def test_welch_power_is_exact_quadrature(n1, n2, sd1, sd2, delta):
    g = seeded("t2", n1, n2, sd1, sd2, delta)
    X = g.normal(delta, sd1, size=(ROWS, n1))
    Y = g.normal(0.0, sd2, size=(ROWS, n2))
    for alt in ALTS:
        want = welch_rejection(n1, n2, sd1, sd2, delta, alt, ALPHA)
        k = int(mcstat.t_test(X, Y, alternative=alt, alpha=ALPHA).reject.sum())
        check(k, ROWS, want, f"t_2 {n1}+{n2} sd {sd1}/{sd2} delta={delta} {alt}")


def test_welch_power_near_noncentral_t_at_equal_sizes():
    n, delta = 25, 0.6
    g = seeded("t2nct", n, delta)
    X = g.normal(delta, 1.0, size=(ROWS, n))
    Y = g.normal(0.0, 1.0, size=(ROWS, n))
    df, nc = 2 * n - 2, delta / math.sqrt(2.0 / n)
    for alt in ALTS:
        nct = t_power(lambda q: stats.nct.sf(q, df, nc), lambda q: stats.nct.cdf(q, df, nc),
                      lambda a: stats.t.isf(a, df), alt)
        gap = abs(nct - welch_rejection(n, n, 1.0, 1.0, delta, alt, ALPHA))
        assert gap < 0.002, (alt, gap)  # the stated tolerance's premise
        k = int(mcstat.t_test(X, Y, alternative=alt, alpha=ALPHA).reject.sum())
        BUDGET.used += 1  # one check of the budget (its region is widened by 0.003)
        assert abs(k / ROWS - nct) <= BUDGET.half_width(ROWS, nct) + 0.003 + 1.0 / ROWS, (alt, k / ROWS, nct)


@pytest.mark.parametrize("n,scale", [(2, 9.0), (3, 5.0), (10, 2.0), (30, 0.5)])
def test_chi_square_power_is_scaled_chi_square(n, scale):
    """scale = sigma^2 / sigma0^2."""
    sigma0_sq = 2.0
    X = seeded("var1", n, scale).normal(3.0, math.sqrt(scale * sigma0_sq), size=(ROWS, n))
    df = n - 1
    for alt in ALTS:
        # statistic = scale * chi2(df); its critical values are chi2(df) quantiles
        if alt == "greater":
            want = stats.chi2.sf(stats.chi2.isf(ALPHA, df) / scale, df)
        elif alt == "less":
            want = stats.chi2.cdf(stats.chi2.ppf(ALPHA, df) / scale, df)
        else:
            want = (stats.chi2.sf(stats.chi2.isf(ALPHA / 2, df) / scale, df)
                    + stats.chi2.cdf(stats.chi2.ppf(ALPHA / 2, df) / scale, df))
        k = int(mcstat.var_test(X, sigma2=sigma0_sq, alternative=alt, alpha=ALPHA).reject.sum())
        check(k, ROWS, want, f"var_1 n={n} scale={scale} {alt}")


@pytest.mark.parametrize("n1,n2,scale", [(2, 3, 30.0), (5, 8, 4.0), (20, 20, 0.4), (40, 12, 2.5)])
def test_f_power_is_scaled_f(n1, n2, scale):
    """scale = (sigma1^2 / sigma2^2) / ratio0."""
    ratio0 = 0.5
    g = seeded("var2", n1, n2, scale)
    X = g.normal(0.0, math.sqrt(scale * ratio0), size=(ROWS, n1))
    Y = g.normal(7.0, 1.0, size=(ROWS, n2))
    d1, d2 = n1 - 1, n2 - 1
    for alt in ALTS:
        if alt == "greater":
            want = stats.f.sf(stats.f.isf(ALPHA, d1, d2) / scale, d1, d2)
        elif alt == "less":
            want = stats.f.cdf(stats.f.ppf(ALPHA, d1, d2) / scale, d1, d2)
        else:
            want = (stats.f.sf(stats.f.isf(ALPHA / 2, d1, d2) / scale, d1, d2)
                    + stats.f.cdf(stats.f.ppf(ALPHA / 2, d1, d2) / scale, d1, d2))
        k = int(mcstat.var_test(X, Y, ratio=ratio0, alternative=alt, alpha=ALPHA).reject.sum())
        check(k, ROWS, want, f"var_2 {n1}+{n2} scale={scale} {alt}")


# ---- K-S ------------------------------------------------------------------------
KS_ROWS = 4000
SHIFTS = (0.8, 1.3, 1.8)
N_SIM = 250  # alpha (n_sim + 1) is not an integer


@pytest.mark.parametrize("weight", ["none", "canner"])
@pytest.mark.parametrize("n1,n2", [(10, 10), (20, 15)])
def test_ks_power(n1, n2, weight):
    """x shifted down by s standard deviations: "less" (x tends to be
    smaller) and two-sided have power rising with s; "greater" has power
    below alpha.  Every decision is predicted by the oracle."""
    methods = ["exact", "simulate"] + (["asymptotic"] if weight == "none" else [])
    nulls = {alt: KSNull(n1, n2, weight, alt) for alt in ALTS}
    crit = {alt: nulls[alt].critical_index(ALPHA) for alt in ALTS}
    top = math.floor(ALPHA * (N_SIM + 1) - 1)
    rates = {}
    for s in SHIFTS:
        g = seeded("ks-power", n1, n2, weight, s)
        X = g.normal(-s, 1.0, size=(KS_ROWS, n1))
        Y = g.normal(0.0, 1.0, size=(KS_ROWS, n2))
        for alt in ALTS:
            null = nulls[alt]
            d = ks_statistic_rows(X, Y, weight, alt)
            kk = np.searchsorted(null.values, d * (1 - 1e-11) - 1e-15)  # index of each row's value
            assert np.allclose(null.values[np.minimum(kk, len(null.values) - 1)], d, rtol=1e-10, atol=1e-14)
            tails = np.array([null.tail(k) for k in kk])
            for method in methods:
                sim = {"n_sim": N_SIM} if method == "simulate" else {}  # n_sim, seed: simulation only
                rej = np.array([bool(mcstat.ks_test(X[i], Y[i], weight=weight, alternative=alt, alpha=ALPHA,
                                                    method=method, threads=1, critical=False,
                                                    **sim, **({"seed": i} if sim else {})).reject)
                                for i in range(KS_ROWS)])
                what = f"ks {weight} {method} {n1}+{n2} shift={s} {alt}"
                if method == "exact":
                    np.testing.assert_array_equal(rej, kk >= crit[alt], err_msg=what)
                elif method == "asymptotic":
                    pa = np.array([null.asymptotic_pvalue(v) for v in d])
                    clear = np.abs(pa - ALPHA) > 1e-9
                    np.testing.assert_array_equal(rej[clear], (pa <= ALPHA)[clear], err_msg=what)
                else:
                    want = float(np.mean(stats.binom.cdf(top, N_SIM, tails)))
                    check(int(rej.sum()), KS_ROWS, want, what)
                rates[method, alt, s] = rej.mean()
    for method in methods:
        for alt in ("two-sided", "less"):
            r = [rates[method, alt, s] for s in SHIFTS]
            # shifts 0.5 sd apart move power by > 0.15 here; the noise is < 0.01
            assert all(b > a + 0.05 for a, b in zip(r, r[1:])), (method, alt, r)
            assert r[0] > ALPHA + BUDGET.half_width(KS_ROWS, ALPHA), (method, alt, r)
        assert all(rates[method, "greater", s] < ALPHA for s in SHIFTS), (method, "greater")
