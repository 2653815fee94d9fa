"""Scan of the F distribution over the documented df range [1e-3, 1e15].

Calls libmcstat through ctypes and reports, over a log-spaced grid of
(df1, df2) and of x (plus the points an outside review listed):
  * MCSTAT_ENUMERIC (or any non-OK status) from mcstat_f_cdf / _f_quantile,
  * monotonicity of the lower tail in x (on the x grid and at 1 -+ ulps),
    counted where F(x_lo) > F(x_hi) (1 + 1e-12), as tests/fuzz/fuzz_dist checks,
  * the peak relative error of the smaller tail (when in [1e-300, 1/2])
    against mpmath at 50 digits (tools/refgen/mpref.py: both tails
    computed directly), for x in 1e-20..1e20: every pair with a df <= 0.03
    against the grid, and a sparser grid of ordinary pairs, split at tails
    of 1e-30 (deeper, the error grows like |log P| ulps),
  * quantiles (p 1e-300..0.5, both tails, one df <= 0.03): the relative
    error in x implied by the mpmath tail at the returned point,
    |T(q) - p| / (q f(q)) (ill-conditioned where df is tiny: T ~ q^(df/2)).
Usage: python3 scan_f_small_df.py [path/to/libmcstat.so] [--quick] [--no-oracle]
(default: build/libmcstat/libmcstat.so; about 2 min for the status and
monotonicity grid and 5 min for the mpmath part on one core; --quick is
about a third).  Prints a summary (the numbers for the accuracy table).
"""
import ctypes
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

args = [a for a in sys.argv[1:] if not a.startswith('--')]
LIB = args[0] if args else os.path.join(HERE, '..', '..', 'build', 'libmcstat', 'libmcstat.so')
sys.stdout.reconfigure(line_buffering=True)
QUICK = '--quick' in sys.argv
ORACLE = '--no-oracle' not in sys.argv

L = ctypes.CDLL(LIB)
D = ctypes.c_double
for fn in ('mcstat_f_cdf', 'mcstat_f_quantile'):
    getattr(L, fn).argtypes = [D, D, D, ctypes.c_int, ctypes.POINTER(D)]
    getattr(L, fn).restype = ctypes.c_int


def fcdf(x, d1, d2, up):
    o = D()
    st = L.mcstat_f_cdf(x, d1, d2, up, ctypes.byref(o))
    return st, o.value


def fq(p, d1, d2, up):
    o = D()
    st = L.mcstat_f_quantile(p, d1, d2, up, ctypes.byref(o))
    return st, o.value


SPECIAL = [0.00103, 0.00164, 1 / 256, 1 / 32, 0.003, 0.01, 100, 159.98, 500, 562, 630784,
           float.fromhex('0x1.ffp+48'), 5.6e14]
step = 2 if QUICK else 4
DFS = sorted(set([10.0 ** (k / step) for k in range(-3 * step, 15 * step + 1)] + SPECIAL))
XS = sorted(set([10.0 ** (k / 2) for k in range(-60, 61)] + [1.5]))
PS = [1e-300, 1e-200, 1e-100, 1e-50, 1e-20, 1e-10, 1e-5, 1e-2, 0.1, 0.5]

t0 = time.time()
n_cdf = n_cdf_bad = n_q = n_q_bad = n_mono = 0
bad_examples, mono_examples = [], []
worst_mono = 0.0
for d1 in DFS:
    for d2 in DFS:
        prev = None
        for x in XS:
            for up in (0, 1):
                n_cdf += 1
                st, v = fcdf(x, d1, d2, up)
                if st:
                    n_cdf_bad += 1
                    if len(bad_examples) < 8:
                        bad_examples.append(('cdf', x, d1, d2, up, st))
            st, v = fcdf(x, d1, d2, 0)
            if st == 0 and prev is not None and prev[1] > v * (1 + 1e-12):
                n_mono += 1
                worst_mono = max(worst_mono, prev[1] / v - 1 if v > 0 else math.inf)
                if len(mono_examples) < 8:
                    mono_examples.append((prev[0], x, d1, d2, prev[1], v))
            if st == 0:
                prev = (x, v)
        # around 1, where large-df F lives: 1 -+ a few ulps
        xs1 = [1.0]
        for _ in range(4):
            xs1 = [math.nextafter(xs1[0], 0)] + xs1 + [math.nextafter(xs1[-1], math.inf)]
        vals = [fcdf(x, d1, d2, 0) for x in xs1]
        for i in range(len(xs1) - 1):
            if vals[i][0] == 0 and vals[i + 1][0] == 0 and vals[i][1] > vals[i + 1][1] * (1 + 1e-12):
                n_mono += 1
                worst_mono = max(worst_mono, vals[i][1] / vals[i + 1][1] - 1)
                if len(mono_examples) < 8:
                    mono_examples.append((xs1[i], xs1[i + 1], d1, d2, vals[i][1], vals[i + 1][1]))
        for p in PS:
            for up in (0, 1):
                n_q += 1
                st, q = fq(p, d1, d2, up)
                if st:
                    n_q_bad += 1
                    if len(bad_examples) < 16:
                        bad_examples.append(('quantile', p, d1, d2, up, st))
t_scan = time.time() - t0
print('grid: %d df values (%d pairs), %d x values, %d p values, %.0f s' % (
    len(DFS), len(DFS) ** 2, len(XS), len(PS), t_scan))
print('cdf calls not OK: %d of %d' % (n_cdf_bad, n_cdf))
print('quantile calls not OK: %d of %d' % (n_q_bad, n_q))
print('monotonicity violations (F(lo) > F(hi)(1+1e-12)): %d, worst relative decrease %.3g' % (n_mono, worst_mono))
for e in bad_examples:
    print('  not OK:', e)
for e in mono_examples:
    print('  not monotone: F(%r) = %r > F(%r) = %r at df %r, %r' % (e[0], e[4], e[1], e[5], e[2], e[3]))

if not ORACLE:
    sys.exit(0)

import mpmath as mp  # noqa: E402
import mpref  # noqa: E402

# Accuracy against mpmath: pairs with a small df (<= 0.03, where the
# incomplete beta needs its small-parameter methods) against every df, and
# a band of ordinary pairs for comparison.
SMALL = [d for d in DFS if d <= 0.03]
OTHER = DFS[:: (4 if QUICK else 2)] + SPECIAL
ODF = [d for d in DFS if d > 0.03][:: (4 if QUICK else 2)]
XO = [10.0 ** k for k in range(-20, 21, 2 if QUICK else 1)] + [1.5, 0.5, 2.0]


def rel_err(x, d1, d2):
    """(relative error of the smaller tail, 'deep' if that tail is below 1e-30).
    Deep in a tail the error grows like |log P| ulps (P = exp of a number
    near log P, which itself is known to an ulp): 1e-13 at P = 1e-300."""
    P, Q = mpref.f_tails(x, d1, d2)
    worst, deep = 0.0, False
    for up, ref in ((0, P), (1, Q)):
        if ref < mp.mpf('1e-300') or ref > 0.5:
            continue  # the larger tail is 1 - small; its error is absolute
        st, v = fcdf(x, d1, d2, up)
        if st:
            return math.inf, False
        worst = max(worst, float(abs(mp.mpf(v) - ref) / ref))
        deep = ref < mp.mpf('1e-30')
    return worst, deep


t0 = time.time()
peak = {}  # region -> (err, point)
n_pts = n_fail = 0
for s in SMALL:
    for o in sorted(set(OTHER)):
        for (d1, d2) in ((s, o), (o, s)):
            for x in XO:
                e, deep = rel_err(x, d1, d2)
                n_pts += 1
                if e == math.inf:
                    n_fail += 1
                    continue
                key = 'one df <= 0.03, ' + ('tail < 1e-30' if deep else 'tail >= 1e-30')
                if e > peak.get(key, (0,))[0]:
                    peak[key] = (e, (x, d1, d2))
for d1 in ODF:
    for d2 in ODF:
        for x in XO[::3]:
            e, deep = rel_err(x, d1, d2)
            n_pts += 1
            if e == math.inf:
                n_fail += 1
                continue
            key = 'both df > 0.03, ' + ('tail < 1e-30' if deep else 'tail >= 1e-30')
            if e > peak.get(key, (0,))[0]:
                peak[key] = (e, (x, d1, d2))
print('accuracy: %d points against mpmath (50 digits), %d not OK (left out of the peaks), %.0f s' % (
    n_pts, n_fail, time.time() - t0))
for k, (e, pt) in sorted(peak.items()):
    print('  %-32s peak relative error of the smaller tail %.3g at (x, df1, df2) = %r' % (k, e, pt))

# Quantiles: the smaller tail at q against p (mpmath), one df small
t0 = time.time()
qpeak = (0.0, None)
nq = 0
for s in SMALL[:: 2 if QUICK else 1]:
    for o in DFS[:: 6 if QUICK else 3]:
        for (d1, d2) in ((s, o), (o, s)):
            for p in PS:
                for up in (0, 1):
                    st, q = fq(p, d1, d2, up)
                    if st or not (0 < q < math.inf) or not (1e-300 < d1 * q / d2 < 1e300):
                        continue
                    P, Q = mpref.f_tails(q, d1, d2)
                    T = Q if up else P
                    # relative error of q implied by the tail mismatch: |T - p| / (q f(q))
                    dens = mpref.f_pdf(q, d1, d2) * q
                    if dens == 0:
                        continue
                    e = float(abs(T - p) / dens)
                    nq += 1
                    if e > qpeak[0]:
                        qpeak = (e, (p, d1, d2, up, q))
print('quantiles: %d checked against mpmath, peak relative error in x %.3g at (p, df1, df2, upper, q) = %r, %.0f s' % (
    nq, qpeak[0], qpeak[1], time.time() - t0))
