# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""results.json: every test's fields, machine-readable and reproducible.

Tests repeated over runs are stored column-wise: one list per field
(``statistic``, ``pvalue``, ``decision``, ...) with one entry per test, so
the file keeps every test without repeating the field names thousands of
times.  Non-finite numbers (a critical value not computed, a failed row)
are written as null, so that the file is strict JSON.

Everything that depends on the wall clock lives under keys starting with
``wall_`` or in the top-level ``timing`` study; :func:`without_wall_clock`
drops them, and what is left is byte-identical for a given ``--seed``.
"""
from __future__ import annotations

import json
import math
from typing import Any, Dict, Iterable, List

import numpy as np

#: TestResult fields written for one test (``ks_test`` adds the simulation's).
TEST_FIELDS = ("method", "alternative", "alpha", "statistic", "df", "pvalue", "conf_int", "estimate", "null_value",
               "critical_values", "reject", "decision", "std_error", "nobs", "pvalue_se")
KS_FIELDS = ("weight", "pvalue_method", "n_sim", "seed", "critical_se")
#: BatchResult columns (one entry per row).
BATCH_FIELDS = ("statistic", "df", "pvalue", "conf_int", "estimate", "critical_values", "std_error", "reject",
                "decision", "nobs", "status")


def jsonable(x: Any) -> Any:
    """Plain JSON types: numpy scalars and arrays to Python, non-finite floats to None."""
    if isinstance(x, dict):
        return {str(k): jsonable(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(v) for v in x]
    if isinstance(x, np.ndarray):
        return jsonable(x.tolist())
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        v = float(x)
        return v if math.isfinite(v) else None
    if isinstance(x, (str, type(None))):
        return x
    if isinstance(x, np.str_):
        return str(x)
    raise TypeError(f"results: cannot write {type(x).__name__}")


def test_fields(r: Any) -> Dict[str, Any]:
    """The fields of one TestResult."""
    out = {f: getattr(r, f) for f in TEST_FIELDS}
    if r.weight is not None:  # a K-S test
        out.update({f: getattr(r, f) for f in KS_FIELDS})
    return jsonable(out)


def columns(results: Iterable[Any]) -> Dict[str, List[Any]]:
    """Column-wise fields of a sequence of TestResults."""
    rows = [test_fields(r) for r in results]
    if not rows:
        return {}
    return {k: [row[k] for row in rows] for k in rows[0]}


def batch_columns(b: Any) -> Dict[str, Any]:
    """Column-wise fields of a BatchResult (one test per row)."""
    out: Dict[str, Any] = dict(method=b.method, alternative=b.alternative, alpha=b.alpha, null_value=b.null_value)
    for f in BATCH_FIELDS:
        out[f] = getattr(b, f)
    return jsonable(out)


def decision_counts(decisions: Iterable[str]) -> Dict[str, int]:
    d = list(decisions)
    return dict(less=d.count("less"), equal=d.count("equal"), greater=d.count("greater"),
                failed=sum(1 for x in d if x not in ("less", "equal", "greater")))


def _encode(x: Any, indent: str) -> str:
    # objects one field per line; lists of scalars (the test columns) on one line
    if isinstance(x, dict):
        if not x:
            return "{}"
        inner = indent + " "
        items = [f"{inner}{json.dumps(k, ensure_ascii=False)}: {_encode(v, inner)}" for k, v in x.items()]
        return "{\n" + ",\n".join(items) + "\n" + indent + "}"
    if isinstance(x, list) and any(isinstance(v, (dict, list)) for v in x):
        if all(isinstance(v, list) and not any(isinstance(w, (dict, list)) for w in v) for v in x) and len(x) > 8:
            return json.dumps(x, allow_nan=False, ensure_ascii=False, separators=(",", ":"))
        inner = indent + " "
        return "[\n" + ",\n".join(inner + _encode(v, inner) for v in x) + "\n" + indent + "]"
    return json.dumps(x, allow_nan=False, ensure_ascii=False, separators=(",", ":"))


def dumps(results: Dict[str, Any]) -> str:
    """Deterministic text: field order as built, floats as Python's repr."""
    return _encode(jsonable(results), "") + "\n"


def write(path: str, results: Dict[str, Any]) -> None:
    with open(path, "w", encoding="utf-8") as f:
        f.write(dumps(results))


def without_wall_clock(results: Dict[str, Any]) -> Dict[str, Any]:
    """A copy without the ``wall_*`` fields and the top-level ``timing`` study."""

    def strip(x: Any) -> Any:
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if not k.startswith("wall_")}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x

    return strip({k: v for k, v in results.items() if k != "timing"})
