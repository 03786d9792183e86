#!/usr/bin/env bash
# Formal proofs of the valid/ready handshake with Yosys 0.23 + yosys-smtbmc + z3
# (docs/verification.md, "Formal proofs"). The properties are immediate assertions under
# `ifdef FORMAL in rtl/tex_skid.sv and rtl/tex_unit.sv; rtl/formal/*_formal.sv are the
# environments (reset in the first clock, then every input free, resets included).
#  1. tex_skid (W=2) and tex_unit (2x2 texels, CW=1, TAG_W=2; the texel datapath cut to a free
#     value): BMC from reset, then k-induction from an arbitrary state, of
#       order    - the n-th response is the n-th accepted item, with its data / tag (none lost,
#                  duplicated or reordered): a tracked item (any constant ordinal) is followed;
#       hold     - a stalled valid stays high, with its data / tag and texel unchanged;
#       probes   - (unit) a request's probes (N = 1..16, any N: tex_aniso's comparisons are cut)
#                  follow each other through the pipeline with its tag, first to last;
#       capacity - in flight (accepted - emitted) = the requests held <= 2 (skid) / 17 (unit).
#  2. Structure (the real RTL, no FORMAL): no combinational path from out_ready to in_ready,
#     rsp_ready to req_ready, or any input to any output of tex_unit.
#  3. Planted bugs: each is a sed on a copy of the RTL and must make a named check fail (BMC
#     counterexample from reset, or the structural check). Exit status non-zero if a proof fails
#     on the real RTL or a planted bug is not caught.
# Usage: scripts/formal.sh [WORKDIR]   (default: a temporary directory, removed at the end;
#        WORKDIR keeps the models, logs and counterexample traces)
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
cd "$(dirname "$0")/.."
for tool in yosys yosys-smtbmc z3; do
  command -v "$tool" > /dev/null ||
    { echo "formal: $tool not found (scripts/install-deps.sh)" >&2; exit 1; }
done
if [ -n "${1:-}" ]; then
  work=$(mkdir -p "$1" && cd "$1" && pwd)
else
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
start=$SECONDS
root=$PWD

SKID_PARAMS="-set W 2"
UNIT_PARAMS="-set MAX_LOG2_W 1 -set MAX_LOG2_H 1 -set CW 1 -set TAG_W 2"
UNIT_CFG="2x2 texels, CW=1, TAG_W=2"
COMB_PARAMS="-chparam MAX_LOG2_W 2 -chparam MAX_LOG2_H 1 -chparam CW 2"  # structural: 4x2, CW=2
SKID_BMC=10; UNIT_BMC=20   # BMC depth (steps from reset): the unit fills up (17 items) in 18
INDUCT=4                   # k-induction length (both close at k = 1)

# sources DIR: the RTL file list with DIR/ in front
sources() { sed "s|^|$1/|" "$root/rtl/tex_files.f" | tr '\n' ' '; }

# model NAME DIR TOP PARAMS: DIR/rtl (+ DIR/rtl/formal) -> $work/NAME.smt2. The simulation checks
# of tex_unit (`ifndef SYNTHESIS, not parsed by Yosys) are left out by -DSYNTHESIS. In tex_unit,
# the texel datapath's result rgba_s11 and tex_aniso's comparisons `reaches` (k^2 Pmin^2 >= the
# target) are cut points (free values each clock, an over-approximation): a derivative request
# issues any number of probes 1..16, and the solver sees the control, tags, probe sequencer and
# skid buffer without the multipliers. The model is bit-blasted (abc -g AND): z3 takes seconds on
# it, minutes or more on the word-level model.
model() {
  local name=$1 dir=$2 top=$3 params=$4 cut=""
  [ "$top" = tex_unit_formal ] &&
    cut="cutpoint w:dut.rgba_s11 w:dut.u_probe.u_aniso.reaches; opt_clean;"
  yosys -q -l "$work/$name.yosys.log" -p "
    read_verilog -formal -DSYNTHESIS -sv $(sources "$dir") $dir/rtl/formal/$top.sv
    chparam $params $top; prep -flatten -top $top; $cut
    memory_map; opt -fast; async2sync; dffunmap; techmap; opt -fast; abc -g AND; opt_clean;
    dffunmap; write_smt2 -wires $work/$name.smt2" \
    > /dev/null 2>&1 ||
    { echo "formal: yosys failed on $name, see $work/$name.yosys.log" >&2; return 2; }
  grep -q 'yosys-smt2-assert' "$work/$name.smt2" ||
    { echo "formal: no assertion in $name (FORMAL blocks missing?)" >&2; return 2; }
}

# failed_props LOG: the properties (order, hold, probes, capacity) of the assertions that failed
# in LOG, told apart by the text of the assertion's line.
failed_props() {
  grep -o '\$assert\$[^$]*:[0-9]*\$' "$1" | sed 's/^\$assert\$//; s/\$$//' | sort -u |
    while IFS=: read -r file line; do
      text=$(sed -n "${line}p" "$file")
      case "$text" in
        *f_stalled_q*) echo hold ;;
        *f_pick*) echo order ;;
        *index*|*aniso_n*|*'!last['*|*'.tag[TGW])'*|*'!accum_held)'*|*'!probe_first)'*) echo probes ;;
        *) echo capacity ;;
      esac
    done | sort -u | tr '\n' ' '
}

# comb_clean DIR TOP SELECTION: the flattened real RTL (no FORMAL, flip-flops unmapped to $dff)
# has no wire in SELECTION, e.g. the forward cone of rsp_ready stopped at flip-flops, intersected
# with req_ready. The named ports must exist (so that the check is not vacuous).
comb_clean() {
  local dir=$1 top=$2 sel=$3 params=""
  [ "$top" = tex_unit ] && params=$COMB_PARAMS
  yosys -q -p "read_verilog -sv $(sources "$dir"); hierarchy -top $top $params; proc; flatten;
               memory_map; opt -fast; dffunmap; opt_clean;
               select -assert-count 1 w:clk; select -assert-min 1 o:*;
               select -assert-none $sel" > /dev/null 2>&1
}
SKID_COMB='w:out_ready %co*:-$dff w:in_ready %i'
UNIT_COMB='w:rsp_ready %co*:-$dff w:req_ready %i'
UNIT_ANY='i:* w:clk %d %co*:-$dff o:* %i'

fail=0
proven=0
ok()  { echo "formal: proven  $1"; proven=$((proven + 1)); }
bad() { echo "formal: FAILED  $1" >&2; fail=1; }

# proof NAME TOP PARAMS LABEL BMC_DEPTH PROPERTY...: BMC from reset (a failure is a real
# counterexample), then k-induction from an arbitrary state (a failure there alone means that the
# invariants are too weak); one line per property.
proof() {
  local name=$1 top=$2 params=$3 label=$4 depth=$5 log="$work/$1"
  shift 5
  model "$name" "$root" "$top" "$params" || { bad "$label: no model"; return; }
  if ! yosys-smtbmc -s z3 -t "$depth" --dump-vcd "$log.bmc.vcd" "$log.smt2" > "$log.bmc.log" 2>&1
  then
    bad "$label: counterexample from reset violates: $(failed_props "$log.bmc.log")($log.bmc.*)"
  elif ! yosys-smtbmc -s z3 -i -t "$INDUCT" --dump-vcd "$log.ind.vcd" "$log.smt2" \
         > "$log.ind.log" 2>&1; then
    bad "$label: induction step fails on: $(failed_props "$log.ind.log")($log.ind.*)"
  else
    for p in "$@"; do ok "$label: $p  [BMC $depth + $INDUCT-induction]"; done
  fi
}
# structural NAME DIR TOP SELECTION: comb_clean on the real RTL, one line.
structural() {
  if comb_clean "$root" "$2" "$3"; then ok "$1"; else bad "$1"; fi
}

# ---------------------------------------------------------------- proofs on the real RTL
proof skid tex_skid_formal "$SKID_PARAMS" "tex_skid W=2" $SKID_BMC \
  "order (none lost, duplicated, reordered)" "hold (out_valid, out_data until out_ready)" \
  "capacity (in flight = out_valid + skid entry <= 2)"
structural "tex_skid: no combinational path out_ready -> in_ready" tex_skid "$SKID_COMB"
proof unit tex_unit_formal "$UNIT_PARAMS" "tex_unit $UNIT_CFG" $UNIT_BMC \
  "order (rsp_tag of the n-th response = req_tag of the n-th request)" \
  "hold (rsp_valid, rsp_tag, rsp_rgba until rsp_ready)" \
  "probes (a request's 1..16 probes contiguous, first to last, with its tag)" \
  "capacity (in flight = requests held <= 4 + 9 + 2 + 2)"
structural "tex_unit 4x2 CW=2: no combinational path rsp_ready -> req_ready" tex_unit "$UNIT_COMB"
structural "tex_unit 4x2 CW=2: no combinational path from any input to any output" \
  tex_unit "$UNIT_ANY"

# ---------------------------------------------------------------- planted bugs
# plant NAME FILE SED: a copy of rtl/ in $work/NAME with FILE changed by SED; prints the dir.
plant() {
  local dir="$work/$1"
  rm -rf "$dir"; mkdir -p "$dir"; cp -r "$root/rtl" "$dir/"
  sed -i "$3" "$dir/rtl/$2"
  if cmp -s "$root/rtl/$2" "$dir/rtl/$2"; then
    echo "formal: planted bug $1 did not change rtl/$2 (the RTL changed?)" >&2; return 1
  fi
  echo "$dir"
}
caught=0
# mutant NAME WHAT EXPECTED FILE SED: EXPECTED is a property (order, hold, capacity: a BMC
# counterexample from reset must violate it) or comb-skid / comb-unit (the structural check).
mutant() {
  local name=$1 what=$2 want=$3 file=$4 expr=$5 dir got=""
  dir=$(plant "$name" "$file" "$expr") || { fail=1; return; }
  case "$want" in
    comb-skid) comb_clean "$dir" tex_skid "$SKID_COMB" || got=$want ;;
    comb-unit) comb_clean "$dir" tex_unit "$UNIT_COMB" || got=$want ;;
    *)
      local top=tex_skid_formal params=$SKID_PARAMS depth=$SKID_BMC
      if [ "$file" != tex_skid.sv ]; then
        top=tex_unit_formal params=$UNIT_PARAMS depth=$UNIT_BMC
      fi
      model "$name" "$dir" $top "$params" || { fail=1; return; }
      # --keep-going: every property violated within the depth, not only the first
      if ! yosys-smtbmc -s z3 --keep-going -t "$depth" --dump-vcd "$work/$name.%.vcd" \
           "$work/$name.smt2" > "$work/$name.log" 2>&1; then
        got=$(failed_props "$work/$name.log")
      fi ;;
  esac
  if [[ " $got " == *" $want "* ]]; then
    echo "formal: caught  $what  [$file: ${got% }]"
    caught=$((caught + 1))
  else
    echo "formal: NOT CAUGHT  $what  [$file: expected $want, got ${got:-a pass}]" >&2
    fail=1
  fi
}

mutant skid_refill "skid refills the output from the input, not the parked item (loss, reorder)" \
  order tex_skid.sv 's/out_data <= skid_valid ? skid_data : in_data;/out_data <= in_data;/'
mutant skid_keep "skid entry never freed: the parked item is sent again (duplicate)" \
  order tex_skid.sv '/out_valid  <= skid_valid || in_valid;/{n;d}'
mutant skid_drop "skid output refilled while stalled when no input comes (valid dropped)" \
  hold tex_skid.sv 's/if (out_ready || !out_valid) begin/if (out_ready || !out_valid || !in_valid) begin/'
mutant skid_full "skid accepts while its entry is full (in_ready = 1)" \
  capacity tex_skid.sv "s/assign in_ready = !skid_valid;/assign in_ready = 1'b1;/"
mutant skid_comb "skid in_ready = !skid_valid || out_ready (combinational path)" \
  comb-skid tex_skid.sv 's/in_ready = !skid_valid;/in_ready = !skid_valid || out_ready;/'
mutant unit_comb "the same skid bug inside tex_unit (rsp_ready -> req_ready)" \
  comb-unit tex_skid.sv 's/in_ready = !skid_valid;/in_ready = !skid_valid || out_ready;/'
mutant unit_tags "tex_unit tags shift while the pipeline is stalled (tag/request mismatch)" \
  order tex_unit.sv 's/if (en) tag <= g_tag\[n-1\].tag;/tag <= g_tag[n-1].tag;/'
mutant unit_index "tex_probe's index advances while the unit is stalled (probes skipped)" \
  probes tex_probe.sv 's/else if (en) index <= index + 4.d1;/else index <= index + 4'"'"'d1;/'
mutant unit_accum "tex_accum's output register loads while the unit is stalled (a sample lost)" \
  capacity tex_accum.sv 's/else if (en) out_valid <= valid_s1 \&\& last_s1;/else out_valid <= valid_s1 \&\& last_s1;/'
mutant unit_reset "tex_unit reset ignored in a stall (valid bits kept: responses, no requests)" \
  capacity tex_unit.sv 's/if (rst) valid <= '"'"'0;/if (rst \&\& en) valid <= '"'"'0;/'

total=$((SECONDS - start))
if [ $fail -ne 0 ]; then
  echo "formal: FAILED ($proven properties proven, $caught planted bugs caught, ${total} s;" \
       "files in $work)" >&2
  [ -n "${1:-}" ] || echo "formal: rerun with a WORKDIR argument to keep the logs and traces" >&2
  exit 1
fi
echo "formal: $proven properties proven (tex_skid W=2; tex_unit $UNIT_CFG)," \
     "$caught planted bugs caught (${total} s)"
