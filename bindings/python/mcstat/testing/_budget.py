# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""One error budget for a whole test suite.

A suite of m statistical tests, each at level alpha, fails on some correct
test with probability up to m alpha: 200 tests at 0.01 fail most runs.
Here the suite has one level, ``alpha`` (the probability that a run with
every tested component correct fails at all), and test i gets the share

    alpha_i = alpha w_i / sum_j w_j

(weights 1 unless a test is marked heavier), split evenly among the
checks it declares.  By Bonferroni's inequality the run's false-failure
probability is at most sum_i alpha_i = alpha, whatever the dependence
among the tests.  Shares are fixed at collection, before any test runs,
so a test's outcome never changes another's level.

`Suite` holds the budget and the records of the checks that ran; `Scope`
is the running test's share, its seed derivation and the count of its
checks.  The pytest plugin makes both; `scope()` makes a Scope by hand for
other runners (unittest, scripts).
"""
from __future__ import annotations

import contextlib
import contextvars
import math
from dataclasses import dataclass, field
from typing import Any, Dict, Iterator, List, Optional, Tuple

from .._errors import InvalidArgumentError
from ._seeds import check_seed, data_seed

__all__ = ["CheckRecord", "Suite", "Scope", "scope", "current_scope", "BudgetError"]


class BudgetError(InvalidArgumentError):
    """A statistical check that would spend more than its test's share:
    more checks than the test declared, or a check outside any budget."""


@dataclass
class CheckRecord:
    """One statistical check as it ran: what the summary and artifacts show."""

    test: str
    index: int
    kind: str
    alpha: float
    seed: int
    samples: int
    decision: str  # "pass", "reject" or "inconclusive"
    stages: int
    p_values: Tuple[float, ...]
    #: what a pass leaves room for: "an error below X could have hidden"
    could_hide: str = ""
    message: str = ""
    #: False for equivalence checks, whose alpha is the chance of a false pass
    spends_budget: bool = True


@dataclass
class Suite:
    """A run's budget: the level of the whole run, the master seed, the escalation."""

    alpha: float
    master_seed: int = 0
    escalate: float = 4.0  # stage 2 has escalate x n samples; 0: no escalation
    alpha0: float = 0.05  # an inconclusive stage 1 escalates when alpha1 < p1 <= alpha0
    artifacts: Optional[str] = None
    #: the whole suite's statistical tests (the sum of their weights), when
    #: only part of it is collected; None: the collected tests' weights
    suite_weight: Optional[float] = None
    #: where the run's node ids are valid (the reproduce line changes there)
    rootdir: Optional[str] = None
    shares: Dict[str, float] = field(default_factory=dict)
    checks: Dict[str, int] = field(default_factory=dict)
    records: List[CheckRecord] = field(default_factory=list)
    #: statistical tests that failed, by a check or an error before one: node id -> phase
    failed_tests: Dict[str, str] = field(default_factory=dict)
    total_weight: float = 0.0
    #: the statistical tests budgeted (len(shares); a pytest-xdist
    #: controller, which collects nothing, learns it from the workers)
    budgeted: int = 0

    def __post_init__(self) -> None:
        if not (isinstance(self.alpha, (int, float)) and 0.0 < self.alpha < 1.0):
            raise InvalidArgumentError(f"the suite's alpha must be in (0, 1), got {self.alpha!r}")
        if not (isinstance(self.master_seed, int) and 0 <= self.master_seed < 2**64):
            raise InvalidArgumentError(f"the master seed must be an integer in [0, 2**64), got {self.master_seed!r}")
        if not (math.isfinite(self.escalate) and (self.escalate == 0 or self.escalate >= 1)):
            raise InvalidArgumentError(f"escalate must be 0 (off) or a factor >= 1, got {self.escalate!r}")
        if not (0.0 < self.alpha0 <= 1.0):
            raise InvalidArgumentError(f"alpha0 must be in (0, 1], got {self.alpha0!r}")
        if self.suite_weight is not None and not (math.isfinite(self.suite_weight) and self.suite_weight > 0):
            raise InvalidArgumentError(f"the suite's test count must be > 0, got {self.suite_weight!r}")

    def allocate(self, tests: List[Tuple[str, float, int]]) -> None:
        """Fixes the shares: (name, weight > 0, checks >= 1) for every statistical test of the run."""
        total = 0.0
        for name, w, k in tests:
            if not (w > 0 and math.isfinite(w)):
                raise InvalidArgumentError(f"{name}: the weight of a statistical test must be > 0, got {w!r}")
            if not (isinstance(k, int) and k >= 1):
                raise InvalidArgumentError(f"{name}: checks must be an integer >= 1, got {k!r}")
            total += w
        if self.suite_weight is not None:
            if self.suite_weight < total * (1 - 1e-12):
                raise InvalidArgumentError(
                    f"the suite's statistical tests were given as {self.suite_weight:g}, but {total:g} (their "
                    "weights' sum) are collected: the shares would spend more than the budget")
            total = self.suite_weight
        self.total_weight = total
        self.shares = {name: self.alpha * w / total for name, w, _ in tests}
        self.budgeted = len(self.shares)
        self.checks = {name: k for name, _, k in tests}

    def scope(self, name: str) -> "Scope":
        if name not in self.shares:
            raise BudgetError(f"{name} is not one of the suite's statistical tests: mark it "
                              "@pytest.mark.mcstat (or use the mcstat fixture) so that the budget counts it")
        return Scope(name=name, alpha=self.shares[name], checks=self.checks[name], master_seed=self.master_seed,
                     escalate=self.escalate, alpha0=self.alpha0, suite=self)

    # ---- what the run spent -------------------------------------------------
    @property
    def spent(self) -> float:
        return sum(r.alpha for r in self.records if r.spends_budget)

    def summary(self) -> str:
        rs = self.records
        tests = len({r.test for r in rs})
        failed = [r for r in rs if r.decision != "pass"]
        esc = [r for r in rs if r.stages > 1]
        # tests that failed without a failing check: an error (bad data, a
        # check beyond the declared count) before any decision
        errored = sorted(t for t in self.failed_tests if t not in {r.test for r in failed})
        lines = [
            f"mcstat: {len(rs)} statistical check(s) in {tests} test(s); alpha spent {self.spent:.3g} of the "
            f"suite's {self.alpha:.3g} ({self.budgeted} test(s) budgeted"
            + (f" of the suite's {self.total_weight:g}" if self.suite_weight is not None else "")
            + f"), master seed {self.master_seed}",
            f"  samples: {sum(r.samples for r in rs)}; escalated {len(esc)} "
            f"({sum(1 for r in esc if r.decision == 'reject')} of them rejected at stage 2); "
            f"failed {len(failed)} check(s)" + (f", and {len(errored)} test(s) without a failing budgeted check"
                                                if errored else ""),
        ]
        for r in failed:
            lines.append(f"  FAILED {r.test} check {r.index} ({r.kind}): {r.decision}, alpha {r.alpha:.3g}, "
                         f"seed {r.seed}")
        for t in errored:
            lines.append(f"  FAILED {t} (in {self.failed_tests[t]}): an error before a decision, or an mcstat "
                         "assertion outside the budget")
        hides = [r for r in rs if r.decision == "pass" and r.could_hide]
        if hides:
            lines.append("  what each pass could have missed (the smallest error each check detects):")
            for r in hides:
                lines.append(f"    {r.test} [{r.index}] {r.kind}: {r.could_hide}")
        return "\n".join(lines)


@dataclass
class Scope:
    """The running test's budget: its share, its checks, its seeds."""

    name: str
    alpha: float
    checks: int = 1
    master_seed: int = 0
    escalate: float = 4.0
    alpha0: float = 0.05
    suite: Optional[Suite] = None
    used: int = 0
    records: List[CheckRecord] = field(default_factory=list)

    def next_check(self, kind: str) -> Tuple[int, float, int]:
        """(index, alpha, seed) of the test's next check; BudgetError past the declared count."""
        if self.used >= self.checks:
            raise BudgetError(
                f"{self.name}: check {self.used + 1} ({kind}) is one more than the {self.checks} the test declared; "
                f"declare them with @pytest.mark.mcstat(checks={self.used + 1}) (or scope(..., checks=)) so the "
                "suite's budget is split before the test runs")
        j = self.used
        self.used += 1
        return j, self.alpha / self.checks, check_seed(self.master_seed, self.name, j)

    def data_seed(self, label: str = "") -> int:
        """A seed for the test's own data, derived from the suite's master
        seed and the test's name (`_seeds.data_seed`): a failure's reproduce
        line (the same master seed) draws the same data again."""
        return data_seed(self.master_seed, self.name, label)

    def rng(self, label: str = "") -> Any:
        """``numpy.random.default_rng(self.data_seed(label))``."""
        import numpy as np

        return np.random.default_rng(self.data_seed(label))

    def record(self, r: CheckRecord) -> None:
        self.records.append(r)
        if self.suite is not None:
            self.suite.records.append(r)


_current: contextvars.ContextVar[Optional[Scope]] = contextvars.ContextVar("mcstat_testing_scope", default=None)


# the pytest plugin's suite, while a run has one: an assertion outside any
# test's scope then says the test is unmarked, not that no budget exists
_active_suite: Optional[Suite] = None


def active_suite() -> Optional[Suite]:
    return _active_suite


def _activate(s: Optional[Suite]) -> None:
    global _active_suite
    _active_suite = s


def current_scope() -> Optional[Scope]:
    """The Scope of the running test, or None outside any budget."""
    return _current.get()


@contextlib.contextmanager
def scope(name: str, alpha: float, *, checks: int = 1, master_seed: int = 0, escalate: float = 4.0,
          alpha0: float = 0.05) -> Iterator[Scope]:
    """A budget by hand (unittest, scripts): the assertions inside spend
    ``alpha`` over ``checks`` checks, with seeds derived from ``name`` and
    ``master_seed`` as under the pytest plugin."""
    Suite(alpha=alpha, master_seed=master_seed, escalate=escalate, alpha0=alpha0)  # validates
    if not (isinstance(checks, int) and checks >= 1):
        raise InvalidArgumentError(f"checks must be an integer >= 1, got {checks!r}")
    s = Scope(name=name, alpha=alpha, checks=checks, master_seed=master_seed, escalate=escalate, alpha0=alpha0)
    token = _current.set(s)
    try:
        yield s
    finally:
        _current.reset(token)


@contextlib.contextmanager
def _enter(s: Scope) -> Iterator[Scope]:
    token = _current.set(s)
    try:
        yield s
    finally:
        _current.reset(token)
