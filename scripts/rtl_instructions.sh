#!/usr/bin/env bash
# rtl_instructions.sh BUILD_DIR OUT_DIR [CONFIG ...]: the Verilated RTL's instructions per clock
# (make bench-ir), a measure of the simulator's speed that does not move with the machine's load:
# callgrind counts the instructions while texunit_rtl_clocks streams make bench's random trilinear
# workload (bench/bench_rtl.h) through each configuration (default: every compiled one), divided
# by the clocks it took: each configuration on an RGBA8 texture, and those with the block decoders
# and sRGB tables also on BC1, BC7, sRGB, ETC2 RGBA8, EAC RG11 and ASTC 8x8 textures. A few minutes.
set -euo pipefail
case "${1:-}" in -h|--help|"") sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
build=$1; out=$2; shift 2
tool=$build/texunit_rtl_clocks
[ -x "$tool" ] || { echo "rtl_instructions: $tool not built (make build)" >&2; exit 1; }
command -v valgrind >/dev/null || { echo "rtl_instructions: valgrind not installed (make deps)" >&2; exit 1; }
listed=$("$tool" --list)
for w in "$@"; do
  grep -q "^$w " <<< "$listed" || { echo "rtl_instructions: unknown configuration '$w' (compiled: $(cut -d' ' -f1 <<< "$listed" | xargs))" >&2; exit 1; }
done
mkdir -p "$out"
printf '%-22s %-8s %12s %16s\n' configuration texture clocks instructions/clock
# (--list: one line per configuration, its name and the textures it takes)
while read -r c textures; do
  if [ $# -gt 0 ]; then
    wanted=0
    for w in "$@"; do [ "$w" = "$c" ] && wanted=1; done
    [ $wanted = 1 ] || continue
  fi
  for t in $textures; do
    log=$out/$c.$t.txt
    valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$out/$c.$t.callgrind" "$tool" --repeat 1 \
      --texture "$t" "$c" > "$log" 2>&1 || { cat "$log" >&2; exit 1; }
    clocks=$(sed -n "s/^$c $t: .* in \([0-9]*\) clocks.*/\1/p" "$log")
    ir=$(sed -n 's/^summary: \([0-9]*\).*/\1/p' "$out/$c.$t.callgrind")
    awk -v c="$c" -v t="$t" -v n="$clocks" -v ir="$ir" 'BEGIN { printf "%-22s %-8s %12d %16.0f\n", c, t, n, ir / n }'
  done
done <<< "$listed"
