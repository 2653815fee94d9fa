"""BY and e-BH on null renders whose pixels a wide reconstruction filter has
made dependent: fixed data, so a fixed outcome (no Mitsuba needed).

data/filtered_null_renders.npz holds, for a Gaussian filter (stddev 1 pixel)
and a Lanczos filter (3 lobes: negative lobes, so correlations of both
signs, outside BH's PRDS condition), one of the 800 null comparisons of
bench/bench_image_calibration.py where BH made a false discovery and BY and
e-BH did not, with margins (BH-adjusted p <= 0.03; BY's and e-BH's >= 0.2),
so that no last-bit difference of a p-value can change a decision: the first
such comparison of each filter.  Each is 8 + 8 renders (reference first) of Mitsuba's
Cornell box at 32 x 32 pixels, 4 spp, llvm_ad_rgb, luminance as float32;
reference and candidate from the same renderer at disjoint seeds (the seeds
are stored next to them).  Written by `bench_image_calibration.py
--export-gate`.

On these data BH discovers (falsely) and the methods valid under any
dependence must not discover anything: a BY or e-BH as lenient as BH fails.
The dependence they are meant to survive must be in the data.
"""
import os

import numpy as np
import pytest

import mcstat.image

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "filtered_null_renders.npz")
K = 8
ALPHA = 0.05


@pytest.fixture(scope="module")
def data():
    with np.load(DATA) as z:
        return {name: z[name] for name in ("gaussian", "lanczos")}


def noise_correlation(stacks, lag):
    """Mean correlation of the noise (deviation from each side's mean,
    standardised by the pixel's pooled variance) of horizontally and
    vertically neighbouring pixels at `lag`."""
    s = stacks.reshape(-1, K, *stacks.shape[-2:]).astype(np.float64)
    r = s - s.mean(axis=1, keepdims=True)
    dof = s.shape[0] * (K - 1)
    z = r / np.sqrt((r * r).sum(axis=(0, 1)) / dof)
    h = (z[..., :, lag:] * z[..., :, :-lag]).sum(axis=(0, 1)) / dof
    v = (z[..., lag:, :] * z[..., :-lag, :]).sum(axis=(0, 1)) / dof
    return float((h.mean() + v.mean()) / 2)


def test_the_filters_correlate_the_pixels(data):
    for name, st in data.items():
        assert st.ndim == 4 and st.shape[1:] == (2 * K, 32, 32) and st.dtype == np.float32, name
        assert np.all(st.reshape(-1, 32, 32).std(axis=0) > 0), name  # every pixel tested
    # Gaussian: strongly positive at lag 1; Lanczos: negative at lag 2
    assert noise_correlation(data["gaussian"], 1) > 0.6
    assert noise_correlation(data["lanczos"], 2) < -0.03


@pytest.mark.parametrize("name", ["gaussian", "lanczos"])
@pytest.mark.parametrize("method", ["BY", "e-BH"])
def test_dependence_valid_methods_discover_nothing(data, name, method):
    for i, st in enumerate(data[name]):
        # the plain Welch test per pixel (the data's premise is BH's false
        # discovery on its p-values; the render guards' df leave none)
        res = mcstat.image.compare(st[:K], st[K:], alpha=ALPHA, method=method, seed_axis=0, render_guards=False)
        bh = mcstat.image.compare(st[:K], st[K:], alpha=ALPHA, method="BH", seed_axis=0, render_guards=False)
        print(f"{name} #{i} {method}: smallest adjusted p {res.padjusted.min():.3g} "
              f"(BH {bh.padjusted.min():.3g}, raw {res.pvalue.min():.3g})")
        assert int(res.tested.sum()) == 32 * 32
        assert int(np.count_nonzero(bh.decision)) >= 1  # the data's premise: BH's false discovery
        assert int(np.count_nonzero(res.decision)) == 0
        # never more lenient than BH on the same p-values
        assert np.all(res.padjusted >= bh.padjusted)
