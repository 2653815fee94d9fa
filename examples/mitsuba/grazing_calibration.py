#!/usr/bin/env python3
"""False rejections of Mitsuba's correct BSDFs by mcstat.check_bsdf at the
suite's wi and at grazing incidence (wi.z = 0.058 and 0.006): rejections and
the routes that rejected, per configuration, over seeds 0..S-1 at alpha =
0.01 (RESULTS.md, "Notes for mcstat's design").

    .venv/bin/python examples/mitsuba/grazing_calibration.py [SEEDS]

dielectric_ggx_all is left out (Mitsuba's weight != eval/pdf there), and
energy is off for the dielectrics (radiance scaling at refraction).
"""
import collections
import os
import sys

import numpy as np

import mcstat

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_adapters as A  # noqa: E402

A.use_variant()
import mitsuba as mi  # noqa: E402


def main():
    seeds = int(sys.argv[1]) if len(sys.argv) > 1 else 20
    print(f"Mitsuba {mi.__version__}, {mi.variant()}, seeds 0..{seeds - 1}, alpha = 0.01")
    for name, (d, wi0, dom, _) in A.BSDF_CONFIGS.items():
        if name == "dielectric_ggx_all":
            continue
        s, e, p = A.bsdf_callables(mi.load_dict(d))
        for wz in (None, 0.058, 0.006):
            wi = A.normalized(wi0) if wz is None else A.normalized((np.sqrt(1 - wz * wz), 0, wz))
            c = collections.Counter()
            for seed in range(seeds):
                r = mcstat.check_bsdf(s, e, p, wi, domain=dom, seed=seed, energy=not name.startswith("dielectric"))
                c["rejected"] += r.reject
                for x in r.routes:
                    if x.reject:
                        c[x.name] += 1
            print(f"{name:26s} wi.z {'suite' if wz is None else wz:>6} {dict(c)}", flush=True)


if __name__ == "__main__":
    main()
