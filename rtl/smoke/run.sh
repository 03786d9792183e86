#!/usr/bin/env bash
# Builds and runs the tex_unit smoke test for a few configurations (not part of `make test`).
# Usage: rtl/smoke/run.sh [BUILD_DIR] [SEED]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build-rtl}/smoke
seed=${2:-1}
for cfg in "4 4 8" "6 3 8" "3 5 16" "0 2 4"; do
  set -- $cfg
  dir="$build/w$1_h$2_c$3"
  mkdir -p "$dir"
  verilator --cc --exe --build -j 2 -Wno-fatal --assert -Irtl -Imodel \
    -GMAX_LOG2_W=$1 -GMAX_LOG2_H=$2 -GCW=$3 -CFLAGS "-std=c++20 -O1 -DMAXW=$1 -DMAXH=$2 -DCWBITS=$3 -I$PWD/model" \
    -Mdir "$dir" --top-module tex_unit -f rtl/tex_files.f "$PWD/rtl/smoke/smoke.cpp" -o smoke >/dev/null
  "$dir/smoke" "$seed"
done
