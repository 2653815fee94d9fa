# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""check_gradient: does a gradient estimator agree with finite differences?

A gradient estimator of a Monte Carlo renderer (automatic differentiation
of the renderer, or a hand-written derivative) is compared with central
finite differences of the same loss, or with another estimator of the same
derivative, over n independent seeds with common random numbers: seed i
gives one AD estimate and one finite difference from the same random
numbers, and the paired differences d_i = AD_i - FD_i are tested.

H0 (per parameter): ``|E d| <= margin``, the gradients agree up to the margin
allowed for the finite difference's bias.  It is rejected when the
1 - alpha confidence interval of E d lies entirely outside
[-margin, margin]: two one-sided t tests, H1 "E d > margin" and H1
"E d < -margin", each at alpha/2 (libmcstat's paired t test,
mcstat_t_test_paired, with mu0 = +-margin); p = min(1, 2 min(p+, p-)).
Its size is at most alpha for every E d inside the margin.

The margin is the user's absolute `margin`, plus `rtol` times an upper
confidence bound of ``|E reference|``, plus (``richardson=True``, the default
when `f` is given) an upper confidence bound of the central difference's
bias estimated by Richardson's rule from steps h and 2h with the same
seeds, bias(h) ~ (FD(2h) - FD(h)) / 3.  Those bounds spend a share of
alpha (`bound_share`, Bonferroni over every bound), the tests the rest,
Holm (or Bonferroni) across the parameters; so a correct gradient is
rejected with probability at most alpha overall provided (i) the seeds
give independent samples with finite variance (the t tests' assumption),
and (ii) the central difference's bias at h is at most
`richardson_factor` (2) times the Richardson term's expectation in
magnitude, plus `margin` (true when h is in the asymptotic range, bias =
c2 h^2 + c4 h^4 + o(h^4) with c4 h^2 >= -c2 / 9 in c2's direction).
"""
from __future__ import annotations

import math
import numbers
import operator
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np

from . import _core
from .distributions import t_quantile
from ._errors import (
    CallbackError,
    DegenerateDataError,
    InvalidArgumentError,
    NonFiniteError,
    TooFewObservationsError,
)

__all__ = ["check_gradient", "GradientReport", "GradientParameter"]

_WHO = "check_gradient"
_ADJUST = {"holm": "Holm", "bonferroni": "Bonferroni"}


def _fmt(v: Optional[float]) -> str:
    if v is None or not math.isfinite(v):
        return str(v)
    return f"{v:.4g}"


@dataclass(eq=False)
class GradientParameter:
    """One parameter's line of a `GradientReport`.

    Attributes
    ----------
    name : str
    mean_grad, mean_ref : float
        Mean of the gradient estimates (AD) and of the finite differences
        (or reference estimates) over the n seeds.
    mean_diff : float
        Mean of d_i = AD_i - FD_i.
    std_error : float
        Its standard error (0 when the differences are constant).
    conf_int : tuple of float
        The 1 - alpha_test confidence interval of E d (per parameter, not
        adjusted for the other parameters); the parameter is rejected alone
        (one parameter) when it lies outside ``(-margin, margin)``.
    margin : float
        The margin tested: ``margin_given + rtol * ref_bound + bias_bound``.
    margin_given : float
        The absolute margin passed in.
    ref_bound : float or None
        Upper confidence bound of ``|E reference|`` (only with ``rtol > 0``).
    bias : float or None
        Richardson's estimate of the central difference's bias at h,
        mean of (FD(2h) - FD(h)) / 3; None without Richardson.
    bias_bound : float or None
        `richardson_factor` times an upper confidence bound of the
        magnitude of that bias: what the margin adds for it.
    pvalue : float
        min(1, 2 min(p+, p-)) of the two one-sided tests.
    pvalues : tuple of float
        (p+, p-): H1 "E d > margin" and H1 "E d < -margin".
    pvalue_adjusted : float
        Holm- (or Bonferroni-) adjusted across the parameters.
    reject : bool
        ``pvalue_adjusted <= alpha_test``.
    detectable : float
        The smallest ``|E d|`` this run detects with probability 0.8 (normal
        approximation with t quantiles, at the Bonferroni level
        alpha_test / k): ``margin + (t(1 - a/2) + t(0.8)) * std_error``.
        A pass says an error of that size could hide.
    exact : bool
        The differences were constant to rounding: decided from their range
        (reject iff all of them lie beyond the margin on one side).
    """

    name: str
    mean_grad: float
    mean_ref: float
    margin: float
    margin_given: float
    ref_bound: Optional[float]
    bias: Optional[float]
    bias_bound: Optional[float]
    mean_diff: float
    std_error: float
    conf_int: Tuple[float, float]
    pvalue: float
    pvalues: Tuple[float, float]
    detectable: float
    exact: bool
    pvalue_adjusted: float
    reject: bool

    def __repr__(self) -> str:
        return (f"GradientParameter(name={self.name!r}, mean_diff={self.mean_diff!r}, "
                f"conf_int={self.conf_int!r}, margin={self.margin!r}, pvalue={self.pvalue!r}, "
                f"pvalue_adjusted={self.pvalue_adjusted!r}, reject={self.reject!r})")


@dataclass(eq=False, repr=False)
class GradientReport:
    """The outcome of `check_gradient`.

    Attributes
    ----------
    reject : bool
        Some parameter's gradient disagrees beyond its margin (family-wise
        level alpha across the parameters and the bounds).
    pvalue : float
        The smallest adjusted p-value, to compare with `alpha_test`.
    alpha : float
        The overall level.
    alpha_test, alpha_bounds : float
        Its split: the tests (adjusted across parameters) and the
        confidence bounds that widen the margins (Bonferroni over
        `n_bounds` bounds); ``alpha_bounds`` is 0 without bounds.
    n_bounds : int
    n : int
        Seeds (paired samples).
    adjust : str
        ``"holm"`` or ``"bonferroni"``.
    method : str
        ``"finite difference"`` (from `f`) or ``"reference"``.
    h : tuple of float or None
        Steps of the finite differences (from `f`).
    richardson, richardson_factor, rtol : bool, float, float
    parameters : list of GradientParameter
    grad, ref : numpy.ndarray
        The (n, k) per-seed gradient estimates and finite differences (or
        reference estimates); ``ref_2h`` those at step 2h, or None.
    """

    reject: bool
    pvalue: float
    alpha: float
    alpha_test: float
    alpha_bounds: float
    n_bounds: int
    n: int
    adjust: str
    method: str
    h: Optional[Tuple[float, ...]]
    richardson: bool
    richardson_factor: float
    rtol: float
    parameters: List[GradientParameter]
    grad: np.ndarray
    ref: np.ndarray
    ref_2h: Optional[np.ndarray]

    def __iter__(self) -> Iterator[GradientParameter]:
        return iter(self.parameters)

    def __len__(self) -> int:
        return len(self.parameters)

    def parameter(self, name: Any) -> GradientParameter:
        """The parameter named `name` (or at index `name`)."""
        if isinstance(name, numbers.Integral) and not isinstance(name, bool):
            return self.parameters[operator.index(name)]
        for p in self.parameters:
            if p.name == name:
                return p
        raise KeyError(name)

    def __repr__(self) -> str:
        return (f"GradientReport(reject={self.reject!r}, pvalue={self.pvalue!r}, alpha={self.alpha!r}, "
                f"n={self.n!r}, parameters={len(self.parameters)})")

    def __str__(self) -> str:
        k = len(self.parameters)
        ref = "central differences" if self.method == "finite difference" else "the reference"
        lines = ["", f"\tGradient check: does the gradient agree with {ref}?", ""]
        split = f"alpha = {_fmt(self.alpha)}"
        if self.n_bounds:
            split += (f" ({_fmt(self.alpha_test)} for the tests, {_fmt(self.alpha_bounds)} for "
                      f"{self.n_bounds} margin bound{'s' if self.n_bounds > 1 else ''})")
        lines.append(f"n = {self.n} seeds (paired, common random numbers), {split}")
        if self.h is not None:
            hs = ", ".join(_fmt(v) for v in self.h)
            lines.append(f"finite differences: central, h = {hs}; Richardson bias bound "
                         f"{f'on (steps h and 2h, x {_fmt(self.richardson_factor)})' if self.richardson else 'off'}")
        else:
            lines.append(f"reference estimator; Richardson bias bound "
                         f"{f'on (reference at 2h, x {_fmt(self.richardson_factor)})' if self.richardson else 'off'}")
        if self.rtol > 0:
            lines.append(f"margin: absolute + rtol {_fmt(self.rtol)} x upper bound of |mean reference|")
        conf = 100 * (1 - self.alpha_test)
        name_w = max(len(p.name) for p in self.parameters)
        adj = _ADJUST[self.adjust] + "-adjusted" if k > 1 else "adjusted"
        lines.append(f"parameters (difference = gradient - {'FD' if self.method == 'finite difference' else 'reference'}):")
        for p in self.parameters:
            verdict = "reject" if p.reject else "pass  "
            lo, hi = p.conf_int
            margin = f"margin {_fmt(p.margin)}"
            parts = []
            if p.bias is not None:
                parts.append(f"Richardson bias {_fmt(p.bias)}, bound {_fmt(p.bias_bound)}")
            if p.ref_bound is not None:
                parts.append(f"|reference| <= {_fmt(p.ref_bound)}")
            if parts:
                margin += f" (given {_fmt(p.margin_given)}; " + "; ".join(parts) + ")"
            exact = ", constant differences: decided exactly" if p.exact else ""
            lines.append(
                f"  {p.name:<{name_w}}  {verdict} gradient {_fmt(p.mean_grad)} vs {_fmt(p.mean_ref)}: "
                f"difference {_fmt(p.mean_diff)}, {conf:g} percent CI [{_fmt(lo)}, {_fmt(hi)}], "
                f"{margin}, p-value = {_fmt(p.pvalue)}, {adj} {_fmt(p.pvalue_adjusted)}{exact}")
        lines.append("smallest |difference| each parameter detects with probability 0.8 at this budget:")
        for p in self.parameters:
            lines.append(f"  {p.name:<{name_w}}  {_fmt(p.detectable)} (margin {_fmt(p.margin)} + "
                         f"{_fmt(p.detectable - p.margin)})")
        if self.reject:
            bad = ", ".join(p.name for p in self.parameters if p.reject)
            lines.append(f"decision at alpha = {_fmt(self.alpha)}: inconsistent (the gradient disagrees: {bad})")
        else:
            lines.append(f"decision at alpha = {_fmt(self.alpha)}: consistent (no parameter rejected; a "
                         "correct gradient is rejected with probability at most alpha)")
        return "\n".join(lines) + "\n"


# ---- arguments ---------------------------------------------------------------------


def _real(v: Any, name: str) -> float:
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise TypeError(f"{_WHO}: {name} must be a real number, got {v!r}")
    return float(v)


def _per_param(v: Any, name: str, k: int, *, positive: bool) -> np.ndarray:
    """a scalar or k values, finite and >= 0 (> 0 when positive)"""
    if isinstance(v, bool):
        raise TypeError(f"{_WHO}: {name} must be a real number or {k} of them, got {v!r}")
    try:
        a = np.asarray(v, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{_WHO}: {name} must be a real number or {k} of them, got {v!r}") from None
    if a.ndim == 0:
        a = np.full(k, float(a))
    elif a.shape != (k,):
        raise InvalidArgumentError(f"{_WHO}: {name} must be a scalar or have {k} values (one per "
                                   f"parameter), got shape {a.shape}")
    bad = ~np.isfinite(a) | ((a <= 0) if positive else (a < 0))
    if bad.any():
        what = "> 0" if positive else ">= 0"
        raise InvalidArgumentError(f"{_WHO}: {name} must be finite and {what}, got {v!r}")
    return a


def _samples(v: Any, name: str) -> np.ndarray:
    """pre-computed per-seed values: (n,) or (n, k) -> (n, k) float64"""
    if isinstance(v, (str, bytes)):
        raise TypeError(f"{_WHO}: {name} must be an array of per-seed values or a callable, got {v!r}")
    try:
        a = np.array(v, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{_WHO}: {name} must be an array of per-seed values or a callable") from None
    if a.ndim == 1:
        a = a[:, None]
    if a.ndim != 2:
        raise InvalidArgumentError(f"{_WHO}: {name} must have shape (n,) or (n, k) (seeds x parameters), "
                                   f"got shape {a.shape}")
    if not np.isfinite(a).all():
        i = tuple(np.argwhere(~np.isfinite(a))[0])
        raise NonFiniteError(f"{_WHO}: {name} holds a non-finite value {a[i]!r} at index {i}")
    return a


def _returned_reals(out: Any, where: str, what: str) -> np.ndarray:
    """what a callable returned as float64, or CallbackError saying it is not `what`"""
    if out is None or isinstance(out, (str, bytes)):
        raise CallbackError(f"{_WHO}: {where} returned {type(out).__name__} {out!r:.80}, not {what}")
    try:
        return np.asarray(out, dtype=np.float64)
    except (TypeError, ValueError):
        raise CallbackError(f"{_WHO}: {where} returned {type(out).__name__} {out!r:.80}, not {what}") from None


def _call_vector(fn: Callable[..., Any], name: str, args: Tuple[Any, ...], k: Optional[int]) -> np.ndarray:
    out = fn(*args)
    where = f"{name}({', '.join(repr(a) for a in args)})"
    a = _returned_reals(out, where, "real numbers")
    if a.ndim > 1 and a.size == max(a.shape):  # (k, 1), (1, k)
        a = a.ravel()
    if a.ndim > 1:
        raise CallbackError(f"{_WHO}: {where} returned an array of shape {a.shape}; expected "
                            f"{'a scalar or 1-D array' if k is None else f'{k} value(s)'}")
    a = a.reshape(-1)
    if k is not None and a.size != k:
        raise CallbackError(f"{_WHO}: {where} returned {a.size} value(s); expected {k} (one per parameter)")
    if a.size == 0:
        raise CallbackError(f"{_WHO}: {where} returned no values")
    if not np.isfinite(a).all():
        raise CallbackError(f"{_WHO}: {where} returned a non-finite value: {out!r:.80}")
    return a


def _call_scalar(fn: Callable[..., Any], name: str, theta: Any, seed: int) -> float:
    out = fn(theta, seed)
    where = f"{name}(theta={theta!r}, seed={seed!r})"
    a = _returned_reals(out, where, "a real number")
    if a.size != 1:
        raise CallbackError(f"{_WHO}: {where} returned {a.size} values (shape {a.shape}); expected one "
                            "real number (the loss)")
    v = float(a.reshape(-1)[0])
    if not math.isfinite(v):
        raise CallbackError(f"{_WHO}: {where} returned a non-finite value {v!r}")
    return v


# ---- statistics (libmcstat's t tests) ------------------------------------------------------


def _abs_upper(x: np.ndarray, a: float) -> float:
    """an upper confidence bound at 1 - a of |E x|: the larger end, in
    magnitude, of the two-sided 1 - a t interval (P(|E x| > bound) <=
    P(E x outside the interval) <= a); the largest |x| when x is constant"""
    try:
        lo, hi = _core.t_test(x, alpha=a).conf_int
    except DegenerateDataError:
        return float(np.max(np.abs(x)))
    return float(max(abs(lo), abs(hi)))


def _test_one(g: np.ndarray, r: np.ndarray, margin: float, alpha_t: float,
              level_k: float) -> Dict[str, Any]:
    d = g - r
    try:
        two = _core.t_test(g, r, paired=True, alpha=alpha_t)
    except DegenerateDataError:
        lo, hi = float(np.min(d)), float(np.max(d))
        p = 0.0 if (lo > margin or hi < -margin) else 1.0
        pp = 0.0 if lo > margin else 1.0
        pm = 0.0 if hi < -margin else 1.0
        return dict(mean_diff=float(np.mean(d)), std_error=0.0, conf_int=(lo, hi), pvalue=p,
                    pvalues=(pp, pm), detectable=margin, exact=True)
    p_plus = _core.t_test(g, r, paired=True, mu=margin, alternative="greater", intervals=False).pvalue
    p_minus = _core.t_test(g, r, paired=True, mu=-margin, alternative="less", intervals=False).pvalue
    df, se = two.df, two.std_error
    detect = margin + (t_quantile(1.0 - level_k / 2.0, df) + t_quantile(0.8, df)) * se
    return dict(mean_diff=float(two.estimate), std_error=float(se), conf_int=tuple(map(float, two.conf_int)),
                pvalue=min(1.0, 2.0 * min(p_plus, p_minus)), pvalues=(float(p_plus), float(p_minus)),
                detectable=float(detect), exact=False)


# ---- the check --------------------------------------------------------------------------


def check_gradient(grad: Any, f: Optional[Callable[..., Any]] = None, theta: Any = None, *,
                   h: Any = None, reference: Any = None, reference_2h: Any = None,
                   n: int = 32, seed: int = 0, seeds: Optional[Sequence[int]] = None,
                   margin: Any = 0.0, rtol: float = 0.0, richardson: Optional[bool] = None,
                   richardson_factor: float = 2.0,
                   alpha: float = 0.05, bound_share: float = 0.2, adjust: str = "holm",
                   names: Optional[Sequence[str]] = None) -> GradientReport:
    """Does a gradient estimator agree with finite differences (or a
    reference estimator) of the same derivative?

    Per parameter, the paired differences d_i = grad_i - FD_i over n seeds
    test H0 ``|E d| <= margin`` against "the gradients disagree by more than
    the margin": rejected when the 1 - alpha_test confidence interval of
    E d lies entirely outside [-margin, margin] (two one-sided paired t
    tests of libmcstat at alpha_test / 2 each).  A correct gradient is
    rejected with probability at most `alpha`, provided the seeds give
    independent samples of finite variance and the finite difference's
    bias lies within the margin (see `richardson`).

    Parameters
    ----------
    grad : callable or array_like
        ``grad(seed)`` -> the gradient estimate(s) of one seed: a scalar or
        k values (one per parameter).  Or the pre-computed per-seed values,
        shape (n,) or (n, k), with `reference` (and `reference_2h`) arrays
        of the same shape (a renderer outside Python).
    f : callable, optional
        ``f(theta, seed)`` -> the scalar loss at `theta`, rendered with the
        random numbers of `seed` (common random numbers: the same seed must
        give the same random numbers at every theta).  Its central
        differences (f(theta + h e_j) - f(theta - h e_j)) / 2h are the
        reference.  Give `f` (with `theta`, `h`) or `reference`.
    theta : float or array_like of k floats
        The parameters at which the gradient is checked (with `f`); passed
        to `f` as a float when a float, else as a NumPy array.
    h : float or k floats, > 0
        Finite-difference steps (with `f`).
    reference : callable or array_like, optional
        ``reference(seed)`` -> another estimate of the same derivative(s)
        (k values), or their per-seed array.  The pairs need not share
        random numbers, but pair i must be independent of pair j.
    reference_2h : callable or array_like, optional
        With `reference` a finite difference at step h computed outside:
        the same at step 2h with the same seeds, for the Richardson bound.
    n : int
        Seeds, at least 2: ``seed, seed + 1, ..., seed + n - 1`` (callables).
    seed : int
        The first seed.
    seeds : sequence of int, optional
        The seeds themselves, in place of `n` and `seed`.
    margin : float or k floats, >= 0
        Absolute margin: differences up to it are agreement.
    rtol : float, >= 0
        Relative margin: plus rtol times an upper confidence bound of
        ``|E reference|`` (spends a share of alpha, see `bound_share`).
    richardson : bool, optional
        Widen each margin by an upper confidence bound of the central
        difference's bias, estimated from steps h and 2h with the same seeds
        (bias(h) ~ (FD(2h) - FD(h)) / 3; costs 2 more evaluations of `f`
        per parameter and seed).  Default: on with `f` or `reference_2h`.
        Assumes h is small enough that the h^2 term dominates the bias; off,
        the margin must cover the bias.
    richardson_factor : float, >= 1
        The margin adds this multiple of the bias bound.  Richardson's term
        is c2 h^2 + 5 c4 h^4 against a bias of c2 h^2 + c4 h^4: it
        underestimates the bias when c4 opposes c2, and the default 2
        covers a next term up to 1/9 of the leading one (c4 h^2 >= -c2 / 9;
        any size with c2's sign).  Common random numbers resolve the bias
        to a few percent, so 1 is not enough in general.
    alpha : float in (0, 1)
        Overall level: a correct gradient is rejected with probability at
        most alpha.
    bound_share : float in (0, 1)
        The share of alpha spent on the margins' confidence bounds (when
        there are any), Bonferroni over the bounds; the tests get the rest.
    adjust : {"holm", "bonferroni"}
        Multiplicity across the parameters (family-wise error rate under
        any dependence).
    names : sequence of str, optional
        The parameters' names in the report.

    Returns
    -------
    GradientReport
        ``reject``, per parameter the means, the interval, the margin, the
        Richardson bias, p-values and the smallest detectable difference;
        ``str()`` prints it.

    Raises
    ------
    TypeError
        A callable that is not one, a non-numeric argument.
    InvalidArgumentError
        alpha, bound_share, h, margin or rtol out of range; mismatched
        shapes; both or neither of `f` and `reference`; an unknown `adjust`.
    TooFewObservationsError
        Fewer than 2 seeds.
    NonFiniteError
        NaN or infinity in pre-computed values.
    CallbackError
        A callable returned the wrong shape, something not numeric, or NaN
        or infinity (the message names the callable and the seed).  An
        exception the callable raises propagates unchanged.
    """
    alpha = _real(alpha, "alpha")
    if not (0.0 < alpha < 1.0):
        raise InvalidArgumentError(f"{_WHO}: alpha must be in (0, 1), got {alpha!r}")
    bound_share = _real(bound_share, "bound_share")
    if not (0.0 < bound_share < 1.0):
        raise InvalidArgumentError(f"{_WHO}: bound_share must be in (0, 1), got {bound_share!r}")
    richardson_factor = _real(richardson_factor, "richardson_factor")
    if not (math.isfinite(richardson_factor) and richardson_factor >= 1.0):
        raise InvalidArgumentError(f"{_WHO}: richardson_factor must be finite and >= 1, got {richardson_factor!r}")
    rtol = _real(rtol, "rtol")
    if not (math.isfinite(rtol) and rtol >= 0.0):
        raise InvalidArgumentError(f"{_WHO}: rtol must be finite and >= 0, got {rtol!r}")
    if not isinstance(adjust, str):
        raise TypeError(f"{_WHO}: adjust must be a string, got {adjust!r}")
    adjust = adjust.lower()
    if adjust not in _ADJUST:
        raise InvalidArgumentError(f"{_WHO}: adjust must be 'holm' or 'bonferroni', got {adjust!r}")
    if richardson is not None and not isinstance(richardson, (bool, np.bool_)):
        raise TypeError(f"{_WHO}: richardson must be True, False or None, got {richardson!r}")

    if (f is None) == (reference is None):
        raise InvalidArgumentError(f"{_WHO}: give either f (with theta and h) or reference, "
                                   f"not {'both' if f is not None else 'neither'}")
    if f is not None and reference_2h is not None:
        raise InvalidArgumentError(f"{_WHO}: reference_2h is for a reference; with f the steps 2h are "
                                   "evaluated here (richardson=True)")
    if f is None and (theta is not None or h is not None):
        raise InvalidArgumentError(f"{_WHO}: theta and h are for f; a reference needs neither")

    arrays = not callable(grad)
    h_arr: Optional[np.ndarray] = None
    if arrays:
        if grad is None:
            raise TypeError(f"{_WHO}: grad must be a callable grad(seed) or an array of per-seed values")
        if f is not None:
            raise InvalidArgumentError(f"{_WHO}: with pre-computed grad values give the finite differences "
                                       "as a reference array, not f")
        if seeds is not None:
            raise InvalidArgumentError(f"{_WHO}: seeds are for callables; the arrays are the samples")
        g = _samples(grad, "grad")
        if callable(reference):
            raise InvalidArgumentError(f"{_WHO}: with pre-computed grad values reference must be an array too")
        r = _samples(reference, "reference")
        if r.shape != g.shape:
            raise InvalidArgumentError(f"{_WHO}: reference has shape {r.shape}, grad {g.shape}; they must "
                                       "match (seeds x parameters)")
        r2 = None
        if reference_2h is not None:
            if callable(reference_2h):
                raise InvalidArgumentError(f"{_WHO}: reference_2h must be an array like reference")
            r2 = _samples(reference_2h, "reference_2h")
            if r2.shape != g.shape:
                raise InvalidArgumentError(f"{_WHO}: reference_2h has shape {r2.shape}, grad {g.shape}; "
                                           "they must match")
        if g.shape[0] < 2:
            raise TooFewObservationsError(f"{_WHO}: need at least 2 seeds (rows), got {g.shape[0]}")
        n_seeds, k = g.shape
        method = "reference"
        use_rich = (r2 is not None) if richardson is None else bool(richardson)
        if use_rich and r2 is None:
            raise InvalidArgumentError(f"{_WHO}: richardson=True needs reference_2h (the finite "
                                       "differences at step 2h)")
    else:
        # seeds
        if seeds is None:
            if isinstance(n, bool) or not isinstance(n, numbers.Integral):
                raise TypeError(f"{_WHO}: n must be an integer, got {n!r}")
            if isinstance(seed, bool) or not isinstance(seed, numbers.Integral):
                raise TypeError(f"{_WHO}: seed must be an integer, got {seed!r}")
            seed_list = [int(seed) + i for i in range(max(int(n), 0))]
        else:
            if isinstance(seeds, (str, bytes)):
                raise TypeError(f"{_WHO}: seeds must be a sequence of integers")
            seed_list = list(seeds)
            for s in seed_list:
                if isinstance(s, bool) or not isinstance(s, numbers.Integral):
                    raise TypeError(f"{_WHO}: seeds must be integers, got {s!r}")
            if len(set(seed_list)) != len(seed_list):
                raise InvalidArgumentError(f"{_WHO}: seeds must be distinct (independent samples)")
        if len(seed_list) < 2:
            raise TooFewObservationsError(f"{_WHO}: need at least 2 seeds, got n = {len(seed_list)}")
        n_seeds = len(seed_list)
        if f is not None:
            if not callable(f):
                raise TypeError(f"{_WHO}: f must be a callable f(theta, seed), got {type(f).__name__}")
            if theta is None or h is None:
                raise InvalidArgumentError(f"{_WHO}: f needs theta and h")
            scalar_theta = isinstance(theta, numbers.Real) and not isinstance(theta, bool)
            if isinstance(theta, bool):
                raise TypeError(f"{_WHO}: theta must be a real number or an array of them, got {theta!r}")
            try:
                th = np.array(theta, dtype=np.float64).reshape(-1) if not scalar_theta else np.array([float(theta)])
            except (TypeError, ValueError):
                raise TypeError(f"{_WHO}: theta must be a real number or an array of them, got {theta!r}") from None
            if np.ndim(theta) > 1:
                raise InvalidArgumentError(f"{_WHO}: theta must be a scalar or 1-D, got shape {np.shape(theta)}")
            if th.size == 0:
                raise InvalidArgumentError(f"{_WHO}: theta is empty")
            if not np.isfinite(th).all():
                raise InvalidArgumentError(f"{_WHO}: theta must be finite, got {theta!r}")
            k = th.size
            h_arr = _per_param(h, "h", k, positive=True)
            use_rich = True if richardson is None else bool(richardson)
            steps = [1, 2] if use_rich else [1]
            # the points theta +- s h e_j and their exact spacing
            points = []
            for j in range(k):
                for s in steps:
                    tp, tm = th.copy(), th.copy()
                    tp[j] += s * h_arr[j]
                    tm[j] -= s * h_arr[j]
                    width = tp[j] - tm[j]
                    if not (width > 0 and math.isfinite(width)):
                        raise InvalidArgumentError(f"{_WHO}: h[{j}] = {float(h_arr[j])!r} vanishes beside "
                                                   f"theta[{j}] = {float(th[j])!r} in floating point")
                    points.append((j, s, tp, tm, width))
            as_arg = (lambda t: float(t[0])) if scalar_theta else (lambda t: t.copy())
            method = "finite difference"
        else:
            if not callable(reference):
                raise InvalidArgumentError(f"{_WHO}: with a callable grad, reference must be a callable "
                                           "reference(seed)")
            if reference_2h is not None and not callable(reference_2h):
                raise InvalidArgumentError(f"{_WHO}: reference_2h must be a callable like reference")
            use_rich = (reference_2h is not None) if richardson is None else bool(richardson)
            if use_rich and reference_2h is None:
                raise InvalidArgumentError(f"{_WHO}: richardson=True needs reference_2h (the finite "
                                           "differences at step 2h) or f")
            k = None  # from the first call
            method = "reference"
        g_rows, r_rows, r2_rows = [], [], []
        for s in seed_list:
            gi = _call_vector(grad, "grad", (s,), k)
            if k is None:
                k = gi.size
            g_rows.append(gi)
            if f is not None:
                fd1, fd2 = np.empty(k), np.empty(k)
                for j, st, tp, tm, width in points:
                    v = (_call_scalar(f, "f", as_arg(tp), s) - _call_scalar(f, "f", as_arg(tm), s)) / width
                    (fd1 if st == 1 else fd2)[j] = v
                r_rows.append(fd1)
                if use_rich:
                    r2_rows.append(fd2)
            else:
                r_rows.append(_call_vector(reference, "reference", (s,), k))
                if use_rich:
                    r2_rows.append(_call_vector(reference_2h, "reference_2h", (s,), k))
        g, r = np.array(g_rows), np.array(r_rows)
        r2 = np.array(r2_rows) if use_rich else None
        if not (np.isfinite(r).all() and (r2 is None or np.isfinite(r2).all())):
            raise CallbackError(f"{_WHO}: f's finite differences overflowed (h too small for f's values?)")
    assert k is not None

    marg = _per_param(margin, "margin", k, positive=False)
    if names is None:
        names_l = ["theta"] if k == 1 else [f"theta[{j}]" for j in range(k)]
    else:
        if isinstance(names, str):
            names = [names]
        names_l = [str(v) for v in names]
        if len(names_l) != k:
            raise InvalidArgumentError(f"{_WHO}: names has {len(names_l)} entries for {k} parameter(s)")

    n_bounds = k * (int(use_rich) + int(rtol > 0))
    alpha_bounds = bound_share * alpha if n_bounds else 0.0
    alpha_test = alpha - alpha_bounds
    a_bound = alpha_bounds / n_bounds if n_bounds else 0.0

    params = []
    for j in range(k):
        bias = bias_bound = ref_bound = None
        m = float(marg[j])
        if rtol > 0:
            ref_bound = _abs_upper(r[:, j], a_bound)
            m += rtol * ref_bound
        if use_rich:
            assert r2 is not None
            rr = (r2[:, j] - r[:, j]) / 3.0
            bias = float(np.mean(rr))
            bias_bound = richardson_factor * _abs_upper(rr, a_bound)
            m += bias_bound
        res = _test_one(g[:, j], r[:, j], m, alpha_test, alpha_test / k)
        params.append(GradientParameter(name=names_l[j], mean_grad=float(np.mean(g[:, j])),
                                        mean_ref=float(np.mean(r[:, j])), margin=m, margin_given=float(marg[j]),
                                        ref_bound=ref_bound, bias=bias, bias_bound=bias_bound,
                                        pvalue_adjusted=math.nan, reject=False, **res))
    p = np.array([q.pvalue for q in params])
    padj = _core.p_adjust(p, method=adjust) if k > 1 else p
    for q, pa in zip(params, padj):
        q.pvalue_adjusted = float(pa)
        q.reject = bool(pa <= alpha_test)
    return GradientReport(reject=any(q.reject for q in params), pvalue=float(np.min(padj)), alpha=alpha,
                          alpha_test=alpha_test, alpha_bounds=alpha_bounds, n_bounds=n_bounds, n=n_seeds,
                          adjust=adjust, method=method, h=None if h_arr is None else tuple(map(float, h_arr)),
                          richardson=use_rich, richardson_factor=richardson_factor, rtol=rtol,
                          parameters=params, grad=g, ref=r, ref_2h=r2)
