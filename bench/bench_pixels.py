#!/usr/bin/env python3
"""The public per-pixel calls, one thread each, against SciPy/NumPy on the
same data in one process, and against the memory floor; writes
bench/RESULTS_pixels.md.

    .venv/bin/python bench/bench_pixels.py [--quick] [--rounds R]

mcstat.t_test / var_test with axis= (libmcstat's mcstat_pixels_test) at
1920 x 1080 pixels x (8 + 8) values, seeds-major (seeds, H, W) with axis=0
and rows (H, W, seeds) with axis=-1, float32 and float64, with and without
intervals; Welch per row at 1e5 rows x 64; the F and chi-squared tests per
pixel against np.var + scipy.stats.f / chi2 by hand.  Every comparison is
one mcstat thread (threads=1) against one SciPy/NumPy thread (the BLAS and
OpenMP pools are held to one thread through the environment before NumPy is
imported; ttest_ind uses neither).  The floor of each layout is a NumPy
pass that reads the same bytes (a.sum() + b.sum()): no kernel that reads
its input can be faster.  The two-thread scaling rows at 3840 x 2160 are
mcstat against itself and labelled so.  In each round every side of a case
is timed in turn; times are medians over the rounds [fastest-slowest
round], ratios of medians.  Not a test: no timing is asserted; the verdicts
are computed from this run.
"""
import os

# one thread for every pool SciPy/NumPy could use, before they are imported
# (a value already in the environment is kept and stated in the header)
THREAD_ENV = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
for _v in THREAD_ENV:
    os.environ.setdefault(_v, "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
import scipy  # noqa: E402
import scipy.stats as st  # noqa: E402

import mcstat  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import Timing, load, machine  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

SPEEDUP = 10.0  # one mcstat thread against one SciPy thread, Welch without intervals
FLOOR = 3.0     # at most this many times the layout's memory floor
LAYOUTS = [(lay, dt) for dt in ("float32", "float64") for lay in ("seeds-major", "rows")]


def scipy_f(a, b, axis):
    """SciPy has no F test: the two-sided p-value by hand."""
    f = np.var(a, axis=axis, ddof=1) / np.var(b, axis=axis, ddof=1)
    d1, d2 = a.shape[axis] - 1, b.shape[axis] - 1
    return f, 2 * np.minimum(st.f.cdf(f, d1, d2), st.f.sf(f, d1, d2))


def scipy_chi2(a, s2, axis):
    c = (a.shape[axis] - 1) * np.var(a, axis=axis, ddof=1) / s2
    df = a.shape[axis] - 1
    return c, 2 * np.minimum(st.chi2.cdf(c, df), st.chi2.sf(c, df))


def scipy_welch_ci(a, b, axis):
    r = st.ttest_ind(a, b, axis=axis, equal_var=False)
    return r, r.confidence_interval()


def timed(f):
    t0 = time.perf_counter()
    f()
    return time.perf_counter() - t0


def run_cases(cases, rounds):
    """cases: [(name, {side: f})]; each round times every case's sides in
    turn.  Returns {name: {side: Timing}}."""
    got = {name: {s: [] for s in sides} for name, sides in cases}
    for _ in range(rounds):
        for name, sides in cases:
            for s, f in sides.items():
                got[name][s].append(timed(f))
    return {name: {s: Timing(v) for s, v in sides.items()} for name, sides in got.items()}


def floor_pass(*arrays):
    """A NumPy pass that reads the same bytes: the sums of the inputs."""
    return lambda: sum(float(a.sum()) for a in arrays)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller images and fewer rounds (not for quoting)")
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    rounds = 2 if args.quick else args.rounds
    H, W = (270, 480) if args.quick else (1080, 1920)
    R = 20000 if args.quick else 100000
    load_before = load()
    rng = np.random.default_rng(2026)
    welch, other, checks = [], [], []

    # ---- Welch per pixel: both layouts, both widths, one thread ----------------
    for dt in (np.float32, np.float64):
        x = rng.normal(1.0, 0.1, (8, H, W)).astype(dt)
        y = rng.normal(1.0, 0.1, (8, H, W)).astype(dt)
        xr, yr = np.ascontiguousarray(np.moveaxis(x, 0, -1)), np.ascontiguousarray(np.moveaxis(y, 0, -1))
        name = np.dtype(dt).name
        cases = []
        for lay, a, b, ax in (("seeds-major", x, y, 0), ("rows", xr, yr, -1)):
            cases.append(((lay, name), {
                "mcstat": lambda a=a, b=b, ax=ax: mcstat.t_test(a, b, axis=ax, intervals=False, threads=1),
                "scipy": lambda a=a, b=b, ax=ax: st.ttest_ind(a, b, axis=ax, equal_var=False),
                "floor": floor_pass(a, b)}))
            cases.append((f"Welch per pixel, {lay}, {name}, with intervals", {
                "mcstat": lambda a=a, b=b, ax=ax: mcstat.t_test(a, b, axis=ax, threads=1).conf_int,
                "scipy": lambda a=a, b=b, ax=ax: scipy_welch_ci(a, b, ax)}))
        cases.append((f"F test per pixel, seeds-major, {name}", {
            "mcstat": lambda: mcstat.var_test(x, y, axis=0, intervals=False, threads=1),
            "scipy": lambda: scipy_f(x, y, 0)}))
        if dt is np.float64:
            cases.append(("chi-squared test per pixel, seeds-major, float64", {
                "mcstat": lambda: mcstat.var_test(x, axis=0, sigma2=0.01, intervals=False, threads=1),
                "scipy": lambda: scipy_chi2(x, 0.01, 0)}))
        res = run_cases(cases, rounds)
        for key, sides in res.items():
            (welch if isinstance(key, tuple) else other).append((key, sides))
        # the same numbers as SciPy's float64 path, checked on this data
        r = mcstat.t_test(x, y, axis=0, intervals=False, threads=1)
        s = st.ttest_ind(x.astype(np.float64), y.astype(np.float64), axis=0, equal_var=False)
        checks.append((name, float(np.nanmax(np.abs(r.pvalue - s.pvalue) / s.pvalue))))
        del x, y, xr, yr

    # ---- Welch per row: 1e5 x 64 ----------------------------------------------------
    X = rng.normal(size=(R, 64))
    Y = rng.normal(0.1, 1.5, size=X.shape)
    res = run_cases([
        (("per row 1e5 x 64", "float64"), {
            "mcstat": lambda: mcstat.t_test(X, Y, intervals=False, threads=1),
            "scipy": lambda: st.ttest_ind(X, Y, axis=1, equal_var=False),
            "floor": floor_pass(X, Y)}),
        ("Welch per row, 1e5 x 64, with intervals", {
            "mcstat": lambda: mcstat.t_test(X, Y, threads=1).conf_int,
            "scipy": lambda: scipy_welch_ci(X, Y, 1)}),
        ("one-sample t per row, 1e5 x 64, with intervals", {
            "mcstat": lambda: mcstat.t_test(X, mu=0.1, threads=1).conf_int,
            "scipy": lambda: st.ttest_1samp(X, 0.1, axis=1).confidence_interval()}),
    ], rounds)
    for key, sides in res.items():
        (welch if isinstance(key, tuple) else other).append((key, sides))
    del X, Y

    # ---- two threads against one at 4K: mcstat against itself ------------------------
    H4, W4 = (540, 960) if args.quick else (2160, 3840)
    x = rng.normal(1.0, 0.1, (8, H4, W4)).astype(np.float32)
    y = rng.normal(1.0, 0.1, (8, H4, W4)).astype(np.float32)
    scale = run_cases([
        (f"Welch per pixel at {W4} x {H4}, float32, seeds-major", {
            "two": lambda: mcstat.t_test(x, y, axis=0, intervals=False, threads=2),
            "one": lambda: mcstat.t_test(x, y, axis=0, intervals=False, threads=1)}),
        (f"F test per pixel at {W4} x {H4}, float32, seeds-major", {
            "two": lambda: mcstat.var_test(x, y, axis=0, intervals=False, threads=2),
            "one": lambda: mcstat.var_test(x, y, axis=0, intervals=False, threads=1)}),
    ], rounds)
    del x, y
    write(welch, other, checks, scale, rounds, args, (W, H), load_before)


def write(welch, other, checks, scale, rounds, args, size, load_before):
    W, H = size
    env = ", ".join(f"{v}={os.environ.get(v, '(unset)')}" for v in THREAD_ENV + ("OPENBLAS_CORETYPE",))
    l0, l1 = load_before, load()
    lines = [
        "## Per-pixel calls, one thread: mcstat.t_test / var_test with axis=", "",
        f"Written by `bench/bench_pixels.py{' --quick' if args.quick else ''}` on "
        f"{datetime.date.today().isoformat()}: Python {platform.python_version()}, NumPy {np.__version__}, "
        f"SciPy {scipy.__version__}; {machine()}.", "",
        f"Threads: mcstat `threads=1` in every comparison (the 2-thread rows at the end are mcstat against "
        f"itself); SciPy and NumPy on one thread, with {env} set before NumPy was imported "
        f"(`ttest_ind` uses neither pool). Load average (1 / 5 / 15 min) at the start "
        f"{l0[0]:.2f} / {l0[1]:.2f} / {l0[2]:.2f}, at the end {l1[0]:.2f} / {l1[1]:.2f} / {l1[2]:.2f}: on a "
        "shared machine a neighbour's load only adds time, so the fastest rounds are shown too.", "",
        f"{W} x {H} pixels, 8 + 8 values each (normal, sd 0.1 about 1); per row 1e5 x 64 (float64). "
        f"In each of {rounds} rounds every side of a case is timed in turn; times are medians "
        "[fastest-slowest round]. The floor is a NumPy pass reading the same bytes (`a.sum() + b.sum()`): "
        "what any kernel that reads its input costs at least.", "",
        "### Welch without intervals: one mcstat thread against SciPy and against the floor", "",
        "| layout | mcstat (1 thread) | SciPy `ttest_ind(equal_var=False)` | floor (`a.sum() + b.sum()`) "
        "| SciPy / mcstat | mcstat / floor | (fastest rounds: SciPy / mcstat, mcstat / floor) |",
        "|---|---:|---:|---:|---:|---:|---:|"]
    verdicts = []
    for (lay, dt), s in welch:
        m, sc, fl = s["mcstat"], s["scipy"], s["floor"]
        speed, over = sc.median / m.median, m.median / fl.median
        lines.append(f"| {lay}, {dt} | {m.fmt()} | {sc.fmt()} | {fl.fmt()} | {speed:.1f}x | {over:.1f}x | "
                     f"{sc.lo / m.lo:.1f}x, {m.lo / fl.lo:.1f}x |")
        verdicts.append((f"{lay}, {dt}: SciPy / mcstat >= {SPEEDUP:g}x", f"{speed:.1f}x", speed >= SPEEDUP))
        verdicts.append((f"{lay}, {dt}: mcstat / floor <= {FLOOR:g}x", f"{over:.1f}x", over <= FLOOR))
    lines += ["", "### The other calls, one thread each", "",
              "| case | mcstat (1 thread) | SciPy / NumPy | SciPy / mcstat |", "|---|---:|---:|---:|"]
    for name, s in other:
        lines.append(f"| {name} | {s['mcstat'].fmt()} | {s['scipy'].fmt()} | "
                     f"{s['scipy'].median / s['mcstat'].median:.1f}x |")
    for name, rel in checks:
        lines.append(f"| (check: largest relative p-value difference from SciPy's float64 on the {name} "
                     f"stack) | {rel:.2g} | | |")
    lines += ["", "### Scaling: mcstat on 2 threads against mcstat on 1 (not a comparison with SciPy)", "",
              "| case | 2 threads | 1 thread | speed-up (medians) | (fastest rounds) |",
              "|---|---:|---:|---:|---:|"]
    for name, s in scale.items():
        two, one = s["two"], s["one"]
        lines.append(f"| {name} | {two.fmt()} | {one.fmt()} | {one.median / two.median:.2f}x | "
                     f"{one.lo / two.lo:.2f}x |")
    lines += ["", "### Targets, as measured in this run (ratios of medians)", "", "| target | measured | verdict |",
              "|---|---:|---|"]
    for what, got, ok in verdicts:
        lines.append(f"| {what} | {got} | {'met' if ok else 'NOT met'} |")
    missed = sum(not ok for _, _, ok in verdicts)
    lines += ["", f"{len(verdicts) - missed} of {len(verdicts)} targets met in this run." if missed else
              f"All {len(verdicts)} targets met in this run."]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(HERE, "RESULTS_pixels.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
