# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The t, chi-squared and F distributions the tests use, as functions.

libmcstat's own (mcstat.h, "Distributions"), over NumPy arrays: the
arguments broadcast against each other as in NumPy's ufuncs; a scalar
result is a float, any other an ndarray of float64.

=====================================  ==========================  ==================================
mcstat                                 SciPy                       value
=====================================  ==========================  ==================================
``t_cdf(x, df)``                       ``stats.t.cdf(x, df)``      P[T <= x]
``t_cdf(x, df, upper=True)``           ``stats.t.sf(x, df)``       P[T > x]
``t_logcdf(x, df[, upper=True])``      ``logcdf`` / ``logsf``      log of the above, finite where
                                                                   the probability underflows
``t_quantile(p, df)``                  ``stats.t.ppf(p, df)``      x with P[T <= x] = p
``t_quantile(p, df, upper=True)``      ``stats.t.isf(p, df)``      x with P[T > x] = p
=====================================  ==========================  ==================================

and the same for ``chisq_*`` (``stats.chi2``) and ``f_*`` (``stats.f``,
two degrees of freedom).

Accuracy (mcstat.h; per-domain tables in libmcstat/ACCURACY.md): tail
probabilities are computed from whichever tail is small, never as 1 - P;
relative error against 50-digit references, for tail probabilities
p >= 1e-30: 3e-14 (t), 1.5e-13 (chi-squared), 4e-14 (F), quantiles 3e-13;
below 1e-30 down to 1e-300 about 6e-13.  Log versions: 8e-16 (t), 5e-15
(chi-squared), 8e-15 (F) relative error of log p.  Promised for degrees of
freedom in [1e-3, 1e15] and x anywhere.

Unlike SciPy these raise instead of returning NaN: `InvalidArgumentError`
(a ValueError) names the first bad argument, its value and its index in
the broadcast shape -- x NaN, p outside [0, 1], a degree of freedom not
positive and finite (infinite df included: use the normal distribution) --
or arguments that do not broadcast; TypeError for non-real input.
"""
from __future__ import annotations

from typing import Any, Optional, Union, cast, overload

import numpy as np
import numpy.typing as npt

from . import _core

__all__ = [
    "t_cdf",
    "t_logcdf",
    "t_quantile",
    "chisq_cdf",
    "chisq_logcdf",
    "chisq_quantile",
    "f_cdf",
    "f_logcdf",
    "f_quantile",
]

_Float = Union[float, int, np.floating[Any], np.integer[Any]]
_Out = Union[float, npt.NDArray[np.float64]]


def _call(name: str, a: Any, b: Any, c: Optional[Any], upper: Any) -> _Out:
    if not isinstance(upper, (bool, np.bool_)):
        raise TypeError(f"{name}(): upper must be a bool, got {upper!r}")
    return cast(_Out, _core._distribution(name, a, b, c, bool(upper)))


# Each function: a float for scalar arguments, an ndarray otherwise.

@overload
def t_cdf(x: _Float, df: _Float, *, upper: bool = False) -> float: ...
@overload
def t_cdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def t_cdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """P[T <= x] for Student's t with `df` degrees of freedom; P[T > x]
    with ``upper=True`` (SciPy's ``t.cdf`` / ``t.sf``)."""
    return _call("t_cdf", x, df, None, upper)


@overload
def t_logcdf(x: _Float, df: _Float, *, upper: bool = False) -> float: ...
@overload
def t_logcdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def t_logcdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """log P[T <= x] (log P[T > x] with ``upper=True``), finite where the
    probability underflows (SciPy's ``t.logcdf`` / ``t.logsf``)."""
    return _call("t_logcdf", x, df, None, upper)


@overload
def t_quantile(p: _Float, df: _Float, *, upper: bool = False) -> float: ...
@overload
def t_quantile(p: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def t_quantile(p: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """x with P[T <= x] = p (P[T > x] = p with ``upper=True``); p in [0, 1]
    (SciPy's ``t.ppf`` / ``t.isf``)."""
    return _call("t_quantile", p, df, None, upper)


@overload
def chisq_cdf(x: _Float, df: _Float, *, upper: bool = False) -> float: ...
@overload
def chisq_cdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def chisq_cdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """P[X <= x] for chi-squared with `df` degrees of freedom; P[X > x]
    with ``upper=True`` (SciPy's ``chi2.cdf`` / ``chi2.sf``)."""
    return _call("chisq_cdf", x, df, None, upper)


@overload
def chisq_logcdf(x: _Float, df: _Float, *, upper: bool = False) -> float: ...
@overload
def chisq_logcdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def chisq_logcdf(x: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """log P[X <= x] (log P[X > x] with ``upper=True``) for chi-squared
    (SciPy's ``chi2.logcdf`` / ``chi2.logsf``)."""
    return _call("chisq_logcdf", x, df, None, upper)


@overload
def chisq_quantile(p: _Float, df: _Float, *, upper: bool = False) -> float: ...
@overload
def chisq_quantile(p: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def chisq_quantile(p: npt.ArrayLike, df: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """x with P[X <= x] = p (P[X > x] = p with ``upper=True``) for
    chi-squared (SciPy's ``chi2.ppf`` / ``chi2.isf``)."""
    return _call("chisq_quantile", p, df, None, upper)


@overload
def f_cdf(x: _Float, df1: _Float, df2: _Float, *, upper: bool = False) -> float: ...
@overload
def f_cdf(x: npt.ArrayLike, df1: npt.ArrayLike, df2: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def f_cdf(x: npt.ArrayLike, df1: npt.ArrayLike, df2: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """P[F <= x] for Fisher's F with (df1, df2) degrees of freedom; P[F > x]
    with ``upper=True`` (SciPy's ``f.cdf`` / ``f.sf``)."""
    return _call("f_cdf", x, df1, df2, upper)


@overload
def f_logcdf(x: _Float, df1: _Float, df2: _Float, *, upper: bool = False) -> float: ...
@overload
def f_logcdf(x: npt.ArrayLike, df1: npt.ArrayLike, df2: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def f_logcdf(x: npt.ArrayLike, df1: npt.ArrayLike, df2: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """log P[F <= x] (log P[F > x] with ``upper=True``) for F (SciPy's
    ``f.logcdf`` / ``f.logsf``)."""
    return _call("f_logcdf", x, df1, df2, upper)


@overload
def f_quantile(p: _Float, df1: _Float, df2: _Float, *, upper: bool = False) -> float: ...
@overload
def f_quantile(p: npt.ArrayLike, df1: npt.ArrayLike, df2: npt.ArrayLike, *, upper: bool = False) -> _Out: ...
def f_quantile(p: npt.ArrayLike, df1: npt.ArrayLike, df2: npt.ArrayLike, *, upper: bool = False) -> _Out:
    """x with P[F <= x] = p (P[F > x] = p with ``upper=True``) for F
    (SciPy's ``f.ppf`` / ``f.isf``)."""
    return _call("f_quantile", p, df1, df2, upper)
