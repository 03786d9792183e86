#!/usr/bin/env bash
# X-propagation check of the RTL in 4-state simulation (Icarus Verilog 11). The bench
# tests/xprop/tb_tex_unit.sv starts every unreset register at X, drives every don't-care input to
# X (request pins while req_valid is low, write pins while wr_en is low) and replays the vectors of
# BUILD_DIR/tests/xprop/xprop_vectors (golden model): textures loaded through the write port, all
# filter and wrap pairs, lambda across every level and out of range, input gaps, output stalls,
# resets with requests in flight. It fails if req_ready or rsp_valid is ever X/Z after the first
# reset, if any bit of a valid response is X/Z, or if the responses differ from the model's
# (values, order, missing, extra). Two configurations: MAX_LOG2 3x3 with CW=8, and 4x2 with CW=4
# (the narrow-operand form of tex_lerp).
# Then planted bugs on a copy of the RTL must each fail the bench, with the right kind of error:
# X from an unreset register into the outputs (three mutants: an X/Z error), a lost response (a
# protocol error) and a wrong rounding (a value error).
# Usage: scripts/xprop.sh BUILD_DIR
#   XPROP_VECTORS=FILE  the xprop_vectors binary to use instead of BUILD_DIR/tests/xprop/xprop_vectors
#   XPROP_SEED=N        seed of the vectors (default 1)
#   XPROP_REQUESTS=N    requests of the main configuration (default 20000; the second runs a third)
#   XPROP_MUTANTS=0     skip the planted bugs
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
if [ $# -ne 1 ] && [ -z "${XPROP_VECTORS:-}" ]; then
  echo "usage: scripts/xprop.sh BUILD_DIR (see --help)" >&2
  exit 2
fi
gen=${XPROP_VECTORS:-${1%/}/tests/xprop/xprop_vectors}
gen=$(realpath -m "$gen")
cd "$(dirname "$0")/.."
if [ ! -x "$gen" ]; then
  echo "xprop: $gen not found: build it first (cmake --build BUILD_DIR --target xprop_vectors)" >&2
  exit 2
fi
for tool in iverilog vvp; do
  command -v "$tool" > /dev/null || { echo "xprop: $tool not found (scripts/install-deps.sh)" >&2; exit 2; }
done
seed=${XPROP_SEED:-1}
requests=${XPROP_REQUESTS:-20000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$SECONDS
mapfile -t sources < <(grep -v '^[[:space:]]*\(#\|//\|$\)' rtl/tex_files.f)

# bench VECTORS_DIR LOG SOURCES...: compile and run the bench on the vectors; the verdict line
# ("xprop: PASS ..." or "xprop: FAIL ...") on stdout, the whole output in LOG; succeeds on a clean
# PASS (exit 0, and no ERROR line from the RTL's own assertions).
bench() {
  local vec=$1 log=$2 bin="$work/tb_$RANDOM.vvp"
  shift 2
  local params=()
  while IFS='=' read -r name value; do
    [ -n "$name" ] && params+=("-Ptb_tex_unit.$name=$value")
  done < "$vec/params.txt"
  if ! iverilog -g2012 -I rtl "${params[@]}" -o "$bin" "$@" tests/xprop/tb_tex_unit.sv > "$log.iverilog" 2>&1; then
    cat "$log.iverilog" >&2
    echo "xprop: iverilog failed" >&2
    return 2
  fi
  local rc=0
  vvp -n "$bin" +vectors="$vec" > "$log" 2>&1 || rc=$?
  grep '^xprop: \(PASS\|FAIL\)' "$log" | tail -1 || echo "xprop: FAIL no verdict (vvp exit $rc)"
  [ "$rc" -eq 0 ] && grep -q '^xprop: PASS' "$log" && ! grep -q '^ERROR' "$log"
}

# The unmodified RTL: must pass, in both configurations.
configs=("3 3 8 $requests" "4 2 4 $((requests / 3 > 0 ? requests / 3 : 1))")  # MAX_LOG2_W MAX_LOG2_H CW REQUESTS
i=0
for cfg in "${configs[@]}"; do
  read -r lw lh cw n <<< "$cfg"
  vec="$work/vectors$i"
  "$gen" "$vec" --seed "$seed" --requests "$n" --max-log2-w "$lw" --max-log2-h "$lh" --cw "$cw" > /dev/null
  t0=$SECONDS
  if ! verdict=$(bench "$vec" "$work/rtl$i.log" "${sources[@]}"); then
    grep -m 12 '^\(xprop: error\|ERROR\)' "$work/rtl$i.log" >&2 || true
    echo "$verdict" >&2
    echo "xprop: FAILED on the RTL (MAX_LOG2_W=$lw MAX_LOG2_H=$lh CW=$cw, seed $seed)" >&2
    exit 1
  fi
  echo "xprop: ${lw}x${lh} CW=$cw: ${verdict#xprop: } ($((SECONDS - t0)) s)"
  i=$((i + 1))
done

if [ "${XPROP_MUTANTS:-1}" = 0 ]; then
  echo "xprop: 4-state run clean, seed $seed, planted bugs skipped ($((SECONDS - start)) s)"
  exit 0
fi

# mutant NAME KIND FILE SED_EXPR: FILE changed by SED_EXPR on a copy; the bench (first
# configuration) must fail with at least one error of KIND (X/Z, value or protocol).
mutants=0
mutant() {
  local name=$1 kind=$2 file=$3 expr=$4 dir="$work/mutant$mutants"
  mkdir -p "$dir"
  local copy
  copy="$dir/$(basename "$file")"
  sed "$expr" "$file" > "$copy"
  if cmp -s "$file" "$copy"; then echo "xprop: the planted bug '$expr' does not change $file" >&2; exit 1; fi
  local srcs=() s verdict
  for s in "${sources[@]}"; do
    if [ "$s" = "$file" ]; then srcs+=("$copy"); else srcs+=("$s"); fi
  done
  if verdict=$(bench "$work/vectors0" "$dir/run.log" "${srcs[@]}"); then
    echo "xprop: NOT CAUGHT planted bug: $name ($verdict)" >&2
    exit 1
  fi
  local count
  count=$(grep -oE "(\(|, )$kind [0-9]+" <<< "$verdict" | grep -oE '[0-9]+$' | head -1 || true)
  if [ -z "$count" ] || [ "$count" -eq 0 ]; then
    echo "xprop: planted bug '$name' failed the bench, but without a $kind error: $verdict" >&2
    exit 1
  fi
  echo "xprop: caught  $name: ${verdict#xprop: }"
  mutants=$((mutants + 1))
}
mutant "tex_skid's out_valid without reset (rsp_valid X after reset)" "X/Z" rtl/tex_skid.sv \
  '/out_valid  <= 1.b0;/d'
mutant "pipeline valid bits without reset (X reaches rsp_valid)" "X/Z" rtl/tex_unit.sv \
  's/if (rst) valid <= .0;/if (1'"'"'b0) valid <= '"'"'0;/'
mutant "tex_skid's output register always loads the skid entry (unwritten: X in a valid response)" "X/Z" \
  rtl/tex_skid.sv 's/out_data <= skid_valid ? skid_data : in_data;/out_data <= skid_data;/'
mutant "tex_skid loses the item it should park under a stall (a lost response)" "protocol" rtl/tex_skid.sv \
  "s/skid_valid <= 1'b1;  \/\/ output stalled/skid_valid <= 1'b0;  \/\/ output stalled/"
mutant "tex_accum rounds with the wrong bit (n * 2^22 instead of n * 2^23)" "value" rtl/tex_accum.sv \
  "s/(n) << 23)/(n) << 22)/"
echo "xprop: 4-state runs clean (seed $seed), $mutants planted bugs caught ($((SECONDS - start)) s)"
