#!/usr/bin/env python3
"""Calibration of the renderer checks at full size (make bench): how often
does mcstat.check_bsdf reject a correct BSDF?

Each model is checked with `--runs` seeds at the default budget (n = 1e5)
and the battery's p-value (the smallest Holm-adjusted one) kept, so that one
run gives the rejection rate at every level.  The count at each level is
judged by the battery meta-test (binomial, one-sided: a conservative battery
is allowed, one that rejects more than alpha is not).  The models: the
paper's two BRDFs from libmcest (Ward at 70 degrees, Ashikhmin-Shirley at
30), handed over as a renderer would (mcstat_app.reproduce.renderer_check),
and two cosine-power lobes in NumPy (exponent 10, and 400: a narrow lobe).
Mitsuba 3's BSDFs: examples/mitsuba (compare_chi2.py --calibration).

Writes bench/RESULTS_check_calibration.md with --write.
"""
import argparse
import math
import os
import sys
import time

import numpy as np

import mcstat
from mcstat import estimators as est

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "programs"))
from mcstat_app.reproduce.renderer_check import adapter  # noqa: E402

LEVELS = (0.001, 0.01, 0.05)


def lobe(e, wi):
    r = np.array([-wi[0], -wi[1], wi[2]], dtype=float)
    r /= np.linalg.norm(r)
    s = math.copysign(1.0, r[2])
    a = -1.0 / (s + r[2])
    b = r[0] * r[1] * a
    t1, t2 = np.array([1 + s * r[0] ** 2 * a, s * b, -s * r[0]]), np.array([b, s + r[1] ** 2 * a, -r[1]])

    def density(x):
        c = x @ r
        return np.where((x[:, 2] > 0) & (c > 0), (e + 1) / (2 * np.pi) * np.maximum(c, 0.0) ** e, 0.0)

    def sample(wi_, u):
        c = u[:, 0] ** (1 / (e + 1))
        sn = np.sqrt(np.maximum(0.0, 1 - c * c))
        phi = 2 * np.pi * u[:, 1]
        x = c[:, None] * r + sn[:, None] * (np.cos(phi)[:, None] * t1 + np.sin(phi)[:, None] * t2)
        p = density(x)
        return x, np.where(p > 0, 0.8, 0.0), p

    return sample, (lambda wi_, x: 0.8 * density(x)), (lambda wi_, x: density(x))


def direction(theta, phi):
    t, p = math.radians(theta), math.radians(phi)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def models():
    wo_w, wo_a = direction(70, 40), direction(30, 40)
    yield "Ward (0.6, 0.2, 0.05), wo at 70 deg", adapter(est.ward(0.0, 0.6, 0.2, 0.05), wo_w, "none"), wo_w
    yield ("Ashikhmin-Shirley (0.6, 20, 500), wo at 30 deg",
           adapter(est.ashikhmin_shirley(0.0, 0.6, 20.0, 500.0), wo_a, "none"), wo_a)
    wi = direction(40, 10)
    yield "cos^10 lobe, wi at 40 deg", lobe(10.0, wi), wi
    yield "cos^400 lobe, wi at 40 deg", lobe(400.0, wi), wi


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=500)
    ap.add_argument("--n", type=int, default=100_000)
    ap.add_argument("--write", action="store_true")
    args = ap.parse_args()
    lines = ["# Renderer checks: false rejections of correct BSDFs", "",
             f"`bench/bench_check_calibration.py --runs {args.runs} --n {args.n}` (in `make bench`): "
             "`mcstat.check_bsdf` with its defaults on correct models, one seed per run; the battery's p-value "
             "(the smallest Holm-adjusted p-value of its statistical routes) gives the rejection rate at every "
             "level. Each count is judged by the battery meta-test (one-sided binomial: more rejections than "
             "alpha allows?). Routes: how often each rejected at alpha = 0.01; invalid: runs in which some route "
             "could not answer (heavy tails, an envelope exceeded).", "",
             "| model | runs | " + " | ".join(f"rejected at {a:g} (meta-test p)" for a in LEVELS)
             + " | routes at 0.01 | invalid | s per check |", "|---|---:|" + "---:|" * len(LEVELS) + "---|---:|---:|"]
    for name, (sample, eval_, pdf), wi in models():
        pvals, routes, invalid = [], {}, 0
        t0 = time.perf_counter()
        for seed in range(args.runs):
            r = mcstat.check_bsdf(sample, eval_, pdf, wi, n=args.n, seed=10_000 + seed, alpha=0.01)
            pvals.append(r.pvalue)
            invalid += any(x.state == "invalid" for x in r.routes)
            for x in r.routes:
                if x.reject:
                    routes[x.name] = routes.get(x.name, 0) + 1
        sec = (time.perf_counter() - t0) / args.runs
        pv = np.array(pvals)
        cells = []
        for a in LEVELS:
            k = int((pv <= a).sum())
            meta = mcstat.battery_test(k, a, n=args.runs, alternative="greater")
            cells.append(f"{k} ({meta.pvalue:.2g})")
        rt = ", ".join(f"{k} {v}" for k, v in sorted(routes.items())) or "-"
        lines.append(f"| {name} | {args.runs} | " + " | ".join(cells) + f" | {rt} | {invalid} | {sec:.3f} |")
        print(lines[-1], flush=True)
    text = "\n".join(lines) + "\n"
    if args.write:
        with open(os.path.join(HERE, "RESULTS_check_calibration.md"), "w") as f:
            f.write(text)
    else:
        print(text)


if __name__ == "__main__":
    main()
