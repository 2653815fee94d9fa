#!/usr/bin/env bash
# Runs every libFuzzer harness for a bounded time, two at a time (the CI
# machine has 2 cores), and fails if any finds a crash, a sanitizer report,
# an invariant violation or a timeout.
#   tests/fuzz/run.sh BUILD_DIR SECONDS [JOBS]
# Each harness starts from its committed corpus and regressions; what it
# discovers goes to BUILD_DIR/fuzz/corpus/<harness> (not the source tree),
# crashing inputs to BUILD_DIR/fuzz/artifacts/, logs to BUILD_DIR/fuzz/logs/.
#
# FUZZ_SEED=S fixes libFuzzer's random seed and FUZZ_RUNS=FILE (lines
# "harness runs") caps each harness's executions: the run is then the same
# sequence of mutations every time, up to coverage feedback (which makes two
# runs only nearly identical); that is how CI runs it (make fuzz-ci), and
# exploration with fresh seeds is `make fuzz`.
set -uo pipefail
BUILD=${1:?build dir}
SECONDS_EACH=${2:-60}
JOBS=${3:-2}
SRC=$(cd "$(dirname "$0")" && pwd)
FUZZ_SEED=${FUZZ_SEED:-}
FUZZ_RUNS=${FUZZ_RUNS:-}
BIN=$BUILD/tests/fuzz
OUT=$BUILD/fuzz
mkdir -p "$OUT/logs" "$OUT/artifacts"

harnesses=$(cd "$SRC" && ls fuzz_*.c | sed 's/\.c$//')
run_one() {
    h=$1
    mkdir -p "$OUT/corpus/$h"
    local fixed=()
    if [ -n "${FUZZ_SEED:-}" ]; then
        fixed+=(-seed="$FUZZ_SEED")
        rm -rf "$OUT/corpus/$h" && mkdir -p "$OUT/corpus/$h" # start from the committed corpus only
    fi
    if [ -n "${FUZZ_RUNS:-}" ]; then
        local runs; runs=$(awk -v h="$h" '$1 == h {print $2}' "$FUZZ_RUNS")
        [ -n "$runs" ] && fixed+=(-runs="$runs")
    fi
    "$BIN/$h" "${fixed[@]}" -max_total_time="$SECONDS_EACH" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$OUT/artifacts/$h-" "$OUT/corpus/$h" "$SRC/corpus/$h" "$SRC/regressions/$h" \
        > "$OUT/logs/$h.log" 2>&1
    rc=$?
    done_line=$(grep -E '^#[0-9]+\s+DONE' "$OUT/logs/$h.log" | tail -1)
    execs=$(grep -E 'stat::number_of_executed_units' "$OUT/logs/$h.log" | awk '{print $2}')
    printf '%-13s rc=%d execs=%s %s\n' "$h" "$rc" "${execs:-?}" \
        "$(echo "$done_line" | grep -oE 'cov: [0-9]+ ft: [0-9]+|exec/s: [0-9]+' | tr '\n' ' ')"
    if [ "$rc" -ne 0 ]; then
        echo "---- $h failed; the end of its log ($OUT/logs/$h.log):"
        grep -E 'invariant violated|runtime error|ERROR|SUMMARY|^  [^ ]' "$OUT/logs/$h.log" | head -20
        ls "$OUT/artifacts/$h-"* 2>/dev/null
    fi
    return "$rc"
}
export -f run_one
export BIN OUT SRC SECONDS_EACH FUZZ_SEED FUZZ_RUNS

echo "fuzzing $(echo $harnesses | wc -w) harnesses, ${SECONDS_EACH}s each, $JOBS at a time"
printf '%s\n' $harnesses | xargs -P "$JOBS" -I{} bash -c 'run_one {}'
status=$?
[ $status -eq 0 ] && echo "fuzz: no findings" || echo "fuzz: FAILED (reproduce: $BIN/<harness> <artifact>)"
exit $status
