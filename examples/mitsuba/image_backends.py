"""Two backends of one renderer compared pixel by pixel: Mitsuba 3's scalar_rgb
against its llvm_ad_rgb (Dr.Jit's LLVM backend), with mcstat.image.compare.

The scene is Mitsuba's Cornell box (mi.cornell_box(): path tracer, max depth
8) at 64 x 64 pixels, 64 samples per pixel, with a box reconstruction filter
(each sample lands in one pixel, so the pixels' tests are independent and
BH's assumption holds; bench/bench_image_calibration.py measures what wide
filters do).  The reference is scalar_rgb at seeds 0..15, the candidate
llvm_ad_rgb at seeds 1000..1015: fixed and disjoint, so the two sides are
independent samples.  Run:

    .venv/bin/python examples/mitsuba/image_backends.py [--out DIR]

It prints
  1. equal backends, per pixel (luminance, BH at alpha 0.05): the rejections
     (there should be none), the smallest adjusted p-value, and how large a
     difference could hide: per pixel, the difference its Welch test would
     just detect at the level of BH's first discovery (alpha / m), i.e.
     t_crit(1 - alpha / 2m, Welch df) * standard error, as quantiles over
     the pixels, absolute and relative to the reference's mean;
  2. the same for 8 x 8 blocks (mcstat.image.compare(..., block=8): per-seed block means);
  3. a planted change: the candidate (llvm_ad_rgb, seeds 2000..2015) with
     the red wall's diffuse reflectance x 1.02.  Per pixel the change is far
     below the noise (the relative standard error of a pixel's difference
     is ~3.5% at this cost); the blocks find it.  The significance maps are
     written as PNG (mcstat_app.image.write_map) to DIR (default
     bench/out/image_backends).

The whole run (48 renders) takes about 21 s of CPU here (24 s with Dr.Jit's
kernel cache cold).
"""
import argparse
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
# mitsuba_adapters points DRJIT_LIBLLVM_PATH at Debian's libllvm19 before
# drjit is imported (LLVM 15 aborts in code generation on some CPUs)
import mitsuba_adapters  # noqa: E402
import mitsuba as mi  # noqa: E402

import mcstat.image  # noqa: E402

SIZE = 64
SPP = 64
SEEDS = 16
BLOCK = 8
ALPHA = 0.05
REFERENCE = ("scalar_rgb", range(0, SEEDS))
CANDIDATE = ("llvm_ad_rgb", range(1000, 1000 + SEEDS))
PLANTED = ("llvm_ad_rgb", range(2000, 2000 + SEEDS))
PLANTED_WALL = "red"
PLANTED_FACTOR = 1.02
LUMINANCE = np.asarray(mcstat.image.LUMINANCE_WEIGHTS)


def scene_dict(size=SIZE, rfilter=None, wall_factor=1.0, wall=PLANTED_WALL):
    d = mi.cornell_box()
    film = d["sensor"]["film"]
    film["width"] = film["height"] = size
    film["rfilter"] = rfilter or {"type": "box"}
    if wall_factor != 1.0:
        refl = d[wall]["reflectance"]
        refl["value"] = [v * wall_factor for v in refl["value"]]
    return d


def render_stack(variant, seeds, spp=SPP, **scene_kw):
    """Per-seed renders (seeds, H, W, 3), float32, one render per seed."""
    if mi.variant() != variant:
        mi.set_variant(variant)
    scene = mi.load_dict(scene_dict(**scene_kw))
    return np.stack([np.array(mi.render(scene, spp=spp, seed=int(s)), dtype=np.float32) for s in seeds])


def luminance(stack):
    return np.einsum("...c,c->...", np.asarray(stack, dtype=np.float64), LUMINANCE)


def detectable_difference(reference, candidate, block=None, alpha=ALPHA):
    """How large a difference in luminance each test (per pixel, or per
    block of block x block pixels) would detect half the time at the per-test
    level BH applied (alpha / m for its first discovery): the quantiles of
    mcstat.image's detectable_bias at power 0.5 (t_crit times the Welch
    standard error, with the per-seed sample variances as if they were the
    true ones), absolute and relative to the reference's mean."""
    res = mcstat.image.compare(reference, candidate, alpha=alpha, method="BH", seed_axis=0, block=block,
                               detect_power=0.5)
    b = res.bias_statistics()
    q = lambda d: {"median": d["median"], "q90": d["p90"]}  # noqa: E731
    return {"tests": int(res.tested.sum()), "absolute": q(b["absolute"]), "relative": q(b["relative"])}


def report(name, res, dd=None):
    s = res.summary(worst=3)
    padj = res.padjusted[res.tested]
    z = np.abs(res.statistic[res.tested])
    print(f"{name}: {s['tested']} tests, {s['rejections_adjusted']} rejections after {res.method} "
          f"({s['rejected_greater']} greater, {s['rejected_less']} less), {s['rejections_unadjusted']} at "
          f"alpha unadjusted; smallest adjusted p {padj.min():.4g}, largest |t| {z.max():.3g}")
    if dd is not None:
        print(f"    detectable difference at alpha/m (m = {dd['tests']}): median {dd['absolute']['median']:.3g} "
              f"({100 * dd['relative']['median']:.1f}%), 90% {dd['absolute']['q90']:.3g} "
              f"({100 * dd['relative']['q90']:.1f}%) of the reference's mean")


def renders():
    """The three stacks of the comparison (reference, equal candidate,
    planted candidate) and the CPU seconds they took."""
    c0 = time.process_time()
    ref = render_stack(*REFERENCE)
    cand = render_stack(*CANDIDATE)
    planted = render_stack(*PLANTED, wall_factor=PLANTED_FACTOR)
    return ref, cand, planted, time.process_time() - c0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "out", "image_backends"))
    args = ap.parse_args()
    ref, cand, planted, cpu = renders()
    print(f"Cornell box {SIZE} x {SIZE}, {SPP} spp, box filter; reference {REFERENCE[0]} seeds "
          f"{REFERENCE[1].start}..{REFERENCE[1].stop - 1}, candidate {CANDIDATE[0]} seeds "
          f"{CANDIDATE[1].start}..{CANDIDATE[1].stop - 1}; libLLVM: {mitsuba_adapters.loaded_libllvm()}; renders {cpu:.1f} s CPU")
    print(f"planted: {PLANTED[0]} seeds {PLANTED[1].start}..{PLANTED[1].stop - 1}, {PLANTED_WALL} wall's "
          f"reflectance x {PLANTED_FACTOR}\n")
    os.makedirs(args.out, exist_ok=True)
    from mcstat_app.image import write_map

    for label, c in (("equal", cand), ("planted", planted)):
        for method in ("BH", "BY"):
            res = mcstat.image.compare(ref, c, alpha=ALPHA, method=method, seed_axis=0)
            report(f"{label:7s} per pixel, {method}", res,
                   detectable_difference(ref, c) if label == "equal" and method == "BH" else None)
            if method == "BH":
                write_map(res, os.path.join(args.out, f"{label}_pixels.png"))
        for method in ("BH", "BY"):
            res = mcstat.image.compare(ref, c, alpha=ALPHA, method=method, seed_axis=0, block=BLOCK)
            report(f"{label:7s} {BLOCK}x{BLOCK} blocks, {method}", res,
                   detectable_difference(ref, c, BLOCK) if label == "equal" and method == "BH" else None)
            if method == "BH":
                write_map(res, os.path.join(args.out, f"{label}_blocks{BLOCK}.png"))
                if label == "planted":
                    rel = res.mean_candidate[..., 0] / res.mean_reference[..., 0] - 1
                    print("    blocks rejected (row, col: adjusted p, t, candidate/reference - 1):")
                    for i, j in zip(*np.nonzero(res.decision[..., 0])):
                        print(f"      {i}, {j}: {res.padjusted[i, j, 0]:.3g}, {res.statistic[i, j, 0]:.2f}, "
                              f"{100 * rel[i, j]:+.2f}%")
        print()
    print(f"maps: {args.out}")


if __name__ == "__main__":
    main()
