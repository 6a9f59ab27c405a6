#!/usr/bin/env bash
# slam_cli_sequence.sh: `harris-cosim slam --sequences 01` writes its report and one pose a
# line in the KITTI and TUM trajectory files. Exits 77 (skipped) without poses/01.txt.
# usage: slam_cli_sequence.sh HARRIS_COSIM DATA_DIR WORK_DIR
set -u
exe=$1
data=${HARRIS_COSIM_DATA:-$2}
out=$3
poses=$data/kitti/poses/01.txt
[ -f "$poses" ] || { echo "SKIPPED: no $poses"; exit 77; }
rm -rf "$out"
"$exe" slam --sequences 01 --kitti "$data/kitti" --out "$out" || exit 1
n=$(wc -l < "$poses")
for f in estimate_kitti.txt dead_reckoning_kitti.txt truth_kitti.txt estimate_tum.txt; do
    lines=$(wc -l < "$out/$f")
    [ "$lines" -eq "$n" ] || { echo "FAIL: $f has $lines lines, poses/01.txt $n"; exit 1; }
done
awk 'NF != 12 { exit 1 }' "$out/estimate_kitti.txt" || { echo "FAIL: a KITTI line without 12 numbers"; exit 1; }
awk 'NF != 8 { exit 1 }' "$out/estimate_tum.txt" || { echo "FAIL: a TUM line without 8 fields"; exit 1; }
grep -q '"ate_m"' "$out/summary.json" && test -s "$out/report.md" && test -s "$out/states.csv"
