#!/usr/bin/env python3
"""Rejection rates of the renderer checks on spherical triangles (Arvo's
sampler in NumPy, tests/python/test_check_sphere_geometry.py): for each
triangle, as a warp and as an emitter, correct and with each planted bug,
how many of --seeds fixed seeds are rejected at alpha = 0.01, and by which
route.  A correct model's count is judged against the 0.999 quantile of
Binomial(seeds, alpha).

    .venv/bin/python bench/bench_check_sphere_geometry.py --n 50000 --seeds 20
"""
import argparse
import os
import sys
import time

from scipy.stats import binom

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "python"))
from test_check_sphere_geometry import ALPHA, CASES, SphericalTriangle  # noqa: E402

ROUTES = ("cells", "mass", "integrals", "ks")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=50000)
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--bugs", default="none,pdf_high,nonuniform")
    args = ap.parse_args()
    bound = int(binom.ppf(0.999, args.seeds, ALPHA))
    print(f"n = {args.n}, {args.seeds} seeds, alpha = {ALPHA}; a correct model may be rejected at most {bound} times")
    print("| case | kind | bug | rejected | by route | seconds |")
    print("|---|---|---|---|---|---|")
    for bug in args.bugs.split(","):
        for case in args.cases.split(","):
            for kind in ("warp", "emitter"):
                t = SphericalTriangle(*CASES[case], bug=None if bug == "none" else bug)
                t0 = time.time()
                reports = [t.check(kind, seed, n=args.n) for seed in range(args.seeds)]
                rejected = sum(r.reject for r in reports)
                by = {q: sum(r.route(q).reject for r in reports) for q in ROUTES}
                by = ", ".join(f"{q} {c}" for q, c in by.items() if c)
                flag = " (above the bound)" if bug == "none" and rejected > bound else ""
                print(f"| {case} | {kind} | {bug} | {rejected}/{args.seeds}{flag} | {by} | {time.time() - t0:.1f} |",
                      flush=True)


if __name__ == "__main__":
    main()
