"""The 50-digit reference cases of tests/data/ref_data.h, read from the header.

The header is written by tools/refgen/make_reference.py (exact rational
moments, mpmath at 50 digits); parsing it here means the C and the Python
tests check against the very same committed numbers.
"""
import os
import re

from conftest import ROOT

HEADER = os.path.join(ROOT, "tests", "data", "ref_data.h")


def _num(tok):
    tok = re.sub(r"/\*.*?\*/", "", tok).strip()
    if tok == "NAN":
        return float("nan")
    if tok in ("INFINITY", "-INFINITY"):
        return float(tok.replace("INFINITY", "inf"))
    if tok.lower().startswith(("0x", "-0x")):
        return float.fromhex(tok)
    return float(tok)


def _load():
    text = open(HEADER).read()
    arrays = {}
    for m in re.finditer(r"static const double ds_(\w+)\[(\d+)\] = \{(.*?)\};", text, re.S):
        vals = [_num(t) for t in m.group(3).split(",") if t.strip()]
        assert len(vals) == int(m.group(2))
        arrays[m.group(1)] = vals
    datasets = {}
    block = re.search(r"REF_DATASETS\[\] = \{(.*?)\n\};", text, re.S).group(1)
    for m in re.finditer(r'\{"(\w+)", (ds_\w+|NULL), (\d+), ([^,]+), (\d+), (\d+), ([^,]+), ([^}]+)\}', block):
        name, src, n, base, mult, mod = m.group(1), m.group(2), int(m.group(3)), _num(m.group(4)), int(m.group(5)), int(m.group(6))
        if src == "NULL":  # x_i = base + ((i * mult) % mod) * 2^-20
            datasets[name] = ("formula", n, base, mult, mod)
        else:
            datasets[name] = ("array", arrays[name])
    cases = []
    block = re.search(r"REF_CASES\[\] = \{(.*?)\n\};", text, re.S).group(1)
    for line in block.strip().splitlines():
        inner = line.strip().rstrip(",")[1:-1]
        toks = [t.strip() for t in inner.split(",")]
        kind, x, y = toks[0].strip('"'), toks[1].strip('"'), toks[2]
        y = None if y == "NULL" else y.strip('"')
        vals = [_num(t) for t in toks[3:]]
        keys = ["null_value", "alternative", "alpha", "statistic", "df0", "df1", "p", "c0", "c1", "ci0", "ci1", "e0", "e1"]
        c = dict(zip(keys, vals), kind=kind, x=x, y=y)
        c["alternative"] = int(c["alternative"])
        cases.append(c)
    return datasets, cases


DATASETS, CASES = _load()


def values(name):
    import numpy as np

    d = DATASETS[name]
    if d[0] == "array":
        return np.array(d[1])
    _, n, base, mult, mod = d
    i = np.arange(n, dtype=np.int64)
    return base + ((i * mult) % mod).astype(np.float64) * 2.0 ** -20


# The bounds of the accuracy table (tests/data/accuracy.tsv, written by
# tools/refgen/make_accuracy.py, explained in libmcstat/ACCURACY.md).
ACCURACY_TSV = os.path.join(ROOT, "tests", "data", "accuracy.tsv")
STIFF_DOMAIN = "ref_data.h stiff data sets (arrays and accumulators)"
# The fields other than the p-value: 2-4 times their measured worst error
# (tests/c/test_reference.c prints it), as test_reference.c holds them.
TOL_STATISTIC, TOL_DF, TOL_CRITICAL, TOL_CONF_INT, TOL_ESTIMATE = 1e-13, 1e-15, 1e-14, 8e-14, 4e-15


def accuracy_bound(func, domain):
    with open(ACCURACY_TSV) as f:
        for line in f:
            r = line.rstrip("\n").split("\t")
            if not line.startswith("#") and r[0] == func and r[1] == domain:
                return float(r[5])
    raise KeyError(f"accuracy.tsv has no row {func} / {domain}")
