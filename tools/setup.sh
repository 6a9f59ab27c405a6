#!/usr/bin/env bash
# setup.sh: installs the Debian packages harris-cosim needs (only the missing ones), then
# configures and builds the project in ./build. Safe to run again.
#   bash tools/setup.sh              everything (libraries, command line, simulators, tests,
#                                    fuzzers, benchmarks)
#   bash tools/setup.sh TARGET...    only those targets and what they need (the main job
#                                    builds `main-job`: the command line and the simulators and
#                                    tests of its co-simulation regression)
set -euo pipefail
cd "$(dirname "$0")/.."

PKGS=(cmake g++ make pkg-config
      ghdl ghdl-gcc ghdl-llvm ghdl-mcode verilator yosys z3 cvc5
      catch2 librapidcheck-dev libbenchmark-dev
      libopencv-dev opencv-doc libcli11-dev nlohmann-json3-dev libfmt-dev libtbb-dev libeigen3-dev
      gnuplot-nox graphviz slurm-wlm munge gcovr jq clang libclang-rt-14-dev)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "[setup] installing: ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
if (($#)); then
  cmake --build build -j"$jobs" --target "$@"
else
  cmake --build build -j"$jobs"
fi
