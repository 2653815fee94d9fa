#!/usr/bin/env python3
"""Writes tests/data/ref_irradiance.h: irradiance scenes and their
exact irradiance, solid angle and projected solid angle at 60 digits.

Run from the repository root:
    python3 tools/refgen/make_irradiance_reference.py
Needs mpmath only.

Every scene is given by float64 numbers; mpmath reads them exactly and
computes, at 60 significant digits,
  * the clipped polygon (the part of the triangle above the receiver's
    tangent plane), in the original coordinates (no frame, no translation
    tricks: 60 digits absorb the 1e6 offsets);
  * E by Lambert's formula, E = L/2 |sum Theta_k n.gamma_k|;
  * E again by an independent route: the area integral
    L int h (n.(y-x)) / |y-x|^4 dA over the clipped polygon, written in
    polar coordinates about the foot point of the receiver on the emitter's
    plane, where the radial integral has a closed form, leaving one smooth
    angular integral per edge for mpmath.quad.  The two must agree to 1e-30
    or the script stops;
  * the solid angle of the clipped polygon (Van Oosterom-Strackee on a fan).
The C tests compare libmcest with these numbers; no Python at test time.
"""
import os
import sys

import mpmath as mp

mp.mp.dps = 60
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "..", "tests", "data", "ref_irradiance.h")


def v(*a):
    return [mp.mpf(x) for x in a]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def mul(s, a):
    return [s * a[i] for i in range(3)]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return mp.sqrt(dot(a, a))


def clip(tri, x, n):
    """Polygon of the triangle on the side n.(p - x) >= 0, in order."""
    out = []
    for k in range(3):
        a, b = tri[k], tri[(k + 1) % 3]
        za, zb = dot(n, sub(a, x)), dot(n, sub(b, x))
        if za >= 0:
            out.append(a)
        if (za >= 0) != (zb >= 0) and za != zb:
            t = za / (za - zb)
            if 0 < t < 1:
                out.append(add(a, mul(t, sub(b, a))))
    return out if len(out) >= 3 else []


def lambert(poly, x, n, L):
    s = mp.mpf(0)
    m = len(poly)
    for k in range(m):
        a, b = sub(poly[k], x), sub(poly[(k + 1) % m], x)
        c = cross(a, b)
        lc = norm(c)
        if lc == 0:
            continue
        th = mp.atan2(lc, dot(a, b))
        s += th * dot(n, c) / lc
    return L / 2 * abs(s)


def area_integral(poly, x, n, L):
    """L * int over poly of h (n.(y-x)) / |y-x|^4 dA, polar about the foot."""
    m = len(poly)
    if m == 0:
        return mp.mpf(0)
    nt = cross(sub(poly[1], poly[0]), sub(poly[2], poly[0]))
    nt = mul(1 / norm(nt), nt)
    hs = dot(nt, sub(poly[0], x))  # signed distance of the plane
    h = abs(hs)
    if h == 0:
        return mp.mpf(0)
    f = add(x, mul(hs, nt))  # foot point
    zf = dot(n, sub(f, x))
    # orthonormal basis of the plane
    a1 = sub(poly[0], f) if norm(sub(poly[0], f)) > 0 else sub(poly[1], f)
    a1 = mul(1 / norm(a1), a1)
    a2 = cross(nt, a1)
    n1, n2 = dot(n, a1), dot(n, a2)

    def I0(R):
        return R * R / (2 * h * h * (R * R + h * h))

    def I1(R):
        return mp.atan(R / h) / (2 * h) - R / (2 * (R * R + h * h))

    total = mp.mpf(0)
    for k in range(m):
        p, q = sub(poly[k], f), sub(poly[(k + 1) % m], f)
        px, py = dot(p, a1), dot(p, a2)
        qx, qy = dot(q, a1), dot(q, a2)
        cr = px * qy - py * qx
        if cr == 0:
            continue
        sgn = 1 if cr > 0 else -1
        phi0 = mp.atan2(py, px)
        dphi = mp.atan2(cr, px * qx + py * qy)  # signed angle p -> q, |.| < pi
        # line through p and q: distance from the origin and its direction
        ex, ey = qx - px, qy - py
        le = mp.sqrt(ex * ex + ey * ey)
        dperp = abs(cr) / le
        # unit normal of the line pointing away from the origin
        nx, ny = ey / le, -ex / le
        if nx * px + ny * py < 0:
            nx, ny = -nx, -ny
        phip = mp.atan2(ny, nx)

        def g(phi):
            R = dperp / mp.cos(phi - phip)
            u = n1 * mp.cos(phi) + n2 * mp.sin(phi)
            return h * (zf * I0(R) + u * I1(R))

        lo, hi = (phi0, phi0 + dphi) if dphi > 0 else (phi0 + dphi, phi0)
        total += sgn * mp.quad(g, [lo, (lo + hi) / 2, hi])
    return L * abs(total)


def solid_angle(poly, x):
    m = len(poly)
    om = mp.mpf(0)
    for j in range(1, m - 1):
        a, b, c = sub(poly[0], x), sub(poly[j], x), sub(poly[j + 1], x)
        la, lb, lc = norm(a), norm(b), norm(c)
        num = abs(dot(a, cross(b, c)))
        den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la
        om += 2 * mp.atan2(num, den)
    return om


def scenes():
    S = []
    paper = ([-0.6, -0.4, 1.0, 0.9, -0.3, 1.3, 0.1, 0.9, 0.8], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0)
    S.append(("paper", *paper))
    S.append(("tilted", paper[0], [0.0, 0.0, 0.0], [0.3, -0.2, 0.9], 2.5))
    S.append(("straddle", [-1.0, 0.2, -0.5, 1.2, -0.3, 0.8, 0.1, 1.1, 0.6],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    S.append(("straddle2", [-1.0, 0.2, 0.5, 1.2, -0.3, -0.8, 0.1, 1.1, -0.6],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    # tiny: edges ~1.4e-5 at distance ~1: solid angle ~1e-10
    c = [0.3, 0.2, 1.0]
    S.append(("tiny", [c[0], c[1], c[2], c[0] + 1.5e-5, c[1], c[2] + 2e-6,
                       c[0] + 3e-6, c[1] + 1.4e-5, c[2] - 1e-6],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    S.append(("tiny12", [c[0], c[1], c[2], c[0] + 1.5e-6, c[1], c[2] + 2e-7,
                         c[0] + 3e-7, c[1] + 1.4e-6, c[2] - 1e-7],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    # sliver: a needle of length ~1.8 and width 1e-7
    S.append(("sliver", [-0.8, 0.1, 0.7, 0.9, 0.15, 1.1, 0.05, 0.1251, 0.9 + 1e-7],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    # grazing: the emitter just above the horizon (elevation ~1e-3)
    S.append(("grazing", [1.0, -0.2, 1e-3, 1.1, 0.3, 2e-3, 0.9, 0.1, 3e-3],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    # edge-on: the receiver 1e-8 from the emitter's plane
    S.append(("edge_on", [0.3 + 1e-8, 0.3, 0.5, 0.8 + 1e-8, 0.8, 1.0, 0.2 + 1e-8, 0.2, 1.2],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    # huge and close: a 3e3 triangle 1e-2 above the receiver
    S.append(("huge_close", [-1e3, -1e3, 0.01, 2e3, -1e3, 0.012, -1e3, 2e3, 0.011],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    # large and close: A is still testable with 1e5 samples
    S.append(("large_close", [-3.0, -3.0, 0.5, 6.0, -3.0, 0.7, -3.0, 6.0, 0.6],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    # everything translated by (1e6, -2e6, 3e6)
    T = [1e6, -2e6, 3e6]

    def tr(t):
        return [t[i] + T[i % 3] for i in range(9)]

    S.append(("far_paper", tr(paper[0]), T[:], [0.0, 0.0, 1.0], 1.0))
    S.append(("far_tiny", tr([0.3, 0.2, 1.0, 0.3 + 1.5e-5, 0.2, 1.0 + 2e-6,
                              0.3 + 3e-6, 0.2 + 1.4e-5, 1.0 - 1e-6]),
              T[:], [0.0, 0.0, 1.0], 1.0))
    S.append(("far_straddle", tr([-1.0, 0.2, -0.5, 1.2, -0.3, 0.8, 0.1, 1.1, 0.6]),
              T[:], [0.1, 0.05, 1.0], 1.0))
    S.append(("below", [-1.0, 0.2, -0.5, 1.2, -0.3, -0.8, 0.1, 1.1, -0.6],
              [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0))
    return S


def hexf(x):
    return float(x).hex()


def main():
    rows = []
    for name, tri, x, n, L in scenes():
        P = [v(*tri[3 * k:3 * k + 3]) for k in range(3)]
        X = v(*x)
        N = v(*n)
        N = mul(1 / norm(N), N)
        poly = clip(P, X, N)
        E = lambert(poly, X, N, mp.mpf(L)) if poly else mp.mpf(0)
        E2 = area_integral(poly, X, N, mp.mpf(L)) if poly else mp.mpf(0)
        if E != 0 and abs(E - E2) > mp.mpf(10) ** -30 * abs(E):
            sys.exit(f"{name}: Lambert {E} and area integral {E2} disagree")
        om = solid_angle(poly, X) if poly else mp.mpf(0)
        psa = E / L
        print(f"{name:13s} E = {mp.nstr(E, 20):>26s}  |E - area|/E = "
              f"{mp.nstr(abs(E - E2) / E if E else 0, 3):>8s}  Omega = {mp.nstr(om, 12)}")
        rows.append((name, tri, x, n, L, E, om, psa))

    with open(OUT, "w") as f:
        f.write("/* Generated by tools/refgen/make_irradiance_reference.py;"
                " do not edit. */\n")
        f.write("#ifndef MCEST_REF_IRRADIANCE_H\n#define MCEST_REF_IRRADIANCE_H\n\n")
        f.write("typedef struct {\n    const char *name;\n    double tri[9], point[3], normal[3], "
                "radiance;\n    double E, omega, proj; /* 60-digit values, rounded */\n"
                "    const char *E_digits;\n} ref_scene;\n\n")
        f.write(f"#define N_REF_SCENES {len(rows)}\n")
        f.write("static const ref_scene ref_scenes[N_REF_SCENES] = {\n")
        for name, tri, x, n, L, E, om, psa in rows:
            f.write(f"    {{\"{name}\",\n")
            f.write("     {" + ", ".join(hexf(t) for t in tri) + "},\n")
            f.write("     {" + ", ".join(hexf(t) for t in x) + "}, {" +
                    ", ".join(hexf(t) for t in n) + f"}}, {hexf(L)},\n")
            f.write(f"     {hexf(E)}, {hexf(om)}, {hexf(psa)},\n")
            f.write(f"     \"{mp.nstr(E, 30)}\"}},\n")
        f.write("};\n\n#endif\n")
    print("wrote", os.path.normpath(OUT))


if __name__ == "__main__":
    main()
