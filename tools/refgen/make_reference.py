#!/usr/bin/env python3
"""Writes tests/data/ref_data.h: stiff data sets and 50-digit reference results.

Run from the repository root:  python3 tools/refgen/make_reference.py
Needs mpmath and scipy (scipy only for starting values of the quantiles).

Every data set is a list of float64 values; its moments are computed exactly
in rational arithmetic (fractions.Fraction of the float64 values), then the
test statistics, degrees of freedom, p-values, critical values and confidence
intervals at 50 digits with mpref.py.  The C tests compare libmcstat with
these numbers, so neither R nor mpmath is needed at test time.
"""
import math
import os
import random
import sys
from fractions import Fraction

import mpmath as mp
from scipy import special

sys.path.insert(0, os.path.dirname(__file__))
import mpref  # noqa: E402

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
OUT = os.path.join(ROOT, "tests", "data", "ref_data.h")


# ---- data sets -------------------------------------------------------------

def nist(name):
    with open(os.path.join(ROOT, "tests", "data", "nist", name + ".txt")) as f:
        return [float(l) for l in f if l.strip() and not l.startswith("#")]


def numacc(x):
    x = int(x)
    return [float(f"{x}.2")] + [float(f"{x}.1"), float(f"{x}.3")] * 500


def normal(rng, n, mu, sd):
    return [mu + sd * rng.gauss(0.0, 1.0) for _ in range(n)]


def build_datasets():
    rng = random.Random(20261123)
    d = {}
    d["lew"] = nist("Lew")
    d["mavro"] = nist("Mavro")
    d["michelso"] = nist("Michelso")
    d["numacc1"] = [10000001.0, 10000003.0, 10000002.0]
    d["numacc2"] = numacc(1)
    d["numacc3"] = numacc(1000000)
    d["numacc4"] = numacc(10000000)
    # 1e9 + noise: naive one-pass moments and naive means lose digits here
    d["off_a"] = [1e9 + v for v in normal(rng, 1000, 0.0, 1e-3)]
    d["off_b"] = [1e9 + v for v in normal(rng, 777, 2e-4, 1.5e-3)]
    # magnitudes near 1e+-300: squares overflow or underflow
    d["big_a"] = [1e300 * v for v in normal(rng, 200, 1.0, 0.1)]
    d["big_b"] = [1e300 * v for v in normal(rng, 150, 1.03, 0.12)]
    d["tiny_a"] = [1e-300 * v for v in normal(rng, 200, 1.0, 0.1)]
    d["tiny_b"] = [1e-300 * v for v in normal(rng, 150, 1.03, 0.12)]
    d["mid_a"] = [1e150 * v for v in normal(rng, 120, 1.0, 0.1)]
    d["mid_t"] = [1e-150 * v for v in normal(rng, 120, 1.0, 0.1)]
    # far-apart samples: p-values far below 1e-50
    d["sep_a"] = normal(rng, 30, 10.0, 1.0)
    d["sep_b"] = normal(rng, 40, -25.0, 2.0)
    d["wide_x"] = normal(rng, 100, 0.0, 10.0)
    d["wide_y"] = normal(rng, 100, 0.0, 0.5)
    d["huge_t"] = normal(rng, 8, 1e6, 1e-3)
    # the smallest samples
    d["two_a"] = [1.0, 3.0]
    d["two_b"] = [2.0, 2.25]
    # an ordinary sample, for ordinary p-values
    d["plain_x"] = normal(rng, 25, 0.3, 1.0)
    d["plain_y"] = normal(rng, 31, 0.0, 1.5)
    return d


# Large data sets described by a formula the C test evaluates exactly:
# x_i = base + ((i * mult) % mod) * 2^-20, i = 0..n-1 (all exactly representable).
FORMULAS = {
    "form_a": (1000000, 1e9, 7919, 1009),
    "form_b": (999983, 1e9 + 3 * 2.0 ** -20, 104729, 1013),
}


def formula_values_exact(n, base, mult, mod):
    counts = [0] * mod
    for i in range(n):
        counts[(i * mult) % mod] += 1
    step = Fraction(1, 2 ** 20)
    b = Fraction(base)
    s1 = sum(c * (b + k * step) for k, c in enumerate(counts))
    mean = s1 / n
    m2 = sum(c * (b + k * step - mean) ** 2 for k, c in enumerate(counts))
    return n, mean, m2


# ---- exact moments and reference statistics --------------------------------

def exact_moments(xs):
    fx = [Fraction(v) for v in xs]
    n = len(fx)
    mean = sum(fx) / n
    m2 = sum((v - mean) ** 2 for v in fx)
    return n, mean, m2


def mpf(fr):
    return mp.mpf(fr.numerator) / fr.denominator


def t_quantile(p, df, upper):
    """t with P[T > x] = p (upper) or P[T <= x] = p, via the positive root
    of P[T > u] = min(p, 1 - p) and symmetry."""
    p = mp.mpf(p)
    if p == mp.mpf(0.5):
        return mp.mpf(0)
    small = min(p, 1 - p)
    x0 = -special.stdtrit(float(df), float(small)) if float(small) > 1e-300 else 1e10
    if not (x0 > 0 and math.isfinite(x0)):
        x0 = 1.0
    u = mpref.quantile(lambda x: mpref.t_tails(x, df), lambda x: mpref.t_pdf(x, df), small, True, x0)
    positive = (p < 0.5) == bool(upper)
    return u if positive else -u


def _start(x0):
    return x0 if (x0 > 0 and math.isfinite(x0)) else 1.0


def chisq_quantile(p, df, upper):
    x0 = special.chdtri(float(df), float(p)) if upper else special.chdtri(float(df), 1 - float(p))
    return mpref.quantile(lambda x: mpref.chisq_tails(x, df), lambda x: mpref.chisq_pdf(x, df), p, upper, _start(x0))


def f_quantile(p, df1, df2, upper):
    x0 = special.fdtri(float(df1), float(df2), 1 - float(p)) if upper else special.fdtri(float(df1), float(df2), float(p))
    return mpref.quantile(lambda x: mpref.f_tails(x, df1, df2), lambda x: mpref.f_pdf(x, df1, df2), p, upper, _start(x0))


ALT = {"two-sided": 0, "less": 1, "greater": 2}


def finish(tails, quant, alt, alpha, support_lo):
    """p-value and critical values as libmcstat defines them."""
    P, Q = tails
    alpha = mp.mpf(alpha)
    if alt == "two-sided":
        p = min(1, 2 * min(P, Q))
        c0, c1 = quant(alpha / 2, False), quant(alpha / 2, True)
    elif alt == "less":
        p = P
        c0, c1 = quant(alpha, False), mp.inf
    else:
        p = Q
        c0, c1 = support_lo, quant(alpha, True)
    return p, c0, c1


def ref_t1(ds, mu0, alt, alpha):
    n, mean, m2 = ds
    var = mpf(m2) / (n - 1)
    se = mp.sqrt(var / n)
    t = (mpf(mean) - mp.mpf(mu0)) / se
    df = n - 1
    p, c0, c1 = finish(mpref.t_tails(t, df), lambda q, u: t_quantile(q, df, u), alt, alpha, -mp.inf)
    m = mpf(mean)
    return dict(statistic=t, df0=df, df1=mp.nan, p=p, c0=c0, c1=c1,
                ci0=m - c1 * se, ci1=m - c0 * se, e0=m, e1=mp.nan)


def ref_t2(dx, dy, mu0, alt, alpha):
    nx, mx, m2x = dx
    ny, my, m2y = dy
    a = mpf(m2x) / (nx - 1) / nx
    b = mpf(m2y) / (ny - 1) / ny
    se = mp.sqrt(a + b)
    diff = mpf(mx) - mpf(my)
    t = (diff - mp.mpf(mu0)) / se
    df = (a + b) ** 2 / (a ** 2 / (nx - 1) + b ** 2 / (ny - 1))
    p, c0, c1 = finish(mpref.t_tails(t, df), lambda q, u: t_quantile(q, df, u), alt, alpha, -mp.inf)
    return dict(statistic=t, df0=df, df1=mp.nan, p=p, c0=c0, c1=c1,
                ci0=diff - c1 * se, ci1=diff - c0 * se, e0=mpf(mx), e1=mpf(my))


def ref_var1(ds, sigma2, alt, alpha):
    n, mean, m2 = ds
    x2 = mpf(m2) / mp.mpf(sigma2)
    df = n - 1
    p, c0, c1 = finish(mpref.chisq_tails(x2, df), lambda q, u: chisq_quantile(q, df, u), alt, alpha, mp.mpf(0))
    M2 = mpf(m2)
    return dict(statistic=x2, df0=df, df1=mp.nan, p=p, c0=c0, c1=c1,
                ci0=M2 / c1 if c1 != mp.inf else mp.mpf(0), ci1=M2 / c0 if c0 != 0 else mp.inf,
                e0=M2 / df, e1=mp.nan)


def ref_var2(dx, dy, ratio, alt, alpha):
    nx, _, m2x = dx
    ny, _, m2y = dy
    est = (mpf(m2x) / (nx - 1)) / (mpf(m2y) / (ny - 1))
    f = est / mp.mpf(ratio)
    d1, d2 = nx - 1, ny - 1
    p, c0, c1 = finish(mpref.f_tails(f, d1, d2), lambda q, u: f_quantile(q, d1, d2, u), alt, alpha, mp.mpf(0))
    return dict(statistic=f, df0=d1, df1=d2, p=p, c0=c0, c1=c1,
                ci0=est / c1 if c1 != mp.inf else mp.mpf(0), ci1=est / c0 if c0 != 0 else mp.inf,
                e0=est, e1=mp.nan)


# (kind, x, y, null value, alternative, alpha)
CASES = [
    ("T_1", "lew", None, -177.435 + 10.0, "two-sided", 0.05),
    ("T_1", "mavro", None, 2.0018, "two-sided", 0.05),
    ("T_1", "michelso", None, 299.85, "greater", 0.01),
    ("T_1", "numacc1", None, 10000002.5, "two-sided", 0.05),
    ("T_1", "numacc2", None, 1.2 + 1e-3, "less", 0.05),
    ("T_1", "numacc3", None, 1000000.2 + 1e-3, "two-sided", 0.05),
    ("T_1", "numacc4", None, 10000000.2 - 1e-3, "two-sided", 0.1),
    ("T_1", "off_a", None, 1e9 + 1e-4, "two-sided", 0.05),
    ("T_1", "form_a", None, 1e9 + 504 * 2.0 ** -20, "two-sided", 0.05),
    ("T_1", "big_a", None, 1.01e300, "two-sided", 0.05),
    ("T_1", "tiny_a", None, 1.02e-300, "greater", 0.05),
    ("T_1", "sep_a", None, 0.0, "two-sided", 0.05),
    ("T_1", "huge_t", None, 1e6 + 1.0, "less", 0.01),
    ("T_1", "two_a", None, 0.5, "two-sided", 0.05),
    ("T_1", "plain_x", None, 0.0, "two-sided", 0.05),
    ("T_2", "off_a", "off_b", 0.0, "two-sided", 0.05),
    ("T_2", "form_a", "form_b", 0.0, "two-sided", 0.05),
    ("T_2", "big_a", "big_b", 0.0, "two-sided", 0.05),
    ("T_2", "tiny_a", "tiny_b", 0.0, "less", 0.05),
    ("T_2", "numacc3", "numacc4", -9000000.0, "two-sided", 0.05),
    ("T_2", "two_a", "two_b", 0.0, "two-sided", 0.05),
    ("T_2", "sep_a", "sep_b", 0.0, "greater", 0.05),
    ("T_2", "plain_x", "plain_y", 0.1, "two-sided", 0.01),
    ("VAR_1", "lew", None, 277.332168044316 ** 2 * 1.1, "two-sided", 0.05),
    ("VAR_1", "numacc4", None, 0.01, "two-sided", 0.05),
    ("VAR_1", "off_a", None, 1.1e-6, "less", 0.05),
    ("VAR_1", "mid_a", None, 1.1e298, "two-sided", 0.05),
    ("VAR_1", "mid_t", None, 0.8e-302, "two-sided", 0.05),
    ("VAR_1", "wide_x", None, 1.0, "greater", 0.05),
    ("VAR_1", "plain_x", None, 1.0, "two-sided", 0.05),
    ("VAR_2", "wide_x", "wide_y", 1.0, "two-sided", 0.05),
    ("VAR_2", "big_a", "big_b", 1.0, "two-sided", 0.05),
    ("VAR_2", "tiny_a", "tiny_b", 1.0, "less", 0.05),
    ("VAR_2", "lew", "michelso", 1.0, "two-sided", 0.05),
    ("VAR_2", "numacc2", "numacc3", 1.0, "two-sided", 0.05),
    ("VAR_2", "off_a", "off_b", 0.5, "greater", 0.05),
    ("VAR_2", "plain_x", "plain_y", 1.0, "two-sided", 0.05),
    ("VAR_2", "two_a", "two_b", 2.0, "two-sided", 0.2),
]

# Quantile table: (kind, p, df1, df2, upper)
Q_DFS = [1, 2, 5, 30, 1e3, 1e6, 1e9]
Q_PS = [0.3, 0.025, 1e-5, 1e-20, 1e-100, 1e-300]
F_PAIRS = [(1, 1), (3, 7), (30, 1e3), (2, 1e9), (1e6, 1e6), (1e9, 1e9)]


def fmt(v):
    v = mp.mpf(v) if not isinstance(v, mp.mpf) else v
    if mp.isnan(v):
        return "NAN"
    if mp.isinf(v):
        return "INFINITY" if v > 0 else "-INFINITY"
    f = float(v)  # correctly rounded from 50 digits
    if f == 0.0 and v != 0:
        return "0.0 /* underflows */"
    if math.isinf(f):
        return ("INFINITY" if f > 0 else "-INFINITY") + " /* overflows */"
    return f.hex() if f != 0.0 else "0.0"


def main():
    data = build_datasets()
    exact = {k: exact_moments(v) for k, v in data.items()}
    for k, (n, base, mult, mod) in FORMULAS.items():
        exact[k] = formula_values_exact(n, base, mult, mod)
    names = list(data) + list(FORMULAS)
    out = []
    out.append("/* Generated by tools/refgen/make_reference.py; do not edit. */")
    out.append("#ifndef MCSTAT_REF_DATA_H\n#define MCSTAT_REF_DATA_H\n#include <math.h>\n#include <stddef.h>\n")
    for k, v in data.items():
        out.append(f"static const double ds_{k}[{len(v)}] = {{")
        for i in range(0, len(v), 4):
            out.append("    " + ", ".join(x.hex() for x in v[i:i + 4]) + ",")
        out.append("};")
    out.append("\ntypedef struct { const char *name; const double *x; size_t n;"
               " double base; unsigned long mult, mod; /* formula when x == NULL */"
               " double mean, var; } ref_dataset;")
    out.append("static const ref_dataset REF_DATASETS[] = {")
    for k in names:
        n, mean, m2 = exact[k]
        var = mpf(m2) / (n - 1)
        if k in FORMULAS:
            _, base, mult, mod = FORMULAS[k]
            out.append(f'    {{"{k}", NULL, {n}, {float(base).hex()}, {mult}, {mod}, {fmt(mpf(mean))}, {fmt(var)}}},')
        else:
            out.append(f'    {{"{k}", ds_{k}, {n}, 0, 0, 0, {fmt(mpf(mean))}, {fmt(var)}}},')
    out.append("};")
    out.append(f"#define REF_NDATASETS {len(names)}\n")

    out.append("typedef struct { const char *kind, *x, *y; double null_value; int alternative; double alpha;"
               " double statistic, df0, df1, p, c0, c1, ci0, ci1, e0, e1; } ref_case;")
    out.append("static const ref_case REF_CASES[] = {")
    for kind, x, y, nv, alt, alpha in CASES:
        if kind == "T_1":
            r = ref_t1(exact[x], nv, alt, alpha)
        elif kind == "T_2":
            r = ref_t2(exact[x], exact[y], nv, alt, alpha)
        elif kind == "VAR_1":
            r = ref_var1(exact[x], nv, alt, alpha)
        else:
            r = ref_var2(exact[x], exact[y], nv, alt, alpha)
        vals = ", ".join(fmt(r[k]) for k in ("statistic", "df0", "df1", "p", "c0", "c1", "ci0", "ci1", "e0", "e1"))
        yy = f'"{y}"' if y else "NULL"
        out.append(f'    {{"{kind}", "{x}", {yy}, {float(nv).hex()}, {ALT[alt]}, {alpha!r}, {vals}}},')
        print(kind, x, y, alt, "p =", mp.nstr(r["p"], 6), file=sys.stderr)
    out.append("};")
    out.append(f"#define REF_NCASES {len(CASES)}\n")

    out.append("typedef struct { char kind; double p, df1, df2; int upper; double x; } ref_quantile;")
    out.append("static const ref_quantile REF_QUANTILES[] = {")
    for df in Q_DFS:
        for p in Q_PS:
            x = t_quantile(mp.mpf(p), df, True)
            out.append(f"    {{'t', {p!r}, {df!r}, 0, 1, {fmt(x)}}},")
            for up in (False, True):
                x = chisq_quantile(mp.mpf(p), df, up)
                out.append(f"    {{'c', {p!r}, {df!r}, 0, {int(up)}, {fmt(x)}}},")
        print("quantiles df", df, file=sys.stderr)
    for d1, d2 in F_PAIRS:
        for p in Q_PS:
            for up in (False, True):
                x = f_quantile(mp.mpf(p), d1, d2, up)
                out.append(f"    {{'f', {p!r}, {d1!r}, {d2!r}, {int(up)}, {fmt(x)}}},")
        print("quantiles F", d1, d2, file=sys.stderr)
    out.append("};")
    out.append("#define REF_NQUANTILES (sizeof REF_QUANTILES / sizeof REF_QUANTILES[0])\n")

    # log tail probabilities at points where naive formulas fail
    out.append("typedef struct { char kind; double x, df1, df2; int upper; double logp; } ref_logcdf;")
    out.append("static const ref_logcdf REF_LOGCDF[] = {")
    pts = []
    for df in [1, 3, 30, 1e4, 1e7]:
        for x in [0.25, 3.0, 40.0, 1e4, 1e20]:
            pts.append(("t", x, df, 0, True))
            pts.append(("t", -x, df, 0, True))
    for df in [1, 4, 100, 1e5, 1e8]:
        for z in [-30, -5, -0.5, 0.5, 5, 40]:
            x = df + z * math.sqrt(2 * df)
            if x <= 0:
                x = df * 10 ** (z / 3)
            pts.append(("c", x, df, 0, False))
            pts.append(("c", x, df, 0, True))
    for d1, d2 in [(1, 1), (2, 50), (40, 3), (1e4, 1e4), (5, 1e8), (1e8, 1e7)]:
        for z in [-30, -3, 0.3, 3, 30]:
            x = math.exp(z * math.sqrt(2 / d1 + 2 / d2))
            pts.append(("f", x, d1, d2, False))
            pts.append(("f", x, d1, d2, True))
    # Temme's expansion (df > 2e8): the series and fraction at 50 digits where
    # they are affordable, quadrature of the density beyond (whose tanh-sinh
    # error reaches 1e-12 in the far tails, so there only |z| <= 5).
    for df in [3e8, 1e10, 1e12, 1e14]:
        for z in [-30, -5, -0.5, 0.5, 5, 30]:
            if df > 1e11 and abs(z) > 5:
                continue
            x = df + z * math.sqrt(2 * df)
            pts.append(("q" if df > 1e11 else "c", x, df, 0, z > 0))
    # F with both df >= 1e14 (the beta's uniform expansion), against
    # quadrature, which is first checked against the continued fraction.
    for z in [-5, 0.5, 4]:
        x = math.exp(z * math.sqrt(4 / 1e6))
        P, Q = mpref.f_tails(x, 1e6, 1e6)
        with mp.workdps(40):
            qd = mpref.f_tail_quad(x, 1e6, 1e6, z > 0)
        assert abs(qd / (Q if z > 0 else P) - 1) < 1e-25, "F quadrature disagrees with the fraction"
    for d1, d2 in [(1e14, 1e14), (1e14, 3e15), (2e16, 5e14), (1e20, 1e19)]:
        for z in [-5, -0.5, 0.5, 5]:
            x = math.exp(z * math.sqrt(2 / d1 + 2 / d2))
            pts.append(("fq", x, d1, d2, z > 0))
    for kind, x, d1, d2, up in pts:
        if kind == "fq":
            with mp.workdps(40):
                lp = mp.log(mpref.f_tail_quad(x, d1, d2, up))
            out.append(f"    {{'f', {float(x).hex()}, {d1!r}, {d2!r}, {int(up)}, {fmt(lp)}}},")
            continue
        if kind == "q":
            with mp.workdps(45):
                lp = mp.log(mpref.chisq_tail_quad(x, d1, up))
            out.append(f"    {{'c', {float(x).hex()}, {d1!r}, {d2!r}, {int(up)}, {fmt(lp)}}},")
            continue
        if kind == "t":
            P, Q = mpref.t_tails(x, d1)
        elif kind == "c":
            P, Q = mpref.chisq_tails(x, d1)
        else:
            P, Q = mpref.f_tails(x, d1, d2)
        lp = mp.log(Q if up else P)
        out.append(f"    {{'{kind}', {float(x).hex()}, {d1!r}, {d2!r}, {int(up)}, {fmt(lp)}}},")
    out.append("};")
    out.append("#define REF_NLOGCDF (sizeof REF_LOGCDF / sizeof REF_LOGCDF[0])\n")
    out.append("#endif")
    with open(OUT, "w") as f:
        f.write("\n".join(out) + "\n")
    print("wrote", OUT, file=sys.stderr)


if __name__ == "__main__":
    main()
