#!/usr/bin/env bash
# Synthesis of tex_unit and tex_unit_cached with Yosys (and nextpnr for iCE40).
#   scripts/synth.sh latch [BUILD]  generic `synth` of a small tex_unit and of tex_lambda; fails on any latch;
#                                   prints the cell counts (run by `make test`)
#   scripts/synth.sh [BUILD]        the latch check; generic `synth` of a small tex_unit_cached,
#                                   RGBA and with the formats (no latches, cell counts); then synth_ice40 + nextpnr-ice40
#                                   --hx8k of tex_unit and of tex_unit_cached, larger to smaller
#                                   configurations until one fits: LUT/BRAM use and Fmax
#                                   (run by `make synth`)
# Configurations: MAX_LOG2_W MAX_LOG2_H CW (tex_unit); LOG2 CW LINES FIFO MISS MEM_W
# (tex_unit_cached, square, 4x4 blocks, through rtl/synth/tex_ice40_cached_top.sv, whose
# parameters are macros: Yosys 0.23 cannot chparam tex_unit_cached). Logs and netlists go to
# BUILD/synth/.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
cd "$(dirname "$0")/.."
mode=full
if [ "${1:-}" = latch ]; then mode=latch; shift; fi
out="${1:-build}/synth"
mkdir -p "$out"
files=$(tr '\n' ' ' < rtl/tex_files.f)
freq=${SYNTH_FREQ:-30}     # MHz target for nextpnr (it exits non-zero when missed)
hx8k_luts=7680

read_cfg() {  # $1 $2 $3 [top] -> yosys commands that read and parameterize the design
  local top=${4:-tex_unit}
  echo "read_verilog -sv $files rtl/synth/tex_ice40_top.sv; chparam -set MAX_LOG2_W $1 -set MAX_LOG2_H $2 -set CW $3 $top; hierarchy -top $top"
}

# ---- latch check: generic synth, no latches allowed
# generic_check NAME TOP "YOSYS READ COMMANDS" LABEL: synth -flatten, fail on any latch, print cells.
generic_check() {
  local log="$out/generic_$1.log" stat="$out/generic_$1_stat.txt"
  if ! yosys -p "$3; synth -top $2 -flatten; tee -o $stat stat;
                 select -assert-none t:\$dlatch t:\$adlatch t:\$dlatchsr t:\$_DLATCH* t:\$_DLATCHSR*" \
       > "$log" 2>&1; then
    grep -i "latch\|error" "$log" | head -20 >&2
    echo "synth: FAILED generic synth / latch check of $4, see $log" >&2
    exit 1
  fi
  echo "synth: generic synth of $4: 0 latches, $(awk '/Number of cells:/{n=$4} END{print n}' "$stat") cells"
}
set -- 4 4 8
generic_check "w$1_h$2_c$3" tex_unit "$(read_cfg "$@")" "tex_unit MAX_LOG2 $1x$2 CW=$3"
awk '/^ +\$/{printf "  %s %s\n", $1, $2}' "$out/generic_w$1_h$2_c$3_stat.txt" | sort -k2 -n -r | head -12
# The LOD unit on its own (also inside tex_unit above): no latches either.
generic_check tex_lambda tex_lambda "read_verilog -sv rtl/tex_pkg.sv rtl/tex_lambda.sv" "tex_lambda (the LOD unit)"
[ "$mode" = latch ] && exit 0

# ---- iCE40 HX8K
# ice40_fit TAG TOP "YOSYS READ COMMANDS" LABEL: synth_ice40, then nextpnr-ice40 --hx8k when the
# LUTs fit; prints the result; returns 0 when it fits (exits on a tool failure).
ice40_fit() {
  local tag=$1 label=$4  # ($2, the top, is set by the read commands)
  # (errexit is off in a function called from `if`: every failure is checked here.)
  # (no -top: the read commands set it, and chparam on a wrapper renames the derived top)
  if ! yosys -p "$3; synth_ice40 -json $out/ice40_$tag.json; tee -o $out/ice40_$tag.stat stat" \
       > "$out/ice40_$tag.log" 2>&1; then
    tail -20 "$out/ice40_$tag.log" >&2
    echo "synth: FAILED synth_ice40 of $label, see $out/ice40_$tag.log" >&2
    exit 1
  fi
  local luts brams ffs
  luts=$(awk '/SB_LUT4/{n=$2} END{print n+0}' "$out/ice40_$tag.stat")
  brams=$(awk '/SB_RAM40_4K/{n=$2} END{print n+0}' "$out/ice40_$tag.stat")
  ffs=$(awk '/SB_DFF/{n+=$2} END{print n+0}' "$out/ice40_$tag.stat")
  echo "synth: synth_ice40 $label: $luts SB_LUT4, $ffs flip-flops, $brams SB_RAM40_4K"
  if [ "$luts" -gt "$hx8k_luts" ]; then
    echo "synth:   does not fit the HX8K ($luts > $hx8k_luts LUTs): skipping place and route"
    return 1
  fi
  local pnr_log="$out/nextpnr_$tag.log" rc fmax util_lc util_ram
  set +e
  nextpnr-ice40 --hx8k --package ct256 --json "$out/ice40_$tag.json" --asc "$out/ice40_$tag.asc" \
    --freq "$freq" --seed 1 > "$pnr_log" 2>&1
  rc=$?
  set -e
  fmax=$(grep -o "Max frequency for clock '[^']*': [0-9.]* MHz" "$pnr_log" | tail -1 | grep -o "[0-9.]* MHz" || true)
  util_lc=$(grep -o "ICESTORM_LC: *[0-9]*/ *[0-9]* *[0-9]*%" "$pnr_log" | tail -1 || true)
  util_ram=$(grep -o "ICESTORM_RAM: *[0-9]*/ *[0-9]* *[0-9]*%" "$pnr_log" | tail -1 || true)
  if grep -q "Unable to place\|Unable to find a placement\|ICESTORM_LC: *[0-9]*/ *[0-9]* *1[0-9][0-9]%" "$pnr_log"; then
    echo "synth:   nextpnr: does not fit the HX8K ($util_lc)"
    return 1
  fi
  if [ -z "$fmax" ]; then
    tail -20 "$pnr_log" >&2
    echo "synth: FAILED nextpnr-ice40 for $label (exit $rc), see $pnr_log" >&2
    exit 1
  fi
  [ $rc -ne 0 ] && echo "synth:   (nextpnr exit $rc: target --freq $freq MHz missed)"
  echo "synth: SUMMARY nextpnr-ice40 --hx8k ct256, $label: Fmax $fmax (target $freq MHz), $util_lc, $util_ram"
}

# tex_ice40_top: tex_unit behind a serial pin wrapper (its ~240 ports exceed the package).
# 16x16 texels, CW=8 first; smaller until one fits.
fit_cfg=""
ice40_configs=("4 4 8" "4 4 4" "3 3 4" "3 3 2")
for cfg in "${ice40_configs[@]}"; do
  set -- $cfg
  if ice40_fit "w$1_h$2_c$3" tex_ice40_top "$(read_cfg "$@" tex_ice40_top)" "MAX_LOG2 $1x$2 CW=$3"; then
    fit_cfg=$cfg
    break
  fi
done
# (a report, not a failure: the cached part below is still measured)
[ -n "$fit_cfg" ] || echo "synth: no tex_unit configuration fits the HX8K (largest first: ${ice40_configs[*]})"

# ---- tex_unit_cached: generic synth with the latch check, then iCE40 from larger to smaller.
read_cached() {  # LOG2 CW LINES FIFO MISS MEM_W [FORMATS] -> yosys commands
  echo "read_verilog -sv -DTEX_SYN_LOG2=$1 -DTEX_SYN_CW=$2 -DTEX_SYN_LINES=$3 -DTEX_SYN_FIFO=$4 \
        -DTEX_SYN_MISS=$5 -DTEX_SYN_MEM_W=$6 -DTEX_SYN_FORMATS=${7:-0} $files rtl/synth/tex_ice40_cached_top.sv; \
        hierarchy -top tex_ice40_cached_top"
}
set -- 4 8 16 16 16 32
generic_check cached tex_ice40_cached_top "$(read_cached "$@")" \
  "tex_unit_cached LOG2 $1 CW=$2 LINES=$3 FIFO=$4 MISS=$5 MEM_W=$6"
# With the block decoders and the sRGB tables (FORMATS: CW 16, 8-bit channels in memory).
set -- 4 16 16 16 16 32 1
generic_check cached_formats tex_ice40_cached_top "$(read_cached "$@")" \
  "tex_unit_cached LOG2 $1 CW=$2 LINES=$3 FIFO=$4 MISS=$5 MEM_W=$6 with the formats"

fit_cached=""
cached_configs=("4 8 16 16 16 32" "3 2 16 2 16 16")  # 16x16 8-bit; 8x8 2-bit, FIFO 2: the smallest
for cfg in "${cached_configs[@]}"; do
  set -- $cfg
  if ice40_fit "cached_l$1_c$2_n$3_f$4" tex_ice40_cached_top "$(read_cached "$@")" \
               "tex_unit_cached LOG2 $1 CW=$2 LINES=$3 FIFO=$4 MISS=$5 MEM_W=$6"; then
    fit_cached=$cfg
    break
  fi
done
[ -n "$fit_cached" ] || echo "synth: no tex_unit_cached configuration fits the HX8K (largest first: ${cached_configs[*]})"

# ---- the block decoders (docs/numerics.md): one texel per decoder, combinational; the cached unit
# will take 8 per sample. synth_ice40 and synth_ecp5 LUTs per decoder, no latches; a table in
# BUILD/synth/decoders.md.
decoder_files="rtl/tex_pkg.sv rtl/tex_bc_channel.sv rtl/tex_bc_colour.sv rtl/tex_bc7_mode.sv rtl/tex_bc7.sv rtl/tex_bc_decode.sv
               rtl/tex_srgb_decode.sv"
decoders=("tex_bc_colour:BC1 (and the colour of BC2, BC3)" "tex_bc_channel:BC4 (and BC3's alpha, each half of BC5)"
          "tex_bc7:BC7" "tex_bc_decode:every format (what the cached unit's taps will take)"
          "tex_srgb_decode:sRGB, one channel (3 per texel)")
{
  echo "| decoder | formats | iCE40 SB_LUT4 | iCE40 SB_CARRY | ECP5 LUT4 | ECP5 CCU2C | ECP5 MULT18X18D |"
  echo "|---|---|---|---|---|---|---|"
} > "$out/decoders.md"
for d in "${decoders[@]}"; do
  top=${d%%:*}
  what=${d#*:}
  for target in ice40 ecp5; do
    if ! yosys -p "read_verilog -sv $decoder_files; synth_$target -top $top; tee -o $out/${target}_$top.stat stat;
                   select -assert-none t:\$dlatch t:\$_DLATCH* t:LATCH*" > "$out/${target}_$top.log" 2>&1; then
      tail -20 "$out/${target}_$top.log" >&2
      echo "synth: FAILED synth_$target of $top, see $out/${target}_$top.log" >&2
      exit 1
    fi
  done
  count() { awk -v c="$2" '$1 == c {n = $2} END {print n + 0}' "$out/$1_$top.stat"; }
  row="| $top | $what | $(count ice40 SB_LUT4) | $(count ice40 SB_CARRY) | $(count ecp5 LUT4) | $(count ecp5 CCU2C) | $(count ecp5 MULT18X18D) |"
  echo "$row" >> "$out/decoders.md"
  echo "synth: decoder $row"
done
