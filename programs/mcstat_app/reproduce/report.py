# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""report.md and its figures, from the results of a run.

Every sentence that states an outcome is built from the numbers in
results.json (the studies' ``findings``); nothing is written in advance.
"""
from __future__ import annotations

import os
from typing import Any, Dict, List

from . import plots
from .studies import STUDIES


def _fmt_vec(v: Any) -> str:
    return "(" + ", ".join(f"{x:g}" for x in v) + ")"


def _outgoing(o: Any) -> str:
    if isinstance(o, dict):
        return f"theta {o['theta']:g}°, phi {o.get('phi', 0):g}°"
    return _fmt_vec(o)


def _details(title: str, text: str) -> List[str]:
    if not text.strip():
        return []
    return ["", f"<details><summary>{title}</summary>", "", "```", text.strip("\n"), "```", "", "</details>", ""]


def _ci(s: Dict[str, Any], digits: int = 3) -> str:
    if s.get("rate") is None:
        return "no test ran"
    failed = f" ({s['failed']} failed)" if s.get("failed") else ""
    return f"{s['rate']:.{digits}f} [{s['ci95'][0]:.{digits}f}, {s['ci95'][1]:.{digits}f}]{failed}"


def _p(v: Any) -> str:
    return "-" if v is None else f"p = {v:.3g}"


def _g(v: Any, spec: str = ".3g") -> str:
    return "-" if v is None else format(v, spec)


def write(out_dir: str, results: Dict[str, Any], transcripts: Dict[str, str]) -> List[str]:
    """Write report.md and the PNGs into out_dir; returns the files written."""
    files: List[str] = []

    def fig(name: str, draw, *args) -> str:
        path = os.path.join(out_dir, name)
        draw(*args, path)
        files.append(path)
        return f"![{name}]({name})"

    L: List[str] = []
    sc = results["scene"]
    st = results["studies"]
    L += [f"# mcstat reproduce: scene \"{sc['name']}\"", ""]
    L += [f"Statistical hypothesis tests of Monte Carlo estimators, the case studies of Subr and Arvo's section 3, "
          f"run by `{results['command']}` with mcstat {results['versions']['mcstat']} (libmcstat "
          f"{results['versions']['libmcstat']}, libmcest {results['versions']['libmcest']}, NumPy "
          f"{results['versions']['numpy']}). Seed {results['seed']}"
          + (", **quick mode** (reduced budgets, see the plan)" if results["quick"] else "")
          + f"; wall time {results['wall_seconds']:.1f} s on {results['wall_threads']} thread(s). "
          "`results.json` beside this file holds every test's fields; the same seed gives the same "
          "results.json apart from the wall-clock fields and the timing study.", ""]
    L += ["## Findings", ""]
    all_findings = results["findings"] + [f for s in STUDIES if s.wall_clock
                                          for f in results.get(s.key, {}).get("findings", [])]
    L += [f"- {f}" for f in all_findings] or ["- (no study ran)"]
    L += ["", "These sentences are computed from the runs (see each section); a rate is a count of rejections among "
              "repeated tests, given with its exact 95% (Clopper-Pearson) interval, and 'consistent with alpha' means "
              "the battery meta-test (libmcstat's exact binomial test of rate = alpha, `mcstat.battery_test`) "
              "gives p >= 0.01.", ""]

    # plan
    plan = results["plan"]
    L += ["## What ran, and what was left out", ""]
    L += ["| section | target | what |", "|---|---|---|"]
    L += [f"| {s['section']} | {s['target']} | {s['what']} |" for s in plan["steps"]]
    L += [""]
    if plan["left_out"]:
        L += ["Left out:", "", "| section | target | what | why |", "|---|---|---|---|"]
        L += [f"| {s['section']} | {s['target']} | {s['what']} | {s['reason']} |" for s in plan["left_out"]]
    else:
        L += ["Nothing was left out."]
    if plan["quick"]:
        L += ["", "Quick mode changed: " + ("; ".join(plan["quick_changes"]) or "nothing") + "."]
    L += [""]

    # scene
    L += ["## Scene", "", sc["description"] or "(no description)", ""]
    L += ["| emitter | vertices | radiance |", "|---|---|---|"]
    L += [f"| {i} | {', '.join(_fmt_vec(v) for v in e['vertices'])} | {e['radiance']:g} |"
          for i, e in enumerate(sc["emitters"])]
    L += ["", "| receiver | point | normal | Lambert's formula per triangle |", "|---|---|---|---|"]
    for r, pr in zip(sc["receivers"], plan["receivers"]):
        L += [f"| {r['name']} | {_fmt_vec(r['point'])} | {_fmt_vec(r['normal'])} | "
              f"{', '.join(f'{e:.9g}' for e in pr['exact_per_triangle'])} |"]
    if sc["brdfs"]:
        L += ["", "| BRDF | model | parameters | outgoing direction |", "|---|---|---|---|"]
        for b in sc["brdfs"]:
            params = {k: v for k, v in b.items() if k not in ("name", "model", "outgoing")}
            L += [f"| {b['name']} | {b['model']} | {', '.join(f'{k} {v:g}' for k, v in params.items())} | "
                  f"{_outgoing(b['outgoing'])} |"]
    L += ["", f"Estimators: {', '.join(sc['estimators'])}; trusted: {sc['trusted']}. The full scene, with "
              "every default filled in, is `scene` in results.json.", ""]

    for study in STUDIES:
        r = results.get(study.key) if study.wall_clock else st.get(study.key)
        if r is not None:
            L += study.report_part()(r, fig, transcripts.get(study.key, ""))

    L += ["## Reproducing this run", "",
          f"`{results['command']}` again gives the same results.json except for the fields named `wall_*` and the "
          "`timing` study. Every random stream is derived from the seed by `numpy.random.SeedSequence(seed, "
          "spawn_key=(study, ...))` (libmcest's counter-based generator then makes estimate i a pure function of "
          "its seed and i, whatever the number of threads); the seeds used are listed under `seeds` in results.json.",
          ""]
    path = os.path.join(out_dir, "report.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(L))
    files.append(path)
    return files


def irradiance(res: Dict[str, Any], fig, transcript: str) -> List[str]:
    L = ["## 3.1 Irradiance estimators", "",
         f"Each observation is a secondary estimate, the mean of k = {res['k']} primary estimates (ERRATA 7); "
         f"each sample has {res['secondary']} of them, and every test is repeated in {res['runs']} runs at "
         f"alpha = {res['alpha']:g}. U samples the hemisphere uniformly, C cosine-weighted, A the triangle's area, "
         "S its solid angle.", ""]
    for r in res["receivers"]:
        slug = r["name"].replace(" ", "_")
        L += [f"### Receiver {r['name']}", ""]
        if r["one_sample"] is not None:
            L += [f"One-sample t tests against Lambert's formula (E = {r['lambert']:.9g}), one per run:", "",
                  "| estimator | less | equal | greater | rejection rate [95% CI] | binomial test of rate = alpha |",
                  "|---|---|---|---|---|---|"]
            for m, s in r["one_sample"].items():
                c = s["counts"]
                L += [f"| {m} | {c['less']} | {c['equal']} | {c['greater']} | {_ci(s)} | {_p(s['binom_pvalue'])} |"]
            L += [""]
        elif r.get("against_trusted"):
            L += [f"No analytic value (several triangles): Welch tests of each estimator against the trusted "
                  f"{res['trusted']}, one per run:", "",
                  "| estimator | equal means | rejection rate [95% CI] | binomial test of rate = alpha |",
                  "|---|---|---|---|"]
            for m, s in r["against_trusted"].items():
                L += [f"| {m} | {s['counts']['equal']}/{s['tests']} | {_ci(s)} | {_p(s['binom_pvalue'])} |"]
            L += [""]
        L += ["Figure 4: every pair, x (rows) against an independent sample of y (columns); bars count the runs "
              "whose decision was less / equal / greater, red for the means (Welch), blue for the variances (F). "
              "The diagonal tests an estimator against itself.", "",
              fig(f"fig4_{slug}.png", plots.figure4, r, res["runs"]), "",
              "| x \\ y | " + " | ".join(r["matrix"]["estimators"]) + " |",
              "|---|" + "---|" * len(r["matrix"]["estimators"])]
        for a, i in enumerate(r["matrix"]["estimators"]):
            cells = []
            for b_, _ in enumerate(r["matrix"]["estimators"]):
                mc, vc = r["matrix"]["mean"][a][b_], r["matrix"]["variance"][a][b_]
                cells.append(f"{mc['less']}/{mc['equal']}/{mc['greater']} · {vc['less']}/{vc['equal']}/{vc['greater']}")
            L += [f"| {i} | " + " | ".join(cells) + " |"]
        L += ["", "(each cell: mean test less/equal/greater · variance test less/equal/greater)", ""]
        L += ["Figure 5: the secondary estimates of all runs, with a normal density of the same mean and standard "
              "deviation" + (" and Lambert's value (dashed)" if r["lambert"] is not None else "") + ".", "",
              fig(f"fig5_{slug}.png", plots.figure5, r), ""]
        o = r["ordering"]
        if len(o["order"]) > 1:
            L += [f"Variance ordering found: **{o['text']}** ('>' where the one-sided F test on the pooled secondary "
                  f"estimates rejects equal variances at alpha = {res['alpha']:g}, '~' where it does not). Standard "
                  "deviation of one primary estimate, estimated as s.d.(secondary) x sqrt(k): "
                  + ", ".join(f"{m} {r['sd_primary_estimated'][m]:.4g}" for m in o["order"]) + ".", ""]
        if r.get("equivalence"):
            L += _equivalence(r["equivalence"], r["lambert"])
    L += _details("R-style output of 3.1", transcript)
    return L


def _equivalence(eq: Dict[str, Any], E: float) -> List[str]:
    """Beyond the paper: is the bias small (TOST), and how many samples would find a small one (power)."""
    margins, biases = eq["margins"], eq["biases"]
    L = ["#### Is the bias small? Equivalence and sample size (beyond the paper)", "",
         "The t tests above can only fail to find a bias. An equivalence test (two one-sided t tests, TOST) turns "
         f"the question round: H0 |bias| >= margin against H1 |bias| < margin, at alpha = {eq['alpha']:g}, on the "
         "pooled secondary estimates; **yes** is evidence that the bias is smaller than the margin (the "
         f"{1 - 2 * eq['alpha']:.0%} confidence interval of the mean, shown relative to E, lies inside "
         "+-margin). The last columns give the number of primary estimates a one-sample t test needs to detect a "
         f"bias of that size with probability {eq['power']:g} (`mcstat.power`), from the estimator's measured "
         "variance.", "",
         "| estimator | (mean - E)/E | " + " | ".join(f"bias < {m:.1%} of E? (p)" for m in margins) + " | "
         + f"{1 - 2 * eq['alpha']:.0%} CI of (mean - E)/E | "
         + " | ".join(f"n to detect {b:.1%}" for b in biases) + " |",
         "|---|---|" + "---|" * len(margins) + "---|" + "---|" * len(biases)]
    for m, e in eq["estimators"].items():
        cells = []
        ci = "-"
        for q in e["equivalence"]:
            if "error" in q:
                cells.append("test failed")
                continue
            cells.append(f"{'**yes**' if q['equivalent'] else 'no'} ({_p(q['pvalue'])})")
            ci = f"[{q['conf_int_relative'][0]:.2e}, {q['conf_int_relative'][1]:.2e}]"
        ns = [f"{q['n_primary']:.3g}" if q["n_primary"] else "-" for q in e["sample_size"]]
        L += [f"| {m} | {e['bias_relative']:.2e} | " + " | ".join(cells) + f" | {ci} | " + " | ".join(ns) + " |"]
    first = next(iter(eq["estimators"].values()), None)
    if first:
        L += ["", f"Each estimator contributed {first['n_primary']} primary estimates ({first['n_secondary']} "
                  "secondary ones) to these tests.", ""]
    return L


def sampling(res: Dict[str, Any], fig, transcript: str) -> List[str]:
    L = ["## 3.2 BRDF sampling", "",
         f"For each BRDF at its outgoing direction, n directions from the model's own sampler against n from exact "
         f"rejection sampling of f cos / albedo, by the two-sample K-S test with Canner's weight (two-sided, alpha = "
         f"{res['alpha']:g}) on the directions' Morton keys, {res['runs']} runs per size. p-values are exact up to "
         f"about 2800 + 2800 and simulated beyond ({res['n_sim']} replicates). Directions the sampler puts below "
         "the horizon (f = 0 there) are "
         + ("discarded before the test (the fraction is reported)" if res["below_horizon"] == "discard"
            else "kept in the test") + ".", "",
         "(The paper reports that Ward's sampler failed at every size and Ashikhmin-Shirley's passed at alpha = "
         "0.005 below 100 directions and failed above.) "
         "Verdict per size: *passes* where the number of rejections is consistent with alpha (exact binomial "
         "test, p >= 0.01), *fails* where most runs reject, *sometimes* in between.", "",
         fig("power_curve.png", plots.power_curve, res), ""]
    for b in res["brdfs"]:
        bh = b["below_horizon"]
        L += [f"### {b['name']}", "", f"{b['description']}.", "",
              "| n | rejected | rate [95% CI] | median p (≤: every simulated p at its floor 1/(n_sim+1)) | p-value | verdict |", "|---|---|---|---|---|---|"]
        for r in b["sizes"]:
            L += [f"| {r['n']} | {r['rejections']}/{r['tests']} | {_ci(r, 2)} | "
                  f"{'≤ ' if r['pvalue_floor'] else ''}{r['median_pvalue']:.3g} | "
                  f"{'/'.join(r['pvalue_method'])} | {r['verdict']} |"]
        L += ["", f"Below the horizon: {bh['count']}/{bh['of']} = {bh['fraction']:.4f} "
                  f"[{bh['ci95'][0]:.4f}, {bh['ci95'][1]:.4f}] of the sampler's directions (rejection sampling: none). "
                  f"Exact sampler acceptance {b['acceptance_exact']:.3f}.", "",
              f"Figure 6: {res['histogram_size']} directions of each, by polar angle (rows) and azimuth (columns), "
              "on one grey scale, zoomed on the window that holds 99.8% of both samples.", "",
              fig(f"fig6_{b['name']}.png", plots.figure6, b), ""]
    L += _details("R-style output of 3.2", transcript)
    return L


def radiance(res: Dict[str, Any], fig, transcript: str) -> List[str]:
    L = ["## 3.3 Reflected radiance", "",
         f"At {res['directions']} outgoing directions spread evenly over the hemisphere, m = {res['m']} estimates of "
         "the reflected radiance under libmcest's analytic environment from BRDF sampling (weighted by the "
         "sampler's true density) and from exact rejection sampling (albedo by cubature to a relative "
         f"{res['albedo_rel_tol']:g}), compared by Welch's test at alpha = {res['alpha']:g}. If both are "
         "unbiased, the number of rejections is binomial with rate about alpha. (The paper reports 98.6% equal means "
         "over 1000 directions at alpha = 0.01, without saying whether that is consistent with alpha.)", ""]
    for b in res["brdfs"]:
        bt = b["binomial"]
        L += [f"### {b['name']}", ""]
        if bt is not None:
            L += [f"Equal means in {b['counts']['equal']}/{b['tests_ok']} = {b['equal_fraction']:.2%} of the tests "
                  f"(less {b['counts']['less']}, greater {b['counts']['greater']}). Rejection rate "
                  f"{bt['estimate']:.4f}, 95% CI [{bt['conf_int'][0]:.4f}, {bt['conf_int'][1]:.4f}]; exact binomial "
                  f"test of rate = {res['alpha']:g}: p = {bt['pvalue']:.3g}.", ""]
        L += [fig(f"radiance_{b['name']}.png", plots.radiance_pvalues, b, res["alpha"]), ""]
    L += _details("R-style output of 3.3", transcript)
    return L


def bugs(res: Dict[str, Any], fig, transcript: str) -> List[str]:
    L = ["## 3.4 Planted bugs", "",
         f"Estimator A with each of the paper's three bugs, and without (the control), against {res['trusted']}: "
         f"Welch's test at alpha = {res['alpha']:g} on {res['secondary']} secondary estimates per sample, "
         f"{res['runs']} runs per budget. A bug counts as detected from the smallest budget at which it, and every "
         f"larger budget, was rejected in at least {res['detected_threshold']:.0%} of the runs.", ""]
    for r in res["receivers"]:
        slug = r["name"].replace(" ", "_")
        vs = ["none"] + res["bugs"]
        L += [f"### Receiver {r['name']}", "", fig(f"bugs_{slug}.png", plots.bug_detection, r, res), "",
              "| budget | k | " + " | ".join("A (control)" if v == "none" else v for v in vs) + " |",
              "|---|---|" + "---|" * len(vs)]
        for row in r["budgets"]:
            L += [f"| {row['budget']} | {row['k']} | "
                  + " | ".join(f"{row['variants'][v]['rejections']}/{row['variants'][v]['tests']}" for v in vs) + " |"]
        c = r["summary"]["none"]["pooled"]
        L += ["", f"Control over all budgets: {c['rejections']}/{c['tests']} rejected, {_ci(c, 4)}; binomial test "
                  f"of rate = alpha: {_p(c['binom_pvalue'])}.", ""]
    L += _details("R-style output of 3.4", transcript)
    return L


def sampler_bugs(res: Dict[str, Any], fig, transcript: str) -> List[str]:
    depth = "about 2 n^0.4 cells per size (Mann and Wald)" if not res["depth"] else f"2^{res['depth']} cells"
    L = ["## 3.2+ Planted sampler bugs: chi-squared against K-S (beyond the paper)", "",
         "libmcest plants four bugs in the BRDF samplers' half-vector warps, while the density the sampler claims "
         "stays the correct one: *roughness* (the lobe 10% too wide), *axes_swapped* (anisotropy axes swapped), "
         "*phi_half* (azimuth over half its range), *jacobian* (the sin theta of d omega forgotten in the polar warp: "
         "a half-normal instead of a Rayleigh polar radius). The same n directions are tested two ways: "
         f"**chi-squared**, Pearson's test of the counts in {depth} of nearly equal probability under the claimed "
         "density (cells are a k-d tree in the equal-area square of the Morton keys; each cell's probability by "
         "cubature; cells with expected counts below 5 pooled with their neighbours), a one-sample test that needs "
         "the density; and **K-S**, Canner's two-sample test of the directions' Morton keys against n directions "
         "of the correct sampler, the route of section 3.2, which needs only a trusted sampler. "
         f"alpha = {res['alpha']:g}, {res['runs']} runs per size; a route detects a bug from the size on which it "
         f"rejects in at least {res['detected_threshold']:.0%} of the runs. The rate with no bug is each route's "
         "size, which should be about alpha.", ""]
    for b in res["brdfs"]:
        vs = ["none"] + res["bugs"]
        L += [f"### {b['name']}", "", fig(f"sampler_bugs_{b['name']}.png", plots.sampler_bug_power, b, res), "",
              "| n | cells | " + " | ".join("no bug (size)" if v == "none" else v for v in vs) + " |",
              "|---|---|" + "---|" * len(vs)]
        for row in b["sizes"]:
            L += [f"| {row['n']} | {2 ** row['depth']} | "
                  + " | ".join(f"{row['variants'][v]['chisq']['rejections']} / {row['variants'][v]['ks']['rejections']}"
                               for v in vs) + " |"]
        L += ["", f"(each entry: rejections of {res['runs']} by chi-squared / by K-S)", ""]
        L += ["| bug | chi-squared detects from | K-S detects from |", "|---|---|---|"]
        for v in res["bugs"]:
            s = b["summary"][v]
            L += [f"| {v} | " + " | ".join(
                f"n = {s[r]['detected_from']}" if s[r]["detected_from"] is not None else
                f"not reliably ({s[r]['rate_at_largest']:.0%} at the largest n)" for r in ("chisq", "ks")) + " |"]
        L += [""]
        for r, label in (("chisq", "chi-squared"), ("ks", "K-S")):
            s = b["size_check"][r]
            L += [f"Size check, {label}: the correct sampler was rejected in {s['rejections']}/{s['tests']} tests, "
                  f"{_ci(s, 4)}; binomial test of rate = alpha: {_p(s['binom_pvalue'])}.", ""]
        cells = "; ".join(f"depth {c['depth']}: probabilities {c['prob_min']:.3g}..{c['prob_max']:.3g}, sum - 1 = "
                          f"{c['sum_minus_one']:.1g}" for c in b["cells"])
        L += [f"Cells: {cells}.", ""]
    L += _details("R-style output of 3.2+", transcript)
    return L


def timing(res: Dict[str, Any], fig, transcript: str) -> List[str]:
    L = ["## Error against run time", "",
         f"Wall-clock times on {res['threads']} thread(s) of the machine that ran this report; on a shared machine "
         "they can be off by tens of percent. The errors themselves are reproducible.", ""]
    irr = res.get("irradiance")
    if irr:
        what = "RMSE against Lambert's formula" if irr["lambert"] is not None else "estimated standard error"
        L += [f"### Irradiance estimators at {irr['receiver']}", "",
              f"{what} of the mean of n primary estimates against the median wall time of one such estimate, "
              f"n = {', '.join(str(r['n']) for r in next(iter(irr['estimators'].values()))['rows'])}, "
              f"{res['reps']} estimates each. Dashed: sigma sqrt(t1 / T), the ideal slope -1/2 of an unbiased "
              "estimator with sigma and t1 (time per primary estimate) measured at the largest n; where points lie "
              "right of it, a fixed cost per call (Python, thread start) dominates.", "",
              fig("error_time.png", plots.error_time, irr), "",
              "| estimator | sigma per primary | time per primary (ns) | efficiency 1/(sigma^2 t1) (1/s) | "
              f"{what} at the largest n |", "|---|---|---|---|---|"]
        for m, e in irr["estimators"].items():
            last = e["rows"][-1]
            err = last["rmse"] if irr["lambert"] is not None else last["se_estimated"]
            L += [f"| {m} | {e['sigma_primary']:.4g} | {e['wall_per_primary'] * 1e9:.3g} | "
                  f"{_g(e['efficiency'])} | {_g(err)} |"]
        L += [""]
        comp = irr.get("comparisons")
        if comp and comp["tests"]:
            L += ["Is the difference in efficiency real? `mcstat.efficiency_test` on "
                  f"{comp['batches']} timed batches of {comp['batch_size']} primary estimates per estimator, "
                  "interleaved so that the machine's load affects all of them: the ratio of efficiencies "
                  f"eff({comp['reference']}) / eff(other) with its 95% confidence interval (delta method on the "
                  "variances, without assuming normal data, and on the batches' times; a t on Satterthwaite's "
                  "degrees of freedom). A ratio above 1 favours "
                  f"{comp['reference']}.", "",
                  "| comparison | ratio of efficiencies | 95% CI | variance ratio | time ratio | p-value | decision |",
                  "|---|---|---|---|---|---|---|"]
            for t in comp["tests"]:
                if "error" in t:
                    L += [f"| {t['x']} / {t['y']} | no test: {t['error']} | | | | | |"]
                    continue
                L += [f"| {t['x']} / {t['y']} | {t['ratio']:.3g} | [{t['conf_int'][0]:.3g}, {t['conf_int'][1]:.3g}] | "
                      f"{t['var_ratio']:.3g} | {t['time_ratio']:.3g} | {_p(t['pvalue'])} | {t['decision']} |"]
            L += [""]
    ks = res.get("ks")
    if ks:
        L += ["### Simulated K-S p-values", "",
              f"{ks['size']} + {ks['size']} directions from {ks['brdf']}'s exact sampler (so H0 holds), exact "
              f"p-value {ks['exact_pvalue']:.4g}; each row repeats the simulation with fresh seeds.", "",
              fig("ks_error_time.png", plots.ks_error_time, ks), "",
              "| n_sim | RMS error | sqrt(p(1-p)/n_sim) | mean reported s.e. | time per test (ms) |",
              "|---|---|---|---|---|"]
        for r in ks["rows"]:
            L += [f"| {r['n_sim']} | {r['rms_error']:.3g} | {r['predicted_se']:.3g} | {r['mean_reported_se']:.3g} | "
                  f"{r['wall_median'] * 1e3:.3g} |"]
        L += [""]
    L += _details("Text output of the timing study", transcript)
    return L


def renderer_check(res: Dict[str, Any], fig, transcript: str) -> List[str]:
    L = ["## The renderer's test kit on planted bugs (beyond the paper)", "",
         "Each BRDF is handed to `mcstat.check_bsdf` as a renderer hands over its own: `sample(wi, u)` returning "
         "directions, weights f cos / pdf and the pdf it claims, `eval` (f cos) and `pdf`. One bug per class is "
         "planted: libmcest's sampler bugs (the directions' distribution wrong, pdf and weight those of the correct "
         "BRDF), `pdf()` 10% high on the half of the sphere on one side of the plane through the normal and the "
         "mirror direction (half the specular lobe), `eval()` 10% high there (the weight still right), the weight "
         "10% high there. "
         f"n = {res['n']} samples per check, alpha = {res['alpha']:g} for the whole battery, {res['runs']} checks "
         "per variant. With no bug the rate is the battery's false-rejection rate, which must not exceed alpha "
         "(binomial p of the count against alpha).", ""]
    for b in res["brdfs"]:
        L += [f"### {b['name']}", "", "| variant | rejected | rate [95% CI] | routes that rejected |",
              "|---|---|---|---|"]
        for row in b["variants"]:
            routes = ", ".join(f"{k} {c}" for k, c in sorted(row["by_route"].items())) or "-"
            ci = row["ci95"]
            L += [f"| {'no bug' if row['variant'] == 'none' else row['variant']} | {row['rejections']}/{row['tests']} "
                  f"| {row['rate']:.2f} [{ci[0]:.2f}, {ci[1]:.2f}] | {routes} |"]
        none = next(r for r in b["variants"] if r["variant"] == "none")
        L += ["", f"Correct BRDF: {none['rejections']}/{none['tests']} rejected, binomial test of rate = alpha: "
                  f"{_p(none['binom_pvalue'])}.", ""]
    L += ["Mitsuba 3's BSDFs against Mitsuba's own `ChiSquareTest`: `examples/mitsuba/RESULTS.md`.", ""]
    L += _details("check reports (run 0 of each planted bug)", transcript)
    return L
