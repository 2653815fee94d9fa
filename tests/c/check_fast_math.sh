#!/bin/sh
# libmcstat refuses to compile with -ffast-math and its parts (src/fpenv.h
# says why), while code that only includes the public headers still compiles
# with them.  Usage: check_fast_math.sh CC SOURCE_DIR
cc=$1
src=$2
inc="-I$src/libmcstat/include -I$src/libmcstat/src"
tmp=${TMPDIR:-/tmp}/mcstat_fast_math.$$
trap 'rm -f "$tmp".*' EXIT
fail=0
# the check is on the flags, not on a broken setup: the plain build works
if ! $cc -std=gnu11 -fsyntax-only $inc "$src/libmcstat/src/moments.c" 2> "$tmp.err"; then
    echo "moments.c does not compile even without -ffast-math:"; cat "$tmp.err"; exit 1
fi
for flags in "-ffast-math" "-Ofast" "-ffinite-math-only" "-funsafe-math-optimizations"; do
    # clang announces -funsafe-math-optimizations by no macro: not detectable
    if ! $cc $flags -dM -E -x c /dev/null 2> /dev/null |
        grep -qE "__FAST_MATH__|__FINITE_MATH_ONLY__ 1|__ASSOCIATIVE_MATH__|__RECIPROCAL_MATH__"; then
        echo "skip: $cc defines no macro for $flags"; continue
    fi
    if $cc -std=gnu11 -fsyntax-only $flags $inc "$src/libmcstat/src/moments.c" 2> "$tmp.err"; then
        echo "FAIL: libmcstat's moments.c compiled with $flags"; fail=1
    elif ! grep -q "libmcstat must be compiled with IEEE floating-point semantics" "$tmp.err"; then
        echo "FAIL: $flags refused without the explanation:"; cat "$tmp.err"; fail=1
    else
        echo "ok: $flags refused"
    fi
done
printf '#include "mcstat.h"\n#include "mcstat/embedded.h"\nint main(void) { return mcstat_strerror(0) == 0; }\n' > "$tmp.c"
if $cc -std=gnu11 -fsyntax-only -ffast-math $inc "$tmp.c" 2> "$tmp.err"; then
    echo "ok: a caller's code with -ffast-math includes mcstat.h and mcstat/embedded.h"
else
    echo "FAIL: mcstat.h does not compile in a caller's -ffast-math code:"; cat "$tmp.err"; fail=1
fi
exit $fail
