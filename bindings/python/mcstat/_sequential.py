# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Render until decided: the driver of a :class:`SequentialTest`.

The test itself (every number, decision and sentence) is libmcstat's
``mcstat_seq``; this module only calls the caller's sampler in batches
and pushes what it returns.
"""
from __future__ import annotations

import sys
from typing import Any, Callable

from ._core import SequentialTest

__all__ = ["run_until_decided"]


def run_until_decided(
    draw: Callable[[int], Any],
    test: SequentialTest,
    *,
    budget: int,
    batch: int = 1000,
    progress: bool = False,
) -> SequentialTest:
    """Calls ``draw(k)`` and pushes its values into `test` until the test
    decides or `budget` values (of x) have been pushed; returns `test`.

    ``draw(k)`` returns k values (an array, or a :class:`Moments`); for the
    two-sample kinds a pair ``(x, y)``.  Every push is one look, so the
    batch size sets how often the test looks: the guarantee holds whatever
    it is (the error rate is at most alpha at any stopping time), smaller
    batches only stop sooner and cost more calls.  At the budget the test
    is returned undecided (``test.decided`` False, ``test.decision`` is
    ``"continue"``): call ``test.finish()`` to learn whether the tails
    ever allowed a decision (it raises :class:`HeavyTailError` if not).

    progress : show a bar on stderr (tqdm when installed, else a line).
    """
    if not isinstance(test, SequentialTest):
        raise TypeError(f"test must be a mcstat.SequentialTest, got {type(test).__name__}")
    for name, v in (("budget", budget), ("batch", batch)):
        if isinstance(v, bool) or not isinstance(v, int):
            raise TypeError(f"{name} must be an int, got {v!r}")
        if v < 1:
            from ._errors import InvalidArgumentError

            raise InvalidArgumentError(f"{name} must be >= 1, got {v!r}")
    if not callable(draw):
        raise TypeError(f"draw must be callable, got {draw!r}")
    two = test.kind in ("mean2", "var2")
    bar = _Progress(budget, test.n) if progress else None
    try:
        while not test.decided and test.n < budget:
            k = min(batch, budget - test.n)
            values = draw(k)
            if two:
                if not (isinstance(values, tuple) and len(values) == 2):
                    raise TypeError(f"draw({k}) must return a pair (x, y) for kind {test.kind!r}")
                test.push(values[0], values[1])
            else:
                test.push(values)
            if bar:
                bar.update(test)
    finally:
        if bar:
            bar.close(test)
    return test


class _Progress:
    """tqdm's bar when tqdm is installed (mcstat[report]), else one line."""

    def __init__(self, budget: int, start: int) -> None:
        self.budget, self.last = budget, start
        try:
            from tqdm import tqdm

            self.bar: Any = tqdm(total=budget, initial=start, unit="value", file=sys.stderr, leave=False)
        except ImportError:
            self.bar = None

    def update(self, test: SequentialTest) -> None:
        if self.bar is not None:
            self.bar.update(test.n - self.last)
            self.bar.set_postfix_str(f"p={test.pvalue:.3g} {test.decision}", refresh=False)
        else:
            sys.stderr.write(f"\r{test.n}/{self.budget} values, p = {test.pvalue:.3g}, {test.decision}   ")
        self.last = test.n

    def close(self, test: SequentialTest) -> None:
        if self.bar is not None:
            self.bar.close()
        else:
            sys.stderr.write("\n")
