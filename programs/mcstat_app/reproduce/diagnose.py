# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Beyond the paper: diagnostics of every estimator's primary estimates.

The paper's tests assume normal secondary estimates (t and F tests on batch
means).  For each irradiance estimator (U, C, A, S) at each receiver that
sees an emitter, and for both reflected-radiance estimators (BRDF sampling
and exact rejection sampling) of each BRDF at its outgoing direction,
``n`` primary estimates are drawn and ``mcstat.diagnose`` reports (numbers
from libmcstat, see mcstat.h "Estimator diagnostics"):

- skewness and excess kurtosis, with their standard errors;
- Hill's tail index of each tail and the heavy-tail warning (infinite or
  nearly infinite variance: "fireflies");
- the predicted rejection rates of each tail of the two-sided t test on
  batch means at the batch size and level the other studies use (3.1: k =
  primary // secondary, m = secondary, its alpha; 3.3: k = 1, m = m, its
  alpha), and the batch size the rule recommends for that m;
- D'Agostino-Pearson and Shapiro-Wilk tests (SciPy) of the normality of the
  batch means at that batch size (3.1) or at the recommended one (3.3).
"""
from __future__ import annotations

import math
from typing import Any, Dict, List

import mcstat
from .context import Context
from .irradiance import ReceiverEstimators
from .plan import Plan


def _entry(d: "mcstat.Diagnostics", study_k: int) -> Dict[str, Any]:
    out = d.to_dict()
    out["study_k"] = study_k
    half = d.alpha / 2
    out["study_k_ok"] = bool(max(abs(d.t_size[0] - half), abs(d.t_size[1] - half)) <= d.tolerance * half)
    return out


def _diagnose(ctx: Context, title: str, x: Any, study_k: int, **kw: Any) -> Dict[str, Any]:
    """One estimator's entry; data the diagnostics cannot use (constant: an
    emitter no sample hit) are recorded as an error, and the run goes on."""
    ctx.print(f"-- {title}")
    try:
        d = mcstat.diagnose(x, **kw)
    except mcstat.McstatError as e:
        ctx.print(f"not diagnosed: {e}")
        return dict(error=str(e))
    ctx.print(str(d))
    return _entry(d, study_k)


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["diagnostics"]
    n, tol = p["n"], p["tolerance"]
    out: Dict[str, Any] = dict(section="diagnostics", n=n, tolerance=tol, receivers=[], brdfs=[])
    irr = plan.params["irradiance"]
    k_irr, m_irr = irr["primary"] // irr["secondary"], irr["secondary"]
    # mcstat.diagnose's normality tests import scipy.stats on first use (1-2 s,
    # more than the rest of the study): before the bars, not inside their first step
    import scipy.stats  # noqa: F401
    for r in plan.receivers:
        if not plan.runs("diagnostics", r["name"]):
            continue
        rec = ReceiverEstimators(ctx, plan, r["index"], "diagnostics")
        ctx.print(f"\n== Diagnostics of the irradiance estimators at {r['name']}: {n} primary estimates each; the t "
                  f"test of 3.1 sees m = {m_irr} batch means of k = {k_irr}, at alpha = {irr['alpha']:g}")
        ests: Dict[str, Any] = {}
        with ctx.bar(len(sc.estimators), f"diagnostics {r['name']}") as bar:
            for m in sc.estimators:
                ests[m] = _diagnose(ctx, m, rec.primaries(m, n, 0), k_irr, k=k_irr, m=m_irr, alpha=irr["alpha"],
                                    tolerance=tol)
                bar.update()
        out["receivers"].append(dict(name=r["name"], k=k_irr, m=m_irr, alpha=irr["alpha"], estimators=ests))
    rad = plan.params["radiance"]
    names = [b["name"] for b in sc.brdfs]
    for name in [s["target"] for s in plan.steps if s["study"] == "diagnostics" and s["target"] in names]:
        b = sc.brdfs[names.index(name)]
        bp = sc.make_brdf(name).plan(b["wo"])
        bp.compute_albedo(1e-5, strict=False)
        ctx.print(f"\n== Diagnostics of the reflected-radiance estimators of {name} at its outgoing direction: "
                  f"{n} primary estimates each; the Welch test of 3.3 sees m = {rad['m']} of them (k = 1), at alpha = "
                  f"{rad['alpha']:g}")
        ests = {}
        for i, how in enumerate(("sampling", "rejection")):
            seed = ctx.stream("diagnostics", 1000 + names.index(name), i, label=f"diagnostics/{name}/{how}")
            x = bp.reflected_radiance(how, n, seed=seed, threads=ctx.threads)
            ests[how] = _diagnose(ctx, how, x, 1, m=rad["m"], alpha=rad["alpha"], tolerance=tol)
        out["brdfs"].append(dict(name=name, m=rad["m"], alpha=rad["alpha"], estimators=ests))
    return out


def _list(xs: List[str]) -> str:
    return ", ".join(xs) if xs else "none"


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    groups = ([(f"irradiance at {r['name']}", r) for r in res["receivers"]]
              + [(f"reflected radiance off {b['name']}", b) for b in res["brdfs"]])
    for what, g in groups:
        e = {m: d for m, d in g["estimators"].items() if "error" not in d}
        failed = [m for m, d in g["estimators"].items() if "error" in d]
        heavy = [m for m, d in e.items() if d["heavy_tail"]]
        short = [f"{m} (needs k >= {d['recommended_k']})" for m, d in e.items() if not d["study_k_ok"]]
        k = g.get("k", 1)
        out.append(f"Diagnostics, {what}: heavy tail (Hill index < 2.2) in {_list(heavy)}; the batch size k = {k} "
                   f"keeps both tails of the t test at alpha = {g['alpha']:g} on m = {g['m']} batch means within "
                   f"{res['tolerance']:.0%} of alpha/2 for "
                   f"{_list([m for m, d in e.items() if d['study_k_ok']])}"
                   + (f", not for {_list(short)}" if short else "") + "."
                   + (f" Not diagnosed (constant estimates): {_list(failed)}." if failed else ""))
    return out


def _fmt(v: Any, spec: str = ".3g") -> str:
    if v is None:
        return "-"
    if isinstance(v, float) and math.isinf(v):
        return "∞"
    return format(v, spec)


def report(res: Dict[str, Any], fig: Any, transcript: str) -> List[str]:
    """The report's section (called by report.py)."""
    L = ["## Estimator diagnostics (beyond the paper)", "",
         f"{res['n']} primary estimates of every estimator, diagnosed by `mcstat.diagnose`: skewness and excess "
         "kurtosis (standard errors under normality), Hill's tail index of each tail (the variance is infinite "
         "when it is at most 2; *heavy* below 2.2), the rejection rates of each tail of the two-sided t test "
         "predicted by an Edgeworth expansion at the batch size and level alpha the study uses (nominal alpha/2 "
         "each), the batch size k recommended for the same number m of batch means (both "
         f"tails within {res['tolerance']:.0%} of alpha/2), and the normality of the batch means (SciPy's "
         "Shapiro-Wilk and D'Agostino-Pearson tests, over all n / k batch means: with thousands of means they "
         "detect departures far too small to matter to the t test).", ""]
    head = ("| estimator | skewness (se) | excess kurtosis (se) | tail index lower / upper | heavy tail | "
            "t test tails less / greater at k | recommended k | batch means tested | Shapiro-Wilk | D'Agostino |")
    rule = "|---|---|---|---|---|---|---|---|---|---|"

    def rows(e: Dict[str, Any]) -> List[str]:
        out = []
        for m, d in e.items():
            if "error" in d:
                out.append(f"| {m} | not diagnosed: {d['error']} |" + " |" * 8)
                continue
            out.append(f"| {m} | {_fmt(d['skewness'])} ({_fmt(d['skewness_se'], '.2g')}) | {_fmt(d['kurtosis'])} "
                       f"({_fmt(d['kurtosis_se'], '.2g')}) | {_fmt(d['tail_index'][0])} / {_fmt(d['tail_index'][1])} | "
                       f"{'**yes**' if d['heavy_tail'] else 'no'} | {d['t_size'][0]:.4f} / {d['t_size'][1]:.4f} "
                       f"(k = {d['k']}) | {d['recommended_k']} | {d['batch_m']} of {d['batch_k']} | "
                       f"{_fmt(d['shapiro_pvalue'])} | {_fmt(d['normaltest_pvalue'])} |")
        return out

    for r in res["receivers"]:
        L += [f"### Irradiance at {r['name']} (3.1 tests m = {r['m']} batch means of k = {r['k']} at alpha = "
              f"{r['alpha']:g})", "", head, rule]
        L += rows(r["estimators"]) + [""]
    for b in res["brdfs"]:
        L += [f"### Reflected radiance off {b['name']} (3.3 tests m = {b['m']} primary estimates, k = 1, at alpha = "
              f"{b['alpha']:g})", "",
              head, rule]
        L += rows(b["estimators"]) + [""]
    if transcript.strip():
        L += ["", "<details><summary>Diagnostics output</summary>", "", "```", transcript.strip("\n"), "```", "",
              "</details>", ""]
    return L
