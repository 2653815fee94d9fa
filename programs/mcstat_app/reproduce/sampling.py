# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Section 3.2: does a BRDF's sampler draw from f cos / albedo?

For each BRDF (at its outgoing direction) and each sample size n, ``runs``
times: n directions from the model's own sampler and n from the exact
rejection sampler of f cos / albedo (libmcest), compared by the two-sample
Kolmogorov-Smirnov test with Canner's weight on the directions' Morton keys
(polar coordinate most significant; the paper linearises the hemisphere
the same way).  The p-value is exact where the lattice recursion is cheap
(up to about 2800 + 2800) and simulated beyond, sharing one simulated null
distribution per size (``KSCache``).  The rejection rate against n is the
power curve.

The half-vector samplers put some directions below the horizon, where
f = 0.  With ``below_horizon = "discard"`` (the default) those are dropped
before the test, as a renderer would give them weight 0, so the test is
about the shape of the distribution on the upper hemisphere; the fraction
dropped is reported on its own (it alone shows that the sampler does not
draw from f cos).  ``"keep"`` tests the sampler's output as drawn.

Figure 6: 2-D histograms of (polar, azimuthal) angle of ``histogram_size``
directions from each sampler, side by side.
"""
from __future__ import annotations

from typing import Any, Dict, List, Tuple

import numpy as np

import mcstat
from mcstat import estimators as est
from . import cost
from .binomial import clopper_pearson, rate_summary
from .context import Context
from .plan import Plan
from .results import columns, decision_counts

HIST_BINS = (48, 96)  # polar angle x azimuth, over the window holding the lobes


def sampler_directions(bp: Any, n: int, seed: int, first: int, keep: bool, threads) -> Tuple[np.ndarray, int, int]:
    """n directions of the BRDF's own sampler: (directions, drawn, below).

    With keep=False, directions below the horizon are dropped and more are
    drawn (consecutive indices from ``first``) until n remain."""
    if keep:
        s = bp.sample(n, seed=seed, first_index=first, threads=threads)
        return s.directions, n, int((s.directions[:, 2] <= 0).sum())
    parts: List[np.ndarray] = []
    got = drawn = below = 0
    while got < n:
        m = int((n - got) * 1.25) + 16
        s = bp.sample(m, seed=seed, first_index=first + drawn, threads=threads)
        up = s.directions[:, 2] > 0
        parts.append(s.directions[up])
        got += int(up.sum())
        drawn += m
        below += int((~up).sum())
    return np.concatenate(parts)[:n], drawn, below


def _angles(w: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    theta = np.degrees(np.arccos(np.clip(w[:, 2], -1.0, 1.0)))
    phi = np.degrees(np.arctan2(w[:, 1], w[:, 0])) % 360.0
    return theta, phi


def histogram_window(*samples: np.ndarray) -> Dict[str, float]:
    """The (polar, azimuth) window, in degrees, holding 99.8% of both samples
    plus a margin: figure 6 zooms on the lobes.  Azimuths are measured from
    the samples' circular mean, so a lobe across phi = 0 stays whole."""
    theta, phi = _angles(np.concatenate(samples))
    c = float(np.degrees(np.arctan2(np.sin(np.radians(phi)).mean(), np.cos(np.radians(phi)).mean())) % 360.0)
    d = (phi - c + 180.0) % 360.0 - 180.0
    t0, t1 = np.quantile(theta, [0.001, 0.999])
    d0, d1 = np.quantile(d, [0.001, 0.999])
    mt, md = 0.1 * (t1 - t0) + 0.5, 0.1 * (d1 - d0) + 0.5
    return dict(theta=[float(max(0.0, t0 - mt)), float(min(90.0, t1 + mt))],
                phi_center=c, dphi=[float(max(-180.0, d0 - md)), float(min(180.0, d1 + md))])


def angles_histogram(w: np.ndarray, win: Dict[str, float]) -> np.ndarray:
    theta, phi = _angles(w)
    d = (phi - win["phi_center"] + 180.0) % 360.0 - 180.0
    h, _, _ = np.histogram2d(theta, d, bins=HIST_BINS, range=[win["theta"], win["dphi"]])
    return h.astype(np.int64)


def verdict(rate: Dict[str, Any]) -> str:
    """'passes': rejections consistent with alpha (exact binomial test, p >= 0.01);
    'fails': rejected in more than half of the runs; 'sometimes' in between."""
    if rate["rate"] > 0.5:
        return "fails"
    return "passes" if rate["binom_pvalue"] >= 0.01 else "sometimes"


def _describe(b: Dict[str, Any]) -> str:
    if b["model"] == "ward":
        d, s, ax, ay = b["params"]
        p = f"Ward, rho_d {d:g}, rho_s {s:g}, alpha {ax:g} x {ay:g}"
    else:
        d, s, nu, nv = b["params"]
        p = f"Ashikhmin-Shirley, Rd {d:g}, Rs {s:g}, exponents {nu:g} x {nv:g}"
    wo = b["wo"]
    th, ph = np.degrees(np.arccos(wo[2])), np.degrees(np.arctan2(wo[1], wo[0])) % 360
    return f"{p}; outgoing direction theta {th:.4g}, phi {ph:.4g} degrees"


def _run_cost(n: int, n_sim: int, first: bool) -> float:
    """Estimated seconds of one run at size n (cost.py): both samples, and a
    K-S test that simulates the null only in the first run at that size."""
    return n * cost.DIRECTION_PAIR + cost.ks(n, n, n_sim, simulate_null=first)


def _histogram_cost(hs: int) -> float:
    return hs * (cost.DIRECTION_PAIR + 2 * cost.DIRECTION)


def run(ctx: Context, plan: Plan) -> Dict[str, Any]:
    sc, p = plan.scene, plan.params["sampling"]
    alpha, sizes, runs, n_sim = p["alpha"], p["sizes"], p["runs"], p["n_sim"]
    keep = p["below_horizon"] == "keep"
    out: Dict[str, Any] = dict(section="3.2", alpha=alpha, sizes=sizes, runs=runs, n_sim=n_sim, weight="canner",
                               alternative="two-sided", below_horizon=p["below_horizon"],
                               histogram_size=p["histogram_size"], histogram_bins=list(HIST_BINS), brdfs=[])
    names = [b["name"] for b in sc.brdfs]
    for name in plan.brdfs_for("sampling"):
        si = names.index(name)
        b = sc.brdf(name)
        bp = sc.make_brdf(name).plan(b["wo"])
        s_seed = ctx.stream("sampling", si, 0, label=f"sampling/{name}/sampler")
        x_seed = ctx.stream("sampling", si, 1, label=f"sampling/{name}/exact sampler")
        k_seed = ctx.stream("sampling", si, 2, label=f"sampling/{name}/K-S simulation")
        cache = mcstat.KSCache(seed=k_seed)
        ctx.print(f"\n== 3.2 BRDF sampling: {name} ({_describe(b)})")
        ctx.print(f"two-sample K-S tests with Canner's weight on Morton keys, sampler (x) against exact rejection "
                  f"sampling (y), two-sided, alpha = {alpha:g}, {runs} runs per size")
        rows = []
        hs = p["histogram_size"]
        with ctx.bar(sum(_run_cost(n, n_sim, r == 0) for n in sizes for r in range(runs)) + _histogram_cost(hs),
                     f"3.2 {name}") as bar:
            for zi, n in enumerate(sizes):
                tests = []
                for r in range(runs):
                    first = (zi * runs + r) << 32  # disjoint counter ranges per (size, run)
                    w, _, _ = sampler_directions(bp, n, s_seed, first, keep, ctx.threads)
                    x = bp.sample_exact(n, seed=x_seed, first_index=first, threads=ctx.threads)
                    keys_a = est.direction_keys(w).astype(float)
                    t = mcstat.ks_test(keys_a, x.keys.astype(float), weight="canner", alpha=alpha, n_sim=n_sim,
                                       seed=k_seed, cache=cache, threads=ctx.threads)
                    tests.append(t)
                    bar.update(_run_cost(n, n_sim, r == 0))  # the first run at a size simulates the K-S null
                c = decision_counts(t.decision for t in tests)
                rejections = sum(t.reject for t in tests)
                pv = np.array([t.pvalue for t in tests])
                # a simulated p-value of 1/(n_sim + 1) means no replicate reached the statistic: p is below it
                floor = all(t.pvalue_method == "simulate" and t.pvalue * (t.n_sim + 1) < 1.5 for t in tests)
                rate = rate_summary(rejections, runs, alpha)
                rows.append(dict(n=n, counts=c, **rate, median_pvalue=float(np.median(pv)), pvalue_floor=floor,
                                 pvalue_method=sorted({t.pvalue_method for t in tests}), verdict=verdict(rate),
                                 results=columns(tests)))
                if zi in (0, len(sizes) - 1):
                    ctx.block(tests[0].format(f"sampler keys (n = {n}, run 0)", "rejection keys"))
            # the fraction below the horizon, and figure 6, from a further index range
            hfirst = (len(sizes) * runs) << 32
            raw = bp.sample(hs, seed=s_seed, first_index=hfirst, threads=ctx.threads)
            below = int((raw.directions[:, 2] <= 0).sum())
            w, _, _ = sampler_directions(bp, hs, s_seed, hfirst, keep, ctx.threads)
            xw = bp.sample_exact(hs, seed=x_seed, first_index=hfirst, threads=ctx.threads)
            win = histogram_window(w, xw.directions)
            bar.update(_histogram_cost(hs))
        res = dict(name=name, model=b["model"], params=list(b["params"]), wo=b["wo"], description=_describe(b),
                   seeds=dict(sampler=s_seed, exact=x_seed, ks=k_seed),
                   below_horizon=dict(count=below, of=hs, fraction=below / hs, ci95=list(clopper_pearson(below, hs))),
                   sizes=rows, histogram=dict(window=win, sampler=angles_histogram(w, win),
                                              exact=angles_histogram(xw.directions, win)),
                   acceptance_exact=hs / xw.trials)
        ctx.print(f"{'n':>8}  {'rejected':>9}  {'rate [95% CI]':>22}  {'median p':>9}  p-value   verdict")
        for row in rows:
            ctx.print(f"{row['n']:>8}  {row['rejections']:>4}/{row['tests']:<4}  {row['rate']:>6.2f} "
                      f"[{row['ci95'][0]:.2f}, {row['ci95'][1]:.2f}]  "
                      f"{('<= ' if row['pvalue_floor'] else '') + format(row['median_pvalue'], '.3g'):>9}  "
                      f"{'/'.join(row['pvalue_method']):8}  {row['verdict']}")
        bh = res["below_horizon"]
        ctx.print(f"sampler directions below the horizon (f = 0 there): {below}/{hs} = {bh['fraction']:.4f} "
                  f"[{bh['ci95'][0]:.4f}, {bh['ci95'][1]:.4f}]; "
                  + ("kept in the tests" if keep else "discarded before the tests"))
        out["brdfs"].append(res)
    return out


def findings(res: Dict[str, Any]) -> List[str]:
    words = {"passes": "passes (rejections consistent with alpha)",
             "sometimes": "is rejected more often than alpha, but in at most half of the runs,",
             "fails": "fails (rejected in most runs)"}
    out = []
    for b in res["brdfs"]:
        groups: List[List[Dict[str, Any]]] = []
        for r in b["sizes"]:
            if groups and groups[-1][0]["verdict"] == r["verdict"]:
                groups[-1].append(r)
            else:
                groups.append([r])
        parts = []
        for g in groups:
            sizes = (f"n = {g[0]['n']}" if len(g) == 1 else
                     f"every size from n = {g[0]['n']} to {g[-1]['n']}")
            counts = ", ".join(f"{r['rejections']}/{r['tests']}" for r in g)
            parts.append(f"{words[g[0]['verdict']]} at {sizes} ({counts})")
        out.append(f"3.2 {b['name']}: the sampler " + "; ".join(parts) + f" - K-S with Canner's weight at "
                   f"alpha = {res['alpha']:g}, {res['runs']} runs per size.")
    return out
