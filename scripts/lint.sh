#!/usr/bin/env bash
# Verilator -Wall lint of tex_unit in several configurations; any warning fails. Then the
# parameter checks: each out-of-range parameter must stop Verilator with tex_unit's message.
# The same for tex_unit_cached, the blocks on their own, the AXI4-Lite slave and tex_unit_axi: four
# groups of Verilator runs at once. Waivers live only in rtl/tex_unit.vlt. Usage: scripts/lint.sh
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
cd "$(dirname "$0")/.."
# clean WHAT CMD...: the Verilator run CMD must pass and print nothing; else its output and
# "lint: FAILED for WHAT", and the group stops.
clean() {
  local what=$1 out
  shift
  if ! out=$("$@" 2>&1) || [ -n "$out" ]; then
    echo "$out" >&2
    echo "lint: FAILED for $what" >&2
    exit 1
  fi
}
# fires PATTERN WHAT CMD...: the run CMD must fail with a message matching PATTERN (a parameter
# check's); else its output and one line naming WHAT.
fires() {
  local pattern=$1 what=$2 out
  shift 2
  if out=$("$@" 2>&1) || ! grep -q "$pattern" <<< "$out"; then
    echo "$out" >&2
    echo "lint: $what: the parameter check did not fire (or not with its message)" >&2
    exit 1
  fi
}
lint() { verilator --lint-only -Irtl -Wall rtl/tex_unit.vlt -f rtl/tex_files.f --top-module tex_unit "$@" 2>&1; }
lint_cached() { verilator --lint-only -Irtl -Wall rtl/tex_unit.vlt -f rtl/tex_files.f --top-module tex_unit_cached "$@" 2>&1; }
cached=("-GMAX_LOG2_W=6 -GMAX_LOG2_H=3" "-GCW=16 -GMAX_LOG2_W=5 -GMAX_LOG2_H=4 -GBLOCK_W=2 -GMEM_W=64 -GBLOCK_FORMATS=0"
        "-GMAX_LOG2_W=0 -GMAX_LOG2_H=0" "-GBLOCK_W=8 -GBLOCK_H=2 -GMAX_WAYS=1 -GLINES=16 -GFILL_DEPTH=1"
        "-GMAX_LOG2_W=13 -GMAX_LOG2_H=13 -GLINES=1024 -GFIFO_DEPTH=1024 -GMEM_W=256 -GAXI_ID_W=4"
        "-GBLOCK_W=8 -GBLOCK_H=8 -GMEM_W=256" "-GBLOCK_W=2 -GBLOCK_H=4 -GBLOCK_FORMATS=0"
        "-GMAX_LOG2_W=13 -GMAX_LOG2_H=0 -GCW=16 -GTEXTURES=1 -GSAMPLERS=1 -GBLOCK_FORMATS=0" "-GTEXTURES=2 -GSAMPLERS=4"
        "-GMAX_LOG2_W=6 -GMAX_LOG2_H=3 -GCW=16 -GSRGB=1" "-GCW=16 -GSRGB=1 -GBLOCK_FORMATS=0" "-GCUBE_MAPS=0"
        "-GCW=16 -GMAX_LOG2_W=5 -GMAX_LOG2_H=4 -GBLOCK_W=2 -GMEM_W=64 -GBLOCK_FORMATS=0 -GCUBE_MAPS=0")
bad_cached=("MAX_LOG2_W=14" "BLOCK_W=3" "BLOCK_H=16" "MAX_WAYS=3" "LINES=24" "FIFO_DEPTH=3" "MISS_DEPTH=8" "MEM_W=1024" "MEM_W=16" "AXI_ID_W=0"
            "TEXTURES=3" "TEXTURES=32" "SAMPLERS=0" "SAMPLERS=12" "SAMPLERS=32" "BLOCK_FORMATS=2" "CW=16" "SRGB=2" "SRGB=1" "CUBE_MAPS=2")

# tex_unit: six configurations, then out-of-range parameters (lint must fail, naming the parameter).
lint_unit() {
  configs=("4 4 8" "6 3 8" "10 10 8" "0 0 8" "11 2 16" "3 7 1")  # MAX_LOG2_W MAX_LOG2_H CW
  for cfg in "${configs[@]}"; do
    set -- $cfg
    clean "MAX_LOG2_W=$1 MAX_LOG2_H=$2 CW=$3" lint -GMAX_LOG2_W="$1" -GMAX_LOG2_H="$2" -GCW="$3"
  done
  # Out-of-range parameters: lint must fail, naming the parameter.
  bad=("MAX_LOG2_W=12" "MAX_LOG2_H=-1" "CW=0" "CW=17" "TAG_W=0")
  for p in "${bad[@]}"; do fires "tex_unit: parameter ${p%%=*} must" "tex_unit $p" lint -G"$p"; done
  echo "lint: verilator -Wall clean for ${#configs[@]} configurations (MAX_LOG2_W MAX_LOG2_H CW: ${configs[*]/%/;});" \
       "parameter checks fire for ${bad[*]}"
}

# tex_unit_cached (docs/memory.md): cache, block, FIFO and beat parameters.
lint_cached_configs() {
  for cfg in "${cached[@]}"; do clean "tex_unit_cached $cfg" lint_cached $cfg; done
  echo "lint: verilator -Wall clean for ${#cached[@]} tex_unit_cached configurations"
}

# tex_unit_cached's parameter checks.
lint_cached_checks() {
  for p in "${bad_cached[@]}"; do
    name=${p%%=*}
    [ "$p" = CW=16 ] && name=BLOCK_FORMATS  # the decoders take 8-bit memory channels (CW 8, or SRGB)
    fires "tex_unit_cached: parameter $name must" "tex_unit_cached $p" lint_cached -G"$p"
  done
  echo "lint: tex_unit_cached's parameter checks fire for ${bad_cached[*]}"
}

# The blocks on their own, the AXI4-Lite slave and the AXI top.
lint_blocks() {
  # The LOD unit on its own (its own test bench; in the units it sits inside tex_probe); alone it uses
  # few of tex_pkg's constants.
  clean tex_lambda verilator --lint-only -Irtl -Wall -Wno-UNUSEDPARAM rtl/tex_unit.vlt rtl/tex_pkg.sv rtl/tex_lambda.sv \
    --top-module tex_lambda
  clean tex_cube verilator --lint-only -Irtl -Wall -Wno-UNUSEDPARAM rtl/tex_unit.vlt rtl/tex_pkg.sv rtl/tex_cube_face.sv \
    rtl/tex_cube.sv --top-module tex_cube
  clean tex_cube_seam verilator --lint-only -Irtl -Wall -Wno-UNUSEDPARAM rtl/tex_unit.vlt rtl/tex_pkg.sv \
    rtl/tex_delay.sv rtl/tex_cube_face.sv rtl/tex_cube_seam.sv --top-module tex_cube_seam
  echo "lint: verilator -Wall clean for tex_lambda, tex_cube and tex_cube_seam"
  # The block decoders and the sRGB table on their own, through their harnesses (tex_unit_cached's
  # taps call them; linted there too).
  lint_decode() { verilator --lint-only -Irtl -Wall -Wno-UNUSEDPARAM rtl/tex_unit.vlt rtl/tex_pkg.sv rtl/tex_bc_colour.sv \
                    rtl/tex_bc_channel.sv rtl/tex_bc7.sv rtl/tex_etc2.sv rtl/tex_astc.sv rtl/tex_bc_decode.sv rtl/synth/tex_bc_decode_top.sv \
                    --top-module tex_bc_decode_top "$@"; }
  clean tex_bc_decode lint_decode
  clean "tex_bc_decode (-DSYNTHESIS: the synthesis form)" lint_decode -DSYNTHESIS
  fires "tex_bc_decode_top: parameter FORMAT must be" "tex_bc_decode_top FORMAT=32" lint_decode -GFORMAT=32
  clean tex_srgb_decode verilator --lint-only -Irtl -Wall rtl/tex_srgb_decode.sv rtl/synth/tex_srgb_decode_top.sv \
    --top-module tex_srgb_decode_top
  clean tex_etc2 verilator --lint-only -Irtl -Wall rtl/tex_unit.vlt rtl/tex_etc2.sv rtl/synth/tex_etc2_top.sv \
    --top-module tex_etc2_top
  clean tex_eac verilator --lint-only -Irtl -Wall rtl/tex_unit.vlt rtl/tex_etc2.sv rtl/synth/tex_eac_top.sv \
    --top-module tex_eac_top
  clean tex_astc verilator --lint-only -Irtl -Wall rtl/tex_unit.vlt rtl/tex_astc.sv rtl/synth/tex_astc_top.sv \
    --top-module tex_astc_top
  echo "lint: verilator -Wall clean for tex_bc_decode (BC1-BC5, BC7, ETC2, EAC, ASTC; as simulated and with -DSYNTHESIS), tex_etc2, tex_eac_top and tex_astc alone and tex_srgb_decode; FORMAT check fires for FORMAT=32"
  # The AXI4-Lite configuration slave on its own (-Wno-UNUSEDPARAM: alone it uses few of tex_pkg's
  # constants; inside tex_unit_axi below it is linted with all warnings), and the AXI top.
  lint_axil() { verilator --lint-only -Irtl -Wall -Wno-UNUSEDPARAM rtl/tex_unit.vlt rtl/tex_pkg.sv rtl/tex_axil_config.sv \
                  --top-module tex_axil_config "$@" 2>&1; }
  axil=("" "-GADDR_W=8 -GTEXTURES=1 -GSAMPLERS=1 -GMAX_WAYS=1 -GLINES=16 -GFIFO_DEPTH=2 -GBEAT_BYTES=1 -GLINE_BYTES=1"
        "-GADDR_W=32 -GFIFO_DEPTH=1024 -GBEAT_BYTES=64 -GSRGB=1 -GBLOCK_FORMATS=0 -GMAX_LOG2_W=13 -GMAX_LOG2_H=0")
  for cfg in "${axil[@]}"; do clean "tex_axil_config ${cfg:-(defaults)}" lint_axil $cfg; done
  bad_axil=("ADDR_W=7" "ADDR_W=33" "MAX_LOG2_W=14" "MAX_LOG2_H=-1" "LINES=24" "MAX_WAYS=3" "FIFO_DEPTH=3" "TEXTURES=3"
            "SAMPLERS=5" "BLOCK_FORMATS=2" "SRGB=2" "LINE_BYTES=48" "BEAT_BYTES=128")
  for p in "${bad_axil[@]}"; do fires "tex_axil_config: parameter ${p%%=*} must" "tex_axil_config $p" lint_axil -G"$p"; done
  lint_top() { verilator --lint-only -Irtl -Wall rtl/tex_unit.vlt -f rtl/tex_files.f --top-module tex_unit_axi "$@" 2>&1; }
  top=("" "-GCW=16 -GSRGB=1 -GMEM_W=32 -GAXI_ID_W=4 -GADDR_W=8 -GTEXTURES=2 -GMAX_LOG2_W=6 -GMAX_LOG2_H=3"
       "-GBLOCK_W=2 -GBLOCK_H=4 -GBLOCK_FORMATS=0 -GMEM_W=256 -GADDR_W=32 -GLINES=16 -GMAX_WAYS=1")
  for cfg in "${top[@]}"; do clean "tex_unit_axi ${cfg:-(defaults)}" lint_top $cfg; done
  # Its parameters reach both parts: each part's check fires.
  for p in "ADDR_W=7:tex_axil_config" "MEM_W=16:tex_unit_cached"; do
    fires "${p#*:}: parameter ${p%%=*} " "tex_unit_axi ${p%%:*} (${p#*:})" lint_top -G"${p%%:*}"
  done
  echo "lint: verilator -Wall clean for ${#axil[@]} tex_axil_config and ${#top[@]} tex_unit_axi configurations;" \
       "parameter checks fire for ${bad_axil[*]} (tex_axil_config), ADDR_W=7 and MEM_W=16 (tex_unit_axi)"
}

# The four groups at once (each Verilator run is one process on one core: about 35 s on 2 cores
# instead of 65 one after another); their lines in order, a failing group's on stderr.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
groups=(lint_unit lint_cached_configs lint_cached_checks lint_blocks)
pids=()
for g in "${groups[@]}"; do
  ("$g") > "$work/$g" 2>&1 &
  pids+=($!)
done
failed=0
for i in "${!groups[@]}"; do
  if wait "${pids[$i]}"; then cat "$work/${groups[$i]}"; else cat "$work/${groups[$i]}" >&2; failed=1; fi
done
exit $failed
