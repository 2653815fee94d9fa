# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""What a pass of mcstat.image.compare means: the per-test level an
adjustment applied (`per_test_level`), the smallest bias each test would
have found (`detectable_bias`) and its quantiles over the passing tests."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, Tuple, cast

import numpy as np

from .. import _core
from .._errors import InvalidArgumentError
from ._inputs import Summary

if TYPE_CHECKING:
    from ._report import ImageComparison

# libmcstat's calibrator for e-BH on p-values, e = kappa p^(kappa - 1) (p_adjust.c)
_EBH_KAPPA = 0.1

# ---- what a pass means -----------------------------------------------------------
def per_test_level(method: str, alpha: float, m: int, rejections: int) -> float:
    """The per-test level an adjustment applied to `m` p-values with
    `rejections` rejected at `alpha`: the raw p-value at or below which one
    more (not yet rejected) test is sure to be rejected, the other p-values
    held fixed -- the threshold of the adjustment's next step (for Holm and
    Bonferroni the largest such p-value; for the step-up methods a p-value
    a little above it can still be rejected when the not-rejected p-values
    above it crowd the next thresholds).  With k = min(rejections + 1, m):

    - BH: alpha k / m (alpha / m when nothing was rejected);
    - BY: alpha k / (m H_m), H_m = 1 + 1/2 + ... + 1/m;
    - e-BH (p calibrated to e = kappa p^(kappa - 1), kappa = 1/10):
      (kappa alpha k / m)^(1 / (1 - kappa));
    - Holm, Hochberg: alpha / (m - k + 1); Hommel: Hochberg's, which it
      never rejects less than (so a lower bound of its level);
    - Bonferroni: alpha / m; none: alpha.
    """
    method = _canonical_method(method)
    if m <= 0:
        return float("nan")
    k = min(rejections + 1, m)
    if method == "BH":
        return alpha * k / m
    if method == "BY":
        return alpha * k / (m * _harmonic(m))
    if method == "e-BH":
        return float((_EBH_KAPPA * alpha * k / m) ** (1.0 / (1.0 - _EBH_KAPPA)))
    if method in ("holm", "hochberg", "hommel"):
        return alpha / (m - k + 1)
    if method == "bonferroni":
        return alpha / m
    return alpha


def _harmonic(m: int) -> float:
    if m < 10**6:
        return float(np.sum(1.0 / np.arange(m, 0, -1, dtype=np.float64)))
    g = 0.5772156649015329  # Euler's; the asymptotic series is exact to rounding here
    return float(np.log(m) + g + 1.0 / (2 * m) - 1.0 / (12.0 * m * m))


_CHUNK = 1 << 18  # values per pass: the temporaries stay in cache and are reused


def _t_upper_quantile(q: float, df: np.ndarray) -> np.ndarray:
    """x with P[T_df > x] = q for an array of real df, NaN where df is not
    positive (libmcstat's ``mcstat_t_quantiles``: a table in 1/df,
    interpolated where that is good to rounding, over the threads)."""
    return cast(np.ndarray, _core._t_quantiles(q, np.asarray(df, dtype=np.float64), True))


def detectable_bias(std_error: Any, df: Any, level: float, *, alternative: str = "two-sided",
                    power: float = 0.8) -> np.ndarray:
    """The smallest absolute difference of means a Welch test with this standard
    error and these degrees of freedom finds with probability `power` at
    the per-test `level` (arrays broadcast; NaN where se or df is not
    positive and finite): se (c (1 - 1/(4 df)) + z sqrt(1 + c^2/(2 df))),
    c the critical t, z the normal `power` quantile (the module's doc gives
    the approximation's error)."""
    from statistics import NormalDist

    if not (0.0 < power < 1.0):
        raise InvalidArgumentError(f"power must lie in (0, 1), got {power}")
    if not (0.0 < level < 1.0):
        raise InvalidArgumentError(f"level must lie in (0, 1), got {level}")
    se = np.asarray(std_error, dtype=np.float64)
    d = np.asarray(df, dtype=np.float64)
    se, d = np.broadcast_arrays(se, d)
    shape = se.shape
    se, d = se.reshape(-1), d.reshape(-1)
    q = level / 2 if alternative == "two-sided" else level
    z = NormalDist().inv_cdf(power)
    out = _t_upper_quantile(q, d)
    # a chunk at a time: at 8.3 M pixels, fresh full-size temporaries cost
    # more than the arithmetic
    for k in range(0, d.size, _CHUNK):
        dk, sk = d[k:k + _CHUNK], se[k:k + _CHUNK]
        c = out[k:k + _CHUNK]
        with np.errstate(invalid="ignore", divide="ignore"):
            inv = np.divide(1.0, dk)
            root = np.multiply(c, c)
            root *= 0.5 * inv
            root += 1.0
            np.sqrt(root, out=root)
            root *= z
            inv *= -0.25
            inv += 1.0
            c *= inv
            c += root           # c (1 - 1/(4 df)) + z sqrt(1 + c^2/(2 df))
            c *= sk
            c[~(sk > 0) | ~np.isfinite(sk)] = np.nan
    return out.reshape(shape)


def _welch_se_df(cand: "Summary", ref: "Summary") -> Tuple[np.ndarray, np.ndarray]:
    """Welch's standard error and degrees of freedom from per-pixel summaries."""
    with np.errstate(invalid="ignore", divide="ignore"):
        vx = cand.m2 / (cand.n - 1) / cand.n
        vy = ref.m2 / (ref.n - 1) / ref.n
        v = vx + vy
        df = v * v / (vx * vx / (cand.n - 1) + vy * vy / (ref.n - 1))
        return np.sqrt(v), df


def _bias_stats(res: "ImageComparison") -> Dict[str, Any]:
    qs = (0.5, 0.9, 0.99)
    out: Dict[str, Any] = {"power": res.detect_power,
                           "level": res.level if np.isfinite(res.level) else None,  # None: nothing tested
                           "bias_quantile": res.bias_quantile,
                           "definition": "smallest |candidate - reference| mean difference found with probability "
                                         "`power` at the per-test `level` the adjustment applied, over the tested "
                                         "tests that were not rejected",
                           "max_detectable_bias": res.max_detectable_bias,
                           "max_relative_detectable_bias": res.max_relative_detectable_bias}
    db = res.detectable_bias
    for key in ("absolute", "relative"):
        out[key] = {"median": None, "p90": None, "p99": None, "at_bias_quantile": None}
    if db is None:
        return out
    keep = res.tested & ~(res.padjusted <= res.alpha) & np.isfinite(db)
    vals = db[keep]
    ref = np.abs(res.mean_reference[keep])
    with np.errstate(invalid="ignore", divide="ignore"):
        rel = vals[ref > 0] / ref[ref > 0]
    for key, v in (("absolute", vals), ("relative", rel)):
        if v.size:
            got = np.quantile(v, qs + (res.bias_quantile,))
            out[key] = {"median": float(got[0]), "p90": float(got[1]), "p99": float(got[2]),
                        "at_bias_quantile": float(got[3])}
    return out


def _canonical_method(m: str) -> str:
    # R's name of the method, whatever alias was given ("fdr_bh" -> "BH")
    return _core._p_adjust_method_name(m)
