"""Backend equivalence on Mitsuba 3: is llvm_ad_rgb's image scalar_rgb's up to
a margin?  mcstat.image.equivalence on the renders of image_backends.py
(Cornell box, 64 x 64, 16 seeds a side, luminance) at 256 spp: at
image_backends' 64 spp the data show no margin below about 1.6% (16 x 16
blocks), so 1% could not be shown whatever the backends do:

  1. equal backends (scalar_rgb seeds 0..15 vs llvm_ad_rgb seeds 1000..1015)
     at margin 1%: the verdict, the blocks shown, the margin the data shows;
  2. the planted change (the red wall's reflectance x 1.02, llvm seeds
     2000..2015) at margin 1%: must not be shown equivalent;
  3. the same at 8 x 8 and 16 x 16 blocks, and at margins 0.5% / 2%.

    .venv/bin/python examples/mitsuba/backend_equivalence.py

Its calibration (false "equivalent" at a true difference of exactly the
margin at most alpha) is tested on synthetic data in
tests/python/test_testing.py; results in RESULTS_image_backends.md.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import image_backends as ib  # noqa: E402

import time  # noqa: E402

import mcstat.image  # noqa: E402

ALPHA = 0.05
SPP = 256


def main():
    c0 = time.process_time()
    ref = ib.render_stack(*ib.REFERENCE, spp=SPP)
    cand = ib.render_stack(*ib.CANDIDATE, spp=SPP)
    planted = ib.render_stack(*ib.PLANTED, spp=SPP, wall_factor=ib.PLANTED_FACTOR)
    cpu = time.process_time() - c0
    print(f"Cornell box {ib.SIZE} x {ib.SIZE}, {SPP} spp; reference {ib.REFERENCE[0]}, candidate "
          f"{ib.CANDIDATE[0]}, {ib.SEEDS} seeds a side; renders {cpu:.1f} s CPU; alpha {ALPHA}\n")
    print("| candidate | margin | block | verdict | blocks shown | margin shown | pixels shown (BH) |")
    print("|---|---|---|---|---|---|---|")
    for label, c in (("equal (llvm)", cand), ("red wall x 1.02", planted)):
        for margin in (0.005, 0.01, 0.02):
            for block in (8, 16):
                e = mcstat.image.equivalence(ref, c, margin=margin, block=block, alpha=ALPHA, seed_axis=0,
                                             channels="luminance")
                print(f"| {label} | {margin:g} | {block} | {'equivalent' if e.equivalent else 'not shown'} | "
                      f"{e.blocks_shown}/{e.block_pvalue.size} | {e.margin_shown:.3g} | "
                      f"{int(e.pixels_shown_equivalent.sum())}/{e.pixel_pvalue.size} |", flush=True)
    e = mcstat.image.equivalence(ref, planted, margin=0.01, block=16, alpha=ALPHA, seed_axis=0,
                                 channels="luminance")
    print("\nThe planted change at margin 1%, 16 x 16 blocks:\n")
    print(e.text())


if __name__ == "__main__":
    main()
