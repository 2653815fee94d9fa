#!/usr/bin/env bash
# Binary wheels for CPython 3.9-3.13 at manylinux_2_28, without docker:
#   1. sources: Debian bookworm's GSL and R (for R's nmath, the standalone
#      libRmath), fetched from the Debian mirror apt uses here, each .dsc
#      checked against a sha256 pinned below and unpacked by dpkg-source
#      (which checks the tarballs against the .dsc and applies Debian's
#      patches); cached in build/wheels/src/;
#   2. zig (the ziglang package from PyPI, pinned) as C and C++ compiler for
#      x86_64-linux-gnu.2.28: GSL and libRmath built as static, -fPIC
#      archives into build/wheels/prefix/ (once; a stamp file each);
#   3. one wheel per interpreter (~/.pyenv/versions/3.X.*): pip wheel in a
#      throwaway venv with scikit-build-core and pybind11, CMake pointed at
#      the zig-built GSL (GSL_ROOT_DIR) and libRmath (PKG_CONFIG_PATH), the
#      extension linked with --exclude-libs,ALL (GSL, Rmath and zig's
#      libc++ stay inside it, unexported); auditwheel repair --plat
#      manylinux_2_28_x86_64, and auditwheel show must report manylinux_2_28
#      or older;
#   4. each wheel in a bare venv of its own interpreter (python -m venv,
#      LD_LIBRARY_PATH empty, cwd a temporary directory outside the
#      checkout): pip install 'WHEEL[report]', mcstat reproduce --quick and
#      import mcstat;
#   5. bench/RESULTS_wheels.md: the wheels, sizes, levels, tests, timings.
#   usage: tools/wheels/build_wheels.sh [3.9 3.10 ...]   (default: 3.9-3.13)
# Environment: WHEELS_DIR (build/wheels), JOBS (2), AUDITWHEEL (the
# developer venv's, .venv/bin/auditwheel), PYENV_ROOT (~/.pyenv),
# WHEELS_PYTEST=3.12 also runs tests/python/test_pixels_api.py and
# test_module.py against that version's wheel (numpy, scipy, pytest in a venv).
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$PWD
W=$(mkdir -p "${WHEELS_DIR:-build/wheels}" && cd "${WHEELS_DIR:-build/wheels}" && pwd)
JOBS=${JOBS:-2}
AUDITWHEEL=${AUDITWHEEL:-$root/.venv/bin/auditwheel}
PYENV_ROOT=${PYENV_ROOT:-$HOME/.pyenv}
VERSIONS=("$@")
[ ${#VERSIONS[@]} -gt 0 ] || VERSIONS=(3.9 3.10 3.11 3.12 3.13)

ZIG_VERSION=0.14.1
GLIBC=2.28
TARGET=x86_64-linux-gnu.$GLIBC
PLAT=manylinux_${GLIBC/./_}_x86_64
SKBUILD_CORE_VERSION=1.1.2
PYBIND11_VERSION=3.1.0
# Debian bookworm's source packages (the versions of the system's
# libgsl-dev and r-mathlib) and the sha256 of each .dsc.
GSL_DSC=pool/main/g/gsl/gsl_2.7.1+dfsg-5+deb12u1.dsc
GSL_DSC_SHA256=77bf2b75142d2b19bd0b837dc7a42189704b9451e6f6c8ddeab3d1227a76ed0a
R_DSC=pool/main/r/r-base/r-base_4.2.2.20221110-2.dsc
R_DSC_SHA256=c4be9998471983df414d35722d86ebbd3bae07db4824cadbb89c1c12e9f20066

fail() { echo "build_wheels FAILED: $*" >&2; exit 1; }
log() { echo "== $*"; }
[ -x "$AUDITWHEEL" ] || fail "no auditwheel at $AUDITWHEEL (make python-deps)"
command -v dpkg-source > /dev/null || fail "dpkg-source missing (apt-get install dpkg-dev)"
t_all=$SECONDS

# ---- 1. sources ---------------------------------------------------------------
# The Debian archive apt uses (deb822 .sources or one-line lists).
mirror() {
    local m
    m=$(cat /etc/apt/sources.list.d/*.sources 2>/dev/null | awk '/^URIs:/ {for (i = 2; i <= NF; i++) print $i}' | grep -E '/debian/?$' | head -1 || true)
    [ -n "$m" ] || m=$(cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
        awk '$1 == "deb" || $1 == "deb-src" {for (i = 2; i <= NF; i++) if ($i ~ /^https?:/) {print $i; break}}' | grep -E '/debian/?$' | head -1 || true)
    [ -n "$m" ] || fail "no Debian mirror in /etc/apt/sources.list*"
    echo "${m%/}"
}
src=$W/src
mkdir -p "$src"
fetch() { # fetch URL FILE: download once (a .part renamed when complete)
    [ -s "$2" ] && return 0
    curl -fsSL --retry 3 -o "$2.part" "$1" || fail "download $1"
    mv "$2.part" "$2"
}
unpack() { # unpack DSC_PATH SHA256 DIR
    local dsc base url f
    dsc=$src/$(basename "$1")
    base=$(mirror)/$(dirname "$1")
    [ -f "$src/$3/.unpacked" ] && return 0
    fetch "$(mirror)/$1" "$dsc"
    echo "$2  $dsc" | sha256sum -c --quiet - || { rm -f "$dsc"; fail "$dsc: sha256 mismatch"; }
    for f in $(awk '/^Checksums-Sha256:/ {on = 1; next} /^[^ ]/ {on = 0} on {print $3}' "$dsc"); do
        fetch "$base/$f" "$src/$f"
    done
    # the tarballs against the .dsc's sha256 (dpkg-source checks them too)
    awk '/^Checksums-Sha256:/ {on = 1; next} /^[^ ]/ {on = 0} on {print $1 "  " $3}' "$dsc" |
        (cd "$src" && sha256sum -c --quiet -) || fail "$dsc: a tarball does not match"
    rm -rf "${src:?}/$3"
    (cd "$src" && dpkg-source --no-copy -x "$dsc" "$3") > "$src/$3.unpack.log" 2>&1 ||
        { cat "$src/$3.unpack.log"; fail "dpkg-source -x $dsc"; }
    touch "$src/$3/.unpacked"
}
log "sources"
unpack "$GSL_DSC" "$GSL_DSC_SHA256" gsl
unpack "$R_DSC" "$R_DSC_SHA256" r-base

# ---- 2. zig, GSL, libRmath ---------------------------------------------------
if [ ! -x "$W/tools/bin/python" ] || ! "$W/tools/bin/python" -m ziglang version 2> /dev/null | grep -qx "$ZIG_VERSION"; then
    log "zig $ZIG_VERSION (ziglang from PyPI)"
    rm -rf "$W/tools"
    python3 -m venv "$W/tools"
    "$W/tools/bin/python" -m pip install -q "ziglang==$ZIG_VERSION"
fi
zig=$("$W/tools/bin/python" -c 'import os, ziglang; print(os.path.join(os.path.dirname(ziglang.__file__), "zig"))')
mkdir -p "$W/bin"
for t in cc c++; do
    printf '#!/bin/sh\nexec %s %s -target %s "$@"\n' "$zig" "$t" "$TARGET" > "$W/bin/zig-${t/++/xx}"
    chmod +x "$W/bin/zig-${t/++/xx}"
done
CC=$W/bin/zig-cc
CXX=$W/bin/zig-cxx
export ZIG_GLOBAL_CACHE_DIR=$W/zig-cache ZIG_LOCAL_CACHE_DIR=$W/zig-cache
prefix=$W/prefix
# Never -ffast-math; no FMA contraction (baseline x86-64 has none anyway),
# as libmcstat's own flags.
DEP_CFLAGS="-O2 -ffp-contract=off -fPIC"

if [ ! -f "$prefix/.gsl" ]; then
    log "GSL with zig cc ($TARGET)"
    t0=$SECONDS
    rm -rf "$W/gsl-build" && mkdir -p "$W/gsl-build" "$prefix"
    (
        cd "$W/gsl-build"
        "$src/gsl/configure" --prefix="$prefix" --disable-shared --enable-static --with-pic \
            CC="$CC" CFLAGS="$DEP_CFLAGS" > configure.log 2>&1 || { tail -30 configure.log; exit 1; }
        # Debian's +dfsg tarball has no documentation sources
        sed -i '/^SUBDIRS = /s/ doc\b//' Makefile
        make -j"$JOBS" > make.log 2>&1 || { grep -n -B2 -A8 'error' make.log | head -60; exit 1; }
        make install > install.log 2>&1
    ) || fail "GSL build (logs in $W/gsl-build)"
    touch "$prefix/.gsl"
    echo "GSL built in $((SECONDS - t0)) s"
fi

# libRmath as R's src/nmath/standalone/Makefile builds it (its source list,
# MATHLIB_STANDALONE, sunif.c as std_unif.c), without R's configure: the
# config.h below holds what configure finds on x86-64 glibc for the macros
# nmath reads; Rconfig.h is made from it by R's own tools/GETCONFIG and
# Rmath.h from Rmath.h0.in as configure would.  glibc 2.28 has no cospi,
# sinpi, tanpi or atanpi, so nmath's own are used (as on Debian 12).
if [ ! -f "$prefix/.rmath" ]; then
    log "libRmath (R's nmath, standalone) with zig cc ($TARGET)"
    t0=$SECONDS
    rs=$src/r-base
    rb=$W/rmath-build
    rm -rf "$rb" && mkdir -p "$rb/include" "$prefix/lib/pkgconfig" "$prefix/include"
    rversion=$(cut -d' ' -f1 "$rs/VERSION")
    cat > "$rb/include/config.h" <<'EOF'
/* nmath's configuration for x86-64 Linux (glibc), as R's configure finds it */
#define IEEE_754 1
#define HAVE_F77_UNDERSCORE 1
#define R_INLINE inline
#define HAVE_VISIBILITY_ATTRIBUTE 1
#define SIZEOF_SIZE_T 8
#define HAVE_ALLOCA_H 1
#define HAVE_UINTPTR_T 1
#define HAVE_LONG_DOUBLE 1
#define HAVE_EXPM1 1
#define HAVE_HYPOT 1
#define HAVE_LOG1P 1
#define HAVE_LOG1PL 1
#define HAVE_WORKING_LOG1P 1
#define HAVE_NEARBYINT 1
#define HAVE_WORKING_ISFINITE 1
EOF
    (cd "$rb/include" && sh "$rs/tools/GETCONFIG" > Rconfig.h) || fail "Rconfig.h"
    sed -e "s/@PACKAGE_VERSION@/$rversion/" -e 's/@RMATH_HAVE_WORKING_LOG1P@/# define HAVE_WORKING_LOG1P 1/' \
        "$rs/src/include/Rmath.h0.in" > "$rb/include/Rmath.h"
    ! grep -n '@[A-Z_]*@' "$rb/include/Rmath.h" || fail "Rmath.h: a configure substitution left"
    # SOURCES_NMATH of the standalone Makefile
    nmath=$(awk '/^SOURCES_NMATH = / {on = 1; sub(/^SOURCES_NMATH = /, "")} on {c = sub(/\\$/, ""); print; if (!c) exit}' \
        "$rs/src/nmath/standalone/Makefile.in")
    [ "$(wc -w <<< "$nmath")" -gt 100 ] || fail "SOURCES_NMATH not found in R's standalone Makefile.in"
    cp "$rs/src/nmath/standalone/sunif.c" "$rb/std_unif.c"
    objs=()
    for f in $nmath std_unif.c; do
        s=$rs/src/nmath/$f
        [ "$f" = std_unif.c ] && s=$rb/std_unif.c
        objs+=("$rb/${f%.c}.o")
        echo "$CC $DEP_CFLAGS -DHAVE_CONFIG_H -DMATHLIB_STANDALONE -I$rb/include -I$rs/src/include -I$rs/src/nmath -c $s -o $rb/${f%.c}.o"
    done > "$rb/compile.sh"
    xargs -P "$JOBS" -I{} sh -c {} < "$rb/compile.sh" > "$rb/compile.log" 2>&1 || { tail -40 "$rb/compile.log"; fail "nmath compile"; }
    ar -cr "$prefix/lib/libRmath.a" "${objs[@]}" && ranlib "$prefix/lib/libRmath.a"
    cp "$rb/include/Rmath.h" "$prefix/include/Rmath.h"
    sed -e "s:@libdir:$prefix/lib:" -e "s:@includedir:$prefix/include:" -e "s/@VERSION/$rversion/" -e 's/@libm/-lm/' \
        "$rs/src/nmath/standalone/libRmath.pc.in" > "$prefix/lib/pkgconfig/libRmath.pc"
    touch "$prefix/.rmath"
    echo "libRmath built in $((SECONDS - t0)) s"
fi

# __builtin_cpu_supports("avx2") (libmcstat's runtime dispatch: moments.c,
# pixels.c, ks_simulate.c) reads __cpu_model, set by __cpu_indicator_init,
# which zig's compiler_rt does not provide.  GCC's libgcc.a (Debian's gcc,
# the compiler of the system build) has them in cpuinfo.o: hidden, position
# independent, no undefined symbol, the layout clang's builtin reads.  That
# one object, as an archive on every link line.
if [ ! -f "$prefix/lib/libcpumodel.a" ]; then
    libgcc=$(gcc -print-libgcc-file-name 2> /dev/null || true)
    [ -f "$libgcc" ] || fail "no libgcc.a (gcc) for __cpu_model"
    rm -rf "$W/cpumodel" && mkdir -p "$W/cpumodel"
    (cd "$W/cpumodel" && ar x "$libgcc" cpuinfo.o) || fail "no cpuinfo.o in $libgcc"
    ! nm "$W/cpumodel/cpuinfo.o" | grep -q ' U ' || fail "cpuinfo.o has undefined symbols"
    ar -cr "$prefix/lib/libcpumodel.a" "$W/cpumodel/cpuinfo.o" && ranlib "$prefix/lib/libcpumodel.a"
fi

# ---- 3. the wheels -------------------------------------------------------------
interpreter() { # interpreter 3.X: the pyenv CPython 3.X.*
    local d
    d=$(ls -d "$PYENV_ROOT"/versions/"$1".* 2> /dev/null | sort -V | tail -1 || true)
    [ -n "$d" ] && [ -x "$d/bin/python3" ] || fail "CPython $1 not found in $PYENV_ROOT/versions/"
    echo "$d/bin/python3"
}
# The extension keeps GSL, libRmath, libmcstat and zig's libc++/libc++abi/
# libunwind to itself: a version script exports PyInit_* alone (zig's
# linker takes no --exclude-libs).  Only the modules: libmcstat.so, built
# beside them, goes into no wheel.
printf '{\n  global: PyInit_*;\n  local: *;\n};\n' > "$W/bin/extension.map"
LINK_FLAGS="-Wl,--version-script=$W/bin/extension.map"
VERSION=$(awk '/#define MCSTAT_VERSION_(MAJOR|MINOR|PATCH) / {v = v (v == "" ? "" : ".") $3} END {print v}' libmcstat/include/mcstat.h)
declare -A R_WHEEL R_SIZE R_LEVEL R_BUILD R_TEST R_STATUS R_PY R_CMP
# WHEELS_COMPARE=PYTHON: an interpreter whose mcstat is the gcc build (make
# python's .venv); its `mcstat reproduce --quick` results.json is the
# reference each wheel's is compared with, number by number.
ref_json=""
if [ -n "${WHEELS_COMPARE:-}" ]; then
    mkdir -p "$W/gcc-reference"
    if (cd /tmp && LD_LIBRARY_PATH= "$WHEELS_COMPARE" -c "import mcstat, sys; sys.exit(mcstat.__version__ != '$VERSION')") 2> /dev/null &&
        (cd /tmp && LD_LIBRARY_PATH= "$(dirname "$WHEELS_COMPARE")/mcstat" reproduce --quick --out "$W/gcc-reference/report" \
            --no-progress > "$W/gcc-reference/reproduce.out" 2>&1); then
        ref_json=$W/gcc-reference/report/results.json
    else
        echo "WHEELS_COMPARE=$WHEELS_COMPARE: no mcstat $VERSION there, or its reproduce failed; no comparison"
    fi
fi
results=$W/results
rm -rf "$results" && mkdir -p "$results"
for v in "${VERSIONS[@]}"; do
    tag=cp${v/./}
    py=$(interpreter "$v")
    R_PY[$v]=$("$py" -c 'import platform; print(platform.python_version())')
    out=$W/out/$tag
    rm -rf "$out" && mkdir -p "$out/dist" "$out/repaired"
    log "CPython ${R_PY[$v]}: wheel"
    t0=$SECONDS
    fresh=""
    ls -d "$W"/cmake/"$tag"-* > /dev/null 2>&1 && fresh=" (incremental)"
    bv=$W/venv/$tag-build
    if [ ! -x "$bv/bin/python" ]; then
        "$py" -m venv "$bv"
        "$bv/bin/python" -m pip install -q --upgrade pip > /dev/null
        "$bv/bin/python" -m pip install -q "scikit-build-core==$SKBUILD_CORE_VERSION" "pybind11==$PYBIND11_VERSION" ||
            fail "$tag: build venv"
    fi
    # Only the zig-built libraries are visible to pkg-config (libRmath's
    # lookup in libmcstat/mcstatRmath.cmake, and FindGSL's); GSL_ROOT_DIR
    # puts the prefix first for FindGSL.  No LTO (pybind11 would add it).
    # kept for an incremental rebuild, configured anew (the defines below win)
    rm -f "$W"/cmake/"$tag"-*/CMakeCache.txt
    CC=$CC CXX=$CXX PKG_CONFIG_LIBDIR=$prefix/lib/pkgconfig PKG_CONFIG_PATH= \
        CMAKE_BUILD_PARALLEL_LEVEL=$JOBS \
        "$bv/bin/python" -m pip wheel -v --no-deps --no-build-isolation \
        -Cbuild-dir="$W/cmake/{wheel_tag}" \
        -Ccmake.define.GSL_ROOT_DIR="$prefix" \
        -Ccmake.define.CMAKE_INTERPROCEDURAL_OPTIMIZATION=OFF \
        -Ccmake.define.CMAKE_MODULE_LINKER_FLAGS="$LINK_FLAGS" \
        -Ccmake.define.CMAKE_C_STANDARD_LIBRARIES="$prefix/lib/libcpumodel.a" \
        -Ccmake.define.CMAKE_CXX_STANDARD_LIBRARIES="$prefix/lib/libcpumodel.a" \
        -w "$out/dist" "$root" > "$out/wheel.log" 2>&1 || { tail -60 "$out/wheel.log"; fail "$tag: pip wheel (log: $out/wheel.log)"; }
    grep -q "zig-cc" "$W/cmake/$tag-$tag-linux_x86_64/CMakeCache.txt" 2> /dev/null ||
        grep -rqs "zig-cc" "$W"/cmake/"$tag"-*/CMakeCache.txt || fail "$tag: CMake did not use zig"
    raw=$(ls "$out"/dist/mcstat-*.whl)
    PATH="$(dirname "$AUDITWHEEL"):$PATH" "$AUDITWHEEL" repair --plat "$PLAT" -w "$out/repaired" "$raw" > "$out/repair.log" 2>&1 ||
        { cat "$out/repair.log"; fail "$tag: auditwheel repair"; }
    whl=$(ls "$out"/repaired/mcstat-*.whl)
    "$AUDITWHEEL" show "$whl" > "$out/show.log" 2>&1 || { cat "$out/show.log"; fail "$tag: auditwheel show"; }
    # "... is consistent with the following platform tag: "manylinux_2_17_x86_64"."
    level=$(tr -s ' \n' ' ' < "$out/show.log" | grep -o 'consistent with the following platform tag: "[^"]*"' | head -1 | cut -d'"' -f2)
    [[ $level =~ ^manylinux_2_([0-9]+)_x86_64$ ]] || { cat "$out/show.log"; fail "$tag: no manylinux level in auditwheel show"; }
    [ "${BASH_REMATCH[1]}" -le "${GLIBC#2.}" ] || { cat "$out/show.log"; fail "$tag: $level is newer than $PLAT"; }
    # nothing bundled, nothing of GSL/Rmath/libc++ exported
    "$bv/bin/python" - "$whl" "$out/exports.txt" <<'PY' || fail "$tag: $(cat "$out/exports.txt")"
import sys, zipfile, subprocess, tempfile, os
whl, report = sys.argv[1:]
z = zipfile.ZipFile(whl)
names = z.namelist()
bad = [n for n in names if ".libs/" in n]
sos = [n for n in names if n.endswith(".so")]
d = tempfile.mkdtemp()
lines = []
for n in sos:
    p = z.extract(n, d)
    syms = subprocess.run(["nm", "-D", "--defined-only", p], capture_output=True, text=True, check=True).stdout.split("\n")
    exported = sorted(s.split()[-1] for s in syms if s.strip())
    extra = [s for s in exported if not s.startswith("PyInit_")]
    needed = subprocess.run(["readelf", "-d", p], capture_output=True, text=True, check=True).stdout
    cxx = [l for l in needed.split("\n") if "NEEDED" in l and ("c++" in l or "gsl" in l or "Rmath" in l)]
    lines.append(f"{n}: exports {exported}; {len(cxx)} unwanted NEEDED")
    if extra or cxx:
        bad.append(f"{n}: exports {extra[:10]} NEEDED {cxx}")
open(report, "w").write("\n".join(lines + bad) + "\n")
sys.exit(1 if bad else 0)
PY
    R_WHEEL[$v]=$(basename "$whl")
    R_SIZE[$v]=$(du -k "$whl" | cut -f1)
    R_LEVEL[$v]=$level
    R_BUILD[$v]="$((SECONDS - t0))$fresh"
    echo "${R_WHEEL[$v]}: $level, ${R_SIZE[$v]} KiB, built in ${R_BUILD[$v]} s"

    # ---- 4. the wheel in a bare venv of its interpreter ---------------------
    log "CPython ${R_PY[$v]}: test in a bare venv"
    t0=$SECONDS
    R_STATUS[$v]=FAIL
    if tests/wheel/bare_venv_reproduce.sh "$py" "$whl" "$out"; then R_STATUS[$v]=pass; fi
    R_TEST[$v]=$((SECONDS - t0))
    R_CMP[$v]="n/a"
    if [ -n "$ref_json" ] && [ -s "$out/report/results.json" ]; then
        R_CMP[$v]=$("$W/tools/bin/python" "$root/tools/wheels/compare_results.py" "$ref_json" "$out/report/results.json" --rtol 1e-9) ||
            { R_STATUS[$v]="FAIL (numbers)"; }
    fi
    echo "$tag: test ${R_STATUS[$v]} in ${R_TEST[$v]} s"
done

# ---- WHEELS_PYTEST=3.X: the Python tests of the pixel kernels and the module
# against that version's zig-built wheel (the tests' own tolerances, the
# same as for the gcc build of make pytest), from a cwd outside the checkout.
PYTEST_LINE=""
if [ -n "${WHEELS_PYTEST:-}" ]; then
    v=$WHEELS_PYTEST
    tag=cp${v/./}
    [ -n "${R_WHEEL[$v]:-}" ] || fail "WHEELS_PYTEST=$v: that version was not built in this run"
    log "CPython ${R_PY[$v]}: tests/python/test_pixels_api.py test_module.py on ${R_WHEEL[$v]}"
    out=$W/out/$tag
    tests=()
    for t in test_pixels_api.py test_module.py; do [ -f "$root/tests/python/$t" ] && tests+=("$root/tests/python/$t"); done
    t0=$SECONDS
    (
        tmp=$(mktemp -d /tmp/mcstat-pytest.XXXXXX)
        trap 'rm -rf "$tmp"' EXIT
        export LD_LIBRARY_PATH=
        cd "$tmp"
        "$(interpreter "$v")" -m venv venv
        venv/bin/python -m pip install -q "$out/repaired/${R_WHEEL[$v]}" numpy scipy pytest > "$out/pytest-pip.log" 2>&1 ||
            { tail -20 "$out/pytest-pip.log"; exit 1; }
        venv/bin/python -c "import mcstat, sys; sys.exit(not mcstat.__file__.startswith('$tmp/venv/'))" ||
            { echo "mcstat not imported from the venv"; exit 1; }
        # Deselected: test_gsl_handler_only_turned_off_when_default sets a
        # handler in the system's libgsl.so (ctypes) and expects mcstat to
        # see it, true of make python's build only: a wheel's GSL is its own
        # (here static and hidden; auditwheel's bundled copy is renamed too).
        venv/bin/python -m pytest -q -p no:cacheprovider "${tests[@]}" \
            -k "not test_gsl_handler_only_turned_off_when_default" 2>&1 | tee "$out/pytest.log"
        exit "${PIPESTATUS[0]}"
    ) || fail "$tag: pytest (log: $out/pytest.log)"
    PYTEST_LINE="- pytest on the CPython ${R_PY[$v]} wheel ($((SECONDS - t0)) s, numpy/scipy/pytest from PyPI): $(for t in "${tests[@]}"; do printf '%s ' "tests/python/$(basename "$t")"; done)→ $(grep -E '[0-9]+ (passed|failed)' "$out/pytest.log" | tail -1 | tr -d '=' | sed 's/^ *//; s/ *$//')"
fi

# ---- 5. bench/RESULTS_wheels.md ---------------------------------------------
failed=0
{
    echo "# Wheels for CPython ${VERSIONS[*]} ($PLAT)"
    echo
    echo "Written by \`make wheels\` (tools/wheels/build_wheels.sh); do not edit by hand."
    echo
    echo "- built: $(date -u +%Y-%m-%dT%H:%MZ), mcstat $VERSION ($(git rev-parse --short HEAD 2> /dev/null || echo '?'))"
    echo "- compiler: zig $ZIG_VERSION (PyPI ziglang), \`zig cc/c++ -target $TARGET\`; libc++ static, PyInit_* the only exports"
    echo "- GSL $(basename "$GSL_DSC" .dsc | sed 's/^gsl_//') and libRmath (R's nmath, standalone) from $(basename "$R_DSC" .dsc | sed 's/^r-base_/r-base /'), Debian source packages, built static with that compiler"
    echo "- scikit-build-core $SKBUILD_CORE_VERSION, pybind11 $PYBIND11_VERSION, $("$AUDITWHEEL" --version 2>&1 | head -1 | cut -d' ' -f1-2)"
    echo "- test: a bare venv of the same interpreter (\`python -m venv\`), LD_LIBRARY_PATH empty, cwd outside the checkout: \`pip install 'WHEEL[report]'\`, \`mcstat reproduce --quick --no-progress\` (report.md, results.json), \`import mcstat; mcstat.__version__\`"
    echo "- $JOBS build jobs; whole run $((SECONDS - t_all)) s (GSL and libRmath built once and cached in $(basename "$W")/prefix)"
    [ -z "$PYTEST_LINE" ] || echo "$PYTEST_LINE"
    [ -z "$ref_json" ] || echo "- vs gcc build: the wheel's results.json against that of \`mcstat reproduce --quick\` by the mcstat of $WHEELS_COMPARE (the system gcc, GSL and libRmath: make python), every number but timings and SciPy's normality p-values (tools/wheels/compare_results.py); a relative difference over 1e-9 fails"
    echo
    echo "| Python | wheel | size (KiB) | auditwheel show | build (s) | test | test (s) | vs gcc build |"
    echo "| --- | --- | ---: | --- | ---: | --- | ---: | --- |"
    for v in "${VERSIONS[@]}"; do
        echo "| ${R_PY[$v]} | ${R_WHEEL[$v]} | ${R_SIZE[$v]} | ${R_LEVEL[$v]} | ${R_BUILD[$v]} | ${R_STATUS[$v]} | ${R_TEST[$v]} | ${R_CMP[$v]} |"
        [ "${R_STATUS[$v]}" = pass ] || failed=1
    done
} > "$results/RESULTS_wheels.md"
mkdir -p "$W/dist"
for v in "${VERSIONS[@]}"; do cp "$W/out/cp${v/./}/repaired/${R_WHEEL[$v]}" "$W/dist/"; done
cp "$results/RESULTS_wheels.md" "$root/bench/RESULTS_wheels.md"
cat "$root/bench/RESULTS_wheels.md"
echo "wheels in $W/dist/"
[ "$failed" = 0 ] || fail "a wheel failed its test (see $W/out/cp*/)"
