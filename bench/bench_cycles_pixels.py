"""Per-image false alarms and power of mcstat.image.compare's per-pixel
(and block) tests on real Cycles renders, with and without the
render guards (report only: writes bench/RESULTS_cycles_pixels.md,
asserts nothing).

The renders come from bench/cycles_render.py (Blender's `bpy` module,
its own venv): one float32 stack (N, H, W, 3) per setting, each setting
rendered with its own seeds (disjoint).  Unbiased pairs: light tree off
against on ("lt_off" vs "base"), path guiding on against off ("guide_on"
vs "base"), and a control: "base" against itself (disjoint seeds).  For
each K in {4, 8, 16} the N seeds are cut into N // K groups: comparison j
tests group j of the reference against group j of the candidate (the
control: group 2j against group 2j + 1), luminance, BH at alpha = 0.05,
two-sided.  A per-image false alarm is any test flagged.

Planted changes ("light_x1.02", "albedo_x1.05" against "base"): the
fraction of comparisons with any flag and the fraction of the changed
region flagged.  The light's region: pixels that take at least 90% of
their light from the changed lights (the "lamp_off" stack's mean over
the base's, all seeds), whose expected change is at least 1.8%; the
albedo's: the pixels where the changed surface is seen ("mask_albedo").
Block tests (--blocks, default 8 and 16 pixels a side) alongside.

Flagged pixels are classed by their K values per side, the first that
fits: "both constant" (each side constant, the two different),
"one side constant" (all zeros or not), "one nonzero" (a side with
exactly one nonzero value), "zeros" (a side with zeros and >= 2 nonzero
values), "spike" (no zeros; a side's largest value is more than half its
sum: a firefly), "smooth" (the rest).

    /work/main/.venv/bin/python bench/bench_cycles_pixels.py \\
        [--cache /work/cycles-cache] [--runs 4:64,16:64,256:32] [--blocks 8,16] \\
        [--out bench/RESULTS_cycles_pixels.md]
"""
import argparse
import json
import os
import platform
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

W = np.array([0.2126, 0.7152, 0.0722])  # mcstat's luminance weights (Rec. 709)
CLASSES = ("both constant", "one side constant", "one nonzero", "zeros", "spike", "smooth")
PAIRS = (("light tree off vs on", "base", "lt_off"),
         ("path guiding on vs off", "base", "guide_on"),
         ("control: base vs base", "base", "base"))
KS = (4, 8, 16)


def clopper(x, n, conf=0.95):
    from scipy import stats
    lo = stats.beta.ppf((1 - conf) / 2, x, n - x + 1) if x > 0 else 0.0
    hi = stats.beta.ppf(1 - (1 - conf) / 2, x + 1, n - x) if x < n else 1.0
    return float(lo), float(hi)


def rate(x, n):
    lo, hi = clopper(x, n)
    return f"{x}/{n} = {x / n:.3f} [{lo:.3f}, {hi:.3f}]"


def groups(ref_name, cand_name, stacks, k):
    """(reference, candidate) seed groups of size k, disjoint seeds."""
    r, c = stacks[ref_name], stacks[cand_name]
    if ref_name == cand_name:
        g = r.shape[0] // (2 * k)
        return [(r[2 * j * k:(2 * j + 1) * k], r[(2 * j + 1) * k:(2 * j + 2) * k]) for j in range(g)]
    g = min(r.shape[0], c.shape[0]) // k
    return [(r[j * k:(j + 1) * k], c[j * k:(j + 1) * k]) for j in range(g)]


def classify(lr, lc):
    """lr, lc: (K, n) luminance of the flagged pixels per side -> class index per pixel."""
    out = np.full(lr.shape[1], len(CLASSES) - 1)
    k = lr.shape[0]
    cr, cc = np.ptp(lr, axis=0) == 0, np.ptp(lc, axis=0) == 0
    nzr, nzc = (lr != 0).sum(0), (lc != 0).sum(0)
    one = (nzr == 1) | (nzc == 1)
    zeros = ((nzr < k) & (nzr >= 2)) | ((nzc < k) & (nzc >= 2))

    def spike(s):
        tot = np.abs(s).sum(0)
        return (np.abs(s).max(0) > 0.5 * tot) & (tot > 0)
    out[spike(lr) | spike(lc)] = 4
    out[zeros] = 3
    out[one] = 2
    out[cr ^ cc] = 1
    out[cr & cc] = 0
    return out


def compare(ref, cand, guards, block=None):
    import mcstat.image as mi
    return mi.compare(ref, cand, seed_axis=0, alpha=0.05, method="BH", render_guards=guards, block=block)


SCALE = 0.05  # emulated fix 2: a side's spread counted at this fraction of |difference of means|


def degenerate_at_scale(lr, lc, c=SCALE):
    """(H, W): a side shows at most one value farther than c |d| from its
    median (d the difference of the means): constant, or at most one
    outlier, at the scale of the difference."""
    d = np.abs(lr.mean(0) - lc.mean(0))
    out = np.zeros(d.shape, bool)
    for s in (lr, lc):
        far = np.abs(s - np.median(s, axis=0)) > c * d
        out |= far.sum(0) <= 1
    return out


def flags(res, variant, lr=None, lc=None):
    """The flagged tests of a result (luminance: (H, W)).
    "pixel": as compare says.
    "emulated": the guards' result with the tests that MCSTAT_PIXELS_RENDER
    calls deterministic differences (constant on both sides, statistic
    +-inf) left untested before BH: what fix 1 (the rule-of-three floor on
    both constant sides, as on one) would give, as no such test could
    then be significant alone.
    "emulated2": also the tests where a side is degenerate at the scale of
    the difference (degenerate_at_scale: fix 2, the same floor for them)
    left untested.  Emulations in this script, not libmcstat's behaviour."""
    if variant == "pixel":
        return res.padjusted[..., 0] <= 0.05
    import mcstat
    drop = np.isinf(res.statistic)
    if variant == "emulated2":
        drop = drop | degenerate_at_scale(lr, lc)[..., None]
    p = np.where(drop, np.nan, res.pvalue)
    return mcstat.p_adjust(p, method="BH")[..., 0] <= 0.05


def fmt_vals(v):
    return " ".join(f"{x:.3g}" for x in v)


def atoms(v):
    """How a pixel's values over all seeds of a setting are distributed:
    the share of zeros and the most frequent nonzero values."""
    z = float(np.mean(v == 0))
    vals, cnt = np.unique(v[v != 0], return_counts=True)
    top = np.argsort(-cnt)[:3]
    return (f"{v.size} seeds: {z:.0%} zero, {vals.size} distinct nonzero values, the commonest "
            + ", ".join(f"{vals[i]:.3g} ({cnt[i] / v.size:.0%})" for i in top))


VARIANTS = (("before", False, "pixel"), ("after", True, "pixel"), ("after, fix 1 emulated", True, "emulated"),
            ("after, fixes 1+2 emulated", True, "emulated2"))


def run(a, spp, size, blocks):
    """The sections of the results file for one (samples per pixel, size);
    pairs whose stacks were not rendered are left out."""
    tag = f"{spp}spp_{size}x{size}"
    names = ("base", "lt_off", "guide_on", "light_x1.02", "albedo_x1.05", "lamp_off")
    stacks = {n: np.ascontiguousarray(np.load(os.path.join(a.cache, f"{n}_{tag}.npy")), dtype=np.float32)
              for n in names if os.path.exists(os.path.join(a.cache, f"{n}_{tag}.npy"))}
    mask = np.load(os.path.join(a.cache, f"mask_albedo_{tag}.npy")) > 0.5
    with open(os.path.join(a.cache, f"meta_{tag}.json")) as f:
        meta = json.load(f)
    lum = {n: v @ W for n, v in stacks.items()}
    summ = []
    base_mean, lamp_off_mean = lum["base"].mean(0), lum["lamp_off"].mean(0)
    lit = base_mean > 0
    share = np.where(lit, lamp_off_mean / np.where(lit, base_mean, 1), 0)
    light_region = lit & (share >= 0.9)
    n_seeds = {n: v.shape[0] for n, v in stacks.items()}
    cmd = (f"    /work/bpy-venv/bin/python bench/cycles_render.py --seeds {n_seeds['base']} --spp {spp} "
           f"--size {size} --cache {a.cache} \\\n"
           f"        --settings {','.join(stacks)},mask_albedo")

    # ---- how render-like the pixels are
    scene = ["| K | side | pixels never nonzero (all seeds) | a group all zeros (mean over groups) | "
             "one nonzero | zeros and >= 2 nonzero | no zeros |", "|---|---|---|---|---|---|---|"]
    for k in KS:
        for n in [n for n in ("base", "lt_off", "guide_on") if n in stacks]:
            lb = lum[n]
            g = lb.shape[0] // k
            nz = np.stack([(lb[j * k:(j + 1) * k] != 0).sum(0) for j in range(g)])
            scene.append(f"| {k} | {n} | {int((lb == 0).all(0).sum())} | "
                         f"{((nz == 0) & lit).sum(axis=(1, 2)).mean():.0f} | "
                         f"{(nz == 1).sum(axis=(1, 2)).mean():.0f} | "
                         f"{((nz >= 2) & (nz < k)).sum(axis=(1, 2)).mean():.0f} | "
                         f"{(nz == k).sum(axis=(1, 2)).mean():.0f} |")

    # ---- false alarms on unbiased pairs
    head = " | ".join(f"per pixel, {v[0]}" for v in VARIANTS)
    bhead = " | ".join(f"block={b}, {w}" for b in blocks for w in ("before", "after"))
    fa = [f"| pair | K | comparisons | {head} | {bhead} |", "|---" * (3 + len(VARIANTS) + 2 * len(blocks)) + "|"]
    cl = ["| pair | K | " + " | ".join(f"flagged pixels, {v[0]}" for v in VARIANTS) + " |",
          "|---" * (2 + len(VARIANTS)) + "|"]
    examples = []
    for title, rn, cn in [p for p in PAIRS if p[1] in stacks and p[2] in stacks]:
        for k in KS:
            gs = groups(rn, cn, stacks, k)
            hits = {v[0]: 0 for v in VARIANTS}
            bh = {(b, g): 0 for b in blocks for g in (False, True)}
            cls_count = {v[0]: np.zeros(len(CLASSES), int) for v in VARIANTS}
            for j, (r, c) in enumerate(gs):
                res = {False: compare(r, c, False), True: compare(r, c, True)}
                lr_all, lc_all = r @ W, c @ W
                for vname, gd, kind in VARIANTS:
                    f = flags(res[gd], kind, lr_all, lc_all)
                    hits[vname] += bool(f.any())
                    if f.any():
                        lr, lc = lr_all[:, f], lc_all[:, f]
                        cls = classify(lr, lc)
                        cls_count[vname] += np.bincount(cls, minlength=len(CLASSES))
                        if vname == "after" and len(examples) < 2000:
                            ys, xs = np.nonzero(f)
                            rr = res[True]
                            for i in range(len(ys)):
                                y, x = int(ys[i]), int(xs[i])
                                examples.append((title, rn, cn, k, j, y, x, CLASSES[cls[i]],
                                                 float(rr.statistic[y, x, 0]), float(rr.pvalue[y, x, 0]),
                                                 float(rr.padjusted[y, x, 0]), lr[:, i], lc[:, i]))
                for b in blocks:
                    for gd in (False, True):
                        bh[(b, gd)] += compare(r, c, gd, block=b).rejections > 0
            n = len(gs)
            summ.append(("null", f"{size} x {size}, {spp} spp", title, k, n, dict(hits),
                         {f"block={b}, {'after' if g else 'before'}": bh[(b, g)]
                          for b in blocks for g in (False, True)}))
            fa.append(f"| {title} | {k} | {n} | " + " | ".join(rate(hits[v[0]], n) for v in VARIANTS) + " | "
                      + " | ".join(rate(bh[(b, g)], n) for b in blocks for g in (False, True)) + " |")
            cl.append(f"| {title} | {k} | " + " | ".join(" / ".join(map(str, cls_count[v[0]])) for v in VARIANTS)
                      + " |")
            print(spp, fa[-1], flush=True)

    # ---- planted changes
    pw = ["| change | K | comparisons | " + " | ".join(f"any flag, {v[0]}" for v in VARIANTS) + " | "
          + " | ".join(f"region flagged, {v[0]}" for v in VARIANTS) + " | "
          + " | ".join(f"flags outside, {v[0]}" for v in VARIANTS) + " | "
          + " | ".join(f"block={b} any flag, {w}" for b in blocks for w in ("before", "after")) + " |",
          "|---" * (3 + 3 * len(VARIANTS) + 2 * len(blocks)) + "|"]
    for title, cn, region in (("light x1.02", "light_x1.02", light_region),
                              ("box albedo x1.05", "albedo_x1.05", mask),
                              ("box pixels x1.3 (scaled after rendering)", "base", mask)):
        if cn not in stacks:
            continue
        for k in KS:
            gs = groups("base", cn, stacks, k)
            if cn == "base":  # a large change planted in the base's own renders (disjoint seeds)
                scale = np.where(mask, np.float32(1.3), np.float32(1.0))[None, :, :, None]
                gs = [(r, c * scale) for r, c in gs]
            n = len(gs)
            vn = [v[0] for v in VARIANTS]
            anyf, frac, outside = {v: 0 for v in vn}, {v: [] for v in vn}, {v: 0 for v in vn}
            bh = {(b, g): 0 for b in blocks for g in (False, True)}
            for r, c in gs:
                res = {False: compare(r, c, False), True: compare(r, c, True)}
                lr_all, lc_all = r @ W, c @ W
                for vname, gd, kind in VARIANTS:
                    f = flags(res[gd], kind, lr_all, lc_all)
                    anyf[vname] += bool(f.any())
                    frac[vname].append(np.count_nonzero(f & region) / max(1, np.count_nonzero(region)))
                    outside[vname] += int(np.count_nonzero(f & ~region))
                for b in blocks:
                    for gd in (False, True):
                        bh[(b, gd)] += compare(r, c, gd, block=b).rejections > 0
            summ.append(("power", f"{size} x {size}, {spp} spp", title, k, n, dict(anyf),
                         {f"block={b}, {'after' if g else 'before'}": bh[(b, g)]
                          for b in blocks for g in (False, True)},
                         {v: float(np.mean(frac[v])) for v in vn}))
            pw.append(f"| {title} | {k} | {n} | " + " | ".join(rate(anyf[v], n) for v in vn) + " | "
                      + " | ".join(f"{np.mean(frac[v]):.4f}" for v in vn) + " | "
                      + " | ".join(str(outside[v]) for v in vn) + " | "
                      + " | ".join(rate(bh[(b, g)], n) for b in blocks for g in (False, True)) + " |")
            print(spp, pw[-1], flush=True)

    # ---- the flags left with the guards: their values
    ex = []
    per_class = max(2, a.examples // len(CLASSES))
    for cname in CLASSES:
        for e in [e for e in examples if e[7] == cname][:per_class]:
            title, rn, cn, k, j, y, x, cls, st, p, pa, vr, vc = e
            ex += [f"- {title}, K = {k}, comparison {j}, pixel (x={x}, y={y}), class {cls}: t = {st:.3g}, p = {p:.3g}, "
                   f"BH-adjusted {pa:.3g}",
                   f"  - {rn}: {fmt_vals(vr)}; over all its {atoms(lum[rn][:, y, x])}",
                   f"  - {cn}: {fmt_vals(vc)}; over all its {atoms(lum[cn][:, y, x])}"]
    with open(os.path.join(a.cache, f"flagged_examples_{tag}.txt"), "w") as f:
        for e in examples:
            f.write(f"{e[0]} K={e[3]} j={e[4]} x={e[6]} y={e[5]} {e[7]} t={e[8]:.4g} p={e[9]:.3g} padj={e[10]:.3g}\n"
                    f"  {e[1]}: {fmt_vals(e[11])}\n  {e[2]}: {fmt_vals(e[12])}\n")

    out = [f"## {size} x {size} pixels, {spp} samples per pixel", "",
           "Rendered with", "", cmd, "",
           f"Blender {meta['blender']} ({meta['build_hash']}), {size} x {size}, {spp} spp, seeds per setting: "
           + ", ".join(f"{n} {v}" for n, v in n_seeds.items()) + ".", "",
           f"### The scene's pixels ({spp} spp)", "",
           "How many of the pixels are zero-inflated in a group of K seeds, per setting (\"a group all zeros\" "
           "counts only pixels lit in some base seed):", ""] + scene + [
           "", f"### Per-image false alarms on unbiased pairs ({spp} spp)", "",
           "Any test flagged after BH.  Target: at most alpha = 0.05.  \"fix 1 emulated\": the guards' result "
           "with the tests constant on both sides and different (which MCSTAT_PIXELS_RENDER calls deterministic "
           "differences, p = 0) left out of BH; \"fixes 1+2 emulated\": also those where a side shows at most "
           f"one value farther than {SCALE} |d| from its median (d the difference of the means).  Emulations in "
           "this script of the proposed fixes (see the discussion), not libmcstat's behaviour.", ""] + fa + [
           "", f"### Which pixels were flagged ({spp} spp, summed over the comparisons)", "",
           "Classes of a flagged pixel by its K values per side: " + " / ".join(CLASSES) +
           " (see the script's docstring).", ""] + cl + [
           "", f"### Planted changes ({spp} spp)", "",
           f"Against base (the last row: base against base with the box's pixels x1.3 in the candidate's renders, "
           "a large change, to show what fix 2 costs).  Light: the region of the "
           f"{int(light_region.sum())} pixels that take at least 90% of their "
           f"light from the changed lights (of {int(lit.sum())} lit pixels); albedo: the {int(mask.sum())} "
           "pixels where "
           "the box is seen.  \"region flagged\": the mean over comparisons of the fraction of the region's pixels "
           "flagged; \"flags outside\": flagged pixels outside the region, summed (the light change also changes "
           "the pixels that take less of their light from it, the albedo change the box's surroundings, so these "
           "are not all false).", ""] + pw + [
           "", f"### Pixels still flagged with the guards on unbiased pairs ({spp} spp): their K values per side", ""]
    out += ex if ex else ["None."]
    return out + [""], meta, summ


DISCUSSION = """## Discussion

What the tables measure, and how to read them (the numbers are in the
tables above; this text names the mechanisms behind them, seen in the
listed pixels' values).

- The scene is built to show the issue's case: without the light tree,
  next event estimation spends most of its picks on the 64 lights behind
  the back wall, so the room's lights are picked rarely and many pixels
  are zero in most renders ("The scene's pixels", lt_off).  Where the
  plain Welch test ("before") flags such pixels, a side is constant (all
  zeros) or shows one nonzero value (class table): a zero variance taken
  at its word.

- Where the guards still flag, the listed pixels' values show a lattice:
  a pixel's value per render is n c plus a small background, where c is
  the contribution of one rare event: one pick of a rarely picked light
  (the dim light without the light tree), or one sample that reaches the
  lamp through its glass shell (multiples of the lamp's 400 / spp at the
  lamp's edge).  When the K renders of a side all land on the same
  lattice point (all of them with exactly one pick), that side looks
  constant, or nearly so, while most of its mass lies elsewhere (the
  "over all its seeds" shares of zeros in the listing).  Two cases:
  1. both sides land exactly on lattice points with no background: both
     constant and different, which MCSTAT_PIXELS_RENDER calls a
     deterministic difference (statistic +-inf, p = 0) - at once
     significant whatever the adjustment ("both constant" in the class
     table);
  2. a small background jitters the values: the side is not constant at
     the numerical floor, so no guard applies, and its tiny variance makes
     Welch's t huge ("spike", "zeros" or "smooth" in the class table, by
     the other side's values).
  The chance that K renders all land on one lattice point falls as p^K:
  it is a small-K failure, K = 4 far more than K = 8 or 16.

- A third kind, not of small K alone: a side whose values vary but
  whose K renders all missed its rare large values (a heavy tail: the
  light tree off, where a pick of the dim light is rare and large), so
  that its sample mean sits well below its mean while the other side's
  does not (the listing's "over all its seeds" shows both means agree).
  Nothing in such a sample says what it lacks; no per-pixel test of
  means holds its level there without assumptions (Bahadur and Savage),
  and neither fix below touches it.  Block tests average such pixels
  with their neighbours.

- Fix 1, now MCSTAT_PIXELS_RENDER's own: a pixel constant on both sides
  and different beyond the floor is what a side constant against a
  varying one is - K draws that may hide another value at rate up to the
  rule of three's pi - so both sides get the rule-of-three variance floor
  d^2 (1 - pi) / pi instead of a deterministic difference: never
  significant alone.  Column "fix 1 emulated" leaves those tests out of
  BH, which is what the floor amounts to; it now agrees with "after".

- Proposed fix 2: count a side as degenerate at the scale of the
  difference rather than at the numerical floor: a side with at most one
  value farther than c |d| from its median (c = 0.05 here) gets the same
  floor.  Column "fixes 1+2 emulated".  Its cost: a pixel whose
  difference is more than 1 / c times a side's spread is untestable per
  pixel, which includes large real differences on low-noise pixels (row
  "box pixels x1.3"): those are left to the block tests, where a large
  change over many pixels shows at once.  A narrower variant: apply it
  only below K = 8, or only when the tight side's values are far above
  (or below) everything the other side shows, as in every listed case.

- Power: at a few samples per pixel, a 2% light change or a 5% albedo
  change is small against one pixel's noise at K = 16 (a render's
  coefficient of variation is tens of percent there): per pixel, before
  and after alike, only renders with many samples per pixel can show it;
  blocks average the noise down.  Where "before" flags a planted change
  per pixel, read it against its false-alarm rate on the unbiased pairs
  of the same renders and the share of the region flagged: a flag that
  an unbiased pair raises as often is no detection.  Compare the block columns before and
  after for what Hsu's min(K) - 1 degrees of freedom cost against
  Satterthwaite's on block means, which are smooth.
"""


def summary(summ, blocks):
    """The summary tables: per run and K, the unbiased pairs pooled (and
    the worst pair), and the planted changes' detection at K = 16."""
    vn = [v[0] for v in VARIANTS]
    bn = [f"block={b}, {w}" for b in blocks for w in ("before", "after")]
    out = ["## Summary", "",
           "Per-image false alarms, the unbiased pairs pooled (light tree, path guiding, and base against "
           "itself); in brackets the worst pair's rate.  Target: at most alpha = 0.05.", "",
           "| renders | K | comparisons | " + " | ".join(f"per pixel, {v}" for v in vn) + " | " + " | ".join(bn) + " |",
           "|---" * (3 + len(vn) + len(bn)) + "|"]
    runs = []
    for e in summ:
        if e[1] not in runs:
            runs.append(e[1])
    for r in runs:
        for k in KS:
            rows = [e for e in summ if e[0] == "null" and e[1] == r and e[3] == k]
            if not rows:
                continue
            n = sum(e[4] for e in rows)

            def cell(get):
                x = sum(get(e) for e in rows)
                worst = max(get(e) / e[4] for e in rows)
                lo, hi = clopper(x, n)
                return f"{x / n:.3f} [{lo:.3f}, {hi:.3f}] (worst {worst:.3f})"
            out.append(f"| {r} | {k} | {n} | " + " | ".join(cell(lambda e, v=v: e[5][v]) for v in vn) + " | "
                       + " | ".join(cell(lambda e, b=b: e[6][b]) for b in bn) + " |")
    out += ["", "Planted changes at K = 16: the share of comparisons with any flag (the mean share of the changed "
            "region flagged).", "",
            "| renders | change | comparisons | " + " | ".join(f"per pixel, {v}" for v in vn) + " | "
            + " | ".join(bn) + " |", "|---" * (3 + len(vn) + len(bn)) + "|"]
    for e in summ:
        if e[0] == "power" and e[3] == 16:
            n = e[4]
            out.append(f"| {e[1]} | {e[2]} | {n} | " + " | ".join(f"{e[5][v] / n:.3f} ({e[7][v]:.3f})" for v in vn)
                       + " | " + " | ".join(f"{e[6][b] / n:.3f}" for b in bn) + " |")
    return out + [""]


def _commit():
    """The checkout's commit: the results are that code's."""
    import subprocess
    r = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                       cwd=os.path.dirname(os.path.abspath(__file__)))
    return r.stdout.strip() or "unknown"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cache", default="/work/cycles-cache")
    ap.add_argument("--runs", default="4:64", help="comma-separated spp:size, one section each")
    ap.add_argument("--blocks", default="8,16")
    ap.add_argument("--examples", type=int, default=15, help="flagged pixels (guards on) to print with their values")
    ap.add_argument("--out", default=os.path.join(HERE, "RESULTS_cycles_pixels.md"))
    a = ap.parse_args()
    import mcstat
    import scipy
    from common import machine
    t0 = time.time()
    blocks = [int(b) for b in a.blocks.split(",") if b]
    sections, meta, summ = [], None, []
    for r in a.runs.split(","):
        spp, size = (int(v) for v in r.split(":"))
        sec, meta, sm = run(a, spp, size, blocks)
        sections += sec
        summ += sm
    lines = ["# Per-pixel tests on real Cycles renders: false alarms and power", "",
             "Generated by `bench/bench_cycles_pixels.py` from the stacks that `bench/cycles_render.py` renders "
             "(their docstrings describe the scene, the settings and the pixel classes); the render commands are "
             "in each section, then:", "",
             f"    /work/main/.venv/bin/python bench/bench_cycles_pixels.py --cache {a.cache} --runs {a.runs} "
             f"--blocks {a.blocks}", "",
             f"Environment: {machine()}; Blender {meta['blender']} (the `bpy` wheel from PyPI under CPython 3.13, "
             "`pip install bpy` in its own venv, no system packages needed; its Cycles is built with path "
             f"guiding), Cycles on the CPU, 1 thread; mcstat {mcstat.__version__} (commit {_commit()}), NumPy "
             f"{np.__version__}, SciPy "
             f"{scipy.__version__}, Python {platform.python_version()}.  Combined pass, linear float32 (K, H, W, 3), "
             "no denoising, no adaptive sampling, no clamping, no glossy filter, the default pixel filter; each "
             "setting rendered with its own seeds (disjoint).  Luminance, BH at alpha = 0.05, two-sided.  "
             "\"before\": `compare(..., render_guards=False)` (the plain Welch test, the behaviour before the guards); \"after\": "
             "the default `render_guards=True` (MCSTAT_PIXELS_RENDER).  Rates: count/comparisons = rate "
             "[Clopper-Pearson 95% interval].", ""] + summary(summ, blocks) + sections
    lines += DISCUSSION.splitlines() + ["", f"Run time: {time.time() - t0:.0f} s.", ""]
    with open(a.out, "w") as f:
        f.write("\n".join(lines))
    print("wrote", a.out)


if __name__ == "__main__":
    sys.exit(main())
