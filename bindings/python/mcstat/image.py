# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Per-pixel comparison of two renderers: Welch tests with multiple-testing control.

A candidate renderer and a reference each render the same image with
several seeds.  Every pixel (and channel) gets Welch's two-sample t test of
"same expected value" (libmcstat's row-wise test, as ``mcstat.t_test``
with 2-D input), and the millions of p-values are adjusted together
(``mcstat.p_adjust``, Benjamini-Hochberg by default): among the pixels
flagged, the expected fraction of false discoveries is at most alpha,
where testing each pixel at alpha would flag alpha of all unchanged pixels.

Inputs, per side, in memory: an array ``(seeds, H, W)`` or ``(seeds, H,
W, C)`` of per-seed renders (``seed_axis`` says where the seeds are; see
`compare` for when it may be left out);
`Samples`; `Summary` (per-pixel n, mean and M2); or a
``mcstat.MomentsArray`` (a render farm's merged accumulators, see
`save_moments`).  Files (EXR, PFM, .npy, .npz of summaries or
accumulators), the significance map's PNG and the ``mcstat image-test``
command belong to the application, ``mcstat_app.image``.

Colour key of the application's significance map (`COLOR_KEY`, also in
`ImageComparison.summary`): red, the candidate is
significantly greater (brighter) than the reference after FDR control;
blue, significantly less; yellow, channels disagree (some greater, some
less); grey, not significant (the reference's tone-mapped luminance, so the
picture stays recognisable); black, not tested (constant in both inputs,
non-finite values, too few seeds).

What a pass means (`ImageComparison.detectable_bias`): for each tested
pixel, the smallest difference of means ``|delta|`` that its test would have
found with probability `detect_power` (0.8 by default) at its own standard
error se and Welch degrees of freedom df, at the per-test level `level`
the adjustment applied (`per_test_level`: the raw p-value at or below
which one more, not yet rejected, test is sure to be rejected, the others'
p-values held fixed -- the threshold of the adjustment's next step).  With c the test's critical value
(t_{1 - level/2, df} two-sided, t_{1 - level, df} one-sided) and z the
normal quantile of the power,

    delta = se * (c (1 - 1/(4 df)) + z sqrt(1 + c^2 / (2 df))),

the Johnson-Welch normal approximation to the noncentral t's power
P(T'(df, delta/se) > c), taking the true standard error to be the
estimated one.  Against the exact noncentral t (levels 0.05 to 1e-7) it
overstates the exact delta, so the power at delta is at least the
target: at power 0.8 by at most 5% at df = 1, 2% at df = 2, 1.6% at
2.5, 1% at 4, 0.3% at 10, 0.06% at 30; at power 0.5 by at most 11%, 5%,
4%, 2.4%, 0.8% and 0.15% (tests/python/test_image_pass.py checks it by
integrating the normal tails over the chi-squared).  The textbook
(c + t_{power, df}) se is off by up to 20% either way at small df and
small levels.  A pass (no rejection) therefore says: a bias larger than `detectable_bias` at a pixel would probably have been
found; smaller ones could hide.  `compare`'s ``max_detectable_bias`` (or
``max_relative_detectable_bias``) turns that into the verdict
"inconclusive" when the pass could hide a larger bias at the chosen
quantile of pixels.

Block tests (``compare(..., block=N)``): the mean of each N x N block per
seed (edge blocks smaller), then the same Welch test per block.  A block
mean's values across seeds are independent whatever the correlation among
the pixels inside the block (a reconstruction filter's, a denoiser's), and
a bias spread over a region adds up while the noise averages out, so block
tests find small regional biases that per-pixel tests miss (Jung et al.
2020, JCGT, tested 32 x 32 blocks; here the sums are in double precision
and the Welch df real).

Equivalence (`equivalence`): the converse question, "is the candidate the
reference up to a margin?", for backends that should agree (CPU and GPU,
scalar and vectorised): two one-sided tests per block, and "equivalent"
only when every block is shown inside the margin.
"""
from __future__ import annotations

import dataclasses
import os
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union, cast

import numpy as np

from . import _core
from ._errors import InvalidArgumentError, NonFiniteError, TooFewObservationsError

__all__ = [
    "Samples",
    "Summary",
    "ImageComparison",
    "save_moments",
    "summary_of_moments",
    "compare",
    "COLOR_KEY",
    "LUMINANCE_WEIGHTS",
    "VERDICTS",
    "per_test_level",
    "detectable_bias",
    "equivalence",
    "ImageEquivalence",
    "Owned",
    "channel_names",
    "seed_axis_of",
]

# ImageComparison.verdict's values
VERDICTS = ("equal", "different", "inconclusive")

# libmcstat's calibrator for e-BH on p-values, e = kappa p^(kappa - 1) (p_adjust.c)
_EBH_KAPPA = 0.1

# Rec. 709 / sRGB primaries, linear light.
LUMINANCE_WEIGHTS = (0.2126, 0.7152, 0.0722)

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


class ImageInputError(InvalidArgumentError):
    """An image input that cannot be used: unreadable, unknown format,
    mismatched shapes, too few seeds, a missing reader package."""


@dataclass
class Samples:
    """Per-seed renders: ``data`` is ``(seeds, H, W, C)``."""

    data: np.ndarray
    channel_names: List[str]

    @property
    def shape(self) -> Tuple[int, int, int]:
        return tuple(self.data.shape[1:])  # type: ignore[return-value]


@dataclass
class Summary:
    """Per-pixel summaries: ``n``, ``mean``, ``m2`` (sum of squared
    deviations), each ``(H, W, C)``.  ``unreliable``: an optional bool
    ``(H, W, C)`` mask of tests whose variance the input lost (e.g. m2 -
    m1^2 of float32 moments, see `mcstat_app.image_exr`); `compare` does
    not test them and counts them under ``unreliable_note``."""

    n: np.ndarray
    mean: np.ndarray
    m2: np.ndarray
    channel_names: List[str]
    unreliable: Optional[np.ndarray] = None
    unreliable_note: str = "variance lost to float32 cancellation in the input (m2 - m1^2)"

    @property
    def shape(self) -> Tuple[int, int, int]:
        return tuple(self.mean.shape)  # type: ignore[return-value]


Side = Union[Samples, Summary]


def channel_names(c: int) -> List[str]:
    """The names of `c` channels as the reports print them: R, G, B[, A]
    for 3 or 4 channels, else c0, c1, ..."""
    return ["R", "G", "B", "A"][:c] if c in (3, 4) else [f"c{i}" for i in range(c)]


def summary_of_moments(acc: "MomentsArray") -> Summary:
    """Per-pixel summaries of a ``mcstat.MomentsArray`` of shape ``(H, W)``
    or ``(H, W, C)``: n, mean and M2 = var (n - 1) (0 where n < 2)."""
    if acc.ndim not in (2, 3):
        raise ImageInputError(f"a MomentsArray side must be (H, W) or (H, W, C), got shape {acc.shape}")
    n = np.asarray(acc.n, dtype=np.float64)
    mean = np.asarray(acc.mean, dtype=np.float64)
    with np.errstate(invalid="ignore"):
        m2 = np.where(n > 1, np.asarray(acc.var, dtype=np.float64) * (n - 1), 0.0)
    if acc.ndim == 2:
        n, mean, m2 = n[..., None], mean[..., None], m2[..., None]
    return Summary(np.ascontiguousarray(n), np.ascontiguousarray(mean), np.ascontiguousarray(m2),
                   channel_names(mean.shape[-1]))


def save_moments(path: str, acc: "MomentsArray") -> None:
    """Writes a ``MomentsArray`` as the ``.npz`` that ``mcstat image-test``
    (``mcstat_app.image.load_side``) reads: key ``moments``, ``uint8 (*shape, 96)``."""
    from ._core import MomentsArray

    if not isinstance(acc, MomentsArray):
        raise TypeError("save_moments expects a mcstat.MomentsArray")
    rec = np.frombuffer(acc.to_bytes(), dtype=np.uint8).reshape(tuple(acc.shape) + (-1,))
    np.savez(path, moments=rec)


def _fmt_tuple(t: Tuple[int, ...]) -> str:
    return "(" + ", ".join(str(v) for v in t) + ("," if len(t) == 1 else "") + ")"


def _seeds_first_is_clear(shape: Tuple[int, ...]) -> bool:
    """Whether a stack of this shape can only sensibly be (seeds, H, W[, C]):
    the first axis shorter than both image axes, or the image axes equal
    (a square image) and the first different; with 4 axes also at most 4
    channels last.  (32, 32, 16) is not: it reads as 32 seeds of 32 x 16
    as well as 16 seeds of 32 x 32."""
    if len(shape) not in (3, 4) or (len(shape) == 4 and shape[3] > 4):
        return False
    a, b, c = shape[:3]
    return a < min(b, c) or (b == c != a)


def _ambiguous(shape: Tuple[int, ...], what: str) -> ImageInputError:
    nd = len(shape)
    last = "(H, W, C, seeds)" if nd == 4 else "(H, W, seeds)"
    return ImageInputError(
        f"cannot tell which axis of {what} of shape {_fmt_tuple(shape)} holds the seeds: pass seed_axis=0 "
        f"if it is (seeds, H, W{', C' if nd == 4 else ''}), seed_axis=-1 if it is {last}, or the axis it is "
        "(seeds first is assumed only when the first axis is shorter than both image axes, or the image "
        "is square" + (", with at most 4 channels last" if nd == 4 else "") + ")")


def seed_axis_of(shape: Tuple[int, ...], what: str = "an image stack") -> int:
    """The seeds axis of one stack of `shape` when ``seed_axis`` was not
    given: 0 when `_seeds_first_is_clear`, else ImageInputError saying how
    to pass seed_axis."""
    if len(shape) not in (3, 4):
        raise ImageInputError(f"{what} must be (seeds, H, W) or (seeds, H, W, C), got shape {_fmt_tuple(shape)}")
    if _seeds_first_is_clear(shape):
        return 0
    raise _ambiguous(shape, what)


def _infer_seed_axis(reference: Any, candidate: Any) -> Optional[int]:
    """The seeds axis of the array sides of a comparison (one for both)
    when ``seed_axis`` was not given; None when neither side is an array.

    In order: (1) two stacks of the same rank that differ in the length of
    only their first, or only their last, axis have their seeds there; (2)
    a stack and the other side's image (a `Samples`, `Summary`,
    ``MomentsArray``): the first or the last axis, if only one of them
    leaves that image when removed; (3) seeds first when that is clear from
    either stack's shape (`_seeds_first_is_clear`).  Else ImageInputError:
    the layout is ambiguous."""
    known = [(_known_shape(reference), "the reference stack"), (_known_shape(candidate), "the candidate stack")]
    stacks = [(k[1], what) for k, what in known if k is not None and k[0] == "stack"]
    if not stacks:
        return None
    for shape, what in stacks:
        if len(shape) not in (3, 4):
            raise ImageInputError(f"an image stack must be (seeds, H, W) or (seeds, H, W, C), "
                                  f"got shape {_fmt_tuple(shape)} ({what})")
    ends = lambda nd: (0, nd - 1)  # noqa: E731  (where a seeds axis is ever put)
    if len(stacks) == 2:
        (sa, _), (sb, _) = stacks
        if len(sa) == len(sb) and sa != sb:
            diff = [k for k in range(len(sa)) if sa[k] != sb[k]]
            if len(diff) == 1 and diff[0] in ends(len(sa)):
                return diff[0]
    else:
        shape = stacks[0][0]
        other = next(k[1] for k, _ in known if k is not None and k[0] == "image") \
            if any(k is not None and k[0] == "image" for k, _ in known) else None
        if other is not None:
            img = other if len(shape) == 4 else other[:2] if other[2] == 1 else None
            if img is not None:
                fits = [k for k in ends(len(shape)) if shape[:k] + shape[k + 1:] == tuple(img)]
                if len(fits) == 1:
                    return fits[0]
    if any(_seeds_first_is_clear(shape) for shape, _ in stacks):
        return 0
    raise _ambiguous(*stacks[0])


def _known_shape(x: Any) -> Any:
    """What `seed_axis_of` can use of a side: ``("stack", shape)`` of an
    array, ``("image", (H, W, C))`` of the other inputs, or None."""
    from ._core import MomentsArray

    if isinstance(x, np.ndarray):
        return ("stack", tuple(x.shape))
    if isinstance(x, (Samples, Summary)):
        return ("image", tuple(x.shape))
    if isinstance(x, MomentsArray) and x.ndim in (2, 3):
        return ("image", tuple(x.shape) + ((1,) if x.ndim == 2 else ()))
    return None


def _as_side(x: Union[Side, np.ndarray, str, Sequence[str]], seed_axis: Optional[int]) -> Side:
    from ._core import MomentsArray

    if isinstance(x, (Samples, Summary)):
        return x
    if isinstance(x, MomentsArray):
        return summary_of_moments(x)
    if isinstance(x, np.ndarray):
        if x.ndim not in (3, 4):
            raise ImageInputError(f"an image stack must be (seeds, H, W) or (seeds, H, W, C), got shape {x.shape}")
        if seed_axis is None:
            seed_axis = seed_axis_of(tuple(x.shape))
        elif not -x.ndim <= seed_axis < x.ndim:
            raise ImageInputError(f"seed_axis {seed_axis} is out of range for a stack of shape {x.shape}")
        a = np.moveaxis(x, seed_axis, 0)
        if a.ndim == 3:
            a = a[..., None]
        if a.ndim != 4:
            raise ImageInputError(f"an image stack must be (seeds, H, W) or (seeds, H, W, C), got shape {x.shape}")
        return Samples(a, channel_names(a.shape[-1]))
    if isinstance(x, (str, os.PathLike)) or (isinstance(x, Sequence) and x and
                                             all(isinstance(p, (str, os.PathLike)) for p in x)):
        # files are the application's (mcstat 0.2.0 removed reading them here)
        raise ImageInputError("mcstat.image.compare takes arrays; to compare files, read them with "
                              "mcstat_app.image.load_side or call mcstat_app.image.compare")
    raise ImageInputError(f"a side must be an array (seeds, H, W[, C]), Samples, Summary or a MomentsArray, "
                          f"got {type(x).__name__}")


# ---- channels ------------------------------------------------------------------
@dataclass
class _WeightedSamples(Samples):
    """Luminance left as the RGB(A) stack and per-channel weights: the
    per-pixel test forms sum_c w_c x_c in double as it reads (no float64
    luminance stack)."""

    weights: Tuple[float, ...] = ()

    @property
    def shape(self) -> Tuple[int, int, int]:
        return tuple(self.data.shape[1:3]) + (1,)  # type: ignore[return-value]


def _luminance_samples(s: Samples) -> Samples:
    c = s.data.shape[-1]
    if c == 1:
        return Samples(s.data, ["Y"])
    if c < 3:
        raise ImageInputError(f"luminance needs RGB images, got {c} channels")
    return _WeightedSamples(s.data, ["Y"], tuple(LUMINANCE_WEIGHTS) + (0.0,) * (c - 3))


def _select(side: Side, channels: str) -> Side:
    if channels == "luminance":
        if isinstance(side, Summary):
            if side.mean.shape[-1] != 1 and "Y" in side.channel_names:
                # a CIE Y channel (Mitsuba's moment AOVs are XYZ) is the luminance
                k = side.channel_names.index("Y")
                u = None if side.unreliable is None else side.unreliable[..., k:k + 1]
                return dataclasses.replace(side, n=side.n[..., k:k + 1], mean=side.mean[..., k:k + 1],
                                           m2=side.m2[..., k:k + 1], channel_names=["Y"], unreliable=u)
            if side.mean.shape[-1] != 1:
                raise ImageInputError("luminance from per-channel summaries needs the channels' covariances; "
                                      "use channels='rgb' (per channel) or give luminance summaries")
            return dataclasses.replace(side, channel_names=["Y"])
        return _luminance_samples(side)
    if channels in ("rgb", "channels"):
        return side
    raise InvalidArgumentError(f"channels must be 'luminance' or 'rgb' (per channel), got {channels!r}")


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
        lines = [
            "\tPer-pixel Welch two-sample t-tests, candidate vs reference" if blk is None else
            f"\tBlock Welch two-sample t-tests ({blk['size']} x {blk['size']} block means), candidate vs reference",
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


# ---- what a pass means -----------------------------------------------------------
def _g(v: Optional[float]) -> str:
    return "n/a" if v is None else f"{v:.3g}"


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


# ---- block tests -----------------------------------------------------------------
def _block_means(s: Samples, n: int, nan_policy: str, name: str) -> Samples:
    """Per seed, the mean of each n x n block (double sums; the blocks at
    the right and bottom edges smaller).  Non-finite values: NonFiniteError
    (nan_policy "raise"), or the block is left untested (all its means NaN)."""
    k, h, w, c = s.data.shape
    ys, xs = np.arange(0, h, n), np.arange(0, w, n)
    d = s.data
    fin = np.isfinite(d)
    allfin = bool(fin.all())
    if not allfin:
        bad = ~fin.all(axis=0)
        if nan_policy == "raise":
            y, x, ch = np.unravel_index(int(np.argmax(bad)), bad.shape)
            chname = s.channel_names[ch] if ch < len(s.channel_names) else channel_names(c)[ch]
            raise NonFiniteError(f"{int(bad.sum())} pixel(s) of the {name} hold NaN or infinite values, the first at "
                                 f"x={x}, y={y} ({chname}); pass nan_policy='omit' (--nan omit) to leave "
                                 "the blocks holding them untested")
        d = np.where(fin, d, 0.0)
    sums = np.add.reduceat(np.add.reduceat(d, ys, axis=1, dtype=np.float64), xs, axis=2, dtype=np.float64)
    cy, cx = np.diff(np.append(ys, h)), np.diff(np.append(xs, w))
    means = sums / (cy[:, None] * cx[None, :]).astype(np.float64)[None, :, :, None]
    if not allfin:
        badb = np.add.reduceat(np.add.reduceat(bad.astype(np.int64), ys, axis=0), xs, axis=1) > 0
        means[:, badb] = np.nan
    if isinstance(s, _WeightedSamples):  # luminance: the channels' block means, weighted by the test
        return _WeightedSamples(means, list(s.channel_names), s.weights)
    return Samples(means, list(s.channel_names))


def _reference_luminance(side: Side) -> np.ndarray:
    if isinstance(side, Summary):
        mean = side.mean
    else:
        mean = side.data.mean(axis=0, dtype=np.float64) if side.data.dtype != np.float64 else side.data.mean(axis=0)
    return _luminance_of_means(mean)


def _luminance_of_means(mean: np.ndarray) -> np.ndarray:
    if mean.shape[-1] >= 3:
        return np.einsum("...c,c->...", mean[..., :3], np.asarray(LUMINANCE_WEIGHTS))
    return mean[..., 0]


class Owned:
    """A side handed over to `compare` by a caller that keeps no other
    reference to it (as mcstat_app hands over the renders it loaded):
    ``compare(Owned(a), Owned(b))`` drops the arrays once the tests have
    read them, so that the peak memory is the input or the outputs, not
    both.  The results are those of ``compare(a, b)``."""

    __slots__ = ("value",)

    def __init__(self, value: Any) -> None:
        self.value = value

    def take(self) -> Any:
        v, self.value = self.value, None
        return v


def _scratch_for_adjust(n: int, method: str, arrays: Sequence[np.ndarray]) -> Optional[np.ndarray]:
    """The first of the handed-over renders whose memory can serve as the
    adjustment's workspace (already resident: fresh pages for it cost as
    much as the sort at image scale), or None."""
    try:
        need = _core.p_adjust_work_size(n, method)
    except InvalidArgumentError:  # an unknown method: p_adjust says so
        return None
    for a in arrays:
        if (need > 0 and a.flags.c_contiguous and a.flags.writeable and a.nbytes >= need
                and a.ctypes.data % 8 == 0):
            return a
    return None


def compare(reference, candidate, *, alpha: float = 0.05, method: str = "BH", alternative: str = "two-sided",
            channels: str = "luminance", seed_axis: Optional[int] = None,
            nan_policy: str = "raise", block: Optional[int] = None, detect_power: float = 0.8,
            max_detectable_bias: Optional[float] = None,
            max_relative_detectable_bias: Optional[float] = None,
            bias_quantile: float = 0.9) -> ImageComparison:
    """Welch's test per pixel (and channel) of candidate against reference,
    p-values adjusted together by `method` (``mcstat.p_adjust``'s names;
    BH controls the false discovery rate at `alpha` for independent or
    positively dependent tests; BY and ``"e-BH"`` under any dependence,
    such as the correlation a reconstruction filter or denoiser puts
    between neighbouring pixels, at a cost in power: BY is the more
    powerful of the two).

    `reference`, `candidate`: `Samples`, `Summary`, a ``MomentsArray`` or an
    array ``(seeds, H, W[, C])`` of per-seed renders.  `seed_axis` says
    which axis of an array holds the seeds (``-1`` for ``(H, W, seeds)``
    or ``(H, W, C, seeds)``), the same for both sides.  Left out (None),
    it is taken from the shapes only where they settle it: the first or
    the last axis when the two sides' stacks differ in the length of that
    axis alone, or when removing it (and not the other) leaves the other
    side's image; else seeds first when a stack's first axis is shorter
    than both image axes or its image is square (and a 4-D stack has at
    most 4 channels last), as in ``(16, 480, 640)`` or ``(64, 32, 32, 3)``.
    A stack such as ``(32, 32, 16)``, which reads as 32 seeds of 32 x 16
    as well as 16 seeds of 32 x 32, raises `ImageInputError` asking for
    seed_axis.
    ``mcstat_app.image.compare`` also takes file paths.  The alternative is a claim about the candidate
    ("greater": the candidate is brighter).  Pixels where the test is
    undefined (constant in both inputs, non-finite values) are not tested:
    NaN p-values, not counted by the adjustment.  NaN or infinite values
    raise `NonFiniteError` (``nan_policy="raise"``), or with
    ``nan_policy="omit"`` NaN values are left out of their pixel's sample and
    pixels with infinities are not tested.  Raises `ImageInputError`
    (an `InvalidArgumentError`) for mismatched shapes and unusable inputs,
    `TooFewObservationsError` for fewer than 2 seeds per side.

    `block`: test the means of `block` x `block` blocks instead of pixels
    (per-seed inputs only: per-pixel summaries lack the covariances of the
    pixels inside a block); the result is at block resolution (``block``
    says the size, ``image_shape`` the image's), the blocks at the right and
    bottom edges smaller when the size does not divide the image's.  With
    ``nan_policy="omit"`` a block holding a non-finite value in any seed is
    not tested.

    `detect_power`: the power behind ``detectable_bias`` (see the module's
    doc).  `max_detectable_bias` (absolute, in the image's units) and
    `max_relative_detectable_bias` (relative to the absolute reference mean): the
    verdict is "inconclusive" rather than "equal" when, at the
    `bias_quantile` of the passing pixels, ``detectable_bias`` exceeds them.
    """
    t0 = time.perf_counter()
    scratch = None  # a handed-over render's memory, reused by the adjustment
    own_r, own_c = isinstance(reference, Owned), isinstance(candidate, Owned)
    if own_r:
        reference = reference.take()
    if own_c:
        candidate = candidate.take()
    if block is not None and (isinstance(block, bool) or not isinstance(block, (int, np.integer)) or block < 1):
        raise InvalidArgumentError(f"block must be a positive integer (the block's side in pixels), got {block!r}")
    if not (0.0 < detect_power < 1.0):
        raise InvalidArgumentError(f"detect_power must lie in (0, 1), got {detect_power}")
    if not (0.0 <= bias_quantile <= 1.0):
        raise InvalidArgumentError(f"bias_quantile must lie in [0, 1], got {bias_quantile}")
    for nm, lim in (("max_detectable_bias", max_detectable_bias),
                    ("max_relative_detectable_bias", max_relative_detectable_bias)):
        if lim is not None and not (np.isfinite(lim) and lim > 0):
            raise InvalidArgumentError(f"{nm} must be positive and finite, got {lim}")
    if seed_axis is None:
        seed_axis = _infer_seed_axis(reference, candidate)
    ref = _as_side(reference, seed_axis)
    cand = _as_side(candidate, seed_axis)
    if not (0.0 < alpha < 1.0):
        raise InvalidArgumentError(f"alpha must lie in (0, 1), got {alpha}")
    if isinstance(ref, Samples) != isinstance(cand, Samples):
        raise ImageInputError("both sides must be per-seed renders, or both per-pixel summaries (.npz)")
    if ref.shape != cand.shape:
        raise ImageInputError(f"the reference is {_fmt_shape(ref.shape)} but the candidate is {_fmt_shape(cand.shape)}")
    # The map's background: per-seed tests compute the reference's means
    # anyway (est_r below: the luminance's, or each channel's, whose
    # weighted sum is the mean luminance), so only other inputs take a pass
    # over the reference for it.
    bg_from_test = channels in ("luminance", "rgb", "channels") and block is None and isinstance(ref, Samples)
    bg = None if bg_from_test else _reference_luminance(ref)
    ref = _select(ref, channels)
    cand = _select(cand, channels)
    image_shape = (ref.shape[0], ref.shape[1])
    if block is not None:
        if not isinstance(ref, Samples) or not isinstance(cand, Samples):
            raise ImageInputError("block tests need per-seed renders: a block mean's variance needs the covariances "
                                  "of the pixels inside the block, which per-pixel summaries (n, mean, M2) lack")
        if nan_policy not in ("raise", "omit"):
            raise InvalidArgumentError(f"nan_policy must be 'raise' or 'omit', got {nan_policy!r}")
        ref = _block_means(ref, int(block), nan_policy, "reference")
        cand = _block_means(cand, int(block), nan_policy, "candidate")
    t1 = time.perf_counter()
    if isinstance(ref, Samples):
        for name, s in (("reference", ref), ("candidate", cand)):
            if s.data.shape[0] < 2:
                raise TooFewObservationsError(f"the {name} has {s.data.shape[0]} seed(s); Welch's test needs at "
                                              "least 2 per side")
        # candidate first: the alternative is a claim about it
        if nan_policy not in ("raise", "omit"):
            raise InvalidArgumentError(f"nan_policy must be 'raise' or 'omit', got {nan_policy!r}")
        # Seeds-major as rendered, read in place (float32 stays float32;
        # luminance is formed from the channels as they are read).
        weights = getattr(cand, "weights", None)
        dt = np.float32 if cand.data.dtype == np.float32 and ref.data.dtype == np.float32 else np.float64
        xc = np.ascontiguousarray(cand.data, dtype=dt)
        yr = np.ascontiguousarray(ref.data, dtype=dt)
        if weights is None:  # one test per channel: the channels are pixels of their own
            xc, yr = xc.reshape(xc.shape[0], -1), yr.reshape(yr.shape[0], -1)
        r = _core._t_test_2_pixels(xc, yr, weights, _core._alternative_code(alternative), alpha,
                                   omit_nan=nan_policy == "omit")
        shp = cand.shape
        # the handed-over renders have been read (see Owned); a side not
        # handed over is the caller's and stays as it is
        scratch = _scratch_for_adjust(r["pvalue"].size, method, [a for a, own in ((xc, own_c), (yr, own_r)) if own])
        if own_r:
            reference = None
            ref.data = None  # type: ignore[assignment]
        if own_c:
            candidate = None
            cand.data = None  # type: ignore[assignment]
        del xc, yr
        pvalue, stat, status = (r[k].reshape(shp) for k in ("pvalue", "statistic", "status"))
        est_c, est_r = r["mean_x"].reshape(shp), r["mean_y"].reshape(shp)  # no stacked copy: memory
    else:
        shp = ref.shape
        f = _core._t_test_2_summary_rows(cand.n, cand.mean, cand.m2, ref.n, ref.mean, ref.m2,
                                         _core._alternative_code(alternative), alpha)
        pvalue, stat, status = (f[k].reshape(shp) for k in ("pvalue", "statistic", "status"))
        est = f["estimate"].reshape(shp + (2,))
        est_c, est_r = est[..., 0], est[..., 1]
        if np.any((ref.n < 2) | (cand.n < 2)):
            raise TooFewObservationsError("a per-pixel summary has n < 2; Welch's test needs at least 2 per side")
    lost, notes = _variance_lost(ref, cand)
    if lost is not None:
        pvalue, stat = np.where(lost, np.nan, pvalue), np.where(lost, np.nan, stat)
        status = np.where(lost, -1, status)
    if nan_policy == "raise":
        bad = status == NonFiniteError.status
        if bad.any():
            y, x, ch = np.unravel_index(int(np.argmax(bad)), bad.shape)
            raise NonFiniteError(f"{int(bad.sum())} pixel(s) hold NaN or infinite values, the first at x={x}, "
                                 f"y={y} ({ref.channel_names[ch]}); pass nan_policy='omit' (--nan omit) to leave "
                                 "NaN values out and not test pixels with infinities")
    t2 = time.perf_counter()
    padj = _core.p_adjust(pvalue, method=method, work=scratch)
    scratch = None
    if isinstance(ref, Samples):
        se, dfw = r["std_error"].reshape(shp), r["df"].reshape(shp)
    else:
        assert isinstance(cand, Summary) and isinstance(ref, Summary)
        se, dfw = _welch_se_df(cand, ref)
    t3 = time.perf_counter()
    if bg is None:  # luminance of the per-channel means (or the luminance's mean) the test computed
        bg = _luminance_of_means(est_r)
    tested = status == 0
    sig = padj <= alpha
    dec = np.zeros(pvalue.shape, dtype=np.int8)
    dec[sig & (est_c > est_r)] = 1
    dec[sig & (est_c < est_r)] = -1
    if alternative == "greater":
        dec[dec < 0] = 0
    elif alternative == "less":
        dec[dec > 0] = 0
    res = ImageComparison(pvalue, padj, stat, dec, tested, est_c, est_r, bg, list(ref.channel_names),
                          alpha, _canonical_method(method), alternative)
    res.variance_lost, res.notes = int(lost.sum()) if lost is not None else 0, notes
    t4 = time.perf_counter()
    m = int(np.count_nonzero(~np.isnan(pvalue)))
    res.level = per_test_level(res.method, alpha, m, res.rejections)
    if m > 0:
        db = detectable_bias(se, dfw, res.level, alternative=alternative, power=detect_power)
        db[~tested] = np.nan
        res.detectable_bias = db
    res.detect_power = detect_power
    res.max_detectable_bias = max_detectable_bias
    res.max_relative_detectable_bias = max_relative_detectable_bias
    res.bias_quantile = bias_quantile
    if block is not None:
        res.block, res.image_shape = int(block), image_shape
    res.timings = {"load_and_channels": t1 - t0, "tests": t2 - t1, "adjust": t3 - t2,
                   "decisions": t4 - t3, "detectable_bias": time.perf_counter() - t4}
    return res


def _variance_lost(ref: Side, cand: Side) -> Tuple[Optional[np.ndarray], List[str]]:
    """The tests that a side's `Summary.unreliable` marks (not tested), and
    the note counting them."""
    sides = [s for s in (ref, cand) if isinstance(s, Summary) and s.unreliable is not None]
    if not sides:
        return None, []
    lost = np.zeros(ref.shape, dtype=bool)
    for s in sides:
        lost |= np.broadcast_to(np.asarray(s.unreliable, dtype=bool), ref.shape)
    notes = sorted({s.unreliable_note for s in sides})
    k = int(lost.sum())
    what = f"{k} pixels" if ref.shape[-1] == 1 else f"{k} tests (pixel channels)"
    return lost, ([f"{what}: {'; '.join(notes)}; not tested"] if k else [])


def _canonical_method(m: str) -> str:
    # R's name of the method, whatever alias was given ("fdr_bh" -> "BH")
    return _core._p_adjust_method_name(m)


def _fmt_shape(s: Tuple[int, int, int]) -> str:
    return f"{s[1]} x {s[0]} pixels (width x height) with {s[2]} channel(s)"


# Backend equivalence (TOST per block, an intersection-union verdict): its own file.
from ._image_equivalence import ImageEquivalence, equivalence  # noqa: E402


# The file readers, the map writer and the command are the application's
# (mcstat_app.image; mcstat 0.2.0 removed their aliases here): say where.
_MOVED = ("load_side", "read_image", "map_rgb", "write_map", "run")


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}: it is mcstat_app.image.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
