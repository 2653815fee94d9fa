# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Backend equivalence: is the candidate image the reference up to a margin?

"Is the GPU (or LLVM, or new) image the same as the CPU one?" asked as a
difference test gets harder to pass the more samples are spent: at large
sample counts a 1e-4 float difference is significant.  Asked as an
equivalence test it gets easier: the claim to show is

    (1 - margin) mu_ref - atol  <  mu_cand  <  (1 + margin) mu_ref + atol

for every block (or pixel), by two one-sided Welch tests (TOST) on the
linear contrasts mu_cand - (1 -+ margin) mu_ref, each libmcstat's per-pixel
Welch test (``mcstat.t_test(..., axis=0)``).  The contrasts are linear in
the means, so no ratio of estimates (and no random margin) enters; radiance
is taken to be non-negative (a negative reference mean leaves the margin
empty, so its block is never shown equivalent).

The verdict: "equivalent" when every block's TOST rejects at alpha, an
intersection-union test (Berger 1982), whose level is alpha without any
multiplicity adjustment: if any block's true difference is outside the
margin, the chance that all blocks are shown equivalent is at most alpha.
Per-seed block means (as ``compare(block=...)``) keep the test valid under
any correlation among the pixels of a block.  Per pixel, the TOST p-values
adjusted by Benjamini-Hochberg say which pixels are shown equivalent, with
the expected share of wrongly claimed pixels at most alpha (a map, not the
verdict).

Units whose values are constant on both sides (a black background) are
decided exactly: equivalent when the constants satisfy the margin.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any, List, Optional, Tuple

import numpy as np

from .. import _core
from .._errors import InvalidArgumentError, NonFiniteError

__all__ = ["ImageEquivalence", "equivalence"]


@dataclass
class ImageEquivalence:
    """The result of `equivalence`."""

    equivalent: bool
    margin: float
    atol: float
    alpha: float
    block: int
    shape: Tuple[int, int, int]
    channel_names: List[str]
    seeds: Tuple[int, int]
    #: per block (H', W', C): the TOST p-value (NaN: untestable)
    block_pvalue: np.ndarray
    #: per block: (mean_cand - mean_ref) / mean_ref
    block_relative_difference: np.ndarray
    #: per block: about the smallest margin its data shows (at alpha)
    block_margin_shown: np.ndarray
    #: per pixel (H, W, C): the TOST p-value, and BH-adjusted
    pixel_pvalue: np.ndarray
    pixel_p_adjusted: np.ndarray
    #: "raise" or "omit" (NaN values left out of their pixel's and block's samples)
    nan_policy: str = "raise"

    @property
    def pixels_shown_equivalent(self) -> np.ndarray:
        """Pixels shown equivalent with the false discovery rate at most alpha (BH)."""
        with np.errstate(invalid="ignore"):
            return self.pixel_p_adjusted <= self.alpha

    @property
    def blocks_shown(self) -> int:
        with np.errstate(invalid="ignore"):
            return int(np.sum(self.block_pvalue <= self.alpha))

    @property
    def blocks_untestable(self) -> int:
        return int(np.sum(np.isnan(self.block_pvalue)))

    @property
    def margin_shown(self) -> float:
        """About the smallest relative margin every block's data shows at
        alpha (where atol is 0): the verdict would be "equivalent" for any
        margin above it.  NaN when a block is untestable."""
        m = self.block_margin_shown
        return float(np.max(m)) if m.size and not np.isnan(m).any() else float("nan")

    def worst(self, k: int = 5) -> List[dict]:
        """The k blocks furthest from being shown equivalent (largest p)."""
        p = np.where(np.isnan(self.block_pvalue), np.inf, self.block_pvalue)
        order = np.argsort(-p, axis=None, kind="stable")[:k]
        out = []
        h, w, _ = self.shape
        for flat in order:
            by, bx, c = np.unravel_index(int(flat), self.block_pvalue.shape)
            y0, x0 = int(by) * self.block, int(bx) * self.block
            out.append({
                "x": (x0, min(x0 + self.block, w) - 1), "y": (y0, min(y0 + self.block, h) - 1),
                "channel": self.channel_names[int(c)], "pvalue": float(self.block_pvalue[by, bx, c]),
                "relative_difference": float(self.block_relative_difference[by, bx, c]),
            })
        return out

    def text(self, worst: int = 5) -> str:
        h, w, c = self.shape
        nb = self.block_pvalue.size
        lines = [
            f"mcstat image equivalence: candidate within {self.margin:.4g} (relative) + {self.atol:.4g} of the "
            f"reference, {w} x {h} x {c} ({', '.join(self.channel_names)}), seeds {self.seeds[1]} candidate, "
            f"{self.seeds[0]} reference",
            f"  blocks of {self.block} x {self.block}: {nb}; shown equivalent {self.blocks_shown}, untestable "
            f"{self.blocks_untestable} (intersection-union test at alpha {self.alpha:.3g}: every block must be)",
            f"  verdict: {'equivalent' if self.equivalent else 'not shown equivalent'}",
            f"  margin the data shows: about {self.margin_shown:.3g} (relative)",
            f"  pixels shown equivalent (BH, FDR {self.alpha:.3g}): {int(self.pixels_shown_equivalent.sum())} of "
            f"{self.pixel_pvalue.size}",
        ]
        if not self.equivalent:
            lines.append("  blocks furthest from equivalence:")
            for b in self.worst(worst):
                lines.append(f"    x {b['x'][0]}..{b['x'][1]}, y {b['y'][0]}..{b['y'][1]} ({b['channel']}): "
                             f"p {b['pvalue']:.3g}, relative difference {b['relative_difference']:+.3g}")
        return "\n".join(lines)

    def summary(self, worst: int = 5) -> dict:
        """The result as plain data (``mcstat image-test --equivalence --json``)."""
        h, w, c = self.shape

        def num(v: float) -> Optional[float]:
            return None if np.isnan(v) else float(v)
        return {
            "test": "equivalence",
            "image": {"height": h, "width": w, "channels": self.channel_names},
            "seeds": {"reference": self.seeds[0], "candidate": self.seeds[1]},
            "margin": self.margin,
            "atol": self.atol,
            "alpha": self.alpha,
            "block": self.block,
            "nan_policy": self.nan_policy,
            "verdict": "equivalent" if self.equivalent else "not shown equivalent",
            "blocks": int(self.block_pvalue.size),
            "blocks_shown": self.blocks_shown,
            "blocks_untestable": self.blocks_untestable,
            "margin_shown": num(self.margin_shown),
            "pixels_shown_equivalent": int(self.pixels_shown_equivalent.sum()),
            "pixels": int(self.pixel_pvalue.size),
            "worst_blocks": [dict(b, pvalue=num(b["pvalue"]), relative_difference=num(b["relative_difference"]))
                             for b in self.worst(worst)],
        }

    def __str__(self) -> str:
        return self.text()


def _stack(x: Any, seed_axis: Optional[int], channels: str, name: str) -> Tuple[np.ndarray, List[str]]:
    from ._inputs import CHANNELS_EACH, LUMINANCE_WEIGHTS, Samples, _as_side

    side = _as_side(x, seed_axis)
    if not isinstance(side, Samples):
        raise InvalidArgumentError(f"{name}: equivalence needs per-seed renders (an array (seeds, H, W[, C]) or "
                                   "Samples), not per-pixel summaries")
    d = side.data
    if channels == "luminance":
        if d.shape[-1] == 1:
            return d, ["Y"]
        if d.shape[-1] < 3:
            raise InvalidArgumentError(f"{name}: luminance needs RGB images, got {d.shape[-1]} channels")
        return np.einsum("...c,c->...", d[..., :3], np.asarray(LUMINANCE_WEIGHTS))[..., None], ["Y"]
    if channels not in CHANNELS_EACH:
        raise InvalidArgumentError(f"channels must be 'luminance' or 'rgb' (each channel; also 'all'), got {channels!r}")
    return d, list(side.channel_names)


def _blocks(d: np.ndarray, n: int) -> np.ndarray:
    if n == 1:
        return d
    k, h, w, c = d.shape
    ys, xs = np.arange(0, h, n), np.arange(0, w, n)
    sums = np.add.reduceat(np.add.reduceat(d, ys, axis=1, dtype=np.float64), xs, axis=2, dtype=np.float64)
    cy, cx = np.diff(np.append(ys, h)), np.diff(np.append(xs, w))
    return sums / (cy[:, None] * cx[None, :]).astype(np.float64)[None, :, :, None]


def _tost(ref: np.ndarray, cand: np.ndarray, margin: float, atol: float,
          nan_policy: str = "raise") -> Tuple[np.ndarray, np.ndarray]:
    """Per unit: the TOST p-value and whether both sides are constant."""
    r = ref.astype(np.float64, copy=False)
    lo = _core.t_test(cand, (1.0 - margin) * r, axis=0, mu=-atol, alternative="greater", intervals=False,
                      on_error="nan", nan_policy=nan_policy)
    hi = _core.t_test(cand, (1.0 + margin) * r, axis=0, mu=atol, alternative="less", intervals=False,
                      on_error="nan", nan_policy=nan_policy)
    p = np.maximum(np.asarray(lo.pvalue), np.asarray(hi.pvalue))
    # both sides constant: decided exactly
    # (NaN omitted: constant over the values left; a unit with none left stays untestable)
    with np.errstate(invalid="ignore"):
        cr, cc = np.nanmax(r, axis=0), np.nanmax(cand, axis=0).astype(np.float64)
        const = (np.all((r == cr) | np.isnan(r), axis=0) & np.all((cand == cc) | np.isnan(cand), axis=0)
                 & np.isfinite(cr) & np.isfinite(cc))
    if const.any():
        inside = (cc > (1.0 - margin) * cr - atol) & (cc < (1.0 + margin) * cr + atol)
        p = np.where(const, np.where(inside, 0.0, 1.0), p)
    return p, const


def equivalence(reference: Any, candidate: Any, *, margin: float, atol: float = 0.0, block: int = 32,
                alpha: float = 0.05, seed_axis: Optional[int] = None, channels: str = "all",
                nan_policy: str = "raise") -> ImageEquivalence:
    """Is the candidate the reference up to ``margin`` (relative) + ``atol``,
    shown at level alpha?  Both sides per-seed renders, ``(seeds, H, W[,
    C])`` (``seed_axis`` as in `compare`), at least 2 seeds each.

    ``block``: the verdict's unit, n x n blocks of per-seed means (1: every
    pixel); see the module's text for what the verdict and the per-pixel
    map claim.  ``nan_policy``: NaN values raise `InvalidArgumentError`
    ("raise"), or are left out ("omit"): of their pixel's sample, and a
    seed whose block holds a NaN leaves that block's sample (a unit with
    fewer than 2 values left on a side is untestable, so the verdict is
    not "equivalent"); infinities are refused either way.  Returns
    `ImageEquivalence` (``equivalent``, per-block and per-pixel p-values,
    ``margin_shown``, ``text()``, ``summary()``).
    """
    if not (isinstance(margin, (int, float)) and np.isfinite(margin) and 0.0 <= margin < 1.0):
        raise InvalidArgumentError(f"margin must be in [0, 1), got {margin!r}")
    if not (isinstance(atol, (int, float)) and np.isfinite(atol) and atol >= 0.0):
        raise InvalidArgumentError(f"atol must be finite and >= 0, got {atol!r}")
    if margin == 0.0 and atol == 0.0:
        raise InvalidArgumentError("margin and atol are both 0: no difference could be shown inside them")
    if not (isinstance(alpha, (int, float)) and 0.0 < alpha < 0.5):
        raise InvalidArgumentError(f"alpha must be in (0, 0.5) (TOST's two tests at alpha each), got {alpha!r}")
    if not (isinstance(block, (int, np.integer)) and not isinstance(block, bool) and block >= 1):
        raise InvalidArgumentError(f"block must be an integer >= 1, got {block!r}")
    r, names = _stack(reference, seed_axis, channels, "reference")
    c, _ = _stack(candidate, seed_axis, channels, "candidate")
    if r.shape[1:] != c.shape[1:]:
        raise InvalidArgumentError(f"reference and candidate images differ in shape: {r.shape[1:]} and {c.shape[1:]}")
    if r.shape[0] < 2 or c.shape[0] < 2:
        raise InvalidArgumentError(f"equivalence needs at least 2 seeds per side, got {r.shape[0]} reference and "
                                   f"{c.shape[0]} candidate")
    if nan_policy not in ("raise", "omit"):
        raise InvalidArgumentError(f"nan_policy must be 'raise' or 'omit', got {nan_policy!r}")
    for d, name in ((r, "reference"), (c, "candidate")):
        bad = np.isinf(d) if nan_policy == "omit" else ~np.isfinite(d)
        if bad.any():
            s_, y, x, ch = (int(i) for i in np.argwhere(bad)[0])
            what = "an infinity" if np.isinf(d[s_, y, x, ch]) else "NaN"
            hint = ("" if nan_policy == "omit" or np.isinf(d[s_, y, x, ch])
                    else "; pass nan_policy='omit' (--nan omit) to leave NaN values out")
            raise NonFiniteError(f"{name} holds {what} at seed {s_}, x={x}, y={y} ({names[ch]}){hint}")
    block = int(block)
    pp, _ = _tost(r, c, margin, atol, nan_policy)
    rb, cb = _blocks(r, block), _blocks(c, block)
    bp, _ = _tost(rb, cb, margin, atol, nan_policy)
    with np.errstate(divide="ignore", invalid="ignore"):
        mr, mc = np.nanmean(rb, axis=0), np.nanmean(cb, axis=0)
        rel = (mc - mr) / mr
        # the margin shown, about: (|d| + atol-free t_{1-alpha} se) / mean_ref with the
        # contrast's se at margin 0 (the exact one grows with the margin, slightly)
        nr, nc = np.sum(~np.isnan(rb), axis=0), np.sum(~np.isnan(cb), axis=0)
        with warnings.catch_warnings():  # a unit left with one value: NaN, untestable
            warnings.simplefilter("ignore", RuntimeWarning)
            vr, vc = np.nanvar(rb, axis=0, ddof=1) / nr, np.nanvar(cb, axis=0, ddof=1) / nc
        se = np.sqrt(vr + vc)
        df = (vr + vc) ** 2 / (vr ** 2 / (nr - 1) + vc ** 2 / (nc - 1))
        df = np.where(np.isfinite(df), df, np.maximum(nr + nc - 2, 1).astype(float))
        tq = np.asarray(_core._t_quantiles(alpha, df.ravel(), True)).reshape(df.shape)
        shown = (np.abs(mc - mr) + tq * se) / mr
        shown = np.where(mr > 0, shown, np.nan)
    padj = np.asarray(_core.p_adjust(pp, method="BH"))
    with np.errstate(invalid="ignore"):
        equivalent = bool(np.all(bp <= alpha))
    return ImageEquivalence(
        equivalent=equivalent, margin=float(margin), atol=float(atol), alpha=float(alpha), block=block,
        shape=tuple(r.shape[1:]), channel_names=names, seeds=(int(r.shape[0]), int(c.shape[0])),  # type: ignore[arg-type]
        block_pvalue=bp, block_relative_difference=rel, block_margin_shown=shown, pixel_pvalue=pp,
        pixel_p_adjusted=padj, nan_policy=nan_policy,
    )
