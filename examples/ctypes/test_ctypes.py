#!/usr/bin/env python3
"""Checks libmcstat through ctypes alone (standard library, no NumPy, no
pybind11) against the reference numbers of the C tests
(tests/data/ffi_ref.txt, made by tools/refgen/make_ffi_ref.py from the
50-digit, exact-fraction and R references).

usage: test_ctypes.py [path/to/libmcstat.so]    (or $MCSTAT_LIB, or pkg-config)
Prints "N passed, N failed" and exits non-zero on any failure.
"""
import ctypes
import math
import os
import struct
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import mcstat_ctypes as mc  # noqa: E402

REF = os.path.join(HERE, "..", "..", "tests", "data", "ffi_ref.txt")
passed = failed = 0


def f64(tok):
    return struct.unpack("<d", struct.pack("<Q", int(tok, 16)))[0]


def rel_err(got, want):
    if got == want or (math.isnan(got) and math.isnan(want)):
        return 0.0
    if not (math.isfinite(got) and math.isfinite(want)):
        return math.inf
    return abs(got) if want == 0 else abs(got - want) / abs(want)


def expect(cond, what):
    global passed, failed
    if cond:
        passed += 1
    else:
        failed += 1
        print("FAIL:", what)


def load_ref():
    data, cases, quantiles, logcdfs, ks, ksblocks, blocks = {}, [], [], [], [], {}, []
    for line in open(REF):
        if line.startswith("#"):
            continue
        t = line.split()
        if t[0] == "data":
            data[t[1]] = [f64(v) for v in t[5:5 + int(t[2])]]
        elif t[0] == "formula":
            n, base, mult, mod = int(t[2]), f64(t[3]), int(t[4]), int(t[5])
            data[t[1]] = (n, base, mult, mod)
        elif t[0] == "case":
            cases.append((t[1], t[2], t[3], f64(t[4]), int(t[5]), [f64(v) for v in t[6:]]))
        elif t[0] == "quantile":
            quantiles.append((t[1], f64(t[2]), f64(t[3]), f64(t[4]), int(t[5]), f64(t[6])))
        elif t[0] == "logcdf":
            logcdfs.append((t[1], f64(t[2]), f64(t[3]), f64(t[4]), int(t[5]), f64(t[6])))
        elif t[0] == "ks":
            nx = int(t[6])
            x = [f64(v) for v in t[7:7 + nx]]
            y = [f64(v) for v in t[8 + nx:]]
            ks.append((int(t[1]), int(t[2]), f64(t[3]), f64(t[4]), f64(t[5]), x, y))
        elif t[0] == "ksblock":
            ksblocks[int(t[1])] = bytes.fromhex(t[2]).decode()
        elif t[0] == "block":
            nx = int(t[8])
            x = [f64(v) for v in t[9:9 + nx]]
            rest = t[9 + nx:]
            y = None if rest[0] == "-" else [f64(v) for v in rest[1:]]
            blocks.append((t[1], t[2], t[3], f64(t[4]), t[5], f64(t[6]), bytes.fromhex(t[7]).decode(), x, y))
    return data, cases, quantiles, logcdfs, ks, ksblocks, blocks


def values(data, name):
    d = data[name]
    if isinstance(d, tuple):  # the 1e6-value formula sets
        n, base, mult, mod = d
        return [base + ((i * mult) % mod) * 2.0 ** -20 for i in range(n)]
    return d


def strip_decision(text):
    return "\n".join(l for l in text.split("\n") if not l.startswith("decision at alpha = "))


def main():
    lib = mc.load(sys.argv[1] if len(sys.argv) > 1 else None)
    data, cases, quantiles, logcdfs, ks, ksblocks, blocks = load_ref()
    expect(lib.mcstat_version().decode().count(".") == 2, "version")
    expect(lib.mcstat_strerror(4).decode().lower().find("spread") >= 0 or len(lib.mcstat_strerror(4)) > 10,
           "strerror")

    # the four tests, on arrays and on accumulators built in pieces and merged
    tests = {"T_1": (mc.t_test_1, "mcstat_t_test_1_moments"), "T_2": (mc.t_test_2, "mcstat_t_test_2_moments"),
             "VAR_1": (mc.var_test_1, "mcstat_var_test_1_moments"),
             "VAR_2": (mc.var_test_2, "mcstat_var_test_2_moments")}
    alt_names = {0: "two-sided", 1: "less", 2: "greater"}
    for kind, xn, yn, null, alt, want in cases:
        x = values(data, xn)
        y = values(data, yn) if yn != "-" else None
        fn, mname = tests[kind]
        args = (x,) if y is None else (x, y)
        r = fn(lib, *args, null, alt_names[alt], want[0])
        mx = mc.moments(lib, x[: len(x) // 3])
        rest = mc.moments(lib, x[len(x) // 3:])
        mc.check(lib, lib.mcstat_moments_merge(ctypes.byref(mx), ctypes.byref(rest)))
        rm = mc.Result()
        margs = [ctypes.byref(mx)] + ([ctypes.byref(mc.moments(lib, y))] if y is not None else [])
        mc.check(lib, getattr(lib, mname)(*margs, null, alt, want[0], ctypes.byref(rm)))
        for how, res in (("array", r), ("moments", rm)):
            got = [res.statistic, res.df[0], res.df[1], res.p_value, res.critical[0], res.critical[1],
                   res.conf_int[0], res.conf_int[1], res.estimate[0], res.estimate[1]]
            worst = max(rel_err(g, w) for g, w in zip(got, want[1:]))
            expect(worst <= 1e-9, "%s %s %s (%s): relative error %.3g" % (kind, xn, yn, how, worst))
            expect(res.reject == (want[4] <= want[0]), "%s %s reject" % (kind, xn))

    # moments: one value at a time, serialization round trip
    m = mc.moments(lib)
    for v in data["michelso"]:
        mc.check(lib, lib.mcstat_moments_add(ctypes.byref(m), v))
    expect(m.n == 100, "moments n")
    expect(rel_err(lib.mcstat_moments_mean(ctypes.byref(m)), sum(data["michelso"]) / 100) < 1e-15, "mean")
    buf = ctypes.create_string_buffer(lib.mcstat_sizeof_moments_bytes())
    mc.check(lib, lib.mcstat_moments_to_bytes(ctypes.byref(m), buf, len(buf)))
    m2 = mc.Moments()
    mc.check(lib, lib.mcstat_moments_from_bytes(buf, len(buf), ctypes.byref(m2)))
    expect(bytes(m2) == bytes(m), "to_bytes/from_bytes round trip")
    raw = bytearray(buf.raw)
    raw[20] ^= 1
    expect(lib.mcstat_moments_from_bytes(bytes(raw), len(raw), ctypes.byref(m2)) == 8, "corrupt bytes")

    # errors carry their status and text
    try:
        mc.t_test_1(lib, [1.0, 1.0, 1.0])
        expect(False, "constant data accepted")
    except mc.McstatError as e:
        expect(e.status == 4, "EDEGENERATE status")
    try:
        mc.t_test_1(lib, [1.0, float("nan")])
        expect(False, "NaN accepted")
    except mc.McstatError as e:
        expect(e.status == 3, "ENONFINITE status")

    # distributions
    q = ctypes.c_double()
    for kind, p, df1, df2, upper, x in quantiles:
        if kind == "t":
            st = lib.mcstat_t_quantile(p, df1, upper, ctypes.byref(q))
        elif kind == "c":
            st = lib.mcstat_chisq_quantile(p, df1, upper, ctypes.byref(q))
        else:
            st = lib.mcstat_f_quantile(p, df1, df2, upper, ctypes.byref(q))
        expect(st == 0 and rel_err(q.value, x) <= 1e-12, "%s quantile p=%g df=%g: %r vs %r" % (kind, p, df1, q.value, x))
    for kind, x, df1, df2, upper, lp in logcdfs:
        if kind == "t":
            st = lib.mcstat_t_logcdf(x, df1, upper, ctypes.byref(q))
        elif kind == "c":
            st = lib.mcstat_chisq_logcdf(x, df1, upper, ctypes.byref(q))
        else:
            st = lib.mcstat_f_logcdf(x, df1, df2, upper, ctypes.byref(q))
        e = abs(q.value - lp) / (abs(lp) if abs(lp) > 700 else 1.0)
        expect(st == 0 and e <= 1e-11, "%s logcdf x=%g: %r vs %r" % (kind, x, q.value, lp))

    # K-S, exact method, unweighted and Canner's: p-values against exact fractions
    for i, alt, stat, p_none, p_canner, x, y in ks:
        r = mc.ks_test_2(lib, x, y, alt_names[alt], 0.05, weight=mc.KS_WEIGHT_NONE, method=mc.METHOD_EXACT)
        expect(abs(r.statistic - stat) <= 1e-13 * max(abs(stat), 1.0), "ks %d statistic" % i)
        expect(rel_err(r.p_value, p_none) <= 1e-12, "ks %d p (none): %r vs %r" % (i, r.p_value, p_none))
        rc = mc.ks_test_2(lib, x, y, alt_names[alt], 0.05, weight=mc.KS_WEIGHT_CANNER, method=mc.METHOD_EXACT)
        expect(rel_err(rc.p_value, p_canner) <= 1e-12, "ks %d p (Canner): %r vs %r" % (i, rc.p_value, p_canner))
        if i in ksblocks:
            expect(strip_decision(mc.format_result(lib, r)) == ksblocks[i], "ks %d block" % i)
    # simulated p-values come with a standard error
    i, alt, stat, p_none, p_canner, x, y = ks[11]
    r = mc.ks_test_2(lib, x, y, "two-sided", 0.05, method=mc.METHOD_SIMULATE, n_sim=4000, seed=7)
    expect(r.method == mc.METHOD_SIMULATE and r.p_value_se > 0, "simulated p-value has a standard error")
    expect(abs(r.p_value - p_canner) < 5 * r.p_value_se + 1e-3, "simulated p near the exact one")
    # the per-test outputs by name, over the storage 0.1.0 called reserved
    expect(r.ks_n_sim == 4000 and r.reserved[1] == 4000 and r.ks_weight == mc.KS_WEIGHT_CANNER,
           "K-S per-test fields")
    expect(r.decision in (mc.DECISION_LESS, mc.DECISION_EQUAL, mc.DECISION_GREATER), "decision value")
    # the efficiency test: its factors by name, in the same storage
    acc = []
    for v in ([1.0, 2.0, 3.0, 4.0, 6.0], [0.0, 0.0, 5.0, 9.0, 1.0, 2.0], [1.0, 1.1, 0.9], [2.0, 2.0]):
        m = mc.Moments()
        mc.check(lib, lib.mcstat_moments_init(ctypes.byref(m)))
        a, n = mc._array(v)
        mc.check(lib, lib.mcstat_moments_add_array(ctypes.byref(m), a, n))
        acc.append(m)
    r = mc.Result()
    mc.check(lib, lib.mcstat_efficiency_test(*[ctypes.byref(m) for m in acc], 1.0, mc.ALTERNATIVES["two-sided"],
                                             0.05, ctypes.byref(r)))
    expect(rel_err(r.estimate[0], 2.0 * (377.0 / 30.0) / 3.7) < 1e-14 and r.eff_time_ratio == 2.0 and
           r.eff_batches_x == 3 and r.eff_batches_y == 2 and r.reserved[1] == 2.0, "efficiency per-test fields")
    # options: the sized initialiser, and 0.1.0's entry point still exported
    o, o_old = mc.KsOptions(), mc.KsOptions()
    mc.check(lib, lib.mcstat_ks_options_init_size(ctypes.byref(o), ctypes.sizeof(o)))
    mc.check(lib, lib.mcstat_ks_options_init(ctypes.byref(o_old)))
    expect(bytes(o) == bytes(o_old) and o.size == ctypes.sizeof(o) and o.threads == 1, "K-S options defaults")
    expect(lib.mcstat_ks_options_init_size(ctypes.byref(o), ctypes.sizeof(o) + 8) == 1, "unknown size refused")

    # R's printed blocks
    for test, xname, yname, null, alt, alpha, text, x, y in blocks:
        if test == "t_test":
            r = mc.t_test_1(lib, x, null, alt, alpha) if y is None else mc.t_test_2(lib, x, y, null, alt, alpha)
        else:
            r = mc.var_test_2(lib, x, y, null, alt, alpha)
        got = strip_decision(mc.format_result(lib, r, xname, yname if yname != "-" else "y"))
        expect(got == text, "R block %s %s %s:\n%s---\n%s" % (test, xname, alt, got, text))

    print("ctypes: libmcstat %s" % lib.mcstat_version().decode())
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
