#!/bin/bash
# make fuzz (tests/fuzz/README.md): each libFuzzer target of BUILD for FUZZ_SECONDS (default 30),
# from its seed corpus (tests/fuzz/corpus/<target>) and the corpus earlier runs grew
# (BUILD/corpus/<target>); a finding is written to tests/fuzz/findings/<target>/, which make test
# replays. Prints a table of executions, corpus sizes and findings per target (also OUT/summary.md).
# FUZZ_TARGETS: the targets to run (default: all). Exits non-zero if any target found something.
set -u
BUILD=${1:-build-fuzz}
OUT=${2:-out/fuzz}
SECS=${FUZZ_SECONDS:-30}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
TARGETS=${FUZZ_TARGETS:-$(sed -n 's/^set(FUZZ_TARGETS \(.*\))$/\1/p' "$ROOT/tests/fuzz/CMakeLists.txt")}
mkdir -p "$OUT"
# Third-party libraries' own leaks and alignment (tests/sanitize/*.supp, as make test-sanitize).
export LSAN_OPTIONS="suppressions=$ROOT/tests/sanitize/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:suppressions=$ROOT/tests/sanitize/ubsan.supp"
summary="$OUT/summary.md"
{
  echo "| target | seconds | executions | executions/s | seeds | corpus | new inputs | findings |"
  echo "|---|---:|---:|---:|---:|---:|---:|---|"
} > "$summary"
failed=0
for t in $TARGETS; do
  bin="$BUILD/tests/fuzz/fuzz_$t"
  [ -x "$bin" ] || { echo "fuzz: $bin not built (make fuzz builds it)" >&2; exit 2; }
  corpus="$BUILD/corpus/$t"
  findings="$ROOT/tests/fuzz/findings/$t"
  mkdir -p "$corpus" "$findings"
  seeds=$(ls "$ROOT/tests/fuzz/corpus/$t" | wc -l)
  before=$(ls "$findings" | wc -l)
  log="$OUT/$t.log"
  echo "fuzz: $t for ${SECS} s (log $log)"
  # -timeout: an input running 10 s is a hang; -rss_limit_mb: one using 2 GiB is unbounded memory.
  "$bin" "$corpus" "$ROOT/tests/fuzz/corpus/$t" -max_total_time="$SECS" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$findings/" -print_final_stats=1 > "$log" 2>&1
  status=$?
  stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
  runs=$(stat number_of_executed_units)
  rate=$(stat average_exec_per_sec)
  added=$(stat new_units_added)
  after=$(ls "$findings" | wc -l)
  found=$((after - before))
  what="none"
  if [ "$status" -ne 0 ] || [ "$found" -gt 0 ]; then
    failed=1
    what="$(ls -t "$findings" | head -1): $(grep -m1 -E 'ERROR: |==[0-9]+==|fuzz: |runtime error' "$log" | cut -c1-120)"
  fi
  echo "| $t | $SECS | ${runs:-0} | ${rate:-0} | $seeds | $(ls "$corpus" | wc -l) | ${added:-0} | $what |" >> "$summary"
done
cat "$summary"
if [ "$failed" -ne 0 ]; then
  echo "fuzz: findings above; each is in tests/fuzz/findings/<target>/ (replay: build/tests/fuzz/fuzz_replay_<target> FILE)" >&2
  exit 1
fi
echo "fuzz: no findings ($(echo $TARGETS | wc -w) targets, ${SECS} s each)"
