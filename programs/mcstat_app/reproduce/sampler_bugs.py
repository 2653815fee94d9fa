# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Beyond the paper: which test catches a buggy direction sampler first?

libmcest plants four realistic bugs in the BRDF samplers' half-vector warps
(``BRDFPlan.sample_bug``; mcest.h): the lobe 10% too wide (``roughness``),
the anisotropy axes swapped (``axes_swapped``), the azimuth over half its
range (``phi_half``), and the sin(theta) of d(omega) forgotten in the polar
warp (``jacobian``).  The density the sampler claims stays the correct one.

At each sample size n and in each of ``runs`` runs, n directions from the
sampler (with each bug, and without as the size check) are tested by two
routes on the same directions:

- chi-squared: Pearson's goodness of fit of the counts in 2^depth cells of
  nearly equal probability under the claimed density, each cell's
  probability by cubature (``estimators.direction_cells``; depth from
  ``estimators.default_depth(n)`` unless the scene fixes it), low cells
  pooled in tree order (``mcstat.chisq_gof``).  A one-sample test: it uses
  the claimed density itself.
- Morton-key K-S: the two-sample K-S test with Canner's weight of the
  directions' Morton keys against n directions from the correct sampler
  (an independent stream), the route section 3.2 uses.  It needs only a
  trusted sampler, not a density.

Directions below the horizon are kept by both.  The rejection rate against
n is each route's power curve; with no bug it is the size, which should be
about alpha.
"""
from __future__ import annotations

from typing import Any, Dict, List, Optional

import numpy as np

import mcstat
from mcstat import estimators as est
from . import cost
from .binomial import rate_summary
from .context import Context
from .plan import Plan

DETECTED = 0.9  # a route "detects" a bug from the size on which it rejects in at least this fraction of runs
ROUTES = ("chisq", "ks")
ROUTE_NAMES = {"chisq": "chi-squared (cells)", "ks": "K-S (Morton keys)"}


def _detected_from(rows: List[Dict[str, Any]], variant: str, route: str) -> Optional[int]:
    rates = [r["variants"][variant][route]["rate"] for r in rows]
    for i in range(len(rows)):
        if all(x is not None and x >= DETECTED for x in rates[i:]):
            return rows[i]["n"]
    return None


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["sampler_bugs"]
    alpha, sizes, runs, n_sim, bugs = p["alpha"], p["sizes"], p["runs"], p["n_sim"], p["bugs"]
    variants = ["none"] + list(bugs)
    out: Dict[str, Any] = dict(section="3.2+", alpha=alpha, sizes=sizes, runs=runs, n_sim=n_sim, bugs=list(bugs),
                               depth=p["depth"], detected_threshold=DETECTED, min_expected=5.0, brdfs=[])
    names = [b["name"] for b in sc.brdfs]
    for name in plan.brdfs_for("sampler_bugs"):
        si = names.index(name)
        bp = sc.make_brdf(name).plan(sc.brdf(name)["wo"])
        ref_seed = ctx.stream("sampler_bugs", si, 0, label=f"sampler_bugs/{name}/reference sampler")
        k_seed = ctx.stream("sampler_bugs", si, 1, label=f"sampler_bugs/{name}/K-S simulation")
        v_seeds = {v: ctx.stream("sampler_bugs", si, 2 + j, label=f"sampler_bugs/{name}/sampler {v}")
                   for j, v in enumerate(variants)}
        cache = mcstat.KSCache(seed=k_seed)
        ctx.print(f"\n== 3.2+ planted sampler bugs: {name}")
        ctx.print(f"each sampler variant against its claimed density: chi-squared on equal-probability cells, and "
                  f"K-S (Canner) of Morton keys against the correct sampler; alpha = {alpha:g}, {runs} runs per size")
        cells_by_depth: Dict[int, Any] = {}
        rows = []
        def step_cost(n: int, first: bool) -> float:  # a run: two samples, chi-squared, K-S (cost.py)
            return n * (2 * cost.DIRECTION + cost.GOF) + cost.ks(n, n, n_sim, simulate_null=first, critical=False)

        depths = {p["depth"] or est.default_depth(n) for n in sizes}  # the cells of each depth, built once
        with ctx.bar(len(depths) * cost.CELLS + sum(step_cost(n, j == r == 0) for n in sizes
                                                    for j in range(len(variants)) for r in range(runs)),
                     f"3.2+ {name}") as bar:
            for zi, n in enumerate(sizes):
                depth = p["depth"] or est.default_depth(n)
                if depth not in cells_by_depth:
                    cells_by_depth[depth] = est.direction_cells(bp, depth)
                    bar.update(cost.CELLS)
                cells = cells_by_depth[depth]
                row: Dict[str, Any] = dict(n=n, depth=depth, variants={})
                examples = {}
                for j, v in enumerate(variants):
                    rej = {r: 0 for r in ROUTES}
                    pv: Dict[str, List[float]] = {r: [] for r in ROUTES}
                    for r in range(runs):
                        first = (zi * runs + r) << 32  # disjoint counter ranges per (size, run)
                        w = bp.sample_bug(n, None if v == "none" else v, seed=v_seeds[v], first_index=first,
                                          threads=ctx.threads)
                        ref = bp.sample(n, seed=ref_seed, first_index=first, threads=ctx.threads)
                        c = est.direction_gof(w.directions, cells=cells, alpha=alpha)
                        k = mcstat.ks_test(w.keys.astype(float), ref.keys.astype(float), weight="canner", alpha=alpha,
                                           n_sim=n_sim, seed=k_seed, cache=cache, threads=ctx.threads, critical=False)
                        for route, t in (("chisq", c), ("ks", k)):
                            rej[route] += bool(t.reject)
                            pv[route].append(float(t.pvalue))
                        if r == 0 and zi == len(sizes) - 1:
                            examples[v] = (c, k)
                        bar.update(step_cost(n, j == r == 0))  # the K-S null is simulated once per size
                    row["variants"][v] = {route: dict(**rate_summary(rej[route], runs, alpha),
                                                      median_pvalue=float(np.median(pv[route])))
                                          for route in ROUTES}
                rows.append(row)
        summary = {v: {route: dict(detected_from=_detected_from(rows, v, route),
                                   rate_at_largest=rows[-1]["variants"][v][route]["rate"]) for route in ROUTES}
                   for v in bugs}
        size_check = {route: rate_summary(sum(r["variants"]["none"][route]["rejections"] for r in rows),
                                          sum(r["variants"]["none"][route]["tests"] for r in rows), alpha)
                      for route in ROUTES}
        cells_info = [dict(depth=d, cells=2 ** d, prob_min=float(c.prob.min()), prob_max=float(c.prob.max()),
                           sum_minus_one=float(c.prob.sum() - 1.0), cubature_error=c.err)
                      for d, c in sorted(cells_by_depth.items())]
        res = dict(name=name, model=sc.brdf(name)["model"], seeds=dict(reference=ref_seed, ks=k_seed, **v_seeds),
                   sizes=rows, summary=summary, size_check=size_check, cells=cells_info)
        _print(ctx, res, variants, examples, runs, alpha)
        out["brdfs"].append(res)
    return out


def _print(ctx: Context, res: Dict[str, Any], variants: List[str], examples, runs: int, alpha: float) -> None:
    n_last = res["sizes"][-1]["n"]
    for v in variants[1:]:
        if v in examples:
            c, k = examples[v]
            ctx.block(c.format(f"cell counts of {res['name']} with bug {v} (n = {n_last}, run 0)"))
            ctx.block(k.format(f"keys with bug {v}", "keys of the correct sampler"))
    for c in res["cells"]:
        ctx.print(f"cells at depth {c['depth']}: {c['cells']} cells, probabilities {c['prob_min']:.4g}.."
                  f"{c['prob_max']:.4g}, sum - 1 = {c['sum_minus_one']:.2g} (cubature error estimate "
                  f"{c['cubature_error']:.2g})")
    ctx.print(f"\nrejections in {runs} runs, chi-squared / K-S:")
    ctx.print(f"{'n':>8} {'depth':>5}" + "".join(f"{('no bug' if v == 'none' else v):>16}" for v in variants))
    for row in res["sizes"]:
        ctx.print(f"{row['n']:>8} {row['depth']:>5}" + "".join(
            f"{row['variants'][v]['chisq']['rejections']:>9}/{row['variants'][v]['ks']['rejections']:<6}"
            for v in variants))
    for route in ROUTES:
        s = res["size_check"][route]
        ctx.print(f"size check, {ROUTE_NAMES[route]}: correct sampler rejected {s['rejections']}/{s['tests']} = "
                  f"{s['rate']:.4f} [{s['ci95'][0]:.4f}, {s['ci95'][1]:.4f}]; binomial test of rate = alpha: "
                  f"p = {s['binom_pvalue']:.3g}")


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    for b in res["brdfs"]:
        parts = []
        for v in res["bugs"]:
            s = b["summary"][v]
            d = {route: s[route]["detected_from"] for route in ROUTES}
            txt = {route: (f"from n = {d[route]}" if d[route] is not None else
                           f"not reliably ({s[route]['rate_at_largest']:.0%} at n = {b['sizes'][-1]['n']})")
                   for route in ROUTES}
            if d["chisq"] is not None and (d["ks"] is None or d["chisq"] < d["ks"]):
                lead = "chi-squared first"
            elif d["ks"] is not None and (d["chisq"] is None or d["ks"] < d["chisq"]):
                lead = "K-S first"
            elif d["ks"] is None:
                lead = "neither reliably"
            else:
                lead = "both at the same size"
            parts.append(f"{v}: chi-squared {txt['chisq']}, K-S {txt['ks']} ({lead})")
        sz = b["size_check"]
        size = ", ".join(f"{ROUTE_NAMES[r]} {sz[r]['rejections']}/{sz[r]['tests']} (binomial p = "
                         f"{sz[r]['binom_pvalue']:.3g})" for r in ROUTES)
        out.append(f"3.2+ {b['name']}: planted sampler bugs detected (rejected in >= {DETECTED:.0%} of runs at "
                   f"alpha = {res['alpha']:g}) " + "; ".join(parts) + f". Correct sampler rejected: {size}.")
    return out
