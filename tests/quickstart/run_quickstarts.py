#!/usr/bin/env python3
"""Builds and runs the README's quickstarts as a new user would: each block
marked `<!-- quickstart: LANG -->` is written to a fresh folder and built
with the README's command (plus warnings as errors), against the staged install (the
`cmake --install` of `make install-test`), the Python one with the package
installed in .venv.  Each program must exit 0 and print the decisions the
README's example leads to: the importance-sampled estimator's mean "equal"
to 1, and its variance "less" than the uniform estimator's; the test-suite
ones (pytest, GoogleTest) must pass every test at the budget their comment
gives.  The seeds are fixed in the examples, so the decisions are too.

  run_quickstarts.py --stage build/stage --python .venv/bin/python [LANG...]

Cargo and Go come from PATH; the Rust build reuses --cargo-target-dir."""
import argparse
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
BLOCK = re.compile(r"^<!-- quickstart: ([\w-]+) -->\n```\w*\n(.*?)^```", re.S | re.M)
# what each program must print, in order: (data names, decision)
EXPECTED = {
    "c": ["importance: equal", "importance and uniform: less"],
    "cpp": ["estimates: equal"],
    "python": ["importance: equal", "importance and uniform: less"],
    "rust": ["importance: equal", "importance and uniform: less"],
    "go": ["importance: equal", "importance and uniform: less"],
    "header": ["estimates: equal"],
}
# the test-suite quickstarts: a line their runner must print (every test passed)
SUITE_EXPECTED = {
    "pytest": re.compile(r"^4 passed in ", re.M),
    "gtest": re.compile(r"^\[  PASSED  \] 1 test\.", re.M),
}
SUITE_ENV = {"MCSTAT_SUITE_ALPHA": "1e-3", "MCSTAT_SEED": "0"}
HEADER = ROOT / "libmcstat" / "include" / "mcstat.h"


def header_example():
    """the program in mcstat.h's introduction: the lines indented under ' * Example:'"""
    lines = HEADER.read_text(encoding="utf-8").splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith(" * Example:"))
    body, i = [], start + 1
    while not lines[i].startswith(" *     "):
        i += 1
    while lines[i].startswith(" *     ") or lines[i] == " *" and lines[i + 1].startswith(" *     "):
        body.append(lines[i][len(" *     "):])
        i += 1
    return "\n".join(body) + "\n"


def blocks():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    found = {}
    for name, body in BLOCK.findall(text):
        if name in found:
            sys.exit(f"README.md: two quickstart blocks named {name!r}")
        found[name] = body.replace("/path/to/mcstat", str(ROOT))
    found["header"] = header_example()
    missing = (EXPECTED.keys() | SUITE_EXPECTED.keys() | {"rust-toml", "go-mod"}) - found.keys()
    if missing:
        sys.exit(f"README.md: no quickstart block for {', '.join(sorted(missing))}")
    return found


def decisions(output):
    """(data, decision) of each R block printed: 'data:  X' ... 'decision at alpha = A: D'"""
    out, data = [], None
    for line in output.splitlines():
        if line.startswith("data:  "):
            data = line[len("data:  "):].strip()
        m = re.match(r"decision at alpha = [0-9.e-]+: (\w+)", line)
        if m:
            out.append(f"{data}: {m.group(1)}")
    return out


def run(cmd, cwd, env):
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"`{' '.join(cmd)}` exited {r.returncode}:\n"
                           + r.stdout[-3000:] + r.stderr[-3000:])
    return r.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--stage", required=True, type=pathlib.Path)
    ap.add_argument("--python", required=True)
    ap.add_argument("--cargo-target-dir", type=pathlib.Path)
    ap.add_argument("langs", nargs="*", default=sorted(EXPECTED.keys() | SUITE_EXPECTED.keys()))
    args = ap.parse_args()
    stage = args.stage.resolve()
    python = str(pathlib.Path(args.python).absolute()) if os.sep in args.python else args.python
    code = blocks()
    env = dict(os.environ, PKG_CONFIG_PATH=str(stage / "lib" / "pkgconfig"))
    env.pop("LD_LIBRARY_PATH", None)  # the README's programs find the library by their run path
    pc = run(["pkg-config", "--cflags", "--libs", "mcstat-rpath"], ROOT, env).split()
    failed = 0
    for lang in args.langs:
        d = pathlib.Path(tempfile.mkdtemp(prefix=f"quickstart-{lang}-"))
        try:
            if lang in ("c", "header"):
                (d / "example.c").write_text(code[lang])
                run(["cc", "-std=c11", "-Wall", "-Wextra", "-Werror", "example.c", *pc, "-lm"], d, env)
                out = run(["./a.out"], d, env)
            elif lang == "cpp":
                (d / "quickstart.cpp").write_text(code["cpp"])
                run(["c++", "-std=c++17", "-Wall", "-Wextra", "-Werror", "quickstart.cpp", *pc, "-pthread"], d, env)
                out = run(["./a.out"], d, env)
            elif lang == "python":
                (d / "quickstart.py").write_text(code["python"])
                out = run([python, "quickstart.py"], d, env)
            elif lang == "rust":
                (d / "src").mkdir()
                (d / "Cargo.toml").write_text(code["rust-toml"])
                (d / "src" / "main.rs").write_text(code["rust"])
                # the workspace's lock file pins the one crate from crates.io (pkg-config)
                shutil.copy(ROOT / "bindings" / "rust" / "Cargo.lock", d / "Cargo.lock")
                renv = dict(env)
                if args.cargo_target_dir:
                    renv["CARGO_TARGET_DIR"] = str(args.cargo_target_dir.resolve())
                out = run(["cargo", "run", "-q"], d, renv)
            elif lang == "go":
                (d / "go.mod").write_text(code["go-mod"])
                (d / "main.go").write_text(code["go"])
                out = run(["go", "run", "."], d, env)
            elif lang == "pytest":
                (d / "test_lambert.py").write_text(code["pytest"])
                out = run([python, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--mcstat-alpha", "1e-3",
                           "test_lambert.py"], d, env)
            elif lang == "gtest":
                (d / "test_lambert.cpp").write_text(code["gtest"])
                run(["c++", "-std=c++14", "-Wall", "-Wextra", "-Werror", "test_lambert.cpp", *pc, "-lgtest",
                     "-lgtest_main", "-pthread"], d, env)
                out = run(["./a.out"], d, dict(env, **SUITE_ENV))
            else:
                sys.exit(f"unknown quickstart {lang!r}")
            if lang in SUITE_EXPECTED:
                if not SUITE_EXPECTED[lang].search(out):
                    raise RuntimeError(f"did not print {SUITE_EXPECTED[lang].pattern!r}:\n{out}")
                print(f"quickstart {lang}: every test passed")
                continue
            got = decisions(out)
            if got != EXPECTED[lang]:
                raise RuntimeError(f"printed the decisions {got}, expected {EXPECTED[lang]}:\n{out}")
            print(f"quickstart {lang}: {'; '.join(got)}")
        except (RuntimeError, OSError) as e:
            failed += 1
            print(f"quickstart {lang}: FAILED\n{e}")
        finally:
            shutil.rmtree(d, ignore_errors=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
