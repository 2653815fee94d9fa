#!/bin/sh
# mcstat/embedded.h is warning-free in the caller's code: check_macros_user.c
# compiled with MCSTAT_CHECKS=0 and =1, as C (C99, C11) and C++ (C++11,
# C++17; -Wold-style-cast, -Wzero-as-null-pointer-constant), under -Wall
# -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wundef
# -Wcast-qual, by the build's compilers and by clang/clang++ when installed;
# and as C11 with MCSTAT_NO_EXPERIMENTAL (the sequential mode then absent).
# Any diagnostic fails.  usage: check_macros_warnings.sh CC CXX INCLUDE_DIR
# (CXX empty: no C++ compiler).
set -eu
cc="$1" cxx="$2" inc="$3"
src="$(dirname "$0")/check_macros_user.c"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
warn="-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wundef -Wcast-qual -Werror"
ccs="$cc" cxxs="$cxx"
if command -v clang > /dev/null 2>&1 && [ "$(command -v clang)" != "$(command -v "$cc")" ]; then ccs="$ccs clang"; fi
if [ -n "$cxx" ] && command -v clang++ > /dev/null 2>&1 && [ "$(command -v clang++)" != "$(command -v "$cxx")" ]; then
    cxxs="$cxxs clang++"
fi
n=0
compile() { # what compiler args...
    what=$1
    shift
    if ! "$@" -I "$inc" -c -o "$tmp/user.o" > "$tmp/out" 2>&1 || [ -s "$tmp/out" ]; then
        cat "$tmp/out"
        echo "mcstat/embedded.h: diagnostics in a caller's code: $what"
        exit 1
    fi
    n=$((n + 1))
}
for checks in 0 1; do
    for c in $ccs; do
        for std in c99 c11; do
            # shellcheck disable=SC2086
            compile "$c -std=$std MCSTAT_CHECKS=$checks" "$c" -std=$std $warn -DMCSTAT_CHECKS=$checks "$src"
        done
    done
    for c in $cxxs; do
        for std in c++11 c++17; do
            # shellcheck disable=SC2086
            compile "$c -std=$std MCSTAT_CHECKS=$checks" "$c" -x c++ -std=$std $warn -Wold-style-cast \
                -Wzero-as-null-pointer-constant -DMCSTAT_CHECKS=$checks "$src"
        done
    done
    # without the experimental sections the rest of the header still compiles
    # shellcheck disable=SC2086
    compile "$cc -std=c11 MCSTAT_CHECKS=$checks MCSTAT_NO_EXPERIMENTAL" "$cc" -std=c11 $warn \
        -DMCSTAT_CHECKS=$checks -DMCSTAT_NO_EXPERIMENTAL "$src"
done
echo "mcstat/embedded.h: no diagnostic in $n compilations (C: $ccs; C++: ${cxxs:-none}; checks on and off)"
