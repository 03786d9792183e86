#!/usr/bin/env bash
# Formal proofs of the valid/ready handshake with Yosys (docs/verification.md, "Formal proofs").
#  1. tex_skid, by k-induction (sat -tempinduct) on rtl/formal/tex_skid_formal.sv, from an
#     arbitrary start state: no item lost, duplicated or reordered; valid held with stable data
#     until ready; at most 2 items held, matching the valid bits.
#  2. Structure, tex_skid and tex_unit: no combinational path from out_ready / rsp_ready to
#     in_ready / req_ready (every path goes through a flip-flop).
#  3. Each check must fail on a planted bug (a copy of the RTL changed with sed); the script fails
#     if one does not.
# Usage: scripts/formal.sh
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$SECONDS
units=$(grep -v '^#' rtl/tex_files.f | grep -v '^$' | tr '\n' ' ')

# prove_skid SKID_SOURCE: k-induction of every assertion of the skid harness.
prove_skid() {
  yosys -p "read_verilog -formal -sv $1 rtl/formal/tex_skid_formal.sv; prep -top tex_skid_formal; flatten;
            async2sync; dffunmap; opt_clean;
            sat -tempinduct -prove-asserts -set-assumes -seq 1 -maxsteps 12 tex_skid_formal" 2>&1 |
    grep -q "Induction step proven: SUCCESS"
}

# no_comb_path TOP FROM TO SOURCES...: no path from input FROM to output TO without a flip-flop
# (tex_unit in a small configuration: the handshake logic is the same in all).
no_comb_path() {
  local top=$1 from=$2 to=$3 params=""
  shift 3
  [ "$top" = tex_unit ] && params="-chparam MAX_LOG2_W 1 -chparam MAX_LOG2_H 1 -chparam CW 2"
  yosys -q -p "read_verilog -sv -DSYNTHESIS $*; hierarchy -top $top $params; proc; flatten; memory_map;
               opt -fast; dffunmap; opt_clean; select -assert-none w:$from %co*:-\$dff w:$to %i" > /dev/null 2>&1
}

check() {  # check NAME COMMAND...: must pass
  if "${@:2}"; then echo "formal: proven   $1"; else echo "formal: FAILED   $1" >&2; exit 1; fi
}
mutant() {  # mutant NAME COMMAND...: must fail
  if "${@:2}"; then echo "formal: NOT CAUGHT planted bug: $1" >&2; exit 1; else echo "formal: caught   $1"; fi
}
plant() {  # plant FILE SED_EXPR: a changed copy in the work directory; prints its path
  local out="$work/$(basename "$1" .sv)_$RANDOM.sv"
  sed "$2" "$1" > "$out"
  if cmp -s "$1" "$out"; then echo "formal: the planted bug '$2' did not change $1" >&2; exit 1; fi
  echo "$out"
}

check "tex_skid: order, hold, capacity (k-induction)" prove_skid rtl/tex_skid.sv
check "tex_skid: in_ready has no combinational path from out_ready" no_comb_path tex_skid out_ready in_ready rtl/tex_skid.sv
check "tex_unit: req_ready has no combinational path from rsp_ready" no_comb_path tex_unit rsp_ready req_ready $units

m=$(plant rtl/tex_skid.sv 's/out_data <= skid_valid ? skid_data : in_data;/out_data <= in_data;/')
mutant "skid refills from the input, not the parked item (reorder/loss)" prove_skid "$m"
m=$(plant rtl/tex_skid.sv 's/end else if (out_ready || !out_valid) begin/end else if (1'"'"'b1) begin/')
mutant "skid overwrites a stalled output (hold)" prove_skid "$m"
m=$(plant rtl/tex_skid.sv 's/assign in_ready = !skid_valid;/assign in_ready = 1'"'"'b1;/')
mutant "skid accepts while its entry is full (capacity)" prove_skid "$m"
m=$(plant rtl/tex_skid.sv 's/assign in_ready = !skid_valid;/assign in_ready = !skid_valid || out_ready;/')
mutant "skid in_ready from out_ready (combinational path)" no_comb_path tex_skid out_ready in_ready "$m"
m=$(plant rtl/tex_skid.sv 's/assign in_ready = !skid_valid;/assign in_ready = !skid_valid || out_ready;/')
mutant "tex_unit req_ready through the skid's out_ready (combinational path)" no_comb_path tex_unit rsp_ready req_ready ${units/rtl\/tex_skid.sv/$m}
echo "formal: 3 checks proven, 5 planted bugs caught ($((SECONDS - start)) s)"
