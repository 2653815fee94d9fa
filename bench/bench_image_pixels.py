#!/usr/bin/env python3
"""Per-pixel Welch at 1920x1080, 8 + 8 float32 seeds: SciPy's ttest_ind
against mcstat's seeds-major path (_core._t_test_2_pixels, what
mcstat.image.compare runs), intervals off and on, and the row-wise path it
replaced (_core.t_test on a pixel-major float64 copy).  One run, the same
data; prints a markdown table.  Not a test (no timing assertions).

    python bench/bench_image_pixels.py [--threads N] [--repeat R] [--width W --height H]
"""
import argparse
import os
import time

import numpy as np


def best(f, repeat):
    t = float("inf")
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = f()
        t = min(t, time.perf_counter() - t0)
    return t, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--threads", type=int, default=min(2, os.cpu_count() or 1))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--width", type=int, default=1920)
    ap.add_argument("--height", type=int, default=1080)
    ap.add_argument("--seeds", type=int, default=8)
    a = ap.parse_args()

    import mcstat
    from mcstat import _core
    from scipy import stats

    mcstat.set_num_threads(a.threads)
    rng = np.random.default_rng(7)
    shape = (a.seeds, a.height, a.width)
    x = rng.normal(1.0, 0.1, shape).astype(np.float32)
    y = rng.normal(1.0, 0.1, shape).astype(np.float32)

    rows = []
    t_sp, r_sp = best(lambda: stats.ttest_ind(x, y, axis=0, equal_var=False), a.repeat)
    rows.append(("SciPy ttest_ind(axis=0, equal_var=False)", t_sp))
    t_off, r_off = best(lambda: _core._t_test_2_pixels(x, y, None, 0, 0.05), a.repeat)
    rows.append(("mcstat seeds-major, intervals off", t_off))
    t_on, _ = best(lambda: _core._t_test_2_pixels(x, y, None, 0, 0.05, intervals=True), a.repeat)
    rows.append(("mcstat seeds-major, intervals on", t_on))

    def old():
        xc = np.ascontiguousarray(np.moveaxis(x, 0, -1), dtype=np.float64)
        yc = np.ascontiguousarray(np.moveaxis(y, 0, -1), dtype=np.float64)
        return _core.t_test(xc, yc, axis=-1, intervals=False, on_error="nan")

    t_old, _ = best(old, max(1, a.repeat - 1))
    rows.append(("mcstat row-wise (moveaxis + float64 copy + t_test), intervals off", t_old))

    p_sp = np.asarray(r_sp.pvalue, dtype=np.float64)
    p_mc = r_off["pvalue"]
    rel = np.nanmax(np.abs(p_mc - p_sp) / p_sp)
    print(f"{a.width}x{a.height}, {a.seeds}+{a.seeds} float32 values per pixel, {a.threads} thread(s), "
          f"best of {a.repeat}, load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs; max relative "
          f"p-value difference to SciPy {rel:.2g} (SciPy returns float32 for float32 input)\n")
    print("| path | seconds | SciPy / path |")
    print("| --- | ---: | ---: |")
    for name, t in rows:
        print(f"| {name} | {t:.3f} | {t_sp / t:.1f} |")


if __name__ == "__main__":
    main()
