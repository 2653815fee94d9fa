# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Section 3.4: the three planted bugs, detected against the trusted estimator.

libmcest plants the paper's errors in estimator A (ERRATA 8): no_cosine
omits the receiver's cosine, barycentric maps uniform numbers to
barycentric coordinates in a way that is not area-preserving, no_jacobian
omits the change of variables n_tri.z/|z|^3.  At each budget (primary
estimates per sample) and in each run, A with each bug, and the correct A
as a control, is compared with the trusted estimator (S in the paper) by
Welch's test on ``secondary`` batch means of k = budget // secondary
primary estimates.  The detection rate against the budget is the power
curve; the control's rejection rate should be about alpha.
"""
from __future__ import annotations

from typing import Any, Dict, List

import mcstat
from . import cost
from .binomial import rate_of_counts, rate_summary
from .context import Context
from .irradiance import ReceiverEstimators
from .plan import Plan
from .results import batch_columns, decision_counts

DETECTED = 0.9  # a bug is "detected" at a budget where at least this fraction of runs reject


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["bugs"]
    alpha, runs, sec, budgets = p["alpha"], p["runs"], p["secondary"], p["budgets"]
    variants = ["none"] + list(p["bugs"])
    out: Dict[str, Any] = dict(section="3.4", alpha=alpha, runs=runs, secondary=sec, trusted=sc.trusted,
                               bugs=list(p["bugs"]), detected_threshold=DETECTED, receivers=[])
    for r in plan.receivers:
        if not plan.runs("bugs", r["name"]):
            continue
        rec = ReceiverEstimators(ctx, plan, r["index"], "bugs")
        rows = []
        def step_cost(budget: int, v: str) -> float:  # runs x budget primary estimates (cost.py)
            return runs * budget * cost.estimates("A", 1) + (runs * budget * cost.estimates(sc.trusted, 1)
                                                             if v == variants[0] else 0.0)

        with ctx.bar(sum(step_cost(b, v) for b in budgets for v in variants), f"3.4 {r['name']}") as bar:
            for zi, budget in enumerate(budgets):
                k = budget // sec
                first = zi << 40  # disjoint counter ranges per budget
                T = rec.secondary(sc.trusted, runs, sec, k, first_index=first)
                row: Dict[str, Any] = dict(budget=k * sec, k=k, variants={})
                for v in variants:
                    V = rec.secondary("A", runs, sec, k, first_index=first, bug=None if v == "none" else v)
                    bt = mcstat.t_test(V, T, alpha=alpha, on_error="nan")
                    c = decision_counts(bt.decision)
                    row["variants"][v] = dict(counts=c, **rate_of_counts(c, alpha),
                                              results=batch_columns(bt))
                    if zi == len(budgets) - 1 and v != "none" and bt.ok[0]:
                        row["variants"][v]["example"] = bt[0].format(f"A with {v} (run 0)", sc.trusted)
                    bar.update(step_cost(budget, v))  # the first variant's step also draws the trusted T
                rows.append(row)
        summary = {}
        for v in variants:
            rates = [row["variants"][v]["rate"] or 0.0 for row in rows]
            from_budget = None
            for i in range(len(rows)):
                if all(x >= DETECTED for x in rates[i:]):
                    from_budget = rows[i]["budget"]
                    break
            last = rows[-1]["variants"][v]["counts"]
            direction = max(("less", "greater"), key=lambda d: last[d]) if last["less"] + last["greater"] else "equal"
            summary[v] = dict(detected_from_budget=from_budget, rate_at_largest=rates[-1], direction=direction,
                              detected=rates[-1] >= DETECTED)
        control = sum(row["variants"]["none"]["rejections"] for row in rows)
        summary["none"]["pooled"] = rate_summary(control, sum(row["variants"]["none"]["tests"] for row in rows), alpha)
        out["receivers"].append(dict(name=r["name"], budgets=rows, summary=summary))
        _print(ctx, sc, r, rows, variants, summary, alpha, runs, sec)
    return out


def _print(ctx, sc, r, rows, variants, summary, alpha, runs, sec) -> None:
    ctx.print(f"\n== 3.4 Planted bugs at {r['name']!r}: A against {sc.trusted}, Welch's t test at alpha = {alpha:g}, "
              f"{runs} runs per budget, {sec} secondary estimates per sample")
    for v in variants[1:]:
        if "example" in rows[-1]["variants"][v]:
            ctx.block(rows[-1]["variants"][v]["example"])
    ctx.print("\nrejections per budget (primary estimates per sample):")
    ctx.print(f"{'budget':>8} {'k':>5}" + "".join(f"{('A (no bug)' if v == 'none' else v):>14}" for v in variants))
    for row in rows:
        ctx.print(f"{row['budget']:>8} {row['k']:>5}"
                  + "".join(f"{row['variants'][v]['rejections']:>9}/{row['variants'][v]['tests']:<4}" for v in variants))
    pooled = summary["none"]["pooled"]
    if pooled["rate"] is None:
        ctx.print("control (A without a bug): every test failed")
        return
    ctx.print(f"control (A without a bug): rejected in {pooled['rejections']}/{pooled['tests']} tests = "
              f"{pooled['rate']:.4f} [{pooled['ci95'][0]:.4f}, {pooled['ci95'][1]:.4f}]; binomial test of rate = "
              f"alpha: p = {pooled['binom_pvalue']:.3g}")


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    for r in res["receivers"]:
        parts = []
        for v in res["bugs"]:
            s = r["summary"][v]
            if s["detected_from_budget"] is not None:
                parts.append(f"{v} detected (rejected in >= {DETECTED:.0%} of runs) from a budget of "
                             f"{s['detected_from_budget']} on, mean {s['direction']} than {res['trusted']}'s")
            else:
                parts.append(f"{v} NOT detected reliably: rejected in {s['rate_at_largest']:.0%} of runs at the "
                             f"largest budget")
        c = r["summary"]["none"]["pooled"]
        control = ("every test of the correct A failed" if c["rate"] is None else
                   f"The correct A was rejected in {c['rejections']}/{c['tests']} tests ({c['rate']:.3f}; binomial "
                   f"test of rate = alpha: p = {c['binom_pvalue']:.3g})")
        out.append(f"3.4 at {r['name']}: " + "; ".join(parts) + f". {control}.")
    return out
