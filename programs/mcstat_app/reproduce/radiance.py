# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Section 3.3: is BRDF sampling, weighted by its true density, unbiased?

For each BRDF, at ``directions`` outgoing directions spread uniformly over
the hemisphere (z stratified, (d + 0.5)/D, azimuth stepped by the golden
angle: a deterministic, even cover), ``m`` primary estimates of the
reflected radiance under libmcest's analytic environment from each of

- BRDF sampling, each direction weighted by f cos / p with p the density
  the sampler really draws from (Walter's for Ward: ERRATA 9), and
- exact rejection sampling of f cos / albedo (albedo by cubature to a
  relative 1e-5: that is the rejection estimator's only bias, far below
  what m estimates resolve),

compared by Welch's test at alpha.  If both are unbiased, each test rejects
with probability about alpha, and the number of rejections is binomial:
an exact binomial test says whether the fraction of equal means is
consistent with alpha (the paper's 98.6% of 1000 left that open).
Primary estimates are skewed, so Welch's level is only approximately alpha
at m = 50; the test would flag a large departure.
"""
from __future__ import annotations

import math
from typing import Any, Dict, List

import numpy as np

import mcstat
from .binomial import binom_test, format_binom
from .context import Context
from .plan import Plan
from .results import batch_columns, decision_counts

GOLDEN_ANGLE = math.pi * (3.0 - math.sqrt(5.0))
ALBEDO_TOL = 1e-5


def directions(D: int) -> np.ndarray:
    d = np.arange(D)
    z = (d + 0.5) / D
    phi = GOLDEN_ANGLE * d
    s = np.sqrt(1.0 - z * z)
    return np.stack([s * np.cos(phi), s * np.sin(phi), z], axis=1)


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["radiance"]
    alpha, D, m = p["alpha"], p["directions"], p["m"]
    out: Dict[str, Any] = dict(section="3.3", alpha=alpha, directions=D, m=m, albedo_rel_tol=ALBEDO_TOL,
                               environment="libmcest's analytic environment (mcest.h)", brdfs=[])
    names = [b["name"] for b in sc.brdfs]
    W = directions(D)
    for name in plan.brdfs_for("radiance"):
        si = names.index(name)
        brdf = sc.make_brdf(name)
        s1 = ctx.stream("radiance", si, 0, label=f"radiance/{name}/sampling")
        s2 = ctx.stream("radiance", si, 1, label=f"radiance/{name}/rejection")
        A = np.empty((D, m))
        B = np.empty((D, m))
        short = 0
        worst = 0.0
        with ctx.bar(D, f"3.3 {name}") as bar:
            for d in range(D):
                bp = brdf.plan(W[d])
                bp.compute_albedo(ALBEDO_TOL, strict=False)
                rel = bp.albedo_err / bp.albedo
                worst = max(worst, rel)
                short += rel > ALBEDO_TOL
                A[d] = bp.reflected_radiance("sampling", m, seed=s1, first_index=d * m, threads=ctx.threads)
                B[d] = bp.reflected_radiance("rejection", m, seed=s2, first_index=d * m, threads=ctx.threads)
                bar.update()
        bt = mcstat.t_test(A, B, alpha=alpha, on_error="nan")
        c = decision_counts(bt.decision)
        ok = D - c["failed"]
        rejections = ok - c["equal"]
        binom = binom_test(rejections, ok, alpha) if ok else None
        ctx.print(f"\n== 3.3 Reflected radiance off {name}: BRDF sampling (x) against rejection sampling (y), "
                  f"Welch's t test at alpha = {alpha:g}, m = {m} estimates each, {D} outgoing directions")
        ctx.print(f"equal means: {c['equal']}/{ok} = {c['equal'] / max(ok, 1):.2%}; less {c['less']}, "
                  f"greater {c['greater']}" + (f"; {c['failed']} tests failed" if c["failed"] else ""))
        if binom is not None:
            ctx.block(format_binom(binom, f"{rejections} rejections", f"{ok} tests"))
        ctx.print(f"(albedo cubature: worst relative error estimate {worst:.2g}"
                  + (f"; {short} of {D} above {ALBEDO_TOL:g}" if short else "") + ")")
        out["brdfs"].append(dict(name=name, seeds=dict(sampling=s1, rejection=s2), counts=c, tests_ok=ok,
                                 equal_fraction=c["equal"] / max(ok, 1), rejections=rejections, binomial=binom,
                                 albedo_worst_rel_err=worst, albedo_short=short, directions_z=W[:, 2],
                                 results=batch_columns(bt)))
    return out


def findings(res: Dict[str, Any]) -> List[str]:
    out = []
    for b in res["brdfs"]:
        bt = b["binomial"]
        if bt is None:
            out.append(f"3.3 {b['name']}: every test failed.")
            continue
        verdict = ("consistent with alpha" if bt["pvalue"] >= 0.01 else "NOT consistent with alpha")
        out.append(f"3.3 {b['name']}: {b['counts']['equal']}/{b['tests_ok']} = {b['equal_fraction']:.1%} of Welch tests "
                   f"at alpha = {res['alpha']:g} report equal means; rejection rate {bt['estimate']:.4f} "
                   f"[{bt['conf_int'][0]:.4f}, {bt['conf_int'][1]:.4f}], exact binomial test of rate = alpha: "
                   f"p = {bt['pvalue']:.3g}, {verdict}.")
    return out
