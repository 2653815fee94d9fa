#!/usr/bin/env bash
# A built wheel as a user's machine runs it: a bare venv of PYTHON (python -m
# venv, nothing else), LD_LIBRARY_PATH empty, cwd a temporary folder outside
# the checkout; `pip install 'WHEEL[report]'`, then `mcstat reproduce --quick`
# must write report.md and results.json with no traceback, mcstat._core must
# come from the venv (and, when the wheel bundles libgsl in mcstat.libs/,
# load it from there, every library resolved), and mcstat.__version__ must be
# the header's.  Logs and the report go to OUT.  The shared last step of
# tests/wheel/test_wheel_extra.sh and tools/wheels/build_wheels.sh.
#   usage: tests/wheel/bare_venv_reproduce.sh PYTHON WHEEL OUT
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
py=$1 whl=$2 out=$3
mkdir -p "$out"
fail() { echo "bare venv: $*" >&2; exit 1; }
version=$(awk '/#define MCSTAT_VERSION_(MAJOR|MINOR|PATCH) / {v = v (v == "" ? "" : ".") $3} END {print v}' \
    "$root/libmcstat/include/mcstat/version.h")
bundled=$("$py" -c 'import sys, zipfile; print(any(n.startswith("mcstat.libs/libgsl-") for n in zipfile.ZipFile(sys.argv[1]).namelist()))' "$whl")
tmp=$(mktemp -d /tmp/mcstat-wheel.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
export LD_LIBRARY_PATH=
unset PYTHONPATH PYTHONHOME
cd "$tmp"
"$py" -m venv venv || fail "$py -m venv"
venv/bin/python -m pip install -q "$whl[report]" > "$out/pip.log" 2>&1 || { tail -20 "$out/pip.log"; fail "pip install $whl[report]"; }
core=$(venv/bin/python -c 'import mcstat._core as c; print(c.__file__)') || fail "import mcstat._core"
case $core in "$tmp"/venv/*) ;; *) fail "mcstat._core imported from $core" ;; esac
deps=$(ldd "$core")
! grep -q "not found" <<< "$deps" || fail "unresolved libraries: $deps"
if [ "$bundled" = True ]; then
    grep -q "mcstat.libs/libgsl-" <<< "$deps" || fail "libgsl not loaded from mcstat.libs: $deps"
fi
rm -rf "$out/report"
venv/bin/mcstat reproduce --quick --out "$out/report" --no-progress > "$out/reproduce.out" 2> "$out/reproduce.err" \
    || { tail -20 "$out/reproduce.err"; fail "mcstat reproduce --quick"; }
! grep -q Traceback "$out/reproduce.err" || { cat "$out/reproduce.err"; fail "mcstat reproduce: a traceback"; }
for f in report.md results.json; do [ -s "$out/report/$f" ] || fail "reproduce wrote no $f"; done
got=$(venv/bin/python -c 'import mcstat; print(mcstat.__version__)') || fail "import mcstat"
[ "$got" = "$version" ] || fail "mcstat.__version__ is $got, the header's $version"
