#!/usr/bin/env bash
# resume_damaged.sh HARRIS_COSIM WORKDIR: a sharded SLAM Monte-Carlo (6 seeds, 3 shards)
# whose result files are then damaged from outside: shard 1's truncated to half its bytes,
# shard 2's with a number of its data changed and its digest left. The merge refuses
# (status 2, naming shard 1's result as damaged), `shard status` lists both as damaged, and
# `--resume` sets both aside (kept as NNNNN.json.damaged-1 with their bytes, named in the
# command's log and the shard's log),
# runs those two shards only, and the reports equal the single-process run's byte for byte.
set -euo pipefail
bin=$1; work=$2
rm -rf "$work"; mkdir -p "$work"; cd "$work"
fail() { echo "FAIL: $*"; exit 1; }
flags=(slam --simulate --runs 6 --steps 80 --seed 7)
reports=(nees.csv states.csv summary.json report.md)

"$bin" "${flags[@]}" --out out > single.log 2>&1 || { tail -20 single.log; fail "single-process run failed"; }
mv out single
"$bin" "${flags[@]}" --out out --shards 3 --runner local --jobs 2 --run-dir run > first.log 2>&1 ||
  { tail -20 first.log; fail "sharded run failed"; }
rm -rf out

s1=run/shards/00001.json; s2=run/shards/00002.json
head -c $(($(stat -c %s "$s1") / 2)) "$s1" > cut && mv cut "$s1"
jq '(first(paths(numbers) | select(.[0] == "data"))) as $p | setpath($p; getpath($p) + 1)' "$s2" > edited
cmp -s edited "$s2" && fail "the edit changed nothing"
[ "$(jq -r .digest edited)" = "$(jq -r .digest "$s2")" ] || fail "the edit changed the digest"
mv edited "$s2"
cp "$s1" damaged1; cp "$s2" damaged2
before0=$(stat -c '%Y.%y' run/shards/00000.json)

set +e
"$bin" shard merge run > merge.log 2>&1; rc=$?
set -e
[ $rc -eq 2 ] || fail "the merge of damaged results ended with status $rc, expected 2"
grep -q "00001.json' is damaged" merge.log || fail "the merge did not name shard 1's result as damaged: $(cat merge.log)"

"$bin" shard status run > status.log 2>&1 || fail "shard status failed: $(cat status.log)"
grep -q "damaged 1: .*does not parse" status.log || fail "shard status does not list shard 1 as damaged: $(cat status.log)"
grep -q "damaged 2: .*does not match its digest" status.log || fail "shard status does not list shard 2 as damaged: $(cat status.log)"

"$bin" "${flags[@]}" --out out --shards 3 --runner local --jobs 2 --run-dir run --resume > resume.log 2>&1 ||
  { tail -20 resume.log; fail "--resume failed"; }
for i in 1 2; do
  kept=run/shards/0000$i.json.damaged-1
  [ -e "$kept" ] || fail "shard $i's damaged result was not kept as $kept"
  cmp "$kept" damaged$i || fail "$kept does not hold the damaged bytes"
  grep -q "shard $i: its result was damaged.*kept as .*0000$i.json.damaged-1" resume.log || fail "resume.log does not name shard $i's damaged result"
  grep -q "damaged-1" run/logs/0000$i.log || fail "shard $i's log does not name its damaged result"
done
grep -q "does not parse" resume.log || fail "resume.log does not say shard 1's result did not parse"
grep -q "does not match its digest" resume.log || fail "resume.log does not say shard 2's content did not match its digest"
[ "$(stat -c '%Y.%y' run/shards/00000.json)" = "$before0" ] || fail "--resume recomputed shard 0, which had an intact result"
grep -q '^\[shards\] 3/3 done' resume.log || fail "the resumed run did not report 3/3 shards done"
for f in "${reports[@]}"; do cmp single/$f out/$f || fail "$f differs from the single-process run"; done
echo "PASS: a truncated and a digest-mismatched result set aside and kept, their shards rerun, ${reports[*]} identical to one process's"
