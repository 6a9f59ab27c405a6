#!/usr/bin/env bash
# eval_resume_after_kill.sh HARRIS_COSIM EVAL_JOBS_TESTS: a sharded `eval --source cycle`
# (4 shards of 16 stereo pairs within one stand-in sequence, one at a time, no retries), whose shard 1 is
# killed with SIGKILL while it computes. The run fails (status 3) leaving no result for
# that shard; `--resume` runs only that shard (the others' results stay untouched) and the
# report data equal the single-process run's byte for byte: nothing lost, nothing twice.
set -uo pipefail
hc=$1; gen=$2
d=$(mktemp -d); trap 'rm -rf "$d"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
"$gen" --make-standin "$d/kitti" 04 640x360 64 || fail "cannot write the stand-in sequence"
flags=(eval --source cycle --kitti "$d/kitti" --sequences 04 --out "$d/out")

"$hc" "${flags[@]}" --runner local --jobs 1 --retries 0 --shards 4 --run-dir "$d/run" > "$d/first.log" 2>&1 &
coord=$!
pid=
for _ in $(seq 1 1200); do
  # one shard at a time: shard 1 is the coordinator's only child once its log exists (a
  # forked copy of the coordinator or a started `shard run` worker)
  [ -e "$d/run/logs/00001.log" ] && pid=$(pgrep -P "$coord" | head -1)
  [ -n "$pid" ] && break
  sleep 0.1
done
[ -n "$pid" ] || { kill "$coord" 2>/dev/null; fail "shard 1 never started"; }
sleep 0.2
[ -e "$d/run/shards/00001.json" ] && fail "shard 1 finished within 0.2 s of its start: nothing left to kill"
kill -KILL "$pid"
echo "killed shard 1 (pid $pid) mid-run"
wait "$coord"; rc=$?
[ $rc -eq 3 ] || fail "the interrupted run ended with status $rc, expected 3"
[ -e "$d/run/shards/00001.json" ] && fail "the killed shard left a result"
ls "$d/run/shards" | grep -v '^0000[0-3]\.json$' && fail "the killed shard left a partial file"
before=$(stat -c '%n %Y.%y' "$d/run/shards"/0000[023].json)

"$hc" "${flags[@]}" --runner local --jobs 1 --retries 0 --shards 4 --run-dir "$d/run" --resume > "$d/resume.log" 2>&1 ||
  fail "--resume failed: $(tail -5 "$d/resume.log")"
after=$(stat -c '%n %Y.%y' "$d/run/shards"/0000[023].json)
[ "$before" = "$after" ] || fail "--resume recomputed shards that had a result"
[ "$(ls "$d/run/shards" | wc -l)" -eq 4 ] || fail "expected 4 shard results after --resume"
cp -r "$d/out" "$d/sharded"

"$hc" "${flags[@]}" > "$d/single.log" 2>&1 || fail "single-process run failed"
for f in frames.csv sequences.csv totals.json; do
  [ -e "$d/sharded/$f" ] || [ "$f" = sequences.csv ] || fail "no $f"
  [ -e "$d/sharded/$f" ] && { cmp "$d/sharded/$f" "$d/out/$f" || fail "$f differs from the single-process run"; }
done
echo "PASS: resumed run equals the single-process run"
