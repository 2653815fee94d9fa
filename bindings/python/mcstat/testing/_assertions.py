# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The assertions: a statistical check that raises on rejection.

Each spends the running test's share of the suite's budget (`_budget`), or
the ``alpha`` given outside any budget.  Checks that draw their own
samples (a BSDF's, a sampler's: callables) escalate instead of being
rerun: stage 1 decides at alpha1 = alpha / 2 or passes above alpha0, and an
inconclusive p-value in between continues on ``escalate`` times as many
fresh samples, the two p-values then combined (`mcstat.Escalation`), so
that the check's level stays alpha.  Checks of data given as arrays
cannot draw more and run once at alpha.

A failure raises `StatisticalAssertionError` (an AssertionError) whose
message holds the deciding stage's report, the alpha spent, the stages'
p-values, the seed and how to reproduce it; a pass records what it could
have missed (the smallest error of each kind the check detects).  A check
that could not answer (the report's verdict "inconclusive": a route it
needed failed an assumption, heavy tails or too few samples) fails as
"inconclusive", naming the routes and why, unless the assertion is given
``allow_inconclusive=True``: no answer is not a pass.  Every route without
an answer is listed with what the pass could miss.
"""
from __future__ import annotations

import math
import shlex
import sys
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Optional, Tuple

import numpy as np

from .. import _core
from .._errors import InvalidArgumentError
from . import _artifacts
from ._budget import BudgetError, CheckRecord, Scope, active_suite, current_scope
from ._seeds import splitmix64, stage2_seed

__all__ = [
    "StatisticalAssertionError",
    "assert_bsdf_consistent",
    "assert_emitter_consistent",
    "assert_warp_consistent",
    "assert_unbiased",
    "assert_same_distribution",
    "assert_images_equivalent",
]


class StatisticalAssertionError(AssertionError):
    """A statistical check rejected (or could not answer).  ``record`` is its `CheckRecord`."""

    def __init__(self, message: str, record: CheckRecord) -> None:
        super().__init__(message)
        self.record = record


@dataclass
class _Stage:
    p: float
    text: str
    samples: int
    could_hide: str = ""
    inconclusive: str = ""  # why there is no answer ("" when there is one)
    pictures: Dict[str, bytes] = field(default_factory=dict)
    payload: Any = None
    brief: str = ""  # the failure message's form of `text` ("" : text itself); text goes to the artifacts


@dataclass
class _Plan:
    scope: Optional[Scope]
    index: int
    alpha: float
    seed: int
    escalate: float
    alpha0: Optional[float]


def _plan(kind: str, alpha: Optional[float], seed: Optional[int], escalate: Optional[float],
          alpha0: Optional[float]) -> _Plan:
    sc = current_scope()
    if sc is None:
        if alpha is None and active_suite() is not None:
            raise BudgetError(f"{kind}: this test is not one of the suite's statistical tests: mark it "
                              "@pytest.mark.mcstat (or use the mcstat fixture) so that the budget counts it")
        if alpha is None:
            raise BudgetError(f"{kind}: no suite budget is active; pass alpha= (or run under pytest with "
                              "--mcstat-alpha, or inside mcstat.testing.scope())")
        j, a, s = 0, alpha, 0 if seed is None else seed
        esc, a0 = (4.0 if escalate is None else escalate), alpha0
    else:
        j, a, s = sc.next_check(kind)
        if alpha is not None:
            if not alpha <= a:
                raise BudgetError(f"{kind}: alpha {alpha!r} exceeds this check's share {a:.3g} of the suite's budget")
            a = alpha
        if seed is not None:
            s = seed
        esc = sc.escalate if escalate is None else escalate
        a0 = sc.alpha0 if alpha0 is None else alpha0
    if not (isinstance(a, (int, float)) and 0.0 < a < 1.0):
        raise InvalidArgumentError(f"alpha must be in (0, 1), got {a!r}")
    if not (isinstance(s, int) and 0 <= s < 2**64):
        raise InvalidArgumentError(f"seed must be an integer in [0, 2**64), got {s!r}")
    if not (math.isfinite(esc) and (esc == 0 or esc >= 1)):
        raise InvalidArgumentError(f"escalate must be 0 (off) or a factor >= 1, got {esc!r}")
    return _Plan(sc, j, float(a), int(s), float(esc), a0)


def _design(alpha: float, alpha0: Optional[float]) -> "_core.Escalation":
    # alpha0 below what the design allows (large alphas outside a suite) is
    # raised to the smallest band that spends the rest: 2 e alpha1
    lo = min(1.0, 2.0 * math.e * 0.5 * alpha)
    return _core.Escalation(alpha, 0.5, max(0.05 if alpha0 is None else alpha0, lo))


def _g(v: float) -> str:
    return f"{v:.3g}"


def _decide(kind: str, plan: _Plan, n: int, stage: Callable[[int, int, float], _Stage], escalatable: bool,
            describe: str) -> _Stage:
    """Runs the stages, records the check, raises on a rejection."""
    __tracebackhide__ = True  # a failure's traceback ends at the user's assertion
    lines = []
    if escalatable and plan.escalate > 0:
        d = _design(plan.alpha, plan.alpha0)
        s1 = stage(n, plan.seed, d.alpha1)
        stages = [s1]
        if s1.inconclusive:
            decision = "inconclusive"
        else:
            decision = d.decide(s1.p)
        lines.append(f"  stage 1: n {n}, seed {plan.seed}: p {_g(s1.p)} "
                     f"(rejects at <= {_g(d.alpha1)}, passes above {_g(d.alpha0)})")
        last = s1
        if decision == "continue":
            n2 = max(int(round(plan.escalate * n)), n)
            seed2 = stage2_seed(plan.seed)
            # stage 2 at c / p1, so that its own report's verdict is the combined one
            s2 = stage(n2, seed2, min(d.c / s1.p, 0.5))
            stages.append(s2)
            last = s2
            if s2.inconclusive:
                decision = "inconclusive"
            else:
                decision = d.decide(s1.p, s2.p)
            lines.append(f"  stage 2 (escalated): n {n2}, seed {seed2}: p {_g(s2.p)}; p1 p2 = {_g(s1.p * s2.p)} "
                         f"{'<=' if decision == 'reject' else '>'} c = {_g(d.c)}")
    else:
        s1 = stage(n, plan.seed, plan.alpha)
        stages = [s1]
        last = s1
        decision = "inconclusive" if s1.inconclusive else ("reject" if s1.p <= plan.alpha else "pass")
        lines.append(f"  one stage: n {n}, seed {plan.seed}: p {_g(s1.p)} (rejects at <= {_g(plan.alpha)})")
    name = plan.scope.name if plan.scope else "(no suite)"
    rec = CheckRecord(test=name, index=plan.index, kind=kind, alpha=plan.alpha, seed=plan.seed,
                      samples=sum(s.samples for s in stages), decision=decision, stages=len(stages),
                      p_values=tuple(s.p for s in stages), could_hide=last.could_hide if decision == "pass" else "")
    if plan.scope is not None:
        plan.scope.record(rec)
    if decision == "pass":
        return last
    share = "this check's share of the suite's budget" if plan.scope else "given"
    verdict = "rejected" if decision == "reject" else (
        "inconclusive" if last.brief else f"inconclusive ({last.inconclusive})")  # a brief report says why
    head = f"{describe}: {verdict} at alpha {_g(plan.alpha)} ({share}; each stage's level below)"
    if plan.scope is not None and plan.scope.suite is not None:
        su = plan.scope.suite
        where = f"cd {shlex.quote(su.rootdir)} && " if su.rootdir else ""
        repro = (f"reproduce: {where}{shlex.quote(sys.executable)} -m pytest {shlex.quote(name)} "
                 f"--mcstat-alpha {su.alpha:g} --mcstat-seed {su.master_seed} --mcstat-escalate {su.escalate:g} "
                 f"--mcstat-alpha0 {su.alpha0:g} --mcstat-tests {su.total_weight:g} "
                 "(the same seeds and the same share)")
    else:
        repro = f"reproduce: the same call with seed={plan.seed}"
    full = "\n".join([head] + lines + [last.text, repro])
    rec.message = full
    root = plan.scope.suite.artifacts if plan.scope is not None and plan.scope.suite is not None else None
    written = _artifacts.write(root, name, plan.index, kind, full, last.pictures)
    if not last.brief:
        raise StatisticalAssertionError(full, rec)
    # the message keeps what failed; the whole report (every route, what
    # each could detect) goes to the artifacts and the record
    more = (f"the whole report: {written[0]}" if written else
            "the whole report: the exception's record.message (or --mcstat-artifacts DIR)")
    raise StatisticalAssertionError("\n".join([head] + lines + [last.brief, more, repro]), rec)


# ---- renderer checks ---------------------------------------------------------------
def _check_stage(run: Callable[..., Any], allow_inconclusive: bool) -> Callable[[int, int, float], _Stage]:
    def stage(n: int, seed: int, a: float) -> _Stage:
        rep = run(n=n, seed=seed, alpha=a)
        invalid = [r.name for r in rep.routes if r.state == "invalid"]
        hide = ", ".join(f"{r.name} {r.detectable:.3g}" for r in rep.routes
                         if r.state == "ran" and r.detectable is not None)
        if invalid:
            hide += ("; " if hide else "") + "no answer from " + ", ".join(invalid)
        # the library's verdict: "inconclusive" when a route the check needed
        # could not answer; no answer is not a pass unless the test allows it
        why = ""
        if rep.verdict == "inconclusive" and not allow_inconclusive:
            why = "; ".join(f"{name} could not answer: {rep.route(name).why}" for name in rep.unanswered)
        text = str(rep)
        return _Stage(p=float(rep.pvalue), text=text, samples=int(rep.n + rep.n_pilot + rep.n_eval),
                      could_hide=("detectable: " + hide) if hide else "",
                      inconclusive=why,
                      payload=rep, brief=_brief_report(text))
    return stage


def _brief_report(text: str) -> str:
    """A check report's lines that say what failed: its title, what was
    checked, the routes that rejected or could not answer, and the decision
    with its reasons (the library's own lines, none composed here)."""
    lines = [x for x in text.splitlines() if x.strip()]
    out, in_routes, in_decision = [], False, False
    for i, x in enumerate(lines):
        if i < 2:
            out.append(x.strip())  # the title and what was checked
        elif x == "routes:":
            in_routes = True
        elif x.startswith("smallest departure"):
            in_routes = False
        elif x.startswith("decision at alpha"):
            in_decision = True
            out.append(x)
        elif in_decision or (in_routes and (" FAIL " in x or "no answer" in x)):
            out.append(x)
    return "\n".join(out)


def assert_bsdf_consistent(sample: Callable[..., Any], eval: Callable[..., Any], pdf: Callable[..., Any], wi: Any,
                           *, n: int = 100_000, alpha: Optional[float] = None, seed: Optional[int] = None,
                           escalate: Optional[float] = None, alpha0: Optional[float] = None,
                           allow_inconclusive: bool = False, **check_kwargs: Any) -> Any:
    """``mcstat.check_bsdf(sample, eval, pdf, wi, **check_kwargs)`` as an
    assertion: its sample(), pdf(), eval() and weight agree.  Returns the
    deciding stage's CheckReport on a pass.  ``alpha``/``seed`` default to
    the suite's (required outside one); ``escalate`` the stage-2 factor (0:
    off), ``alpha0`` the escalation band's top.  A report whose verdict is
    "inconclusive" (a route the check needed could not answer) fails with
    the routes and the reasons, unless ``allow_inconclusive``."""
    __tracebackhide__ = True
    plan = _plan("bsdf", alpha, seed, escalate, alpha0)
    w = tuple(float(v) for v in np.asarray(wi, dtype=np.float64).ravel())
    st = _check_stage(lambda **k: _core.check_bsdf(sample, eval, pdf, wi, **k, **check_kwargs), allow_inconclusive)
    return _decide("bsdf", plan, n, st, True, f"check_bsdf at wi {w}").payload


def assert_emitter_consistent(sample: Callable[..., Any], eval: Callable[..., Any], pdf: Callable[..., Any], *,
                              n: int = 100_000, alpha: Optional[float] = None, seed: Optional[int] = None,
                              escalate: Optional[float] = None, alpha0: Optional[float] = None,
                              allow_inconclusive: bool = False, **check_kwargs: Any) -> Any:
    """``mcstat.check_emitter`` as an assertion (see `assert_bsdf_consistent`)."""
    __tracebackhide__ = True
    plan = _plan("emitter", alpha, seed, escalate, alpha0)
    st = _check_stage(lambda **k: _core.check_emitter(sample, eval, pdf, **k, **check_kwargs), allow_inconclusive)
    return _decide("emitter", plan, n, st, True, "check_emitter").payload


def assert_warp_consistent(sample: Callable[..., Any], pdf: Callable[..., Any], *, n: int = 100_000,
                           alpha: Optional[float] = None, seed: Optional[int] = None,
                           escalate: Optional[float] = None, alpha0: Optional[float] = None,
                           allow_inconclusive: bool = False, **check_kwargs: Any) -> Any:
    """``mcstat.check_warp`` as an assertion (see `assert_bsdf_consistent`)."""
    __tracebackhide__ = True
    plan = _plan("warp", alpha, seed, escalate, alpha0)
    st = _check_stage(lambda **k: _core.check_warp(sample, pdf, **k, **check_kwargs), allow_inconclusive)
    return _decide("warp", plan, n, st, True, "check_warp").payload


def assert_phase_consistent(sample: Callable[..., Any], eval: Callable[..., Any], pdf: Callable[..., Any], wi: Any,
                            *, n: int = 100_000, alpha: Optional[float] = None, seed: Optional[int] = None,
                            escalate: Optional[float] = None, alpha0: Optional[float] = None,
                            allow_inconclusive: bool = False, **check_kwargs: Any) -> Any:
    """``mcstat.check_phase`` as an assertion: a phase function's sample(),
    pdf(), eval() and weight agree and it is normalised (its energy route
    is two-sided).  See `assert_bsdf_consistent`."""
    __tracebackhide__ = True
    plan = _plan("phase", alpha, seed, escalate, alpha0)
    w = tuple(float(v) for v in np.asarray(wi, dtype=np.float64).ravel())
    st = _check_stage(lambda **k: _core.check_phase(sample, eval, pdf, wi, **k, **check_kwargs), allow_inconclusive)
    return _decide("phase", plan, n, st, True, f"check_phase at wi {w}").payload


def assert_medium_consistent(sample: Callable[..., Any], eval: Callable[..., Any], pdf: Callable[..., Any], *,
                             sigma_ref: float, n: int = 100_000, alpha: Optional[float] = None,
                             seed: Optional[int] = None, escalate: Optional[float] = None,
                             alpha0: Optional[float] = None, allow_inconclusive: bool = False,
                             **check_kwargs: Any) -> Any:
    """``mcstat.check_medium`` as an assertion: a medium's distance
    sampling, its density and its weights agree (``escape_transmittance=`` also
    checks the escapes' weights).  See `assert_bsdf_consistent`."""
    __tracebackhide__ = True
    plan = _plan("medium", alpha, seed, escalate, alpha0)
    st = _check_stage(lambda **k: _core.check_medium(sample, eval, pdf, sigma_ref=sigma_ref, **k, **check_kwargs),
                      allow_inconclusive)
    return _decide("medium", plan, n, st, True, "check_medium").payload


# ---- estimators and samplers ---------------------------------------------------------
Draw = Callable[[int, int], Any]


def _values(draw: Any, n: int, seed: int, name: str) -> np.ndarray:
    x = draw(n, seed) if callable(draw) else draw
    a = np.asarray(x, dtype=np.float64).ravel()
    if callable(draw) and a.size != n:
        raise InvalidArgumentError(f"{name}(n, seed) returned {a.size} values; {n} were asked for")
    return a


def assert_unbiased(draw: Any, expected: float, *, n: int = 10_000, alpha: Optional[float] = None,
                    seed: Optional[int] = None, escalate: Optional[float] = None,
                    alpha0: Optional[float] = None) -> Any:
    """The estimator's mean is ``expected``: the two-sided one-sample t test.

    ``draw``: ``draw(n, seed) -> n`` independent estimates (escalates), or
    the estimates themselves (one stage).  The t test assumes a finite
    variance and enough estimates for the mean to be near normal (batch
    means, ``mcstat.batch_means``, help with skewed estimators).  Returns
    the deciding TestResult; a pass records the interval of the bias it
    leaves open, absolute and relative to ``expected``.

    An exact estimator (every estimate the same value) has no spread to
    test: it passes when that value is ``expected`` up to the resolution
    of its arithmetic (64 units in the last place: of float32 when the
    estimates come as a float32 array, else of float64) and fails
    otherwise; the TestResult is then None."""
    __tracebackhide__ = True
    if not (isinstance(expected, (int, float)) and math.isfinite(expected)):
        raise InvalidArgumentError(f"expected must be a finite number, got {expected!r}")
    plan = _plan("unbiased", alpha, seed, escalate, alpha0)

    def stage(k: int, s: int, a: float) -> _Stage:
        raw = draw(k, s) if callable(draw) else draw
        x = np.asarray(raw, dtype=np.float64).ravel()
        if callable(draw) and x.size != k:
            raise InvalidArgumentError(f"draw(n, seed) returned {x.size} values; {k} were asked for")
        if x.size >= 2 and np.all(np.isfinite(x)) and np.all(x == x[0]):
            single = getattr(np.asarray(raw), "dtype", None) == np.float32
            res = _core.RESOLUTION_FLOAT32 if single else _core.RESOLUTION_FLOAT64
            off = abs(float(x[0]) - expected)
            exact = off <= res * max(abs(expected), abs(float(x[0])))
            text = (f"every one of the {x.size} estimates is {float(x[0])!r}: an exact estimator, "
                    f"{'equal to' if exact else 'not'} {expected!r} within {res:.3g} relative "
                    f"({'float32' if single else 'float64'} arithmetic)")
            return _Stage(p=1.0 if exact else 0.0, text=text, samples=int(x.size),
                          could_hide="nothing beyond rounding: every estimate is the same value" if exact else "")
        r = _core.t_test(x, mu=float(expected), alpha=a)
        lo, hi = r.conf_int
        rel = (f"; relative to {expected:g}: [{(lo - expected) / abs(expected):+.3g}, "
               f"{(hi - expected) / abs(expected):+.3g}]") if expected != 0 else ""
        return _Stage(p=float(r.pvalue), text=str(r), samples=int(x.size),
                      could_hide=f"a bias in [{lo - expected:.3g}, {hi - expected:.3g}] (the {1 - a:.6g} interval"
                                 f"{rel})",
                      payload=r)

    return _decide("unbiased", plan, n, stage, callable(draw), f"the mean is {expected!r}").payload


def assert_same_distribution(draw_a: Any, draw_b: Any, *, n: int = 10_000, alpha: Optional[float] = None,
                             seed: Optional[int] = None, escalate: Optional[float] = None,
                             alpha0: Optional[float] = None, **ks_kwargs: Any) -> Any:
    """Two samplers draw the same distribution: the two-sample
    Kolmogorov-Smirnov test (``mcstat.ks_test``, unweighted unless
    ``weight=`` says otherwise: its p-values are exact or asymptotic, where
    Canner's are simulated and cannot reach a suite's small shares).  ``draw_a``/``draw_b``: ``draw(n, seed) ->
    n`` values (independent seeds for the two; escalates) or the values."""
    __tracebackhide__ = True
    plan = _plan("same_distribution", alpha, seed, escalate, alpha0)
    both = callable(draw_a) and callable(draw_b)
    # the plain statistic by default: its exact and asymptotic p-values reach
    # a suite's tiny shares, where Canner's are simulated (floor 1/(n_sim + 1))
    kw = dict(ks_kwargs)
    kw.setdefault("weight", "none")

    def stage(k: int, s: int, a: float) -> _Stage:
        x = _values(draw_a, k, s, "draw_a")
        y = _values(draw_b, k, splitmix64(s ^ 0xB), "draw_b")
        r = _core.ks_test(x, y, alpha=a, **kw)
        if r.pvalue_method == "simulate" and 1.0 / (r.n_sim + 1) > a:
            why = (f"a simulated p-value cannot go below {1.0 / (r.n_sim + 1):.3g} with n_sim {r.n_sim}, and this "
                   f"stage rejects at {a:.3g}: use weight='none' (exact and asymptotic p-values) or more n_sim")
            return _Stage(p=float(r.pvalue), text=str(r), samples=int(x.size + y.size), inconclusive=why)
        # the plain K-S distance the asymptotic test at level a would detect half the time
        m1, m2 = x.size, y.size
        dcrit = math.sqrt(-math.log(a / 2.0) / 2.0 * (m1 + m2) / (m1 * m2))
        return _Stage(p=float(r.pvalue), text=str(r), samples=int(m1 + m2),
                      could_hide=f"a K-S distance (largest cdf difference) below about {dcrit:.3g}",
                      pictures={"histogram": _artifacts.histogram_png(x, y)}, payload=r)

    return _decide("same_distribution", plan, n, stage, both, "both samplers draw the same distribution").payload


# ---- images ---------------------------------------------------------------------
def assert_images_equivalent(reference: Any, candidate: Any, *, margin: float, atol: float = 0.0, block: int = 32,
                             alpha: float = 0.05, seed_axis: Optional[int] = None, channels: str = "all",
                             nan_policy: str = "raise") -> Any:
    """The candidate renders the reference up to ``margin`` (relative) +
    ``atol`` in every block (``mcstat.image.equivalence``: TOST per block,
    an intersection-union verdict).  Both sides per-seed stacks ``(seeds,
    H, W[, C])``; ``nan_policy`` as equivalence's.  Returns the ImageEquivalence.

    Here alpha is the other error: the probability of passing images that
    differ by more than the margin somewhere.  So this check spends nothing
    of the suite's false-failure budget, and a pass's worth is its
    ``margin_shown``: a correct candidate fails when the renders are too
    few to show the margin (more seeds or larger blocks)."""
    __tracebackhide__ = True
    from ..image import equivalence

    sc = current_scope()
    e = equivalence(reference, candidate, margin=margin, atol=atol, block=block, alpha=alpha, seed_axis=seed_axis,
                    channels=channels, nan_policy=nan_policy)
    name = sc.name if sc else "(no suite)"
    index = len(sc.records) if sc else 0
    p = 1.0 if e.blocks_untestable else float(np.max(e.block_pvalue))
    rec = CheckRecord(test=name, index=index, kind="images_equivalent", alpha=float(alpha), seed=0,
                      samples=int(sum(e.seeds) * e.shape[0] * e.shape[1] * e.shape[2]),
                      decision="pass" if e.equivalent else "reject", stages=1, p_values=(p,),
                      could_hide=f"differences inside a margin of about {e.margin_shown:.3g}",
                      spends_budget=False)
    if sc is not None:
        sc.record(rec)
    if e.equivalent:
        return e
    msg = (f"the candidate is not shown to render the reference within {margin:g} (relative) + {atol:g}: "
           f"{e.blocks_shown} of {e.block_pvalue.size} blocks shown at alpha {alpha:g} (the chance of passing "
           "images outside the margin; no share of the suite's budget)\n" + e.text())
    rec.message = msg
    root = sc.suite.artifacts if sc is not None and sc.suite is not None else None
    _artifacts.write(root, name, index, "images_equivalent", msg,
                     {"block-pvalues": _artifacts.pvalue_map_png(e.block_pvalue, alpha, scale=8)})
    raise StatisticalAssertionError(msg, rec)
