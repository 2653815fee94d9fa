#!/bin/sh
# Every dynamic symbol the shared library defines starts with mcstat_, and the
# API's entry points are among them.
set -eu
lib="$1"
syms=$(nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBRVW]$/ {print $3}')
bad=$(printf '%s\n' "$syms" | grep -v '^mcstat_' || true)
if [ -n "$bad" ]; then
    echo "symbols without the mcstat_ prefix:"; printf '%s\n' "$bad"; exit 1
fi
# Every function the public header declares (MCSTAT_API ... mcstat_name(...))
# is exported: the list comes from the header, so a new entry point is checked
# without editing this script.
# mcstat.h and the families it includes (mcstat/*.h beside it)
header="$2"
headers="$header $(dirname "$header")/mcstat/*.h"
# (a name in parentheses, int (mcstat_x_init)(...), is one a macro of the same name covers)
# shellcheck disable=SC2086
api=$(cat $headers | tr '\n' ' ' | grep -o 'MCSTAT_\(EXPERIMENTAL_\)\{0,1\}API[^;{]*(' | grep -o 'mcstat_[a-z0-9_]*)\{0,1\}[[:space:]]*($' | tr -d ' ()' | sort -u)
[ -n "$api" ] || { echo "no MCSTAT_API declarations found in $header"; exit 1; }
for s in $api; do
    printf '%s\n' "$syms" | grep -qx "$s" || { echo "missing export: $s (declared in $header)"; exit 1; }
done
if printf '%s\n' "$syms" | grep -q '^mcstat__'; then
    echo "internal (mcstat__) symbols are exported"; exit 1
fi
echo "exports ok: $(printf '%s\n' "$syms" | wc -l) symbols, all mcstat_, $(printf '%s\n' "$api" | wc -l) declared in the header"
