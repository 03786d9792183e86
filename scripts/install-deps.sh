#!/usr/bin/env bash
# Installs the Debian bookworm packages the project needs, if any are missing.
# Called by the Makefile before every build; quiet and quick when all are present.
set -euo pipefail
case "${1:-}" in -h|--help) sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
packages=(
  cmake g++ make pkg-config
  libgtest-dev libbenchmark-dev          # tests and benchmarks
  libopenimageio-dev openimageio-tools   # images in and out; maketx for the pyramid check
  libpng-dev libjpeg62-turbo-dev         # PNG and JPEG without loading OpenImageIO (fast start)
  libcli11-dev nlohmann-json3-dev libfmt-dev
  libassimp-dev libglm-dev assimp-testmodels  # 3D models (render --model), vector math, the test models
  libsquish-dev                          # BC1-BC5 encoder (--format) and reference decoder (tests)
  libastcenc-dev                         # ASTC encoder (--format astc*) and reference decoder (tests)
  libosmesa6-dev libglu1-mesa-dev        # OpenGL (Mesa) as the reference of real frames (tests)
  verilator zlib1g-dev                   # RTL simulation (FST traces need zlib)
  libsystemc-dev                         # SystemC/TLM-2.0 wrapper
  yosys nextpnr-ice40 fpga-icestorm      # synthesis and place-and-route
  z3                                     # yosys-smtbmc's solver (make formal)
  iverilog                               # 4-state simulation (make xprop)
  valgrind                               # instructions per clock (make bench-ir)
  time                                   # GNU time: peak memory of each run (make hostile-models)
  parallel                               # GNU parallel: emitted sweeps (texsim explore --emit parallel; tested)
  clang libclang-rt-14-dev               # libFuzzer, ASan and UBSan (make fuzz)
  python3 python3-matplotlib python3-numpy  # reports and plots (/usr/bin/python3)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: error: not root; run: sudo apt-get install ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
