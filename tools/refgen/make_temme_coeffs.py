#!/usr/bin/env python3
"""Prints the Taylor coefficients at eta = 0 of C0 and C1 in Temme's uniform
expansion of the incomplete gamma function (DLMF 8.12.3-8.12.9), the two
tables of temme_c0 and temme_c1 in libmcstat/src/special.c:

  C0(eta) = 1/u - 1/eta,
  C1(eta) = 1/eta^3 - 1/u^3 - 1/u^2 - 1/(12 u),
  u - log(1 + u) = eta^2 / 2,  u and eta of the same sign (u = x/a - 1).

Both closed forms cancel near eta = 0, where special.c sums these series
instead.  The coefficients are exact rationals: u(eta) is the reversion of
eta = u sqrt(2 (u - log(1+u)) / u^2) in rational arithmetic (fractions);
mpmath then checks the series against the closed forms at 60 digits, with
u solved from eta numerically (independent of the reversion).

  python3 tools/refgen/make_temme_coeffs.py            print both tables
  python3 tools/refgen/make_temme_coeffs.py --check    compare with special.c

special.c is not rewritten: its tables are code; --check fails (exit 1) if
any coefficient differs from the committed one, as text or as a number.
"""
import argparse
import os
import re
import sys
from fractions import Fraction as Q

import mpmath as mp

N_COEF = 9          # coefficients per table in special.c
ORDER = N_COEF + 4  # series terms kept (C1 needs three more than C0)
SPECIAL_C = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                         "libmcstat", "src", "special.c")


def mul(a, b):
    c = [Q(0)] * ORDER
    for i, x in enumerate(a):
        if x:
            for j in range(ORDER - i):
                c[i + j] += x * b[j]
    return c


def inv(a):
    """1 / a for a power series with a[0] != 0."""
    b = [Q(0)] * ORDER
    b[0] = 1 / a[0]
    for n in range(1, ORDER):
        b[n] = -sum(a[k] * b[n - k] for k in range(1, n + 1)) / a[0]
    return b


def sqrt1(a):
    """sqrt(a) for a power series with a[0] = 1."""
    b = [Q(0)] * ORDER
    b[0] = Q(1)
    for n in range(1, ORDER):
        b[n] = (a[n] - sum(b[k] * b[n - k] for k in range(1, n))) / 2
    return b


def series():
    # 2 (u - log(1+u)) / u^2 = sum_{n>=0} 2 (-1)^n u^n / (n + 2)
    g = sqrt1([Q(2 * (-1) ** n, n + 2) for n in range(ORDER)])  # eta = u g(u)
    # u = eta h(eta): the reversion, by fixed-point iteration h = 1 / g(eta h),
    # each pass fixing one more coefficient
    h = [Q(1)] + [Q(0)] * (ORDER - 1)
    for _ in range(ORDER):
        u = [Q(0)] + h[:-1]                                     # eta h(eta)
        comp = [Q(0)] * ORDER                                   # g(u(eta))
        p = [Q(1)] + [Q(0)] * (ORDER - 1)
        for k in range(ORDER):
            comp = [c + g[k] * x for c, x in zip(comp, p)]
            p = mul(p, u)
        h = inv(comp)
    r = inv(h)                                                  # eta / u
    r2, r3 = mul(r, r), mul(mul(r, r), r)
    # 1/u = r / eta, so C0 = (r - 1) / eta
    c0 = r[1:1 + N_COEF]
    # C1 eta^3 = 1 - r^3 - eta r^2 - eta^2 r / 12
    t = [Q(0)] * ORDER
    for n in range(ORDER):
        t[n] = (1 if n == 0 else 0) - r3[n] - (r2[n - 1] if n >= 1 else 0) - (r[n - 2] / 12 if n >= 2 else 0)
    assert t[0] == t[1] == t[2] == 0
    c1 = t[3:3 + N_COEF]
    return c0, c1


def check_mpmath(c0, c1):
    """The series against the closed forms, u from eta by root finding."""
    mp.mp.dps = 60
    worst = 0
    for eta in (mp.mpf("0.001"), mp.mpf("-0.002"), mp.mpf("0.0005")):
        u = mp.findroot(lambda v: v - mp.log1p(v) - eta ** 2 / 2, eta)
        for cs, closed, drop in ((c0, 1 / u - 1 / eta, N_COEF),
                                 (c1, 1 / eta ** 3 - 1 / u ** 3 - 1 / u ** 2 - 1 / (12 * u), N_COEF)):
            s = mp.fsum(mp.mpf(c.numerator) / c.denominator * eta ** k for k, c in enumerate(cs))
            # what the truncated series leaves: O(eta^N_COEF), coefficients below 1e-5
            err = abs(s - closed) / abs(eta) ** drop
            worst = max(worst, err)
    if worst > 1e-4:
        sys.exit("mpmath disagrees with the rational series: %s" % mp.nstr(worst, 5))


def c_text(q):
    """A coefficient as special.c writes it: N.0 / D (D in double when it
    does not fit an int)."""
    d = "%d.0" % q.denominator if q.denominator > 2 ** 31 - 1 else "%d" % q.denominator
    return "%d.0 / %s" % (q.numerator, d) if q.denominator != 1 else "%d.0" % q.numerator


def committed(name):
    text = open(SPECIAL_C).read()
    m = re.search(r"static double %s\(.*?static const double c\[\] = \{(.*?)\};" % name, text, re.S)
    if not m:
        sys.exit("special.c: no table in %s" % name)
    return [" ".join(t.split()) for t in m.group(1).split(",")]


def value(text):
    num, _, den = text.partition("/")
    return Q(num.strip()) / Q(den.strip() or "1")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="compare with libmcstat/src/special.c; exit 1 on a difference")
    args = ap.parse_args()
    c0, c1 = series()
    check_mpmath(c0, c1)
    bad = 0
    for name, cs in (("temme_c0", c0), ("temme_c1", c1)):
        texts = [c_text(q) for q in cs]
        print("%s: static const double c[] = {%s};" % (name, ", ".join(texts)))
        if args.check:
            have = committed(name)
            for k, (want, got) in enumerate(zip(texts, have)):
                if want != got or value(got) != cs[k] or float(value(got)) != float(cs[k]):
                    print("  %s c[%d]: special.c has %s, the series gives %s" % (name, k, got, want))
                    bad += 1
            if len(have) != len(texts):
                print("  %s: special.c has %d coefficients, expected %d" % (name, len(have), len(texts)))
                bad += 1
    if args.check:
        print("special.c: %s" % ("agrees, every coefficient" if not bad else "%d differences" % bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
