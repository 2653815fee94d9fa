# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The planner: which studies and tests a scene calls for, and why not the others.

Rules (the issue's, in code):

- Section 3.1 runs at every receiver that sees an emitter.  One-sample
  tests against Lambert's formula only where an analytic value exists: a
  scene of exactly one (hence unoccluded) triangle.  With several triangles
  each estimator is run per triangle and summed, and the estimators are
  compared with the trusted one (two-sample tests) instead.  The figure-4
  matrix compares every pair of the listed estimators.
- Section 3.4 needs estimator A (where the bugs are planted) and a trusted
  estimator other than A.
- Sections 3.2 and 3.3 need BRDFs (those listed for each study), and so
  does the comparison of the chi-squared and K-S routes on planted
  sampler bugs (3.2+, beyond the paper).
- The timing study times the listed estimators at the first receiver that
  sees an emitter (RMSE against Lambert with one triangle, else the
  estimated standard error), and the K-S simulation when 3.2 runs.
- The sequential tests (3.4+, beyond the paper) need what 3.4 needs and run
  at the first receiver that sees an emitter.
- ``enabled = false`` leaves a study out.

``--quick`` caps the expensive budgets (see :data:`QUICK`); the plan says
what it changed.
"""
from __future__ import annotations

import copy
from typing import Any, Dict, List, Optional

from mcstat import estimators as est
from .scene import Scene
from .studies import BY_KEY


def equivalence_what() -> str:
    from .equivalence import WHAT  # equivalence.py imports the package; plan.py stays light
    return WHAT


#: --quick: (study, field, cap); list fields keep the values <= cap (at least the first).
QUICK = [
    ("sampling", "sizes", 10000),
    ("sampling", "runs", 10),
    ("sampling", "histogram_size", 20000),
    ("radiance", "directions", 200),
    ("bugs", "runs", 40),
    ("timing", "budgets", 100000),
    ("timing", "reps", 6),
    ("timing", "ks_n_sim", 9999),
    ("timing", "ks_reps", 5),
    ("timing", "eff_batches", 12),
    ("timing", "eff_batch_size", 50000),
    ("diagnostics", "n", 20000),
    ("sampler_bugs", "sizes", 3000),
    ("sampler_bugs", "runs", 20),
    ("renderer_check", "n", 20000),
    ("renderer_check", "runs", 5),
    ("sequential", "runs", 40),
    ("sequential", "h0_runs", 500),
    ("sequential", "pilot", 200000),
]


class Plan:
    """What a run will do: ``steps`` and ``left_out`` (each a dict with
    study, section, target, what [, reason]), the effective study
    parameters ``params`` (quick caps applied) and per receiver the exact
    irradiance of each triangle."""

    def __init__(self, scene: Scene, quick: bool = False) -> None:
        self.scene = scene
        self.quick = quick
        self.params: Dict[str, Dict[str, Any]] = copy.deepcopy(scene.studies)
        self.quick_changes: List[str] = []
        if quick:
            self._apply_quick()
        self.steps: List[Dict[str, Any]] = []
        self.left_out: List[Dict[str, Any]] = []
        self.receivers: List[Dict[str, Any]] = []
        for i, r in enumerate(scene.receivers):
            exact = [est.irradiance_exact(triangle=t, point=r["point"], normal=r["normal"], radiance=float(L))
                     for t, L in zip(scene.triangles, scene.radiances)]
            self.receivers.append(dict(index=i, name=r["name"], exact_per_triangle=exact,
                                       visible=any(e > 0 for e in exact),
                                       lambert=exact[0] if scene.n_emitters == 1 else None))
        self._irradiance()
        self._brdf_study("sampling", "K-S tests (Canner's weight) of the sampler against exact rejection "
                                     "sampling on Morton keys, a power curve and 2-D histograms")
        self._brdf_study("radiance", "Welch tests of BRDF sampling against rejection sampling at many "
                                     "outgoing directions, and a binomial test of the fraction of equal means")
        self._bugs()
        self._brdf_study("sampler_bugs", "each BRDF's sampler with each planted bug (and without: the size check), "
                                         "chi-squared on equal-probability cells of the claimed density against K-S "
                                         "(Canner) of Morton keys against the correct sampler: power curves")
        self._brdf_study("renderer_check", "mcstat.check_bsdf on each BRDF with one planted bug of each class "
                                           "(sampler, pdf, eval, weight) and without: rejection rates and routes")
        self._sequential()
        self._timing()
        self._diagnostics()

    # -- helpers ---------------------------------------------------------------
    def _apply_quick(self) -> None:
        for study, field, cap in QUICK:
            p = self.params[study]
            old = p[field]
            if isinstance(old, list):
                new = [x for x in old if x <= cap] or old[:1]
                if new != old:
                    dropped = [x for x in old if x not in new]
                    self.quick_changes.append(f"studies.{study}.{field}: {', '.join(map(str, dropped))} dropped "
                                              f"(quick keeps values <= {cap})")
            else:
                new = min(old, cap)
                if new != old:
                    self.quick_changes.append(f"studies.{study}.{field}: {old} -> {new}")
            p[field] = new

    def _add(self, study: str, target: str, what: str) -> None:
        self.steps.append(dict(study=study, section=BY_KEY[study].section, target=target, what=what))

    def _leave(self, study: str, target: str, what: str, reason: str) -> None:
        self.left_out.append(dict(study=study, section=BY_KEY[study].section, target=target, what=what, reason=reason))

    def runs(self, study: str, target: Optional[str] = None) -> bool:
        return any(s["study"] == study and (target is None or s["target"] == target) for s in self.steps)

    def visible_receivers(self) -> List[Dict[str, Any]]:
        return [r for r in self.receivers if r["visible"]]

    def brdfs_for(self, study: str) -> List[str]:
        return [s["target"] for s in self.steps if s["study"] == study]

    # -- the rules -------------------------------------------------------------
    def _disabled(self, study: str) -> bool:
        if not self.params[study]["enabled"]:
            self._leave(study, "all", BY_KEY[study].title, f"disabled in the scene (studies.{study}.enabled = false)")
            return True
        return False

    def _irradiance(self) -> None:
        if self._disabled("irradiance"):
            return
        sc, p = self.scene, self.params["irradiance"]
        ests = ", ".join(sc.estimators)
        k = p["primary"] // p["secondary"]
        for r in self.receivers:
            if not r["visible"]:
                self._leave("irradiance", r["name"], "all irradiance tests",
                            "no emitter is above this receiver's horizon (Lambert's formula gives 0 for every "
                            "triangle): every estimator returns 0 and there is nothing to test")
                continue
            if sc.n_emitters == 1:
                self._add("irradiance", r["name"],
                          f"one-sample t tests of {ests} against Lambert's formula (E = {r['lambert']:.6g}); "
                          f"{p['runs']} runs of {p['secondary']} secondary estimates (means of k = {k})")
                if p["alpha"] < 0.5:
                    self._add("irradiance", r["name"], equivalence_what())
                else:
                    self._leave("irradiance", r["name"], "equivalence and sample sizes",
                                f"alpha = {p['alpha']:g}: an equivalence test needs alpha < 0.5 (its interval has "
                                "level 1 - 2 alpha)")
            else:
                self._leave("irradiance", r["name"], "one-sample tests against Lambert's formula",
                            f"the scene has {sc.n_emitters} emitter triangles: Lambert's formula is exact for one "
                            "unoccluded triangle, and nothing here checks that the triangles do not occlude one "
                            f"another, so no analytic value is trusted; the estimators are compared with the "
                            f"trusted estimator {sc.trusted} (each run per triangle and summed) instead")
                self._leave("irradiance", r["name"], "equivalence with Lambert's formula and sample sizes",
                            "they are stated relative to the exact irradiance, which a scene of several triangles "
                            "does not have")
            if len(sc.estimators) >= 2:
                self._add("irradiance", r["name"],
                          f"figure-4 matrix: Welch and F tests of every pair of {ests}, {p['runs']} runs; "
                          "histograms of the secondary estimates; the variance ordering"
                          + ("" if sc.n_emitters == 1 else f"; equal means with the trusted {sc.trusted}"))
            else:
                self._add("irradiance", r["name"],
                          f"figure-4 matrix of {ests} against itself (the scene lists one estimator); histograms")
                self._leave("irradiance", r["name"], "comparisons between estimators and their variance ordering",
                            "the scene lists only one estimator")

    def _bugs(self) -> None:
        if self._disabled("bugs"):
            return
        sc = self.scene
        if "A" not in sc.estimators:
            self._leave("bugs", "all", BY_KEY["bugs"].title,
                        "the scene does not list estimator A, in which the paper plants the three bugs")
            return
        if sc.trusted == "A":
            self._leave("bugs", "all", BY_KEY["bugs"].title,
                        "the trusted estimator is A itself; list another estimator (S in the paper) as `trusted`")
            return
        p = self.params["bugs"]
        for r in self.receivers:
            if not r["visible"]:
                self._leave("bugs", r["name"], BY_KEY["bugs"].title, "no emitter is above this receiver's horizon")
                continue
            self._add("bugs", r["name"],
                      f"A with {', '.join(p['bugs'])} (and without, as a control) against {sc.trusted}: "
                      f"Welch tests at budgets {p['budgets'][0]}..{p['budgets'][-1]}, {p['runs']} runs each")

    def _sequential(self) -> None:
        if self._disabled("sequential"):
            return
        sc, title = self.scene, BY_KEY["sequential"].title
        if "A" not in sc.estimators or sc.trusted == "A":
            self._leave("sequential", "all", title,
                        "the scene does not list estimator A, in which the bugs are planted" if "A" not in sc.estimators
                        else "the trusted estimator is A itself; list another estimator as `trusted`")
            return
        vis = self.visible_receivers()
        if not vis:
            self._leave("sequential", "all", title, "no receiver sees an emitter")
            return
        p = self.params["sequential"]
        B = p["batch"]
        nmax = max(1, p["max_n"] // B) * B
        self._add("sequential", vis[0]["name"],
                  f"A with {', '.join(p['bugs'])} against {sc.trusted}: anytime-valid sequential tests at alpha = "
                  f"{p['alpha']:g}, a look every {B} primary estimates up to {nmax}, {p['runs']} runs each; the "
                  f"fixed-n Welch test at power {p['power']:g}; under H0 (the correct A) {p['h0_runs']} runs against "
                  "a fixed-n test peeked at every look")

    def _brdf_study(self, study: str, what: str) -> None:
        if self._disabled(study):
            return
        sc = self.scene
        if not sc.brdfs:
            self._leave(study, "all", BY_KEY[study].title, "the scene has no BRDFs")
            return
        listed = self.params[study]["brdfs"]
        for b in sc.brdfs:
            if b["name"] in listed:
                self._add(study, b["name"], what)
            else:
                self._leave(study, b["name"], BY_KEY[study].title, f"not listed in studies.{study}.brdfs")

    def _timing(self) -> None:
        if self._disabled("timing"):
            return
        sc = self.scene
        vis = self.visible_receivers()
        if not vis:
            self._leave("timing", "estimators", "error of the irradiance estimators against run time",
                        "no receiver sees an emitter")
        elif sc.n_emitters == 1:
            self._add("timing", "estimators", f"RMSE against Lambert's formula against wall time, at "
                                              f"{vis[0]['name']}: {', '.join(sc.estimators)}")
        else:
            self._add("timing", "estimators", f"estimated standard error against wall time, at {vis[0]['name']}: "
                                              f"{', '.join(sc.estimators)}")
            self._leave("timing", "estimators", "RMSE against Lambert's formula",
                        f"the scene has {sc.n_emitters} triangles and so no trusted analytic value; the standard "
                        "error estimated from the samples is shown instead")
        if self.runs("sampling"):
            self._add("timing", "ks", f"simulated K-S p-value error against run time, {self.params['timing']['ks_size']}"
                                      f" + {self.params['timing']['ks_size']} directions of "
                                      f"{self.brdfs_for('sampling')[0]}")
        else:
            self._leave("timing", "ks", "simulated K-S p-value error against run time",
                        "section 3.2 does not run, so there are no direction samples to test")

    def _diagnostics(self) -> None:
        """Shape, tails and batch size of every estimator the other
        studies test (irradiance at each receiver that sees an emitter; both
        reflected-radiance estimators of the BRDFs section 3.3 tests)."""
        if self._disabled("diagnostics"):
            return
        sc, n = self.scene, self.params["diagnostics"]["n"]
        for r in self.receivers:
            if not r["visible"]:
                self._leave("diagnostics", r["name"], "diagnostics of the irradiance estimators",
                            "no emitter is above this receiver's horizon: every estimator returns 0")
                continue
            self._add("diagnostics", r["name"], f"skewness, kurtosis, tail index, normality of batch means and "
                                                f"recommended batch size of {', '.join(sc.estimators)} ({n} primary "
                                                "estimates each)")
        if not sc.brdfs:
            self._leave("diagnostics", "BRDFs", "diagnostics of the reflected-radiance estimators",
                        "the scene has no BRDFs")
            return
        tested = self.brdfs_for("radiance")
        for b in sc.brdfs:
            if b["name"] in tested:
                self._add("diagnostics", b["name"], f"the same for BRDF sampling and rejection sampling of the "
                                                    f"reflected radiance at the BRDF's outgoing direction ({n} each)")
            else:
                self._leave("diagnostics", b["name"], "diagnostics of the reflected-radiance estimators",
                            "section 3.3 does not test this BRDF")

    # -- output ----------------------------------------------------------------
    def to_dict(self) -> Dict[str, Any]:
        return dict(quick=self.quick, quick_changes=self.quick_changes, params=self.params, steps=self.steps,
                    left_out=self.left_out,
                    receivers=[dict(index=r["index"], name=r["name"], visible=r["visible"], lambert=r["lambert"],
                                    exact_per_triangle=r["exact_per_triangle"]) for r in self.receivers])

    def text(self) -> str:
        sc = self.scene
        lines = [f"scene {sc.name!r} ({sc.source}): {sc.n_emitters} emitter triangle{'s' * (sc.n_emitters != 1)}, "
                 f"{len(sc.receivers)} receiver{'s' * (len(sc.receivers) != 1)}, estimators "
                 f"{', '.join(sc.estimators)} (trusted {sc.trusted}), "
                 + (f"BRDFs {', '.join(b['name'] for b in sc.brdfs)}" if sc.brdfs else "no BRDFs")]
        if self.quick:
            lines.append("quick mode: " + ("\n  ".join([""] + self.quick_changes) if self.quick_changes
                                           else "no budget changed"))
        lines.append("will run:")
        for s in self.steps:
            lines.append(f"  [{s['section']}] {s['target']}: {s['what']}")
        if self.left_out:
            lines.append("left out:")
            for s in self.left_out:
                lines.append(f"  [{s['section']}] {s['target']}: {s['what']}: {s['reason']}")
        else:
            lines.append("left out: nothing")
        return "\n".join(lines)
