#!/usr/bin/env bash
# Formal proofs of the valid/ready handshake with Yosys 0.23 + yosys-smtbmc + z3
# (docs/verification.md, "Formal proofs"). The properties are immediate assertions under
# `ifdef FORMAL in rtl/tex_skid.sv, rtl/tex_unit.sv, rtl/tex_axil_config.sv, rtl/tex_cached_fetch.sv
# and the two parts of its memory path it names (rtl/tex_miss_ring.sv, rtl/tex_fill_fifo.sv);
# rtl/formal/*_formal.sv are the environments (reset in the first clock, then every input free,
# resets included; tex_axil_config's AXI4-Lite master keeps the protocol's rules).
#  1. tex_skid (W=2) and tex_unit (2x2 texels, CW=1, TAG_W=2; the texel datapath cut to a free
#     value): BMC from reset, then k-induction from an arbitrary state, of
#       order    - the n-th response is the n-th accepted item, with its data / tag (none lost,
#                  duplicated or reordered): a tracked item (any constant ordinal) is followed;
#       hold     - a stalled valid stays high, with its data / tag and texel unchanged;
#       probes   - (unit) a request's probes (N = 1..16, any N: tex_aniso's comparisons are cut)
#                  follow each other through the pipeline with its tag, first to last;
#       capacity - in flight (accepted - emitted) = the requests held <= 2 (skid) / 17 (unit).
#     tex_axil_config (ADDR_W=8; its counters cut to free values), BMC from reset and
#     k-induction, of
#       bhold, rhold - BVALID (RVALID) held until BREADY (RREADY), BRESP (RDATA, RRESP) stable;
#       bone, rone   - one B per write whose AW and W were both taken (in either order), one R
#                      per taken AR; none without a request;
#       slverr       - a write to an undefined or read-only address, or with WSTRB != 4'b1111,
#                      answers SLVERR; a read of an undefined address SLVERR with RDATA 0;
#       nochange     - a SLVERR write changes no output and clears no counter;
#       desc         - cfg_desc_we is one clock, exactly at each accepted DESC_COMMIT write, and
#                      only when the unit was ready (cfg_desc_ready) in the clock of the write.
#     tex_cached_fetch (tex_unit_cached's AXI4 read master: 2x2-texel lines, 16 lines, miss ring
#     16, fill FIFO 1, 64-bit beats; tag answers, line numbers and bank words cut; the slave
#     assumed to send no beat without an open burst), BMC from reset and k-induction, of
#       arhold        - ARVALID held until ARREADY, ARADDR stable;
#       arburst       - every read is one whole line at an aligned address;
#       aroutstanding - at most MISS_DEPTH reads in flight, and the bursts open are those accepted
#                       less those fully received (with the ring's pointer invariants);
#       rready        - a beat is taken only when the fill FIFO has room for its line.
#  2. Structure (the real RTL, no FORMAL): no combinational path from out_ready to in_ready,
#     rsp_ready to req_ready, or any input to any output of tex_unit and of tex_axil_config.
#  3. Planted bugs: each is a sed on a copy of the RTL and must make a named check fail (BMC
#     counterexample from reset, or the structural check). Exit status non-zero if a proof fails
#     on the real RTL or a planted bug is not caught.
# Usage: scripts/formal.sh [--proofs] [WORKDIR]   (default: a temporary directory, removed at the
#        end; WORKDIR keeps the models, logs and counterexample traces). --proofs: 1 and 2 only,
#        no planted bugs (make test: about a minute; make formal runs all, about 5 minutes)
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
proofs_only=0
if [ "${1:-}" = --proofs ]; then proofs_only=1; shift; fi
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

SKID_PARAMS="-chparam W 2"
UNIT_PARAMS="-chparam MAX_LOG2_W 1 -chparam MAX_LOG2_H 1 -chparam CW 1 -chparam TAG_W 2"
UNIT_CFG="2x2 texels, CW=1, TAG_W=2"
COMB_PARAMS="-chparam MAX_LOG2_W 2 -chparam MAX_LOG2_H 1 -chparam CW 2"  # structural: 4x2, CW=2
AXIL_PARAMS="-chparam ADDR_W 8"
AXIL_CFG="ADDR_W=8"
SKID_BMC=10; UNIT_BMC=20   # BMC depth (steps from reset): the unit fills up (17 items) in 18
AXIL_BMC=8                 # a write clearing unit_reset, then a descriptor commit: step 4
CACHED_PARAMS="-chparam MISS_DEPTH 16"  # (the environment's defaults: 2x2 texels per line, 16 lines,
CACHED_CFG="2x2-texel lines, 16 lines, FIFO 2, miss ring 16, fill FIFO 1, 64-bit beats"  # ...)
CACHED_BMC=10              # 3 pushes of 8 misses: step 4; a second line received: step 8
INDUCT=4                   # k-induction length (all close at k = 1)

# sources DIR [TOP]: the RTL file list with DIR/ in front (tex_axil_config: only the package and
# the module, which keeps its many planted-bug models quick to build)
sources() {
  if [[ "${2:-}" == tex_axil_config* ]]; then echo "$1/rtl/tex_pkg.sv $1/rtl/tex_axil_config.sv"
  else sed "s|^|$1/|" "$root/rtl/tex_files.f" | tr '\n' ' '; fi
}

# model NAME DIR TOP PARAMS: DIR/rtl (+ DIR/rtl/formal) -> $work/NAME.smt2. Read with -defer, so
# that only the modules under TOP are elaborated (tex_bc_decode alone, its decoder functions
# inlined, takes Yosys 27 s; no proof instantiates it). The simulation checks
# of tex_unit (`ifndef SYNTHESIS, not parsed by Yosys) are left out by -DSYNTHESIS. In tex_unit,
# the texel datapath's result rgba_s11 and tex_aniso's comparisons `reaches` (k^2 Pmin^2 >= the
# target) are cut points (free values each clock, an over-approximation): a derivative request
# issues any number of probes 1..16, and the solver sees the control, tags, probe sequencer and
# skid buffer without the multipliers. The model is bit-blasted (abc -g AND): z3 takes seconds on
# it, minutes or more on the word-level model. In tex_axil_config the 9 64-bit counters are cut
# (no property is about their values; the model builds in half the time). In tex_cached_fetch the
# cache tags' answers (hit, slot), the line numbers and the data banks' words are cut: every pattern
# of hits and misses at any address is reachable, and the tag and data memories drop out.
model() {
  local name=$1 dir=$2 top=$3 params=$4 cut=""
  [ "$top" = tex_unit_formal ] &&
    cut="cutpoint w:dut.rgba_s11 w:dut.u_probe.u_aniso.reaches; opt_clean;"
  [ "$top" = tex_axil_config_formal ] && cut="cutpoint w:dut.cnt; opt_clean;"
  [ "$top" = tex_cached_fetch_formal ] &&
    cut="cutpoint w:dut.u_tag.hit_c* w:dut.u_tag.slot_c* w:dut.u_tag.look_line* w:dut.bank_word*; opt_clean;"
  yosys -q -l "$work/$name.yosys.log" -p "
    read_verilog -defer -formal -DSYNTHESIS -sv $(sources "$dir" "$top") $dir/rtl/formal/$top.sv
    hierarchy -top $top $params; prep -flatten -top $top; $cut
    memory_map; opt -fast; async2sync; dffunmap; techmap; opt -fast; abc -g AND; opt_clean;
    dffunmap; write_smt2 -wires $work/$name.smt2" \
    > /dev/null 2>&1 ||
    { echo "formal: yosys failed on $name, see $work/$name.yosys.log" >&2; return 2; }
  grep -q 'yosys-smt2-assert' "$work/$name.smt2" ||
    { echo "formal: no assertion in $name (FORMAL blocks missing?)" >&2; return 2; }
}

# failed_props LOG: the properties (order, hold, probes, capacity) of the assertions that failed
# in LOG, told apart by the text of the assertion's line; tex_axil_config's assertions are
# labelled p_<property>_<n> (bhold, rhold, bone, rone, slverr, nochange, desc).
failed_props() {
  {
    grep -o 'Assert failed in [^:]*: [^ ]*' "$1" | sed -n 's/.*[ .]p_\([a-z]*\)_[0-9]*$/\1/p'
    grep -o '\$assert\$[^$]*:[0-9]*\$' "$1" | sed 's/^\$assert\$//; s/\$$//' | sort -u |
      while IFS=: read -r file line; do
        text=$(sed -n "${line}p" "$file")
        case "$text" in
          *f_stalled_q*) echo hold ;;
          *f_pick*) echo order ;;
          *index*|*aniso_n*|*'!last['*|*'.tag[TGW])'*|*'!accum_held)'*|*'!probe_first)'*) echo probes ;;
          *) echo capacity ;;
        esac
      done
    true  # (either grep may find nothing)
  } | sort -u | tr '\n' ' '
}

# comb_clean DIR TOP SELECTION: the flattened real RTL (no FORMAL, flip-flops unmapped to $dff)
# has no wire in SELECTION, e.g. the forward cone of rsp_ready stopped at flip-flops, intersected
# with req_ready. The named ports must exist (so that the check is not vacuous).
comb_clean() {
  local dir=$1 top=$2 sel=$3 params=""
  [ "$top" = tex_unit ] && params=$COMB_PARAMS
  yosys -q -p "read_verilog -defer -sv $(sources "$dir" "$top"); hierarchy -top $top $params; proc; flatten;
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
proof axil tex_axil_config_formal "$AXIL_PARAMS" "tex_axil_config $AXIL_CFG" $AXIL_BMC \
  "bhold (BVALID, BRESP until BREADY)" "rhold (RVALID, RDATA, RRESP until RREADY)" \
  "bone (one B per write: AW and W both taken, either order; none without them)" \
  "rone (one R per taken AR; none without it)" \
  "slverr (undefined or read-only address, partial WSTRB: SLVERR; undefined read: SLVERR, 0)" \
  "nochange (a SLVERR write changes no output, clears no counter)" \
  "desc (cfg_desc_we: one clock, exactly at each accepted DESC_COMMIT, with its index, only with cfg_desc_ready)"
structural "tex_axil_config: no combinational path from any input to any output" \
  tex_axil_config "$UNIT_ANY"
proof cached tex_cached_fetch_formal "$CACHED_PARAMS" "tex_cached_fetch $CACHED_CFG" $CACHED_BMC \
  "arhold (ARVALID stays high, ARADDR unchanged, until ARREADY)" \
  "arburst (every read is one whole, aligned line)" \
  "aroutstanding (at most MISS_DEPTH reads in flight; bursts open = accepted - fully received)" \
  "rready (a beat is taken only with room for its line)"

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
# mutant NAME WHAT EXPECTED FILE SED: EXPECTED is a property (order, hold, capacity, or one of
# tex_axil_config's: a BMC counterexample from reset must violate it) or comb-skid / comb-unit /
# comb-axil (the structural check).
mutant() {
  local name=$1 what=$2 want=$3 file=$4 expr=$5 dir got=""
  dir=$(plant "$name" "$file" "$expr") || { fail=1; return; }
  case "$want" in
    comb-skid) comb_clean "$dir" tex_skid "$SKID_COMB" || got=$want ;;
    comb-unit) comb_clean "$dir" tex_unit "$UNIT_COMB" || got=$want ;;
    comb-axil) comb_clean "$dir" tex_axil_config "$UNIT_ANY" || got=$want ;;
    *)
      local top=tex_skid_formal params=$SKID_PARAMS depth=$SKID_BMC
      if [ "$file" = tex_axil_config.sv ]; then
        top=tex_axil_config_formal params=$AXIL_PARAMS depth=$AXIL_BMC
      elif [[ "$file" =~ ^tex_(cached_fetch|miss_ring|fill_fifo)\.sv$ ]]; then
        top=tex_cached_fetch_formal params=$CACHED_PARAMS depth=$CACHED_BMC
      elif [ "$file" != tex_skid.sv ]; then
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

if [ $proofs_only = 0 ]; then  # (to the fi after the last mutant: --proofs skips them)
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
mutant axil_bdrop "tex_axil_config drops BVALID without BREADY" \
  bhold tex_axil_config.sv 's/else if (s_axi_bready) bvalid <= 1.b0;/else bvalid <= 1'"'"'b0;/'
mutant axil_rdata "tex_axil_config reloads RDATA while the response waits (a new ARVALID)" \
  rhold tex_axil_config.sv 's/    if (ar_take) begin/    if (ar_take || s_axi_arvalid) begin/'
mutant axil_no_w "tex_axil_config writes (and answers) when AW comes, without waiting for W" \
  bone tex_axil_config.sv 's/assign do_write = (aw_full || aw_take) \&\& (w_full || w_take) \&\& !desc_wait;/assign do_write = (aw_full || aw_take) \&\& !desc_wait;/'
mutant axil_ar_busy "tex_axil_config takes AR while an R response waits (one response lost)" \
  rone tex_axil_config.sv "s/assign s_axi_arready = !rvalid;/assign s_axi_arready = 1'b1;/"
mutant axil_undef "tex_axil_config answers OKAY to a write to an undefined address" \
  slverr tex_axil_config.sv 's/default:       wr_ok = 1.b0;  \/\/ undefined or read-only/default: ;/'
mutant axil_wstrb "tex_axil_config ignores WSTRB (a partial write answers OKAY)" \
  slverr tex_axil_config.sv "s/wr_ok = ws == 4'hF;/wr_ok = 1'b1;/"
mutant axil_cache "tex_axil_config applies a refused CACHE write (unit running, bad geometry)" \
  nochange tex_axil_config.sv 's/if (wr_en \&\& sel_cache)/if (do_write \&\& sel_cache)/'
mutant axil_clear "tex_axil_config clears the counters on a refused CONTROL write" \
  nochange tex_axil_config.sv 's/assign cnt_clear = wr_en \&\& sel_control \&\& wd\[2\];/assign cnt_clear = do_write \&\& sel_control \&\& wd[2];/'
mutant axil_desc "tex_axil_config pulses cfg_desc_we on a DESC_ATTR write too" \
  desc tex_axil_config.sv 's/desc_we <= wr_en \&\& sel_commit;/desc_we <= wr_en \&\& (sel_commit || sel_attr);/'
mutant axil_desc_held "tex_axil_config holds cfg_desc_we high after a commit" \
  desc tex_axil_config.sv 's/desc_we <= wr_en \&\& sel_commit;/desc_we <= desc_we || (wr_en \&\& sel_commit);/'
mutant axil_desc_ready "tex_axil_config commits while the unit sets up the last descriptor (cfg_desc_ready ignored)" \
  desc tex_axil_config.sv 's/ \&\& !desc_wait;/;/'
mutant axil_smp "tex_axil_config pulses cfg_smp_we on a FILTER write too (a half-staged sampler written)" \
  smp tex_axil_config.sv 's/smp_we  <= wr_en \&\& sel_smp_commit;/smp_we  <= wr_en \&\& (sel_smp_commit || sel_filter);/'
mutant axil_comb "tex_axil_config AWREADY = !aw_full && (!bvalid || BREADY) (combinational path)" \
  comb-axil tex_axil_config.sv 's/assign s_axi_awready = !aw_full \&\& !bvalid;/assign s_axi_awready = !aw_full \&\& (!bvalid || s_axi_bready);/'
mutant cached_arhold "tex_miss_ring reads the newest miss's bank, not the oldest's (ARADDR moves while stalled)" \
  arhold tex_miss_ring.sv 's/assign mem_req_addr  = {bank_line\[iss\[RBW-1:0\]\]/assign mem_req_addr  = {bank_line[wr[RBW-1:0] - 1'"'"'b1]/'
mutant cached_arburst "tex_miss_ring reads from the second byte of a line (a misaligned burst)" \
  arburst tex_miss_ring.sv "s/, LOG2_LB'(0)};/, LOG2_LB'(1)};/"
mutant cached_ring "tex_cached_fetch admits a sample with 8 misses into a full miss ring" \
  aroutstanding tex_cached_fetch.sv "s/ring_next <= MCW'(MISS_DEPTH - 8)/ring_next <= MCW'(MISS_DEPTH)/"
mutant cached_rready "tex_fill_fifo takes beats with the fill FIFO full (RREADY always high)" \
  rready tex_fill_fifo.sv "s/assign mem_rsp_ready = count != LCW'(DEPTH);/assign mem_rsp_ready = 1'b1;/"
fi

total=$((SECONDS - start))
bugs="$caught planted bugs caught"
[ $proofs_only = 1 ] && bugs="no planted bugs (make formal)"
if [ $fail -ne 0 ]; then
  echo "formal: FAILED ($proven properties proven, $bugs, ${total} s; files in $work)" >&2
  [ -n "${1:-}" ] || echo "formal: rerun with a WORKDIR argument to keep the logs and traces" >&2
  exit 1
fi
echo "formal: $proven properties proven (tex_skid W=2; tex_unit $UNIT_CFG; tex_axil_config $AXIL_CFG;" \
     "tex_cached_fetch $CACHED_CFG)," \
     "$bugs (${total} s)"
