#!/usr/bin/env bash
# Synthesis of tex_unit and tex_unit_cached with Yosys (and nextpnr-ice40 where an iCE40 holds it).
#   scripts/synth.sh latch [BUILD]  a small tex_unit after `proc`, generic `synth` of tex_lambda and of
#                                   tex_axil_config; fails on any latch; prints the last two's cell
#                                   counts (run by `make test`, about 10 s)
#   scripts/synth.sh [BUILD [OUT]]  the latch check; then every compiled configuration (TEX_RTL_CONFIGS in
#                                   sim/engines/rtl/CMakeLists.txt: tex_unit and tex_unit_cached with its
#                                   cache fields) through synth_ecp5, synth_xilinx -family xc7 -flatten and
#                                   synth_ice40: LUTs, flip-flops, block RAMs, DSPs and the parts each fits
#                                   (ECP5 LFE5U-25F/45F/85F, Artix-7 XC7A35T/100T/200T, iCE40 HX8K/UP5K;
#                                   capacities in scripts/synth_report.py); nextpnr-ice40 (Fmax, critical
#                                   path) for each iCE40 part that holds a configuration; the largest
#                                   reduced on-chip unit (λ requests only) that places on the HX8K, for a
#                                   measured Fmax and critical path; the block decoders' table.
#                                   Writes OUT/synth/synth.json and synth.md (run by `make synth`, ~2 h)
# Every design is read with the unit itself as the top (all its ports are top-level ports, nothing
# is optimized away) and checked for latches after `proc` (Yosys fails on any). nextpnr places
# through the pin-serializing wrappers rtl/synth/tex_ice40_top.sv and tex_ice40_cached_top.sv.
# Environment: SYNTH_CONFIGS="Vtex_unit_4x4 ..." only these configurations; SYNTH_TARGETS="ecp5 xc7
# ice40" only these targets; SYNTH_REFERENCE=0 skips the reduced iCE40 unit, SYNTH_DECODERS=0 the
# decoders; SYNTH_FREQ nextpnr's target clock (MHz, default 30; timing may fail, Fmax is reported);
# SYNTH_APPEND=1 adds to the rows of an earlier run (to finish or redo some configurations);
# SYNTH_ICE40_ALL=1 runs synth_ice40 also where the ECP5 result already needs more than 4x the
# largest iCE40's logic cells (skipped by default: the slowest run, and it cannot fit).
# Logs, stats and netlists go to BUILD/synth/ (one `TARGET_CONFIG.log` per run). A tool failure stops
# the script with one line naming the configuration and its log.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
cd "$(dirname "$0")/.."
mode=full
if [ "${1:-}" = latch ]; then mode=latch; shift; fi
out="${1:-build}/synth"
res_dir="${2:-out}/synth"   # synth.json, synth.md (full mode)
mkdir -p "$out"
files=$(tr '\n' ' ' < rtl/tex_files.f)
freq=${SYNTH_FREQ:-30}     # MHz target for nextpnr (--timing-allow-fail: Fmax is reported either way)
t_start=$(date +%s)

# read_cfg LOG2_W LOG2_H CW -> yosys commands that read tex_unit so parameterized. (-defer: only the
# modules under the top are elaborated; tex_bc_decode alone, its functions inlined, takes 27 s.)
read_cfg() {
  echo "read_verilog -sv -defer $files; hierarchy -top tex_unit -chparam MAX_LOG2_W $1 -chparam MAX_LOG2_H $2 -chparam CW $3"
}

# ---- latch check: no latches allowed
# generic_check NAME TOP "YOSYS READ COMMANDS" LABEL [proc]: synth -flatten and print the cells, or
# with `proc` that pass alone (where Yosys infers latches: 1 s where synth takes a minute); fail on
# any latch with Yosys's error line.
generic_check() {
  local log="$out/generic_$1.log" stat="$out/generic_$1_stat.txt" passes="synth -top $2 -flatten"
  [ "${5:-}" = proc ] && passes="proc"
  if ! yosys -p "$3; $passes; tee -o $stat stat;
                 select -assert-none t:\$dlatch t:\$adlatch t:\$dlatchsr t:\$_DLATCH* t:\$_DLATCHSR*" \
       > "$log" 2>&1; then
    grep -o "ERROR: .*" "$log" | head -5 >&2
    echo "synth: FAILED $passes / latch check of $4, see $log" >&2
    exit 1
  fi
  if [ "${5:-}" = proc ]; then echo "synth: $4 after proc: 0 latches"
  else echo "synth: generic synth of $4: 0 latches, $(awk '/Number of cells:/{n=$4} END{print n}' "$stat") cells"
  fi
}
set -- 4 4 8
if [ "$mode" = latch ]; then  # make test; make synth below runs the generic synth
  generic_check "w$1_h$2_c$3" tex_unit "$(read_cfg "$@")" "tex_unit MAX_LOG2 $1x$2 CW=$3" proc
else
  generic_check "w$1_h$2_c$3" tex_unit "$(read_cfg "$@")" "tex_unit MAX_LOG2 $1x$2 CW=$3"
  awk '/^ +\$/{printf "  %s %s\n", $1, $2}' "$out/generic_w$1_h$2_c$3_stat.txt" | sort -k2 -n -r | head -12
fi
# The LOD unit on its own (also inside tex_unit above): no latches either.
generic_check tex_lambda tex_lambda "read_verilog -sv rtl/tex_pkg.sv rtl/tex_lambda.sv" "tex_lambda (the LOD unit)"
# The AXI4-Lite configuration slave of tex_unit_axi on its own (default parameters).
generic_check tex_axil_config tex_axil_config "read_verilog -sv rtl/tex_pkg.sv rtl/tex_axil_config.sv" \
  "tex_axil_config (AXI4-Lite configuration and counters)"
# The cube stages (inside tex_unit_cached with CUBE_MAPS), after proc: Yosys reads them as written.
cube_files="rtl/tex_pkg.sv rtl/tex_delay.sv rtl/tex_cube_face.sv rtl/tex_cube.sv rtl/tex_cube_seam.sv"
generic_check tex_cube tex_cube "read_verilog -sv $cube_files" "tex_cube (a cube lookup's face and derivatives)" proc
generic_check tex_cube_seam tex_cube_seam "read_verilog -sv $cube_files" "tex_cube_seam (probes across a seam)" proc
# The ETC2 decoders (inside tex_bc_decode too), through their harness, after proc.
generic_check tex_etc2 tex_etc2_top "read_verilog -sv -DSYNTHESIS rtl/tex_etc2.sv rtl/synth/tex_etc2_top.sv" \
  "tex_etc2 (the ETC2 and EAC decoders)" proc
generic_check tex_eac tex_eac_top "read_verilog -sv -DSYNTHESIS rtl/tex_etc2.sv rtl/synth/tex_eac_top.sv" \
  "tex_etc2::r11 (an EAC R11 channel, unsigned and signed)" proc
# The ASTC decoder, through its harness, after proc.
generic_check tex_astc tex_astc_top "read_verilog -sv -DSYNTHESIS rtl/tex_astc.sv rtl/synth/tex_astc_top.sv" \
  "tex_astc (the ASTC LDR decoder, every footprint)" proc
[ "$mode" = latch ] && exit 0

# ---- every compiled configuration on ECP5, Artix-7 and iCE40
py=/usr/bin/python3
report=scripts/synth_report.py
mkdir -p "$res_dir"
rows="$out/rows.jsonl" ref_rows="$out/ice40_reference.jsonl" run_secs="$out/run_seconds"
# SYNTH_APPEND=1 keeps the rows of an earlier run (the JSON takes the last row of each
# configuration and target, and the sum of the runs' times)
[ "${SYNTH_APPEND:-0}" = 1 ] || rm -f "$rows" "$ref_rows" "$run_secs"
fail() { echo "synth: FAILED $1, see $2" >&2; exit 1; }
elapsed() { echo $(( $(date +%s) - $1 )); }
latch_guard='proc; select -assert-none t:$dlatch t:$adlatch t:$dlatchsr'
# Compiled configurations: the quoted entries of set(TEX_RTL_CONFIGS ...).
mapfile -t configs < <(sed 's/#.*//' sim/engines/rtl/CMakeLists.txt | sed -n '/^set(TEX_RTL_CONFIGS/,/)/p' |
                       grep -o '"Vtex_[^"]*"' | tr -d '"')
[ ${#configs[@]} -gt 0 ] || fail "reading TEX_RTL_CONFIGS" sim/engines/rtl/CMakeLists.txt
if [ -n "${SYNTH_CONFIGS:-}" ]; then  # in the order given
  keep=()
  for want in $SYNTH_CONFIGS; do
    for c in "${configs[@]}"; do
      [ "${c%% *}" = "$want" ] && keep+=("$c")
    done
  done
  configs=("${keep[@]}")
fi
targets=(${SYNTH_TARGETS:-ecp5 xc7 ice40})
n_runs=$(( ${#configs[@]} * ${#targets[@]} )) run=0

# yosys_run LOG "SCRIPT" LABEL: one Yosys run (newlines in SCRIPT are spaces: commands end with
# `;`); a failure ends the script naming LABEL and LOG.
yosys_run() {
  if ! yosys -p "${2//$'\n'/ }" > "$1" 2>&1; then
    grep -m3 "ERROR\|Assertion" "$1" >&2 || tail -3 "$1" >&2
    fail "$3" "$1"
  fi
}

# nextpnr_run TAG PART "OPTIONS" NETLIST: place and route; prints "placed" or "unplaced".
nextpnr_run() {
  local log="$out/nextpnr_$1_$2.log" rc
  set +e
  nextpnr-ice40 $3 --json "$4" --asc "$out/nextpnr_$1_$2.asc" --report "$out/nextpnr_$1_$2.json" \
    --freq "$freq" --seed 1 --timing-allow-fail > "$log" 2>&1
  rc=$?
  set -e
  if [ $rc -eq 0 ] && grep -q "Max frequency for clock" "$log"; then
    echo placed
  elif grep -q "Unable to place\|Failed to expand region\|Unable to find a placement\|Failed to place\|too many\|ICESTORM_LC: *[0-9]*/ *[0-9]* *1[0-9][0-9]%" "$log"; then
    echo unplaced
  else
    tail -5 "$log" >&2
    fail "nextpnr-ice40 $2 of $1 (exit $rc)" "$log"
  fi
}

for cfg in "${configs[@]}"; do
  set -- $cfg
  name=$1 w=$2 h=$3 cw=$4 cached=0
  if [ $# -ge 10 ]; then
    cached=1 bw=$5 bh=$6 lines=$7 fifo=$8 mem_w=$9 miss=${10} formats=0 cubes=0
    for option in "${@:11}"; do
      case $option in FORMATS) formats=1;; CUBES) cubes=1;; *) fail "option $option of $name" sim/engines/rtl/CMakeLists.txt;; esac
    done
    params="tex_unit_cached ${w}x${h}, CW $cw, ${bw}x${bh} blocks, $lines lines, FIFO $fifo, MEM_W $mem_w, MISS $miss"
    [ $formats = 1 ] && params="$params, block formats + sRGB"
    [ $cubes = 1 ] && params="$params, cube maps"
    # (chparam, not read_verilog -defer with hierarchy -chparam: that hits Yosys 0.23's assertion
    # `modules_.count(module->name) == 0` on tex_unit_cached)
    # (-DTEX_SYNTH_NO_ASTC: the unit without its 8 ASTC decoders, which Yosys 0.23's resource
    # sharing cannot take in 20 GB; the decoder alone is in the decoder table, docs/rtl.md)
    read_cmd="read_verilog -sv -DTEX_SYNTH_NO_ASTC $files; chparam -set MAX_LOG2_W $w -set MAX_LOG2_H $h -set CW $cw
      -set TAG_W 16 -set BLOCK_W $bw -set BLOCK_H $bh -set LINES $lines -set FIFO_DEPTH $fifo
      -set MEM_W $mem_w -set MISS_DEPTH $miss -set BLOCK_FORMATS $formats -set SRGB $formats
      -set CUBE_MAPS $cubes tex_unit_cached;
      hierarchy -top tex_unit_cached"
  else
    params="tex_unit ${w}x${h}, CW $cw"
    read_cmd="read_verilog -sv -defer $files; hierarchy -top tex_unit -chparam MAX_LOG2_W $w
      -chparam MAX_LOG2_H $h -chparam CW $cw -chparam TAG_W 16"
  fi
  # no latches: after `proc`, in a run of its own (the same `proc` before synth_* changes the
  # netlist's order and abc's result by a few per cent)
  t0=$(date +%s)
  yosys_run "$out/latch_$name.log" "$read_cmd; $latch_guard" "latch check of $name (a latch, or Yosys)"
  echo "synth: $name ($params): 0 latches ($(elapsed "$t0") s)"
  for target in "${targets[@]}"; do
    run=$((run + 1))
    case $target in
      ecp5)  synth_cmd="synth_ecp5 -run :check";;
      xc7)   synth_cmd="synth_xilinx -family xc7 -flatten -run :check";;
      ice40) synth_cmd="synth_ice40 -run :check";;
      *) fail "unknown target $target (SYNTH_TARGETS)" "$0";;
    esac
    if [ "$target" = ice40 ] && [ "${SYNTH_ICE40_ALL:-0}" != 1 ]; then
      skip=$("$py" "$report" ice40-skip --rows "$rows" --config "$name")
      if [ -n "$skip" ]; then
        echo "synth: [$run/$n_runs] $name: $target skipped"
        "$py" "$report" row --rows "$rows" --config "$name" --params "$params" --target ice40 --skipped "$skip"
        continue
      fi
    fi
    echo "synth: [$run/$n_runs] $name: $target ..."
    t0=$(date +%s)
    log="$out/${target}_$name.log" stat="$out/${target}_$name.stat"
    # (synth_*'s `check` step without its `autoname`, which only renames: minutes on iCE40)
    yosys_run "$log" "$read_cmd; $synth_cmd; hierarchy -check; tee -o $stat stat; check -noinit" \
      "$target synthesis of $name"
    secs=$(elapsed "$t0")
    pnr_args=()
    if [ "$target" = ice40 ]; then
      # nextpnr for each iCE40 part whose capacities hold the counts, through the pin wrapper
      candidates=$("$py" "$report" ice40-candidates --stat "$stat")
      parts=()
      [ -n "$candidates" ] && mapfile -t parts <<< "$candidates"
      net=""
      for p in "${parts[@]}"; do
        part=${p%% *} opts=${p#* }
        if [ -z "$net" ]; then
          net="$out/ice40_${name}_top.json"
          if [ $cached = 1 ]; then
            # (the wrapper measures a different unit unless it takes these shapes)
            if { [ "$bw$bh" != 44 ] && ! grep -q TEX_SYN_BLOCK_W rtl/synth/tex_ice40_cached_top.sv; } ||
               { [ "$w" != "$h" ] && ! grep -q TEX_SYN_LOG2_H rtl/synth/tex_ice40_cached_top.sv; }; then
              echo "synth:   $part: not placed (tex_ice40_cached_top has no TEX_SYN_BLOCK_W/H or TEX_SYN_LOG2_H for this shape)"
              net=none
              break
            fi
            wrap_cmd="read_verilog -sv -DTEX_SYNTH_NO_ASTC -DTEX_SYN_LOG2=$w -DTEX_SYN_LOG2_H=$h -DTEX_SYN_CW=$cw -DTEX_SYN_LINES=$lines
              -DTEX_SYN_FIFO=$fifo -DTEX_SYN_MISS=$miss -DTEX_SYN_MEM_W=$mem_w -DTEX_SYN_FORMATS=$formats
              -DTEX_SYN_BLOCK_W=$bw -DTEX_SYN_BLOCK_H=$bh $files rtl/synth/tex_ice40_cached_top.sv;
              hierarchy -top tex_ice40_cached_top"
          else
            wrap_cmd="read_verilog -sv $files rtl/synth/tex_ice40_top.sv; chparam -set MAX_LOG2_W $w
              -set MAX_LOG2_H $h -set CW $cw -set DERIV 1 tex_ice40_top; hierarchy -top tex_ice40_top"
          fi
          yosys_run "$out/ice40_${name}_top.log" "$wrap_cmd; synth_ice40 -json $net" \
            "synth_ice40 of the pin wrapper of $name"
        fi
        state=$(nextpnr_run "$name" "$part" "$opts" "$net")
        echo "synth:   nextpnr-ice40 $part: $state"
        pnr_args+=(--pnr "$part=$out/nextpnr_${name}_$part.json:$out/nextpnr_${name}_$part.log")
      done
      secs=$(elapsed "$t0")
    fi
    "$py" "$report" row --rows "$rows" --config "$name" --params "$params" --target "$target" \
      --stat "$stat" --seconds "$secs" "${pnr_args[@]}"
  done
done

# ---- a measured iCE40 Fmax: no compiled configuration fits an iCE40, so the largest reduced
# on-chip unit that places on the HX8K (λ requests only: tex_ice40_top with DERIV = 0 ties the
# derivative inputs off and the LOD/anisotropy unit is optimized away), from larger to smaller.
if [ "${SYNTH_REFERENCE:-1}" != 0 ]; then
  for cfg in "3 3 2" "3 3 1" "2 2 1" "2 1 1" "1 1 1"; do
    set -- $cfg
    tag="ref_w$1_h$2_c$3" t0=$(date +%s)
    echo "synth: iCE40 reference: tex_unit $1x$2, CW $3, λ requests only ..."
    yosys_run "$out/ice40_$tag.log" "read_verilog -sv $files rtl/synth/tex_ice40_top.sv;
      chparam -set MAX_LOG2_W $1 -set MAX_LOG2_H $2 -set CW $3 -set DERIV 0 tex_ice40_top;
      hierarchy -top tex_ice40_top; $latch_guard; synth_ice40 -json $out/ice40_$tag.json;
      tee -o $out/ice40_$tag.stat stat" "synth_ice40 of the iCE40 reference $1x$2 CW $3"
    state=$(nextpnr_run "$tag" iCE40HX8K "--hx8k --package ct256" "$out/ice40_$tag.json")
    echo "synth:   nextpnr-ice40 iCE40HX8K: $state"
    "$py" "$report" row --rows "$ref_rows" --config "$tag" --target ice40 --stat "$out/ice40_$tag.stat" \
      --params "tex_unit $1x$2, CW $3, λ requests only (tex_ice40_top DERIV=0)" --seconds "$(elapsed "$t0")" \
      --pnr "iCE40HX8K=$out/nextpnr_${tag}_iCE40HX8K.json:$out/nextpnr_${tag}_iCE40HX8K.log"
    [ "$state" = placed ] && break
  done
fi

# ---- the block decoders (docs/numerics.md): one texel per call, combinational; the cached unit's
# taps call them 8 times per sample (the sRGB table 24 times). Each through its harness
# (rtl/synth/tex_bc_decode_top.sv with FORMAT fixing a format, so that only that format's decoder
# is kept; tex_srgb_decode_top.sv): synth_ice40 and synth_ecp5 LUTs, no latches; a table in
# BUILD/synth/decoders.md.
if [ "${SYNTH_DECODERS:-1}" != 0 ]; then
# (one line: a newline inside `yosys -p` ends a command)
decoder_files="rtl/tex_pkg.sv rtl/tex_bc_colour.sv rtl/tex_bc_channel.sv rtl/tex_bc7.sv rtl/tex_etc2.sv rtl/tex_astc.sv rtl/tex_bc_decode.sv rtl/tex_srgb_decode.sv rtl/synth/tex_bc_decode_top.sv rtl/synth/tex_srgb_decode_top.sv rtl/synth/tex_etc2_top.sv rtl/synth/tex_eac_top.sv rtl/synth/tex_astc_top.sv"
# name:top:FORMAT (empty: none):what
decoders=("bc1:tex_bc_decode_top:1:BC1 (tex_bc_colour; also the colour of BC2, BC3)"
          "bc4:tex_bc_decode_top:4:BC4 (tex_bc_channel; also BC3's alpha, each half of BC5)"
          "bc7:tex_bc_decode_top:7:BC7 (tex_bc7)" "all:tex_bc_decode_top::every format but ASTC (what each tap calls; ASTC below)"
          "srgb:tex_srgb_decode_top::sRGB, one channel (tex_srgb_decode; 3 per texel)"
          "etc2:tex_etc2_top::ETC2 RGB8, RGB8A1 and RGBA8 with EAC alpha (tex_etc2; inside every)"
          "eac:tex_eac_top::EAC R11, one channel, unsigned and signed (tex_etc2::r11; RG11 takes two; inside every)"
          "astc:tex_astc_top::ASTC LDR, every footprint 4x4 .. 12x12, linear and sRGB (tex_astc, without resource sharing)")
{
  echo "| decoder | formats | iCE40 SB_LUT4 | iCE40 SB_CARRY | ECP5 LUT4 | ECP5 CCU2C | ECP5 MULT18X18D |"
  echo "|---|---|---|---|---|---|---|"
} > "$out/decoders.md"
# synth_TARGET without the SAT-based resource sharing of its `coarse` step (Yosys 0.23's lists):
# on tex_astc `share` ran out of 20 GB. The other steps as synth_TARGET runs them.
coarse_noshare() {
  case $1 in
    ecp5)  echo "proc; flatten; tribuf -logic; deminout; opt_expr; opt_clean; check; opt -nodffe -nosdff; fsm; opt;
                 wreduce; peepopt; opt_clean; techmap -map +/cmp2lut.v -D LUT_WIDTH=4; opt_expr; opt_clean;
                 techmap -map +/mul2dsp.v -map +/ecp5/dsp_map.v -D DSP_A_MAXWIDTH=18 -D DSP_B_MAXWIDTH=18 -D DSP_A_MINWIDTH=2 -D DSP_B_MINWIDTH=2 -D DSP_NAME=\$__MUL18X18;
                 chtype -set \$mul t:\$__soft_mul; alumacc; opt; memory -nomap; opt_clean";;
    ice40) echo "opt_expr; opt_clean; check; opt -nodffe -nosdff; fsm; opt; wreduce; peepopt; opt_clean;
                 techmap -map +/cmp2lut.v -D LUT_WIDTH=4; opt_expr; opt_clean; memory_dff; wreduce t:\$mul; alumacc; opt;
                 memory -nomap; opt_clean";;
  esac
}
for d in "${decoders[@]}"; do
  IFS=: read -r name top format what <<< "$d"
  param=""
  [ -n "$format" ] && param="chparam -set FORMAT $format $top;"
  defs=""
  [ "$name" = all ] && defs="-DTEX_SYNTH_NO_ASTC"  # (every format but ASTC: its row is its own)
  for target in ice40 ecp5; do
    flow="synth_$target -top $top"
    [ "$name" = astc ] && flow="synth_$target -top $top -run begin:coarse; $(coarse_noshare $target); synth_$target -top $top -run map_ram:"
    if ! yosys -p "read_verilog -sv $defs -Irtl $decoder_files; $param ${flow//$'\n'/ }; tee -o $out/${target}_decoder_$name.stat stat;
                   select -assert-none t:\$dlatch t:\$_DLATCH* t:LATCH*" > "$out/${target}_decoder_$name.log" 2>&1; then
      tail -20 "$out/${target}_decoder_$name.log" >&2
      echo "synth: FAILED synth_$target of decoder $name, see $out/${target}_decoder_$name.log" >&2
      exit 1
    fi
  done
  count() { awk -v c="$2" '$1 == c {n = $2} END {print n + 0}' "$out/$1_decoder_$name.stat"; }
  row="| $name | $what | $(count ice40 SB_LUT4) | $(count ice40 SB_CARRY) | $(count ecp5 LUT4) | $(count ecp5 CCU2C) | $(count ecp5 MULT18X18D) |"
  echo "$row" >> "$out/decoders.md"
  echo "synth: decoder $row"
done
fi

# ---- the JSON and the Markdown tables (the tables come from the JSON alone)
rtl_state=$(git diff --quiet HEAD -- rtl 2>/dev/null && echo "" || echo " (rtl/ modified)")
elapsed "$t_start" >> "$run_secs"
"$py" "$report" collect --rows "$rows" --reference "$ref_rows" --out "$res_dir/synth.json" \
  --seconds "$(awk '{s += $1} END {print s}' "$run_secs")" --commit "$(git rev-parse --short HEAD 2>/dev/null || echo unknown)$rtl_state" \
  --tools "$(yosys -V | cut -d' ' -f1,2); $(nextpnr-ice40 --version 2>&1 | head -1)"
"$py" "$report" markdown --json "$res_dir/synth.json" --out "$res_dir/synth.md"
cat "$res_dir/synth.md"
echo "synth: $res_dir/synth.json, $res_dir/synth.md; logs in $out/ ($(( $(elapsed "$t_start") / 60 )) min;" \
     "with earlier appended runs $(( $(awk '{s += $1} END {print s}' "$run_secs") / 60 )) min)"
