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
for s in mcstat_chisq_gof mcstat_version mcstat_strerror mcstat_t_test_1 mcstat_t_test_2 mcstat_var_test_1 mcstat_var_test_2 \
         mcstat_moments_init mcstat_moments_add mcstat_moments_merge mcstat_result_format \
         mcstat_stream_init mcstat_stream_flush mcstat_stream_merge mcstat_stream_check_mean mcstat_stream_check_var; do
    printf '%s\n' "$syms" | grep -qx "$s" || { echo "missing export: $s"; exit 1; }
done
# Per-pixel accumulator arrays.
for s in mcstat_moments_init_rows mcstat_moments_add_rows mcstat_moments_merge_rows \
         mcstat_moments_to_bytes_rows mcstat_moments_from_bytes_rows mcstat_t_test_1_moments_rows \
         mcstat_t_test_2_moments_rows mcstat_var_test_1_moments_rows mcstat_var_test_2_moments_rows; do
    printf '%s\n' "$syms" | grep -qx "$s" || { echo "missing export: $s"; exit 1; }
done
if printf '%s\n' "$syms" | grep -q '^mcstat__'; then
    echo "internal (mcstat__) symbols are exported"; exit 1
fi
echo "exports ok: $(printf '%s\n' "$syms" | wc -l) symbols, all mcstat_"
