# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Equivalence (TOST), power and sample size.

``equivalence_test`` and ``power`` are thin: libmcstat computes the numbers,
the decision and the R-style text (``mcstat_equivalence_test_*``,
``mcstat_power_*``); this module checks arguments and wraps the results.
``ks_power`` and ``ks_sample_size`` estimate the power of the K-S test by
simulation (there is no closed form), running libmcstat's K-S test on
generated samples.
"""
from __future__ import annotations

import math
import numbers
from typing import Any, Callable, Dict, Optional, Tuple, Union

import numpy as np

from . import _core
from ._errors import InvalidArgumentError

__all__ = [
    "equivalence_test",
    "EquivalenceResult",
    "power",
    "PowerResult",
    "ks_power",
    "ks_sample_size",
    "KSPowerResult",
]

_ALT_NAMES = ("two-sided", "less", "greater")


def _alternative(alternative: str) -> int:
    # libmcstat's parser (mcstat_alternative_parse), as every test's
    return _core._alternative_code(alternative)


def _real(v: Any, name: str) -> float:
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise TypeError(f"{name} must be a real number, got {v!r}")
    return float(v)


# ---- equivalence ---------------------------------------------------------------

class EquivalenceResult:
    """The outcome of `equivalence_test` (two one-sided t tests, TOST).

    Attributes
    ----------
    equivalent : bool
        Both one-sided tests reject at `alpha`: the mean (difference) lies
        inside `bounds`, i.e. ``|bias| < margin`` is supported.  Same as
        `reject` (H0 "outside the bounds" rejected).
    decision : str
        ``"equivalent"`` or ``"not equivalent"``.
    pvalue : float
        max of the two one-sided p-values.
    statistic : float
        The t of the one-sided test with the larger p-value.
    statistics, pvalues : tuple of float
        ``(lower, upper)``: t and p of H1 "mean > lower bound" and H1
        "mean < upper bound".
    bounds : tuple of float
        The equivalence interval: ``(mu + lower, mu + upper)`` for one
        sample, ``(lower, upper)`` for the difference of two.
    df : float
        Degrees of freedom (Welch-Satterthwaite for two samples).
    conf_int : tuple of float
        The ``1 - 2 alpha`` confidence interval; equivalent exactly when it
        lies inside `bounds`.
    estimate : float or tuple of float
        Mean of x, or ``(mean of x, mean of y)``.
    critical_values : tuple of float
        ``(-c, c)``, c = t(1 - alpha, df): equivalent when the lower t > c
        and the upper t < -c.
    null_value, alpha, std_error, nobs, method, margin
    """

    __slots__ = ("statistic", "df", "pvalue", "statistics", "pvalues", "bounds", "conf_int",
                 "estimate", "null_value", "alpha", "reject", "decision_code", "critical_values",
                 "std_error", "nobs", "_text", "two_sample", "margin")
    statistic: float
    df: float
    pvalue: float
    statistics: Tuple[float, float]
    pvalues: Tuple[float, float]
    bounds: Tuple[float, float]
    conf_int: Tuple[float, float]
    estimate: Union[float, Tuple[float, float]]
    null_value: float
    alpha: float
    reject: bool
    decision_code: int
    critical_values: Tuple[float, float]
    std_error: float
    nobs: Union[int, Tuple[int, int]]
    _text: str
    two_sample: bool
    margin: Tuple[float, float]

    def __init__(self, d: Dict[str, Any], margin: Tuple[float, float]) -> None:
        for k in ("statistic", "df", "pvalue", "statistics", "pvalues", "bounds", "conf_int",
                  "estimate", "null_value", "alpha", "reject", "decision_code", "critical_values",
                  "std_error", "nobs", "two_sample"):
            setattr(self, k, d[k])
        self._text = d["text"]
        self.margin = margin

    @property
    def equivalent(self) -> bool:
        return bool(self.reject)

    @property
    def decision(self) -> str:
        return "equivalent" if self.reject else "not equivalent"

    @property
    def method(self) -> str:
        return ("Welch Two Sample TOST equivalence t-test" if self.two_sample
                else "One Sample TOST equivalence t-test")

    def __str__(self) -> str:
        return self._text

    def __repr__(self) -> str:
        return (f"EquivalenceResult(decision={self.decision!r}, pvalue={self.pvalue:.6g}, "
                f"bounds=({self.bounds[0]:.6g}, {self.bounds[1]:.6g}), "
                f"conf_int=({self.conf_int[0]:.6g}, {self.conf_int[1]:.6g}))")


def _margin(margin: Any) -> Tuple[float, float]:
    if margin is None:
        raise TypeError("equivalence_test() missing required keyword argument 'margin'")
    if isinstance(margin, numbers.Real) and not isinstance(margin, bool):
        m = float(margin)
        if not (m > 0 and math.isfinite(m)):
            raise InvalidArgumentError(f"margin must be a positive finite number, got {margin!r}")
        return (-m, m)
    try:
        lower, upper = margin
    except (TypeError, ValueError):
        raise TypeError(f"margin must be a positive number or a (lower, upper) pair, got {margin!r}") from None
    lower, upper = _real(lower, "margin[0]"), _real(upper, "margin[1]")
    if not (math.isfinite(lower) and math.isfinite(upper) and lower < upper):
        raise InvalidArgumentError(f"margin (lower, upper) must be finite with lower < upper, got {margin!r}")
    return (lower, upper)


def equivalence_test(x: Any, y: Any = None, *, margin: Any = None, mu: float = 0.0,
                     alpha: float = 0.05, nan_policy: str = "raise") -> EquivalenceResult:
    """Equivalence test by two one-sided t tests (TOST).

    One sample (``y`` None): is the mean of x within ``[mu + lower, mu +
    upper]``?  Two samples: is ``mean(x) - mean(y)`` within ``[lower,
    upper]`` (Welch: unequal variances)?  ``margin`` is a positive number
    m (the bounds ``(-m, m)``) or a ``(lower, upper)`` pair.  Each bound is
    tested by a one-sided t test at level alpha; the result is "equivalent"
    when both reject, the p-value is the larger of the two, and the
    ``1 - 2 alpha`` interval lies inside the bounds exactly then.

    For an estimator with exact value E, ``equivalence_test(x, mu=E,
    margin=0.001 * E)`` is the evidence that its bias is below 0.1% of E.
    x and y may be array-like (1-D) or `mcstat.Moments` accumulators.
    alpha must be in (0, 0.5).  Errors: the `ValueError` subclasses of
    `mcstat` (too few values, NaN with nan_policy="raise", constant data).
    """
    lower, upper = _margin(margin)
    mu = _real(mu, "mu")
    alpha = _real(alpha, "alpha")
    if not math.isfinite(mu):
        raise InvalidArgumentError(f"mu must be finite, got {mu!r}")
    if nan_policy not in ("raise", "omit"):
        raise InvalidArgumentError(f"nan_policy must be 'raise' or 'omit', got {nan_policy!r}")
    if y is not None and mu != 0.0:
        raise InvalidArgumentError("mu applies to one sample; for two, give the margin of the difference")
    d = _core._equivalence(x, y, mu, lower, upper, alpha, nan_policy == "omit")
    return EquivalenceResult(d, (lower, upper))


# ---- power -----------------------------------------------------------------------

_TESTS = {"t": 1, "one.sample": 1, "one-sample": 1, "t2": 2, "two.sample": 2, "two-sample": 2,
          "welch": 3, "var": 4, "chisq": 4, "f": 5}
_TEST_NAMES = {1: "t", 2: "t2", 3: "welch", 4: "var", 5: "f"}
_UNKNOWN = {"power": 0, "n": 1, "effect": 2, "alpha": 3}
_N_EXACT = 4  # MCSTAT_POWER_SOLVE_N_EXACT: the real root


class PowerResult:
    """The outcome of `power`: all four of n, effect, alpha and power.

    Attributes
    ----------
    test : str
        ``"t"``, ``"t2"``, ``"welch"``, ``"var"`` or ``"f"``.
    n : int or float
        Sample size (per group for ``"t2"``, of x for ``"welch"``/``"f"``).
        When solved for, an ``int``: the smallest n whose power reaches
        `power` (R users take ``ceiling()`` of power.t.test's n); otherwise
        the n given.
    n_exact : float
        The real n at which the power equals the target exactly (R's
        ``power.t.test(...)$n``, statsmodels' ``solve_power``), when n was
        solved for; else the n given.
    n_y : float or None
        ``n_ratio * n`` for ``"welch"`` and ``"f"``.
    effect : float
        d = difference / sd for the t tests; the variance ratio rho for
        ``"var"`` (sigma^2/sigma0^2) and ``"f"`` ((var_x/var_y)/ratio0).
    alpha, power : float
        When n was solved for, `power` is the power at that n (>= asked).
    alternative : str
    strict : bool
    solved_for : str
        ``"n"``, ``"effect"``, ``"alpha"`` or ``"power"``.
    """

    __slots__ = ("test", "n", "n_exact", "n_y", "effect", "alpha", "power", "alternative", "strict",
                 "solved_for", "sd_ratio", "_text")
    test: str
    n: float
    n_y: Optional[float]
    effect: float
    alpha: float
    power: float
    alternative: str
    strict: bool
    solved_for: str
    sd_ratio: float
    _text: str

    def __str__(self) -> str:
        return self._text

    def __repr__(self) -> str:
        return (f"PowerResult(test={self.test!r}, n={self.n:.7g}, effect={self.effect:.7g}, "
                f"alpha={self.alpha:.7g}, power={self.power:.7g}, alternative={self.alternative!r}, "
                f"solved_for={self.solved_for!r})")


def power(test: str = "t", *, n: Optional[float] = None, effect: Optional[float] = None,
          alpha: Optional[float] = 0.05, power: Optional[float] = None,
          alternative: str = "two-sided", strict: Optional[bool] = None, delta: Optional[float] = None,
          sd: Optional[float] = None, n_ratio: Optional[float] = None,
          sd_ratio: Optional[float] = None) -> PowerResult:
    """Power and sample size of the t, chi-squared and F tests.

    Experimental (libmcstat's mcstat/power.h): its name and options may change before 1.0; a
    renamed function stays as a deprecated alias for one release.

    Give all but one of ``n``, ``effect``, ``alpha`` and ``power``
    (``None`` marks the unknown; ``alpha`` defaults to 0.05, pass
    ``alpha=None`` to solve for it), as R's ``power.t.test`` and
    statsmodels' ``solve_power``.  n comes back as the smallest integer
    whose power reaches the target (``n_exact``: the real root).

    test:
      ``"t"``
        one-sample t; effect d = (mean - mu0)/sd
      ``"t2"``
        two-sample t, n per group, common sd (R's type="two.sample")
      ``"welch"``
        Welch's t, n_y = n_ratio * n, sd_y = sd_ratio * sd_x; effect
        d = (mean_x - mean_y)/sd_x (Welch-Satterthwaite approximation)
      ``"var"``
        one-sample chi-squared; effect rho = sigma^2/sigma0^2 (exact)
      ``"f"``
        two-sample F, n_y = n_ratio * n; effect rho = (var_x/var_y)/ratio0 (exact)

    For the t tests, ``delta`` and ``sd`` may be given instead of ``effect``
    (effect = delta / sd, sd defaults to 1).  ``strict`` (two-sided): count
    rejections in both tails (True, the default: the true rejection
    probability) or only in the effect's tail (False, R's default).
    Arguments that do not apply raise `InvalidArgumentError` naming them: ``n_ratio``
    (default 1) is for ``"welch"`` and ``"f"`` only (``"t2"`` has equal
    groups: use ``"welch"`` for unequal ones), ``sd_ratio`` (default 1) for
    ``"welch"``, ``delta`` and ``sd`` for the t tests, ``strict`` for the
    two-sided alternative.  When solving for the effect
    the solution is on the alternative's side (d > 0 or rho > 1 for
    two-sided).

    Example: samples to detect a 0.1% bias of an estimator whose primary
    estimates have mean E and standard deviation s, at power 0.9:
    ``power("t", effect=0.001 * E / s, power=0.9).n``.
    """
    code = _TESTS.get(test) if isinstance(test, str) else None
    if code is None:
        raise InvalidArgumentError(f"test must be one of 't', 't2', 'welch', 'var', 'f', got {test!r}")
    is_t = code <= 3
    name = _TEST_NAMES[code]
    if n_ratio is not None and code not in (3, 5):
        raise InvalidArgumentError(f"n_ratio applies to test='welch' and test='f' only, not test={name!r}"
                        + (" (whose groups are equal: use test='welch' for unequal ones)" if code == 2 else ""))
    if sd_ratio is not None and code != 3:
        raise InvalidArgumentError(f"sd_ratio applies to test='welch' only, not test={name!r}")
    alt = _alternative(alternative)
    if strict is not None and alt != 0:
        raise InvalidArgumentError(f"strict applies to the two-sided alternative only, not "
                        f"alternative={_ALT_NAMES[alt]!r}")
    strict = True if strict is None else strict
    n_ratio = 1.0 if n_ratio is None else n_ratio
    sd_ratio = 1.0 if sd_ratio is None else sd_ratio
    if delta is not None or sd is not None:
        if not is_t:
            raise InvalidArgumentError(f"delta and sd apply to the t tests, not test={name!r}; give effect "
                            "(a variance ratio)")
        if effect is not None:
            raise InvalidArgumentError("give effect, or delta (and sd), not both")
        if delta is not None:
            s = 1.0 if sd is None else _real(sd, "sd")
            if not (s > 0 and math.isfinite(s)):
                raise InvalidArgumentError(f"sd must be positive, got {sd!r}")
            effect = _real(delta, "delta") / s
    values = {"n": n, "effect": effect, "alpha": alpha, "power": power}
    missing = [k for k, v in values.items() if v is None]
    if len(missing) != 1:
        raise InvalidArgumentError(
            "exactly one of n, effect (or delta), alpha and power must be None (the unknown), got "
            + (", ".join(missing) if missing else "none"))
    unknown = missing[0]
    nums = {k: (math.nan if v is None else _real(v, k)) for k, v in values.items()}
    args = (code, alt, bool(strict), nums["n"], _real(n_ratio, "n_ratio"), _real(sd_ratio, "sd_ratio"),
            nums["effect"], nums["alpha"], nums["power"])
    d = _core._power(*args, _UNKNOWN[unknown])
    r = PowerResult()
    r.test = name
    if unknown == "n":
        r.n = int(d["n"])  # libmcstat's smallest integer n reaching the power
        r.n_exact = _core._power(*args, _N_EXACT)["n"]
    else:
        r.n = r.n_exact = d["n"]
    r.n_y = d["n"] * d["n_ratio"] if code in (3, 5) else None
    r.effect = d["effect"]
    r.alpha = d["alpha"]
    r.power = d["power"]
    r.alternative = _ALT_NAMES[alt]
    r.strict = bool(strict)
    r.solved_for = unknown
    r.sd_ratio = d["sd_ratio"]
    r._text = d["text"]
    return r


# ---- K-S power by simulation ----------------------------------------------------------

class KSPowerResult:
    """Simulated power of the two-sample K-S test.

    Attributes
    ----------
    power : float
        Fraction of the ``n_rep`` simulated pairs of samples rejected at `alpha`.
    se : float
        Its Monte Carlo standard error, sqrt(power (1 - power) / n_rep).
    n, n_y, n_rep, alpha, weight, alternative
    """

    __slots__ = ("power", "se", "n", "n_y", "n_rep", "alpha", "weight", "alternative")
    power: float
    se: float
    n: int
    n_y: int
    n_rep: int
    alpha: float
    weight: str
    alternative: str

    def __str__(self) -> str:
        return (f"\n     Two-sample Kolmogorov-Smirnov test power (simulated, weight {self.weight})\n\n"
                f"{'n':>15} = {self.n}\n{'n.y':>15} = {self.n_y}\n{'sig.level':>15} = {self.alpha:.7g}\n"
                f"{'power':>15} = {self.power:.7g}\n{'MC std. error':>15} = {self.se:.3g}\n"
                f"{'replicates':>15} = {self.n_rep}\n{'alternative':>15} = {self.alternative}\n\n")

    def __repr__(self) -> str:
        return f"KSPowerResult(power={self.power:.4g}, se={self.se:.2g}, n={self.n}, n_y={self.n_y})"


Sampler = Callable[[np.random.Generator, int], np.ndarray]


def _normal(rng: np.random.Generator, k: int) -> np.ndarray:
    return rng.standard_normal(k)


def ks_power(n: int, n_y: Optional[int] = None, *, sampler: Optional[Sampler] = None,
             sampler_y: Optional[Sampler] = None, shift: float = 0.0, scale: float = 1.0,
             weight: str = "canner", alternative: str = "two-sided", alpha: float = 0.05,
             n_rep: int = 1000, seed: int = 0) -> KSPowerResult:
    """Power of `mcstat.ks_test` by simulation.

    Experimental (libmcstat's mcstat/power.h family): its name and options may change before
    1.0; a renamed function stays as a deprecated alias for one release.

    Draws ``n_rep`` pairs: y from ``sampler_y`` (default: ``sampler``, or the
    standard normal) and x = shift + scale * (a draw of ``sampler``), each a
    function ``(numpy Generator, size) -> array``; counts the rejections at
    ``alpha`` and reports the fraction with its Monte Carlo standard error.
    Deterministic for a seed.
    """
    n = int(n)
    n_y = n if n_y is None else int(n_y)
    if n < 1 or n_y < 1:
        raise InvalidArgumentError(f"sample sizes must be >= 1, got n={n}, n_y={n_y}")
    n_rep = int(n_rep)
    if n_rep < 1:
        raise InvalidArgumentError(f"n_rep must be >= 1, got {n_rep}")
    shift, scale = _real(shift, "shift"), _real(scale, "scale")
    if not (math.isfinite(shift) and scale > 0 and math.isfinite(scale)):
        raise InvalidArgumentError(f"shift must be finite and scale positive, got {shift!r}, {scale!r}")
    alpha = _real(alpha, "alpha")
    if not (0 < alpha < 1):
        raise InvalidArgumentError(f"alpha must be in (0, 1), got {alpha!r}")
    sx = sampler or _normal
    sy = sampler_y or sampler or _normal
    rng = np.random.default_rng(seed)
    rejected = 0
    for i in range(n_rep):
        x = shift + scale * np.asarray(sx(rng, n), dtype=np.float64)
        y = np.asarray(sy(rng, n_y), dtype=np.float64)
        r = _core.ks_test(x, y, weight=weight, alternative=alternative, alpha=alpha, seed=seed + i)
        rejected += bool(r.reject)
    p = rejected / n_rep
    out = KSPowerResult()
    out.power, out.se = p, math.sqrt(p * (1 - p) / n_rep)
    out.n, out.n_y, out.n_rep, out.alpha = n, n_y, n_rep, alpha
    out.weight, out.alternative = weight, alternative
    return out


def ks_sample_size(power: float = 0.9, *, n_ratio: float = 1.0, n_max: int = 100000,
                   **kwargs: Any) -> KSPowerResult:
    """The smallest n whose simulated K-S power reaches ``power``.

    Experimental (libmcstat's mcstat/power.h family): its name and options may change before
    1.0; a renamed function stays as a deprecated alias for one release.

    Doubling, then bisection over n (``n_y = ceil(n_ratio * n)``), each step
    a `ks_power` run with the given keyword arguments (samplers, shift,
    scale, weight, alternative, alpha, n_rep, seed).  The simulated power is
    noisy (its `se` is reported): n is the smallest size whose *estimate*
    reaches the target; raise n_rep for a sharper answer.  Returns the
    `KSPowerResult` at that n.  InvalidArgumentError beyond n_max.
    """
    target = _real(power, "power")
    if not (0 < target < 1):
        raise InvalidArgumentError(f"power must be in (0, 1), got {power!r}")

    def run(k: int) -> KSPowerResult:
        return ks_power(k, max(1, math.ceil(n_ratio * k)), **kwargs)

    lo, hi = 1, 2
    r_hi = run(hi)
    while r_hi.power < target:
        lo, hi = hi, hi * 2
        if hi > n_max:
            raise InvalidArgumentError(f"no n up to n_max={n_max} reaches power {target}")
        r_hi = run(hi)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        r = run(mid)
        if r.power >= target:
            hi, r_hi = mid, r
        else:
            lo = mid
    return r_hi
