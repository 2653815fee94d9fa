#!/usr/bin/env python3
"""Plots the simulated K-S p-value's error against its run time.

Reads the CSV that `ks_bench error` writes (n, p_exact, n_sim,
seconds_per_test, rms_abs_error, ...) and draws, for each size and exact
p-value, the RMS relative error of the simulated p-value against the time
per test, on log-log axes with the Monte Carlo slope -1/2, so that a user can
pick n_sim for the accuracy and time they want.

Usage: plot_ks_error_time.py CSV PNG
"""
import csv
import sys
from collections import defaultdict


def main(src, dst):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    series = defaultdict(list)
    with open(src) as f:
        for row in csv.DictReader(f):
            key = (int(row["n"]), float(row["p_exact"]))
            series[key].append((float(row["seconds_per_test"]), float(row["rms_rel_error"]), int(row["n_sim"])))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for (n, p), pts in sorted(series.items()):
        pts.sort()
        t, e = [x[0] for x in pts], [x[1] for x in pts]
        ax.loglog(t, e, "o-", label=f"{n} + {n}, exact p = {p:.3g}")
        # the ideal slope -1/2 through the first point
        ax.loglog([t[0], t[-1]], [e[0], e[0] * (t[-1] / t[0]) ** -0.5], ":", color="0.6", lw=1)
        for ti, ei, ns in pts:
            ax.annotate(f"{ns}", (ti, ei), textcoords="offset points", xytext=(3, 3), fontsize=6, color="0.4")
    ax.set_xlabel("seconds per test (Canner's weight, simulated)")
    ax.set_ylabel("RMS relative error of the p-value")
    ax.set_title("Simulated K-S p-value: error against run time\n(dotted: slope -1/2; labels: n_sim)", fontsize=10)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(dst, dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
