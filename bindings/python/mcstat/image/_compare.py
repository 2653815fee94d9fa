# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""mcstat.image.compare: Welch's test per pixel (or per block) of two
renders' sides, the p-values adjusted together, and what a pass means."""
from __future__ import annotations

import time
from typing import Any, List, Optional, Sequence, Tuple

import numpy as np

from .. import _core
from .._errors import InvalidArgumentError, NonFiniteError, TooFewObservationsError
from ._bias import _canonical_method, _welch_se_df, detectable_bias, per_test_level
from ._inputs import (
    LUMINANCE_WEIGHTS,
    ImageInputError,
    Samples,
    Side,
    Summary,
    _as_side,
    _infer_seed_axis,
    _select,
    _WeightedSamples,
    channel_names,
)
from ._report import ImageComparison


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
        return _WeightedSamples(means, list(s.channel_names), weights=s.weights)
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
            bias_quantile: float = 0.9, render_guards: bool = True,
            resolution: Optional[float] = None, paired: bool = False) -> ImageComparison:
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

    `render_guards` (default True; per-seed inputs): libmcstat's
    MCSTAT_PIXELS_RENDER, which makes the per-pixel test valid on renders.
    A pixel constant on one side (all zeros: lit only by rare paths) or
    with at most one nonzero value there carries no information about the
    rare values that side may hide; its variance is floored by the rule of
    three (the 95% bound on an unseen value's rate from K seeds), so that
    such a pixel can never be significant alone: it is untestable per
    pixel and needs ``block=`` tests or more seeds.  The degrees of freedom
    are Hsu's conservative min(K) - 1 (a side with zeros counts its nonzero
    values less one).  Spreads and differences within `resolution` of the
    larger mean (relative; None: 2^-18, 64 float32 ulps, for float32 inputs,
    2^-47 for float64, as the renderer checks derive theirs) are rounding: a
    pixel constant on both sides and equal within it is not tested;
    different beyond it, both sides take the rule-of-three variance (at a
    few samples per pixel a light's edge gives every seed the same count of
    hits by chance: constant is not deterministic).  The value used is
    ``resolution`` of the result.  False: the plain Welch test of ``mcstat.t_test``
    (R's t.test) per pixel.  A side that hides a rare component while its
    other values vary (a light sampled too rarely to show in K seeds)
    cannot be detected by any per-pixel test of means (Bahadur and
    Savage): block tests see it.

    `paired`: seed s of the candidate was rendered with the same seed as
    seed s of the reference (same-seed renders): the paired t test on the
    per-seed differences instead of Welch's (R's ``t.test(paired = TRUE)``
    per pixel or block).  Renders of the same seed share their random
    numbers, and where the change leaves a path alone its noise cancels
    from the difference, so the paired test sees smaller changes at the
    same seeds; it is valid only for such pairs (per-seed inputs of equal
    seed counts; the pairs in the order given).  The render guards apply
    to the differences: a pixel whose differences, or either side, are
    constant or show at most one nonzero value takes the rule-of-three
    variance; pixels equal in every seed (the change did not reach them)
    are not tested.

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
    input_notes = _input_notes(ref, cand)  # before channel selection and blocks: their sources and types
    if not (0.0 < alpha < 1.0):
        raise InvalidArgumentError(f"alpha must lie in (0, 1), got {alpha}")
    if isinstance(ref, Samples) != isinstance(cand, Samples):
        raise ImageInputError("both sides must be per-seed renders, or both per-pixel summaries (.npz)")
    paired = bool(paired)
    if paired and not isinstance(ref, Samples):
        raise ImageInputError("paired=True needs per-seed renders on both sides (the pairs), not per-pixel summaries")
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
    if block is not None and block > max(image_shape):
        raise InvalidArgumentError(f"block {block} is larger than the image ({image_shape[0]} x {image_shape[1]}): "
                                   "it would be one block; give a block side at most the image's")
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
                raise TooFewObservationsError(f"the {name} has {s.data.shape[0]} seed(s); "
                                              f"{'the paired' if paired else 'Welch' + chr(39) + 's'} test needs at "
                                              "least 2 per side")
        if paired and ref.data.shape[0] != cand.data.shape[0]:
            raise ImageInputError(f"paired=True needs the same seeds on both sides, got {cand.data.shape[0]} "
                                  f"candidate and {ref.data.shape[0]} reference seeds")
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
        if resolution is not None and not (np.isfinite(resolution) and 0.0 <= resolution < 1.0):
            raise InvalidArgumentError(f"resolution must lie in [0, 1), got {resolution}")
        eps_used = (float(resolution) if resolution else
                    _core.RESOLUTION_FLOAT32 if dt == np.float32 else _core.RESOLUTION_FLOAT64)
        r = _core._t_test_2_pixels(xc, yr, weights, _core._alternative_code(alternative), alpha,
                                   omit_nan=nan_policy == "omit", render=bool(render_guards), resolution=eps_used,
                                   paired=paired)
        if paired:  # the test gives the mean difference; the reference's mean for the map and relative bias
            w = None if weights is None else np.asarray(weights, dtype=np.float64)
            yv = yr if w is None else yr @ w  # the tested values, as the test forms them
            if nan_policy == "omit":  # over the pairs the test kept: neither side NaN
                xv = xc if w is None else xc @ w
                with np.errstate(invalid="ignore"):
                    my = np.nanmean(np.where(np.isnan(xv), np.nan, yv), axis=0, dtype=np.float64)
            else:
                my = yv.mean(axis=0, dtype=np.float64)
            r["mean_y"] = my.reshape(r["mean_x"].shape)
            r["mean_d"] = r["mean_x"]
            r["mean_x"] = r["mean_y"] + r["mean_d"]
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
        # the sign of the difference (paired: of the mean difference, which
        # the sum est_r + d could round away)
        delta = r["mean_d"].reshape(shp) if paired else None
    else:
        shp = ref.shape
        delta = None
        f = _core._t_test_2_summary_rows(cand.n, cand.mean, cand.m2, ref.n, ref.mean, ref.m2,
                                         _core._alternative_code(alternative), alpha)
        pvalue, stat, status = (f[k].reshape(shp) for k in ("pvalue", "statistic", "status"))
        est = f["estimate"].reshape(shp + (2,))
        est_c, est_r = est[..., 0], est[..., 1]
        if np.any((ref.n < 2) | (cand.n < 2)):
            raise TooFewObservationsError("a per-pixel summary has n < 2; Welch's test needs at least 2 per side")
    lost, notes = _variance_lost(ref, cand)
    notes = input_notes + notes
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
    if delta is None:
        delta = est_c - est_r
    dec[sig & (delta > 0)] = 1
    dec[sig & (delta < 0)] = -1
    if alternative == "greater":
        dec[dec < 0] = 0
    elif alternative == "less":
        dec[dec > 0] = 0
    res = ImageComparison(pvalue, padj, stat, dec, tested, est_c, est_r, bg, list(ref.channel_names),
                          alpha, _canonical_method(method), alternative)
    res.paired = paired
    res.variance_lost, res.notes = int(lost.sum()) if lost is not None else 0, notes
    res.render_guards = bool(render_guards) and isinstance(ref, Samples)
    res.resolution = eps_used if res.render_guards else None
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


def _input_notes(ref_in: Side, cand_in: Side) -> List[str]:
    """What each side was read from (a file's layer), and inputs of a
    low bit depth: integer or half values are clipped, tone-mapped or
    quantised renders, whose means are not the radiance's."""
    out = []
    for name, s in (("reference", ref_in), ("candidate", cand_in)):
        src = getattr(s, "source", "")
        if src:
            out.append(f"{name}: {src}")
        data = s.data if isinstance(s, Samples) else None
        if data is not None and (np.issubdtype(data.dtype, np.integer) or data.dtype == np.float16):
            out.append(f"{name}: {data.dtype} values ({np.dtype(data.dtype).itemsize * 8} bits): a display "
                       "image (clipped, tone-mapped or quantised) is compared, not radiance; render to "
                       "float32 (EXR, PFM, .npy) for a test of the renderer's estimates")
    return out


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


def _fmt_shape(s: Tuple[int, int, int]) -> str:
    return f"{s[1]} x {s[0]} pixels (width x height) with {s[2]} channel(s)"
