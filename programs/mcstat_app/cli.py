# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""The ``mcstat`` command (also ``python -m mcstat_app``).

    mcstat reproduce [--scene FILE] [--out DIR] [--seed N] [--quick]   the paper's case studies
    mcstat plan [SCENE] [--quick]       what reproduce would run on a scene, and what it leaves out
    mcstat scene [SCENE]                a scene with every default filled in (JSON; the built-in one by default)
    mcstat schema                       the scene format (JSON Schema)
    mcstat test X [Y] [options]         one test on samples in .npy / .csv files, printed as R does
    mcstat image-test -r REF... -c CAND... [options]   per-pixel Welch tests with FDR control: PNG map + JSON

No traceback reaches the user: every failure is one line on stderr that
says what to do, with an exit status per kind (`errors`; ``mcstat --help``
lists them): 0 success, 1 H0 rejected with ``--fail-on-reject``
(``image-test``: verdict "different", any pixel differs after the
adjustment), 2 bad command line, 3 bad input file or data, 4 a missing
Python package, 5 an output that cannot be written, 6 ``image-test
--fail-on-reject``'s verdict "inconclusive" (nothing could be tested, or
the pass could hide a bias above ``--max-detectable-bias``), 70 an
internal error, 130 interrupted, 141 stdout closed early (broken pipe).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
from typing import List, Optional

import mcstat
from . import errors as E

DEFAULT_SEED = 1


def _reproduce(a: argparse.Namespace) -> int:
    from .reproduce.run import missing_report_packages, reproduce

    if not a.no_report:
        missing = missing_report_packages()
        if missing:
            print(f"mcstat reproduce: the report needs {' and '.join(missing)}, which "
                  f"{'is' if len(missing) == 1 else 'are'} not installed: pip install 'mcstat[report]' "
                  f"(or: pip install {' '.join(missing)}), or run with --no-report to write results.json only",
                  file=sys.stderr)
            return E.EXIT_MISSING_PACKAGE
    reproduce(a.scene, a.out, a.seed, quick=a.quick, threads=a.threads, progress=a.progress,
              report=not a.no_report)
    return 0


def _plan(a: argparse.Namespace) -> int:
    from .reproduce.plan import Plan
    from .reproduce.scene import load_scene

    print(Plan(load_scene(a.scene), a.quick).text())
    return 0


def _scene(a: argparse.Namespace) -> int:
    from .reproduce.scene import load_scene

    print(json.dumps(load_scene(a.scene).data, indent=2))
    return 0


def _schema(a: argparse.Namespace) -> int:
    from .reproduce.scene import schema_text

    sys.stdout.write(schema_text())
    return 0


def _test(a: argparse.Namespace) -> int:
    from .samples import load_samples

    x = load_samples(a.x, a.column)
    y = load_samples(a.y, a.column) if a.y else None
    if a.batch:
        x = mcstat.batch_means(x, a.batch)
        y = mcstat.batch_means(y, a.batch) if y is not None else None
    xn = os.path.basename(a.x)
    yn = os.path.basename(a.y) if a.y else "y"
    if a.test == "t":
        r = mcstat.t_test(x, y, mu=a.mu, alternative=a.alternative, alpha=a.alpha, nan_policy=a.nan)
    elif a.test == "var":
        if y is None and a.sigma2 is None:
            raise E.UsageError("--test var on one sample needs --sigma2 (the variance under H0)")
        null = dict(sigma2=a.sigma2) if y is None else dict(ratio=a.ratio)
        r = mcstat.var_test(x, y, **null, alternative=a.alternative, alpha=a.alpha, nan_policy=a.nan)
    else:
        if y is None:
            raise E.UsageError("--test ks compares two samples: give X and Y")
        r = mcstat.ks_test(x, y, weight=a.weight, alternative=a.alternative, alpha=a.alpha, method=a.method,
                           n_sim=a.n_sim, seed=a.seed)
    if a.json:
        from .reproduce.results import test_fields

        print(json.dumps(test_fields(r), indent=1))
    else:
        sys.stdout.write(r.format(xn, yn))
    return 1 if (a.fail_on_reject and r.reject) else 0


def _image_equivalence(a: argparse.Namespace) -> int:
    from .image import run_equivalence

    if not 0.0 <= a.equivalence < 1.0:
        raise E.UsageError(f"--equivalence (the relative margin) must lie in [0, 1), got {a.equivalence}")
    if not (a.atol >= 0.0):
        raise E.UsageError(f"--atol must be >= 0, got {a.atol}")
    if a.equivalence == 0.0 and a.atol == 0.0:
        raise E.UsageError("--equivalence 0 needs --atol > 0: no difference could be shown inside a zero margin")
    if not 0.0 < a.alpha < 0.5:
        raise E.UsageError(f"--alpha must lie in (0, 0.5) with --equivalence (two one-sided tests), got {a.alpha}")
    unused = [f"--{n.replace('_', '-')}" for n in ("png", "bias_png", "max_detectable_bias",
                                                   "max_relative_detectable_bias", "spp")
              if getattr(a, n) is not None]
    unused += ["--alternative"] if a.alternative != "two-sided" else []
    unused += ["--adjust"] if a.adjust != "BH" else []
    unused += ["--paired"] if a.paired else []
    if unused:
        raise E.UsageError(f"{', '.join(unused)} belong to the difference test; --equivalence writes its summary "
                           "with --json")
    res, sources = run_equivalence(a.reference, a.candidate, margin=a.equivalence, atol=a.atol, block=a.block,
                                   alpha=a.alpha, channels=a.channels, seed_axis=a.seed_axis, nan_policy=a.nan,
                                   layer=a.layer, json_path=a.json, worst=a.worst)
    if not a.quiet:
        sys.stdout.write(res.text(a.worst) + "\n")
        if sources:
            print("read:\n" + "\n".join(sources))
        if a.json:
            print(f"summary: {a.json}")
    if not a.fail_on_reject:
        return E.EXIT_OK
    return E.EXIT_OK if res.equivalent else E.EXIT_REJECTED


def _image_test(a: argparse.Namespace) -> int:
    from .image import run

    if a.equivalence is not None:
        return _image_equivalence(a)

    for name in ("block", "max_detectable_bias", "max_relative_detectable_bias"):
        v = getattr(a, name)
        if v is not None and not v > 0:
            raise E.UsageError(f"--{name.replace('_', '-')} must be positive, got {v}")
    if not 0.0 < a.detect_power < 1.0:
        raise E.UsageError(f"--detect-power must lie in (0, 1), got {a.detect_power}")
    if not 0.0 <= a.bias_quantile <= 1.0:
        raise E.UsageError(f"--bias-quantile must lie in [0, 1], got {a.bias_quantile}")
    res = run(a.reference, a.candidate, png=a.png, json_path=a.json, worst=a.worst, alpha=a.alpha,
              method=a.adjust, alternative=a.alternative, channels=a.channels, seed_axis=a.seed_axis,
              nan_policy=a.nan, spp=a.spp, layer=a.layer, bias_png=a.bias_png, block=a.block,
              detect_power=a.detect_power, paired=a.paired,
              max_detectable_bias=a.max_detectable_bias,
              max_relative_detectable_bias=a.max_relative_detectable_bias, bias_quantile=a.bias_quantile)
    if not a.quiet:
        sys.stdout.write(res.text(a.worst))
        if a.png:
            print(f"\nsignificance map: {a.png} (red: candidate greater, blue: less, yellow: channels "
                  "disagree, grey: not significant, black: not tested; the key is in the image)")
        if a.bias_png:
            print(f"detectable-bias map: {a.bias_png} (the colour bar and scale are in the image)")
        if a.json:
            print(f"summary: {a.json}")
    if not a.fail_on_reject:
        return E.EXIT_OK
    return {"equal": E.EXIT_OK, "different": E.EXIT_REJECTED, "inconclusive": E.EXIT_INCONCLUSIVE}[res.verdict]


def _add_image_test(sub) -> None:
    it = sub.add_parser(
        "image-test", help="per-pixel Welch tests of a candidate against a reference, with FDR control",
        description="Compares a candidate renderer's images with a reference's, pixel by pixel: Welch's t test "
                    "on the renders of several seeds per side, p-values adjusted together (Benjamini-Hochberg "
                    "by default, so that at most alpha of the flagged pixels are expected to be false "
                    "discoveries). Writes a significance map (PNG) and a summary (text, JSON). Inputs per side: "
                    "one .npy stack (seeds, H, W[, C]); or one image per seed (.exr, .pfm, .npy); or one .npz of "
                    "per-pixel summaries n, mean, M2 (or var); or one .npz of per-pixel accumulators (key moments: "
                    "mcstat.image.save_moments of a merged MomentsArray); or one .exr of Mitsuba 3's moment "
                    "integrator (channels P.X.. and m2_P.X..; needs --spp and a box reconstruction filter: "
                    "with another filter the moments are weighted over samples shared between pixels and the "
                    "test is not valid); or one .exr with one layer per seed (seed0.R, seed0.G, ..., "
                    "seed1.R, ...). Pixels whose variance m2 - m1^2 is lost to float32 rounding are not "
                    "tested and counted. Arnold's variance AOVs and Cycles' sample-count pass are refused.")
    it.add_argument("-r", "--reference", nargs="+", required=True, metavar="FILE", help="the reference's input")
    it.add_argument("-c", "--candidate", nargs="+", required=True, metavar="FILE", help="the candidate's input")
    it.add_argument("--png", metavar="FILE", default=None, help="write the significance map here")
    it.add_argument("--json", metavar="FILE", default=None, help="write the summary here (JSON)")
    it.add_argument("--alpha", type=float, default=0.05, help="level of the FDR (or FWER) (default: %(default)s)")
    it.add_argument("--adjust", default="BH",
                    choices=("BH", "BY", "e-BH", "holm", "hochberg", "hommel", "bonferroni", "none"),
                    help="p-value adjustment (default: %(default)s, the false discovery rate for independent or "
                         "positively dependent pixels; BY and e-BH: under any dependence, e.g. a reconstruction "
                         "filter's or denoiser's, at a cost in power)")
    it.add_argument("--channels", choices=("luminance", "rgb"), default="luminance",
                    help="test the luminance, or each channel (default: %(default)s)")
    it.add_argument("--alternative", choices=("two-sided", "less", "greater"), default="two-sided",
                    help="a claim about the candidate (default: %(default)s)")
    it.add_argument("--layer", default=None, metavar="NAME",
                    help="the layer of one-image-per-seed EXR files (default: the unprefixed R, G, B, else "
                         "Blender's Combined, else the only colour layer; the output says which)")
    it.add_argument("--seed-axis", type=int, default=None,
                    help="the seeds axis of a .npy stack, -1 for (H, W, seeds) (default: from the shapes; "
                         "an ambiguous stack is refused)")
    it.add_argument("--spp", type=int, nargs="+", default=None, metavar="N",
                    help="samples per pixel of a Mitsuba moment EXR: N (both sides) or REF CAND")
    it.add_argument("--nan", choices=("raise", "omit"), default="raise",
                    help="NaN values: an error, or left out of their pixel's sample (default: %(default)s)")
    it.add_argument("--worst", type=int, default=10, help="list this many smallest p-values (default: 10)")
    it.add_argument("--quiet", action="store_true", help="print nothing")
    it.add_argument("--bias-png", metavar="FILE", default=None,
                    help="write the detectable-bias map here: per pixel the smallest difference its test would "
                         "have found with probability --detect-power, in false colour with its colour bar")
    it.add_argument("--block", type=int, default=None, metavar="N",
                    help="test the means of N x N blocks per seed instead of pixels (valid whatever the correlation "
                         "among the pixels inside a block, e.g. a reconstruction filter's; more power for regional "
                         "biases; per-seed inputs only; edge blocks smaller)")
    it.add_argument("--paired", action="store_true",
                    help="the two sides' seeds are the same, in the same order (same-seed renders): the paired t "
                         "test on the per-seed differences instead of Welch's; more power where the change leaves "
                         "paths alone, valid only for such pairs (per-seed inputs of equal seed counts)")
    it.add_argument("--detect-power", type=float, default=0.8,
                    help="the power behind the detectable bias (default: %(default)s)")
    it.add_argument("--max-detectable-bias", type=float, default=None, metavar="X",
                    help="with no rejection, the verdict is 'inconclusive' unless the detectable bias at "
                         "--bias-quantile of the passing pixels is at most X (absolute, the images' units)")
    it.add_argument("--max-relative-detectable-bias", type=float, default=None, metavar="R",
                    help="as --max-detectable-bias, relative to |reference mean| per pixel (0.01: 1%%)")
    it.add_argument("--bias-quantile", type=float, default=0.9,
                    help="the quantile of the passing pixels' detectable bias that the limits apply to "
                         "(default: %(default)s)")
    it.add_argument("--equivalence", type=float, default=None, metavar="MARGIN",
                    help="instead of a difference test: is the candidate the reference within MARGIN (relative) "
                         "+ --atol, shown at --alpha?  Two one-sided Welch tests per block of per-seed means "
                         "(--block, default 32), every block shown or the verdict is 'not shown equivalent' "
                         "(an intersection-union test: level alpha, no adjustment); per-seed inputs only")
    it.add_argument("--atol", type=float, default=0.0,
                    help="with --equivalence, an absolute margin added to the relative one (default: %(default)s)")
    it.add_argument("--fail-on-reject", action="store_true",
                    help="exit with the verdict: 0 equal, 1 different (some pixel differs after the adjustment), "
                         "6 inconclusive (nothing tested, or a larger bias than --max-detectable-bias could hide); "
                         "with --equivalence: 0 equivalent, 1 not shown equivalent")
    it.set_defaults(func=_image_test)


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="mcstat", description="Statistical hypothesis tests for Monte Carlo estimators (Subr & Arvo).",
        epilog="Run 'mcstat COMMAND --help' for a command's options.\n\n" + E.EXIT_STATUS_HELP,
        formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version",
                   version=f"mcstat {mcstat.__version__} (libmcstat {mcstat.__libmcstat_version__})")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")

    r = sub.add_parser("reproduce", help="run the paper's case studies on a scene and write a report",
                       description="Runs the case studies of the paper's section 3 that the scene calls for "
                                   "(see 'mcstat plan'), prints R-style summaries, and writes report.md with PNG "
                                   "figures and results.json (every test's fields) into --out. The same --seed "
                                   "gives the same results.json apart from wall-clock fields.")
    r.add_argument("--scene", metavar="FILE", help="scene file (.json or .toml); default: the built-in paper scene "
                                                   "(examples/scenes/paper.toml)")
    r.add_argument("--out", metavar="DIR", default="report", help="output folder (default: %(default)s)")
    r.add_argument("--seed", type=int, default=DEFAULT_SEED, help="seed of every random stream (default: %(default)s)")
    r.add_argument("--quick", action="store_true", help="smaller budgets (CI: well under a minute on 2 cores)")
    r.add_argument("--threads", type=int, default=None, metavar="N",
                   help="threads for the estimators and K-S simulations (results do not depend on it)")
    g = r.add_mutually_exclusive_group()
    g.add_argument("--progress", dest="progress", action="store_true", default=None,
                   help="always show progress bars (default: when stderr is a terminal)")
    g.add_argument("--no-progress", dest="progress", action="store_false")
    r.add_argument("--no-report", action="store_true", help="write results.json only (no matplotlib needed)")
    r.set_defaults(func=_reproduce)

    pl = sub.add_parser("plan", help="show what reproduce would run on a scene and what it would leave out")
    pl.add_argument("scene", nargs="?", help="scene file (default: the built-in scene)")
    pl.add_argument("--quick", action="store_true")
    pl.set_defaults(func=_plan)

    s = sub.add_parser("scene", help="print a scene with every default filled in (JSON)")
    s.add_argument("scene", nargs="?", help="scene file (default: the built-in scene)")
    s.set_defaults(func=_scene)

    sc = sub.add_parser("schema", help="print the scene format (JSON Schema)")
    sc.set_defaults(func=_schema)

    t = sub.add_parser("test", help="test samples read from .npy / .csv files",
                       description="One test on one or two samples, printed as R prints it, with the paper's "
                                   "less / equal / greater decision. Files: .npy, or text with one number per line "
                                   "or a table (.csv, .tsv, .txt; a header row is allowed; pick a column with "
                                   "--column).")
    t.add_argument("x", help="the first sample")
    t.add_argument("y", nargs="?", help="the second sample (two-sample tests)")
    t.add_argument("--test", choices=("t", "var", "ks"), default="t",
                   help="t: one-sample or Welch t; var: chi-squared or F; ks: Kolmogorov-Smirnov (default: t)")
    t.add_argument("--mu", type=float, default=0.0, help="mean under H0 (one-sample t)")
    t.add_argument("--sigma2", type=float, default=None, help="variance under H0 (one-sample var)")
    t.add_argument("--ratio", type=float, default=1.0, help="variance ratio under H0 (two-sample var)")
    t.add_argument("--alternative", choices=("two-sided", "less", "greater"), default="two-sided",
                   help="a claim about x (for ks the opposite of SciPy's and R's naming)")
    t.add_argument("--alpha", type=float, default=0.05)
    t.add_argument("--batch", type=int, default=None, metavar="K",
                   help="test secondary estimates: means of K consecutive values")
    t.add_argument("--column", default=None, help="the column of a table, by index or header name")
    t.add_argument("--nan", choices=("raise", "omit"), default="raise", help="NaN policy (t and var)")
    t.add_argument("--weight", choices=("canner", "none"), default="canner", help="K-S weight")
    t.add_argument("--method", choices=("auto", "exact", "simulate", "asymptotic"), default="auto",
                   help="K-S p-value")
    t.add_argument("--n-sim", type=int, default=None, help="K-S simulation replicates")
    t.add_argument("--seed", type=int, default=None, help="K-S simulation seed")
    t.add_argument("--json", action="store_true", help="print the result's fields as JSON")
    t.add_argument("--fail-on-reject", action="store_true", help="exit with status 1 when H0 is rejected")
    t.set_defaults(func=_test)

    _add_image_test(sub)
    return p


def _report(command: str, message: str) -> None:
    print(f"mcstat {command}: {message}", file=sys.stderr)


def _status(a: argparse.Namespace) -> int:
    """Runs the command; every exception becomes one line on stderr and its status."""
    from mcstat.estimators import EstimatorError

    from .image import ImageInputError
    from .reproduce.scene import SceneError
    from .samples import SampleFileError

    cmd = a.command
    try:
        status = a.func(a)
        sys.stdout.flush()  # a closed pipe shows here, not at exit
        return status
    except BrokenPipeError:
        return _broken_pipe()
    except KeyboardInterrupt:
        _report(cmd, "interrupted")
        return E.EXIT_INTERRUPTED
    except E.UsageError as e:
        _report(cmd, f"error: {e}")
        return E.EXIT_USAGE
    except E.MissingPackageError as e:  # before ImageInputError: a missing reader is one
        _report(cmd, str(e))
        return E.EXIT_MISSING_PACKAGE
    except SceneError as e:
        _report(cmd, f"bad scene: {e}")
        return E.EXIT_INPUT
    except (SampleFileError, ImageInputError) as e:
        _report(cmd, f"{type(e).__name__}: {e}" if isinstance(e, ImageInputError) else str(e))
        return E.EXIT_INPUT
    except mcstat.InvalidArgumentError as e:  # an option's value the library refuses
        _report(cmd, f"{type(e).__name__}: {e}")
        return E.EXIT_USAGE
    except (mcstat.McstatError, EstimatorError) as e:  # data the test cannot use
        _report(cmd, f"{type(e).__name__}: {e}")
        return E.EXIT_INPUT
    except ModuleNotFoundError as e:
        _report(cmd, str(E.MissingPackageError(e.name or "?", f"mcstat {cmd}")))
        return E.EXIT_MISSING_PACKAGE
    except E.OutputError as e:
        _report(cmd, str(e))
        return E.EXIT_OUTPUT
    except OSError as e:  # inputs are read through the readers above: what is left is an output
        where = f"{e.filename}: " if e.filename else ""
        _report(cmd, f"cannot write: {where}{e.strerror or e}")
        return E.EXIT_OUTPUT
    except Exception as e:
        if os.environ.get("MCSTAT_TRACEBACK"):
            raise
        _report(cmd, f"internal error: {type(e).__name__}: {e} (a bug: please report it with the command; "
                     "MCSTAT_TRACEBACK=1 shows the traceback)")
        return E.EXIT_INTERNAL


def _broken_pipe() -> int:
    """The reader of stdout went away (``| head``): stop quietly.  Python
    flushes stdout again at exit, which would print a second error: point
    the descriptor at /dev/null first."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):  # stdout replaced by an object without a descriptor
        pass
    return E.EXIT_BROKEN_PIPE


def main(argv: Optional[List[str]] = None) -> int:
    parser = build_parser()
    try:
        try:
            a = parser.parse_args(argv)
        except SystemExit:  # --help, --version, a usage error: flush what was printed here
            sys.stdout.flush()
            raise
    except BrokenPipeError:  # into a closed pipe
        return _broken_pipe()
    if not getattr(a, "func", None):
        parser.print_help()
        return E.EXIT_USAGE
    return _status(a)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
