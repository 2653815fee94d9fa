# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Beyond the paper: the renderer's test kit on the paper's BRDFs.

Each BRDF of the scene is handed to ``mcstat.check_bsdf`` the way a renderer
hands over its own: a ``sample(wi, u)`` returning directions, weights
f cos / pdf and the pdf it claims, ``eval`` (f cos) and ``pdf``.  One bug of
each class a renderer's users report is planted, about 10% each:

- sampler: libmcest's planted half-vector warp bugs (``roughness``: the lobe
  10% too wide; ``jacobian``; ...), the pdf and weight reported as the
  correct BRDF's at the drawn direction, so that only the distribution of
  the directions is wrong;
- pdf: ``pdf()`` 10% high on half of the sphere, ``sample()`` correct
  (the half on one side of the plane through the normal and the mirror
  direction of wo, so that it holds half the specular lobe);
- eval: ``eval()`` 10% high on that half, the weight still the correct one;
- weight: the weight 10% high on that half.

``runs`` checks per variant, each with its own seed, at level alpha: the
rejection rate of each variant and the routes that rejected, and with no
bug the false-rejection rate, judged by the battery meta-test.  libmcest's
samplers draw from their own counter-based streams, so the adapter seeds
each batch from mcstat's first uniform of it: a check is still a pure
function of its seed.
"""
from __future__ import annotations

from typing import Any, Dict, List

import numpy as np

import mcstat
from .binomial import rate_summary
from .context import Context
from .plan import Plan

FACTOR = 1.1  # the planted pdf, eval and weight bugs: 10% on half of the lobe


def adapter(brdf, wo: np.ndarray, variant: str):
    """sample, eval, pdf of a libmcest BRDF with the fixed direction wo
    (libmcest's wo is the check's wi), with `variant` planted."""
    plan = brdf.plan(wo)
    sampler_bug = variant if variant in ("roughness", "axes_swapped", "phi_half", "jacobian") else None

    def f_cos(x):
        return brdf.eval(x, wo) * np.maximum(x[:, 2], 0.0)

    # the plane through the normal and the mirror direction m cuts the lobe in two
    m = np.array([-wo[0], -wo[1], wo[2]])
    side = np.array([-m[1], m[0], 0.0])
    side = side / np.linalg.norm(side) if np.linalg.norm(side) > 1e-9 else np.array([0.0, 1.0, 0.0])

    def half(x):
        return np.where(x @ side > 0, FACTOR, 1.0)

    def sample(wi, u):
        seed = int(u[0, 0] * 2.0 ** 53)
        if sampler_bug:
            x = plan.sample_bug(len(u), sampler_bug, seed=seed, threads=1)
            x = x.directions if hasattr(x, "directions") else np.asarray(x)
        else:
            x = plan.sample(len(u), seed=seed, threads=1).directions
        p = plan.pdf(x)
        ok = p > 0
        w = np.where(ok, f_cos(x) / np.where(ok, p, 1.0), 0.0)
        if variant == "weight":
            w = w * half(x)
        return x, w, np.where(ok, p, 0.0)

    def pdf(wi, x):
        p = plan.pdf(x)
        return p * half(x) if variant == "pdf" else p

    def eval_(wi, x):
        v = f_cos(x)
        return v * half(x) if variant == "eval" else v

    return sample, eval_, pdf


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["renderer_check"]
    alpha, n, runs, variants = p["alpha"], p["n"], p["runs"], ["none"] + list(p["bugs"])
    out: Dict[str, Any] = dict(section="kit", alpha=alpha, n=n, runs=runs, bugs=list(p["bugs"]), brdfs=[])
    names = [b["name"] for b in sc.brdfs]
    for name in plan.brdfs_for("renderer_check"):
        si = names.index(name)
        brdf, wo = sc.make_brdf(name), np.asarray(sc.brdf(name)["wo"], dtype=float)
        ctx.print(f"\n== renderer check kit: {name}")
        ctx.print(f"mcstat.check_bsdf on the BRDF with one planted bug per class; n = {n}, alpha = {alpha:g}, "
                  f"{runs} runs per variant")
        rows = []
        with ctx.bar(len(variants) * runs, f"kit {name}") as bar:
            for j, v in enumerate(variants):
                seed0 = ctx.stream("renderer_check", si, j, label=f"renderer_check/{name}/{v}")
                s, e, d = adapter(brdf, wo, v)
                rejected, by_route, invalid = 0, {}, 0
                example = None
                for r in range(runs):
                    rep = mcstat.check_bsdf(s, e, d, wo, n=n, alpha=alpha, seed=seed0 + r)
                    rejected += rep.reject
                    invalid += any(x.state == "invalid" for x in rep.routes)
                    for x in rep.routes:
                        if x.reject:
                            by_route[x.name] = by_route.get(x.name, 0) + 1
                    if r == 0:
                        example = str(rep)
                    bar.update()
                rows.append(dict(variant=v, seed=seed0, **rate_summary(rejected, runs, alpha), by_route=by_route,
                                 runs_with_invalid_route=invalid))
                if v != "none" or rejected:
                    ctx.block(f"{name}, {v}, run 0:{example}")
        res = dict(name=name, model=sc.brdf(name)["model"], variants=rows)
        _print(ctx, res, runs)
        out["brdfs"].append(res)
    return out


def _print(ctx: Context, res: Dict[str, Any], runs: int) -> None:
    ctx.print(f"\n{'variant':>14} {'rejected':>9}  routes that rejected")
    for row in res["variants"]:
        routes = ", ".join(f"{k} {c}" for k, c in sorted(row["by_route"].items())) or "-"
        ctx.print(f"{row['variant']:>14} {row['rejections']:>4}/{runs:<4}  {routes}")


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    for b in res["brdfs"]:
        rows = {r["variant"]: r for r in b["variants"]}
        none = rows["none"]
        caught = "; ".join(f"{v} {rows[v]['rejections']}/{rows[v]['tests']}" for v in res["bugs"])
        out.append(f"kit {b['name']}: check_bsdf (n = {res['n']}, alpha = {res['alpha']:g}) rejected the planted "
                   f"bugs {caught}; the correct BRDF {none['rejections']}/{none['tests']} (binomial p = "
                   f"{none['binom_pvalue']:.3g}).")
    return out
