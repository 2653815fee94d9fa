"""Compare two results.json of `mcstat reproduce` (same seed): every number
at the same place in both, timings, versions and SciPy's p-values left out.  Prints one line,
"N numbers, K identical, max relative difference D at PATH", and exits 1 if
the structures differ or a difference exceeds --rtol.
    usage: python compare_results.py A.json B.json [--rtol 1e-9]"""
import argparse
import json
import math
import sys

SKIP = ("time", "timing", "elapsed", "versions", "duration", "wall",
        # SciPy's tests of normality (mcstat.diagnose), not mcstat's numbers:
        # they change with the SciPy release pip picks for each Python
        "shapiro_pvalue", "normaltest_pvalue")


def leaves(x, path=""):
    if isinstance(x, dict):
        for k in sorted(x):
            if any(s in k.lower() for s in SKIP):
                continue
            yield from leaves(x[k], f"{path}/{k}")
    elif isinstance(x, list):
        for i, v in enumerate(x):
            yield from leaves(v, f"{path}[{i}]")
    else:
        yield path, x


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rtol", type=float, default=1e-9)
    args = ap.parse_args()
    a = dict(leaves(json.load(open(args.a))))
    b = dict(leaves(json.load(open(args.b))))
    if a.keys() != b.keys():
        diff = sorted(a.keys() ^ b.keys())
        print(f"different structure: {len(diff)} places, e.g. {diff[:3]}")
        return 1
    n = same = 0
    worst, where = 0.0, ""
    for k, x in a.items():
        y = b[k]
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not isinstance(y, (int, float)):
            if x != y:
                print(f"{k}: {x!r} != {y!r}")
                return 1
            continue
        n += 1
        if x == y or (isinstance(x, float) and math.isnan(x) and math.isnan(y)):
            same += 1
            continue
        d = abs(x - y) / max(abs(x), abs(y))
        if d > worst:
            worst, where = d, k
    print(f"{n} numbers, {same} identical, max relative difference {worst:.3g}" + (f" at {where}" if where else ""))
    return 0 if worst <= args.rtol else 1


if __name__ == "__main__":
    sys.exit(main())
