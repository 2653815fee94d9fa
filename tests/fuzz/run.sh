#!/usr/bin/env bash
# Runs every libFuzzer harness for a bounded time, two at a time (the CI
# machine has 2 cores).
#   tests/fuzz/run.sh BUILD_DIR SECONDS [JOBS]
# Each harness starts from its committed corpus and regressions; what it
# discovers goes to BUILD_DIR/fuzz/corpus/<harness> (not the source tree),
# inputs that fail to BUILD_DIR/fuzz/artifacts/, logs to BUILD_DIR/fuzz/logs/.
#
# Mutation fuzzing is exploration: two runs of one binary with one seed and
# one corpus still differ (coverage feedback, ASan heap addresses in the
# comparison dictionary, time caps under load), so it can never be part of a
# pass/fail gate.  Two modes:
#   default         (make fuzz) exit status 1 when any harness found a crash,
#                   a sanitizer report, an invariant violation or a timeout;
#   FUZZ_REPORT=F   (make fuzz-report, run by make test) write the findings to
#                   the Markdown file F, print them, and exit 0 whatever was
#                   found.  A finding is turned into a committed regression
#                   input (README.md, "Running"), which ctest then replays
#                   deterministically on every build.
# FUZZ_SEED=S fixes libFuzzer's seed (default: libFuzzer's own choice, which
# each log records).
set -uo pipefail
BUILD=${1:?build dir}
SECONDS_EACH=${2:-60}
JOBS=${3:-2}
SRC=$(cd "$(dirname "$0")" && pwd)
FUZZ_SEED=${FUZZ_SEED:-}
FUZZ_REPORT=${FUZZ_REPORT:-}
BIN=$BUILD/tests/fuzz
OUT=$BUILD/fuzz
mkdir -p "$OUT/logs" "$OUT/artifacts" "$OUT/status"
rm -f "$OUT/status/"*

harnesses=$(cd "$SRC" && ls fuzz_*.c | sed 's/\.c$//')
run_one() {
    h=$1
    mkdir -p "$OUT/corpus/$h"
    local fixed=()
    [ -n "${FUZZ_SEED:-}" ] && fixed+=(-seed="$FUZZ_SEED")
    "$BIN/$h" "${fixed[@]}" -max_total_time="$SECONDS_EACH" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$OUT/artifacts/$h-" "$OUT/corpus/$h" "$SRC/corpus/$h" "$SRC/regressions/$h" \
        > "$OUT/logs/$h.log" 2>&1
    rc=$?
    done_line=$(grep -E '^#[0-9]+\s+DONE' "$OUT/logs/$h.log" | tail -1)
    execs=$(grep -E 'stat::number_of_executed_units' "$OUT/logs/$h.log" | awk '{print $2}')
    seed=$(grep -oE 'Seed: [0-9]+' "$OUT/logs/$h.log" | head -1 | awk '{print $2}')
    printf '%s\t%d\t%s\t%s\t%s\n' "$h" "$rc" "${execs:-?}" "${seed:-?}" \
        "$(echo "$done_line" | grep -oE 'cov: [0-9]+ ft: [0-9]+' | head -1)" > "$OUT/status/$h"
    printf '%-13s rc=%d execs=%s seed=%s %s\n' "$h" "$rc" "${execs:-?}" "${seed:-?}" \
        "$(echo "$done_line" | grep -oE 'cov: [0-9]+ ft: [0-9]+|exec/s: [0-9]+' | tr '\n' ' ')"
    if [ "$rc" -ne 0 ]; then
        echo "---- $h: finding; the end of its log ($OUT/logs/$h.log):"
        grep -E 'invariant violated|runtime error|ERROR|SUMMARY|^  [^ ]' "$OUT/logs/$h.log" | head -20
        ls "$OUT/artifacts/$h-"* 2>/dev/null
    fi
    return 0
}
export -f run_one
export BIN OUT SRC SECONDS_EACH FUZZ_SEED

echo "fuzzing $(echo $harnesses | wc -w) harnesses, ${SECONDS_EACH}s each, $JOBS at a time"
printf '%s\n' $harnesses | xargs -P "$JOBS" -I{} bash -c 'run_one {}'

findings=$(awk -F'\t' '$2 != 0 {print $1}' "$OUT"/status/* | tr '\n' ' ')
if [ -n "$FUZZ_REPORT" ]; then
    {
        echo "# Fuzzing report (report only: it never fails the run)"
        echo
        echo "$(date -u '+%Y-%m-%d %H:%M UTC'), ${SECONDS_EACH} s per harness, $JOBS at a time, commit $(git -C "$SRC" rev-parse --short HEAD 2>/dev/null || echo '?')."
        echo
        echo "| harness | exit | executions | seed | coverage |"
        echo "|---|---|---|---|---|"
        awk -F'\t' '{printf "| %s | %s | %s | %s | %s |\n", $1, $2, $3, $4, $5}' "$OUT"/status/*
        echo
        if [ -n "$findings" ]; then
            echo "## Findings: $findings"
            echo
            echo "Inputs in \`$OUT/artifacts/\`. For each: replay it with"
            echo "\`MCSTAT_FUZZ_VERBOSE=1 $BIN/<harness> <input>\`, fix the library, commit the input"
            echo "to \`tests/fuzz/regressions/<harness>/\` and a test with an oracle to"
            echo "\`tests/c/test_fuzz_regressions.c\` (tests/fuzz/README.md)."
            for h in $findings; do
                echo
                echo "### $h"
                echo '```'
                grep -E 'invariant violated|runtime error|ERROR|SUMMARY|^  [^ ]' "$OUT/logs/$h.log" | head -20
                ls "$OUT/artifacts/$h-"* 2>/dev/null
                echo '```'
            done
        else
            echo "No findings."
        fi
    } > "$FUZZ_REPORT"
    echo "fuzz-report: ${findings:-no findings} (report only; written to $FUZZ_REPORT)"
    exit 0
fi
[ -z "$findings" ] && echo "fuzz: no findings" || echo "fuzz: findings in $findings (reproduce: $BIN/<harness> <artifact>)"
[ -z "$findings" ]
