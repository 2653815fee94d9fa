#!/usr/bin/env python3
# Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
"""Every function libmcstat exports is reachable from every binding.

The list of functions comes from the built library itself
(`nm -D --defined-only libmcstat.so`), so a function added to the C library
without a binding fails this check.  What counts as reaching a function:

  rust-sys  declared in bindings/rust/mcstat-sys (the raw layer): all of them,
            the deprecated ones included
  rust      called by the safe crate bindings/rust/mcstat
  go        called as C.<name> by the Go package (not its tests)
  python    called in the extension's sources (bindings/python/src), or
            passed there as a function pointer (an argument outside string
            literals); a function-like macro of the header
            (mcstat_ks_options_init) counts as the function it expands to

Deprecated functions (the header's last section) are required of rust-sys
only.  A function a binding deliberately does not call is listed in
tests/bindings/coverage_exempt.txt with the reason; an exemption that names
a function the binding does call, or one the library does not export, fails
too, so the list cannot go stale.

usage: check_coverage.py LIBMCSTAT_SO [--root DIR] [--lang LANG]...

--lang (repeatable) checks only those bindings (default: all four); the
exemption file is still read whole, so a malformed line fails any run.
"""
import argparse
import os
import re
import subprocess
import sys

LANGS = ("rust-sys", "rust", "go", "python")


def exported(lib):
    out = subprocess.run(["nm", "-D", "--defined-only", lib], check=True, capture_output=True, text=True).stdout
    return {f[2] for f in (line.split() for line in out.splitlines())
            if len(f) == 3 and f[1] == "T" and f[2].startswith("mcstat_")}


def header_facts(root):
    inc = os.path.join(root, "libmcstat/include")
    # mcstat.h's families (not embedded.h, a macro header of its own), the
    # deprecated names last (mcstat/deprecated.h)
    fam = sorted(f for f in os.listdir(os.path.join(inc, "mcstat")) if f.endswith(".h") and f not in ("deprecated.h", "embedded.h"))
    text = "".join(open(os.path.join(inc, "mcstat", f)).read() for f in fam)
    text += open(os.path.join(inc, "mcstat", "deprecated.h")).read()
    macros = dict(re.findall(r"#define (mcstat_\w+)\([^)]*\)\s+(mcstat_\w+)\(", text))
    # the header's static inline functions (mcstat_stream_add): not exported,
    # a binding may mirror them
    for name in re.findall(r"static inline [\w\s*]*?\b(mcstat_\w+)\s*\(", text):
        macros[name] = name
    found = re.search(r"^/\* \d+\. Deprecated names\.", text, re.M)
    cut = found.start() if found else -1
    if cut < 0:
        sys.exit("check_coverage: the header has no 'N. Deprecated names.' section")
    tail = re.sub(r"/\*.*?\*/", " ", text[cut:], flags=re.S)
    # MCSTAT_DEPRECATED("mcstat_t_test_1_matrix (...)") names the replacement,
    # which is not itself deprecated
    tail = re.sub(r'"[^"\n]*"', " ", tail)
    deprecated = set(re.findall(r"\(?\b(mcstat_\w+)\)?\s*\(", tail))
    # inline functions of the header (mcstat_stream_add): called, never exported
    inline = set(re.findall(r"static inline [^(;]*?\b(mcstat_\w+)\s*\(", text))
    return macros, deprecated, inline


def sources(directory, exts, skip=lambda name: False):
    for base, _, files in os.walk(directory):
        if "target" in base.split(os.sep):
            continue
        for name in sorted(files):
            if name.endswith(exts) and not skip(name):
                with open(os.path.join(base, name), encoding="utf-8") as f:
                    yield re.sub(r"//[^\n]*", "", f.read())


def code_only(text):
    """C++ text without its string literals (raw ones included): docstrings
    that name a function do not reach it."""
    text = re.sub(r'R"(\w*)\((.*?)\)\1"', '""', text, flags=re.S)
    return re.sub(r'"(?:\\.|[^"\\\n])*"', '""', text)


def reached(root, macros, lib):
    b = os.path.join(root, "bindings")
    words = lambda texts, pattern: {m for t in texts for m in re.findall(pattern, t)}
    rust_sys = words(sources(os.path.join(b, "rust/mcstat-sys/src"), (".rs",)), r"\bfn\s+(mcstat_\w+)\s*\(")
    rust = words(sources(os.path.join(b, "rust/mcstat/src"), (".rs",)), r"\b(mcstat_\w+)\s*\(")
    go = words(sources(os.path.join(b, "go"), (".go",), lambda n: n.endswith("_test.go")), r"\bC\.(mcstat_\w+)\b")
    py_src = list(sources(os.path.join(b, "python/src"), (".cpp", ".hpp")))
    py = words(py_src, r"\b(mcstat_\w+)\s*\(")
    # a function passed by name (parse_enum(..., mcstat_check_domain_parse, ...));
    # only exported names count, so types in sizeof(...) do not
    py |= words((code_only(t) for t in py_src), r"[(,]\s*(mcstat_\w+)\s*[,)]") & lib
    py |= {macros[m] for m in py if m in macros}
    return {"rust-sys": rust_sys, "rust": rust, "go": go, "python": py}


def exemptions(path):
    ex = {lang: {} for lang in LANGS}
    bad = []
    if os.path.exists(path):
        for n, line in enumerate(open(path), 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            m = re.match(r"(\S+)\s+(mcstat_\w+)\s+--\s+(\S.*)$", line)
            if not m or m.group(1) not in LANGS:
                bad.append(f"{path}:{n}: expected 'LANG mcstat_name -- reason' with LANG one of {', '.join(LANGS)}")
                continue
            ex[m.group(1)][m.group(2)] = m.group(3)
    return ex, bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("lib")
    ap.add_argument("--root", default=os.path.normpath(os.path.join(os.path.dirname(__file__), "../..")))
    ap.add_argument("--lang", action="append", choices=LANGS,
                    help="check only this binding (repeatable; default: all)")
    args = ap.parse_args()
    langs = [lang for lang in LANGS if lang in args.lang] if args.lang else list(LANGS)
    lib = exported(args.lib)
    macros, deprecated, inline = header_facts(args.root)
    got = reached(args.root, macros, lib)
    ex, problems = exemptions(os.path.join(args.root, "tests/bindings/coverage_exempt.txt"))
    print(f"libmcstat exports {len(lib)} functions, {len(lib & deprecated)} of them deprecated")
    for lang in langs:
        want = lib if lang == "rust-sys" else lib - deprecated
        missing = sorted(want - got[lang] - set(ex[lang]))
        for name in missing:
            problems.append(f"{lang}: {name} is exported by libmcstat but not reached")
        for name in sorted(ex[lang]):
            if name not in lib:
                problems.append(f"{lang}: exemption for {name}, which libmcstat does not export")
            elif name in got[lang]:
                problems.append(f"{lang}: exemption for {name}, which the binding does reach")
        unknown = sorted(got[lang] - lib - set(macros) - inline)
        for name in unknown:
            problems.append(f"{lang}: {name} is used but libmcstat does not export it")
        reach = len(want & got[lang])
        print(f"  {lang:8s} reaches {reach:3d} of {len(want)}"
              f"{' (deprecated included)' if lang == 'rust-sys' else ''}"
              f", {len(set(ex[lang]) & want)} exempt with a reason, {len(missing)} missing")
    for p in problems:
        print("FAIL", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
