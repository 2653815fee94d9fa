"""Mitsuba 3's automatic differentiation checked by mcstat.check_gradient:
the AD gradient of a tiny scene's loss against central finite differences
of the same loss, seed by seed with common random numbers, correct and with
a planted dr.detach.

    .venv/bin/python examples/mitsuba/gradient.py [--checks 20] [--n 32] [--correct-checks 200] [--rtol 0]

prints the Markdown table of RESULTS.md's section "Gradients": for each
integrator, in how many checks (each its own n seeds, disjoint between
checks) check_gradient rejected at alpha = 0.05, and which parameters.

The scene (llvm_ad_rgb): a 16 x 16 perspective view of a diffuse floor
(rectangle, reflectance 0.5) lit by a downward-facing rectangular area light
(radiance 3) above it, outside the camera's view; 4 samples per pixel.  The
two parameters: the floor's reflectance and the light's radiance.  The loss
is the mean over pixels of p / (1 + p) (Reinhard's tone curve) of the
pixels' luminance p: non-linear in both parameters, so the central
differences have an O(h^2) bias that the Richardson bound covers.

The integrator is written here in Python on Dr.Jit (no mi.render): direct
illumination with multiple importance sampling (power heuristic) of an
emitter sample (scene.sample_emitter_direction) and a BSDF sample that may
hit the light.  Its random numbers come from a PCG32 seeded by the seed
(hashed), a fixed number per path, so the same seed gives the same random
numbers at every parameter value (common random numbers).  The AD gradient
of the loss is one dr.backward per seed (both parameters at once).

Planted bugs, each a dr.detach on one factor of one term: its primal value
is unchanged, so the finite differences are the same, but the reflectance's
gradient loses that term's share; the radiance's gradient is unaffected.
  detach_em    the emitter-sampling term's bsdf.eval (most of the gradient)
  detach_bsdf  the BSDF-sampling term's sample weight bsdf.sample() returns
               (that term is a small share of the light: the gradient is
               wrong by under 1%)
The same finite differences serve every integrator (the primal renders do
not depend on the bug), and the per-seed values go to check_gradient as
arrays (the path of a renderer outside Python).

Margins: the Richardson bound (check_gradient's default factor 2) for the
finite differences' truncation bias, and nothing else by default.  The
renders are float32, and the AD and finite differences round differently;
--rtol (of an upper bound of |E FD|; default 0) would allow for that, which
this scene does not need (RESULTS.md).
"""
import argparse
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
# mitsuba_adapters points DRJIT_LIBLLVM_PATH at Debian's libllvm19 before
# drjit is imported (LLVM 15 aborts in code generation on some CPUs)
import mitsuba_adapters  # noqa: E402
import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402

import mcstat  # noqa: E402

VARIANT = "llvm_ad_rgb"
RES, SPP = 16, 4
THETA = np.array([0.5, 3.0])  # floor reflectance, light radiance
KEYS = ("floor.bsdf.reflectance.value", "light.emitter.radiance.value")
NAMES = ("reflectance", "radiance")
H = np.array([0.02, 0.1])
ALPHA, RTOL = 0.05, 0.0


def make_scene():
    T = mi.ScalarTransform4f
    return mi.load_dict({
        "type": "scene",
        "sensor": {"type": "perspective", "fov": 40,
                   "to_world": T().look_at(origin=[0, -3, 1], target=[0, 0, 0], up=[0, 0, 1]),
                   "film": {"type": "hdrfilm", "width": RES, "height": RES, "rfilter": {"type": "box"}}},
        "floor": {"type": "rectangle", "to_world": T().scale(2.0),
                  "bsdf": {"type": "diffuse", "reflectance": float(THETA[0])}},
        # rectangles face +z: turned over to light the floor
        "light": {"type": "rectangle", "to_world": T().translate([0, 0, 1.5]).rotate([1, 0, 0], 180).scale(0.5),
                  "emitter": {"type": "area", "radiance": float(THETA[1])}},
    })


def _hash(seed):
    """splitmix64 of the seed: PCG32 starting states far apart"""
    z = (seed * 0x9E3779B97F4A7C15 + 0x632BE59BD9B4E019) & 0xFFFFFFFFFFFFFFFF
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & 0xFFFFFFFFFFFFFFFF
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & 0xFFFFFFFFFFFFFFFF
    return z ^ (z >> 31)


def _mis(a, b):
    a2, b2 = dr.square(a), dr.square(b)
    return dr.select(a2 + b2 > 0, a2 / (a2 + b2), 0.0)


def radiance(scene, seed, planted):
    """per-sample radiance (Color3f, RES * RES * SPP samples, pixel-major)"""
    n = RES * RES * SPP
    rng = mi.PCG32(size=n, initstate=dr.opaque(mi.UInt64, _hash(seed)), initseq=dr.arange(mi.UInt64, n))
    idx = dr.arange(mi.UInt32, n) // SPP
    px = mi.Point2f(mi.Float(idx % RES), mi.Float(idx // RES))
    pos = (px + mi.Point2f(rng.next_float32(), rng.next_float32())) / RES
    ray, _ = scene.sensors()[0].sample_ray(0.0, 0.5, pos, mi.Point2f(0.5))
    si = scene.ray_intersect(ray)
    ctx = mi.BSDFContext()
    bsdf = si.bsdf(ray)
    L = mi.Color3f(si.emitter(scene).eval(si))
    active = si.is_valid()
    # emitter sampling
    u_em = mi.Point2f(rng.next_float32(), rng.next_float32())
    ds, em_w = scene.sample_emitter_direction(si, u_em, True, active)
    wo = si.to_local(ds.d)
    f = bsdf.eval(ctx, si, wo, active)
    if planted == "detach_em":
        f = dr.detach(f)
    pdf_b = bsdf.pdf(ctx, si, wo, active)
    L += dr.select(active & (ds.pdf > 0), f * em_w * _mis(ds.pdf, pdf_b), 0.0)
    # BSDF sampling
    u1 = rng.next_float32()
    u2 = mi.Point2f(rng.next_float32(), rng.next_float32())
    bs, bw = bsdf.sample(ctx, si, u1, u2, active)
    if planted == "detach_bsdf":
        bw = dr.detach(bw)
    ray2 = si.spawn_ray(si.to_world(bs.wo))
    si2 = scene.ray_intersect(ray2, active)
    em = si2.emitter(scene, active)
    hit = active & (em != None)  # noqa: E711  (Dr.Jit's mask of a non-null pointer)
    ds2 = mi.DirectionSample3f(scene, si2, si)
    pdf_e = scene.pdf_emitter_direction(si, ds2, hit)
    L += dr.select(hit, bw * em.eval(si2, hit) * _mis(bs.pdf, pdf_e), 0.0)
    return L


def loss_of(L):
    lum = mi.luminance(L)
    pix = dr.block_sum(lum, SPP) / SPP
    return dr.mean(pix / (1.0 + pix))


class Renderer:
    def __init__(self):
        self.scene = make_scene()
        self.params = mi.traverse(self.scene)

    def _set(self, theta, grad=False):
        vals = []
        for key, v in zip(KEYS, theta):
            x = dr.opaque(mi.Float, float(v))
            if grad:
                dr.enable_grad(x)
            self.params[key] = x
            vals.append(x)
        return vals

    def loss(self, theta, seed):
        with dr.suspend_grad():
            self._set(theta)
            self.params.update()
            out = loss_of(radiance(self.scene, seed, None))
            dr.eval(out)
        return float(out[0])

    def grad(self, seed, planted):
        vals = self._set(THETA, grad=True)
        self.params.update()
        out = loss_of(radiance(self.scene, seed, planted))
        dr.backward(out)
        g = [float(dr.grad(x)[0]) for x in vals]
        self._set(THETA)
        self.params.update()
        return g

    def fd(self, seed, step):
        """central differences at step * H, per parameter"""
        out = []
        for j in range(len(THETA)):
            tp, tm = THETA.copy(), THETA.copy()
            tp[j] += step * H[j]
            tm[j] -= step * H[j]
            out.append((self.loss(tp, seed) - self.loss(tm, seed)) / (tp[j] - tm[j]))
        return out


PLANTS = ("detach_em", "detach_bsdf")


def run(r, seeds, plants):
    """per-seed arrays: AD of each integrator (None: correct), FD(h), FD(2h)"""
    ad = {p: [] for p in (None,) + plants}
    fd1, fd2 = [], []
    for s in seeds:
        for p in ad:
            ad[p].append(r.grad(s, p))
        fd1.append(r.fd(s, 1))
        fd2.append(r.fd(s, 2))
    return {p: np.array(v) for p, v in ad.items()}, np.array(fd1), np.array(fd2)


def check(ad, fd1, fd2, rtol, factor):
    return mcstat.check_gradient(ad, reference=fd1, reference_2h=fd2, rtol=rtol, alpha=ALPHA, names=NAMES,
                                 richardson_factor=factor)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--checks", type=int, default=20, help="checks of each integrator (each its own n seeds)")
    ap.add_argument("--correct-checks", type=int, default=None,
                    help="checks of the correct integrator (default: --checks); the planted ones are "
                         "checked on the first --checks of them")
    ap.add_argument("--n", type=int, default=32, help="seeds per check")
    ap.add_argument("--rtol", type=float, default=RTOL, help="relative margin (float32 rounding)")
    ap.add_argument("--richardson-factor", type=float, default=2.0,
                    help="check_gradient's richardson_factor (default 2, its default)")
    ap.add_argument("--show", action="store_true", help="print the first check's reports")
    args = ap.parse_args()
    n_ok = max(args.correct_checks or args.checks, args.checks)
    mi.set_variant(VARIANT)
    r = Renderer()
    t0, c0 = time.time(), time.process_time()
    rows = {p: [] for p in (None,) + PLANTS}
    for c in range(n_ok):
        plants = PLANTS if c < args.checks else ()
        ad, fd1, fd2 = run(r, range(c * args.n, (c + 1) * args.n), plants)
        line = []
        for p, g in ad.items():
            rep = check(g, fd1, fd2, args.rtol, args.richardson_factor)
            rows[p].append(rep)
            line.append(f"{p or 'correct'} {'REJECT' if rep.reject else 'pass'} (p {rep.pvalue:.3g})")
        print(f"check {c}: " + ", ".join(line), file=sys.stderr, flush=True)
    wall, cpu = time.time() - t0, time.process_time() - c0
    if args.show:
        for p in rows:
            print(rows[p][0])
    renders = n_ok * args.n * (1 + 4 * len(THETA)) + args.checks * args.n * len(PLANTS)
    print(f"Mitsuba {mi.__version__} ({VARIANT}), mcstat {mcstat.__version__}: {RES}x{RES} pixels, {SPP} spp, "
          f"n = {args.n} seeds per check (disjoint), alpha = {ALPHA}, rtol = {args.rtol:g}, "
          f"h = ({H[0]:g}, {H[1]:g}), Richardson bound on (factor {args.richardson_factor:g}); {renders} renders "
          f"({n_ok} checks x {args.n} seeds x (1 AD + {4 * len(THETA)} FD), and 1 AD per planted bug in "
          f"{args.checks} checks) in {wall:.0f} s wall, {cpu:.0f} s CPU; libLLVM: {mitsuba_adapters.loaded_libllvm()}")
    print()
    print("| integrator | checks | rejected | reflectance rejected | radiance rejected | "
          "median detectable \\|E d\\| (reflectance, radiance) |")
    print("|---|---|---|---|---|---|")
    for p, reps in rows.items():
        k = len(reps)
        rej = sum(x.reject for x in reps)
        per = [sum(x.parameter(nm).reject for x in reps) for nm in NAMES]
        det = [np.median([x.parameter(nm).detectable for x in reps]) for nm in NAMES]
        print(f"| {p or 'correct'} | {k} | {rej}/{k} | {per[0]}/{k} | {per[1]}/{k} | {det[0]:.3g}, {det[1]:.3g} |")
    print()
    for p, reps in rows.items():
        print(f"first check, {p or 'correct'}: " + "; ".join(
            f"{q.name}: AD {q.mean_grad:.5g}, FD {q.mean_ref:.5g}, difference {q.mean_diff:.3g} "
            f"(CI {q.conf_int[0]:.3g}, {q.conf_int[1]:.3g}), margin {q.margin:.3g}, Richardson bias {q.bias:.3g}, "
            f"adjusted p {q.pvalue_adjusted:.3g}"
            for q in reps[0].parameters))
    meta = mcstat.battery_test(sum(x.reject for x in rows[None]), ALPHA, n=len(rows[None]), alternative="greater")
    print(f"\ncorrect: {sum(x.reject for x in rows[None])} of {len(rows[None])} rejected; battery meta-test "
          f"(too many rejections for alpha = {ALPHA}?) p = {meta.pvalue:.3g}")


if __name__ == "__main__":
    main()
