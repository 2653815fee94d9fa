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
"""
from __future__ import annotations

import os
import time
import warnings
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

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
]

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
    deviations), each ``(H, W, C)``."""

    n: np.ndarray
    mean: np.ndarray
    m2: np.ndarray
    channel_names: List[str]

    @property
    def shape(self) -> Tuple[int, int, int]:
        return tuple(self.mean.shape)  # type: ignore[return-value]


Side = Union[Samples, Summary]


def _channel_names(c: int) -> List[str]:
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
                   _channel_names(mean.shape[-1]))


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


def _seed_axis_of(shape: Tuple[int, ...], what: str = "an image stack") -> int:
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
    """What `_seed_axis_of` can use of a side: ``("stack", shape)`` of an
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
            seed_axis = _seed_axis_of(tuple(x.shape))
        elif not -x.ndim <= seed_axis < x.ndim:
            raise ImageInputError(f"seed_axis {seed_axis} is out of range for a stack of shape {x.shape}")
        a = np.moveaxis(x, seed_axis, 0)
        if a.ndim == 3:
            a = a[..., None]
        if a.ndim != 4:
            raise ImageInputError(f"an image stack must be (seeds, H, W) or (seeds, H, W, C), got shape {x.shape}")
        return Samples(a, _channel_names(a.shape[-1]))
    if isinstance(x, (str, os.PathLike)) or (isinstance(x, Sequence) and x and
                                             all(isinstance(p, (str, os.PathLike)) for p in x)):
        # Files are the application's; reading them here is kept for one release.
        warnings.warn("mcstat.image.compare reading files is deprecated: read them with "
                      "mcstat_app.image.load_side, or call mcstat_app.image.compare", DeprecationWarning,
                      stacklevel=3)
        from mcstat_app.image import load_side

        return load_side(x, seed_axis=seed_axis)
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
            if side.mean.shape[-1] != 1:
                raise ImageInputError("luminance from per-channel summaries needs the channels' covariances; "
                                      "use channels='rgb' (per channel) or give luminance summaries")
            return Summary(side.n, side.mean, side.m2, ["Y"])
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
            "worst": self.worst(worst),
            "timings_s": {k: round(v, 4) for k, v in self.timings.items()},
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
        lines = [
            "\tPer-pixel Welch two-sample t-tests, candidate vs reference",
            "",
            f"image:  {w} x {h}, channels {', '.join(s['image']['channels'])}: {s['tests']} tests, "
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
        if s["worst"]:
            lines += ["", "smallest p-values:", "     x      y  ch    p-value   adjusted          t  decision"]
            for r in s["worst"]:
                lines.append(f"{r['x']:6d} {r['y']:6d} {r['channel']:>3s} {r['pvalue']:10.3g} "
                             f"{r['padjusted']:10.3g} {r['t']:10.4g}  {r['decision']}")
        return "\n".join(lines) + "\n"


def _reference_luminance(side: Side) -> np.ndarray:
    if isinstance(side, Summary):
        mean = side.mean
    else:
        mean = side.data.mean(axis=0, dtype=np.float64) if side.data.dtype != np.float64 else side.data.mean(axis=0)
    if mean.shape[-1] >= 3:
        return np.einsum("...c,c->...", mean[..., :3], np.asarray(LUMINANCE_WEIGHTS))
    return mean[..., 0]


def compare(reference, candidate, *, alpha: float = 0.05, method: str = "BH", alternative: str = "two-sided",
            channels: str = "luminance", seed_axis: Optional[int] = None,
            nan_policy: str = "raise") -> ImageComparison:
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
    """
    t0 = time.perf_counter()
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
    bg = _reference_luminance(ref)
    ref = _select(ref, channels)
    cand = _select(cand, channels)
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
        pvalue, stat, status = (r[k].reshape(shp) for k in ("pvalue", "statistic", "status"))
        est = np.stack([r["mean_x"].reshape(shp), r["mean_y"].reshape(shp)], axis=-1)
    else:
        shp = ref.shape
        f = _core._t_test_2_summary_rows(cand.n, cand.mean, cand.m2, ref.n, ref.mean, ref.m2,
                                         _core._alternative_code(alternative), alpha)
        pvalue, stat, status = (f[k].reshape(shp) for k in ("pvalue", "statistic", "status"))
        est = f["estimate"].reshape(shp + (2,))
        if np.any((ref.n < 2) | (cand.n < 2)):
            raise TooFewObservationsError("a per-pixel summary has n < 2; Welch's test needs at least 2 per side")
    if nan_policy == "raise":
        bad = status == NonFiniteError.status
        if bad.any():
            y, x, ch = np.unravel_index(int(np.argmax(bad)), bad.shape)
            raise NonFiniteError(f"{int(bad.sum())} pixel(s) hold NaN or infinite values, the first at x={x}, "
                                 f"y={y} ({ref.channel_names[ch]}); pass nan_policy='omit' (--nan omit) to leave "
                                 "NaN values out and not test pixels with infinities")
    t2 = time.perf_counter()
    padj = _core.p_adjust(pvalue, method=method)
    t3 = time.perf_counter()
    tested = status == 0
    sig = padj <= alpha
    dec = np.zeros(pvalue.shape, dtype=np.int8)
    diff = est[..., 0] - est[..., 1]
    dec[sig & (diff > 0)] = 1
    dec[sig & (diff < 0)] = -1
    if alternative == "greater":
        dec[dec < 0] = 0
    elif alternative == "less":
        dec[dec > 0] = 0
    res = ImageComparison(pvalue, padj, stat, dec, tested, est[..., 0], est[..., 1], bg, list(ref.channel_names),
                          alpha, _canonical_method(method), alternative)
    res.timings = {"load_and_channels": t1 - t0, "tests": t2 - t1, "adjust": t3 - t2,
                   "decisions": time.perf_counter() - t3}
    return res


def _canonical_method(m: str) -> str:
    # R's name of the method, whatever alias was given ("fdr_bh" -> "BH")
    return _core._p_adjust_method_name(m)


def _fmt_shape(s: Tuple[int, int, int]) -> str:
    return f"{s[1]} x {s[0]} pixels (width x height) with {s[2]} channel(s)"


# The file readers, the map writer and the command moved to the application
# (mcstat_app.image); these names resolve there for one release.
_MOVED = ("load_side", "read_image", "map_rgb", "write_map", "run")


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        warnings.warn(f"mcstat.image.{name} is deprecated: use mcstat_app.image.{name}", DeprecationWarning,
                      stacklevel=2)
        import mcstat_app.image

        return getattr(mcstat_app.image, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
