#!/usr/bin/env python3
"""Python benchmarks of mcstat against SciPy; writes bench/RESULTS_python.md.

    .venv/bin/python bench/bench_python.py [--quick] [--no-image]

Each ratio compares the two libraries in one run on the same data: the
ratio of the median times (bench/common.py: median over rounds, with the
fastest and slowest round as the spread).  Each case also reports the peak
resident memory one call adds (kernel high-water mark), for both sides;
the 1e7 cases in addition the peak traced by tracemalloc.
"""
import argparse
import datetime
import os
import platform
import sys
import tracemalloc

import numpy as np
import scipy
import scipy.stats as st

import mcstat

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import fmt_bytes, machine, measure, peak_rss  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

# The speed targets of the Python API: (case prefix, minimum ratio).  The verdicts in
# RESULTS_python.md are computed from this run's rows, never written by hand.
TARGETS = [
    ("Welch t, n = 50 + 50 (one call)", 100.0),
    ("one-sample t, n = 1e7", 8.0),
    ("Welch t, n = 1e7 + 1e7", 8.0),
    ("Welch per row, 1e5 rows x 64", 10.0),
]

NOTES = """## Where the time goes

- One call (Welch, 2 x 50): about 1 us in libmcstat (two 64-value moments,
  the t tail by its all-positive central series, one t quantile: Hill's start
  and one Halley step) and a few hundred ns of Python (vectorcall argument
  parsing in C++, the result struct copied; tuples and text made on access).
- 1e7 values: one memory pass, no copy (peak traced memory above).
- Per row (1e5 x 64): about 4000 instructions per Welch row without
  intervals (callgrind): half in the two moment passes (each exact to the
  last digits: shifted sums about a pilot, double-double mean), half in the
  p-value's incomplete beta (the df differs per row, so nothing is shared).
  Intervals add one t quantile per row.  SciPy's vectorised float path costs
  ~1.4-2 us per row here, so the ratio sits between 5x and 10x: reaching 10x
  at 64 values per row would take a less exact algorithm, which mcstat does
  not trade for speed.  One-sample rows share one quantile (equal df).
"""


def verdicts(rows):
    lines = ["## Targets, as measured in this run\n", "| target | measured | verdict |", "|---|---:|---|"]
    for prefix, want in TARGETS:
        got = [r for r in rows if r[0].strip().startswith(prefix)]
        if not got:
            lines.append(f"| {prefix}: >= {want:g}x | not run | - |")
            continue
        ratio = got[0][3]
        lines.append(f"| {got[0][0].strip()}: >= {want:g}x | {ratio:.1f}x | {'met' if ratio >= want else 'NOT met'} |")
    return "\n".join(lines) + "\n"


def peak(f):
    tracemalloc.start()
    try:
        f()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="fewer repeats")
    ap.add_argument("--no-image", action="store_true", help="skip the 1920x1080x64 cases (2 GB of input)")
    args = ap.parse_args()
    rep = 3 if args.quick else 7
    rng = np.random.default_rng(12345)
    rows = []

    def side(f, repeat, number):
        """(Timing, peak RSS added by one call) of f."""
        return measure(f, repeat, number), peak_rss(f)

    def add(case, ours, theirs, note=""):
        (t_o, m_o), (t_t, m_t) = ours, theirs
        ratio = t_t.median / t_o.median
        rows.append((case, t_o, t_t, ratio, note, m_o, m_t))
        print(f"{case:58s} mcstat {t_o.fmt():28s} scipy {t_t.fmt():28s} x{ratio:8.1f}  "
              f"rss {fmt_bytes(m_o)} / {fmt_bytes(m_t)}  {note}", flush=True)

    # ---- small samples: the per-call overhead ------------------------------
    x, y = rng.normal(size=50), rng.normal(0.2, 1.5, size=50)
    n = 20000 if not args.quick else 5000
    sc = side(lambda: st.ttest_ind(x, y, equal_var=False), rep, max(1, n // 50))
    add("Welch t, n = 50 + 50 (one call)", side(lambda: mcstat.t_test(x, y), rep, n), sc)
    add("  same, intervals=False", side(lambda: mcstat.t_test(x, y, intervals=False), rep, n), sc)
    mx, my = mcstat.Moments(x), mcstat.Moments(y)
    add("  same, on two Moments", side(lambda: mcstat.t_test(mx, my), rep, n), sc)
    add("  same, inputs as Python lists", side(lambda: mcstat.t_test(list(x), list(y)), rep, n // 4),
        sc, "list conversion included")
    sc1 = side(lambda: st.ttest_1samp(x, 0.1), rep, max(1, n // 50))
    add("one-sample t, n = 50 (one call)", side(lambda: mcstat.t_test(x, mu=0.1), rep, n), sc1)

    def scipy_f(a, b):  # SciPy has no F test function: the same numbers by hand
        f = np.var(a, ddof=1) / np.var(b, ddof=1)
        d1, d2 = len(a) - 1, len(b) - 1
        p = 2 * min(st.f.cdf(f, d1, d2), st.f.sf(f, d1, d2))
        return f, p, st.f.ppf(0.025, d1, d2), st.f.isf(0.025, d1, d2)

    add("F test, n = 50 + 50 (one call)", side(lambda: mcstat.var_test(x, y), rep, n // 4),
        side(lambda: scipy_f(x, y), rep, max(1, n // 50)), "scipy: np.var + scipy.stats.f by hand")

    def scipy_chi2(a, s2):  # nor a one-sample variance test
        c = (len(a) - 1) * np.var(a, ddof=1) / s2
        df = len(a) - 1
        return c, 2 * min(st.chi2.cdf(c, df), st.chi2.sf(c, df)), st.chi2.ppf(0.025, df), st.chi2.isf(0.025, df)

    add("chi-square variance test, n = 50 (one call)", side(lambda: mcstat.var_test(x, sigma2=1.0), rep, n // 4),
        side(lambda: scipy_chi2(x, 1.0), rep, max(1, n // 50)), "scipy: np.var + scipy.stats.chi2 by hand")
    xs, ys = rng.normal(size=100), rng.normal(0.3, 1.0, size=100)
    add("K-S exact, weight none, n = 100 + 100 (one call)",
        side(lambda: mcstat.ks_test(xs, ys, weight="none", method="exact"), rep, max(1, n // 20)),
        side(lambda: st.ks_2samp(xs, ys, method="exact"), rep, max(1, n // 200)),
        "both exact p-values; mcstat also its critical value")

    # ---- large samples --------------------------------------------------------
    big = rng.normal(0.001, 1, size=10_000_000)
    big2 = rng.normal(0, 2, size=10_000_000)
    r = 3 if args.quick else 5
    add("one-sample t, n = 1e7", side(lambda: mcstat.t_test(big), r, 1), side(lambda: st.ttest_1samp(big, 0.0), r, 1))
    add("Welch t, n = 1e7 + 1e7", side(lambda: mcstat.t_test(big, big2), r, 1),
        side(lambda: st.ttest_ind(big, big2, equal_var=False), r, 1))
    add("moments (mean, variance), n = 1e7", side(lambda: mcstat.Moments(big), r, 1),
        side(lambda: (np.mean(big), np.var(big, ddof=1)), r, 1), "numpy: np.mean + np.var (two passes)")
    add("F test, n = 1e7 + 1e7", side(lambda: mcstat.var_test(big, big2), r, 1),
        side(lambda: scipy_f(big, big2), r, 1), "scipy: np.var + scipy.stats.f by hand")
    mem = {
        "mcstat.t_test(x), n = 1e7": peak(lambda: mcstat.t_test(big)),
        "scipy.stats.ttest_1samp(x), n = 1e7": peak(lambda: st.ttest_1samp(big, 0.0)),
        "mcstat.t_test(x, y), n = 1e7 + 1e7": peak(lambda: mcstat.t_test(big, big2)),
        "scipy.stats.ttest_ind(x, y), n = 1e7 + 1e7": peak(lambda: st.ttest_ind(big, big2, equal_var=False)),
        "mcstat.Moments(x), n = 1e7": peak(lambda: mcstat.Moments(big)),
    }
    del big, big2

    # ---- per pixel: one test per row ----------------------------------------------
    X, Y = rng.normal(size=(100_000, 64)), rng.normal(0.01, 1.2, size=(100_000, 64))
    threads = mcstat.get_num_threads()
    sc = side(lambda: st.ttest_ind(X, Y, axis=1, equal_var=False), r, 1)

    def scipy_with_ci():
        s = st.ttest_ind(X, Y, axis=1, equal_var=False)
        return s.confidence_interval()

    sc_ci = side(scipy_with_ci, r, 1)
    add(f"Welch per row, 1e5 rows x 64 ({threads} threads)", side(lambda: mcstat.t_test(X, Y), r, 1), sc_ci,
        "both with confidence intervals")
    add(f"  same, intervals=False ({threads} threads)", side(lambda: mcstat.t_test(X, Y, intervals=False), r, 1),
        sc, "scipy without confidence_interval()")
    mcstat.set_num_threads(1)
    add("  same, intervals=False, 1 thread", side(lambda: mcstat.t_test(X, Y, intervals=False), r, 1), sc)
    add("  same, with intervals, 1 thread", side(lambda: mcstat.t_test(X, Y), r, 1), sc_ci)
    mcstat.set_num_threads(0)
    add(f"one-sample t per row, 1e5 x 64 ({threads} threads)", side(lambda: mcstat.t_test(X, mu=0.01), r, 1),
        side(lambda: (lambda s: s.confidence_interval())(st.ttest_1samp(X, 0.01, axis=1)), r, 1),
        "both with confidence intervals")

    def scipy_f_rows(a, b):
        f = np.var(a, ddof=1, axis=1) / np.var(b, ddof=1, axis=1)
        d1, d2 = a.shape[1] - 1, b.shape[1] - 1
        return f, 2 * np.minimum(st.f.cdf(f, d1, d2), st.f.sf(f, d1, d2))

    add(f"F test per row, 1e5 x 64 ({threads} threads)", side(lambda: mcstat.var_test(X, Y), r, 1),
        side(lambda: scipy_f_rows(X, Y), r, 1), "scipy: np.var + scipy.stats.f by hand, no intervals")
    del X, Y

    image = []
    if not args.no_image:
        X = rng.standard_normal(size=(1080, 1920, 64))
        image.append(("one-sample t, with intervals", side(lambda: mcstat.t_test(X, mu=0.0), 3, 1)))
        image.append(("one-sample t, intervals=False", side(lambda: mcstat.t_test(X, mu=0.0, intervals=False), 3, 1)))
        Y = rng.standard_normal(size=(1080, 1920, 64))
        image.append(("Welch, with intervals", side(lambda: mcstat.t_test(X, Y), 3, 1)))
        image.append(("Welch, intervals=False", side(lambda: mcstat.t_test(X, Y, intervals=False), 3, 1)))
        del X, Y
        for case, (t, m) in image:
            print(f"1920x1080 x 64 {case:40s} {t.fmt()}  rss {fmt_bytes(m)}", flush=True)

    write(rows, mem, image, threads, args)


def write(rows, mem, image, threads, args):
    out = []
    out.append("# mcstat Python benchmarks\n")
    out.append(f"Written by `bench/bench_python.py{' --quick' if args.quick else ''}` on "
               f"{datetime.date.today()}: Python {platform.python_version()}, NumPy {np.__version__}, "
               f"SciPy {scipy.__version__}, mcstat threads = {threads}; machine at the end of the run: "
               f"{machine()} (shared with other work: treat single numbers as +-20%).\n")
    out.append("Times are medians per call over several rounds, [fastest - slowest round] beside them; each "
               "ratio compares SciPy/NumPy and mcstat in the same run on the same data (ratio = SciPy median / "
               "mcstat median). Peak RSS: resident memory one call adds at its peak (VmHWM after reset - VmRSS "
               "before; 0 = served from memory the process already held).\n")
    out.append("| case | mcstat | SciPy / NumPy | ratio | peak RSS mcstat | peak RSS SciPy | note |\n"
               "|---|---:|---:|---:|---:|---:|---|")
    for case, ours, theirs, ratio, note, m_o, m_t in rows:
        out.append(f"| {case.strip()} | {ours.fmt()} | {theirs.fmt()} | {ratio:.1f}x | "
                   f"{fmt_bytes(m_o)} | {fmt_bytes(m_t)} | {note} |")
    out.append("\n## Peak memory on top of the input (tracemalloc)\n")
    out.append("| call | peak |\n|---|---:|")
    for k, v in mem.items():
        out.append(f"| `{k}` | {v / 2**20:.3f} MiB |")
    out.append("\nThe input is 76 MiB per 1e7 float64 array: mcstat reads it in place (no copy); SciPy's "
               "peaks are its temporaries.\n")
    if image:
        out.append("## The per-pixel case: 1920 x 1080 pixels x 64 secondary estimates\n")
        out.append("One test per pixel (2,073,600 tests; 1.06 GB per input image), all threads.\n")
        out.append("| test | time, median [range] of 3 | peak RSS added |\n|---|---:|---:|")
        for case, (t, m) in image:
            out.append(f"| {case} | {t.fmt('s')} | {fmt_bytes(m)} |")
        out.append("")
    out.append(verdicts(rows))
    out.append(NOTES)
    with open(os.path.join(HERE, "RESULTS_python.md"), "w") as f:
        f.write("\n".join(out) + "\n")
    print("wrote bench/RESULTS_python.md")


if __name__ == "__main__":
    sys.exit(main())
