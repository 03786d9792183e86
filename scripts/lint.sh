#!/usr/bin/env bash
# Verilator -Wall lint of tex_unit in several configurations; any warning fails.
# Waivers live only in rtl/tex_unit.vlt. Usage: scripts/lint.sh
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
cd "$(dirname "$0")/.."
configs=("4 4 8" "6 3 8" "10 10 8" "0 0 8" "11 2 16" "3 7 1")  # MAX_LOG2_W MAX_LOG2_H CW
for cfg in "${configs[@]}"; do
  set -- $cfg
  if ! out=$(verilator --lint-only -Wall rtl/tex_unit.vlt -f rtl/tex_files.f --top-module tex_unit \
               -GMAX_LOG2_W="$1" -GMAX_LOG2_H="$2" -GCW="$3" 2>&1) || [ -n "$out" ]; then
    echo "$out" >&2
    echo "lint: FAILED for MAX_LOG2_W=$1 MAX_LOG2_H=$2 CW=$3" >&2
    exit 1
  fi
done
echo "lint: verilator -Wall clean for ${#configs[@]} configurations (MAX_LOG2_W MAX_LOG2_H CW: ${configs[*]/%/;})"
