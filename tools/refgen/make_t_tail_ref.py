#!/usr/bin/env python3
# Writes tests/data/t_tail_ref.tsv: both tails of Student's t, P(T <= t) and
# P(T > t), at 40 digits with mpmath, for non-integer df in [1, 1000] and
# |t| from 0 to 1e8 (including p-values far below the smallest double and
# the t quantiles at the usual levels), and the upper quantiles at
# p = 0.025, 0.005 and 5e-7.  The t and df are exact doubles (written with
# 17 digits).  Read by tests/c/test_pixels.c (the fast tail and quantile of
# libmcstat/src/pixels_dist.c and t_quantiles.c).  Run from the repository root:
#   .venv/bin/python tools/refgen/make_t_tail_ref.py
import mpmath as mp
import math
import random

mp.mp.dps = 40


def tails(t, df):
    t, df = mp.mpf(t), mp.mpf(df)
    if t == 0:
        return mp.mpf(0.5), mp.mpf(0.5)
    x = df / (df + t * t)
    small = mp.betainc(df / 2, mp.mpf(1) / 2, 0, x, regularized=True) / 2
    big = 1 - small
    return (big, small) if t > 0 else (small, big)


def quantile(p, df):
    """t with P(T > t) = p, p < 1/2."""
    df = mp.mpf(df)
    lo, hi = mp.mpf(-3), mp.mpf(16)  # bisection in log t: the upper tail decreases
    for _ in range(150):
        mid = (lo + hi) / 2
        if tails(mp.exp(mid), df)[1] > p:
            lo = mid
        else:
            hi = mid
    return mp.exp((lo + hi) / 2)


def main():
    rng = random.Random(20261203)
    rows = []
    dfs = [math.exp(rng.uniform(0.0, math.log(1000.0))) for _ in range(70)]
    dfs += [1.0000001, 7.3, 13.9, 999.99]
    for df in dfs:
        df = float(df)
        ts = [math.exp(rng.uniform(math.log(1e-6), math.log(1e8))) for _ in range(8)]
        ts += [rng.uniform(0.0, 4.0) for _ in range(4)] + [1.96, 2.5, 3.0, math.sqrt(df), 30.0]
        for t in ts:
            for sgn in (1.0, -1.0):
                t = sgn * float(t)
                lo, up = tails(t, df)
                rows.append(f"tail\t{t!r}\t{df!r}\t{mp.nstr(lo, 20)}\t{mp.nstr(up, 20)}")
    for df in list(dfs[::5]) + [1.0, 2.5, 7.0, 14.0]:
        df = float(df)
        for p in (0.025, 0.005, 5e-7):
            rows.append(f"quantile\t{p!r}\t{df!r}\t{mp.nstr(quantile(mp.mpf(p), df), 20)}\t0")
    with open("tests/data/t_tail_ref.tsv", "w") as f:
        f.write("# kind\tt (or p)\tdf\tP(T <= t) (or the upper p-quantile)\tP(T > t)\n")
        f.write("# mpmath at 40 digits (tools/refgen/make_t_tail_ref.py)\n")
        f.write("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
