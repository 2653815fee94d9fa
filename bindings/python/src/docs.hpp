// docs.hpp - the docstrings of t_test and var_test (NumPy style).
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#pragma once

namespace mcs {

inline constexpr const char T_TEST_DOC[] = R"doc(t_test($module, /, x, y=None, *, mu=0.0, alternative='two-sided', alpha=0.05, axis=-1, nan_policy='raise', intervals=True, on_error='raise', threads=None, equal_var=False, paired=False)
--

Student's one-sample t test, Welch's two-sample t test, Student's pooled
two-sample t test (``equal_var=True``) or the paired t test
(``paired=True``).

One sample (``y`` is None): H0 mean(x) = mu (paper, section 2.1).  Two
samples: H0 mean(x) - mean(y) = mu, with Welch-Satterthwaite degrees of
freedom (section 2.3) -- the paper's test and mcstat's default.  NOTE:
SciPy's ``ttest_ind`` defaults to the pooled test (``equal_var=True``) and
R's ``t.test`` to Welch's; pass ``equal_var=True`` for SciPy's default.

Parameters
----------
x, y : array_like or Moments
    Samples.  Anything NumPy converts to float64; C-contiguous float64 is
    read in place, anything else is converted once.  A `Moments`
    accumulator may stand in for either sample (an array beside it must
    then be 1-D).  With N-D input, one test per row along `axis`.
mu : float, optional
    Mean (difference of means, mean difference) under H0.
alternative : {"two-sided", "less", "greater"}, optional
    A claim about the first sample: "less" means mean(x) < mu (or
    mean(x) - mean(y) < mu).
alpha : float, optional
    Significance level in (0, 1), for `reject`, `decision`, the critical
    values and the 1 - alpha confidence interval.
axis : int, optional
    The axis holding each sample in N-D input (default: the last).  x and
    y must then have the same shape except along `axis` (no broadcasting).
    N-D input is one test per pixel (libmcstat's mcstat_pixels_test):
    float32 stays float32 when both arrays are (other dtypes, and views
    whose pixels are not one stride apart, are copied to float64 first);
    seeds-major stacks ``(seeds, H, W)`` with ``axis=0`` and rows
    ``(H, W, seeds)`` with ``axis=-1`` are read in place.  Each pixel's
    result is the single call's on its values bit for bit, except for
    Welch's test and the variance tests, whose block paths agree to the
    bounds of mcstat.h (p-value 6e-14 + 8e-16 abs(log p) relative, the rest
    about 1e-14, Welch's critical values 3e-13).  Fields of pairs (``conf_int``, ``estimate``, ...) are formed
    when first read.
nan_policy : {"raise", "omit", "propagate"}, optional
    NaN raises `NonFiniteError` (the default), is omitted from its sample
    (row; paired: the pair is dropped), or, with "propagate" (SciPy's
    default), makes the result NaN as SciPy's: statistic, pvalue, df and
    the other fields NaN, ``decision`` "" (row-wise: those rows NaN, with
    a non-zero ``status``, not raised).  This is decided here before
    calling libmcstat, which never returns NaN with success.  Infinities
    always raise.
intervals : bool, optional
    False skips the critical values and the confidence interval (NaN):
    the cheap path when only p-values and decisions are wanted.
on_error : {"raise", "nan"}, optional
    Row-wise tests only: a failed row raises (the exception's ``rows``
    names them), or gets NaN fields, ``reject`` False and a non-zero
    ``status``.  A single test always raises.
threads : int, optional
    Row-wise tests only: threads for the pixels, 1..64 (default
    `get_num_threads()`, capped at 64); each thread takes a contiguous
    range of at least 4096 pixels.  Results do not depend on it.
equal_var : bool, optional
    True: Student's test with pooled variance, df = nx + ny - 2 (R's
    ``t.test(var.equal=TRUE)``, SciPy's ``ttest_ind`` default).
paired : bool, optional
    True: the paired test, the one-sample t on the differences x - y
    (R's ``t.test(paired=TRUE)``, SciPy's ``ttest_rel``); x and y must be
    arrays of the same length (along `axis`), not accumulators.

Returns
-------
TestResult or BatchResult
    One result, or arrays of results for N-D input.  A TestResult unpacks
    as SciPy's: ``t, p = mcstat.t_test(x, y)``.

Raises
------
TooFewObservationsError
    A sample with fewer than 2 values (also empty input).
NonFiniteError
    NaN or infinity in the data.
DegenerateDataError
    Constant data (Welch and pooled: both samples constant; paired:
    constant differences).
InvalidArgumentError
    alpha outside (0, 1), non-finite mu, unknown alternative, nan_policy or
    on_error, axis out of range, scalar input, mismatched shapes; paired
    samples of different lengths, paired with equal_var, paired or
    equal_var without y, paired with accumulators.
TypeError
    x is None, or an option of the wrong type.

Examples
--------
>>> r = mcstat.t_test(new, trusted, alpha=0.01)
>>> r.pvalue, r.decision
>>> print(r.format("new", "trusted"))   # R's print.htest layout
)doc";

inline constexpr const char VAR_TEST_DOC[] = R"doc(var_test($module, /, x, y=None, *, sigma2=None, ratio=1.0, alternative='two-sided', alpha=0.05, axis=-1, nan_policy='raise', intervals=True, on_error='raise', threads=None)
--

Chi-squared test of one variance, or the F test of two.

One sample (``y`` is None): H0 var(x) = sigma2, statistic (n-1) s^2 /
sigma2 on n-1 degrees of freedom (section 2.2).  Two samples: H0
var(x)/var(y) = ratio, statistic (s_x^2 / s_y^2) / ratio on (nx-1, ny-1)
degrees of freedom (section 2.4).

Parameters
----------
x, y : array_like or Moments
    Samples, as for `t_test`.
sigma2 : float
    Variance under H0 (required for one sample, positive).
ratio : float, optional
    Ratio of variances under H0 (two samples, positive).
alternative : {"two-sided", "less", "greater"}, optional
    A claim about the first sample: "less" means var(x) < sigma2 (or
    var(x)/var(y) < ratio): the new estimator has the lower variance
    (ERRATA 4).
alpha, axis, nan_policy, intervals, on_error, threads
    As for `t_test`.

Returns
-------
TestResult or BatchResult

Raises
------
TooFewObservationsError, NonFiniteError, DegenerateDataError,
InvalidArgumentError, TypeError
    As for `t_test`; DegenerateDataError for either sample constant;
    InvalidArgumentError also for a missing or non-positive sigma2, a
    non-positive ratio, sigma2 with two samples or ratio with one.
)doc";

inline constexpr const char KS_TEST_DOC[] = R"doc(ks_test($module, /, x, y, *, weight='canner', alternative='two-sided', alpha=0.05, method='auto', n_sim=None, seed=None, threads=None, cache=None, critical=True, nan_policy='raise')
--

Two-sample Kolmogorov-Smirnov test, unweighted or with Canner's weight.

H0: x and y come from the same continuous distribution (paper, section
2.5).  F and G are the empirical CDFs of x and y, z the pooled one; the
statistic is

- ``weight="none"``: D = ``sup |F - G|`` (as R's ``ks.test`` and SciPy's
  ``ks_2samp`` report it);
- ``weight="canner"`` (the paper's): D2 = ``sqrt(nx ny / (nx + ny)) *
  sup |F - G| / sqrt(z (1 - z))``, over the pooled points with 0 < z < 1.

With ties the ECDFs are compared only after the last of a run of equal
values, and p-values are conditional on the tie pattern.

.. warning::
   **One-sided alternatives are claims about x, as in every mcstat test,
   which is the OPPOSITE of SciPy's and R's naming.**  ``alternative="less"``
   means *x tends to be smaller than y* (its CDF lies above: the statistic
   is sup (F - G)); that is ``scipy.stats.ks_2samp(x, y,
   alternative="greater")`` and R's ``ks.test(x, y, alternative =
   "greater")``.  ``"greater"`` here is their ``"less"``.  The printed
   block keeps R's wording ("the CDF of x lies above that of y").

Parameters
----------
x, y : array_like
    1-D samples (at least one value each).  Anything NumPy converts to
    float64; C-contiguous float64 is read in place.  NaN raises
    `NonFiniteError`; +-inf are ordinary (extreme) values.
weight : {"canner", "none"}, optional
    Canner's weight [z (1 - z)]^(-1/2) (default), or none.
alternative : {"two-sided", "less", "greater"}, optional
    "less": x tends to be smaller (SciPy's "greater"); "greater": x tends
    to be larger (SciPy's "less").  See the warning above.
alpha : float, optional
    Significance level in (0, 1) for `reject`, `decision` and the
    critical value.
method : {"auto", "exact", "simulate", "asymptotic"}, optional
    How the p-value is obtained.  "exact": the permutation distribution
    for these sizes by lattice-path counting (relative error ~1e-13;
    `TooBigError` beyond ``(min(nx,ny)+1)(nx+ny+1) = 2e11`` cells, about
    3.2e5 + 3.2e5 values).  "simulate": `n_sim` random label arrangements,
    p = (1 + #{D* >= D}) / (n_sim + 1) (never 0), with its Monte Carlo
    standard error in `pvalue_se`.  "asymptotic" (weight "none" only):
    Kolmogorov's limit at sqrt(nx ny/(nx+ny)) D, conservative (within 2%
    at 300 + 300 and beyond).  "auto": exact up to about 2800 + 2800
    values, beyond it asymptotic (weight "none" without ties) or simulate.
n_sim : int, optional
    Replicates when simulating (default 10000); the p-value's standard
    error is about sqrt(p (1 - p) / n_sim).  Only with method "simulate"
    or "auto": with "exact" or "asymptotic" giving it (or `seed`) raises.
seed : int, optional
    Seed of the simulation, in [0, 2**64).  Results are bit-identical for
    a given seed whatever the number of threads.  None: the cache's seed
    when `cache` is given, else 64 bits of fresh OS entropy; either way the
    seed used is reported as ``result.seed``, so ``seed=result.seed``
    repeats the run exactly.
threads : int, optional
    Simulation (and, above 65536 values, sorting) threads, 1..64; default
    `get_num_threads()`.  Results do not depend on it.
cache : KSCache, optional
    Simulated null distributions to reuse: a battery of tests at the same
    sizes, weight, alternative, n_sim, seed and tie pattern simulates once
    (the paper's 1000 directions of section 3.3).  Thread-safe.
critical : bool, optional
    Compute the critical value (default).  With the exact method it costs
    10-40 p-value evaluations (1000 + 1000, Canner: ~4 ms instead of
    ~0.2 ms); False leaves ``critical_values[1]`` NaN.
nan_policy : {"raise", "omit", "propagate"}, optional
    NaN raises `NonFiniteError` (the default), is dropped from its sample,
    or with "propagate" (SciPy's default) makes statistic and pvalue NaN
    (decided here, before libmcstat, which never returns NaN with success).

Returns
-------
TestResult
    `statistic` (D or D2, or their one-sided versions), `pvalue`,
    `pvalue_se` (0 unless simulated), `pvalue_method` ("exact",
    "simulate" or "asymptotic"), `critical_values` ``(-inf, c)``: H0 is
    rejected when statistic > c (simulated: the order statistic of the
    null sample, with Monte Carlo error `critical_se`), `n_sim` (0 unless
    simulated), `seed` (None unless simulated), `weight`, `reject`,
    `decision` ("less": x tends to be smaller, "equal", "greater"),
    `nobs`.  ``str(result)`` is libmcstat's R-style block, whose method
    line names the weight and how the p-value was obtained, with the
    Monte Carlo error when simulated.  df, estimate, conf_int, null_value
    and std_error are NaN.

Raises
------
TooFewObservationsError
    An empty sample.
NonFiniteError
    NaN in the data.
InvalidArgumentError
    alpha outside (0, 1), unknown weight, alternative or method,
    method="asymptotic" with weight="canner", n_sim < 1, threads outside
    1..64, a negative seed, n_sim or seed with method "exact" or
    "asymptotic", input that is not 1-D.
TooBigError
    method="exact" beyond its size limit, or nx * ny >= 2**62.
TypeError
    x or y None or missing, an option of the wrong type, a cache that is
    not a KSCache.

Examples
--------
>>> r = mcstat.ks_test(new, trusted)              # Canner's weight, auto
>>> r.pvalue, r.decision
>>> cache = mcstat.KSCache(seed=1)
>>> rs = [mcstat.ks_test(a, b, method="simulate", cache=cache) for a, b in pairs]
>>> print(rs[0])
)doc";

inline constexpr const char KS_CACHE_DOC[] = R"doc(KSCache(max_bytes=None, seed=None)

Simulated K-S null distributions kept for reuse by `ks_test`.

Under H0 the simulated null distribution depends only on (nx, ny, weight,
alternative, n_sim, seed, tie pattern), so a battery of tests at the same
sizes, such as the paper's 1000 outgoing directions, simulates once and
looks the distribution up for every other test.  Entries are copied in
and out under the cache's own lock: one cache may be shared by any
number of threads.

Parameters
----------
max_bytes : int, optional
    Memory limit of the entries (default 256 MiB; one entry holds n_sim
    doubles, plus the tie pattern when there are ties); beyond it the
    least recently used entries are dropped.
seed : int, optional
    The seed used by tests that pass ``cache=`` without a ``seed=`` of
    their own (default: fresh OS entropy, readable as ``cache.seed``).
    Tests sharing a cache and a seed share one null sample, so their
    Monte Carlo errors are not independent; that is the price of reuse.

Attributes
----------
seed, max_bytes : int
hits, misses, entries : int
    Lookups that found a distribution, lookups that did not, and the
    number of distributions held.
)doc";

} // namespace mcs
