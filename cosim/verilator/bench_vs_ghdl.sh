#!/bin/sh
# bench_vs_ghdl.sh BUILD_DIR [GHDL_WRITES] [BACKENDS]: the "Verilator vs GHDL" figures of
# docs/performance.md. Streams the same KITTI 01 stream (left frame of pair 0, 1241x376,
# 806,785 writes) through
#   harris-cosim verilate (one whole frame, reads compared with the model), then
#   harris-cosim rtl --backend B (its first GHDL_WRITES writes; a whole frame would take
#   ~10 minutes per back end),
# one after the other on the same machine, and prints writes/s of each and the ratio.
# Verilator's rate is its own time (verilator_seconds: inside the netlist), the model's
# time reported beside it; GHDL's is the rtl command's wall-clock rate, which also includes
# its model comparison (the GHDL process dominates).
set -e
build=$1 n=${2:-20000} backends=${3:-"mcode gcc"}
exe=$build/tools/harris-cosim
out=$(mktemp -d)
"$exe" verilate --no-gate --pairs 0:1 --frames 1 --json "$out/vl.json" 2>"$out/vl.log"
for b in $backends; do
    "$exe" rtl --backend "$b" --quiet --pairs 0:1 --frames 1 --max-writes "$n" --json "$out/ghdl_$b.json" \
        >"$out/ghdl_$b.log" 2>&1 || { echo "GHDL $b: failed, see $out/ghdl_$b.log"; continue; }
done
python3 - "$out" $backends <<'PY'
import json, sys, os
d = sys.argv[1]
vl = json.load(open(os.path.join(d, "vl.json")))
vr = vl["verilator_writes_per_second"]
print(f"load average: {os.getloadavg()[0]:.2f} (2 cores)")
print(f"Verilator: {vl['writes']} writes, {vl['verilator_seconds']:.3f} s in the netlist "
      f"({vr:,.0f} writes/s), model {vl['model_seconds']:.3f} s, wall {vl['wall_seconds']:.3f} s, "
      f"mismatches {vl['mismatches']['writes']}")
for b in sys.argv[2:]:
    p = os.path.join(d, f"ghdl_{b}.json")
    if not os.path.exists(p):
        continue
    g = json.load(open(p))
    gr = g["writes"] / g["wall_seconds"]
    print(f"GHDL {b}: {g['writes']} writes in {g['wall_seconds']:.3f} s ({gr:,.0f} writes/s); "
          f"frame {806785 / gr:,.0f} s; Verilator/GHDL = {vr / gr:,.0f}x "
          f"(Verilator incl. model {vl['writes'] / vl['wall_seconds'] / gr:,.0f}x)")
PY
rm -rf "$out"
