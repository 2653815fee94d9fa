"""Independent computations behind bench/RESULTS_null_zoo.md's diagnoses:
for each class of model the null zoo found outside its bounds, numbers that
do not come from mcstat (float64 closed forms, dense quadrature of
Mitsuba's own pdf(), Mitsuba's success share from many samples, Mitsuba's
pdf() under one-ulp perturbations of its float32 directions).

    .venv/bin/python bench/null_zoo_evidence.py CLASS [CLASS ...]

CLASS: float32, beckmann, spike, cubature, energy, sggx, isotropic, excluded,
excluded-quad (or all).
Each prints its own Markdown block; scalar_rgb, one thread.
"""
import math
import os
import sys
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import null_zoo as z  # noqa: E402  (sets scalar_rgb, imports the adapters)

mi, ma, mcstat = z.mi, z.ma, z.mcstat
F32 = np.float32


def mirror(w):
    return np.array([-w[0], -w[1], w[2]])


# ---- dense quadrature of a density over the sphere, in float64 ------------------------

def theta_nodes(pole=True, horizon=True, below=False):
    """theta nodes on [0, pi/2] (or [0, pi]), geometric toward the pole and the horizon."""
    parts = [np.array([0.0])]
    if pole:
        parts.append(np.geomspace(1e-7, 0.02, 500))
    parts.append(np.linspace(0.02, math.pi / 2 - 0.02, 1200))
    if horizon:
        parts.append(math.pi / 2 - np.geomspace(1e-7, 0.02, 500))
    parts.append(np.array([math.pi / 2]))
    if below:
        parts.append(math.pi / 2 + np.geomspace(1e-7, 0.02, 500))
        parts.append(np.linspace(math.pi / 2 + 0.02, math.pi - 0.02, 1200))
        parts.append(math.pi - np.geomspace(1e-7, 0.02, 500))
        parts.append(np.array([math.pi]))
    return np.unique(np.concatenate(parts))


def quad_sphere(f, below=False, n_phi=720):
    """Integral of f(directions (k, 3)) over the hemisphere (or sphere) by the
    trapezoid rule in (theta, phi) on theta_nodes x n_phi (periodic in phi)."""
    th = theta_nodes(below=below)
    ph = (np.arange(n_phi) + 0.5) * 2 * math.pi / n_phi
    T, P = np.meshgrid(th, ph, indexing="ij")
    d = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1).reshape(-1, 3)
    v = np.asarray(f(d), dtype=np.float64).reshape(T.shape)
    ring = v.mean(axis=1) * 2 * math.pi * np.sin(th)
    return float(np.trapezoid(ring, th))


def success_share(sample, wi, n, seed=12345):
    u = np.random.default_rng(seed).random((n, 3))
    _, _, pdf = sample(wi, u)
    k = int(np.sum(pdf > 0))
    p = k / n
    return p, math.sqrt(max(p * (1 - p), 1.0 / n) / n), k


# ---- microfacet closed forms, float64 -------------------------------------------------

def D(m, au, av, dist):
    x2, y2, z2 = m[:, 0] ** 2 / au ** 2, m[:, 1] ** 2 / av ** 2, m[:, 2] ** 2
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if dist == "ggx":
            r = 1.0 / (math.pi * au * av * (x2 + y2 + z2) ** 2)
        else:
            r = np.exp(-(x2 + y2) / z2) / (math.pi * au * av * z2 * z2)
    return np.where(m[:, 2] > 0, np.nan_to_num(r), 0.0)


def G1(v, m, au, av, dist, rational=True):
    """Smith's G1; Beckmann either exact (erf) or Walter et al.'s rational
    approximation (what Mitsuba's MicrofacetDistribution::smith_g1 uses)."""
    from scipy.special import erf
    v = np.atleast_2d(v)
    xy_alpha2 = (au * v[:, 0]) ** 2 + (av * v[:, 1]) ** 2
    tan2 = xy_alpha2 / v[:, 2] ** 2
    if dist == "ggx":
        g = 2.0 / (1.0 + np.sqrt(1.0 + tan2))
    else:
        a = 1.0 / np.sqrt(tan2) if np.all(tan2 > 0) else np.where(tan2 > 0, 1.0 / np.sqrt(np.maximum(tan2, 1e-300)),
                                                                   np.inf)
        if rational:
            g = np.where(a >= 1.6, 1.0, (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a))
        else:
            g = 2.0 / (1.0 + erf(a) + np.exp(-a * a) / (a * math.sqrt(math.pi)))
    ok = (np.sum(v * m, axis=1) * v[:, 2]) > 0
    return np.where(ok, g, 0.0)


def visible_pdf_mass(wi, au, av, dist, rational, reflect_above=True):
    """Integral over microfacet normals m of D_wi(m) = G1(wi, m) max(0, wi.m) D(m) / wi.z,
    restricted (reflect_above) to the m whose mirror reflection of wi lies above
    the surface: the mass of the reflection pdf D_wi(m) / (4 wo.m)."""
    def f(m):
        g = G1(np.broadcast_to(wi, m.shape), m, au, av, dist, rational)
        dm = np.maximum(0.0, m @ wi)
        v = g * dm * D(m, au, av, dist) / wi[2]
        if reflect_above:
            wo = 2 * (m @ wi)[:, None] * m - wi
            v = np.where(wo[:, 2] > 0, v, 0.0)
        return v
    return quad_sphere(f)


# ---- classes ------------------------------------------------------------------------

def ulp_spread(fn, wi, wo, k=8, rng=None):
    """Largest relative change of fn(wi, wo') over k directions wo' that differ
    from the float32 wo by one ulp in each component (renormalised in float32)."""
    rng = rng or np.random.default_rng(0)
    wo32 = np.asarray(wo, dtype=F32)
    base = fn(wi, wo32[None, :].astype(np.float64))[0]
    out = []
    for _ in range(k):
        s = rng.choice([-1, 0, 1], size=3)
        w = wo32.copy()
        for i in range(3):
            if s[i]:
                w[i] = np.nextafter(w[i], F32(np.inf) if s[i] > 0 else F32(-np.inf))
        w = (w / np.linalg.norm(w.astype(np.float64))).astype(F32)
        out.append(fn(wi, w[None, :].astype(np.float64))[0])
    return base, float(np.max(np.abs(np.array(out) / base - 1.0))) if base > 0 else float("nan")


def ggx_pdf64(wi, wo, au, av, dist="ggx", visible=True):
    """Mitsuba's roughconductor pdf (visible normals, or D(m) cos theta_m), in float64 at the given wo."""
    m = wi + wo
    m = m / np.linalg.norm(m, axis=1)[:, None]
    if not visible:
        return np.where(wo[:, 2] > 0, D(m, au, av, dist) * m[:, 2] / (4 * np.abs(np.sum(wo * m, axis=1))), 0.0)
    g = G1(np.broadcast_to(wi, m.shape), m, au, av, dist)
    return np.where(wo[:, 2] > 0, D(m, au, av, dist) * g / (4 * wi[2]), 0.0)


def cls_float32(n=20000):
    print("\n### float32 at grazing incidence and in sharp peaks (pdf_value, weight)\n")
    print("Samples of Mitsuba's sample() (scalar_rgb, float32), at the points where the sample's pdf "
          "and pdf() differ by more than the kit's rtol 1e-3: the float64 closed form at the float32 wo, "
          "and how much Mitsuba's own pdf() moves when wo moves by one float32 ulp.\n")
    print("| model | points beyond 1e-3 | largest \\|bs.pdf/pdf() - 1\\| | \\|pdf()/float64 - 1\\| (median / largest) "
          "| \\|bs.pdf/float64 - 1\\| | median one-ulp spread of pdf() at those points |")
    print("|---|---|---|---|---|---|")
    cases = [("roughconductor ggx alpha 0.01 theta 89.9",
              {"type": "roughconductor", "alpha": 0.01, "distribution": "ggx"}, 89.9, 0.01, "ggx"),
             ("roughconductor ggx alpha 0.001 theta 89.9",
              {"type": "roughconductor", "alpha": 0.001, "distribution": "ggx"}, 89.9, 0.001,
              "ggx"),
             ("roughconductor ggx alpha 0.3 sample_visible false theta 89.9",
              {"type": "roughconductor", "alpha": 0.3, "sample_visible": False, "distribution": "ggx"}, 89.9, 0.3,
              "ggx-all"),
             ("roughconductor beckmann alpha 0.001 theta 89.9",
              {"type": "roughconductor", "alpha": 0.001, "distribution": "beckmann"}, 89.9, 0.001, "beckmann"),
             ("roughdielectric ggx alpha 0.01 theta 89.9",
              {"type": "roughdielectric", "alpha": 0.01, "distribution": "ggx"},
              89.9, None, None),
             ("roughdielectric beckmann alpha 0.01 eta 1.0001 theta 45",
              {"type": "roughdielectric", "alpha": 0.01, "int_ior": 1.0001, "ext_ior": 1.0}, 45, None, None),
             ("roughdielectric beckmann alpha 0.3 eta 1.0001 theta 45",
              {"type": "roughdielectric", "alpha": 0.3, "int_ior": 1.0001, "ext_ior": 1.0}, 45, None, None)]
    for name, spec, th, a, dist in cases:
        wi = z.direction(th)
        s, e, p = ma.bsdf_callables(spec)
        u = np.random.default_rng(7).random((n, 3))
        wo, w, bpdf = s(wi, u)
        ok = bpdf > 0
        wo, bpdf = wo[ok], bpdf[ok]
        pp = p(wi, wo)
        rel = np.abs(bpdf / np.where(pp > 0, pp, np.nan) - 1)
        bad = np.nan_to_num(rel, nan=1.0) > 1e-3
        idx = np.flatnonzero(bad)
        if a is not None:
            p64 = ggx_pdf64(wi, wo[idx], a, a, dist.split("-")[0], visible=not dist.endswith("-all"))
            e1, e2 = np.abs(pp[idx] / p64 - 1), np.abs(bpdf[idx] / p64 - 1)
            r1s = f"{np.median(e1):.2g} / {np.max(e1):.2g}" if len(idx) else "-"
            r2s = f"{np.median(e2):.2g} / {np.max(e2):.2g}" if len(idx) else "-"
        else:
            r1s = r2s = "(no closed form here)"
        spreads = [ulp_spread(p, wi, wo[i])[1] for i in idx[:40]]
        print(f"| {name} | {len(idx)} of {len(wo)} ({len(idx) / len(wo):.2%}) | {np.nanmax(rel):.2g} | {r1s} | {r2s} "
              f"| {np.median(spreads) if spreads else float('nan'):.2g} |", flush=True)
    # a peaked phase function: hg g = 0.99
    import phase_medium as pm
    ph = pm.MitsubaPhase({"type": "hg", "g": 0.99})
    wi = z.direction(40.0, 20.0)
    u = np.random.default_rng(7).random((n, 3))
    wo, w, bpdf = ph.sample(wi, u)
    pp = ph.pdf(wi, wo)
    rel = np.abs(bpdf / pp - 1)
    idx = np.flatnonzero(rel > 1e-3)
    g = 0.99
    cos = -(wo @ wi)  # Mitsuba's hg: wi points back along the ray (cosine to the forward direction)
    p64 = (1 - g * g) / (4 * math.pi * (1 + g * g + 2 * g * (wo @ wi)) ** 1.5)
    e1, e2 = np.abs(pp[idx] / p64[idx] - 1), np.abs(bpdf[idx] / p64[idx] - 1)
    spreads = [ulp_spread(ph.pdf, wi, wo[i])[1] for i in idx[:40]]
    print(f"| phase hg g 0.99 | {len(idx)} of {len(wo)} ({len(idx) / len(wo):.2%}) | {np.max(rel):.2g} "
          f"| {np.median(e1):.2g} / {np.max(e1):.2g} | {np.median(e2):.2g} / {np.max(e2):.2g} "
          f"| {np.median(spreads) if spreads else float('nan'):.2g} |")
    print(f"\n(hg: cos theta between the scattered and the forward direction at the worst point: "
          f"{cos[idx[np.argmax(rel[idx])]] if len(idx) else float('nan'):.9f})")


def cls_beckmann(n=400000):
    print("\n### Beckmann at grazing incidence (mass)\n")
    print("The mass of Mitsuba's reflection pdf() D(m) G1(wi, m) / (4 cos theta_i) over the hemisphere: "
          "from dense float64 quadrature of Mitsuba's own pdf(); from the float64 closed form with the "
          "rational G1 Mitsuba's smith_g1 uses and with the exact G1 (erf); and the share of Mitsuba's "
          f"samples that succeed ({n} samples).\n")
    print("| model | quadrature of Mitsuba's pdf() | closed form, rational G1 | closed form, exact G1 "
          "| Mitsuba's success share (se) |")
    print("|---|---|---|---|---|")
    for a, th in ((1.0, 89.9), (1.0, 75.0), (0.1, 89.9), (0.5, 89.9)):
        wi = z.direction(th)
        spec = {"type": "roughconductor", "distribution": "beckmann", "alpha": a}
        s, e, p = ma.bsdf_callables(spec)
        # (a lobe narrower than this grid resolves at grazing incidence: no quadrature)
        q = quad_sphere(lambda d: p(wi, d), n_phi=360) if a >= 0.5 else float("nan")
        cr = visible_pdf_mass(wi, a, a, "beckmann", True)
        ce = visible_pdf_mass(wi, a, a, "beckmann", False)
        sh, se, _ = success_share(s, wi, n)
        print(f"| roughconductor beckmann alpha {a:g} theta {th:g} | {q:.5f} | {cr:.5f} | {ce:.5f} "
              f"| {sh:.5f} ({se:.1g}) |", flush=True)


def cls_spike(n=400000):
    print("\n### A sharp specular peak at the pole (roughplastic alpha 1e-3 at normal incidence)\n")
    print("Dense float64 quadrature of Mitsuba's pdf() (theta nodes geometric from 1e-7 rad at the pole), "
          "the share of Mitsuba's samples that succeed, and the mass mcstat's check reports.\n")
    print("| model | quadrature of Mitsuba's pdf() | success share | mcstat's mass (seed 0) |")
    print("|---|---|---|---|")
    for dist, a, dif, th in (("beckmann", 1e-3, 1.0, 0.0), ("beckmann", 1e-3, 0.0, 0.0)):
        wi = z.direction(th)
        spec = {"type": "roughplastic", "distribution": dist, "alpha": a, "diffuse_reflectance": z.rgb(dif)}
        s, e, p = ma.bsdf_callables(spec)
        q = quad_sphere(lambda d: p(wi, d), n_phi=360)
        sh, se, _ = success_share(s, wi, n)
        r = mcstat.check_bsdf(s, e, p, wi, n=20000, seed=0, alpha=0.01, domain="hemisphere")
        print(f"| roughplastic {dist} alpha {a:g} diffuse {dif:g} theta {th:g} | {q:.5f} | {sh:.5f} ({se:.1g}) "
              f"| {r.mass:.5f} (cubature error {r.mass_error:.2g}) |", flush=True)


def cls_energy(n=400000):
    print("\n### Albedo above 1 (energy)\n")
    print("The albedo from dense float64 quadrature of Mitsuba's eval() plus the discrete lobe's value "
          f"(Fresnel), and Mitsuba's mean sample weight ({n} samples).\n")
    print("| model | quadrature of eval() + discrete lobe | mean weight (se) |")
    print("|---|---|---|")
    for spec, th, lob, name in (
            ({"type": "plastic", "int_ior": 1.5, "ext_ior": 1.0, "nonlinear": False,
              "diffuse_reflectance": z.rgb(1.0)}, 89.9, z.lobes_plastic(1.5, 1.0), "plastic diffuse 1"),
            ({"type": "plastic", "int_ior": 1.5, "ext_ior": 1.0, "nonlinear": False,
              "diffuse_reflectance": z.rgb(1.0)}, 0.0, z.lobes_plastic(1.5, 1.0), "plastic diffuse 1"),
            ({"type": "roughplastic", "alpha": 0.1, "diffuse_reflectance": z.rgb(1.0)}, 89.9, None,
             "roughplastic beckmann alpha 0.1 diffuse 1"),
            ({"type": "roughplastic", "alpha": 1.0, "diffuse_reflectance": z.rgb(1.0)}, 89.9, None,
             "roughplastic beckmann alpha 1 diffuse 1")):
        wi = z.direction(th)
        bsdf = mi.load_dict(spec)
        ctx = mi.BSDFContext()
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*map(float, wi))

        def ev(d):
            return np.array([bsdf.eval(ctx, si, mi.Vector3f(*map(float, x)))[0] for x in d])
        q = quad_sphere(ev, n_phi=360)
        if lob is not None:
            q += float(np.sum(lob(wi)[2]))
        u = np.random.default_rng(3).random((n, 3))
        if lob is not None:
            m = z.dl.MitsubaDelta(spec, lob)
            _, w, _ = m.sample(wi, u)
        else:
            w = ma.bsdf_callables(spec)[0](wi, u)[1]
        print(f"| {name} theta {th:g} | {q:.5f} | {w.mean():.5f} ({w.std() / math.sqrt(n):.1g}) |", flush=True)


def sggx_closed(S):
    Sm = np.array([[S[0], S[3], S[4]], [S[3], S[1], S[5]], [S[4], S[5], S[2]]], dtype=np.float64)
    Si = np.linalg.inv(Sm)
    det = np.linalg.det(Sm)

    def Dm(m):
        q = np.einsum("ki,ij,kj->k", m, Si, m)
        return 1.0 / (math.pi * math.sqrt(det) * q * q)

    def sigma(w):
        return np.sqrt(np.einsum("ki,ij,kj->k", w, Sm, w))

    def phase(wi, wo):  # specular microflakes: D(wh) / (4 sigma(wi)), wh = normalize(wi + wo)
        h = wi + wo
        h = h / np.linalg.norm(h, axis=1)[:, None]
        return Dm(h) / (4.0 * sigma(wi))
    return phase


def cls_sggx(n=200000):
    import phase_medium as pm
    from scipy import stats
    print("\n### SGGX\n")
    print("Mitsuba's sggx eval against the closed form of the specular SGGX microflake phase function "
          "(Heitz et al. 2015: D(wh) / (4 sigma(wi)), wh = normalize(wi + wo), with wi or -wi), its "
          f"integral over the sphere, and a chi-squared of {n} of Mitsuba's samples on 20 bins of the "
          "cosine to the surface-like axis against Mitsuba's own pdf() (quadrature per bin).\n")
    S = (1, 1, 0.01, 0, 0, 0)
    grid = mi.VolumeGrid(np.array(S, dtype=np.float32).reshape(1, 1, 1, 6))
    spec = {"type": "sggx", "S": {"type": "gridvolume", "grid": grid, "raw": True, "filter_type": "nearest"}}
    ph = pm.MitsubaPhase(spec)
    wi = z.direction(10.0, 20.0)
    phase = sggx_closed(S)
    d = np.random.default_rng(1).normal(size=(2000, 3))
    d /= np.linalg.norm(d, axis=1)[:, None]
    ev = ph.eval(wi, d)
    pd = ph.pdf(wi, d)
    for label, w in (("wi", wi), ("-wi", -wi)):
        c = phase(np.broadcast_to(w, d.shape), d)
        print(f"- eval / closed form with {label}: median {np.median(ev / c):.5f}, range "
              f"[{np.min(ev / c):.4g}, {np.max(ev / c):.4g}]")
    print(f"- eval / pdf: range [{np.min(ev / pd):.6g}, {np.max(ev / pd):.6g}]")
    total = quad_sphere(lambda x: ph.pdf(wi, x), below=True, n_phi=360)
    print(f"- integral of Mitsuba's pdf() over the sphere: {total:.5f}")
    u = np.random.default_rng(2).random((n, 3))
    wo, w, bpdf = ph.sample(wi, u)
    edges = np.linspace(-1, 1, 21)
    obs = np.histogram(wo[:, 2], edges)[0]
    th = theta_nodes(below=True)
    ph_ = (np.arange(360) + 0.5) * 2 * math.pi / 360
    T, P = np.meshgrid(th, ph_, indexing="ij")
    dd = np.stack([np.sin(T) * np.cos(P), np.sin(T) * np.sin(P), np.cos(T)], axis=-1).reshape(-1, 3)
    v = ph.pdf(wi, dd).reshape(T.shape).mean(axis=1) * 2 * math.pi * np.sin(th)
    cz = np.cos(th)
    exp = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        msk = (cz >= lo) & (cz <= hi)
        exp.append(np.trapezoid(v[msk], th[msk]) if msk.sum() > 1 else 0.0)
    exp = np.array(exp) / np.sum(exp) * n
    chi = float(np.sum((obs - exp) ** 2 / exp))
    print(f"- samples' z against pdf(): chi-squared {chi:.1f} on 19 df, p = {stats.chi2.sf(chi, 19):.3g}")
    # Heitz et al.'s visible-normal sampler in float64, with the matrix S projected into the
    # frame (wk, wj, wi) of the incident direction as F^T S F (the paper) and as F S F^T,
    # fed the same uniforms and the same frame as Mitsuba's sample()
    Sm = np.array([[S[0], S[3], S[4]], [S[3], S[1], S[5]], [S[4], S[5], S[2]]], dtype=np.float64)
    fr = mi.Frame3f(mi.Vector3f(*map(float, wi)))
    F = np.array([[fr.s[i], fr.t[i], fr.n[i]] for i in range(3)], dtype=np.float64)  # columns s, t, n

    def heitz(P, uvw):
        k, j, i = 0, 1, 2
        isi = 1 / math.sqrt(P[i, i])
        tmp = math.sqrt(P[j, j] * P[i, i] - P[j, i] ** 2)
        mk = np.array([math.sqrt(abs(np.linalg.det(P))) / tmp, 0, 0])
        mj = np.array([-isi * (P[k, i] * P[j, i] - P[k, j] * P[i, i]) / tmp, isi * tmp, 0])
        mi_ = isi * np.array([P[k, i], P[j, i], P[i, i]])
        m = uvw[:, :1] * mk + uvw[:, 1:2] * mj + uvw[:, 2:] * mi_
        m = (m / np.linalg.norm(m, axis=1)[:, None]) @ F.T
        return 2 * (m @ wi)[:, None] * m - wi
    uu = z.u32(u[:2000])
    uvw = np.array([list(mi.warp.square_to_cosine_hemisphere(mi.Point2f(float(a), float(b))))
                    for a, b in uu[:, 1:3]], dtype=np.float64)
    for label, P in (("F^T S F (Heitz et al.)", F.T @ Sm @ F), ("F S F^T", F @ Sm @ F.T)):
        wo_np = heitz(P, uvw)
        ang = np.degrees(np.arccos(np.clip(np.sum(wo_np * wo[:2000], axis=1), -1, 1)))
        print(f"- Mitsuba's sampled directions against this sampler with S projected as {label}, same uniforms: "
              f"angle median {np.median(ang):.3g} deg, largest {np.max(ang):.3g} deg")
        # the same sampler's own distribution against Mitsuba's pdf() (cosine hemisphere by Malley)
        v = np.random.default_rng(4).random((n, 2))
        r_, ph2 = np.sqrt(v[:, 0]), 2 * math.pi * v[:, 1]
        c3 = np.stack([r_ * np.cos(ph2), r_ * np.sin(ph2), np.sqrt(1 - v[:, 0])], axis=1)
        o2 = np.histogram(heitz(P, c3)[:, 2], edges)[0]
        chi2 = float(np.sum((o2 - exp) ** 2 / exp))
        print(f"  its {n} samples' z against Mitsuba's pdf(): chi-squared {chi2:.1f} on 19 df, "
              f"p = {stats.chi2.sf(chi2, 19):.3g}")
    print("- bins (z from -1 to 1), observed / expected: "
          + ", ".join(f"{o / e:.3f}" for o, e in zip(obs, exp)))


def cls_isotropic(n=400000):
    import phase_medium as pm
    from scipy import stats
    print("\n### isotropic\n")
    ph = pm.MitsubaPhase({"type": "isotropic"})
    wi = z.direction(40.0, 20.0)
    u = np.random.default_rng(5).random((n, 3))
    wo, w, p = ph.sample(wi, u)
    print(f"- pdf values: {np.unique(p)}, weights {np.unique(w)}")
    for axis in range(3):
        obs = np.histogram(wo[:, axis], np.linspace(-1, 1, 41))[0]
        chi = float(np.sum((obs - n / 40) ** 2 / (n / 40)))
        print(f"- axis {axis}: chi-squared of {n} samples on 40 equal-probability bins {chi:.1f} (39 df), "
              f"p = {stats.chi2.sf(chi, 39):.3g}")
    rej = [mcstat.check_phase(ph.sample, ph.eval, ph.pdf, wi, n=20000, seed=s, alpha=0.01, n_uniforms=3).reject
           for s in range(20)]
    print(f"- check_phase rejections at seeds 0..19: {sum(rej)}")


def cls_excluded(seeds=20, sizes=(20000, 80000)):
    os.environ["MCSTAT_MITSUBA_VARIANT"] = "scalar_rgb"
    sys.path.insert(0, os.path.join(ROOT, "examples", "mitsuba", "suite"))
    import cases
    print("\n### The demo suite's EXCLUDED cases, re-run\n")
    print(f"Each case's callables as cases.py makes them (mitsuba_adapters, {mi.variant()}), checked directly "
          f"(check_emitter / check_bsdf, alpha 0.01, no escalation) at seeds 0..{seeds - 1}, at n = 20000 (the "
          "suite's stage 1) and 80000 (its stage 2).\n")
    print("| case | n | rejected | routes (runs) | mass (cubature): min / median / max "
          "| mass (Monte Carlo at the table points): min / max "
          "| s per check |")
    print("|---|---|---|---|---|---|---|")
    for cid in cases.EXCLUDED:
        kind, rest = cid.split("-", 1)
        for n in sizes:
            t0 = time.perf_counter()
            rej, routes, masses, shares = 0, {}, [], []
            for seed in range(seeds):
                if kind == "emitter":
                    shape, idx = rest.split("-")
                    refs = [(0.1, 0.1, -0.5), (-0.3, -0.3, 0.3), (0.6, 0.0, 0.4), (0.0, 0.4, 0.7), (-0.5, 0.2, -0.2),
                            (0.2, 0.6, 0.1), (-0.6, -0.2, 0.6), (0.4, 0.4, -0.3), (0.0, -0.6, 0.5), (0.7, 0.3, 0.2)]
                    ref = refs[int(idx[3:])] if idx.startswith("far") else cases.EMITTER_REFS[int(idx)]
                    s, e, p = ma.emitter_callables(shape, ref=ref)
                    r = mcstat.check_emitter(s, e, p, n=n, seed=seed, alpha=0.01)
                else:
                    name, t, ph = rest.rsplit("-", 2)
                    d, _, domain, _ = ma.BSDF_CONFIGS[name]
                    s, e, p = ma.bsdf_callables(d)
                    r = mcstat.check_bsdf(s, e, p, cases._wi(float(t[1:]), float(ph[1:])), n=n, seed=seed,
                                          alpha=0.01, domain=domain)
                rej += r.reject
                masses.append(r.mass)
                shares.append(r.mass_sampled)
                for x in r.routes:
                    if x.state == "ran" and x.reject:
                        routes[x.name] = routes.get(x.name, 0) + 1
                if r.reject:
                    print(f"<!-- {cid} n {n} seed {seed}:\n{r}\n-->", file=sys.stderr, flush=True)
            dt = (time.perf_counter() - t0) / seeds
            which = ", ".join(f"{k} ({v})" for k, v in routes.items()) or "-"
            print(f"| {cid} | {n} | {rej}/{seeds} | {which} | {min(masses):.5f} / {np.median(masses):.5f} / "
                  f"{max(masses):.5f} | {min(shares):.5f} / {max(shares):.5f} | {dt:.1f} |", flush=True)


def cls_excluded_quad(refs=None, title="The excluded lights' pdf() by dense quadrature"):
    """Lights' pdf() integrated by dense quadrature around the light."""
    print(f"\n### {title}\n")
    refs = refs or {"emitter-rectangle-far4": ("rectangle", (-0.5, 0.2, -0.2)),
                    "emitter-rectangle-far6": ("rectangle", (-0.6, -0.2, 0.6)),
                    "emitter-sphere-far6": ("sphere", (-0.6, -0.2, 0.6))}
    for cid, (shape, ref) in refs.items():
        s, e, p = ma.emitter_callables(shape, ref=ref)
        u = np.random.default_rng(9).random((100000, 2))
        d, w, sp = s(u)
        share = float(np.mean(sp > 0))
        # quadrature on a polar grid around the light's mean direction, fine enough for its rim
        c = d[sp > 0].mean(axis=0)
        c /= np.linalg.norm(c)
        ang = np.arccos(np.clip(d[sp > 0] @ c, -1, 1)).max() * 1.05
        t = np.linspace(0.0, ang, 1500)
        n_phi = 1500
        ph = (np.arange(n_phi) + 0.5) * 2 * math.pi / n_phi
        a = np.cross(c, [1.0, 0, 0] if abs(c[0]) < 0.9 else [0, 1.0, 0])
        a /= np.linalg.norm(a)
        b = np.cross(c, a)
        ring = np.empty(len(t))
        for i, ti in enumerate(t):
            dirs = (np.cos(ti) * c[None, :] + np.sin(ti) * (np.cos(ph)[:, None] * a + np.sin(ph)[:, None] * b))
            ring[i] = p(dirs).mean() * 2 * math.pi * math.sin(ti)
        total = float(np.trapezoid(ring, t))
        print(f"- {cid}: integral of pdf() {total:.5f} (polar grid 1500 x 1500 to {math.degrees(ang):.1f} deg "
              f"around the light), success share of 100000 samples {share:.5f}", flush=True)


def cls_cubature(n=400000):
    """Models where mcstat's mass fell short: Mitsuba's pdf() by dense quadrature."""
    cls_excluded_quad({"near-pole triangle from (0, 0, 0)": ("near-pole triangle", (0.0, 0.0, 0.0)),
                       "triangle from (0, 0, 0)": ("triangle", (0.0, 0.0, 0.0))},
                      "Small lights: Mitsuba's pdf() by dense quadrature")
    print("\n| model | quadrature of Mitsuba's pdf() | success share (se) | mcstat's mass, seeds 0..4 |")
    print("|---|---|---|---|")
    spec = {"type": "blendbsdf", "weight": 0.3, "a": {"type": "diffuse"},
            "b": {"type": "roughconductor", "alpha": 0.05, "distribution": "ggx"}}
    for th in (89.9, 45.0):
        wi = z.direction(th)
        s, e, p = ma.bsdf_callables(spec)
        q = quad_sphere(lambda d: p(wi, d), n_phi=2880)
        sh, se, _ = success_share(s, wi, n)
        ms = [mcstat.check_bsdf(s, e, p, wi, n=20000, seed=k, alpha=0.01, domain="hemisphere").mass for k in range(5)]
        print(f"| blendbsdf 0.7 diffuse + 0.3 ggx alpha 0.05, theta {th:g} | {q:.5f} | {sh:.5f} ({se:.1g}) | "
              + ", ".join(f"{m:.4f}" for m in ms) + " |", flush=True)


CLASSES = {"cubature": cls_cubature, "float32": cls_float32, "beckmann": cls_beckmann, "spike": cls_spike,
           "energy": cls_energy,
           "sggx": cls_sggx, "isotropic": cls_isotropic, "excluded": cls_excluded, "excluded-quad": cls_excluded_quad}

if __name__ == "__main__":
    which = sys.argv[1:] or ["all"]
    if which == ["all"]:
        which = list(CLASSES)
    for c in which:
        t0 = time.perf_counter()
        CLASSES[c]()
        print(f"\n({c}: {time.perf_counter() - t0:.0f} s)", flush=True)
