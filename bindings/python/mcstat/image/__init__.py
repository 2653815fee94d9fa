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

from typing import Any

# The modules: _inputs (sides, seed axes, channels), _compare (compare),
# _report (ImageComparison), _bias (what a pass means), _equivalence.  Every
# name mcstat.image had before they were split stays importable from it,
# the private ones too (the tests reach _core, _harmonic, _t_upper_quantile
# and _infer_seed_axis here).
from .. import _core  # noqa: F401
from ._bias import (  # noqa: F401
    _CHUNK,
    _EBH_KAPPA,
    _bias_stats,
    _canonical_method,
    _harmonic,
    _t_upper_quantile,
    _welch_se_df,
    detectable_bias,
    per_test_level,
)
from ._compare import (  # noqa: F401
    Owned,
    _block_means,
    _fmt_shape,
    _luminance_of_means,
    _reference_luminance,
    _scratch_for_adjust,
    _variance_lost,
    compare,
)
from ._equivalence import ImageEquivalence, equivalence
from ._inputs import (  # noqa: F401
    LUMINANCE_WEIGHTS,
    ImageInputError,
    Samples,
    Side,
    Summary,
    _ambiguous,
    _as_side,
    _fmt_tuple,
    _infer_seed_axis,
    _known_shape,
    _luminance_samples,
    _seeds_first_is_clear,
    _select,
    _WeightedSamples,
    channel_names,
    save_moments,
    seed_axis_of,
    summary_of_moments,
)
from ._report import _ASSUMES, COLOR_KEY, VERDICTS, ImageComparison, _g  # noqa: F401

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


# The file readers, the map writer and the command are the application's
# (mcstat_app.image; mcstat 0.2.0 removed their aliases here): say where.
_MOVED = ("load_side", "read_image", "map_rgb", "write_map", "run")


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}: it is mcstat_app.image.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
