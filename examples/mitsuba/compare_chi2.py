"""Mitsuba's own chi2 test (mitsuba.chi2.ChiSquareTest) against mcstat.check_bsdf
on the same BSDFs, correct and with planted bugs (mitsuba_adapters.PLANTED_BUGS).

For each BSDF of mitsuba_adapters.BSDF_CONFIGS (set up as Mitsuba's test suite
sets them up) x {correct, sampler, pdf, eval, weight} x seeds 0..S-1:
  - Mitsuba: ChiSquareTest with the suite's arguments for that BSDF (its res and
    ires, SphericalDomain, sample_dim 3), sample_count 1M (its default), seed
    varied, at its significance level 0.01;
  - mcstat: check_bsdf(n=100_000) with its defaults (alpha 0.01), seed varied;
    and check_bsdf(..., stochastic=True), which leaves out the two deterministic
    routes (pdf_value, weight) so that only statistical routes decide.
Then, for the bug classes that both can see statistically (sampler, pdf), the
smallest sample count of a grid at which each detects in >= 90% of the power
seeds.  Prints markdown.

  python compare_chi2.py [--seeds 30] [--bsdfs a,b] [--bugs none,sampler] [--quick]

Needs only the mitsuba wheel, numpy, scipy and mcstat; the JIT variant
llvm_ad_rgb (Mitsuba's ChiSquareTest does not run in scalar variants).
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_adapters as ma  # noqa: E402
import mcstat  # noqa: E402

N_GRID = (1000, 3000, 10_000, 30_000, 100_000, 300_000, 1_000_000)


class Counted:
    """Wraps the three callables and counts the points each is asked for."""

    def __init__(self, sample, eval_, pdf):
        self.n_sample = self.n_eval = self.n_pdf = 0
        self._s, self._e, self._p = sample, eval_, pdf

    def sample(self, wi, u):
        self.n_sample += len(u)
        return self._s(wi, u)

    def eval(self, wi, wo):
        self.n_eval += len(wo)
        return self._e(wi, wo)

    def pdf(self, wi, wo):
        self.n_pdf += len(wo)
        return self._p(wi, wo)


def run_mcstat(name, bug, seed, n, stochastic=False, factor=ma.BUG_FACTOR):
    s, e, p, wi, domain = ma.config_callables(name, bug, factor=factor)
    c = Counted(s, e, p)
    t = time.perf_counter()
    r = mcstat.check_bsdf(c.sample, c.eval, c.pdf, wi, n=n, seed=seed, domain=domain, stochastic=stochastic)
    dt = time.perf_counter() - t
    routes = [x.name for x in r.routes if x.reject]
    return dict(reject=r.reject, p=r.pvalue, time=dt, routes=routes, points=(c.n_sample, c.n_pdf, c.n_eval))


def run_chi2(name, bug, seed, n=1_000_000, factor=ma.BUG_FACTOR):
    cfg = ma.BSDF_CONFIGS[name]
    kw = cfg[3]
    res, ires = kw.get("res", 101), kw.get("ires", 4)
    t = time.perf_counter()
    ok, p, _ = ma.mitsuba_chi2(name, bug, seed=seed, sample_count=n, factor=factor)
    dt = time.perf_counter() - t
    # SphericalDomain: res x 2 res cells, each integrated with ires^2 pdf() points
    return dict(reject=not ok, p=p, time=dt, points=(n, 2 * res * res * ires * ires, 0))


def rate(rows):
    k = sum(r["reject"] for r in rows)
    return "%d/%d" % (k, len(rows))


def fmt_points(pts):
    def f(x):
        return "%.3g" % x if x < 1e4 else "%.2gM" % (x / 1e6) if x >= 1e6 else "%.0fk" % (x / 1e3)
    return "%s / %s / %s" % tuple(f(x) for x in pts)


def timing(bsdfs, variants=("scalar_rgb", "llvm_ad_rgb"), k_scalar=20_000, k_jit=1_000_000):
    """Per-sample cost of Mitsuba's sample() through the adapters: a Python loop
    in scalar_rgb, one vectorised call in llvm_ad_rgb (after a warm-up call that
    compiles the kernel); and of the whole check_bsdf(n=100_000) run."""
    rows = ["| BSDF | variant | sample() us/sample | check_bsdf(n=100k) s |", "|---|---|---|---|"]
    rng = np.random.default_rng(0)
    for v in variants:
        ma.use_variant(v)
        k = k_scalar if v.startswith("scalar") else k_jit
        for name in bsdfs:
            s, e, p, wi, domain = ma.config_callables(name)
            s(wi, rng.random((1000, 3)))  # warm-up (JIT compile)
            u = rng.random((k, 3))
            t = time.perf_counter()
            s(wi, u)
            per = 1e6 * (time.perf_counter() - t) / k
            t = time.perf_counter()
            mcstat.check_bsdf(s, e, p, wi, domain=domain, seed=0)
            rows.append("| %s | %s | %.3g | %.2f |" % (name, v, per, time.perf_counter() - t))
            print("  timing %s %s" % (name, v), file=sys.stderr)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", type=int, default=30, help="seeds 0..S-1 per BSDF and bug (default 30)")
    ap.add_argument("--power-seeds", type=int, default=10,
                    help="seeds per grid point of the smallest-n search (default 10)")
    ap.add_argument("--bsdfs", default=",".join(ma.BSDF_CONFIGS), help="comma-separated names of BSDF_CONFIGS")
    ap.add_argument("--bugs", default="none," + ",".join(ma.PLANTED_BUGS), help="none and/or planted bugs")
    ap.add_argument("--factor", type=float, default=ma.BUG_FACTOR, help="the planted bugs' factor (default 1.1)")
    ap.add_argument("--n", type=int, default=100_000, help="mcstat's sample count (default 100000)")
    ap.add_argument("--chi2-n", type=int, default=1_000_000, help="Mitsuba chi2's sample_count (default 1M)")
    ap.add_argument("--no-power", action="store_true", help="skip the smallest-n search")
    ap.add_argument("--quick", action="store_true", help="3 seeds, 3 power seeds, a short n grid")
    ap.add_argument("--variant", default=None, help="Mitsuba variant (default: llvm_ad_rgb if it works)")
    ap.add_argument("--timing", action="store_true",
                    help="only measure sample()'s cost per sample in scalar_rgb and llvm_ad_rgb")
    a = ap.parse_args(argv)
    bsdfs = [b for b in a.bsdfs.split(",") if b]
    for b in bsdfs:
        if b not in ma.BSDF_CONFIGS:
            sys.exit("unknown BSDF %r (known: %s)" % (b, ", ".join(ma.BSDF_CONFIGS)))
    if a.timing:
        print("\n".join(timing(bsdfs)))
        return
    if a.quick:
        a.seeds, a.power_seeds = min(a.seeds, 3), min(a.power_seeds, 3)
    grid = (1000, 10_000, 100_000, 1_000_000) if a.quick else N_GRID
    variant = ma.use_variant(a.variant)
    if not ma.is_jit():
        sys.exit("Mitsuba's ChiSquareTest needs a JIT variant (llvm_ad_rgb); this one is %s" % variant)
    bugs = [None if b == "none" else b for b in a.bugs.split(",") if b]
    for b in bugs:
        if b is not None and b not in ma.PLANTED_BUGS:
            sys.exit("unknown bug %r (known: none, %s)" % (b, ", ".join(ma.PLANTED_BUGS)))
    t0 = time.time()
    out = []
    p = out.append
    p("Mitsuba %s, variant %s, mcstat %s; bugs' factor %g; seeds 0..%d" % (
        ma.mi.__version__, variant, getattr(mcstat, "__version__", "?"), a.factor, a.seeds - 1))
    p("")
    p("### Rejections per seeds (alpha = 0.01): Mitsuba's ChiSquareTest (%s samples) vs mcstat.check_bsdf (n = %d)"
      % (format(a.chi2_n, ","), a.n))
    p("")
    p("Points: sample() / pdf() / eval() points asked for per run (mean).  "
      "mcstat stochastic: the same check without its deterministic routes (pdf_value, weight).")
    p("")
    p("| BSDF | bug | Mitsuba chi2 | mcstat | mcstat stochastic | mcstat routes that rejected | "
      "chi2 time (s) | mcstat time (s) | chi2 points | mcstat points |")
    p("|---|---|---|---|---|---|---|---|---|---|")
    summary = {}
    for name in bsdfs:
        for bug in bugs:
            c = [run_chi2(name, bug, s, a.chi2_n, a.factor) for s in range(a.seeds)]
            m = [run_mcstat(name, bug, s, a.n, False, a.factor) for s in range(a.seeds)]
            ms = [run_mcstat(name, bug, s, a.n, True, a.factor) for s in range(a.seeds)]
            hits = {}
            for r in m:
                for x in r["routes"]:
                    hits[x] = hits.get(x, 0) + 1
            rs = ", ".join("%s %d" % kv for kv in sorted(hits.items(), key=lambda kv: -kv[1])) or "-"
            mp = tuple(np.mean([r["points"][i] for r in m]) for i in range(3))
            p("| %s | %s | %s | %s | %s | %s | %.2f | %.2f | %s | %s |" % (
                name, bug or "correct", rate(c), rate(m), rate(ms), rs,
                np.mean([r["time"] for r in c]), np.mean([r["time"] for r in m]),
                fmt_points(c[0]["points"]), fmt_points(mp)))
            summary[(name, bug)] = (c, m, ms)
            print("  done %s %s (%.0f s)" % (name, bug, time.time() - t0), file=sys.stderr)
    if None in bugs:
        p("")
        p("False rejections on the correct BSDFs (dielectric_ggx_all left out: Mitsuba's own weight "
          "bug, see above):")
        ok_names = [n for n in bsdfs if n != "dielectric_ggx_all"]
        for i, label in enumerate(("Mitsuba chi2", "mcstat", "mcstat stochastic")):
            rows = [r for n in ok_names for r in summary[(n, None)][i]]
            if rows:
                p("- %s: %s" % (label, rate(rows)))
    pbugs = [b for b in bugs if b in ("sampler", "pdf")]
    if pbugs and not a.no_power:
        p("")
        p("### Smallest n of %s detecting in >= 90%% of %d seeds (bugs' factor %g)" % (
            "/".join(format(x, ",") for x in grid), a.power_seeds, a.factor))
        p("")
        p("'>' : not reached within the grid.  chi2: ChiSquareTest's sample_count; mcstat: check_bsdf's n "
          "(its pilot sample and eval-only points come on top; see the points column above).")
        p("")
        p("| BSDF | bug | Mitsuba chi2 | mcstat | mcstat stochastic |")
        p("|---|---|---|---|---|")
        for name in bsdfs:
            for bug in pbugs:
                cells = []
                for fn in (lambda s, n: run_chi2(name, bug, s, n, a.factor),
                           lambda s, n: run_mcstat(name, bug, s, n, False, a.factor),
                           lambda s, n: run_mcstat(name, bug, s, n, True, a.factor)):
                    found = ">%s" % format(grid[-1], ",")
                    for n in grid:
                        k = sum(fn(s, n)["reject"] for s in range(a.power_seeds))
                        if k >= 0.9 * a.power_seeds:
                            found = "%s (%d/%d)" % (format(n, ","), k, a.power_seeds)
                            break
                    cells.append(found)
                p("| %s | %s | %s | %s | %s |" % (name, bug, *cells))
                print("  power %s %s (%.0f s)" % (name, bug, time.time() - t0), file=sys.stderr)
    p("")
    p("Total wall time %.0f s." % (time.time() - t0))
    print("\n".join(out))


if __name__ == "__main__":
    main()
