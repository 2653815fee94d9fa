#!/usr/bin/env python3
"""The demo suite's calibration and power, measured (examples/mitsuba/RESULTS_suite.md).

    .venv/bin/python examples/mitsuba/suite/measure_suite.py [--seeds 50] [--alpha 1e-2] [--out DIR]

1. The correct suite (every case of cases.py) under the plugin, once per
   master seed 0..S-1 (a pytest subprocess each, --mcstat-report): runs
   with any failure, against the binomial bound of the budget; the failures
   per case (a case failing at many seeds is a systematic finding, not a
   false rejection at rate alpha); and, on the same stage-1 p-values, the
   naive suite that tests each case at 0.01.
2. Planted bugs, one class at a time in one case, at that case's share of
   the suite (alpha / number of cases) and the seeds the plugin would give
   it (check_seed(master, node id, 0)): the share of master seeds at which
   the planted test fails.  Calling the case inside mcstat.testing.scope
   instead of rerunning the whole suite per seed measures the same thing
   for the planted test; the other tests' false failures are part 1's.
3. Escalation against fixed n at equal samples: the same planted bugs,
   smaller, checked with escalation at n and without at the n whose cost
   equals escalation's mean cost on the correct suite (part 1).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
sys.path.insert(0, HERE)

# (class, case, factor): one case per class, the bug 5% unless said
PLANTS = [
    ("bsdf-sampler", "bsdf-conductor_ggx_aniso-t35-p70", 1.05),
    ("bsdf-pdf", "bsdf-plastic-t20-p0", 1.05),
    ("bsdf-eval", "bsdf-principled-t50-p140", 1.05),
    ("bsdf-weight", "bsdf-dielectric-t35-p210", 1.05),
    ("emitter-sampler", "emitter-sphere-1", 1.05),
    ("emitter-pdf", "emitter-rectangle-0", 1.05),
    ("emitter-eval", "emitter-rectangle-2", 1.05),
    ("emitter-weight", "emitter-sphere-3", 1.05),
    ("warp-sampler", "warp-von_mises_fisher-10", 1.05),
    ("warp-sampler", "warp-beckmann-0.3", 1.05),
    # the two sampler bugs below 95% at 5%, at 10%
    ("bsdf-sampler", "bsdf-conductor_ggx_aniso-t35-p70", 1.10),
    ("warp-sampler", "warp-von_mises_fisher-10", 1.10),
]
# bugs of the size where detection is partial, for the escalation comparison
SMALL = [
    ("bsdf-sampler", "bsdf-conductor_ggx_aniso-t35-p70", 1.05),
    ("bsdf-sampler", "bsdf-conductor_ggx_aniso-t35-p70", 1.04),
    ("emitter-sampler", "emitter-sphere-1", 1.03),
    ("warp-sampler", "warp-von_mises_fisher-10", 1.05),
    ("warp-sampler", "warp-von_mises_fisher-10", 1.07),
]


def node_id(case_id):
    kind = case_id.split("-", 1)[0]
    return f"examples/mitsuba/suite/test_{kind}s.py::test_{kind}[{case_id}]"


def binom_upper(k, n, conf=0.95):
    """Clopper-Pearson upper bound of a rate from k of n."""
    from scipy.stats import beta
    return 1.0 if k >= n else float(beta.ppf(conf, k + 1, n - k))


def part1(seeds, alpha, out):
    runs = []
    for s in range(seeds):
        path = os.path.join(out, f"correct-{s}.json")
        if not os.path.exists(path):
            t = time.time()
            subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "examples/mitsuba/suite",
                            "--mcstat-alpha", str(alpha), "--mcstat-seed", str(s), "--mcstat-report", path],
                           cwd=ROOT, capture_output=True, text=True)
            print(f"seed {s}: {time.time() - t:.0f} s", flush=True)
        with open(path) as f:
            runs.append(json.load(f))
    return runs


def run_planted(case_id, plant, factor, master, share, **kw):
    import cases
    from mcstat.testing import StatisticalAssertionError, scope
    _, _, run = cases.BY_ID[case_id]
    with scope(node_id(case_id), alpha=share, master_seed=master, escalate=kw.pop("escalate", 4.0)) as sc:
        try:
            run(plant=plant, factor=factor, **kw)
            caught = False
        except StatisticalAssertionError:
            caught = True
    return caught, sc.records[0].samples


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=50)
    ap.add_argument("--alpha", type=float, default=1e-2)
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "suite-measure"))
    ap.add_argument("--parts", default="123", help="which parts to run (part 1's runs are cached in --out)")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    import cases
    import mitsuba as mi

    print(f"# Mitsuba {mi.__version__}, {mi.variant()}; {len(cases.CASES)} cases, n = {cases.N}, suite alpha "
          f"{a.alpha:g}, seeds 0..{a.seeds - 1}\n")
    runs = part1(a.seeds, a.alpha, a.out)
    m = runs[0]["tests"]
    failed_runs = sum(any(r["decision"] != "pass" for r in run["records"]) for run in runs)
    naive_runs = sum(any(r["p_values"][0] <= 0.01 for r in run["records"]) for run in runs)
    per_case = {}
    for run in runs:
        for r in run["records"]:
            if r["decision"] != "pass":
                per_case.setdefault(r["test"], []).append((run["master_seed"], r["decision"], r["p_values"]))
    samples = [sum(r["samples"] for r in run["records"]) for run in runs]
    escalated = sum(r["stages"] > 1 for run in runs for r in run["records"])
    checks = sum(len(run["records"]) for run in runs)
    print("## 1. The correct suite, under the plugin\n")
    print(f"- runs with any failure: {failed_runs} of {len(runs)} (budget {a.alpha:g} per run: expected "
          f"{a.alpha * len(runs):.2g}; 95% upper bound of the rate {binom_upper(failed_runs, len(runs)):.3g})")
    print(f"- the naive suite (each test at 0.01, same stage-1 p-values): {naive_runs} of {len(runs)} runs fail "
          f"(1 - 0.99^{m} = {1 - 0.99 ** m:.3f} expected)")
    print(f"- checks escalated: {escalated} of {checks} ({escalated / checks:.3%}; the band's rate alpha0 - "
          f"alpha1 is about {0.05:.0%})")
    print(f"- samples per run: {sum(samples) / len(samples):.4g} (mean; {sum(samples) / len(samples) / m:.4g} per "
          f"check)")
    print("- failures per case:" + ("" if per_case else " none"))
    for test, fails in sorted(per_case.items(), key=lambda kv: -len(kv[1])):
        shown = "; ".join("s%d %s p %s" % (s, d, ", ".join("%.2g" % p for p in ps)) for s, d, ps in fails[:4])
        print(f"  - {test.split('[')[-1][:-1]}: {len(fails)} of {len(runs)} seeds ({shown})")
    share = a.alpha / m
    print(f"\n## 2. Planted bugs, the planted test at its share {share:.3g}\n")
    print("| class | case | factor | failed (of seeds) |\n|---|---|---|---|")
    for cls, case, factor in (PLANTS if "2" in a.parts else []):
        k = sum(run_planted(case, cls, factor, s, share)[0] for s in range(a.seeds))
        print(f"| {cls} | {case} | {factor:g} | {k}/{a.seeds} |", flush=True)
    per_check = sum(samples) / len(samples) / m
    print(f"\n## 3. Escalation vs fixed n at equal samples\n\nEscalation at n = {cases.N} costs {per_check:.4g} "
          "samples per correct check (part 1, pilot and eval points included); fixed n below is scaled to the "
          "same cost on each case.\n")
    print("| class | case | factor | escalation (n, x4) | fixed n | fixed n's samples / escalation's on the "
          "correct case |\n|---|---|---|---|---|---|")
    for cls, case, factor in (SMALL if "3" in a.parts else []):
        # the fixed n with the same cost as escalation on the correct case
        _, s_fixed_n = run_planted(case, None, factor, 0, share, escalate=0)
        esc_cost = [r["samples"] for run in runs for r in run["records"] if r["test"] == node_id(case)]
        mean_esc = sum(esc_cost) / len(esc_cost)
        n_fixed = int(cases.N * mean_esc / s_fixed_n)
        _, s_check = run_planted(case, None, factor, 0, share, escalate=0, n=n_fixed)
        ke = sum(run_planted(case, cls, factor, s, share)[0] for s in range(a.seeds))
        kf = sum(run_planted(case, cls, factor, s, share, escalate=0, n=n_fixed)[0] for s in range(a.seeds))
        print(f"| {cls} | {case} | {factor:g} | {ke}/{a.seeds} | {kf}/{a.seeds} (n {n_fixed}) | "
              f"{s_check / mean_esc:.3f} |", flush=True)


if __name__ == "__main__":
    main()
