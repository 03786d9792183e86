#!/usr/bin/env bash
# X-propagation in 4-state simulation (Icarus Verilog): tests/xprop/tb_tex_unit.sv drives tex_unit
# with random requests, every filter and wrap, stalls, a reset mid-traffic, and X on every
# don't-care input; it fails if an X or Z reaches req_ready, rsp_valid, or a valid response, or if
# the responses' tags are out of order. Then planted bugs (sed on a copy of the RTL) must fail it.
# Usage: scripts/xprop.sh
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$SECONDS
sources=$(grep -v '^#' rtl/tex_files.f | grep -v '^$' | tr '\n' ' ')

# bench SOURCES...: compile and run; prints the bench's verdict line, succeeds on PASS.
bench() {
  local bin="$work/tb_$RANDOM"
  if ! iverilog -g2012 -o "$bin" "$@" tests/xprop/tb_tex_unit.sv > "$bin.log" 2>&1; then
    cat "$bin.log" >&2
    echo "xprop: iverilog failed" >&2
    return 2
  fi
  local out
  out=$(vvp -n "$bin" | grep '^xprop:' | tail -1)
  echo "$out"
  [[ $out == "xprop: PASS"* ]]
}

if ! bench $sources; then echo "xprop: FAILED on the RTL" >&2; exit 1; fi

plant() {  # plant FILE SED_EXPR: the sources with FILE replaced by a changed copy
  local copy="$work/$(basename "$1")"
  sed "$2" "$1" > "$copy"
  if cmp -s "$1" "$copy"; then echo "xprop: the planted bug '$2' did not change $1" >&2; exit 1; fi
  echo "${sources/$1/$copy}"
}
mutant() {  # mutant NAME SOURCES...: the bench must fail
  local verdict
  if verdict=$(bench "${@:2}"); then echo "xprop: NOT CAUGHT planted bug: $1" >&2; exit 1; fi
  echo "xprop: caught   $1 ($verdict)"
}
mutant "skid buffer's out_valid without reset" \
  $(plant rtl/tex_skid.sv 's/      out_valid  <= 1'"'"'b0;/      out_valid  <= out_valid;/')
mutant "pipeline valid bits without reset" \
  $(plant rtl/tex_unit.sv 's/if (rst) valid <= .0;/if (1'"'"'b0) valid <= '"'"'0;/')
echo "xprop: 4-state run clean, 2 planted bugs caught ($((SECONDS - start)) s)"
