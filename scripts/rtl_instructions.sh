#!/usr/bin/env bash
# rtl_instructions.sh BUILD_DIR OUT_DIR [CONFIG ...]: the Verilated RTL's instructions per clock
# (make bench-ir), a measure of the simulator's speed that does not move with the machine's load:
# callgrind counts the instructions while texunit_rtl_clocks streams make bench's random trilinear
# workload (bench/bench_rtl.h) through each configuration (default: every compiled one), divided
# by the clocks it took. About 30 seconds for all seven.
set -euo pipefail
case "${1:-}" in -h|--help|"") sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
build=$1; out=$2; shift 2
tool=$build/texunit_rtl_clocks
[ -x "$tool" ] || { echo "rtl_instructions: $tool not built (make build)" >&2; exit 1; }
command -v valgrind >/dev/null || { echo "rtl_instructions: valgrind not installed (make deps)" >&2; exit 1; }
configs=("$@")
[ ${#configs[@]} -gt 0 ] || mapfile -t configs < <("$tool" --list)
mkdir -p "$out"
printf '%-22s %12s %16s\n' configuration clocks instructions/clock
for c in "${configs[@]}"; do
  log=$out/$c.txt
  valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$out/$c.callgrind" "$tool" --repeat 1 "$c" \
    > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
  clocks=$(sed -n "s/^$c: .* in \([0-9]*\) clocks.*/\1/p" "$log")
  ir=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$out/$c.callgrind")
  awk -v c="$c" -v n="$clocks" -v ir="$ir" 'BEGIN { printf "%-22s %12d %16.0f\n", c, n, ir / n }'
done
