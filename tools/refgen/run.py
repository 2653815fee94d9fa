#!/usr/bin/env python3
"""Runs every reference generator of tools/refgen/, in dependency order
(`make references`).  The reference data are committed (tests/data/, and
libmcstat/src/log_gammastar_cheb.h): no test runs this, and CI does not
need R.  Regenerating then `git diff` shows what a generator or an oracle
version changed.

Each generator is one entry of GENERATORS below: what it reads, what it
writes.  The order is computed from them (a generator runs after those
writing its inputs), so a new generator is one new entry.

  python3 tools/refgen/run.py --list           the order, inputs and outputs
  python3 tools/refgen/run.py -n               print the commands, run nothing
  python3 tools/refgen/run.py --lib build/libmcstat/libmcstat.so [--build build]
                                               run them all (make references)
  python3 tools/refgen/run.py --only NAME...   run only these (still in order)

Beside the generators (make_*): mpref.py, the mpmath oracle they share, and
measurements run by hand, whose findings the code's comments cite:
scan_f_small_df.py (the F distribution over its documented df range),
rformat_stress.R and .c (libmcstat's number formatting against R's on
290,000 values), diagnose_rates.py (how often the heavy-tail flag fires).
The fuzz seed corpus has its own generator, tests/fuzz/make_corpus.py.

Needs: Python with mpmath and numpy (requirements-dev.txt), Rscript
(tools/deps-debian.sh references), and for `accuracy` a built shared
library (--lib), rebuilt first when --build names its build directory (the
Chebyshev table it compiles in may have just been regenerated).
"""
import argparse
import os
import shutil
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
G = "tools/refgen/"
D = "tests/data/"

# name: (interpreter, script and arguments, inputs, outputs, what it is)
GENERATORS = {
    "log_gammastar": ("python", [G + "make_log_gammastar.py"], [],
                      ["libmcstat/src/log_gammastar_cheb.h"],
                      "Chebyshev expansions of log Gamma*(a), compiled into libmcstat (mpmath)"),
    "temme": ("python", [G + "make_temme_coeffs.py", "--check"], ["libmcstat/src/special.c"], [],
              "Temme's C0, C1 coefficients, checked against special.c's tables (exact rationals)"),
    "reference": ("python", [G + "make_reference.py"], [D + "nist"], [D + "ref_data.h"],
                  "stiff data sets, the four tests, quantiles, log CDFs (mpmath, 50 digits)"),
    "ks": ("R", [G + "make_ks_ref.R"], [], [D + "ref_ks.h"], "R's ks.test: statistic, exact p, printed block"),
    "ks_exact": ("python", [G + "make_ks_exact.py"], [D + "ref_ks.h"], [D + "ref_ks_exact.h"],
                 "exact rational K-S p-values of R's cases"),
    "rformat": ("R", [G + "make_rformat.R"], [], [D + "ref_rformat.h"], "R's number formatting"),
    "rblocks": ("R", [G + "make_rblocks_python.R"], [], [D + "r_blocks.json"],
                "R's printed t.test / var.test blocks"),
    "binom": ("R", [G + "make_binom_ref.R"], [], [D + "ref_binom.h", D + "binom_ref.csv"], "R's binom.test"),
    "chisq": ("R", [G + "make_chisq_ref.R"], [], [D + "ref_chisq.h", D + "chisq_ref.json"],
              "R's chisq.test"),
    "p_adjust": ("R", [G + "make_p_adjust_ref.R"], [], [D + "p_adjust_ref.txt"], "R's p.adjust"),
    "t": ("R", [G + "make_t_ref.R"], [], [D + "t_ref.tsv"],
          "R's t.test (pooled, paired, Welch, one-sample), var.test, pt(log.p) and qt: log p-values, other levels"),
    "power": ("R", [G + "make_power_ref.R"], [], [D + "power_ref.tsv", D + "equivalence_ref.tsv"],
              "R's power.t.test, closed forms, TOST"),
    "sequential": ("python", [G + "make_seq_ref.py"], [], [D + "seq_ref.tsv"],
                   "every look of the sequential tests: e-value, boundary, sequence, decision (mpmath, 50 digits)"),
    "efficiency": ("python", [G + "make_efficiency_ref.py"], [], [D + "efficiency_ref.tsv"],
                   "the efficiency-ratio test's delta method, df, t p-value and interval (mpmath, 50 digits)"),
    "t_tail": ("python", [G + "make_t_tail_ref.py"], [], [D + "t_tail_ref.tsv"],
               "Student t tails at non-integer df in [1, 1000], |t| to 1e8, and quantiles (mpmath, 40 digits)"),
    "ffi": ("python", [G + "make_ffi_ref.py"],
            [D + "ref_data.h", D + "ref_ks.h", D + "ref_ks_exact.h", D + "r_blocks.json"], [D + "ffi_ref.txt"],
            "the C tests' references for the ctypes, Rust and Go bindings"),
    "philox": ("python", [G + "make_philox_reference.py"], [], [D + "ref_philox.h"],
               "libmcest's Philox4x64 stream against NumPy"),
    "irradiance": ("python", [G + "make_irradiance_reference.py"], [], [D + "ref_irradiance.h"],
                   "libmcest's reference scenes (mpmath, 60 digits)"),
    "accuracy": ("python", [G + "make_accuracy.py"],
                 ["libmcstat/src/log_gammastar_cheb.h", D + "ref_data.h", D + "ref_ks_exact.h"],
                 [D + "accuracy_cases.tsv", D + "accuracy.tsv", "libmcstat/ACCURACY.md"],
                 "the accuracy table: the built library against mpmath (cases redrawn with --accuracy-refs)"),
}


def order(names):
    """names sorted so that every generator follows those writing its inputs."""
    writer = {out: n for n, g in GENERATORS.items() for out in g[3]}
    done, seq = set(), []

    def visit(n, path):
        if n in done:
            return
        if n in path:
            sys.exit("refgen: dependency cycle: %s" % " -> ".join(path + [n]))
        for i in GENERATORS[n][2]:
            if i in writer and writer[i] != n:
                visit(writer[i], path + [n])
        done.add(n)
        seq.append(n)

    for n in GENERATORS:
        visit(n, [])
    return [n for n in seq if n in names]


def command(name, args):
    lang, argv = GENERATORS[name][0], list(GENERATORS[name][1])
    if name == "accuracy":
        argv += ["--lib", args.lib] + (["--refs"] if args.accuracy_refs else []) \
            + (["--accept-looser"] if args.accept_looser else [])
    return ([args.python] if lang == "python" else [args.rscript]) + argv


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog="\n".join("%-14s %s" % (n, GENERATORS[n][4]) for n in order(GENERATORS)),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--list", action="store_true", help="print the order, inputs and outputs; run nothing")
    ap.add_argument("-n", "--dry-run", action="store_true", help="print the commands; run nothing")
    ap.add_argument("--only", nargs="+", metavar="NAME", choices=sorted(GENERATORS), help="run only these")
    ap.add_argument("--lib", help="the built libmcstat.so, for accuracy (without it, accuracy is skipped)")
    ap.add_argument("--build", help="rebuild libmcstat in this build directory before accuracy")
    ap.add_argument("--accuracy-refs", action="store_true",
                    help="accuracy draws its cases afresh (x from the library's own quantiles, so new "
                         "cases whenever the library changed) and recomputes their references: 2 minutes")
    ap.add_argument("--accept-looser", action="store_true", help="passed to make_accuracy.py")
    ap.add_argument("--python", default=sys.executable, help="the Python with mpmath and numpy")
    ap.add_argument("--rscript", default="Rscript")
    args = ap.parse_args()

    names = order(args.only or GENERATORS)
    if "accuracy" in names and not args.lib and not args.list:
        if args.only:
            ap.error("accuracy needs --lib")
        print("refgen: no --lib, accuracy skipped", file=sys.stderr)
        names.remove("accuracy")
    if args.list:
        for n in names:
            lang, argv, ins, outs, what = GENERATORS[n]
            print("%-14s %s\n%14s reads: %s\n%14s writes: %s" % (n, what, "", ", ".join(ins) or "-", "",
                                                                   ", ".join(outs) or "- (checks only)"))
        return 0
    if not args.dry_run and any(GENERATORS[n][0] == "R" for n in names) and not shutil.which(args.rscript):
        sys.exit("refgen: %s not found (tools/deps-debian.sh references installs R)" % args.rscript)
    for n in names:
        if n == "accuracy" and args.build:
            cmd = ["cmake", "--build", args.build, "--target", "mcstat"]
            print("+", " ".join(cmd), flush=True)
            if not args.dry_run:
                subprocess.run(cmd, cwd=ROOT, check=True)
        cmd = command(n, args)
        print("+", " ".join(cmd), flush=True)
        if not args.dry_run:
            r = subprocess.run(cmd, cwd=ROOT)
            if r.returncode:
                sys.exit("refgen: %s failed (exit %d)" % (n, r.returncode))
    return 0


if __name__ == "__main__":
    sys.exit(main())
