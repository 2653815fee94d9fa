#!/usr/bin/env python3
"""An independent integral of a Mitsuba BSDF's pdf() over the hemisphere, the
reference for test_check_regressions.py's grazing rough plastic.

Composite Gauss-Legendre on the equal-area square (z = 1 - s, phi = 2 pi t),
its panels refined geometrically toward the horizon s = 1 and toward the
azimuth of the mirror direction, where the pdf of a microfacet BSDF at
grazing incidence gathers (its lobe and the half-vector Jacobian's peak
just below the horizon); printed at two refinements, which agree to 1e-8.

    .venv/bin/python examples/mitsuba/pdf_quadrature.py [ALPHA [THETA]]
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_adapters as ma  # noqa: E402


def plastic(alpha):
    return {"type": "roughplastic", "distribution": "beckmann", "alpha": alpha,
            "diffuse_reflectance": {"type": "rgb", "value": [1.0, 1.0, 1.0]}}


def direction(theta, phi=30.0):
    t, p = math.radians(theta), math.radians(phi)
    return np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])


def pdf_integral(pdf, wi, refine=1):
    """The integral of pdf(wi, wo) over the hemisphere."""
    tc = (math.degrees(math.atan2(-wi[1], -wi[0])) % 360) / 360  # the mirror direction's azimuth
    sb = sorted(set(list(np.linspace(0, 1, 21)) + [1 - 2.0 ** -k for k in range(4, 30)]))
    tb = sorted(set(list(np.linspace(0, 1, 65 * refine))
                    + [tc + d * 2.0 ** -k for k in range(3, 28) for d in (-1, 1)]))
    tb = [x for x in tb if 0 <= x <= 1]
    xg, wg = np.polynomial.legendre.leggauss(8 * refine)
    total = 0.0
    for s0, s1 in zip(sb[:-1], sb[1:]):
        s = s0 + (s1 - s0) * (xg + 1) / 2
        for t0, t1 in zip(tb[:-1], tb[1:]):
            t = t0 + (t1 - t0) * (xg + 1) / 2
            S, T = np.meshgrid(s, t, indexing="ij")
            r, ph = np.sqrt(S * (2 - S)), 2 * np.pi * T
            wo = np.stack([r * np.cos(ph), r * np.sin(ph), 1 - S], -1).reshape(-1, 3)
            w = np.outer(wg, wg) * (s1 - s0) * (t1 - t0) / 4
            total += 2 * np.pi * float(np.sum(w * pdf(wi, wo).reshape(S.shape)))
    return total


def main():
    alpha = float(sys.argv[1]) if len(sys.argv) > 1 else 0.1
    theta = float(sys.argv[2]) if len(sys.argv) > 2 else 89.9
    ma.use_variant()
    _, _, pdf = ma.bsdf_callables(plastic(alpha))
    wi = direction(theta)
    for refine in (1, 2):
        print(f"roughplastic beckmann alpha {alpha:g}, wi at {theta:g} degrees ({ma.mi.variant()}), "
              f"refinement {refine}: {pdf_integral(pdf, wi, refine):.8f}")


if __name__ == "__main__":
    main()
