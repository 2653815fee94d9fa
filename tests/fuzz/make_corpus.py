#!/usr/bin/env python3
"""Writes the seed corpus of every harness: tests/fuzz/corpus/<harness>/.

Each seed is a small, meaningful input in the byte layout that fuzz_input.h
decodes (the encoders below mirror it): typical data, offset data, ties,
degenerate and extreme samples, each option of each entry point.  The
fuzzer starts from these instead of from nothing.  Deterministic: running
it again rewrites the same files (python3 tests/fuzz/make_corpus.py).
"""
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
SPECIAL = [0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-3, 1e3,
           "DBL_MIN", "-DBL_MIN", "TRUE_MIN", "-TRUE_MIN", "DBL_MAX", "-DBL_MAX", "inf", "-inf",
           "nan", "EPS", "1+EPS", "1-EPS/2", 1e9, -1e9, 1e-300, 1e300,
           0.05, 0.95, 1e12, 1e-12, "HALF_MIN", 9007199254740993.0, 3.0, 7.0]


def u8(v):
    return bytes([v & 0xFF])


def u16(v):
    return struct.pack("<H", v & 0xFFFF)


def u32(v):
    return struct.pack("<I", v & 0xFFFFFFFF)


def u64(v):
    return struct.pack("<Q", v & 0xFFFFFFFFFFFFFFFF)


def special(i):
    """The tag of FZ_SPECIAL[i]."""
    return u8(i)


def dbl(x):
    """fz_double: small multiples of 1/256 compactly, anything else raw."""
    if isinstance(x, str):
        return special(SPECIAL.index(x))
    k = x * 256.0
    if k == int(k) and -32768 <= k < 32768 and not (x == 0.0 and str(x).startswith("-")):
        return u8(32) + struct.pack("<h", int(k))
    return u8(128) + struct.pack("<d", x)


def rng(v, lo, hi):
    """fz_range(lo, hi) decoding to v."""
    span = hi - lo
    k = v - lo
    return u8(k) if span <= 0xFF else u16(k) if span <= 0xFFFF else u32(k)


def alpha(a=None, raw=None):
    if raw is not None:
        return u8(250) + dbl(raw)
    b = int(round(a * 250 - 0.5))
    return u8(b)


def alt(a):
    return u8(a) if a in (0, 1, 2) else u8(3) + u32(a)


def doubles(xs, maxn, mode=0, base=0.0, step=1.0):
    """fz_doubles: mode 0 each value, 1 base + step * int8, 2 constant, 3 int8."""
    out = rng(len(xs), 0, maxn) + u8(mode)
    if mode == 0:
        out += b"".join(dbl(x) for x in xs)
    elif mode == 1:
        out += dbl(base) + dbl(step) + bytes((int(k) & 0xFF) for k in xs)
    elif mode == 2:
        out += dbl(xs[0] if xs else 0.0)
    else:
        out += bytes((int(k) & 0xFF) for k in xs)
    return out


def samples(r, maxn):
    """A handful of (x, y) sample encodings of every kind."""
    g = [round(r.gauss(0, 1), 3) for _ in range(maxn)]
    h = [round(r.gauss(0.5, 2), 3) for _ in range(maxn)]
    ints = [r.randint(-5, 5) for _ in range(maxn)]
    return [
        (doubles(g[:10], maxn), doubles(h[:12], maxn)),
        (doubles(g[:3], maxn), doubles(h[:2], maxn)),
        (doubles(ints[:20], maxn, mode=1, base=1e9, step=1e-3), doubles(ints[20:35], maxn, mode=1, base=1e9, step=2e-3)),
        (doubles(ints[:16], maxn, mode=3), doubles(ints[16:30], maxn, mode=3)),
        (doubles([4.0] * 6, maxn, mode=2), doubles(h[:6], maxn)),
        (doubles(ints[:8], maxn, mode=1, base=1e-300, step=1e-302), doubles(ints[8:16], maxn, mode=1, base=0.0, step=1e300)),
        (doubles([1.0, "nan", 2.0, 3.0], maxn), doubles([1.0, "inf", 2.0], maxn)),
        (doubles([], maxn), doubles([1.0], maxn)),
    ]


def write(harness, seeds):
    d = os.path.join(HERE, "corpus", harness)
    os.makedirs(d, exist_ok=True)
    for f in os.listdir(d):
        os.remove(os.path.join(d, f))
    for i, s in enumerate(seeds):
        with open(os.path.join(d, "seed-%02d" % i), "wb") as f:
            f.write(s)


def fuzz_tests(r):
    seeds = []
    for i, (x, y) in enumerate(samples(r, 64)):
        for which in range(5):
            null = [0.0, 0.5, 1.0, 1.5, 0.25][which]
            a = [0.05, 0.01, 0.5, 0.9][(i + which) % 4]
            s = u8(which) + x + y + dbl(null) + alt((i + which) % 3) + alpha(a) + u8(i)
            if which == 4:
                s += dbl([0.0, 0.1, 1e-9, 2.0][i % 4])
            seeds.append(s)
    seeds.append(u8(0) + samples(r, 64)[0][0] + samples(r, 64)[0][1] + dbl(0.0) + alt(7) + alpha(raw=1.5) + u8(1))
    return seeds


def fuzz_ks(r):
    seeds = []
    for i, (x, y) in enumerate(samples(r, 40)):
        for weight in (0, 1):
            for method in range(5):
                n_sim = [49, 99, 199, 9][(i + method) % 4]
                flags = [0, 4, 0, 1, 2][method] if i % 3 else 4
                s = x + y + alt((i + method) % 3) + alpha([0.05, 0.1, 0.01][i % 3]) + u8(flags)
                s += u8(weight) + u8(method) + u8(1 + (i & 1)) + u8(n_sim - 1) + u64(r.getrandbits(64)) + u8(1)
                if flags & 2:
                    s += rng(48, 0, 96)
                s += rng([0, 1000, 65536][i % 3], 0, 1 << 20)
                seeds.append(s)
    return seeds


def moments_seed(r, ops):
    s = b""
    for op in ops:
        s += u8(op)
        if op == 0:
            s += dbl(round(r.gauss(3, 1), 2))
        elif op in (1, 2, 3, 6):
            xs = [round(r.gauss(0, 1), 3) for _ in range(r.randint(1, 30))]
            if op == 2:
                xs[0] = "nan"
            s += doubles(xs, 48)
            if op == 2:
                s += u8(0)
        elif op == 7:
            s += u8(r.randint(0, 1))
    return s


def fuzz_moments(r):
    seeds = [moments_seed(r, [r.randint(0, 8) for _ in range(r.randint(3, 20))]) for _ in range(16)]
    seeds.append(u8(1) + doubles(list(range(40)), 48, mode=1, base=1e9, step=1e-6) + u8(3) +
                 doubles(list(range(10)), 48, mode=1, base=-1e9, step=1e-6) + u8(4) + u8(5) + u8(8))
    seeds.append(u8(1) + doubles(list(range(20)), 48, mode=1, base=1e300, step=1e290) + u8(0) + dbl(1e-300) + u8(8))
    return seeds


def fnv1a(b):
    h = 0xCBF29CE484222325
    for c in b:
        h = ((h ^ c) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def moments_bytes(n, scale, mean, mean_lo, m2, m3, m4, mn, mx):
    b = b"MCSM" + u32(1) + u64(n)
    b += (struct.pack("<i", scale) + u32(0) + struct.pack("<7d", mean, mean_lo, m2, m3, m4, mn, mx)) if n else bytes(64)
    b += u64(0)
    return b + u64(fnv1a(b))


def fuzz_bytes(r):
    tail = doubles([1.0, 2.0, 3.5, 0.5], 32) + dbl(1.0) + alt(0) + alpha(0.05)
    valid = [
        moments_bytes(0, 0, 0, 0, 0, 0, 0, 0, 0),
        moments_bytes(1, 0, 2.0, 0.0, 0.0, 0.0, 0.0, 2.0, 2.0),
        moments_bytes(5, 0, 2.6, 0.0, 5.2, 1.0, 9.0, 1.0, 4.5),
        moments_bytes(1000, 0, 1e9, 1e-8, 80.0, -3.0, 1500.0, 1e9 - 3, 1e9 + 3),
        moments_bytes(10, -990, 1e-298, 0.0, 9.0, 0.0, 20.0, 0.5e-298, 2e-298),
        moments_bytes(7, 1000, 1e300, 0.0, 5.0, 1.0, 7.0, 0.2e300, 2e300),
    ]
    seeds = [u8(0) + v + tail for v in valid]          # as they are
    seeds += [u8(3) + v[:88] + tail for v in valid]   # checksum recomputed by the harness
    bad = bytearray(valid[2])
    bad[40] ^= 1
    seeds.append(u8(0) + bytes(bad) + tail)
    seeds.append(u8(4 | (16 << 3)) + valid[2] + tail)  # wrong length
    return seeds


def fuzz_rows(r):
    seeds = []
    for which in range(4):
        for flags in range(4):
            rows, nx, ny = 1 + (which + flags) % 6, 2 + flags * 3, 3 + which * 2
            sx, sy = nx + flags % 4, ny
            xs = [round(r.gauss(0, 1), 2) for _ in range(rows * sx)]
            ys = [round(r.gauss(0, 1), 2) for _ in range(rows * sy)]
            if flags & 2:
                xs[1] = "nan"
            s = u8(which) + rng(rows, 0, 6) + rng(nx, 0, 12) + rng(ny, 0, 12) + rng(sx - nx, 0, 3) + rng(0, 0, 3)
            # the matrices: fz_doubles with max = rows * stride, every value given
            s += u8(flags) + doubles(xs, len(xs)) + doubles(ys, len(ys))
            s += dbl([0.0, 0.0, 1.0, 1.0][which]) + alt(flags % 3) + alpha(0.05) + u8(flags & 1)
            seeds.append(s)
    seeds.append(u8(0) + rng(2, 0, 6) + rng(4, 0, 12) + rng(4, 0, 12) + rng(0, 0, 3) + rng(0, 0, 3) + u8(250) + u32(8))
    return seeds


def fuzz_dist(r):
    seeds = []
    cases = [
        (0, 2.0, 0.0, 10.0, 1.0, 0.025), (0, -1.5, 3.0, 1e-3, 1.0, 0.5), (0, 40.0, 1e5, 3.5, 1.0, 1e-200),
        (0, 1e200, 0.0, 2.0, 1.0, 1e-300), (1, 3.0, 10.0, 5.0, 1.0, 0.05), (1, 1e6, 0.0, 1e6, 1.0, 0.5),
        (1, 1e-3, 1.0, 1e-3, 1.0, 1e-100), (2, 1.5, 0.5, 5.0, 7.0, 0.05), (2, 1.0000001, 2.0, 1e9, 1e9, 0.5),
        (2, 3.0, 1.0, 1e25, 4.0, 0.01), (2, 0.2, 9.0, 2.0, 1e25, 0.99), (0, "inf", "-inf", "DBL_MAX", 1.0, 1.0),
        (1, "TRUE_MIN", "DBL_MIN", "HALF_MIN", 1.0, 0.0), (0, "nan", 1.0, 1.0, 1.0, "nan"),
    ]
    for i, (fam, x, x2, d1, d2, p) in enumerate(cases):
        for upper in (0, 1):
            seeds.append(u8(fam) + dbl(x) + dbl(x2) + dbl(d1) + dbl(d2) + dbl(p) + u8(upper))
    seeds.append(u8(0) + dbl(1.0) + dbl(2.0) + dbl(3.0) + dbl(1.0) + dbl(0.3) + u8(250) + u8(2))
    return seeds


def fuzz_format(r):
    seeds = []

    def result(test, method, alternative, reject, decision, weight, n0, n1, d):
        s = u8(test) + u8(method) + u8(alternative) + u8(reject) + u8(decision + 1) + u8(weight)
        s += u8(0) + u8(n0) + u8(0) + u8(n1)
        return s + b"".join(dbl(x) for x in d)

    t1 = [2.5, 9.0, "nan", 0.034, 0.0, 0.1, 1.9, 1.0, "nan", 0.0, 0.05, -2.26, 2.26, 0.4, "nan", "nan"]
    t2 = [-1.2, 17.3, "nan", 0.25, 0.0, -2.0, 0.5, 1.0, 1.75, 0.0, 0.05, -2.1, 2.1, 0.6, "nan", "nan"]
    v1 = [12.0, 9.0, "nan", 0.4, 0.0, 0.5, 3.3, 1.1, "nan", 1.0, 0.05, 2.7, 19.0, "nan", "nan", "nan"]
    v2 = [1.7, 9.0, 11.0, 0.4, 0.0, 0.5, 5.3, 1.7, "nan", 1.0, 0.05, 0.26, 3.9, "nan", "nan", "nan"]
    ks = [1.3, "nan", "nan", 0.07, 0.002, "nan", "nan", "nan", "nan", "nan", 0.05, "-inf", 1.36, "nan", 0.01, 999.0]
    names = [(b"x", b"y"), (b"", b""), (b"renderer A" * 60, b"B"), None]
    for i, (test, d) in enumerate([(1, t1), (2, t2), (3, v1), (4, v2), (5, ks)]):
        for j, nm in enumerate(names):
            s = result(test, 0 if test < 5 else 2 + j % 3, j % 3, j & 1, (j % 3) - 1 if j & 1 else 0, j & 1, 10, 12 if test in (2, 4, 5) else 0, d)
            if nm is None:
                s += u16(0xFFFF) + u16(0xFFFF)
            else:
                s += u16(len(nm[0])) + nm[0] + u16(len(nm[1])) + nm[1]
            s += rng([4096, 50, 0, 200][j], 0, 4096)
            word = [b"two-sided", b"less", b"greater", b"two.sided", b"sideways"][(i + j) % 5]
            s += u16(len(word)) + word + u32([0, 1, 2, -1, 3][(i + j) % 5])
            seeds.append(s)
    return seeds


def check_seed(kind, domain, nu=3, weight=0, reports=1, variant=0, albedo=0.8, oflags=0, routes=0x4000,
               stochastic=0, reciprocal=0, cells=b"\x00", n_pilot=b"\x00", n_eval=b"\x00", batch=b"\x00",
               rtol=b"\x00", n=1000, a=0.05, seed=1, wi=(60, 40), work=0, faults=()):
    """fuzz_checks: the model, the options, n, alpha, seed, wi, the scratch, the faults."""
    s = u8(kind) + u8(domain) + u8(nu - 1) + u8(weight) + u8(reports) + u8(variant) + u8(int(albedo * 240) - 1)
    s += u8(oflags) + u16(routes) + u8(stochastic) + u8(reciprocal) + cells + n_pilot + n_eval + batch + rtol
    s += u8(0) + rng(n, 1000, 4000) + alpha(a) + u64(seed) + u8(0) + u8(wi[0]) + u8(wi[1]) + u8(work)
    s += rng(len(faults), 0, 8)
    for f in faults:
        s += f
    return s


def check_fault(cb, what, call=0, sel=2, point=0, threshold=0, field=0, arg=b""):
    """One fault: cb 0 sample, 1 pdf, 2 eval (call 255: every call); sel 0 all points, 1 a region
    (x[0] > threshold / 128), 2 one point; what 0 status, 1 set, 2 scale, 3 length, 4 zero, 5 flip,
    6 subnormal, 7 huge; field (sample) 0 point, 1 weight, 2 pdf."""
    return u8(cb) + u8(call) + u8(sel) + u16(point) + u8(threshold & 0xFF) + u8(what) + u8(field) + arg


def fuzz_checks(r):
    seeds = []
    # correct models of every kind and domain, both variants, both weight conventions
    for domain in range(5):
        for kind in (0, 1, 2):
            if kind == 0 and domain > 1 or kind == 1 and domain > 1:
                continue
            for variant in (0, 1):
                seeds.append(check_seed(kind, domain, nu=[3, 2, 2, 2, 1][domain], weight=variant,
                                        reports=1 if kind < 2 else variant, variant=variant,
                                        seed=r.getrandbits(64), work=(domain + variant) % 4))
    # options: small cells and pilot, explicit n_eval, a small batch, tight rtol, reciprocity
    seeds.append(check_seed(0, 1, routes=0x1FF, reciprocal=1, cells=u8(128 + 14), n_pilot=u8(128) + u16(400),
                            n_eval=u8(128) + u16(500), batch=u8(100) + u16(100), rtol=u8(210), n=2500, work=1))
    seeds.append(check_seed(0, 0, stochastic=1, routes=0x21, n=4000, wi=(200, 10), work=2))
    seeds.append(check_seed(1, 0, routes=0x100, batch=u8(100) + u16(0), n=1500, work=3))
    # invalid options and arguments
    seeds.append(check_seed(2, 2, reports=0, routes=0, work=1))
    seeds.append(check_seed(2, 3, reports=0, cells=u8(240) + u32(1)))
    seeds.append(check_seed(2, 4, reports=0, n_pilot=u8(200) + u16(10)))
    seeds.append(check_seed(0, 0, n_eval=u8(230) + u32(5), work=2))
    seeds.append(check_seed(0, 0, batch=u8(200) + u8(12)))
    seeds.append(check_seed(0, 1, rtol=u8(240) + dbl(1.5)))
    seeds.append(check_seed(0, 2))  # a BSDF on the square
    seeds.append(check_seed(1, 3))  # an emitter on the disk
    seeds.append(check_seed(0, 1, oflags=0x1c))  # reserved options field
    # faults: statuses, NaN/Inf/negative values, points off the domain, zero pdf
    f = check_fault
    seeds.append(check_seed(0, 1, faults=[f(0, 0, call=1, arg=u8(3))]))
    seeds.append(check_seed(0, 1, faults=[f(1, 0, call=2, arg=u8(250) + u32(0xFFFFFFFF))]))
    seeds.append(check_seed(0, 0, faults=[f(2, 1, call=3, point=17, arg=dbl("nan"))]))
    seeds.append(check_seed(1, 0, faults=[f(0, 1, point=5, field=1, arg=dbl(-1.0))]))
    seeds.append(check_seed(1, 1, faults=[f(0, 1, point=9, field=2, arg=dbl("inf"))]))
    seeds.append(check_seed(2, 2, reports=1, faults=[f(0, 1, point=3, field=0, arg=dbl(1.5))]))
    seeds.append(check_seed(2, 3, reports=0, faults=[f(0, 3, call=1, sel=0, arg=u8(2))]))
    seeds.append(check_seed(0, 0, faults=[f(0, 3, sel=2, point=40, arg=u8(1))]))   # 4e-5 off: accepted
    seeds.append(check_seed(0, 0, faults=[f(0, 3, sel=2, point=40, arg=u8(4))]))   # 1.5e-4 off: refused
    seeds.append(check_seed(0, 1, faults=[f(0, 5, sel=2, point=2)]))               # below the horizon
    seeds.append(check_seed(0, 1, faults=[f(1, 4, call=255, sel=0)]))              # pdf 0 everywhere
    seeds.append(check_seed(0, 0, faults=[f(1, 4, call=255, sel=1, threshold=64)]))  # pdf 0 where eval > 0
    seeds.append(check_seed(0, 1, faults=[f(0, 4, call=255, sel=1, threshold=-32, field=2)]))  # failed samples
    seeds.append(check_seed(0, 0, faults=[f(0, 4, call=255, sel=0, field=2)]))     # every sample fails: ETOOFEW
    seeds.append(check_seed(0, 1, faults=[f(2, 7, call=255, sel=1, point=1, threshold=100)]))  # huge eval
    seeds.append(check_seed(0, 1, weight=1, faults=[f(0, 6, call=255, sel=2, point=7, field=2)]))  # subnormal pdf
    seeds.append(check_seed(2, 4, reports=1, faults=[f(0, 2, call=255, sel=0, field=2, arg=dbl(1.1))]))  # pdf off
    seeds.append(check_seed(0, 1, faults=[f(2, 2, call=255, sel=1, threshold=0, arg=dbl(1.1)),
                                          f(0, 2, call=255, sel=0, field=1, arg=dbl(0.9))]))
    # several faults at once, on later calls (a small batch: many calls), so that longer inputs are in reach
    seeds.append(check_seed(0, 0, variant=1, reciprocal=1, batch=u8(100) + u16(200), n=3000, work=1,
                            faults=[f(0, 3, call=4, sel=2, point=31, arg=u8(3)), f(1, 2, call=9, sel=1, threshold=40,
                                    arg=dbl(1.0001)), f(2, 6, call=255, sel=2, point=3), f(0, 2, call=7, sel=0, field=1,
                                    arg=dbl(1e-3)), f(1, 7, call=12, sel=2, point=63), f(2, 1, call=255, sel=1,
                                    threshold=120, arg=dbl(0.0)), f(0, 5, call=11, sel=2, point=5),
                                    f(2, 0, call=15, arg=u8(7))]))
    seeds.append(check_seed(1, 1, weight=1, stochastic=1, batch=u8(100) + u16(500), n=4000, work=2,
                            faults=[f(0, 6, call=3, sel=2, point=9, field=2), f(0, 1, call=5, sel=2, point=2, field=1,
                                    arg=dbl("DBL_MAX")), f(1, 2, call=255, sel=0, arg=dbl(2.0)), f(2, 2, call=255, sel=0,
                                    arg=dbl(2.0))]))
    seeds.append(check_seed(2, 3, reports=1, variant=1, batch=u8(100) + u16(64), n=2000, work=3,
                            faults=[f(0, 3, call=2, sel=2, point=17, arg=u8(0)), f(0, 3, call=6, sel=2, point=20, arg=u8(8)),
                                    f(1, 1, call=255, sel=1, threshold=100, arg=dbl(0.0)), f(0, 4, call=9, sel=1,
                                    threshold=0, field=2), f(1, 0, call=14, arg=u8(250) + u32(2))]))
    # random models, options and 1-3 faults (values near the extremes, every call, regions)
    vals = [0.0, 1e-300, 1e300, "DBL_MAX", "TRUE_MIN", "DBL_MIN", 2.0, 0.5, 1e-12, 1e12, 1.0001, 1e-200, 1e150]
    for _ in range(24):
        kind = r.randrange(3)
        kw = dict(weight=r.randrange(2), reports=1 if kind < 2 else r.randrange(2), variant=r.randrange(2),
                  albedo=r.choice([0.1, 0.5, 1.0, 1.05]), stochastic=r.randrange(2), reciprocal=r.randrange(2),
                  n=r.randrange(1000, 4001), seed=r.getrandbits(64), work=r.randrange(4), nu=r.randrange(1, 9),
                  wi=(r.randrange(256), r.randrange(256)), a=r.choice([0.05, 0.5, 0.002]))
        if r.random() < 0.3:
            kw["cells"] = u8(128 + r.randrange(96))
        if r.random() < 0.3:
            kw["batch"] = u8(100) + u16(r.randrange(4000))
        if r.random() < 0.3:
            kw["routes"] = r.randrange(1, 512)
        faults = []
        for _ in range(r.randrange(1, 4)):
            what = r.choice([1, 2, 2, 3, 4, 5, 6, 7])
            arg = u8(r.randrange(10)) if what == 3 else dbl(r.choice(vals)) if what in (1, 2) else b""
            faults.append(f(r.randrange(3), what, call=r.choice([0, 1, 2, 255]), sel=r.choice([0, 1, 2]),
                            point=r.randrange(2000), threshold=r.randrange(-128, 128), field=r.randrange(3), arg=arg))
        seeds.append(check_seed(kind, r.randrange(2) if kind < 2 else r.randrange(5), faults=faults, **kw))
    return seeds


def fuzz_pixels(r):
    seeds = []
    for sel in range(4):
        for flags in range(4):
            pixels, nx, ny = 1 + (sel + flags) % 5, 2 + flags * 2, 3 + sel
            ch = 1 + flags % 3 if sel & 2 else 1
            xs = [round(r.gauss(1, 1), 2) for _ in range(nx * pixels * ch)]
            ys = [round(r.gauss(1, 1), 2) for _ in range(ny * pixels * ch)]
            if flags & 2:
                xs[1] = "nan"
            s = u8(sel) + rng(pixels, 0, 5) + rng(nx, 0, 9) + rng(ny, 0, 9)
            if sel & 2:
                s += rng(ch, 1, 3) + b"".join(dbl(w) for w in [0.2126, 0.7152, 0.0722][:ch])
            s += rng(0, 0, 5) + rng(pixels, 0, 5) + u8(flags)
            s += doubles(xs, len(xs)) + doubles(ys, len(ys))
            s += dbl([0.0, 0.0, 0.5, -1.0][sel]) + alt(flags % 3) + alpha(0.05)
            seeds.append(s)
    seeds.append(u8(0) + rng(2, 0, 5) + rng(4, 0, 9) + rng(4, 0, 9) + rng(0, 0, 5) + rng(2, 0, 5) + u8(250) + u32(8))
    return seeds


def fuzz_pixels_test(r):
    seeds = []
    for test in range(8):
        for variant in range(4):
            f32, rows, weighted = variant & 1, (variant >> 1) & 1, test % 3 == 0
            sel = test | f32 << 3 | rows << 4 | weighted << 5
            pixels, nx, ny = 1 + (test + variant) % 5, 2 + variant, 3 + test % 4
            if test == 3:
                ny = nx
            ch = 1 + variant % 3 if weighted else 1
            xs = [round(r.gauss(1, 1), 2) for _ in range(nx * pixels * ch)]
            ys = [round(r.gauss(1, 1), 2) for _ in range(ny * pixels * ch)]
            flags = variant % 4
            if flags & 2:
                xs[1] = "nan"
            s = u8(sel) + rng(pixels, 0, 5) + rng(nx, 0, 9) + rng(ny, 0, 9)
            if weighted:
                s += rng(ch, 1, 3) + b"".join(dbl(w) for w in [0.2126, 0.7152, 0.0722][:ch])
            s += rng(0, 0, 5) + rng(pixels, 0, 5) + u8(flags) + u8(variant)
            s += doubles(xs, len(xs)) + doubles(ys, len(ys))
            s += dbl(1.5 if test in (4, 5) else 0.25 * variant) + alt(variant % 3) + alpha(0.05)
            seeds.append(s)
    # unequal paired sizes, an invalid thread count, unknown flags
    seeds.append(u8(3 | 64) + rng(2, 0, 5) + rng(4, 0, 9) + rng(3, 0, 9) + rng(0, 0, 5) + rng(2, 0, 5) + u8(0) + u8(0))
    seeds.append(u8(1) + rng(2, 0, 5) + rng(4, 0, 9) + rng(4, 0, 9) + rng(0, 0, 5) + rng(2, 0, 5) + u8(0) + u8(251))
    seeds.append(u8(5) + rng(2, 0, 5) + rng(4, 0, 9) + rng(4, 0, 9) + rng(0, 0, 5) + rng(2, 0, 5) + u8(250) + u32(8))
    return seeds


def main():
    for name, make in [("fuzz_tests", fuzz_tests), ("fuzz_ks", fuzz_ks), ("fuzz_moments", fuzz_moments),
                       ("fuzz_bytes", fuzz_bytes), ("fuzz_rows", fuzz_rows), ("fuzz_dist", fuzz_dist),
                       ("fuzz_format", fuzz_format), ("fuzz_checks", fuzz_checks), ("fuzz_pixels", fuzz_pixels),
                       ("fuzz_pixels_test", fuzz_pixels_test)]:
        seeds = make(random.Random(name))
        write(name, seeds)
        print("%-13s %3d seeds, %5d bytes" % (name, len(seeds), sum(len(s) for s in seeds)))


if __name__ == "__main__":
    main()
