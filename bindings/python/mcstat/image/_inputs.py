# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat.image's inputs: per-seed renders (`Samples`), per-pixel summaries
(`Summary`, `summary_of_moments`, `save_moments`), which axis of a stack
holds the seeds (`seed_axis_of`), a side as `compare` takes it, and the
channels tested (luminance or each channel)."""
from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from typing import Any, List, Optional, Sequence, Tuple, Union

import numpy as np

from .._errors import InvalidArgumentError

# Rec. 709 / sRGB primaries, linear light.
LUMINANCE_WEIGHTS = (0.2126, 0.7152, 0.0722)


class ImageInputError(InvalidArgumentError):
    """An image input that cannot be used: unreadable, unknown format,
    mismatched shapes, too few seeds, a missing reader package."""


@dataclass
class Samples:
    """Per-seed renders: ``data`` is ``(seeds, H, W, C)``.  ``source``:
    what was read, when it came from files (e.g. the EXR layer), which
    `compare` states in its notes."""

    data: np.ndarray
    channel_names: List[str]
    source: str = ""

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
    from .._core import MomentsArray

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
        "(on the command line: --seed-axis 0, --seed-axis -1; seeds first is assumed only when the first "
        "axis is shorter than both image axes, or the image is square"
        + (", with at most 4 channels last" if nd == 4 else "") + ")")


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
    from .._core import MomentsArray

    if isinstance(x, np.ndarray):
        return ("stack", tuple(x.shape))
    if isinstance(x, (Samples, Summary)):
        return ("image", tuple(x.shape))
    if isinstance(x, MomentsArray) and x.ndim in (2, 3):
        return ("image", tuple(x.shape) + ((1,) if x.ndim == 2 else ()))
    return None


def _as_side(x: Union[Side, np.ndarray, str, Sequence[str]], seed_axis: Optional[int]) -> Side:
    from .._core import MomentsArray

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
    return _WeightedSamples(s.data, ["Y"], weights=tuple(LUMINANCE_WEIGHTS) + (0.0,) * (c - 3))


# the words for "test each channel": compare's 'rgb' and equivalence's 'all'
# mean the same, and both functions take either
CHANNELS_EACH = ("rgb", "all", "channels")


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
    if channels in CHANNELS_EACH:
        return side
    raise InvalidArgumentError(f"channels must be 'luminance' or 'rgb' (each channel; also 'all'), got {channels!r}")
