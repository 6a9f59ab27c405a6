#!/bin/sh
# eval's rtl source (the Verilator netlist, after its gate) and cycle source (the cycle
# model) must classify every pixel identically: equal TP, FP and FN on KITTI 01 pairs 0-2.
#   rtl_equals_cycle.sh HARRIS_COSIM DATA_DIR
set -u
cli="$1"; data="${HARRIS_COSIM_DATA:-$2}"
if [ ! -d "$data/kitti/sequences/01/image_0" ]; then
  echo "SKIP: KITTI sequence 01 not found under '$data' (set HARRIS_COSIM_DATA)"; exit 77
fi
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
counts() { sed -n 's/.*(TP \([0-9]*\) FP \([0-9]*\) FN \([0-9]*\)).*/TP \1 FP \2 FN \3/p' "$1" | tail -1; }
for src in cycle rtl; do
  "$cli" eval --data "$data" --source $src --pairs 0:3 --no-ablation --out "$out/$src" > "$out/$src.log" 2>&1 || {
    cat "$out/$src.log"; echo "FAIL: eval --source $src exited non-zero"; exit 1; }
done
c=$(counts "$out/cycle.log"); r=$(counts "$out/rtl.log")
echo "cycle: $c"; echo "rtl:   $r"
[ -n "$c" ] && [ "$c" = "$r" ] && { echo "PASS: identical counts"; exit 0; }
echo "FAIL: the rtl and cycle sources differ"; exit 1
