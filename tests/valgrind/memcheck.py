#!/usr/bin/env python3
"""Runs every ctest test of a build tree under valgrind's memcheck.

    tests/valgrind/memcheck.py BUILD_DIR [-j JOBS] [-R REGEX] [-E REGEX]

The list of tests, their commands, working directories and environments
come from `ctest --show-only=json-v1`, so a test added to CMake is covered
without touching this script.  Each ELF executable runs as

    valgrind --tool=memcheck --error-exitcode=86 --leak-check=full
             --show-leak-kinds=definite --errors-for-leak-kinds=definite ...

so an invalid read or write, a use of uninitialised memory, an invalid free
or a definite leak fails the test (exit status 86), as does the test's own
failure.  Commands that are not ELF executables (shell scripts such as the
exports check) are not memory-checked; they are listed as such.  Extra
valgrind options may be given in VALGRIND_OPTS (e.g. --track-origins=yes to
find where an uninitialised value came from).

Exit status: 0 when every test passed under memcheck, 1 otherwise.
"""
import argparse
import concurrent.futures
import json
import os
import re
import shlex
import subprocess
import sys
import time

VALGRIND = [
    "valgrind", "--tool=memcheck", "--error-exitcode=86", "--leak-check=full",
    "--show-leak-kinds=definite", "--errors-for-leak-kinds=definite",
    "--num-callers=30", "--quiet",
]


def is_elf(path):
    try:
        with open(path, "rb") as f:
            return f.read(4) == b"\x7fELF"
    except OSError:
        return False


def load_tests(build):
    out = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"],
                         check=True, capture_output=True, text=True).stdout
    tests = []
    for t in json.loads(out)["tests"]:
        props = {p["name"]: p["value"] for p in t.get("properties", [])}
        env = dict(os.environ)
        # valgrind 3.19 stops at some AVX2 encodings GCC emits for the
        # per-pixel loops; their SSE2 code gives the same results bit for bit
        env["MCSTAT_NO_AVX2"] = "1"
        for kv in props.get("ENVIRONMENT", []):
            k, _, v = kv.partition("=")
            env[k] = v
        tests.append({"name": t["name"], "command": t["command"],
                      "cwd": props.get("WORKING_DIRECTORY", build), "env": env,
                      "disabled": props.get("DISABLED", False),
                      # ctest's WILL_FAIL: a test that must fail (a planted bug) passes on a
                      # failing exit status, but never on a memory error
                      "will_fail": props.get("WILL_FAIL", False) in (True, "ON", "TRUE", "1", 1),
                      # PASS_REGULAR_EXPRESSION: the output decides, not the exit status
                      "pass_regex": props.get("PASS_REGULAR_EXPRESSION", [])})
    return tests


def run(test):
    cmd = test["command"]
    checked = is_elf(cmd[0])
    if checked:
        cmd = VALGRIND + shlex.split(os.environ.get("VALGRIND_OPTS", "")) + cmd
    t0 = time.monotonic()
    p = subprocess.run(cmd, cwd=test["cwd"], env=test["env"], capture_output=True, text=True)
    rc = p.returncode
    if not (rc == 86 and checked):
        if test["pass_regex"]:
            rc = 0 if any(re.search(r, p.stdout + p.stderr, re.DOTALL) for r in test["pass_regex"]) else 1  # CMake: . matches newlines
        elif test["will_fail"]:
            rc = 0 if rc != 0 else 1
    return test["name"], checked, rc, time.monotonic() - t0, p.stdout + p.stderr


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("build")
    ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("-R", "--regex", default="", help="only the tests whose name matches")
    ap.add_argument("-E", "--exclude", default="", help="not the tests whose name matches")
    a = ap.parse_args()
    tests = [t for t in load_tests(a.build) if not t["disabled"] and re.search(a.regex, t["name"])
             and not (a.exclude and re.search(a.exclude, t["name"]))]
    if not tests:
        print("memcheck: no tests found in", a.build)
        return 1
    failed = []
    t0 = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        for fut in concurrent.futures.as_completed([pool.submit(run, t) for t in tests]):
            name, checked, rc, secs, output = fut.result()
            what = "memcheck" if checked else "not an ELF executable: run without valgrind"
            verdict = "ok" if rc == 0 else ("MEMORY ERROR" if rc == 86 and checked else f"FAILED ({rc})")
            print(f"{name:32s} {verdict:14s} {secs:7.1f} s  ({what})", flush=True)
            if rc != 0:
                failed.append(name)
                sys.stdout.write(output[-20000:])
    print(f"memcheck: {len(tests) - len(failed)}/{len(tests)} tests passed in {time.monotonic() - t0:.0f} s")
    if failed:
        print("memcheck failures:", " ".join(failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
