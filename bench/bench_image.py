#!/usr/bin/env python3
"""Per-pixel image comparison (`mcstat image-test`'s pipeline): the per-pixel
Welch tests at 1920 x 1080 against SciPy (bench_image_pixels.py), and at 4K
the time per stage and end to end, with the peak memory of the whole run,
against SciPy's Welch test plus BH adjustment (statsmodels' multipletests and
SciPy's false_discovery_control) on the same data.  --write rewrites
bench/RESULTS_image.md.

Data: 3840 x 2160, 8 seeds per side, float32 .npy stacks (as a renderer
would write them), a smooth image plus unit noise, the candidate 3.0
brighter in a 400 x 300 box; then a second pair without the box (equal
renders: no rejection, the usual outcome in a CI job).  Luminance (8.3
million tests) and RGB (24.9 million tests, each channel tested).
"""
import argparse
import os
import platform
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def make(path_r, path_c, k, h, w, c, rng, bias=3.0):
    yy = np.linspace(0, 1, h, dtype=np.float32)[:, None, None]
    xx = np.linspace(0, 1, w, dtype=np.float32)[None, :, None]
    base = (1.0 + np.sin(6 * xx) * np.float32(0.5) + yy) * np.array([1.0, 0.8, 0.6][:c], dtype=np.float32)
    for path, b in ((path_r, 0.0), (path_c, bias)):
        a = np.empty((k, h, w, c), dtype=np.float32)
        for s in range(k):
            a[s] = base + rng.standard_normal((h, w, c), dtype=np.float32)
        a[:, 900:1200, 1700:2100, :] += np.float32(b)
        np.save(path, a if c > 1 else a[..., 0])
        del a
    # the files written back now, not by the kernel's flusher threads while
    # the timed runs use both CPUs (measured: 1.2 s instead of 0.25 s for the
    # 4K tests stage right after writing the stacks)
    os.sync()


def best(f, reps):
    """The fastest of reps runs and that run's result (its stage timings
    then add up to the time reported)."""
    t_best, out = float("inf"), None
    for _ in range(reps):
        t = time.perf_counter()
        r = f()
        dt = time.perf_counter() - t
        if dt < t_best:
            t_best, out = dt, r
    return t_best, out


PEAK_SCRIPT = """
import json, sys, time
sys.path.insert(0, {here!r})
what, pr, pc, png, channels = sys.argv[1:6]
import numpy as np
t = time.perf_counter()
if what == "idle":
    from mcstat_app import image as mi
elif what == "mcstat":
    from mcstat_app import image as mi
    mi.run(pr, pc, png=png or None, channels=channels)
else:
    from scipy import stats
    from statsmodels.stats.multitest import multipletests
    r = stats.ttest_ind(np.load(pc), np.load(pr), axis=0, equal_var=False)
    multipletests(np.asarray(r.pvalue, dtype=np.float64).ravel(), method="fdr_bh")
# VmHWM, not ru_maxrss: a child's ru_maxrss starts at its parent's peak
# (kept across fork and exec), this process's own high-water mark does not
hwm = [l for l in open("/proc/self/status") if l.startswith("VmHWM:")][0].split()[1]
print(json.dumps({{"seconds": time.perf_counter() - t, "peak": int(hwm) * 1024}}))
"""


def peak(what, pr, pc, png, channels):
    """Wall time and peak resident memory of one whole run in a fresh process."""
    import json
    import subprocess

    out = subprocess.run([sys.executable, "-c", PEAK_SCRIPT.format(here=HERE), what, pr, pc, png or "", channels],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def run_case(tmp, k, h, w, c, reps, rng):
    import mcstat
    from mcstat_app import image as mi  # the command's pipeline: read files, compare, write the map
    from scipy import stats
    from statsmodels.stats.multitest import multipletests

    pr, pc = os.path.join(tmp, "ref.npy"), os.path.join(tmp, "cand.npy")
    make(pr, pc, k, h, w, c, rng)
    channels = "rgb" if c > 1 else "luminance"
    png = os.path.join(tmp, "map.png")
    rows = []
    # end to end, as the CLI runs it: with the PNG map and without (as the baseline)
    t_e2e, res = best(lambda: mi.run(pr, pc, png=png, channels=channels), reps)
    st = res.timings
    t_nopng, _ = best(lambda: mi.run(pr, pc, channels=channels), reps)
    mem = {"mcstat": peak("mcstat", pr, pc, png, channels), "scipy": peak("scipy", pr, pc, "", channels),
           "idle": peak("idle", pr, pc, "", channels),
           "input": os.path.getsize(pr) + os.path.getsize(pc)}
    ntests = res.pvalue.size
    # stages of the baseline, on the same arrays
    ref = np.load(pr)
    cand = np.load(pc)
    t_sc, sc = best(lambda: stats.ttest_ind(cand, ref, axis=0, equal_var=False), 1)
    p = res.pvalue.reshape(sc.pvalue.shape)
    assert np.allclose(p, sc.pvalue, rtol=1e-5, atol=1e-12), "p-values differ from SciPy's"
    flat = sc.pvalue.ravel().astype(np.float64)
    t_sm, sm = best(lambda: multipletests(flat, method="fdr_bh")[1], 1)
    t_fdc, fdc = best(lambda: stats.false_discovery_control(flat), 1)
    t_pa, pa = best(lambda: mcstat.p_adjust(flat, method="BH"), reps)
    assert np.allclose(pa, sm, rtol=1e-9, atol=0), "BH differs from statsmodels'"
    t_holm, _ = best(lambda: mcstat.p_adjust(flat, method="holm"), 1)
    t_hommel, _ = best(lambda: mcstat.p_adjust(flat, method="hommel"), 1)
    t_load, _ = best(lambda: (np.load(pr), np.load(pc)), 1)
    base_total = t_load + t_sc + t_sm
    rows.append((f"{w} x {h}, {k}+{k} seeds, {channels} ({ntests / 1e6:.1f} M tests)", st, t_e2e, t_load, t_sc,
                 t_sm, t_fdc, t_pa, t_holm, t_hommel, base_total, int((res.padjusted <= 0.05).sum()), t_nopng, mem,
                 ntests))
    del ref, cand, sc
    for f in (pr, pc, png):
        os.remove(f)
    # Equal renders (the usual outcome in a CI job): no rejection, so the
    # per-test level is alpha/m and the detectable bias takes the critical
    # values at the far tail
    make(pr, pc, k, h, w, c, rng, bias=0.0)
    # one run more than the box case's reps: its no-PNG runs come after as many with the PNG
    t_eq, res_eq = best(lambda: mi.run(pr, pc, channels=channels), reps + 1)
    ref, cand = np.load(pr), np.load(pc)
    t0 = time.perf_counter()
    sc = stats.ttest_ind(cand, ref, axis=0, equal_var=False)
    multipletests(np.asarray(sc.pvalue, dtype=np.float64).ravel(), method="fdr_bh")
    t_eq_base = t_load + time.perf_counter() - t0
    rows[-1][1]["equal"] = {"seconds": t_eq, "baseline": t_eq_base, "stages": res_eq.timings,
                            "rejections": int((res_eq.padjusted <= 0.05).sum()),
                            "fresh": peak("mcstat", pr, pc, "", channels)["seconds"]}
    del ref, cand, sc
    for f in (pr, pc):
        os.remove(f)
    return rows


def table(rows):
    out = []
    for (name, st, e2e, tload, tsc, tsm, tfdc, tpa, tholm, thommel, btot, nrej, nopng, mem, ntests) in rows:
        out.append(f"### {name}\n")
        out.append("| stage | mcstat | baseline | baseline / mcstat |")
        out.append("|---|---:|---:|---:|")
        out.append(f"| load + channels (np.load of float32 stacks{', luminance' if 'lumin' in name else ''}) "
                   f"| {st['load_and_channels']:.2f} s | {tload:.2f} s (np.load) | |")
        out.append(f"| per-pixel Welch tests | {st['tests']:.2f} s | {tsc:.2f} s (scipy.stats.ttest_ind) | "
                   f"{tsc / st['tests']:.1f} |")
        out.append(f"| BH adjustment (in the pipeline) | {st['adjust']:.2f} s | {tsm:.2f} s (statsmodels "
                   f"multipletests fdr_bh) | {tsm / st['adjust']:.1f} |")
        out.append(f"| BH adjustment alone, best of runs | {tpa:.2f} s | {tfdc:.2f} s (scipy "
                   f"false_discovery_control) | {tfdc / tpa:.1f} |")
        out.append(f"| decisions + summary arrays | {st['decisions']:.2f} s | | |")
        out.append(f"| detectable bias (what a pass means) | {st.get('detectable_bias', float('nan')):.2f} s | | |")
        out.append(f"| significance map PNG (with its key) | {st['png']:.2f} s | | |")
        out.append(f"| **end to end, no PNG** (`mcstat_app.image.run`, best of runs) | **{nopng:.2f} s** | {btot:.2f} s "
                   f"(load + SciPy + statsmodels) | **{btot / nopng:.1f}** |")
        out.append(f"| end to end with the PNG map | {e2e:.2f} s | | {btot / e2e:.1f} |")
        eq = st.get("equal")
        if eq:
            es = eq["stages"]
            out.append(f"| **end to end, equal renders, no PNG** (best of runs; tests {es['tests']:.2f} s, BH "
                       f"{es['adjust']:.2f} s, detectable bias {es['detectable_bias']:.2f} s) | **{eq['seconds']:.2f} s** "
                       f"| {eq['baseline']:.2f} s (load + SciPy + statsmodels) | **{eq['baseline'] / eq['seconds']:.1f}** |")
        out.append("")
        if eq:
            out.append(f"Equal renders: a second pair of stacks without the box ({eq['rejections']} rejections), "
                       "where the per-test level is alpha/m and the detectable bias takes its critical values "
                       f"at the far tail; {eq['fresh']:.2f} s end to end in a fresh process.\n")
        mb = 1024.0 ** 2
        pm, ps = mem["mcstat"]["peak"], mem["scipy"]["peak"]
        pi = mem["idle"]["peak"]
        out.append(f"Peak resident memory of a whole run in a fresh process (VmHWM): mcstat "
                   f"{pm / mb:.0f} MiB ({mem['mcstat']['seconds']:.2f} s with the PNG), the SciPy + statsmodels "
                   f"pipeline {ps / mb:.0f} MiB; Python with mcstat_app imported and nothing run {pi / mb:.0f} MiB. "
                   f"The input files hold {mem['input'] / mb:.0f} MiB and one float64 per test is "
                   f"{8 * ntests / mb:.0f} MiB: mcstat's peak above the idle interpreter is the input plus "
                   f"{(pm - pi - mem['input']) / (8 * ntests):.1f} float64 per test.\n")
        out.append(f"Other adjustments of the same p-values: Holm {tholm:.2f} s, Hommel {thommel:.2f} s "
                   f"(O(n log n); R's p.adjust is O(n^2) for Hommel). Rejections after BH at 0.05: {nrej} "
                   f"(the biased box holds {400 * 300 * (3 if 'rgb' in name else 1)} tests).\n")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="rewrite bench/RESULTS_image.md")
    ap.add_argument("--small", action="store_true", help="960 x 540 (smoke run)")
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--no-rgb", action="store_true")
    a = ap.parse_args()
    import mcstat

    h, w = (540, 960) if a.small else (2160, 3840)
    rng = np.random.default_rng(1)
    rows = []
    load0 = os.getloadavg()[0]
    import bench_image_pixels as bip

    pw, ph = (960, 540) if a.small else (1920, 1080)
    prep = max(7, a.reps)  # the per-pixel rows are short: more repeats against the machine's noise
    prow, psp, prel = bip.measure(mcstat.get_num_threads(), prep, pw, ph)
    pixels = bip.table(prow, psp, prel, mcstat.get_num_threads(), prep, pw, ph)
    with tempfile.TemporaryDirectory() as tmp:
        rows += run_case(tmp, 8, h, w, 1, a.reps, rng)
        if not a.no_rgb:
            rows += run_case(tmp, 8, h, w, 3, a.reps, rng)
    text = ("# Per-pixel image comparison (`mcstat image-test`)\n\n"
            "`bench/bench_image.py` (in `make bench`): the pipeline of `mcstat image-test` on float32 .npy "
            "stacks, stage by stage, against SciPy's Welch test (`scipy.stats.ttest_ind(equal_var=False)`) and "
            "statsmodels' / SciPy's Benjamini-Hochberg on the same data; p-values checked equal. "
            f"mcstat threads: {mcstat.get_num_threads()} (the tests and nothing else run in parallel); SciPy "
            f"and statsmodels single-threaded. Load average before / after: {load0:.1f} / "
            f"{os.getloadavg()[0]:.1f} (shared machine: trust ratios more than seconds). Python "
            f"{platform.python_version()}, NumPy {np.__version__}.\n\n"
            "### Per-pixel Welch tests (`bench/bench_image_pixels.py`)\n\n" + pixels + "\n\n" + table(rows))
    print(text)
    if a.write:
        with open(os.path.join(HERE, "RESULTS_image.md"), "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    sys.exit(main())
