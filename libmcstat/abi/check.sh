#!/bin/sh
# check.sh BASELINE.abi LIBRARY.so HEADERS_DIR: compares the ABI of a freshly
# built libmcstat (built with -g) against the committed baseline.
# Fails on any change abidiff reports other than additions:
#   exit bit 8 (ABIDIFF_ABI_INCOMPATIBLE_CHANGE): a symbol removed, the
#     SONAME changed;
#   exit bit 4 (ABIDIFF_ABI_CHANGE) alone: a change abidiff cannot judge
#     (a struct member's type, offset or size, a parameter's type, an enum
#     value), which breaks 0.1.0 binaries as surely here.
# Added functions and variables are allowed (--no-added-syms leaves them out
# of the verdict), and so are options structs grown by members appended at
# the end (grown-options.suppr); changes libabigail knows to be harmless (a member replaced
# by an anonymous union over the same storage) are filtered by abidiff
# itself and listed below for review.  An intended break bumps
# MCSTAT_SOVERSION in mcstat.h and regenerates the baseline (README.md here).
set -u
base="$1" lib="$2" headers="$3"
[ -f "$base" ] && [ -f "$lib" ] || { echo "usage: $0 BASELINE.abi LIBRARY.so HEADERS_DIR" >&2; exit 2; }
cur=$(mktemp --suffix=.abi) || exit 1
trap 'rm -f "$cur"' EXIT
# the same options as the baseline (README.md)
abidw --headers-dir "$headers" --drop-private-types --no-corpus-path --no-comp-dir-path --no-show-locs \
  --type-id-style hash --out-file "$cur" "$lib" || { echo "abidw failed on $lib" >&2; exit 1; }
# options structs that grew by appended members (grown-options.suppr says why)
suppr="$(dirname "$0")/grown-options.suppr"
echo "== every change against $(basename "$base") (additions and harmless changes included):"
abidiff --harmless --leaf-changes-only "$base" "$cur"
echo "== the verdict (additions and options grown at the end left out):"
abidiff --no-added-syms --suppressions "$suppr" "$base" "$cur"
rc=$?
if [ "$rc" -eq 0 ]; then
    echo "abi-check: compatible with $(basename "$base")"
    exit 0
fi
if [ $((rc & 3)) -ne 0 ]; then
    echo "abi-check: abidiff failed (exit $rc)" >&2
elif [ $((rc & 8)) -ne 0 ]; then
    echo "abi-check: INCOMPATIBLE ABI change (abidiff exit $rc): see above" >&2
else
    echo "abi-check: ABI change that breaks binaries built against the baseline (abidiff exit $rc): see above" >&2
fi
exit 1
