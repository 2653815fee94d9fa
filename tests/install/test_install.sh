#!/usr/bin/env bash
# The installed package, as an outside project sees it: cmake --install into
# a staging prefix, then build consumers against it with
#   1. find_package(mcstat) -> mcstat::mcstat (shared) and mcstat::mcstat_static,
#      including the checks example through the installed mcstat_check.h;
#   2. pkg-config mcstat (shared), and pkg-config --static for a fully static
#      executable (Requires.private: gsl, Libs.private: -lm -pthread);
# and run each.  usage: tests/install/test_install.sh BUILD_DIR
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(cd "${1:-build}" && pwd)
stage="$build/stage"
work="$build/install-test"
rm -rf "$stage" "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$stage" > "$work/install.log"

fail() { echo "install test FAILED: $*" >&2; exit 1; }
for f in include/mcstat.h include/mcstat/base.h include/mcstat/check.h include/mcstat/embedded.h include/mcstat/version.h include/mcstat/gof.h include/mcstat_check.h include/mcstat_testing.h include/mcstat_pbrt.h; do
    [ -f "$stage/$f" ] || fail "missing $f"
done
libdir=$(dirname "$(find "$stage" -name libmcstat.a | head -1)")
[ -f "$libdir/libmcstat.a" ] || fail "no static library"
ls "$libdir"/libmcstat.so.* > /dev/null || fail "no versioned shared library"
for f in cmake/mcstat/mcstatConfig.cmake cmake/mcstat/mcstatConfigVersion.cmake cmake/mcstat/mcstatTargets.cmake \
         pkgconfig/mcstat.pc pkgconfig/mcstat-rpath.pc; do
    [ -f "$libdir/$f" ] || fail "missing $libdir/$f"
done

# `cmd | grep -q` under pipefail fails when grep exits at its first match
# and cmd then dies of SIGPIPE (ldd's output grew with libRmath): read the
# whole output first.
has() { local out; out=$("${@:2}") || return 2; grep -q -- "$1" <<< "$out"; }

check_demo() { # every question the demo asks gets its R-style block with a decision
    local out; out=$("$@") || fail "$* exited $?"
    local asked answered
    asked=$(grep -c '^==> ' <<< "$out"); answered=$(grep -c '^decision at alpha = 0.05: ' <<< "$out")
    [ "$asked" -ge 5 ] && [ "$asked" = "$answered" ] || fail "$*: $asked questions, $answered decisions"
}

# 1. CMake package
cmake -S examples/c -B "$work/cmake" -DCMAKE_PREFIX_PATH="$stage" -DCMAKE_BUILD_TYPE=Release > "$work/cmake.log"
cmake --build "$work/cmake" -j 2 > "$work/cmake-build.log" || { cat "$work/cmake-build.log"; fail "cmake consumer"; }
check_demo "$work/cmake/mcstat_demo"
check_demo "$work/cmake/mcstat_demo_static"
if has libmcstat ldd "$work/cmake/mcstat_demo_static"; then fail "static demo links libmcstat.so"; fi
has "$stage" ldd "$work/cmake/mcstat_demo" || fail "shared demo does not use the staged libmcstat.so"
"$work/cmake/mcstat_integrator" --samples 200000 --frames 1 > "$work/integrator.log" || fail "integrator checks"
"$work/cmake/mcstat_integrator" --samples 200000 --frames 1 --bug bias --expect-failure mean \
    > "$work/integrator-bug.log" 2>&1 || fail "integrator did not catch its bug"
grep -q "checks on" "$work/integrator.log" || fail "integrator built without checks"

# 2. pkg-config
export PKG_CONFIG_PATH="$libdir/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
# the version and the SOVERSION are the installed header's (their one source)
hdr_version=$(for p in MAJOR MINOR PATCH; do sed -n "s/^#define MCSTAT_VERSION_$p \([0-9]*\)$/\1/p" "$stage/include/mcstat/version.h"; done | paste -sd.)
hdr_soversion=$(sed -n 's/^#define MCSTAT_SOVERSION \([0-9]*\)$/\1/p' "$stage/include/mcstat/version.h")
[ -n "$hdr_soversion" ] && [ "$(pkg-config --modversion mcstat)" = "$hdr_version" ] || fail "pkg-config version"
[ -f "$libdir/libmcstat.so.$hdr_soversion" ] && [ -f "$libdir/libmcstat.so.$hdr_version" ] \
    || fail "libmcstat.so.$hdr_soversion / libmcstat.so.$hdr_version not installed"
cc=${CC:-cc}
# shellcheck disable=SC2046
$cc -O2 -o "$work/demo-pc" examples/c/demo.c $(pkg-config --cflags --libs mcstat) -Wl,-rpath,"$libdir" -lm
check_demo "$work/demo-pc"
# shellcheck disable=SC2046
$cc -O2 -static -o "$work/demo-pc-static" examples/c/demo.c $(pkg-config --static --cflags --libs mcstat) \
    2> "$work/static.log" || { cat "$work/static.log"; fail "static link through pkg-config --static"; }
if has NEEDED readelf -d "$work/demo-pc-static"; then fail "not a static executable"; fi
check_demo "$work/demo-pc-static"
# 3. libRmath (Requires.private of mcstat.pc): a consumer of the power
# calculations, shared and fully static
# shellcheck disable=SC2046
$cc -O2 -o "$work/power-pc" tests/install/power_consumer.c $(pkg-config --cflags --libs mcstat) -Wl,-rpath,"$libdir" -lm
"$work/power-pc" > /dev/null || fail "power consumer (shared)"
# shellcheck disable=SC2046
$cc -O2 -static -o "$work/power-pc-static" tests/install/power_consumer.c $(pkg-config --static --cflags --libs mcstat) \
    2> "$work/power-static.log" || { cat "$work/power-static.log"; fail "static power consumer through pkg-config --static"; }
if has NEEDED readelf -d "$work/power-pc-static"; then fail "power consumer: not a static executable"; fi
"$work/power-pc-static" > /dev/null || fail "power consumer (static)"
# 4. the pbrt adapter as a pbrt user builds it: the drop-in GoogleTest file
# against the installed mcstat_pbrt.h and mcstat_testing.h (its stand-in
# BxDFs from the source tree), when GoogleTest is there
cxx=${CXX:-c++}
if command -v "$cxx" > /dev/null && printf '#include <gtest/gtest.h>\n' | "$cxx" -E -x c++ - > /dev/null 2>&1; then
    # shellcheck disable=SC2046
    "$cxx" -std=c++17 -O2 -o "$work/pbrt-dropin" examples/pbrt/test_pbrt_bsdf.cpp $(pkg-config --cflags --libs mcstat) \
        -Wl,-rpath,"$libdir" -lgtest -lgtest_main -pthread 2> "$work/pbrt.log" || { cat "$work/pbrt.log"; fail "pbrt drop-in test"; }
    MCSTAT_SEED=0 MCSTAT_SUITE_ALPHA=1e-3 "$work/pbrt-dropin" > "$work/pbrt-run.log" 2>&1 \
        || { cat "$work/pbrt-run.log"; fail "pbrt drop-in test failed"; }
    pbrt="and the pbrt adapter's drop-in test"
else
    pbrt="(no GoogleTest: the pbrt adapter's drop-in test skipped)"
fi
echo "install test: headers, shared + static libraries, CMake package (shared, static, checks),"
echo "pkg-config (shared, fully static) consumers $pbrt built from $stage and run"
echo "1 passed, 0 failed"
