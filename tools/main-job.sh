#!/usr/bin/env bash
# main-job.sh: installs what is missing, builds what the job runs (target main-job), then runs
# the main job into ./out:
#  1. the co-simulation regression (GHDL, every register after every write, on every back end;
#     the entity benches): ctest -L cosim -LE "slow|mutants";
#  2. the RTL in GHDL on the default dataset: a crop of KITTI sequence 01 when ../shared/data
#     (or $HARRIS_COSIM_DATA) has it, else generated frames;
#  3. the precision/recall report against OpenCV on the same dataset: the spec model with the
#     ablation table, and the RTL itself through its Verilator netlist (trusted after its
#     GHDL/Verilator/model gate), run once over the whole stream in lock step with the cycle
#     model: any read on which they disagree fails the job, and its corners are scored.
# The test programs, fuzzers and benchmarks are built by tools/test-all.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh main-job
cli=build/tools/harris-cosim
mkdir -p out
jobs=$(nproc 2>/dev/null || echo 2)

echo "== 1. co-simulation regression (GHDL vs cycle model) =="
ctest --test-dir build -L cosim -LE "slow|mutants" -j"$jobs" --output-on-failure

data="${HARRIS_COSIM_DATA:-$(cd .. && pwd)/shared/data}"
if [ -d "$data/kitti/sequences/01/image_0" ]; then
  echo "== 2. RTL on KITTI 01 (data: $data) =="
  # GHDL: a 128x64 crop of the first two stereo pairs, every register compared
  "$cli" rtl --data "$data" --pairs 0:2 --size 128x64 --json out/rtl-kitti01-crop.json \
         --vcd out/rtl-mismatch.vcd
  eval_args=(--kitti "$data/kitti" --sequence 01)
else
  echo "== 2. RTL on generated frames (no KITTI data under $data) =="
  "$cli" rtl --pattern blocks --size 128x64 --frames 3 --json out/rtl-blocks.json --vcd out/rtl-mismatch.vcd
  eval_args=()
fi

echo "== 3. precision/recall against OpenCV (thesis Table 5 protocol) =="
"$cli" eval "${eval_args[@]}" --source spec --out out/eval-spec
if "$cli" verilate --help >/dev/null 2>&1; then
  # the hardware's corners: the Verilator netlist, gated against GHDL and the model, in lock
  # step with the cycle model (the first read on which they disagree stops the job with status 1,
  # naming the read)
  "$cli" eval "${eval_args[@]}" --source rtl --no-ablation --out out/eval-rtl
else
  "$cli" eval "${eval_args[@]}" --source cycle --no-ablation --out out/eval-cycle
fi
echo "== done: reports in out/ =="
