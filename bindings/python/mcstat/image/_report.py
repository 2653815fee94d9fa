# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat.image.compare's result: `ImageComparison`, its verdict, summary
and text report, and the colour key of the application's map."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

from ._bias import _bias_stats

# ImageComparison.verdict's values
VERDICTS = ("equal", "different", "inconclusive")

# What each adjustment's guarantee assumes of the dependence among the
# pixels' tests.  Reconstruction filters and denoisers correlate neighbouring
# pixels: BH's positive-dependence condition (PRDS) is plausible there but
# not guaranteed; BY and e-BH hold whatever the dependence.
_ASSUMES = {
    "BH": "independent or positively dependent (PRDS) tests",
    "BY": "nothing about the dependence (any dependence)",
    "e-BH": "nothing about the dependence (any dependence)",
    "holm": "nothing about the dependence (any dependence)",
    "bonferroni": "nothing about the dependence (any dependence)",
    "hochberg": "independent or positively dependent (PRDS) tests",
    "hommel": "independent or positively dependent (PRDS) tests",
    "none": "nothing (no family-wise statement)",
}

COLOR_KEY = {
    "greater": (230, 40, 40),
    "less": (40, 90, 230),
    "mixed": (235, 200, 30),
    "not significant": "grey: the reference's luminance, tone-mapped to 60..200",
    "not tested": (0, 0, 0),
}


# ---- the comparison ------------------------------------------------------------
@dataclass
class ImageComparison:
    """Per-pixel results, each ``(H, W, C)`` (C = 1 for luminance)."""

    pvalue: np.ndarray
    padjusted: np.ndarray
    statistic: np.ndarray
    decision: np.ndarray          # int8: -1 less, 0 not significant or untested, +1 greater (after FDR)
    tested: np.ndarray            # bool
    mean_candidate: np.ndarray
    mean_reference: np.ndarray
    reference_luminance: np.ndarray  # (H, W), for the map's background
    channel_names: List[str]
    alpha: float
    method: str
    alternative: str
    timings: Dict[str, float] = field(default_factory=dict)
    # tests left out because an input lost their variance, and why
    variance_lost: int = 0
    notes: List[str] = field(default_factory=list)
    # What a pass means (see the module's doc): (H, W, C) smallest |delta|
    # found with probability detect_power, NaN where not tested.
    detectable_bias: Optional[np.ndarray] = None
    detect_power: float = 0.8
    level: float = float("nan")   # the per-test level behind detectable_bias (per_test_level)
    # the verdict's bias limit: absolute, relative to |reference mean|, at this quantile of pixels
    max_detectable_bias: Optional[float] = None
    max_relative_detectable_bias: Optional[float] = None
    bias_quantile: float = 0.9
    # Block tests: the block's side in pixels (None: per pixel); the arrays
    # are then at block resolution, reference_luminance and image_shape the image's.
    block: Optional[int] = None
    image_shape: Optional[Tuple[int, int]] = None
    # per-seed inputs: whether the render guards ran (MCSTAT_PIXELS_RENDER)
    # and the numerical floor they applied (relative; None without them)
    render_guards: bool = False
    resolution: Optional[float] = None
    # the paired t test on same-seed pairs instead of Welch's
    paired: bool = False
    _bias_stats: Optional[Dict[str, Any]] = field(default=None, repr=False)

    @property
    def shape(self) -> Tuple[int, int, int]:
        return tuple(self.pvalue.shape)  # type: ignore[return-value]

    def pixel_decision(self) -> np.ndarray:
        """(H, W) int8: 1 greater, -1 less, 2 mixed channels, 0 not
        significant, -2 not tested (in no channel)."""
        d = self.decision
        g = (d > 0).any(axis=-1)
        l_ = (d < 0).any(axis=-1)
        out = np.zeros(d.shape[:2], dtype=np.int8)
        out[~self.tested.any(axis=-1)] = -2
        out[g & ~l_] = 1
        out[l_ & ~g] = -1
        out[g & l_] = 2
        return out

    @property
    def rejections(self) -> int:
        """Tests rejected after the adjustment."""
        return int(np.count_nonzero(self.padjusted <= self.alpha))

    def bias_statistics(self) -> Dict[str, Any]:
        """Quantiles (median, 90%, 99%) of `detectable_bias` over the
        tested pixels that were not rejected (the pass's pixels), absolute
        and relative to the absolute reference mean (pixels where it is not 0), and
        the quantile the verdict uses (`bias_quantile`)."""
        if self._bias_stats is None:
            self._bias_stats = _bias_stats(self)
        return self._bias_stats

    @property
    def verdict(self) -> str:
        """``"different"``: some test rejected after the adjustment;
        ``"inconclusive"``: nothing could be tested, or a bias limit was
        given (``max_detectable_bias``, ``max_relative_detectable_bias``)
        and at the `bias_quantile` of the passing pixels a larger bias
        could have hidden (`detectable_bias` above the limit);
        ``"equal"``: no rejection, and at least one test ran (and the
        limits, if given, are met)."""
        return self.verdict_reason()[0]

    def verdict_reason(self) -> Tuple[str, str]:
        """`verdict` and one line saying why."""
        r = self.rejections
        if r > 0:
            return "different", f"{r} test(s) rejected after the {self.method} adjustment"
        if not self.tested.any():
            return "inconclusive", "no test could be made (constant or non-finite inputs, too few seeds)"
        b = self.bias_statistics()
        q = self.bias_quantile
        for key, limit, what in (("absolute", self.max_detectable_bias, "--max-detectable-bias"),
                                 ("relative", self.max_relative_detectable_bias, "--max-relative-detectable-bias")):
            if limit is None:
                continue
            v = b[key]["at_bias_quantile"]
            if v is None or not v <= limit:
                return "inconclusive", (f"no rejection, but at the {100 * q:g}th percentile of the passing tests a bias "
                                        f"of {_g(v)} could have hidden ({key}), above the limit {limit:g} ({what})")
        return "equal", "no rejection" + ("; the detectable bias is within the limit" if (
            self.max_detectable_bias is not None or self.max_relative_detectable_bias is not None) else "")

    def summary(self, worst: int = 10) -> dict:
        m = int(self.tested.sum())
        p = self.pvalue
        raw = int(np.count_nonzero(p <= self.alpha))
        adj = int(np.count_nonzero(self.padjusted <= self.alpha))
        fdr = self.method in ("BH", "BY", "e-BH")
        pd = self.pixel_decision()
        h, w, c = self.shape
        out = {
            "image": {"height": h, "width": w, "channels": self.channel_names},
            "alpha": self.alpha,
            "test": "paired" if self.paired else "welch",
            "alternative": self.alternative,
            "adjustment": self.method,
            "controls": "false discovery rate" if fdr else (
                "family-wise error rate" if self.method != "none" else "nothing (per-test level)"),
            "assumes": _ASSUMES.get(self.method, "valid p-values"),
            "pixels": h * w,
            "tests": h * w * c,
            "tested": m,
            "not_tested": h * w * c - m,
            "rejections_unadjusted": raw,
            "rejections_adjusted": adj,
            "rejected_greater": int(np.count_nonzero(self.decision > 0)),
            "rejected_less": int(np.count_nonzero(self.decision < 0)),
            "pixels_significant": int(np.count_nonzero((pd == 1) | (pd == -1) | (pd == 2))),
            # Unadjusted, alpha of the true nulls are rejected on average; m * alpha
            # is that number if no pixel differs.
            "expected_false_rejections_unadjusted_if_all_null": self.alpha * m,
            # BH: E[V / max(R, 1)] <= alpha (m0 / m), so E[V] <= alpha * R on
            # average over runs with R rejections; FWER methods: P(V > 0) <= alpha.
            "expected_false_discoveries_bound": (self.alpha * adj) if fdr else None,
            "probability_any_false_discovery_bound": None if fdr or self.method == "none" else self.alpha,
            "color_key": {k: (list(v) if isinstance(v, tuple) else v) for k, v in COLOR_KEY.items()},
            "verdict": self.verdict,
            "verdict_reason": self.verdict_reason()[1],
            "detectable_bias": self.bias_statistics(),
            "block": None if self.block is None else {
                "size": self.block, "grid": [h, w],
                "image": list(self.image_shape) if self.image_shape else None,
                "note": "each test is one block's mean per seed; blocks at the right and bottom edges are "
                        "smaller when the image's size is not a multiple of the block's; x, y in 'worst' are "
                        "block indices (the block's first pixel is x * size, y * size)"},
            "worst": self.worst(worst),
            "timings_s": {k: round(v, 4) for k, v in self.timings.items()},
            "variance_lost": self.variance_lost,
            "notes": list(self.notes),
        }
        return out

    def worst(self, k: int = 10) -> List[dict]:
        """The k tests with the smallest p-values."""
        flat = np.where(np.isnan(self.pvalue), np.inf, self.pvalue).ravel()
        k = min(k, int(np.isfinite(flat).sum()))
        if k <= 0:
            return []
        idx = np.argpartition(flat, k - 1)[:k] if k < flat.size else np.arange(flat.size)
        t = np.abs(self.statistic.ravel()[idx])
        idx = idx[np.lexsort((-np.nan_to_num(t, nan=0.0), flat[idx]))]
        h, w, c = self.shape
        out = []
        for i in idx:
            y, x, ch = np.unravel_index(int(i), (h, w, c))
            d = int(self.decision[y, x, ch])
            out.append({
                "x": int(x), "y": int(y), "channel": self.channel_names[ch],
                "pvalue": float(self.pvalue[y, x, ch]), "padjusted": float(self.padjusted[y, x, ch]),
                "t": float(self.statistic[y, x, ch]),
                "mean_candidate": float(self.mean_candidate[y, x, ch]),
                "mean_reference": float(self.mean_reference[y, x, ch]),
                "decision": {1: "greater", -1: "less", 0: "equal"}[d],
            })
        return out

    def text(self, worst: int = 10) -> str:
        s = self.summary(worst)
        h, w = s["image"]["height"], s["image"]["width"]
        blk = s["block"]
        test = "paired t-tests (same-seed pairs)" if s["test"] == "paired" else "Welch two-sample t-tests"
        lines = [
            f"\tPer-pixel {test}, candidate vs reference" if blk is None else
            f"\tBlock {test} ({blk['size']} x {blk['size']} block means), candidate vs reference",
            "",
            (f"image:  {w} x {h}" if blk is None else
             f"blocks: {w} x {h} of a {blk['image'][1]} x {blk['image'][0]} image (edge blocks smaller)") +
            f", channels {', '.join(s['image']['channels'])}: {s['tests']} tests, "
            f"{s['tested']} tested, {s['not_tested']} not tested",
            f"alternative: {s['alternative']}, alpha = {s['alpha']:g}, adjustment: {s['adjustment']} "
            f"(controls the {s['controls']}; assumes {s['assumes']})",
            f"rejections at alpha without adjustment: {s['rejections_unadjusted']} "
            f"(about {s['expected_false_rejections_unadjusted_if_all_null']:.0f} expected if no pixel differed)",
            f"rejections after adjustment: {s['rejections_adjusted']} "
            f"({s['rejected_greater']} greater, {s['rejected_less']} less) in {s['pixels_significant']} pixels",
        ]
        if s["expected_false_discoveries_bound"] is not None:
            lines.append(f"expected false discoveries among them: at most {s['expected_false_discoveries_bound']:.2f}")
        elif s["probability_any_false_discovery_bound"] is not None:
            lines.append(f"probability of any false discovery: at most {s['probability_any_false_discovery_bound']:g}")
        b = s["detectable_bias"]
        if b["absolute"]["median"] is not None:
            what = "block" if blk is not None else "pixel"
            rel = b["relative"]
            reltxt = (f"; relative to the reference: {_g(rel['median'])}, {_g(rel['p90'])}"
                      if rel["median"] is not None else "")
            if s["rejections_adjusted"] == 0:
                lines.append(f"no differences found; a bias smaller than {_g(b['absolute']['median'])} (median {what}; "
                             f"{_g(b['absolute']['p90'])} at the 90th percentile{reltxt}) could have hidden")
            else:
                lines.append(f"where nothing was found, a bias smaller than {_g(b['absolute']['median'])} (median "
                             f"{what}; {_g(b['absolute']['p90'])} at the 90th percentile{reltxt}) could have hidden")
            lines.append(f"  (smallest |difference| found with probability {b['power']:g} at the per-test level "
                         f"{b['level']:.3g} the adjustment applied)")
        lines += [f"note: {n}" for n in s["notes"]]
        lines.append(f"verdict: {s['verdict']} ({s['verdict_reason']})")
        if s["worst"]:
            lines += ["", "smallest p-values" + ("" if blk is None else " (x, y: block indices)") + ":",
                      "     x      y  ch    p-value   adjusted          t  decision"]
            for r in s["worst"]:
                lines.append(f"{r['x']:6d} {r['y']:6d} {r['channel']:>3s} {r['pvalue']:10.3g} "
                             f"{r['padjusted']:10.3g} {r['t']:10.4g}  {r['decision']}")
        return "\n".join(lines) + "\n"


def _g(v: Optional[float]) -> str:
    return "n/a" if v is None else f"{v:.3g}"
