# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat's pytest plugin: one error budget for the suite's statistical tests.

Installed with the package (entry point ``pytest11``) and inert until a
run opts in, by ``--mcstat-alpha A`` or the ini option ``mcstat_alpha``.
Then:

- the statistical tests are those marked ``@pytest.mark.mcstat`` (or
  using the ``mcstat`` fixture), counted over the whole collection
  (before ``-k``/``-m`` deselection, or ``--mcstat-tests N`` for the
  whole suite when only part of it is collected), and each gets its share
  of A before any runs (``mcstat.testing._budget``): the run fails on a
  correct suite with probability at most A, and a test run alone decides
  at its share of the full run.  ``@pytest.mark.mcstat(weight=2, checks=3)``
  gives a test twice the share, split over three checks;
- each check's seed is a function of ``--mcstat-seed`` (default 0), the
  test's node id and the check's index, printed on failure;
- a suspicious check escalates (``--mcstat-escalate F``, default 4: F
  times the samples; 0: off) instead of being rerun;
- the terminal summary says what ran, the alpha and samples spent, the
  escalations and failures, and what each pass could have missed (``-v``);
  ``--mcstat-artifacts DIR`` writes each failure's report and pictures
  there, ``--mcstat-report FILE`` every check's record as JSON.  Each
  test's share is in its report (``user_properties``: JUnit XML shows it).

Without the option the marker is still known (no warnings) and the
assertions need ``alpha=``.  Under pytest-xdist each worker computes the
same shares from the same collection, and the checks' records travel to
the controller with the tests' reports: its summary and report cover the
whole run.
"""
from __future__ import annotations

import dataclasses
import json
from typing import Any, Generator, List, Optional, Tuple

import pytest

from ._budget import CheckRecord, Scope, Suite, _activate, _enter, active_suite

_KEY = pytest.StashKey[Suite]()
_SCOPE = pytest.StashKey[Scope]()


def pytest_addoption(parser: Any) -> None:
    g = parser.getgroup("mcstat", "mcstat: one error budget for the suite's statistical tests")
    g.addoption("--mcstat-alpha", type=float, default=None,
                help="the run's false-failure budget, split over the statistical tests (turns the plugin on)")
    g.addoption("--mcstat-seed", type=int, default=None, help="master seed of every check (default 0)")
    g.addoption("--mcstat-escalate", type=float, default=None,
                help="stage-2 size factor of an inconclusive check (default 4; 0: no escalation)")
    g.addoption("--mcstat-alpha0", type=float, default=None,
                help="stage-1 p-values up to this escalate (default 0.05)")
    g.addoption("--mcstat-artifacts", default=None, help="folder for the failures' reports and pictures")
    g.addoption("--mcstat-report", default=None,
                help="write every check's record (test, alpha, seed, samples, p-values, decision) as JSON here")
    g.addoption("--mcstat-tests", type=float, default=None,
                help="the whole suite's statistical tests (the sum of their weights): the shares' divisor, so that "
                     "a run of some of them (-k, -m, a node id) decides each at its suite share; default: those "
                     "collected before -k/-m deselection")
    parser.addini("mcstat_alpha", "the run's false-failure budget (turns the plugin on)", default=None)
    parser.addini("mcstat_seed", "master seed", default=None)
    parser.addini("mcstat_escalate", "stage-2 size factor (0: off)", default=None)
    parser.addini("mcstat_alpha0", "the escalation band's top", default=None)
    parser.addini("mcstat_artifacts", "folder for failure artifacts", default=None)
    parser.addini("mcstat_tests", "the whole suite's statistical tests (the sum of their weights)", default=None)


def _opt(config: Any, name: str) -> Optional[str]:
    v = config.getoption("--mcstat-" + name.replace("_", "-"))
    if v is None:
        v = config.getini("mcstat_" + name)
    return None if v in (None, "") else v


def _num(config: Any, name: str, default: float) -> float:
    # 0 is a value (--mcstat-escalate 0: no escalation), not "unset"
    v = _opt(config, name)
    return default if v is None else float(v)


def pytest_configure(config: Any) -> None:
    config.addinivalue_line("markers", "mcstat(weight=1, checks=1): a statistical test, counted in mcstat's "
                            "suite budget (weight: its share relative to the others; checks: how many statistical "
                            "assertions it makes)")
    alpha = _opt(config, "alpha")
    if alpha is None:
        return
    try:
        tests = _opt(config, "tests")
        suite = Suite(alpha=float(alpha), master_seed=int(_num(config, "seed", 0)),
                      escalate=_num(config, "escalate", 4.0), alpha0=_num(config, "alpha0", 0.05),
                      artifacts=_opt(config, "artifacts"), suite_weight=None if tests is None else float(tests),
                      rootdir=str(config.rootpath))
    except (ValueError, TypeError) as e:
        raise pytest.UsageError(f"mcstat: {e}") from None
    config.stash[_KEY] = suite
    _activate(suite)


def pytest_unconfigure(config: Any) -> None:
    if config.stash.get(_KEY, None) is not None:
        _activate(None)


def _statistical(item: Any) -> Optional[Tuple[float, int]]:
    m = item.get_closest_marker("mcstat")
    uses = "mcstat" in getattr(item, "fixturenames", ())
    if m is None and not uses:
        return None
    kw = m.kwargs if m is not None else {}
    unknown = set(kw) - {"weight", "checks"}
    if unknown or (m is not None and m.args):
        raise pytest.UsageError(f"{item.nodeid}: @pytest.mark.mcstat takes weight= and checks= only, got "
                                f"{sorted(unknown) or list(m.args)}")
    return float(kw.get("weight", 1.0)), int(kw.get("checks", 1))


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(session: Any, config: Any, items: List[Any]) -> None:
    # before -k/-m deselect: the shares are the whole collected suite's, so
    # that a selection decides each test at the share the full run gives it
    suite = config.stash.get(_KEY, None)
    if suite is None:
        return
    tests: List[Tuple[str, float, int]] = []
    for item in items:
        s = _statistical(item)
        if s is not None:
            tests.append((item.nodeid, s[0], s[1]))
    if tests:
        try:
            suite.allocate(tests)
        except ValueError as e:
            raise pytest.UsageError(f"mcstat: {e}") from None


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item: Any) -> None:
    # before the fixtures, so that the mcstat fixture can hand the scope over
    suite = item.config.stash.get(_KEY, None)
    if suite is None or item.nodeid not in suite.shares:
        return
    sc = suite.scope(item.nodeid)
    item.stash[_SCOPE] = sc
    item.user_properties.append(("mcstat_alpha", sc.alpha))


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_call(item: Any) -> Generator[None, Any, None]:
    sc = item.stash.get(_SCOPE, None)
    if sc is None:
        yield
        return
    with _enter(sc):
        yield


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: Any, call: Any) -> Generator[None, Any, None]:
    outcome = yield
    rep = outcome.get_result()
    if call.when == "call" and call.excinfo is not None and _is_mcstat_failure(call.excinfo.value):
        # counted by the summary even when no check decided (an error before
        # one, or an assertion outside any budgeted test)
        rep.user_properties.append((_FAILURE, call.excinfo.typename))
    sc = item.stash.get(_SCOPE, None)
    if sc is None or call.when != "call":
        return
    lines = [f"share of the suite's alpha: {sc.alpha:.3g} over {sc.checks} check(s), {sc.used} ran"]
    for r in sc.records:
        lines.append(f"check {r.index} {r.kind}: {r.decision}, p {', '.join(f'{p:.3g}' for p in r.p_values)}, "
                     f"seed {r.seed}, samples {r.samples}" + (f"; could miss {r.could_hide}" if r.could_hide else ""))
    rep.sections.append(("mcstat", "\n".join(lines)))
    # the records travel with the report: under pytest-xdist the controller
    # has run no check and learns them here (pytest_runtest_logreport)
    rep.user_properties.append((_RECORDS, [dataclasses.asdict(r) for r in sc.records]))
    if sc.suite is not None:
        rep.user_properties.append((_BUDGET, [sc.suite.budgeted, sc.suite.total_weight]))


_RECORDS = "mcstat_records"
_BUDGET = "mcstat_budget"
_FAILURE = "mcstat_failure"


def _is_mcstat_failure(e: BaseException) -> bool:
    from .._errors import McstatError
    from ._assertions import StatisticalAssertionError
    return isinstance(e, (StatisticalAssertionError, McstatError))


def pytest_runtest_logreport(report: Any) -> None:
    suite = active_suite()
    if suite is None:
        return
    records = next((v for k, v in getattr(report, "user_properties", ()) if k == _RECORDS), None)
    if report.when == "call" and records is not None and getattr(report, "node", None) is not None:
        # a pytest-xdist worker's report on the controller (its own checks are
        # recorded as they run)
        for d in records:
            suite.records.append(CheckRecord(**{k: tuple(v) if k == "p_values" else v for k, v in d.items()}))
        budget = next((v for k, v in report.user_properties if k == _BUDGET), None)
        if budget is not None and not suite.shares:
            suite.budgeted, suite.total_weight = int(budget[0]), float(budget[1])
    props = dict(getattr(report, "user_properties", ()))
    if report.failed and (records is not None or report.nodeid in suite.shares or _FAILURE in props):
        # a statistical test that failed, by a check or by an error before
        # one, or a test whose mcstat assertion failed outside the budget
        suite.failed_tests[report.nodeid] = report.when


@pytest.fixture
def mcstat(request: Any) -> Optional[Scope]:
    """The running test's budget (its Scope: ``alpha``, ``checks``, seeds),
    or None when the plugin is off.  Using it makes the test statistical."""
    sc: Optional[Scope] = request.node.stash.get(_SCOPE, None)
    return sc


def pytest_terminal_summary(terminalreporter: Any, exitstatus: int, config: Any) -> None:
    suite = config.stash.get(_KEY, None)
    if suite is None:
        return
    path = config.getoption("--mcstat-report")
    if path:
        with open(path, "w", encoding="utf-8") as f:
            json.dump({"alpha": suite.alpha, "master_seed": suite.master_seed, "escalate": suite.escalate,
                       "alpha0": suite.alpha0, "tests": suite.budgeted, "suite_weight": suite.total_weight,
                       "failed_tests": sorted(suite.failed_tests),
                       "records": [dataclasses.asdict(r) for r in suite.records]}, f, indent=1)
    text = suite.summary()
    if config.getoption("verbose") < 1:  # the per-pass lines only when asked
        text = text.split("\n  what each pass could have missed")[0]
    terminalreporter.write_sep("-", "mcstat")
    terminalreporter.write_line(text)
