# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Beyond the paper: equivalence and sample size in section 3.1.

The paper's one-sample t test can only fail to find a bias; it never shows
that an estimator's bias is small.  Where Lambert's formula gives the
exact irradiance E (one triangle), for every estimator:

- equivalence (TOST, ``mcstat.equivalence_test``) of the pooled secondary
  estimates with E, for each margin in :data:`MARGINS` (relative to E):
  "equivalent" is evidence that |bias| < margin * E;
- the sample size (``mcstat.power``, one-sample t) needed to detect a bias
  of each size in :data:`BIASES` (relative to E) at power :data:`POWER`,
  from the estimator's measured standard deviation of one primary
  estimate: s.d.(secondary) x sqrt(k).

Nothing is drawn: the study reuses section 3.1's estimates, so the
results are as deterministic as that section's.
"""
from __future__ import annotations

import math
from typing import Any, Dict, List

import numpy as np

import mcstat
from .context import Context

MARGINS = (0.01, 0.001)  # equivalence margins, relative to E
BIASES = (0.01, 0.001)   # biases to detect, relative to E
POWER = 0.9

WHAT = (f"equivalence (TOST) of each estimator with Lambert's formula, margins "
        f"{' and '.join(f'{m:.1%}' for m in MARGINS)} of E; primary estimates needed to detect a "
        f"{' / '.join(f'{b:.1%}' for b in BIASES)} bias at power {POWER:g}, from each estimator's measured variance")


def analyse(ctx: Context, pooled: Dict[str, np.ndarray], E: float, k: int, alpha: float) -> Dict[str, Any]:
    """TOST and sample sizes for the pooled secondary estimates of each estimator."""
    res: Dict[str, Any] = dict(margins=list(MARGINS), biases=list(BIASES), power=POWER, alpha=alpha,
                               estimators={})
    ctx.print(f"\nEquivalence with Lambert's formula (TOST on the pooled secondary estimates, alpha = {alpha:g}) "
              f"and primary estimates needed to detect a bias at power {POWER:g}:")
    ctx.print(f"{'':3}{'mean - E':>12}{'(rel.)':>11}   " + "".join(f"{'|bias| < ' + format(m, '.1%'):>22}"
                                                                    for m in MARGINS)
              + "".join(f"{'n for ' + format(b, '.1%'):>16}" for b in BIASES))
    for m, x in pooled.items():
        e: Dict[str, Any] = dict(n_secondary=int(x.size), n_primary=int(x.size) * k)
        sd_primary = float(np.std(x, ddof=1)) * math.sqrt(k)
        e["sd_primary_estimated"] = sd_primary
        e["mean"] = float(np.mean(x))
        e["bias_relative"] = (e["mean"] - E) / E
        eq: List[Dict[str, Any]] = []
        for margin in MARGINS:
            try:
                t = mcstat.equivalence_test(x, mu=E, margin=margin * E, alpha=alpha)
            except mcstat.McstatError as err:  # e.g. an estimator whose secondary estimates are all equal
                eq.append(dict(margin=margin, error=f"{type(err).__name__}: {err}"))
                continue
            eq.append(dict(margin=margin, equivalent=t.equivalent, pvalue=t.pvalue, conf_int=list(t.conf_int),
                           conf_int_relative=[(c - E) / E for c in t.conf_int], statistics=list(t.statistics),
                           pvalues=list(t.pvalues), df=t.df, text=str(t)))
        e["equivalence"] = eq
        need: List[Dict[str, Any]] = []
        for b in BIASES:
            if not sd_primary > 0:
                need.append(dict(bias=b, n_primary=None, reason="zero measured variance"))
                continue
            d = b * E / sd_primary
            p = mcstat.power("t", effect=d, power=POWER, alpha=alpha)
            need.append(dict(bias=b, effect=d, n_primary=int(p.n), achieved_power=p.power))
        e["sample_size"] = need
        res["estimators"][m] = e
        cells = "".join(f"{('yes' if q.get('equivalent') else 'no') + (' (p = ' + format(q['pvalue'], '.2g') + ')' if 'pvalue' in q else ' (failed)'):>22}"
                        for q in eq)
        ns = "".join(f"{(format(q['n_primary'], '.4g') if q['n_primary'] else '-'):>16}" for q in need)
        ctx.print(f"{m:3}{e['mean'] - E:>12.4g}{e['bias_relative']:>11.2e}   {cells}{ns}")
    ctx.print(f"(the runs pooled {next(iter(res['estimators'].values()))['n_primary'] if res['estimators'] else 0} "
              "primary estimates per estimator; 'n for x%' is the number of primary estimates a one-sample t test "
              f"needs to detect a bias of x% of E with probability {POWER:g} at alpha, given the measured variance)")
    return res


def findings(where: str, eq: Dict[str, Any]) -> List[str]:
    out = []
    for margin in eq["margins"]:
        shown = [m for m, e in eq["estimators"].items()
                 for q in e["equivalence"] if q["margin"] == margin and q.get("equivalent")]
        out.append(f"{where}: bias shown smaller than {margin:.1%} of E (TOST at alpha = {eq['alpha']:g}) for "
                   + (", ".join(shown) if shown else "no estimator") + ".")
    for b in eq["biases"]:
        parts = [f"{m} {q['n_primary']:.3g}" for m, e in eq["estimators"].items()
                 for q in e["sample_size"] if q["bias"] == b and q["n_primary"]]
        if parts:
            out.append(f"{where}: primary estimates needed to detect a {b:.1%} bias at power {eq['power']:g}: "
                       + ", ".join(parts) + ".")
    return out
