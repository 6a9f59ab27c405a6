#!/usr/bin/env bash
# eval_slurm_no_wait.sh HARRIS_COSIM EVAL_JOBS_TESTS (run under slurm-local.sh run): `eval
# --runner slurm --no-wait` submits the shards and the merge job and returns without a
# report; once the jobs are done, the same command with --resume renders the report from the
# merged results, equal byte for byte to the single-process run, without submitting again.
set -uo pipefail
hc=$1; gen=$2
d=$(mktemp -d); trap 'rm -rf "$d"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$gen" --make-standin "$d/kitti" || fail "cannot write the stand-in sequences"

flags=(eval --source spec --kitti "$d/kitti" --sequences 02,03 --out "$d/out")
"$hc" "${flags[@]}" 2> "$d/single.log" || fail "single-process eval"$'\n'"$(tail -5 "$d/single.log")"
mv "$d/out" "$d/single"

sharded=("${flags[@]}" --runner slurm --shards 3 --run-dir "$d/run")
"$hc" "${sharded[@]}" --no-wait > "$d/submit.log" 2>&1 || fail "eval --no-wait"$'\n'"$(tail -5 "$d/submit.log")"
grep -q "submitted 3 shard(s)" "$d/submit.log" || fail "no submission message: $(cat "$d/submit.log")"
[ ! -e "$d/out/frames.csv" ] || fail "--no-wait wrote a report before the shards ran"
echo "submitted: $(head -1 "$d/submit.log")"

for _ in $(seq 1 300); do
  "$hc" shard status "$d/run" | grep -q "3 of 3 shards done" && [ -e "$d/run/merged.json" ] && break
  sleep 1
done
"$hc" shard status "$d/run" | grep -q "3 of 3 shards done" || fail "the shards did not finish: $("$hc" shard status "$d/run")"
[ -e "$d/run/merged.json" ] || fail "the merge job wrote no merged.json"
jobs_before=$(ls "$d/run/slurm" | grep -c '^jobs-')

"$hc" "${sharded[@]}" --no-wait --resume > "$d/render.log" 2>&1 || fail "eval --resume"$'\n'"$(tail -5 "$d/render.log")"
[ "$(ls "$d/run/slurm" | grep -c '^jobs-')" -eq "$jobs_before" ] || fail "--resume submitted jobs again"
for f in frames.csv sequences.csv totals.json; do
  cmp "$d/single/$f" "$d/out/$f" || fail "$f differs between one process and the Slurm run"
done
echo "PASS: --no-wait returned at once; --resume rendered the report, equal to the single-process run"
