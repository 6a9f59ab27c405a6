#!/usr/bin/env bash
# eval_cli_shards.sh HARRIS_COSIM EVAL_JOBS_TESTS: `eval` (spec, cycle, rtl) and `verilate`
# over two stand-in KITTI sequences, once in one process and once through the local runner
# in shards: the report data (frames.csv, sequences.csv, totals.json; verilate's JSON) must
# be the same byte for byte. A missing sequence is bad input (status 2) naming it.
set -uo pipefail
hc=$1; gen=$2
d=$(mktemp -d); trap 'rm -rf "$d"' EXIT
"$gen" --make-standin "$d/kitti" || { echo "FAIL: cannot write the stand-in sequences"; exit 1; }
fail() { echo "FAIL: $*"; exit 1; }

for src in spec cycle rtl; do
  flags=(eval --source "$src" --kitti "$d/kitti" --sequences 02,03 --out "$d/out")
  [ "$src" = rtl ] && flags+=(--no-ablation)
  "$hc" "${flags[@]}" 2> "$d/single-$src.log" || fail "single-process eval --source $src (see below)"$'\n'"$(tail -5 "$d/single-$src.log")"
  mkdir -p "$d/single-$src"
  cp "$d/out"/{frames.csv,sequences.csv,totals.json} "$d/single-$src/"
  "$hc" "${flags[@]}" --runner local --jobs 2 --shards 5 --run-dir "$d/run-$src" 2> "$d/sharded-$src.log" ||
    fail "sharded eval --source $src"$'\n'"$(tail -5 "$d/sharded-$src.log")"
  for f in frames.csv sequences.csv totals.json; do
    cmp "$d/single-$src/$f" "$d/out/$f" || fail "eval --source $src: $f differs between one process and shards"
  done
  shards=$(ls "$d/run-$src/shards" | wc -l)
  echo "eval --source $src: $shards shards, report data identical to the single-process run"
  [ "$src" = rtl ] && [ "$shards" -ne 2 ] && fail "rtl ran $shards shards, expected one per sequence (2)"
  [ "$src" != rtl ] && [ "$shards" -ne 5 ] && fail "$src ran $shards shards, expected 5"
done

"$hc" verilate --kitti "$d/kitti" --sequences 02,03 --json "$d/v-single.json" 2> "$d/v1.log" || fail "verilate --sequences"
"$hc" verilate --kitti "$d/kitti" --sequences 02,03 --json "$d/v-sharded.json" --runner local --jobs 2 \
  --run-dir "$d/run-verilate" 2> "$d/v2.log" || fail "sharded verilate"
cmp "$d/v-single.json" "$d/v-sharded.json" || fail "verilate: the JSON differs between one process and shards"
echo "verilate: JSON identical to the single-process run"

"$hc" eval --kitti "$d/kitti" --sequences 02,04,07 --out "$d/bad" > "$d/bad.log" 2>&1
rc=$?
[ $rc -eq 2 ] || fail "a missing sequence gave status $rc, expected 2"
grep -q "04, 07" "$d/bad.log" || fail "the message does not name the missing sequences: $(cat "$d/bad.log")"
echo "missing sequences: status 2, named"
echo "PASS"
