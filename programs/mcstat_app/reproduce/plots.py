# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The report's figures (matplotlib, Agg backend: no display needed).

Each function takes the part of results.json it draws and a file path, and
writes one PNG.  Only bookkeeping here: every number drawn was computed by
the studies.
"""
from __future__ import annotations

import functools
import math
from typing import Any, Callable, Dict, List

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.text  # noqa: E402
import numpy as np  # noqa: E402

DECISIONS = ("less", "equal", "greater")

# Every figure is drawn at its printed size: at most the text width of a
# paper page (16 cm), every text at least 7 pt there (legibility_problems;
# tests/python/test_cli.py checks each figure of a report).  The PNGs have
# 200 dpi, enough for print at that size.
TEXT_WIDTH = 6.3  # inches
MIN_PT = 7.0
DPI = 150
# Irradiance of an emitter of radiance L is L times a projected solid angle.
E_UNIT = "units of L sr"
# the report's sizes, within each drawing function only (matplotlib's global settings stay as they are)
STYLE = {"font.size": 8, "axes.titlesize": 8.5, "axes.labelsize": 8, "xtick.labelsize": 7, "ytick.labelsize": 7,
         "legend.fontsize": 7, "figure.titlesize": 9}


def _styled(draw: Callable[..., None]) -> Callable[..., None]:
    @functools.wraps(draw)
    def wrapper(*args: Any, **kw: Any) -> None:
        with plt.rc_context(STYLE):
            draw(*args, **kw)
    return wrapper


def legibility_problems(fig) -> List[str]:
    """What would not be legible in print: a figure wider than the text, a
    text under MIN_PT points, a 2-D histogram (image) without a colour bar."""
    out = []
    w, _ = fig.get_size_inches()
    if w > TEXT_WIDTH + 1e-9:
        out.append(f"{w:.2f} in wide, more than the text width {TEXT_WIDTH} in")
    for t in fig.findobj(matplotlib.text.Text):
        if t.get_visible() and t.get_text().strip() and t.get_fontsize() < MIN_PT:
            out.append(f"text {t.get_text()!r} at {t.get_fontsize():.1f} pt")
    bars = [ax for ax in fig.axes if ax.get_label() == "<colorbar>"]
    for ax in fig.axes:
        if ax.images and not bars:
            out.append(f"an image in {ax.get_title()!r} without a colour bar")
    return out


def _save(fig, path: str) -> None:
    fig.savefig(path, dpi=DPI, bbox_inches="tight", metadata={"Software": None})
    plt.close(fig)


def _grid(n: int, cols: int, height: float, **kw):
    """n panels in rows of at most `cols`, the text width wide; spare axes hidden."""
    rows = (n + cols - 1) // cols
    ncols = min(n, cols)
    fig, axes = plt.subplots(rows, ncols, figsize=(TEXT_WIDTH, height * rows + 0.5), squeeze=False, **kw)
    flat = list(axes.ravel())
    for ax in flat[n:]:
        ax.set_visible(False)
    return fig, flat[:n]


@_styled
def figure4(rec: Dict[str, Any], runs: int, path: str) -> None:
    ests = rec["matrix"]["estimators"]
    n = len(ests)
    fig, axes = plt.subplots(n, n, figsize=(TEXT_WIDTH, min(1.25 * n + 0.9, 8.0)), sharex=True, sharey=True,
                             squeeze=False)
    x = np.arange(3)
    for a, i in enumerate(ests):
        for b, j in enumerate(ests):
            ax = axes[a][b]
            mc = rec["matrix"]["mean"][a][b]
            vc = rec["matrix"]["variance"][a][b]
            ax.bar(x - 0.2, [mc[d] for d in DECISIONS], 0.4, color="tab:red", label="mean (Welch)")
            ax.bar(x + 0.2, [vc[d] for d in DECISIONS], 0.4, color="tab:blue", label="variance (F)")
            ax.set_ylim(0, runs)
            ax.set_xticks(x, ["<", "=", ">"])
            if a == 0:
                ax.set_title(f"y = {j}")
            if b == 0:
                ax.set_ylabel(f"x = {i}: runs")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, frameon=False, bbox_to_anchor=(0.5, -0.02))
    fig.suptitle(f"Figure 4 at {rec['name']}: decisions over {runs} runs (x against y: less, equal, greater)")
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    _save(fig, path)


@_styled
def figure5(rec: Dict[str, Any], path: str) -> None:
    hs = rec["histograms"]
    fig, axes = _grid(len(hs), 2, 2.1)
    for ax, (m, h) in zip(axes, hs.items()):
        edges = np.array(h["edges"])
        counts = np.array(h["counts"])
        w = np.diff(edges)
        ax.bar(edges[:-1], counts, w, align="edge", color="0.6", edgecolor="0.3", linewidth=0.3)
        xs = np.linspace(edges[0], edges[-1], 200)
        if h["sd"] > 0:
            pdf = np.exp(-0.5 * ((xs - h["mean"]) / h["sd"]) ** 2) / (h["sd"] * math.sqrt(2 * math.pi))
            ax.plot(xs, pdf * h["n"] * w.mean(), color="k", lw=1, label="normal, same mean and s.d.")
        if rec["lambert"] is not None:
            ax.axvline(rec["lambert"], color="tab:red", lw=1, ls="--", label="Lambert")
        ax.set_title(f"{m}: s.d. {h['sd']:.3g}")
        ax.set_xlabel(f"secondary estimate of E ({E_UNIT})")
        ax.set_ylabel("count")
    handles, labels = axes[-1].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, frameon=False)
    fig.suptitle(f"Figure 5 at {rec['name']}: secondary estimates (each panel on its own scale)")
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    _save(fig, path)


@_styled
def power_curve(res: Dict[str, Any], path: str) -> None:
    fig, ax = plt.subplots(figsize=(5.5, 3.4))
    for b in res["brdfs"]:
        n = np.array([r["n"] for r in b["sizes"]])
        rate = np.array([r["rate"] for r in b["sizes"]])
        lo = np.array([r["ci95"][0] for r in b["sizes"]])
        hi = np.array([r["ci95"][1] for r in b["sizes"]])
        ax.errorbar(n, rate, yerr=[rate - lo, hi - rate], marker="o", capsize=3, label=b["name"])
    ax.axhline(res["alpha"], color="0.5", ls="--", lw=1, label=f"alpha = {res['alpha']:g}")
    ax.set_xscale("log")
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel("sample size n (directions in each sample)")
    ax.set_ylabel(f"rejection rate ({res['runs']} runs)")
    ax.set_title("K-S (Canner) of each sampler against rejection sampling")
    ax.legend()
    _save(fig, path)


@_styled
def figure6(b: Dict[str, Any], path: str) -> None:
    hs, hx = np.array(b["histogram"]["sampler"]), np.array(b["histogram"]["exact"])
    win = b["histogram"]["window"]
    c = win["phi_center"]
    extent = (c + win["dphi"][0], c + win["dphi"][1], win["theta"][1], win["theta"][0])
    vmax = max(hs.max(), hx.max(), 1)
    fig, axes = plt.subplots(1, 2, figsize=(TEXT_WIDTH, 2.6), sharey=True, layout="constrained")
    for ax, h, title in ((axes[0], hs, "the BRDF's sampler"), (axes[1], hx, "rejection sampling (f cos)")):
        im = ax.imshow(h, cmap="gray", vmin=0, vmax=vmax, extent=extent, aspect="auto", interpolation="nearest")
        ax.set_title(f"{b['name']}: {title}")
        ax.set_xlabel("azimuth (degrees)")
    axes[0].set_ylabel("polar angle (degrees)")
    n = int(hs.sum())
    fig.colorbar(im, ax=list(axes), label=f"directions per bin (of {n})", shrink=0.95)
    _save(fig, path)


@_styled
def radiance_pvalues(b: Dict[str, Any], alpha: float, path: str) -> None:
    p = np.array([v for v in b["results"]["pvalue"] if v is not None])
    fig, ax = plt.subplots(figsize=(5, 3))
    ax.hist(p, bins=20, range=(0, 1), color="0.6", edgecolor="0.3")
    ax.axhline(p.size / 20, color="k", ls="--", lw=1, label="uniform (both unbiased)")
    ax.set_xlabel("Welch p-value")
    ax.set_ylabel("directions")
    ax.set_title(f"3.3 {b['name']}: {b['counts']['equal']}/{b['tests_ok']} equal at alpha = {alpha:g}")
    ax.legend()
    _save(fig, path)


@_styled
def bug_detection(rec: Dict[str, Any], res: Dict[str, Any], path: str) -> None:
    fig, ax = plt.subplots(figsize=(5.5, 3.4))
    budgets = np.array([r["budget"] for r in rec["budgets"]])
    for v in ["none"] + res["bugs"]:
        rate = np.array([r["variants"][v]["rate"] for r in rec["budgets"]])
        lo = np.array([r["variants"][v]["ci95"][0] for r in rec["budgets"]])
        hi = np.array([r["variants"][v]["ci95"][1] for r in rec["budgets"]])
        ax.errorbar(budgets, rate, yerr=[rate - lo, hi - rate], marker="o", capsize=3,
                    label="A, no bug (control)" if v == "none" else v, ls=":" if v == "none" else "-")
    ax.axhline(res["alpha"], color="0.5", ls="--", lw=1, label=f"alpha = {res['alpha']:g}")
    ax.set_xscale("log")
    ax.set_ylim(-0.03, 1.03)
    ax.set_xlabel("primary estimates per sample")
    ax.set_ylabel(f"rejection rate ({res['runs']} runs)")
    ax.set_title(f"3.4 at {rec['name']}: A against {res['trusted']} (Welch)")
    ax.legend()
    _save(fig, path)


@_styled
def error_time(irr: Dict[str, Any], path: str) -> None:
    fig, ax = plt.subplots(figsize=(5.5, 3.8))
    key = "rmse" if irr["lambert"] is not None else "se_estimated"
    for m, e in irr["estimators"].items():
        t = np.array([r["wall_median"] for r in e["rows"]])
        err = np.array([r[key] for r in e["rows"]])
        line = ax.plot(t, err, marker="o", label=m)[0]
        tt = np.geomspace(t.min(), t.max(), 20)
        ax.plot(tt, e["sigma_primary"] * np.sqrt(e["wall_per_primary"] / tt), ls="--", lw=1, color=line.get_color())
    ax.plot([], [], ls="--", color="0.3", label="sigma sqrt(t1/T): slope -1/2")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per estimate T (s)")
    ax.set_ylabel(("RMSE against Lambert" if key == "rmse" else "estimated standard error") + f" ({E_UNIT})")
    ax.set_title(f"Error against run time at {irr['receiver']}")
    ax.legend()
    _save(fig, path)


@_styled
def ks_error_time(ks: Dict[str, Any], path: str) -> None:
    fig, ax = plt.subplots(figsize=(5.5, 3.6))
    t = np.array([r["wall_median"] for r in ks["rows"]])
    err = np.array([r["rms_error"] for r in ks["rows"]])
    pred = np.array([r["predicted_se"] for r in ks["rows"]])
    ax.plot(t, err, marker="o", label="RMS error of the simulated p-value")
    ax.plot(t, pred, ls="--", color="0.3", label="sqrt(p(1-p)/n_sim)")
    for r, x, y in zip(ks["rows"], t, err):
        ax.annotate(f"{r['n_sim']}", (x, y), fontsize=MIN_PT, xytext=(3, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per test (s)")
    ax.set_ylabel("error of the p-value")
    ax.set_title(f"K-S simulation, {ks['size']} + {ks['size']} (exact p = {ks['exact_pvalue']:.3g}); "
                 "labels: replicates")
    ax.legend()
    _save(fig, path)


@_styled
def sampler_bug_power(b: Dict[str, Any], res: Dict[str, Any], path: str) -> None:
    """3.2+: rejection rate against n, chi-squared and K-S, one panel per sampler variant."""
    variants = ["none"] + res["bugs"]
    fig, axes = _grid(len(variants), 3, 1.9, sharey=True)
    n = np.array([r["n"] for r in b["sizes"]])
    for i, (ax, v) in enumerate(zip(axes, variants)):
        for route, label, style in (("chisq", "chi-squared", "-"), ("ks", "K-S (Morton)", "--")):
            s = [r["variants"][v][route] for r in b["sizes"]]
            rate = np.array([x["rate"] for x in s])
            lo = np.array([x["ci95"][0] for x in s])
            hi = np.array([x["ci95"][1] for x in s])
            ax.errorbar(n, rate, yerr=[rate - lo, hi - rate], marker="o", ms=3, capsize=2, ls=style, label=label)
        ax.axhline(res["alpha"], color="0.5", ls=":", lw=1)
        ax.set_xscale("log")
        ax.set_ylim(-0.03, 1.03)
        ax.set_title("no bug (size)" if v == "none" else v)
        ax.set_xlabel("directions n")
        if i % 3 == 0:
            ax.set_ylabel(f"rejection rate ({res['runs']} runs)")
    axes[0].legend()
    fig.suptitle(f"3.2+ {b['name']}: planted sampler bugs, alpha = {res['alpha']:g}")
    fig.tight_layout()
    _save(fig, path)
