# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Section 3.1: the four irradiance estimators against Lambert and each other.

At each receiver, every listed estimator draws ``runs`` pairs of samples;
each observation is a secondary estimate, the mean of k primary estimates
(ERRATA 7), so that the normal-theory tests apply.  Per run:

- one-sample t test of each estimator against Lambert's formula (only for
  a scene of one triangle, where that value is exact);
- the figure-4 matrix: for rows x and columns y, Welch's t and the F test of
  x's first sample against y's second (independent) sample, so the diagonal
  tests an estimator against itself; the frequencies of less / equal /
  greater over the runs are the figure.

Pooled over the runs, the secondary estimates give the figure-5 histograms,
a one-sample t test per estimator, and the variance ordering: estimators
sorted by their sample variance, each adjacent pair tested with the
one-sided F test.  With several triangles each estimator is run per
triangle (triangles below the receiver's horizon contribute exactly 0 and
are skipped) and the estimates summed.
"""
from __future__ import annotations

from typing import Any, Dict, List, Optional

import numpy as np

import mcstat
from mcstat import estimators as est
from . import equivalence
from .binomial import rate_of_counts
from .context import Context
from .plan import Plan
from .results import batch_columns, decision_counts, test_fields

GREEK = {"U": "σU", "C": "σC", "A": "σA", "S": "σS"}
_CHUNK = 2_000_000  # primary estimates per libmcest call (bounded memory)


class ReceiverEstimators:
    """The irradiance plans of one receiver, one per visible triangle, and
    draws of an estimator summed over them."""

    def __init__(self, ctx: Context, plan: Plan, r_index: int, study: str) -> None:
        sc = plan.scene
        r = sc.receivers[r_index]
        self.name = r["name"]
        self.threads = ctx.threads
        self.plans = []
        for t, (tri, L) in enumerate(zip(sc.triangles, sc.radiances)):
            p = est.IrradiancePlan(triangle=tri, point=r["point"], normal=r["normal"], radiance=float(L))
            if p.exact > 0:  # a triangle below the horizon contributes exactly 0 to every estimator
                seed = ctx.stream(study, r_index, t, label=f"{study}/{self.name}/triangle {t}")
                self.plans.append((p, seed))

    def primaries(self, method: str, n: int, first_index: int, bug: Optional[str] = None) -> np.ndarray:
        out = np.zeros(n)
        for p, seed in self.plans:
            out += p.estimates(method, n, seed=seed, first_index=first_index, bug=bug, threads=self.threads)
        return out

    def secondary(self, method: str, rows: int, per_row: int, k: int, first_index: int = 0,
                  bug: Optional[str] = None, bar: Any = None) -> np.ndarray:
        """(rows, per_row) secondary estimates (means of k); row i uses the
        primary estimates [first_index + i * per_row * k, ...) of the stream."""
        N = per_row * k
        out = np.empty((rows, per_row))
        step = max(1, _CHUNK // N)
        for a in range(0, rows, step):
            b = min(rows, a + step)
            prim = self.primaries(method, (b - a) * N, first_index + a * N, bug)
            out[a:b] = mcstat.batch_means(prim.reshape(b - a, N), k)
            if bar is not None:
                bar.update(b - a)
        return out


def _rate_text(s: Dict[str, Any]) -> str:
    if s["rate"] is None:
        return "no test ran"
    failed = f" ({s['failed']} failed)" if s.get("failed") else ""
    return (f"{s['rejections']}/{s['tests']} = {s['rate']:.3f} [{s['ci95'][0]:.3f}, {s['ci95'][1]:.3f}]{failed}")


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["irradiance"]
    alpha, runs, sec = p["alpha"], p["runs"], p["secondary"]
    k = p["primary"] // sec
    ests = sc.estimators
    out: Dict[str, Any] = dict(section="3.1", alpha=alpha, runs=runs, secondary=sec, k=k, primary=k * sec,
                               estimators=ests, trusted=sc.trusted, receivers=[])
    for r in plan.receivers:
        if not plan.runs("irradiance", r["name"]):
            continue
        rec = ReceiverEstimators(ctx, plan, r["index"], "irradiance")
        X: Dict[str, np.ndarray] = {}
        with ctx.bar(runs * 2 * len(ests), f"3.1 {r['name']}") as bar:
            for m in ests:
                # rows 2i and 2i+1 are run i's two independent samples
                X[m] = rec.secondary(m, 2 * runs, sec, k, bar=bar).reshape(runs, 2, sec)
        out["receivers"].append(_tests(ctx, sc, r, X, alpha, runs, sec, k))
    return out


def _tests(ctx: Context, sc, r: Dict[str, Any], X: Dict[str, np.ndarray], alpha: float, runs: int, sec: int,
           k: int) -> Dict[str, Any]:
    ests = sc.estimators
    E = r["lambert"]
    res: Dict[str, Any] = dict(name=r["name"], lambert=E, analytic=E is not None)
    pooled = {m: X[m][:, 0, :].ravel() for m in ests}
    ctx.print(f"\n== 3.1 Irradiance estimators at {r['name']!r}"
              + (f" (Lambert's formula: E = {E:.9g})" if E is not None else
                 f" ({sc.n_emitters} triangles: no analytic value; trusted estimator {sc.trusted})"))
    ctx.print(f"each observation is a secondary estimate, the mean of k = {k} primary estimates; "
              f"{sec} per sample, {runs} runs, alpha = {alpha:g}")

    # one-sample tests against Lambert, per run
    if E is not None:
        one: Dict[str, Any] = {}
        ctx.print("\nOne-sample t tests against Lambert's formula, one per run:")
        ctx.print(f"{'':3}{'less':>6}{'equal':>7}{'greater':>8}   rejected (rate [95% CI])        "
                  f"binomial test of rate = alpha")
        for m in ests:
            b = mcstat.t_test(X[m][:, 0, :], mu=E, alpha=alpha, on_error="nan")
            c = decision_counts(b.decision)
            s = rate_of_counts(c, alpha)
            one[m] = dict(counts=c, **s, results=batch_columns(b))
            ctx.print(f"{m:3}{c['less']:>6}{c['equal']:>7}{c['greater']:>8}   {_rate_text(s):31} "
                      + (f"p = {s['binom_pvalue']:.3g}" if s["rate"] is not None else ""))
        res["one_sample"] = one
        ctx.print(f"\nPooled over the runs ({runs * sec} secondary estimates each), against Lambert:")
        res["pooled_one_sample"] = {}
        for m in ests:
            try:
                t = mcstat.t_test(pooled[m], mu=E, alpha=alpha)
            except mcstat.McstatError as e:
                res["pooled_one_sample"][m] = dict(error=f"{type(e).__name__}: {e}")
                ctx.print(f"{m}: the test failed: {type(e).__name__}: {e}")
                continue
            res["pooled_one_sample"][m] = test_fields(t)
            ctx.block(t.format(m))
    else:
        res["one_sample"] = None

    # figure 4
    mean_counts: List[List[Dict[str, int]]] = []
    var_counts: List[List[Dict[str, int]]] = []
    tests: Dict[str, Any] = {}
    for i in ests:
        mean_counts.append([])
        var_counts.append([])
        for j in ests:
            bm = mcstat.t_test(X[i][:, 0, :], X[j][:, 1, :], alpha=alpha, on_error="nan")
            bv = mcstat.var_test(X[i][:, 0, :], X[j][:, 1, :], alpha=alpha, on_error="nan")
            mean_counts[-1].append(decision_counts(bm.decision))
            var_counts[-1].append(decision_counts(bv.decision))
            tests[f"{i} vs {j}"] = dict(mean=batch_columns(bm), variance=batch_columns(bv))
    res["matrix"] = dict(estimators=ests, mean=mean_counts, variance=var_counts, tests=tests,
                         description="cell [i][j]: estimator i's first sample (x) against estimator j's second "
                                     "sample (y), one test per run; counts of the decisions less / equal / greater")
    ctx.print(f"\nFigure 4: row x against column y, {runs} runs; each cell gives the counts of "
              "less/equal/greater for the means (Welch) | the variances (F):")
    w = 22
    ctx.print("   " + "".join(f"{j:^{w}}" for j in ests))
    for a, i in enumerate(ests):
        cells = []
        for b_, j in enumerate(ests):
            mc, vc = mean_counts[a][b_], var_counts[a][b_]
            cells.append(f"{mc['less']}/{mc['equal']}/{mc['greater']} | {vc['less']}/{vc['equal']}/{vc['greater']}")
        ctx.print(f"{i:3}" + "".join(f"{c:^{w}}" for c in cells))

    # two-sample against the trusted estimator (the fallback without an analytic value)
    if sc.trusted in ests and len(ests) > 1:
        jt = ests.index(sc.trusted)
        vs: Dict[str, Any] = {}
        for a, m in enumerate(ests):
            if m == sc.trusted:
                continue
            c = mean_counts[a][jt]
            vs[m] = dict(counts=c, **rate_of_counts(c, alpha))
        res["against_trusted"] = vs
        if E is None:
            ctx.print(f"\nWelch tests against the trusted estimator {sc.trusted}, one per run:")
            for m, s in vs.items():
                ctx.print(f"{m} vs {sc.trusted}: equal means in {s['counts']['equal']}/{runs} runs; rejected "
                          f"{_rate_text(s)}" + (f"; binomial test of rate = alpha: p = {s['binom_pvalue']:.3g}"
                                                if s["rate"] is not None else ""))

    # variance ordering: adjacent pairs by sample variance, one-sided F tests on the pooled estimates
    sd = {m: float(np.std(pooled[m], ddof=1)) for m in ests}
    res["sd_secondary"] = sd
    res["sd_primary_estimated"] = {m: sd[m] * float(np.sqrt(k)) for m in ests}
    order = sorted(ests, key=lambda m: -sd[m])
    steps = []
    text = GREEK[order[0]]
    if len(order) > 1:
        ctx.print(f"\nVariance ordering: one-sided F tests of adjacent estimators (by sample variance) on the "
                  f"pooled secondary estimates, alpha = {alpha:g}:")
    for a, b in zip(order, order[1:]):
        try:
            t = mcstat.var_test(pooled[a], pooled[b], alternative="greater", alpha=alpha)
        except mcstat.McstatError as e:  # e.g. an estimator whose every secondary estimate is 0
            steps.append(dict(pair=[a, b], test=None, error=f"{type(e).__name__}: {e}", shown=False))
            text += " ? " + GREEK[b]
            ctx.print(f"{a} against {b}: the F test failed: {type(e).__name__}: {e}")
            continue
        steps.append(dict(pair=[a, b], test=test_fields(t), shown=bool(t.reject)))
        text += (" > " if t.reject else " ~ ") + GREEK[b]
        ctx.block(t.format(a, b))
    # and from the runs (figure 4): i above j where the F test said "greater" in most runs
    majority = {f"{i} vs {j}": var_counts[a][b]["greater"] > runs / 2
                for a, i in enumerate(ests) for b, j in enumerate(ests) if i != j}
    res["ordering"] = dict(order=order, text=text, steps=steps, majority_greater=majority,
                           note="'>' where the one-sided F test rejects equal variances at alpha, '~' where not, "
                                "'?' where the test could not run")
    ctx.print(f"ordering found: {text}  (sample standard deviations of the secondary estimates: "
              + ", ".join(f"{m} {sd[m]:.4g}" for m in order) + ")")

    # figure 5: histograms of the pooled secondary estimates
    res["histograms"] = {}
    for m in ests:
        x = pooled[m]
        counts, edges = np.histogram(x, bins=40)
        res["histograms"][m] = dict(counts=counts, edges=edges, mean=float(x.mean()), sd=sd[m], n=int(x.size))

    # beyond the paper: equivalence with Lambert and sample sizes (equivalence.py)
    if E is not None and alpha < 0.5:
        res["equivalence"] = equivalence.analyse(ctx, pooled, E, k, alpha)
    return res


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    alpha = res["alpha"]
    for r in res["receivers"]:
        where = f"3.1 at {r['name']}"
        if r["one_sample"] is not None:
            summary, what = r["one_sample"], "means against Lambert's formula"
        elif r.get("against_trusted"):
            summary, what = r["against_trusted"], f"no analytic value; means against the trusted estimator {res['trusted']}"
        else:
            summary = None
        if summary:
            parts, odd, none = [], [], []
            for m, s in summary.items():
                if s["rate"] is None:
                    none.append(m)
                    continue
                parts.append(f"{m} {s['rejections']}/{s['tests']}" + (f" ({s['failed']} failed)" if s["failed"] else ""))
                if s["binom_pvalue"] < 0.01:
                    odd.append(f"{m} (rate {s['rate']:.3f}, binomial p = {s['binom_pvalue']:.2g})")
            text = f"{where}: {what}"
            if parts:
                text += (f" rejected in {', '.join(parts)} runs at alpha = {alpha:g}: "
                         + ("every rejection count is consistent with alpha (exact binomial tests, p >= 0.01)"
                            if not odd else "NOT consistent with alpha for " + ", ".join(odd)))
            if none:
                text += (f"{'; ' if parts else ': '}no test of {', '.join(none)} could run (constant samples, e.g. "
                         "no direction hit the emitter; see the R-style output)")
            out.append(text + ".")
        if r.get("equivalence"):
            out += equivalence.findings(where, r["equivalence"])
        if len(r["ordering"]["order"]) > 1:
            out.append(f"{where}: variance ordering {r['ordering']['text']} (one-sided F tests on pooled "
                       f"secondary estimates; '~' = not resolved at alpha = {alpha:g}"
                       + ("; '?' = the test could not run" if "?" in r["ordering"]["text"] else "") + ").")
    return out
