# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Beyond the paper (3.4+): anytime-valid sequential tests on the planted bugs.

Section 3.4 fixes the budget before looking.  Here a renderer's workflow is
simulated instead: render a batch, look, stop as soon as the test decides
("render until decided").  At the first receiver that sees an emitter,
estimator A with each planted bug is compared with the trusted estimator
by ``mcstat.SequentialTest("mean2")`` (libmcstat's Gaussian-mixture
confidence sequence, mcstat/sequential.h), pushing ``batch`` primary
estimates of each per look, up to ``max_n`` per run.  Measured:

- the stopping time (primary estimates per sample at the deciding look, or
  censored at ``max_n``) and the decision of each of ``runs`` runs per bug;
- the fixed-n Welch test at equal power: its n for power 0.9, from the
  bug's effect size and standard deviations on a large pilot sample
  (``mcstat.power``), checked by simulating fixed-n tests at that n;
- under H0 (the correct A against the trusted estimator, ``h0_runs`` runs
  of every look up to ``max_n``): the rate of ever rejecting with the
  sequential test, against a fixed-n Welch test looked at after every
  batch and stopped at its first p <= alpha (the naive "peeking").

Counter ranges of the seed streams: run i draws primary estimates
[i max_n, (i + 1) max_n) of each estimator (the trusted estimator's draws
are shared by the bugs and the H0 run of the same index, as in 3.4); the
pilot and the fixed-n check have ranges of their own.
"""
from __future__ import annotations

import math
from typing import Any, Dict, List, Optional

import numpy as np

import mcstat
from . import cost
from .binomial import clopper_pearson, rate_summary
from .context import Context
from .irradiance import ReceiverEstimators
from .plan import Plan

PILOT_FIRST = 1 << 42       # counter range of the pilot samples
CHECK_FIRST = 2 << 42       # and of the simulated fixed-n tests
CHECK_MAX_VALUES = 50_000_000  # the fixed-n check is skipped beyond this many values per estimator
_CHUNK = 2_000_000          # primary estimates per estimator drawn at once (bounded memory)
CHECK_N_GUESS = 100         # the progress bar's guess at a fixed n
MIN_N = 100                 # the test holds below this many values per sample (SequentialTest's default)


def _quantile(stops: np.ndarray, q: float) -> Optional[int]:
    """The q-quantile of stopping times with censored runs as +inf (None: beyond max_n)."""
    v = float(np.quantile(stops, q, method="inverted_cdf"))
    return int(v) if math.isfinite(v) else None


def _rows(rec: ReceiverEstimators, method: str, rows: int, n: int, first: int, bug: Optional[str]):
    """(rows, n) primary estimates, row i from [first + i n, ...), in chunks of bounded size."""
    step = max(1, _CHUNK // n)
    for a in range(0, rows, step):
        b = min(rows, a + step)
        yield a, rec.primaries(method, (b - a) * n, first + a * n, bug).reshape(b - a, n)


def _sequential(x: np.ndarray, y: np.ndarray, batch: int, p: Dict[str, Any]) -> "mcstat.SequentialTest":
    """One run: push a batch of each per look until the test decides or the run's values are used up."""
    s = mcstat.SequentialTest("mean2", alpha=p["alpha"], t_opt=p["t_opt"], min_n=MIN_N)
    for j in range(0, x.size, batch):
        s.push(x[j:j + batch], y[j:j + batch])
        if s.decided:
            break
    return s


def _pilot(ctx: Context, rec: ReceiverEstimators, p: Dict[str, Any], trusted: str) -> Dict[str, Any]:
    n = p["pilot"]
    y = rec.primaries(trusted, n, PILOT_FIRST)
    out = dict(n=n, trusted=dict(mean=float(y.mean()), sd=float(y.std(ddof=1))), bugs={})
    for v in p["bugs"]:
        x = rec.primaries("A", n, PILOT_FIRST, v)
        mx, sx = float(x.mean()), float(x.std(ddof=1))
        d = (mx - out["trusted"]["mean"]) / sx if sx > 0 else math.nan
        out["bugs"][v] = dict(mean=mx, sd=sx, effect=d, sd_ratio=out["trusted"]["sd"] / sx if sx > 0 else math.nan,
                              direction="greater" if d > 0 else "less")
    return out


def _fixed_n(ctx: Context, rec: ReceiverEstimators, p: Dict[str, Any], trusted: str, bug: str,
             pil: Dict[str, Any]) -> Dict[str, Any]:
    """n of the fixed-n Welch test with power `power` at the pilot's effect, and its simulated power there."""
    out: Dict[str, Any] = dict(power_target=p["power"], n=None, power_planned=None, check=None)
    d, ratio = abs(pil["effect"]), pil["sd_ratio"]
    if not (math.isfinite(d) and d > 0 and math.isfinite(ratio) and ratio > 0):
        out["reason"] = "no effect measurable on the pilot sample"
        return out
    try:
        pw = mcstat.power("welch", n=None, effect=d, alpha=p["alpha"], power=p["power"], sd_ratio=ratio)
    except mcstat.McstatError as e:
        out["reason"] = f"mcstat.power failed: {type(e).__name__}: {e}"
        return out
    n = max(2, int(pw.n))  # Welch's test needs two values per sample
    out.update(n=n, n_exact=float(pw.n_exact), power_planned=float(
        mcstat.power("welch", n=n, effect=d, alpha=p["alpha"], power=None, sd_ratio=ratio).power))
    R = p["h0_runs"]
    if R * n > CHECK_MAX_VALUES:
        out["reason"] = f"the check would draw {R} x {n} values of each estimator"
        return out
    decided = dict(less=0, greater=0)
    for (a, X), (_, Y) in zip(_rows(rec, "A", R, n, CHECK_FIRST, bug), _rows(rec, trusted, R, n, CHECK_FIRST, None)):
        b = mcstat.t_test(X, Y, alpha=p["alpha"], intervals=False, on_error="nan")
        for k in decided:
            decided[k] += int(np.sum(b.decision == k))
    correct = decided[pil["direction"]]
    lo, hi = clopper_pearson(correct, R)
    out["check"] = dict(rejections=correct, tests=R, rate=correct / R, ci95=[lo, hi], decided=decided)
    return out


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["sequential"]
    alpha, runs, h0_runs, B = p["alpha"], p["runs"], p["h0_runs"], p["batch"]
    looks = max(1, p["max_n"] // B)
    nmax = looks * B
    r = plan.visible_receivers()[0]
    rec = ReceiverEstimators(ctx, plan, r["index"], "sequential")
    tr = sc.trusted
    out: Dict[str, Any] = dict(section="3.4+", receiver=r["name"], trusted=tr, alpha=alpha, runs=runs,
                               h0_runs=h0_runs, batch=B, max_n=nmax, looks=looks, t_opt=p["t_opt"],
                               power=p["power"], bugs=list(p["bugs"]), min_n=MIN_N)
    per_value = cost.estimates("A", 1) + cost.estimates(tr, 1)
    check = h0_runs * CHECK_N_GUESS * per_value  # the fixed-n check's n is known only after the pilot
    total = (p["pilot"] * (len(p["bugs"]) * cost.ESTIMATE["A"] + cost.estimates(tr, 1))
             + len(p["bugs"]) * runs * (nmax * per_value + looks * cost.SEQ_LOOK)
             + h0_runs * (nmax * per_value + looks * (cost.SEQ_LOOK + cost.NAIVE_LOOK))
             + len(p["bugs"]) * check)
    with ctx.bar(total, f"3.4+ {r['name']}") as bar:
        pilot = _pilot(ctx, rec, p, tr)
        bar.update(p["pilot"] * (len(p["bugs"]) * cost.ESTIMATE["A"] + cost.estimates(tr, 1)))
        out["pilot"] = pilot
        out["per_bug"] = {}
        for v in p["bugs"]:
            stops = np.full(runs, np.inf)
            decisions: List[str] = []
            example = None
            for (a, X), (_, Y) in zip(_rows(rec, "A", runs, nmax, 0, v), _rows(rec, tr, runs, nmax, 0, None)):
                for i in range(X.shape[0]):
                    s = _sequential(X[i], Y[i], B, p)
                    decisions.append(s.decision)
                    if s.decided:
                        stops[a + i] = s.n_decided
                    if a + i == 0:
                        example = str(s)
                bar.update(X.shape[0] * (nmax * per_value + looks * cost.SEQ_LOOK))
            fixed = _fixed_n(ctx, rec, p, tr, v, pilot["bugs"][v])
            bar.update(check)
            out["per_bug"][v] = _summary(stops, decisions, pilot["bugs"][v]["direction"], fixed, nmax, example)
        out["planned_for_smallest"] = _smallest(out)
        out["h0"] = _h0(rec, p, tr, nmax, B, bar, per_value)
    _print(ctx, out)
    return out


def _summary(stops: np.ndarray, decisions: List[str], direction: str, fixed: Dict[str, Any], nmax: int,
             example: Optional[str]) -> Dict[str, Any]:
    runs = stops.size
    decided = int(np.isfinite(stops).sum())
    counts = {k: decisions.count(k) for k in ("less", "greater", "equal", "continue")}
    med, q = _quantile(stops, 0.5), _quantile(stops, fixed["power_target"])
    n90 = fixed["n"]
    out = dict(stops=[int(x) if math.isfinite(x) else None for x in stops], decisions=counts, decided=decided,
               fraction_decided=decided / runs, direction=direction, correct=counts[direction],
               wrong=decided - counts[direction], median=med, q=q, fixed=fixed,
               median_over_fixed=(med / n90) if (med is not None and n90) else None,
               q_over_fixed=(q / n90) if (q is not None and n90) else None,
               # the sequential test's power at the fixed test's n: correct decisions by n_90
               decided_by_fixed_n=(int(np.sum(stops <= n90)) / runs) if n90 else None)
    if example is not None:
        out["example"] = example
    return out


def _smallest(res: Dict[str, Any]) -> Optional[Dict[str, Any]]:
    """A fixed-n test is sized before the effect is known: sized for the smallest of the bugs' effects
    (power `power` there), it spends that n on every bug; the sequential test adapts to each."""
    sized = [v for v in res["bugs"] if res["per_bug"][v]["fixed"]["n"]]
    if not sized:
        return None
    v = max(sized, key=lambda b: res["per_bug"][b]["fixed"]["n"])
    n = res["per_bug"][v]["fixed"]["n"]
    return dict(bug=v, n=n, median_over_n={b: (res["per_bug"][b]["median"] / n if res["per_bug"][b]["median"]
                                                  is not None else None) for b in res["bugs"]})


def _h0(rec: ReceiverEstimators, p: Dict[str, Any], tr: str, nmax: int, B: int, bar: Any,
        per_value: float) -> Dict[str, Any]:
    """The correct A against the trusted estimator: the look of the first rejection, if any, of the
    sequential test and of the fixed-n Welch test peeked at every look."""
    R, alpha, looks = p["h0_runs"], p["alpha"], nmax // B
    seq_look = np.full(R, -1, dtype=np.int64)
    naive_look = np.full(R, -1, dtype=np.int64)
    for (a, X), (_, Y) in zip(_rows(rec, "A", R, nmax, 0, None), _rows(rec, tr, R, nmax, 0, None)):
        m = X.shape[0]
        for i in range(m):
            s = _sequential(X[i], Y[i], B, p)
            if s.decided:
                seq_look[a + i] = s.n_decided // B - 1
        # the naive test: Welch's p-value of the cumulative samples at every look, all runs of the chunk at once
        ax, ay = mcstat.MomentsArray((m,)), mcstat.MomentsArray((m,))
        first = naive_look[a:a + m]
        for j in range(looks):
            ax.push(np.ascontiguousarray(X[:, j * B:(j + 1) * B].T))
            ay.push(np.ascontiguousarray(Y[:, j * B:(j + 1) * B].T))
            rej = mcstat.t_test(ax, ay, alpha=alpha, intervals=False, on_error="nan").reject
            first[(first < 0) & rej] = j
        bar.update(m * (nmax * per_value + looks * (cost.SEQ_LOOK + cost.NAIVE_LOOK)))
    out: Dict[str, Any] = {}
    for name, first in (("sequential", seq_look), ("naive", naive_look)):
        ever = int(np.sum(first >= 0))
        curve = np.cumsum(np.bincount(first[first >= 0], minlength=looks))[:looks] / R
        out[name] = dict(rate_summary(ever, R, alpha), first_look=first.tolist(), curve=curve.tolist())
    out["n"] = [B * (j + 1) for j in range(looks)]
    return out


def _n(v: Optional[int], nmax: int) -> str:
    return f"> {nmax}" if v is None else str(v)


def _print(ctx: Context, res: Dict[str, Any]) -> None:
    ctx.print(f"\n== 3.4+ Sequential tests on the planted bugs at {res['receiver']!r}: A against {res['trusted']}, "
              f"anytime-valid two-sample test (mcstat.SequentialTest('mean2')) at alpha = {res['alpha']:g}, a look "
              f"every {res['batch']} primary estimates of each, up to {res['max_n']}, {res['runs']} runs per bug")
    pil = res["pilot"]
    ctx.print(f"pilot ({pil['n']} primary estimates each): {res['trusted']} mean {pil['trusted']['mean']:.6g}, "
              f"s.d. {pil['trusted']['sd']:.4g}")
    for v in res["bugs"]:
        b = pil["bugs"][v]
        ctx.print(f"  A with {v}: mean {b['mean']:.6g}, s.d. {b['sd']:.4g}, effect d = (mean - mean of "
                  f"{res['trusted']}) / s.d. = {b['effect']:.4g}")
    for v in res["bugs"]:
        if "example" in res["per_bug"][v]:
            ctx.print(f"\nA with {v}, run 0:")
            ctx.block(res["per_bug"][v]["example"])
    ctx.print("\nstopping times (primary estimates per sample) and the fixed-n Welch test at equal power "
              f"({res['power']:g}):")
    ctx.print(f"{'bug':>12} {'decided':>9} {'correct':>8} {'median':>7} {'q':>7} {'fixed n':>8} "
              f"{'simulated power':>24} {'median/n':>9} {'q/n':>7}")
    for v in res["bugs"]:
        s = res["per_bug"][v]
        f = s["fixed"]
        chk = f["check"]
        power = (f"{chk['rate']:.3f} [{chk['ci95'][0]:.3f}, {chk['ci95'][1]:.3f}]" if chk else "-")
        ctx.print(f"{v:>12} {s['decided']:>5}/{len(s['stops']):<3} {s['correct']:>8} {_n(s['median'], res['max_n']):>7} "
                  f"{_n(s['q'], res['max_n']):>7} {f['n'] if f['n'] else '-':>8} {power:>24} "
                  f"{_ratio(s['median_over_fixed']):>9} {_ratio(s['q_over_fixed']):>7}")
    h = res["h0"]
    ctx.print(f"\nH0 (the correct A against {res['trusted']}), {res['h0_runs']} runs of {res['looks']} looks up to "
              f"{res['max_n']}: rate of ever rejecting at alpha = {res['alpha']:g}")
    for name, label in (("sequential", "sequential (anytime-valid)"), ("naive", "fixed-n Welch peeked at every look")):
        s = h[name]
        ctx.print(f"  {label:36} {s['rejections']}/{s['tests']} = {s['rate']:.4f} "
                  f"[{s['ci95'][0]:.4f}, {s['ci95'][1]:.4f}]")


def _ratio(v: Optional[float]) -> str:
    return "-" if v is None else f"{v:.2f}"


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    where = f"3.4+ at {res['receiver']}"
    nmax = res["max_n"]
    for v in res["bugs"]:
        s = res["per_bug"][v]
        f = s["fixed"]
        runs = len(s["stops"])
        text = (f"{where}: A with {v} (effect d = {res['pilot']['bugs'][v]['effect']:.3g}) against "
                f"{res['trusted']}: the sequential test decided in {s['decided']}/{runs} runs by n = {nmax} "
                f"({s['correct']} in the right direction, '{s['direction']}'), median stop {_n(s['median'], nmax)}, "
                f"{res['power']:.0%} quantile {_n(s['q'], nmax)} primary estimates per sample")
        if f["n"]:
            chk = f["check"]
            text += (f"; the fixed-n Welch test needs n = {f['n']} for power {f['power_target']:g}"
                     + (f" (simulated: {chk['rate']:.3f} [{chk['ci95'][0]:.3f}, {chk['ci95'][1]:.3f}])"
                        if chk else ""))
            m = s["median_over_fixed"]
            if m is None:
                text += "; the sequential median is beyond the budget"
            elif m < 1:
                text += f"; sequential median / fixed n = {m:.2f}: the sequential test stops sooner"
            else:
                text += (f"; sequential median / fixed n = {m:.2f}: the sequential test does NOT stop sooner than "
                         "a fixed-n test sized with the effect known from the pilot"
                         + (f" (it cannot decide before min_n = {res['min_n']} values or before the first look)"
                            if s["median"] is not None and s["median"] <= max(res["min_n"], res["batch"]) else
                            " (it needs no effect size in advance, and pays for looking at every batch)"))
        else:
            text += f"; no fixed-n comparison ({f.get('reason', 'n not computed')})"
        out.append(text + ".")
    sm = res.get("planned_for_smallest")
    if sm and len(res["bugs"]) > 1:
        wins = [b for b, r in sm["median_over_n"].items() if r is not None and r < 1]
        out.append(f"{where}: sized in advance for the smallest of the bugs' effects ({sm['bug']}), the fixed-n test "
                   f"spends n = {sm['n']} on every bug; the sequential median is below that for "
                   + (", ".join(wins) if wins else "none of them") + " ("
                   + ", ".join(f"{b} {_ratio(r)}" for b, r in sm["median_over_n"].items()) + " of it).")
    h = res["h0"]
    sq, nv = h["sequential"], h["naive"]
    text = (f"{where}: under H0 (the correct A, {res['h0_runs']} runs, a look every {res['batch']} up to {nmax}) the "
            f"sequential test ever rejected in {sq['rejections']}/{sq['tests']} runs = {sq['rate']:.4f} "
            f"[{sq['ci95'][0]:.4f}, {sq['ci95'][1]:.4f}]"
            + (" (its whole 95% interval below alpha)" if sq["ci95"][1] <= res["alpha"] else
               " (consistent with alpha)" if sq["ci95"][0] <= res["alpha"] else f" (ABOVE alpha = {res['alpha']:g})")
            + f"; the fixed-n Welch test peeked at every look rejected in {nv['rejections']}/{nv['tests']} = "
              f"{nv['rate']:.4f} [{nv['ci95'][0]:.4f}, {nv['ci95'][1]:.4f}]"
            + (f", {nv['rate'] / res['alpha']:.1f} times alpha = {res['alpha']:g}" if nv["ci95"][0] > res["alpha"]
               else f", not shown above alpha = {res['alpha']:g} with these runs"))
    out.append(text + ".")
    return out


# -- report ----------------------------------------------------------------------

def report(res: Dict[str, Any], fig: Any, transcript: str) -> List[str]:
    from . import report as rep  # matplotlib: only when the report is written

    nmax = res["max_n"]
    L = ["## 3.4+ Sequential tests on the planted bugs (beyond the paper)", "",
         f"Render until decided: at {res['receiver']}, A with each planted bug against {res['trusted']} by "
         f"`mcstat.SequentialTest(\"mean2\", alpha={res['alpha']:g})`, the anytime-valid test of libmcstat (a "
         f"Gaussian-mixture confidence sequence; mcstat/sequential.h), pushing {res['batch']} primary estimates of "
         f"each per look, up to {nmax} per run, {res['runs']} runs per bug. It may be looked at after every batch "
         f"and stopped at any time with its error rate still at most alpha; it holds (no decision) below "
         f"{res['min_n']} values per sample. The stopping time is n, the primary estimates per sample at the "
         f"deciding look. The fixed-n Welch test is sized for power {res['power']:g} by `mcstat.power` from each "
         f"bug's effect d = (mean of A - mean of {res['trusted']}) / s.d. of A and the ratio of the standard "
         f"deviations, measured on a pilot of {res['pilot']['n']} primary estimates each, and its power at that n "
         f"checked by simulating {res['h0_runs']} such tests. The sequential test's power at n is the fraction of "
         f"runs decided in the right direction by n, so it reaches the same power at the {res['power']:.0%} quantile "
         "of its stopping time (q below); its median is the number it is usually judged by.", "",
         fig("sequential.png", draw, res), "",
         f"| bug | effect d | decided by {nmax} | right direction | median n | q, the {res['power']:.0%} quantile "
         f"| fixed n (power "
         f"{res['power']:g}) | simulated power of fixed n | median / fixed n | q / fixed n | "
         "sequential decided by fixed n |",
         "|---|---|---|---|---|---|---|---|---|---|---|"]
    for v in res["bugs"]:
        s, f = res["per_bug"][v], res["per_bug"][v]["fixed"]
        chk = f["check"]
        L += [f"| {v} | {res['pilot']['bugs'][v]['effect']:.3g} | {s['decided']}/{len(s['stops'])} | "
              f"{s['correct']}/{s['decided']} ({s['direction']}) | {_n(s['median'], nmax)} | {_n(s['q'], nmax)} | "
              f"{f['n'] or '-'} | " + (f"{chk['rate']:.3f} [{chk['ci95'][0]:.3f}, {chk['ci95'][1]:.3f}]" if chk
                                      else "-")
              + f" | {_ratio(s['median_over_fixed'])} | {_ratio(s['q_over_fixed'])} | "
              + ("-" if s["decided_by_fixed_n"] is None else f"{s['decided_by_fixed_n']:.2f}") + " |"]
    sm = res.get("planned_for_smallest")
    if sm and len(res["bugs"]) > 1:
        L += ["", f"A fixed-n test is sized before the effect is known. Sized for the smallest of these effects "
                  f"({sm['bug']}: n = {sm['n']}), it spends n = {sm['n']} on every bug; the sequential median as a "
                  "fraction of that: " + ", ".join(f"{b} {_ratio(r)}" for b, r in sm["median_over_n"].items()) + "."]
    h = res["h0"]
    L += ["", f"Under H0 (the correct A against {res['trusted']}, {res['h0_runs']} runs of all {res['looks']} looks "
              f"up to {nmax}), the rate of ever rejecting at alpha = {res['alpha']:g}, with exact 95% intervals:", "",
          "| test | ever rejected | rate [95% CI] |", "|---|---|---|"]
    for name, label in (("sequential", "sequential (anytime-valid)"),
                        ("naive", "fixed-n Welch, peeked at every look (stop at the first p <= alpha)")):
        s = h[name]
        L += [f"| {label} | {s['rejections']}/{s['tests']} | {rep._ci(s, 4)} |"]
    L += ["", _reading(res), ""]
    L += rep._details("Text output of 3.4+", transcript)
    return L


def _reading(res: Dict[str, Any]) -> str:
    """The short paragraph under the tables, from the numbers above."""
    ratios = {v: res["per_bug"][v]["median_over_fixed"] for v in res["bugs"]}
    known = {v: r for v, r in ratios.items() if r is not None}
    below = [v for v, r in known.items() if r < 1]
    h = res["h0"]
    text = "Reading: "
    if known:
        text += (f"against a fixed-n test sized with the effect known from the pilot, the sequential median is "
                 f"{min(known.values()):.2f} to {max(known.values()):.2f} times the fixed n, "
                 + (f"below it for {', '.join(below)}. " if below else
                    "so here the sequential test does NOT stop sooner than that test. ")
                 + f"It cannot stop before {max(res['min_n'], res['batch'])} values per sample (min_n and the "
                   "first look), and it needs no effect size in advance: that is what it buys. ")
    text += (f"Under H0 the fixed-n test peeked at every look rejected in {h['naive']['rate']:.1%} of the runs, "
             f"{h['naive']['rate'] / res['alpha']:.1f} times alpha = {res['alpha']:g}; the sequential test in "
             f"{h['sequential']['rate']:.1%} (95% CI up to {h['sequential']['ci95'][1]:.1%}).")
    return text


def draw(res: Dict[str, Any], path: str) -> None:
    from . import plots

    plots._styled(_draw)(res, path)


def _draw(res: Dict[str, Any], path: str) -> None:
    from . import plots

    plt = plots.plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(plots.TEXT_WIDTH, 2.8))
    nmax = res["max_n"]
    lo = nmax
    for i, v in enumerate(res["bugs"]):
        s = res["per_bug"][v]
        color = f"C{i}"
        t = np.sort([x for x in s["stops"] if x is not None])
        runs = len(s["stops"])
        if t.size:
            frac = np.concatenate([[0], np.arange(1, t.size + 1), [t.size]]) / runs
            a1.step(np.concatenate([[t[0]], t, [nmax]]), frac, where="post", color=color, label=v)
            lo = min(lo, t[0])
        n90 = s["fixed"]["n"]
        if n90:
            a1.axvline(n90, color=color, ls="--", lw=1)
            lo = min(lo, n90)
    a1.plot([], [], color="0.3", ls="--", lw=1, label=f"fixed n, power {res['power']:g}")
    a1.axhline(res["power"], color="0.6", ls=":", lw=1)
    a1.set_xscale("log")
    a1.set_xlim(lo / 1.5, nmax * 1.2)
    a1.set_ylim(-0.02, 1.02)
    a1.set_xlabel("primary estimates per sample n")
    a1.set_ylabel(f"fraction of runs decided ({res['runs']} runs)")
    a1.set_title("Stopping times of the sequential test")
    a1.legend(loc="lower right")
    h = res["h0"]
    n = np.array(h["n"])
    for name, label, style in (("naive", "fixed-n Welch, peeked", "-"), ("sequential", "sequential", "-")):
        a2.step(n, h[name]["curve"], where="post", ls=style, label=label)
    a2.axhline(res["alpha"], color="0.5", ls="--", lw=1, label=f"alpha = {res['alpha']:g}")
    a2.set_xscale("log")
    a2.set_ylim(bottom=0)
    a2.set_xlabel("primary estimates per sample n")
    a2.set_ylabel(f"fraction ever rejected by n ({res['h0_runs']} runs)")
    a2.set_title(f"H0: correct A against {res['trusted']}")
    a2.legend(loc="upper left")
    fig.tight_layout()
    plots._save(fig, path)
