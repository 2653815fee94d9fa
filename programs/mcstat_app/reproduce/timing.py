# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Error against run time: what each estimator's variance costs.

Irradiance: at the first receiver that sees an emitter, each estimator
computes ``reps`` estimates (means of n primary estimates) at each budget
n, each timed with ``time.perf_counter`` around the libmcest call and the
mean.  The RMSE against Lambert's formula (one triangle; otherwise the
standard error estimated from the samples, sigma / sqrt(n)) is plotted
against the median wall time per estimate; an unbiased estimator follows
RMSE = sigma sqrt(t1 / T), slope -1/2 on log-log axes, t1 the time per
primary estimate.  The efficiency 1 / (sigma^2 t1) compares estimators at
equal cost (Kalos and Whitlock): the one with the larger value reaches a
given error sooner.  Whether one is *significantly* more efficient than
another is `mcstat.efficiency_test`'s question: every estimator is timed
over ``eff_batches`` batches of ``eff_batch_size`` primary estimates,
interleaved (the order rotates each round, so machine load affects all
alike), and S (else the first listed) is compared with each other one:
"S is X times more efficient than A, 95% CI [lo, hi]" from the variances
of the primaries and the batches' times per primary.

K-S simulation: two samples of exact-sampler directions from the first
BRDF of section 3.2 (H0 true), picked so that the exact p-value lies in
[0.01, 0.2] where a level-alpha decision is sensitive; simulated p-values
with n_sim replicates are compared with the exact one: the RMS error
should follow sqrt(p (1 - p) / n_sim) while the time grows like n_sim.

Wall-clock numbers depend on the machine and its load (this study is left
out of the reproducibility check of results.json); the errors do not.
"""
from __future__ import annotations

import math
import time
from typing import Any, Dict, List

import numpy as np

import mcstat
from . import cost
from .context import Context
from .irradiance import ReceiverEstimators
from .plan import Plan
from .results import columns, test_fields


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    p = plan.params["timing"]
    out: Dict[str, Any] = dict(threads=ctx.threads or mcstat.get_num_threads(), budgets=p["budgets"], reps=p["reps"])
    if plan.runs("timing", "estimators"):
        out["irradiance"] = _irradiance(ctx, plan, p)
    if plan.runs("timing", "ks"):
        out["ks"] = _ks(ctx, plan, p)
    return out


def _irradiance(ctx: Context, plan: Plan, p: Dict[str, Any]) -> Dict[str, Any]:
    sc = plan.scene
    r = plan.visible_receivers()[0]
    E = r["lambert"]
    rec = ReceiverEstimators(ctx, plan, r["index"], "timing")
    budgets, reps = p["budgets"], p["reps"]
    res: Dict[str, Any] = dict(receiver=r["name"], lambert=E, reference="lambert" if E is not None else "none",
                               estimators={})
    ctx.print(f"\n== Error against run time at {r['name']!r}: {reps} estimates per budget, "
              f"{'RMSE against Lambert' if E is not None else 'no analytic value: estimated standard error'}; "
              f"{out_threads(ctx)} thread(s); wall times on a shared machine are noisy")
    with ctx.bar(sum(cost.estimates(m, n) * reps for m in sc.estimators for n in budgets), "timing") as bar:
        for m in sc.estimators:
            rec.primaries(m, 1000, first_index=(len(budgets) + 1) << 40)  # warm-up (page faults, caches)
            rows, var_last = [], []
            for bi, n in enumerate(budgets):
                vals, times = [], []
                for rep in range(reps):
                    t0 = time.perf_counter()
                    prim = rec.primaries(m, n, first_index=(bi << 40) + rep * n)
                    v = float(prim.mean())
                    times.append(time.perf_counter() - t0)
                    vals.append(v)
                    if bi == len(budgets) - 1:
                        var_last.append(float(prim.var(ddof=1)))
                    bar.update(cost.estimates(m, n))
                vals_a = np.array(vals)
                rmse = float(np.sqrt(np.mean((vals_a - E) ** 2))) if E is not None else None
                rows.append(dict(n=n, estimates=vals, rmse=rmse, wall_times=times,
                                 wall_median=float(np.median(times))))
            sigma = math.sqrt(float(np.mean(var_last)))
            t1 = rows[-1]["wall_median"] / budgets[-1]
            for row in rows:
                row["se_estimated"] = sigma / math.sqrt(row["n"])
            res["estimators"][m] = dict(rows=rows, sigma_primary=sigma, wall_per_primary=t1,
                                        efficiency=1.0 / (sigma * sigma * t1) if sigma > 0 else None)
    res["comparisons"] = _compare(ctx, rec, sc.estimators, p, first_index=(len(budgets) + 2) << 40)
    ctx.print(f"{'':3}{'sigma per primary':>18}{'ns per primary':>16}{'efficiency 1/(s^2 t)':>22}"
              f"{'RMSE at largest n' if E is not None else 'std. error at largest n':>26}")
    for m, e in res["estimators"].items():
        last = e["rows"][-1]
        err = last["rmse"] if E is not None else last["se_estimated"]
        ctx.print(f"{m:3}{e['sigma_primary']:>18.4g}{e['wall_per_primary'] * 1e9:>16.3g}"
                  f"{e['efficiency'] or float('nan'):>22.4g}{err:>26.3g}")
    _print_comparisons(ctx, res["comparisons"])
    return res


def _compare(ctx: Context, rec: ReceiverEstimators, methods: List[str], p: Dict[str, Any],
             first_index: int) -> Dict[str, Any]:
    """Interleaved timed batches of every estimator, then the efficiency
    test of the reference (S, else the first) against each other one."""
    k, size = p["eff_batches"], p["eff_batch_size"]
    ref = "S" if "S" in methods else methods[0]
    acc = {m: mcstat.Moments() for m in methods}
    times: Dict[str, List[float]] = {m: [] for m in methods}
    with ctx.bar(sum(cost.estimates(m, size) for m in methods) * k, "timing efficiency") as bar:
        for b in range(k):
            # rotate the order each round: no estimator always runs first
            for m in methods[b % len(methods):] + methods[:b % len(methods)]:
                t0 = time.perf_counter()
                prim = rec.primaries(m, size, first_index=first_index + b * size)
                times[m].append((time.perf_counter() - t0) / size)
                acc[m].push(prim)
                bar.update(cost.estimates(m, size))
    out: Dict[str, Any] = dict(batches=k, batch_size=size, reference=ref, alpha=0.05, tests=[])
    for m in methods:
        if m == ref:
            continue
        try:
            r = mcstat.efficiency_test(acc[ref], acc[m], times[ref], times[m])
        except mcstat.McstatError as e:  # e.g. an estimator with zero variance here
            out["tests"].append(dict(x=ref, y=m, error=str(e)))
            continue
        e = r.efficiency or {}
        out["tests"].append(dict(x=ref, y=m, ratio=r.estimate, conf_int=list(r.conf_int), pvalue=r.pvalue,
                                 df=r.df, decision=r.decision, var_ratio=e.get("var_ratio"),
                                 time_ratio=e.get("time_ratio"), result=test_fields(r),
                                 block=r.format(ref, m)))
    return out


def _print_comparisons(ctx: Context, c: Dict[str, Any]) -> None:
    ctx.print(f"\nEfficiency ratios (mcstat.efficiency_test): {c['batches']} interleaved batches of "
              f"{c['batch_size']} primary estimates per estimator; 95% confidence intervals")
    for t in c["tests"]:
        ctx.print("  " + comparison_sentence(t))


def comparison_sentence(t: Dict[str, Any]) -> str:
    """"S is 3.1x more efficient than A, 95% CI [2.4, 4.0] (p = ...)"."""
    if "error" in t:
        return f"{t['x']} against {t['y']}: no test ({t['error']})"
    lo, hi = t["conf_int"]
    verdict = {"greater": "significantly more efficient", "less": "significantly less efficient",
               "equal": "not significantly different"}.get(t["decision"], t["decision"])
    return (f"{t['x']} is {t['ratio']:.3g}x as efficient as {t['y']}, 95% CI [{lo:.3g}, {hi:.3g}] "
            f"(variance ratio {t['var_ratio']:.3g}, time ratio {t['time_ratio']:.3g}; p = {t['pvalue']:.2g}: "
            f"{verdict})")


def out_threads(ctx: Context) -> int:
    return ctx.threads or mcstat.get_num_threads()


def _ks(ctx: Context, plan: Plan, p: Dict[str, Any]) -> Dict[str, Any]:
    sc = plan.scene
    name = plan.brdfs_for("sampling")[0]
    n = p["ks_size"]
    bp = sc.make_brdf(name).plan(sc.brdf(name)["wo"])
    seed = ctx.stream("timing", 100, 0, label=f"timing/K-S data ({name} exact sampler)")
    # H0 data whose exact p-value is where decisions are made
    best = None
    for j in range(40):
        x = bp.sample_exact(n, seed=seed, first_index=(2 * j) * n).keys.astype(float)
        y = bp.sample_exact(n, seed=seed, first_index=(2 * j + 1) * n).keys.astype(float)
        pe = mcstat.ks_test(x, y, weight="canner", method="exact", critical=False).pvalue
        score = abs(math.log(pe / 0.05))
        if best is None or score < best[0]:
            best = (score, j, x, y, pe)
        if 0.01 <= pe <= 0.2:
            break
    _, j, x, y, pe = best
    res: Dict[str, Any] = dict(brdf=name, size=n, pair=j, exact_pvalue=pe, rows=[])
    def ks_cost(ns: int) -> float:  # no cache here: every test simulates its null (cost.py)
        return cost.ks(len(x), len(y), ns, method="simulate")

    with ctx.bar(sum(ks_cost(ns) for ns in p["ks_n_sim"]) * p["ks_reps"], "timing K-S") as bar:
        for si, ns in enumerate(p["ks_n_sim"]):
            errs, ses, times, seeds, tests = [], [], [], [], []
            for rep in range(p["ks_reps"]):
                s = ctx.stream("timing", 101, si, rep, label=f"timing/K-S simulation/n_sim {ns}/rep {rep}")
                t0 = time.perf_counter()
                r = mcstat.ks_test(x, y, weight="canner", method="simulate", n_sim=ns, seed=s, critical=False,
                                   threads=ctx.threads)
                times.append(time.perf_counter() - t0)
                errs.append(r.pvalue - pe)
                ses.append(r.pvalue_se)
                seeds.append(s)
                tests.append(r)
                bar.update(ks_cost(ns))
            res["rows"].append(dict(n_sim=ns, errors=errs, rms_error=float(np.sqrt(np.mean(np.square(errs)))),
                                    mean_reported_se=float(np.mean(ses)),
                                    predicted_se=math.sqrt(pe * (1 - pe) / ns), wall_times=times,
                                    wall_median=float(np.median(times)), seeds=seeds, results=columns(tests)))
    ctx.print(f"\nSimulated K-S p-values ({n} + {n} directions of {name}, exact p = {pe:.4g}):")
    ctx.print(f"{'n_sim':>8}{'RMS error':>12}{'sqrt(p(1-p)/n_sim)':>20}{'mean reported s.e.':>20}{'ms per test':>13}")
    for row in res["rows"]:
        ctx.print(f"{row['n_sim']:>8}{row['rms_error']:>12.3g}{row['predicted_se']:>20.3g}"
                  f"{row['mean_reported_se']:>20.3g}{row['wall_median'] * 1e3:>13.3g}")
    return res


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    irr = res.get("irradiance")
    if irr:
        eff = {m: e["efficiency"] for m, e in irr["estimators"].items() if e["efficiency"]}
        order = sorted(eff, key=lambda m: -eff[m])
        out.append("Timing: efficiency 1/(sigma^2 t) per primary estimate, best first: "
                   + ", ".join(f"{m} {eff[m]:.3g}/s" for m in order)
                   + " (wall-clock: machine-dependent and noisy on a shared machine).")
        for t in irr.get("comparisons", {}).get("tests", []):
            out.append("Timing: " + comparison_sentence(t) + ".")
    return out
