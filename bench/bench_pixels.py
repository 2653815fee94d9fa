#!/usr/bin/env python3
"""The public per-pixel calls against SciPy/NumPy on the same data in one run;
writes bench/RESULTS_pixels.md.

    .venv/bin/python bench/bench_pixels.py [--quick] [--rounds R]

mcstat.t_test / var_test with axis= (libmcstat's mcstat_pixels_test) at
1920 x 1080 pixels x (8 + 8) values, seeds-major (seeds, H, W) with axis=0
and rows (H, W, seeds) with axis=-1, float32 and float64, with and without
intervals; Welch per row at 1e5 rows x 64; the F and chi-squared tests per
pixel against np.var + scipy.stats.f / chi2 by hand; and the two-thread
scaling at 3840 x 2160.  mcstat on 2 threads (the machine's), SciPy and
NumPy single-threaded, as they are.  Each ratio is SciPy's median over the
rounds divided by mcstat's, both measured in turn within each round.
Not a test: no timing is asserted; the verdicts are computed from this run.
"""
import argparse
import datetime
import os
import platform
import sys

import numpy as np
import scipy
import scipy.stats as st

import mcstat

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import Timing, machine  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
import time  # noqa: E402

# (case prefix, minimum ratio): the targets of the per-pixel calls
TARGETS = [
    ("Welch per pixel, seeds-major, float32, intervals=False", 10.0),
    ("Welch per pixel, seeds-major, float64, intervals=False", 10.0),
    ("Welch per pixel, rows, float32, intervals=False", 10.0),
    ("Welch per pixel, rows, float64, intervals=False", 10.0),
    ("Welch per pixel, seeds-major, float32, with intervals", 6.0),
    ("Welch per pixel, seeds-major, float64, with intervals", 6.0),
    ("Welch per pixel, rows, float32, with intervals", 6.0),
    ("Welch per pixel, rows, float64, with intervals", 6.0),
    ("Welch per row, 1e5 x 64, intervals=False", 10.0),
    ("Welch per row, 1e5 x 64, with intervals", 10.0),
    ("F test per pixel, seeds-major, float32", 8.0),
    ("F test per pixel, seeds-major, float64", 8.0),
    ("chi-squared test per pixel, seeds-major, float64", 8.0),
]


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
    out = f()
    return time.perf_counter() - t0, out


def run_pairs(pairs, rounds):
    """pairs: [(case, mcstat f, baseline f, note)]; each round times every
    pair's two sides in turn.  Returns [(case, Timing, Timing, note)]."""
    ours = [[] for _ in pairs]
    theirs = [[] for _ in pairs]
    for _ in range(rounds):
        for k, (_, f, g, _) in enumerate(pairs):
            ours[k].append(timed(f)[0])
            theirs[k].append(timed(g)[0])
    return [(c, Timing(o), Timing(t), n) for (c, _, _, n), o, t in zip(pairs, ours, theirs)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="smaller images and fewer rounds (not for quoting)")
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    rounds = 2 if args.quick else args.rounds
    H, W = (270, 480) if args.quick else (1080, 1920)
    threads = min(2, os.cpu_count() or 1)
    mcstat.set_num_threads(threads)
    rng = np.random.default_rng(2026)
    rows = []

    # ---- Welch per pixel: both layouts, both widths ----------------------------
    for dt in (np.float32, np.float64):
        x = rng.normal(1.0, 0.1, (8, H, W)).astype(dt)
        y = rng.normal(1.0, 0.1, (8, H, W)).astype(dt)
        xr, yr = np.ascontiguousarray(np.moveaxis(x, 0, -1)), np.ascontiguousarray(np.moveaxis(y, 0, -1))
        name = np.dtype(dt).name
        pairs = []
        for lay, a, b, ax in (("seeds-major", x, y, 0), ("rows", xr, yr, -1)):
            pairs.append((f"Welch per pixel, {lay}, {name}, intervals=False",
                          lambda a=a, b=b, ax=ax: mcstat.t_test(a, b, axis=ax, intervals=False),
                          lambda a=a, b=b, ax=ax: st.ttest_ind(a, b, axis=ax, equal_var=False),
                          "SciPy ttest_ind(equal_var=False) on the same arrays"))
            pairs.append((f"Welch per pixel, {lay}, {name}, with intervals",
                          lambda a=a, b=b, ax=ax: mcstat.t_test(a, b, axis=ax).conf_int,
                          lambda a=a, b=b, ax=ax: scipy_welch_ci(a, b, ax),
                          "both with the 95% interval (SciPy: confidence_interval())"))
        if dt is np.float64:
            pairs.append(("F test per pixel, seeds-major, float64",
                          lambda: mcstat.var_test(x, y, axis=0, intervals=False),
                          lambda: scipy_f(x, y, 0), "np.var + scipy.stats.f by hand, no intervals"))
            pairs.append(("chi-squared test per pixel, seeds-major, float64",
                          lambda: mcstat.var_test(x, axis=0, sigma2=0.01, intervals=False),
                          lambda: scipy_chi2(x, 0.01, 0), "np.var + scipy.stats.chi2 by hand, no intervals"))
        else:
            pairs.append(("F test per pixel, seeds-major, float32",
                          lambda: mcstat.var_test(x, y, axis=0, intervals=False),
                          lambda: scipy_f(x, y, 0), "np.var + scipy.stats.f by hand, no intervals"))
        rows += run_pairs(pairs, rounds)
        # the same numbers as SciPy's float64 path, checked on this data
        r = mcstat.t_test(x, y, axis=0, intervals=False)
        s = st.ttest_ind(x.astype(np.float64), y.astype(np.float64), axis=0, equal_var=False)
        rel = float(np.nanmax(np.abs(r.pvalue - s.pvalue) / s.pvalue))
        rows.append((f"(check: largest relative p-value difference from SciPy's float64, {name})", None, None,
                     f"{rel:.2g}"))
        del x, y, xr, yr

    # ---- Welch per row: 1e5 x 64 --------------------------------------------------
    X = rng.normal(size=(20000 if args.quick else 100000, 64))
    Y = rng.normal(0.1, 1.5, size=X.shape)
    rows += run_pairs([
        ("Welch per row, 1e5 x 64, intervals=False", lambda: mcstat.t_test(X, Y, intervals=False),
         lambda: st.ttest_ind(X, Y, axis=1, equal_var=False), "SciPy without confidence_interval()"),
        ("Welch per row, 1e5 x 64, with intervals", lambda: mcstat.t_test(X, Y).conf_int,
         lambda: scipy_welch_ci(X, Y, 1), "both with the 95% interval"),
        ("one-sample t per row, 1e5 x 64, with intervals", lambda: mcstat.t_test(X, mu=0.1).conf_int,
         lambda: st.ttest_1samp(X, 0.1, axis=1).confidence_interval(), "both with the 95% interval"),
    ], rounds)
    del X, Y

    # ---- threads at 4K --------------------------------------------------------------
    H4, W4 = (540, 960) if args.quick else (2160, 3840)
    x = rng.normal(1.0, 0.1, (8, H4, W4)).astype(np.float32)
    y = rng.normal(1.0, 0.1, (8, H4, W4)).astype(np.float32)
    scale = run_pairs([
        (f"Welch per pixel at {W4} x {H4}, float32, seeds-major: 2 threads against 1",
         lambda: mcstat.t_test(x, y, axis=0, intervals=False, threads=2),
         lambda: mcstat.t_test(x, y, axis=0, intervals=False, threads=1), "mcstat against itself"),
        (f"F test per pixel at {W4} x {H4}, float32: 2 threads against 1",
         lambda: mcstat.var_test(x, y, axis=0, intervals=False, threads=2),
         lambda: mcstat.var_test(x, y, axis=0, intervals=False, threads=1), "mcstat against itself"),
    ], rounds)
    del x, y
    write(rows, scale, threads, rounds, args, (W, H))


def write(rows, scale, threads, rounds, args, size):
    W, H = size
    lines = ["## Per-pixel calls: mcstat.t_test / var_test with axis=", "",
             f"Written by `bench/bench_pixels.py{' --quick' if args.quick else ''}` on "
             f"{datetime.date.today().isoformat()}: Python {platform.python_version()}, NumPy {np.__version__}, "
             f"SciPy {scipy.__version__}, mcstat threads = {threads}; {machine()}.", "",
             f"{W} x {H} pixels, 8 + 8 values each (normal, sd 0.1 about 1); per row 1e5 x 64. Each case's sides "
             f"are timed in turn within each of {rounds} rounds; times are medians [fastest-slowest round], the "
             "ratio SciPy's median over mcstat's. SciPy and NumPy run on one thread (they have no other), mcstat "
             f"on {threads}; the one-thread figures are the 2-against-1 rows at the end.", "",
             "| case | mcstat | SciPy / NumPy | ratio | note |", "|---|---:|---:|---:|---|"]
    by_case = {}
    for case, ours, theirs, note in rows:
        if ours is None:
            lines.append(f"| {case} | | | | {note} |")
            continue
        ratio = theirs.median / ours.median
        by_case[case] = ratio
        lines.append(f"| {case} | {ours.fmt()} | {theirs.fmt()} | {ratio:.1f}x | {note} |")
    # the fastest rounds too: on a shared VM a neighbour's load only adds time,
    # and it takes one of two cores from the two-thread call
    lines += ["", "| threads | 2 threads | 1 thread | speed-up (medians) | (fastest rounds) |",
              "|---|---:|---:|---:|---:|"]
    for case, two, one, _ in scale:
        lines.append(f"| {case} | {two.fmt()} | {one.fmt()} | {one.median / two.median:.2f}x | "
                     f"{one.lo / two.lo:.2f}x |")
        by_case[case] = one.median / two.median
    lines += ["", "### Targets, as measured in this run", "", "| target | measured | verdict |", "|---|---:|---|"]
    for prefix, want in TARGETS + [(scale[0][0], 1.7)]:
        got = by_case.get(prefix)
        if got is None:
            continue
        lines.append(f"| {prefix}: >= {want:g}x | {got:.1f}x | {'met' if got >= want else 'NOT met'} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(HERE, "RESULTS_pixels.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
