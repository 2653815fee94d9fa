"""Calibration of mcstat.image.compare's adjustments on null renders with
wide reconstruction filters (report only: writes
bench/RESULTS_image_calibration.md, asserts nothing).

A reconstruction filter wider than a pixel splats each sample into several
pixels, so neighbouring pixels' noise (and their Welch tests) are
correlated: positively under a Gaussian, with negative correlations where a
filter has negative lobes (Lanczos), which is outside the positive
dependence (PRDS) that Benjamini-Hochberg's guarantee assumes.  BY and
e-BH hold under any dependence.  Here every comparison is a null one: the
reference and the candidate come from the same renderer with the same
settings, at disjoint seeds; the rate of comparisons with at least one
discovery at alpha = 0.05 is what each method's guarantee bounds (under the
global null, FDR = P(any discovery)).

Scene: Mitsuba 3's Cornell box (mi.cornell_box(), path tracer, max depth
8), variant llvm_ad_rgb (after the first kernel compile one render costs
~12 ms of CPU), 32 x 32 pixels, 4 spp, luminance.  Comparison i of a
filter uses seeds base + 2ki .. base + 2ki + k - 1 for the reference and
the next k for the candidate (k = 8): every render belongs to exactly one
comparison, so the comparisons are independent and the Clopper-Pearson
intervals apply.  base differs between filters (so no two filters share a
seed).  Renders are cached under bench/out/image_calibration (luminance,
float32).

    .venv/bin/python bench/bench_image_calibration.py [--comparisons 800]
    .venv/bin/python bench/bench_image_calibration.py --export-gate   # after it: the gate's .npz
"""
import argparse
import os
import platform
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, ".."))
sys.path.insert(0, os.path.join(ROOT, "examples", "mitsuba"))
import image_backends as ib  # noqa: E402  (sets DRJIT_LIBLLVM_PATH to libllvm19 first)
import mitsuba as mi  # noqa: E402

import mcstat  # noqa: E402
import mcstat.image  # noqa: E402

VARIANT = "llvm_ad_rgb"
SIZE = 32
SPP = 4
K = 8
ALPHA = 0.05
METHODS = ("BH", "BY", "e-BH")
# name -> (Mitsuba rfilter, seed base)
FILTERS = {
    "box": ({"type": "box"}, 0),
    "gaussian": ({"type": "gaussian", "stddev": 1.0}, 10_000_000),
    "lanczos": ({"type": "lanczos", "lobes": 3}, 20_000_000),
}
FILTER_TEXT = {
    "box": "box (each sample in one pixel: independent pixels, the control)",
    "gaussian": "gaussian, stddev 1 pixel (radius 4): positive correlations",
    "lanczos": "lanczos, 3 lobes (radius 3, negative lobes): correlations of both signs",
}
OUT = os.path.join(HERE, "out", "image_calibration")
CHUNK = 2 * K * 50  # renders per cache file: 50 comparisons


def renders(name, n_comp):
    """(2 K n_comp, SIZE, SIZE) float32 luminance of the filter's seeds, from
    the cache where it has them.  Returns (stack, CPU seconds spent rendering)."""
    rfilter, base = FILTERS[name]
    os.makedirs(OUT, exist_ok=True)
    scene = None
    parts, cpu = [], 0.0
    for start in range(0, 2 * K * n_comp, CHUNK):
        stop = min(start + CHUNK, 2 * K * n_comp)
        path = os.path.join(OUT, f"{name}_{SIZE}px_{SPP}spp_seeds{base + start}-{base + stop - 1}.npy")
        if os.path.exists(path):
            parts.append(np.load(path))
            continue
        if scene is None:
            if mi.variant() != VARIANT:
                mi.set_variant(VARIANT)
            scene = mi.load_dict(ib.scene_dict(size=SIZE, rfilter=rfilter))
        c0 = time.process_time()
        y = np.stack([ib.luminance(np.array(mi.render(scene, spp=SPP, seed=base + s))).astype(np.float32)
                      for s in range(start, stop)])
        cpu += time.process_time() - c0
        np.save(path, y)
        parts.append(y)
    return np.concatenate(parts), cpu


def clopper_pearson(x, n, level=0.95):
    from scipy import stats

    a = (1 - level) / 2
    lo = stats.beta.ppf(a, x, n - x + 1) if x > 0 else 0.0
    hi = stats.beta.isf(a, x + 1, n - x) if x < n else 1.0
    return float(lo), float(hi)


def neighbour_correlations(y, n_comp, lags=(1, 2, 3)):
    """Correlation of the pixel noise at horizontal and vertical lags: the
    deviations from each side's own mean (k - 1 degrees of freedom per side),
    standardised by each pixel's pooled variance, averaged over pixel pairs."""
    s = y.reshape(2 * n_comp, K, SIZE, SIZE).astype(np.float64)
    r = s - s.mean(axis=1, keepdims=True)
    dof = 2 * n_comp * (K - 1)
    var = (r * r).sum(axis=(0, 1)) / dof
    ok = var > 0
    z = np.where(ok, r / np.sqrt(np.where(ok, var, 1.0)), 0.0)
    out = {}
    for lag in lags:
        h = (z[..., :, lag:] * z[..., :, :-lag]).sum(axis=(0, 1)) / dof
        hm = ok[:, lag:] & ok[:, :-lag]
        v = (z[..., lag:, :] * z[..., :-lag, :]).sum(axis=(0, 1)) / dof
        vm = ok[lag:, :] & ok[:-lag, :]
        out[lag] = (float(h[hm].mean()), float(v[vm].mean()))
    return out


def t_correlation(tstats):
    """Mean correlation, over horizontally adjacent pixel pairs, of the two
    pixels' Welch t statistics across the (independent) comparisons."""
    t = np.asarray(tstats)
    ok = np.all(np.isfinite(t), axis=0)
    t = np.where(ok, t, 0.0)
    t = (t - t.mean(axis=0)) / np.where(ok, t.std(axis=0), 1.0)
    c = (t[:, :, 1:] * t[:, :, :-1]).mean(axis=0)
    return float(c[ok[:, 1:] & ok[:, :-1]].mean())


def run_filter(name, n_comp):
    y, cpu = renders(name, n_comp)
    any_disc = {m: 0 for m in METHODS}
    disc_counts = {m: [] for m in METHODS}
    raw = {0.05: [], 0.01: [], 0.001: []}
    tstats, minp = [], []
    c0 = time.process_time()
    for i in range(n_comp):
        ref = y[2 * K * i: 2 * K * i + K]
        cand = y[2 * K * i + K: 2 * K * (i + 1)]
        for m in METHODS:
            res = mcstat.image.compare(ref, cand, alpha=ALPHA, method=m, seed_axis=0)
            d = int(np.count_nonzero(res.decision))
            any_disc[m] += d > 0
            disc_counts[m].append(d)
            if m == "BH":
                p = res.pvalue[res.tested]
                for a in raw:
                    raw[a].append(float(np.mean(p <= a)))
                tstats.append(res.statistic[..., 0])
                minp.append(float(res.padjusted[res.tested].min()))
        tested = int(res.tested.sum())
    return {"name": name, "n": n_comp, "render_cpu": cpu, "compare_cpu": time.process_time() - c0,
            "tested": tested, "any": any_disc, "counts": disc_counts, "raw": raw,
            "corr": neighbour_correlations(y, n_comp), "tcorr": t_correlation(tstats), "minp": minp}


def fmt_rate(x, n):
    lo, hi = clopper_pearson(x, n)
    return f"{x}/{n} = {x / n:.3f} [{lo:.3f}, {hi:.3f}]"


def mean_ci(v):
    v = np.asarray(v)
    se = v.std(ddof=1) / np.sqrt(len(v))
    return f"{v.mean():.5f} ± {1.96 * se:.5f}"


def write_results(results, path, wall, args):
    load = os.getloadavg()
    lines = [
        "# Calibration of the per-pixel adjustments on filtered null renders",
        "",
        "`bench/bench_image_calibration.py` (report only; not part of `make bench`): "
        "`mcstat.image.compare` (Welch's test per pixel, luminance) on null comparisons - reference and "
        "candidate rendered by the same renderer with the same settings at disjoint seeds - and the rate of "
        f"comparisons with at least one discovery at alpha = {ALPHA} after BH, BY and e-BH.  Under the "
        "global null every discovery is false, so that rate is the FDR, which each method bounds by alpha: "
        "BH for independent or positively dependent (PRDS) tests, BY and e-BH under any dependence.",
        "",
        f"Scene: Mitsuba 3.9.1 `mi.cornell_box()` (path tracer, max depth 8), variant {VARIANT} "
        f"(libLLVM {ib.loaded_libllvm()}), {SIZE} x {SIZE} pixels, {SPP} spp, luminance "
        f"({SIZE * SIZE} tests per comparison, of which those constant in both sides - pixels that see no "
        "light - are not tested).  "
        f"Seeds: comparison i of a filter takes seeds base + {2 * K}i .. base + {2 * K}i + {K - 1} as the "
        f"reference and the next {K} as the candidate ({K} + {K} seeds); every render belongs to one "
        "comparison only, so the comparisons are independent (no pool reused) and the Clopper-Pearson "
        "intervals (95%) apply; each filter has its own seed base (0, 1e7, 2e7), so no two filters share a "
        "seed.  Renders cached under bench/out/image_calibration (git-ignored).",
        "",
        f"Machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores shared with other "
        f"jobs (load average {load[0]:.1f} at the end); whole run {wall / 60:.1f} min wall"
        + (" (renders from the cache)" if all(r["render_cpu"] == 0 for r in results) else "") + ".  "
        f"Command: `.venv/bin/python bench/bench_image_calibration.py --comparisons {args.comparisons}"
        + (f" --spp {args.spp}" if args.spp != 4 else "") + "`.",
        "",
        "## Dependence induced by the filter",
        "",
        "Noise correlation: the deviations of each render from its side's mean, standardised by the "
        "pixel's pooled standard deviation, correlated with the pixel at the given lag (horizontal / "
        "vertical), averaged over pixel pairs.  t correlation: the correlation, across the comparisons, of "
        "horizontally adjacent pixels' Welch t statistics (the dependence among the tests themselves).",
        "",
        "| filter | noise lag 1 | noise lag 2 | noise lag 3 | t statistics, lag 1 |",
        "|---|---|---|---|---|",
    ]
    for r in results:
        c = r["corr"]
        lags = " | ".join(f"{c[lag][0]:+.3f} / {c[lag][1]:+.3f}" for lag in (1, 2, 3))
        lines.append(f"| {FILTER_TEXT[r['name']]} | {lags} | {r['tcorr']:+.3f} |")
    lines += [
        "",
        "## Per-pixel false rejections without adjustment",
        "",
        "The fraction of tested pixels with p <= level, averaged over the comparisons (± 1.96 standard "
        "errors across comparisons; the pixels of one comparison are correlated, so the comparisons are "
        "the independent units).  Each should be about its level; the tail (0.001) is what the "
        "adjustments' thresholds (alpha/m ~ 5e-5 for BH's first discovery) lean on, and Welch's t with "
        f"{K} + {K} seeds of skewed {SPP}-spp pixels is least accurate there.",
        "",
        "| filter | tested pixels | p <= 0.05 | p <= 0.01 | p <= 0.001 |",
        "|---|---|---|---|---|",
    ]
    for r in results:
        lines.append(f"| {r['name']} | {r['tested']} | {mean_ci(r['raw'][0.05])} | {mean_ci(r['raw'][0.01])} | "
                     f"{mean_ci(r['raw'][0.001])} |")
    lines += [
        "",
        f"## Comparisons with at least one discovery (alpha = {ALPHA})",
        "",
        "Rate with its 95% Clopper-Pearson interval; each guarantee bounds it by 0.05.  Discoveries: the "
        "total number of pixels rejected over all comparisons (false, every one).",
        "",
        "| filter | comparisons | BH | BY | e-BH | discoveries BH / BY / e-BH "
        "| smallest BH-adjusted p (median over comparisons) |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in results:
        n = r["n"]
        lines.append(f"| {r['name']} | {n} | " + " | ".join(fmt_rate(r["any"][m], n) for m in METHODS)
                     + " | " + " / ".join(str(int(np.sum(r["counts"][m]))) for m in METHODS)
                     + f" | {np.median(r['minp']):.3f} |")
    cpu = "; ".join(f"{r['name']} renders {r['render_cpu']:.0f} s, comparisons {r['compare_cpu']:.0f} s"
                    for r in results)
    lines += ["", f"CPU time: {cpu}.", ""]
    with open(path, "w") as f:
        f.write("\n".join(lines))


GATE_DATA = os.path.join(ROOT, "examples", "mitsuba", "data", "filtered_null_renders.npz")


def export_gate(n_comp, per_filter=2, filters=("gaussian", "lanczos")):
    """Writes null comparisons of the cached renders where BH made a false
    discovery and BY and e-BH did not, with margins (BH-adjusted p <= 0.03,
    BY and e-BH >= 0.2, so that the last bits of a p-value cannot change a
    decision), the first `per_filter` such of each filter, to GATE_DATA for
    examples/mitsuba/test_filtered_null.py: luminance float32, key <filter>
    of shape (comparisons, 2 K, SIZE, SIZE), reference first."""
    out = {}
    for name in filters:
        y, _ = renders(name, n_comp)
        pick = []
        for i in range(n_comp):
            ref = y[2 * K * i: 2 * K * i + K]
            cand = y[2 * K * i + K: 2 * K * (i + 1)]
            p = {m: float(mcstat.image.compare(ref, cand, alpha=ALPHA, method=m, seed_axis=0).padjusted.min())
                 for m in METHODS}
            if p["BH"] <= 0.03 and p["BY"] >= 0.2 and p["e-BH"] >= 0.2:
                pick.append(i)
                print(name, "comparison", i, "smallest adjusted p", p)
                if len(pick) == per_filter:
                    break
        out[name] = np.stack([y[2 * K * i: 2 * K * (i + 1)] for i in pick])
        out[name + "_seeds"] = np.array([FILTERS[name][1] + 2 * K * i for i in pick], dtype=np.int64)
    os.makedirs(os.path.dirname(GATE_DATA), exist_ok=True)
    np.savez_compressed(GATE_DATA, **out)
    print("wrote", GATE_DATA, os.path.getsize(GATE_DATA), "bytes")


def main():
    global SPP
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--comparisons", type=int, default=800, help="null comparisons per filter")
    ap.add_argument("--filters", default=",".join(FILTERS))
    ap.add_argument("--spp", type=int, default=SPP, help="samples per pixel")
    ap.add_argument("--out", default=os.path.join(HERE, "RESULTS_image_calibration.md"))
    ap.add_argument("--export-gate", action="store_true",
                    help="only write the gate's data (the hardest null comparisons of the cached renders)")
    args = ap.parse_args()
    SPP = args.spp
    if args.export_gate:
        export_gate(args.comparisons)
        return
    t0 = time.time()
    results = []
    for name in args.filters.split(","):
        r = run_filter(name, args.comparisons)
        results.append(r)
        print(name, {m: r["any"][m] for m in METHODS}, "raw@0.05", np.mean(r["raw"][0.05]),
              "corr", r["corr"][1], "tcorr", round(r["tcorr"], 3), f"{time.time() - t0:.0f} s", flush=True)
    write_results(results, args.out, time.time() - t0, args)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
