"""Measures the heavy-tail flag of mcstat.diagnose: how often it fires on
infinite-variance data (U^-1/2, Pareto 1.5, t_2, Cauchy) and, as false
alarms, on finite-variance data and the paper's estimators (irradiance U, C,
A, S; reflected radiance off Ward's and Ashikhmin-Shirley's BRDFs), 200
samples each at n = 1e3 and 1e4.  The figures are quoted in mcstat.h
("Estimator diagnostics"); tests/python/test_diagnose.py checks the same
rates with binomial bounds.  Run: .venv/bin/python tools/refgen/diagnose_rates.py
"""
import math
import sys

import numpy as np

import mcstat
from mcstat import estimators as est
from mcstat_app.reproduce.scene import load_scene
sc = load_scene(None)
tri = sc.triangles[0]; r0 = sc.receivers[0]
seed = [100]
def irr(mth):
    def f(n, rng):
        seed[0] += 1
        return est.irradiance(mth, n, triangle=tri, point=r0["point"], normal=r0["normal"], radiance=1.0, seed=seed[0])
    return f
def rad(brdf_name, how, d):
    b = sc.make_brdf(brdf_name)
    th = math.radians(d); w = np.array([math.sin(th) * math.cos(0.4), math.sin(th) * math.sin(0.4), math.cos(th)])
    p = b.plan(w); p.compute_albedo(1e-5, strict=False)
    def f(n, rng):
        seed[0] += 1
        return p.reflected_radiance(how, n, seed=seed[0], first_index=0)
    return f
dists = {
 "uniform": lambda n, rng: rng.random(n),
 "normal": lambda n, rng: rng.standard_normal(n),
 "exponential": lambda n, rng: rng.exponential(size=n),
 "gamma0.5": lambda n, rng: rng.gamma(0.5, size=n),
 "t5": lambda n, rng: rng.standard_t(5, n),
 "lognormal1": lambda n, rng: rng.lognormal(0, 1, n),
 "pareto3": lambda n, rng: rng.pareto(3, n) + 1,
 "U^-1/2": lambda n, rng: rng.random(n) ** -0.5,
 "pareto1.5": lambda n, rng: rng.pareto(1.5, n) + 1,
 "t2": lambda n, rng: rng.standard_t(2, n),
 "cauchy": lambda n, rng: rng.standard_cauchy(n),
 "99% zeros+U^-1/2": lambda n, rng: np.where(rng.random(n) < 0.99, 0.0, rng.random(n) ** -0.5),
 "irr U": irr("U"), "irr C": irr("C"), "irr A": irr("A"), "irr S": irr("S"),
 # outgoing directions at polar angles (degrees); 51.6 = 0.9 rad has the longest tail seen
 **{f"{b} {how} {th}": rad(b, how, th) for b in ("ward", "ashikhmin_shirley")
    for how in ("sampling", "rejection") for th in (17, 51.6, 80)},
}
rng = np.random.default_rng(9)
for n in (1000, 10000):
    R = 200
    for name, f in dists.items():
        fl = []; tix = []
        for _ in range(R):
            d = mcstat.diagnose(f(n, rng), normality=False)
            fl.append(d.heavy_tail); tix.append(min(d.tail_index))
        print(f"n={n} {name:30s} flagged {np.mean(fl):.3f}  median index {np.median(tix):.2f}")
    sys.stdout.flush()
