#!/usr/bin/env python3
"""Reference values of the sequential tests (mcstat/sequential.h) at
50 digits, written to tests/data/seq_ref.tsv for tests/c/test_sequential.c.

An independent implementation of the header's formulas: the moments are
summed exactly (mpmath, from the raw values, not from mergeable
accumulators), the e-value, the boundary (closed form two-sided, a
root-find one-sided), the running intersection and the decision rule at
every look.  The data are integer formulas that C and Python evaluate to
the same doubles (one correctly rounded division each, exact scalings by
powers of two), so the test regenerates them instead of reading them.

  python3 tools/refgen/make_seq_ref.py      (from the repository root; 20 s)
"""
from __future__ import annotations

import math
import sys

import mpmath as mp

mp.mp.dps = 50


def value(gen: str, i: int, shift: float) -> float:
    """The i-th value (i >= 0) of a generator; tests/c/test_sequential.c has the same."""
    u = float((i * 7919) % 1000) / 1000.0 - 0.5
    if gen == "lin":
        return u + shift
    if gen == "big":
        return math.ldexp(u + shift, 500)
    if gen == "tiny":
        return math.ldexp(u + shift, -600)
    if gen == "offset":  # 1e9 plus a small signal: the mean needs its low digits
        return 1e9 + (u + shift) * 1e-3
    if gen == "zeros":  # 1% non-zero, heavy right tail
        return float(((i * 31) % 17 + 1) * 10) + shift if (i * 7919) % 1000 < 10 else 0.0
    if gen == "skew":  # a square of the uniform: right skew, light tail
        return (u + 0.5) * (u + 0.5) * 4.0 + shift
    raise ValueError(gen)


# name, kind, alternative, alpha, eps, t_opt, gate, ucb_z, min_n, null, genx, shiftx, geny, shifty, batch, looks
SCENARIOS = [
    ("mean_two", 1, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 0.0, "lin", 0.02, "", 0.0, 200, 20),
    ("mean_greater", 1, 2, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 0.0, "lin", 0.02, "", 0.0, 200, 20),
    ("mean_less", 1, 1, 0.01, 0.0, 1e3, 10.0, 3.0, 100, 0.1, "lin", 0.02, "", 0.0, 150, 20),
    ("mean_plain", 1, 0, 0.1, 0.0, 500.0, 0.0, 0.0, 2, 0.0, "lin", 0.05, "", 0.0, 50, 12),
    ("mean_equiv", 1, 0, 0.05, 0.05, 1e4, 10.0, 3.0, 100, 0.0, "lin", 0.0, "", 0.0, 500, 30),
    ("mean_big", 1, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, math.ldexp(0.01, 500), "big", 0.02, "", 0.0, 200, 10),
    ("mean_tiny", 1, 2, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 0.0, "tiny", 0.02, "", 0.0, 200, 10),
    ("mean_offset", 1, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 1e9, "offset", 0.03, "", 0.0, 200, 10),
    ("mean_zeros", 1, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 1.0, "zeros", 0.0, "", 0.0, 500, 30),
    ("mean2_two", 2, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 0.0, "lin", 0.1, "skew", -1.3, 150, 15),
    ("mean2_unequal", 2, 1, 0.05, 0.0, 2e3, 10.0, 3.0, 100, 0.0, "skew", -1.35, "lin", 0.0, 100, 15),
    ("mean2_equiv", 2, 0, 0.05, 0.1, 1e4, 10.0, 3.0, 100, 0.0, "lin", 0.0, "lin", 0.0, 400, 20),
    ("var_two", 3, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 1.0 / 12.0 * 0.9, "lin", 0.0, "", 0.0, 300, 20),
    ("var_greater", 3, 2, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 1.0 / 12.0 * 0.95, "lin", 0.0, "", 0.0, 300, 20),
    ("var_big", 3, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, math.ldexp(1.0 / 12.0 * 0.9, 1000), "big", 0.0, "", 0.0, 300, 8),
    ("var2_two", 4, 0, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 1.0, "lin", 0.0, "skew", 0.0, 300, 15),
    ("var2_less", 4, 1, 0.05, 0.0, 1e4, 10.0, 3.0, 100, 1.0, "skew", 0.0, "lin", 0.0, 300, 15),
]


def moments(xs):
    n = len(xs)
    if n == 0:
        return 0, mp.mpf(0), mp.mpf(0), mp.mpf(0)
    m = mp.fsum(xs) / n
    m2 = mp.fsum((x - m) ** 2 for x in xs)
    m4 = mp.fsum((x - m) ** 4 for x in xs)
    return n, m, m2, m4


def sample(xs, gate, ucb_z, min_n, on_var=False):
    """hold bits, n, v (variance UCB), w (n var of log s^2), n_gate."""
    n, mean, m2, m4 = moments(xs)
    hold = 1 if n < min_n else 0
    if n < 2:
        return hold | 2, n, None, None, 0
    var = m2 / (n - 1)
    if m2 == 0 or mp.sqrt(var) < 10 * mp.mpf(2) ** -52 * abs(mean):
        return hold | 2, n, None, None, 0
    b2 = n * m4 / m2 ** 2
    n_gate = gate * b2 * (b2 if on_var else 1) if gate > 0 else 0
    if gate > 0 and n < n_gate:
        hold |= 4
    spread = m4 / n - (m2 / n) ** 2
    v = var + ucb_z * mp.sqrt(max(spread, 0) / n)
    w = b2 - mp.mpf(n - 3) / (n - 1)
    return hold, n, v, w, n_gate


def mixture_c(alpha, alt):
    a1 = alpha if alt == 0 or 2 * alpha >= 1 else 2 * alpha
    l = -2 * mp.log(a1)
    return l + mp.log(1 + l)


def log_e(z, a, alt):
    base = z * z * a / (2 * (1 + a)) - mp.log(1 + a) / 2
    if alt == 0:
        return base
    zz = z if alt == 2 else -z
    return base + mp.log(2) + mp.log(mp.ncdf(zz * mp.sqrt(a / (1 + a))))


def boundary(a, alpha, alt):
    two = mp.sqrt((1 + a) / a * (-2 * mp.log(alpha) + mp.log(1 + a)))
    if alt == 0:
        return two
    target = -mp.log(alpha)
    return mp.findroot(lambda z: log_e(z, a, 2) - target, (mp.mpf(0), two), solver="anderson")


def run(sc):
    (name, kind, alt, alpha, eps, t_opt, gate, ucb_z, min_n, null, genx, shx, geny, shy, batch, looks) = sc
    alpha, eps, t_opt, null = mp.mpf(alpha), mp.mpf(eps), mp.mpf(t_opt), mp.mpf(null)
    xs, ys = [], []
    cs = [mp.mpf("-inf"), mp.mpf("inf")]
    log_e_max = mp.mpf("-inf")
    state, decision, n_decided = 0, 0, 0
    two = kind in (2, 4)
    ny_batch = batch * 2 // 3 if name == "mean2_unequal" else batch
    rows = []
    for look in range(1, looks + 1):
        xs += [mp.mpf(value(genx, i, shx)) for i in range(len(xs), len(xs) + batch)]
        if two:
            ys += [mp.mpf(value(geny, i + 500000, shy)) for i in range(len(ys), len(ys) + ny_batch)]
        hx, nx, vx, wx, gx = sample(xs, gate, ucb_z, min_n, kind > 2)
        hy, ny, vy, wy, gy = sample(ys, gate, ucb_z, min_n, kind > 2) if two else (0, 0, 0, 0, 0)
        hold = hx | hy
        row = dict(name=name, look=look, nx=nx, ny=ny, hold=hold)
        if not (hold & 2):
            if kind == 1:
                se = mp.sqrt(vx / nx)
                th = mp.fsum(xs) / nx
                z, t_eff, t0 = (th - null) / se, nx, null
            elif kind == 2:
                se2 = vx / nx + vy / ny
                se = mp.sqrt(se2)
                th = mp.fsum(xs) / nx - mp.fsum(ys) / ny
                z, t_eff, t0 = (th - null) / se, (vx + vy) / se2, null
            elif kind == 3:
                th = mp.log(moments(xs)[2] / (nx - 1))
                se = mp.sqrt(wx / nx)
                z, t_eff, t0 = (th - mp.log(null)) / se, nx, mp.log(null)
            else:
                th = mp.log(moments(xs)[2] / (nx - 1)) - mp.log(moments(ys)[2] / (ny - 1))
                se2 = wx / nx + wy / ny
                se = mp.sqrt(se2)
                z, t_eff, t0 = (th - mp.log(null)) / se, (wx + wy) / se2, mp.log(null)
        if hold:
            row.update(z="NaN", log_e="-Inf", crit="Inf")
        else:
            a = t_eff * mixture_c(alpha, alt) / t_opt
            b = boundary(a, alpha, alt)
            le = log_e(z, a, alt)
            log_e_max = max(log_e_max, le)
            lo = th - b * se if alt in (0, 2) else mp.mpf("-inf")
            hi = th + b * se if alt in (0, 1) else mp.mpf("inf")
            cs = [max(cs[0], lo), min(cs[1], hi)]
            if state == 0:
                if log_e_max >= -mp.log(alpha):
                    state, n_decided = 1, nx
                    decision = -1 if alt == 1 else 1 if alt == 2 else (-1 if z < 0 else 1)
                elif eps > 0 and cs[0] > t0 - eps and cs[1] < t0 + eps:
                    state, n_decided, decision = 1, nx, 0
            row.update(z=mp.nstr(z, 20), log_e=mp.nstr(le, 20), crit=mp.nstr(b, 20))
        p = mp.exp(-log_e_max) if log_e_max > 0 else mp.mpf(1)
        f = (lambda v: mp.exp(v)) if kind in (3, 4) else (lambda v: v)
        row.update(p=mp.nstr(p, 20), cs0=mp.nstr(f(cs[0]), 20), cs1=mp.nstr(f(cs[1]), 20), state=state,
                   decision=decision, n_decided=n_decided)
        rows.append(row)
    return rows


def fmt(v):
    s = str(v)
    return {"-inf": "-Inf", "+inf": "Inf", "inf": "Inf"}.get(s, s)


OUT = "tests/data/seq_ref.tsv"


def main() -> None:
    with open(OUT, "w") as out:
        write(out)
    print(f"wrote {OUT}", file=sys.stderr)


def write(out) -> None:
    out.write("# made by tools/refgen/make_seq_ref.py (mpmath, 50 digits); one row per look\n")
    out.write("# scenario\tkind\talt\talpha\teps\tt_opt\tgate\tucb_z\tmin_n\tnull\tgenx\tshiftx\tgeny\tshifty\tbatch\tbatchy"
              "\tlook\tnx\tny\thold\tz\tlog_e\tcrit\tp\tcs0\tcs1\tstate\tdecision\tn_decided\n")
    for sc in SCENARIOS:
        head = "\t".join(repr(v) if isinstance(v, float) else (str(v) or "-") for v in sc[:15])
        head += "\t" + str((sc[14] * 2 // 3 if sc[0] == "mean2_unequal" else sc[14]) if sc[1] in (2, 4) else 0)
        for r in run(sc):
            out.write(head + "\t" + "\t".join(
                fmt(r[k]) for k in ("look", "nx", "ny", "hold", "z", "log_e", "crit", "p", "cs0", "cs1", "state",
                                    "decision", "n_decided")) + "\n")


if __name__ == "__main__":
    main()
