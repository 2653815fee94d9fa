#!/usr/bin/env bash
# The source distribution builds a wheel, as `pip install mcstat-X.tar.gz`
# does on a user's machine:
#   1. python -m build --sdist;
#   2. unpacked into a read-only folder, `pip wheel` of it with build
#      isolation (scikit-build-core and pybind11 from [build-system].requires,
#      the CMake build in a temporary folder): nothing may be written into the
#      source tree;
#   3. the wheel holds the same files as the checkout's (make wheel-test's
#      wheel, when it is there): nothing the package needs is left out of the sdist.
# A full build of libmcstat, libmcest and the extension: a few minutes on 2 cores.
#   usage: tests/wheel/test_sdist.sh BUILD_DIR PYTHON
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(mkdir -p "${1:-build}" && cd "${1:-build}" && pwd)
py=$(cd "$(dirname "${2:-.venv/bin/python}")" && pwd)/$(basename "${2:-.venv/bin/python}")
work="$build/sdist-test"
[ -d "$work/src" ] && chmod -R u+w "$work/src"
rm -rf "$work"
mkdir -p "$work/sdist" "$work/src" "$work/wheel"
t0=$SECONDS

fail() { echo "sdist test FAILED: $*" >&2; exit 1; }

"$py" -m build --sdist --no-isolation -o "$work/sdist" . > "$work/sdist.log" 2>&1 || { cat "$work/sdist.log"; fail "build --sdist"; }
sdist=$(ls "$work"/sdist/mcstat-*.tar.gz)
tar xzf "$sdist" -C "$work/src"
src=$(ls -d "$work"/src/mcstat-*)
(cd "$src" && find . | sort) > "$work/before.txt"
chmod -R a-w "$src"
touch "$work/stamp"
t1=$SECONDS
CMAKE_BUILD_PARALLEL_LEVEL=${JOBS:-2} "$py" -m pip wheel -q --no-deps -w "$work/wheel" "$src" > "$work/wheel.log" 2>&1 \
    || { chmod -R u+w "$src"; cat "$work/wheel.log"; fail "pip wheel of the sdist"; }
t_wheel=$((SECONDS - t1))
chmod -R u+w "$src"
(cd "$src" && find . | sort) > "$work/after.txt"
diff "$work/before.txt" "$work/after.txt" > /dev/null || fail "the build wrote into the source tree: $(diff "$work/before.txt" "$work/after.txt" | head)"
changed=$(find "$src" -newer "$work/stamp" | head)
[ -z "$changed" ] || fail "the build changed files of the source tree: $changed"

whl=$(ls "$work"/wheel/mcstat-*.whl)
names() { "$py" -c 'import sys, zipfile; print("\n".join(sorted(n for n in zipfile.ZipFile(sys.argv[1]).namelist() if ".dist-info/" not in n)))' "$1"; }
ref=$(ls "$build"/wheel-test/dist/mcstat-*.whl 2> /dev/null | head -1 || true)
if [ -n "$ref" ]; then
    d=$(diff <(names "$ref") <(names "$whl")) || fail "the sdist's wheel differs from the checkout's: $d"
    echo "sdist test: the wheel of the sdist holds the files of the checkout's ($(names "$whl" | wc -l) files)"
else
    echo "sdist test: no checkout wheel in $build/wheel-test (make wheel-test): file lists not compared"
fi
echo "sdist test passed: $(basename "$sdist") ($(du -k "$sdist" | cut -f1) KiB) built $(basename "$whl") in ${t_wheel} s; $((SECONDS - t0)) s in all"
