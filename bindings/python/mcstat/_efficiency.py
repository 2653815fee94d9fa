# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""compare_efficiency: time two estimators and test the ratio of their
efficiencies (`mcstat.efficiency_test` does the statistics, in C)."""
from __future__ import annotations

import operator
import time
from typing import Callable, Literal, Tuple

import numpy as np
import numpy.typing as npt

from ._core import Moments, TestResult, efficiency_test
from ._errors import InvalidArgumentError

__all__ = ["compare_efficiency"]


def _count(value: int, name: str, least: int) -> int:
    if isinstance(value, bool):
        raise TypeError(f"{name} must be an int, got {value!r}")
    try:
        k = operator.index(value)
    except TypeError:
        raise TypeError(f"{name} must be an int, got {value!r}") from None
    if k < least:
        raise InvalidArgumentError(f"{name} must be at least {least}, got {k}")
    return k


def _batch(draw: Callable[[int], npt.ArrayLike], size: int, name: str) -> Tuple[npt.NDArray[np.float64], float]:
    start = time.perf_counter()
    values = draw(size)
    elapsed = time.perf_counter() - start
    v = np.asarray(values, dtype=np.float64).reshape(-1)
    if v.size != size:
        raise InvalidArgumentError(f"{name}({size}) returned {v.size} values, expected {size}")
    return v, elapsed


def compare_efficiency(
    draw_x: Callable[[int], npt.ArrayLike],
    draw_y: Callable[[int], npt.ArrayLike],
    *,
    n: int,
    batches: int = 20,
    ratio: float = 1.0,
    alternative: Literal["two-sided", "less", "greater"] = "two-sided",
    alpha: float = 0.05,
    warmup: bool = True,
) -> TestResult:
    """Time two estimators and test the ratio of their efficiencies.

    ``draw_x(m)`` and ``draw_y(m)`` must return m samples (primary
    estimates) of each estimator.  Each is called `batches` times with
    ``m = n // batches``, alternately (x then y, then y then x, ...), so
    that whatever else loads the machine affects both; each call is timed
    with :func:`time.perf_counter`, its time per sample (the call's wall
    time / m) is one timing value, and its samples go into a `Moments`.
    The result is ``efficiency_test(samples_x, samples_y, times_x,
    times_y, ratio=..., alternative=..., alpha=...)``: rho = eff(x) /
    eff(y), "greater" means x is more efficient.

    Wall times are noisy (other processes, frequency scaling, caches): the
    test takes their batch-to-batch spread into account (a batch during
    which the process was preempted widens the interval), but not a bias
    common to all batches of one estimator.  Time on a quiet machine, with
    batches long enough (milliseconds) for the clock's resolution.  With
    ``warmup=True`` each callable is first called once, untimed and its
    values discarded (first-call costs: imports, allocations, caches).

    Parameters
    ----------
    draw_x, draw_y : callable
        ``f(m) -> array_like`` of m values.
    n : int
        Samples per estimator in total (at least 2 per batch).
    batches : int
        Timed batches per estimator (>= 2; 10-30 is typical).
    ratio, alternative, alpha
        As for `efficiency_test`.
    warmup : bool
        Call each callable once before timing (values discarded).

    Returns
    -------
    TestResult
        That of `efficiency_test`; ``str()`` prints its block.

    Raises
    ------
    InvalidArgumentError
        n or batches too small, a draw returning the wrong number of
        values, and `efficiency_test`'s errors.
    """
    if not callable(draw_x):
        raise TypeError(f"draw_x must be callable, got {draw_x!r}")
    if not callable(draw_y):
        raise TypeError(f"draw_y must be callable, got {draw_y!r}")
    k = _count(batches, "batches", 2)
    total = _count(n, "n", 2 * k)
    size = total // k
    if warmup:
        _batch(draw_x, size, "draw_x")
        _batch(draw_y, size, "draw_y")
    mx, my = Moments(), Moments()
    tx = np.empty(k)
    ty = np.empty(k)
    for b in range(k):
        # alternate which goes first, so a drift in load is shared
        order = ((draw_x, "draw_x", mx, tx), (draw_y, "draw_y", my, ty))
        for draw, name, m, t in order if b % 2 == 0 else order[::-1]:
            v, elapsed = _batch(draw, size, name)
            m.push(v)
            t[b] = elapsed / size
    return efficiency_test(mx, my, tx, ty, ratio=ratio, alternative=alternative, alpha=alpha)
