#!/usr/bin/env bash
# sharded_equals_single.sh KIND HARRIS_COSIM WORKDIR [RUNNER FLAGS...]
# Runs one command of job kind KIND (slam, mutate, sweep, sweep_rtl, sweep_rtl_no_wait,
# sweep_verilator, landmarks) twice on small inputs:
# in one process, then in shards through the given runner flags (default: --runner local
# --jobs 2), with the same --out (moved aside in between, so that the command quoted in the
# reports is the same), and compares the report data byte for byte; time columns and the
# synthesis cache flag are left out of the comparison. Exit 77 (skipped) without the data.
# HC_SHARD_REFERENCE=write:DIR keeps the single-process run in DIR; HC_SHARD_REFERENCE=read:DIR
# takes it from there instead of running it, when DIR holds the run of the same binary and
# arguments, newer than the binary and rtl/ (else the run is made here, and the log says which);
# every path in the commands below is the same in every work directory, so that a run of
# another test's work directory is this one's.
set -euo pipefail
kind=$1; bin=$2; work=$3; shift 3
runner=("$@"); [ ${#runner[@]} -gt 0 ] || runner=(--runner local --jobs 2)
src=$(cd "$(dirname "$0")/../.." && pwd)   # the repository
rm -rf "$work"; mkdir -p "$work"; cd "$work"
data=${HARRIS_COSIM_DATA:-$src/../shared/data}
need() { [ -e "$1" ] || { echo "skipped: $1 not found (set HARRIS_COSIM_DATA)"; exit 77; }; }
fail() { echo "FAIL: $*"; exit 1; }
same() {   # same FILE-A FILE-B: byte for byte
  cmp "$1" "$2" || { diff "$1" "$2" | head -20; fail "$1 and $2 differ"; }
}
stale() {   # stale DIR KEY: why DIR holds no single-process run of KEY usable now ("" if it does)
  if [ ! -e "$1/done" ]; then echo "none there"
  elif [ "$(cat "$1/args")" != "$2" ]; then echo "made with other arguments"
  elif [ "$bin" -nt "$1/done" ]; then echo "older than $bin"
  elif [ -n "$(find "$src/rtl" -newer "$1/done" -print -quit)" ]; then echo "older than rtl/"
  fi
}
single_run() {   # single_run ARGS...: the single-process run into single/ (HC_SHARD_REFERENCE above)
  local setting=${HC_SHARD_REFERENCE:-} mode ref key why
  mode=${setting%%:*} ref=${setting#*:}
  key=$(printf '%s\n' "$bin" "$@")
  if [ "$mode" = read ]; then
    why=$(stale "$ref" "$key")
    if [ -z "$why" ]; then
      cp -a "$ref/single" single && cp "$ref/single.log" single.log
      echo "single-process run: the one in $ref (same binary and arguments)"
      return
    fi
    echo "single-process run: made here ($ref: $why)"
  fi
  mkdir -p out
  "$bin" "$@" > single.log 2>&1 || { tail -20 single.log; fail "single-process run failed"; }
  mv out single
  if [ "$mode" = write ]; then
    rm -rf "$ref" "$ref.new"; mkdir -p "$ref.new"
    cp -a single single.log "$ref.new/" && printf '%s' "$key" > "$ref.new/args" && touch "$ref.new/done"
    mv "$ref.new" "$ref"
  fi
}
between=:   # a command run between the two runs of both()
both() {   # both ARGS...: the single-process run into single/, the sharded one into sharded/
  single_run "$@"
  $between
  mkdir -p out
  "$bin" "$@" --shards "$shards" "${runner[@]}" > sharded.log 2>&1 || { tail -30 sharded.log; fail "sharded run failed"; }
  mv out sharded
  grep -q "^\[shards\] $shards/$shards done" sharded.log || fail "the sharded run did not report $shards/$shards shards done"
}
shards_done() {   # shards_done RUN_DIR: every shard of the run has a result and the merge job wrote merged.json
  "$bin" shard status "$1" 2>/dev/null | grep -Eq '(^|[ ,])([0-9]+) of \2 shards done' && [ -e "$1/merged.json" ]
}
wait_done() {   # wait_done RUN_DIR: until shards_done (at most 10 minutes)
  for _ in $(seq 1 600); do shards_done "$1" && return 0; sleep 1; done
  fail "the shards of $1 did not finish: $("$bin" shard status "$1" 2>&1 | head -3)"
}
both_no_wait() {   # as both, the sharded run submitted with --no-wait and finished by two --resume
  single_run "$@"
  $between
  mkdir -p out
  local sharded=("$@" --shards "$shards" "${runner[@]}" --no-wait)
  "$bin" "${sharded[@]}" > submit.log 2>&1 || { tail -20 submit.log; fail "the --no-wait submission failed"; }
  [ ! -e out/sweep.csv ] || fail "--no-wait wrote a report before the shards ran"
  wait_done out/run
  "$bin" "${sharded[@]}" --resume > checks.log 2>&1 || { tail -20 checks.log; fail "the first --resume failed"; }
  [ ! -e out/sweep.csv ] || fail "the first --resume wrote a report before the checks ran"
  wait_done out/run/checks
  "$bin" "${sharded[@]}" --resume > sharded.log 2>&1 || { tail -20 sharded.log; fail "the second --resume failed"; }
  [ -e out/sweep.csv ] || fail "the second --resume wrote no report"
  mv out sharded
}
sweep_rtl_inputs() {   # spec.json, streams.txt and the cache of the sweep_rtl kinds
  need "$data/kitti/sequences/01"
  cat > spec.json <<'SPEC'
{"name": "shard-rtl-test", "configs": [{"name": "m6", "m_drop": 6}], "data": {"sequence": "01", "pairs": "0:3"},
 "trust": {"rtl": true, "verilator_pairs": "", "verilator_gate": false}}
SPEC
  printf 'flat 33x21 3 0\nrandom 40x30 3 13\n' > streams.txt
  fresh_trust_cache
}
sweep_cache() {   # sweep_cache: $cache = ./cache, an empty trust cache of this test's own beside the
                 # syntheses, ranges and stage proofs that every sweep kind shares (content-keyed
                 # entries, written atomically, so concurrent tests may fill them)
  local shared=$work/../sweep-shared-cache d
  cache=$work/cache
  mkdir -p "$cache"
  for d in synth ranges stages; do mkdir -p "$shared/$d"; ln -s "$shared/$d" "$cache/$d"; done
}
fresh_trust_cache() {   # fresh_trust_cache: sweep_cache, its trust cache emptied now and between the runs
  sweep_cache
  between="rm -rf $cache/trust"
  $between
}
checks_equal() {   # checks_equal N KIND: N check shards in sharded/run/checks, each a passing,
                  # simulated KIND check, and the sweep reports of both runs the same
  local run=sharded/run/checks
  [ "$(ls "$run"/shards/*.json | wc -l)" -eq "$1" ] || fail "expected the $1 RTL checks as $1 shards in $run"
  jq -e -s --argjson n "$1" --arg k "$2" \
    'map(.data.outcomes[0]) | length == $n and all(.kind == $k and .status == "pass" and (.result.cached | not))' \
    "$run"/shards/*.json > /dev/null || fail "the check shards did not each run a passing $2 check"
  same_sweep_reports
}
same_sweep_reports() {   # sweep.csv, sweep.json without times and cache flags, sweep.md without its timing line
  same single/sweep.csv sharded/sweep.csv
  untimed_json single/sweep.json > single.json
  untimed_json sharded/sweep.json > sharded.json
  same single.json sharded.json
  grep -v '^Timing: ' single/sweep.md > single.md
  grep -v '^Timing: ' sharded/sweep.md > sharded.md
  same single.md sharded.md
}
untimed_json() { jq -S 'del(.. | objects | .seconds?, .synth_seconds?, .eval_seconds?, .overflow_seconds?, .seconds_interval?, .seconds_search?, .seconds_solver?, .solver_seconds?, .cached?, .synthesised?, .synth_cached?, .synth_seconds_sum?)' "$1"; }

case "$kind" in
slam)
  shards=3
  both slam --simulate --runs 6 --steps 80 --seed 7 --out out
  for f in nees.csv states.csv summary.json report.md; do same single/$f sharded/$f; done
  echo "slam: 6 seeds in 3 shards: nees.csv, states.csv, summary.json, report.md identical"
  ;;
mutate)
  # HC_MUTATE_SUBSET=N: the first N mutants of the list; else all
  list=$src/mutation/mutations.json
  if [ -n "${HC_MUTATE_SUBSET:-}" ]; then
    jq --argjson n "$HC_MUTATE_SUBSET" '.mutants |= .[0:$n]' "$list" > subset.json
    list=$PWD/subset.json
  fi
  shards=${HC_MUTATE_SHARDS:-4}
  both mutate --mutations "$list" --report out/campaign.md
  # the baseline's wall time is the report's only timing
  sed -E 's/\(([0-9.]+) s\)/(TIME)/' single/campaign.md > single.md
  sed -E 's/\(([0-9.]+) s\)/(TIME)/' sharded/campaign.md > sharded.md
  same single.md sharded.md
  echo "mutate: $(grep -c '^| M' single.md) mutants in $shards shards: campaign.md identical (baseline time aside)"
  ;;
sweep)
  need "$data/kitti/sequences/01"
  cat > spec.json <<'SPEC'
{"name": "shard-test", "configs": [{"name": "thesis"}, {"name": "m6", "m_drop": 6}, {"name": "b5", "bf_drop": 5},
 {"name": "sobel9", "sobel_w": 9}], "data": {"sequence": "01", "pairs": "0:3"}}
SPEC
  sweep_cache
  shards=3
  both sweep --config spec.json --out out --kitti "$data/kitti" --cache cache --quiet --no-rtl --threads 1
  same_sweep_reports
  echo "sweep: $(($(wc -l < single/sweep.csv) - 1)) configurations in 3 shards: sweep.csv, sweep.json (timings aside), sweep.md (timing line aside) identical"
  ;;
sweep_rtl)
  # the sweep with its RTL checks on the smallest spec: m6 and the thesis configuration,
  # which the spec adds (three syntheses), both on the Pareto front, each checked by GHDL
  # (mcode) on two streams of the regression set. Before each run the trust cache is
  # emptied (the synthesis cache is kept), so that both runs simulate every check, the
  # sharded one each in a shard of its own.
  sweep_rtl_inputs
  shards=1
  both sweep --config spec.json --out out --kitti "$data/kitti" --cache cache --quiet --threads 1 --backend mcode \
    --regression-set streams.txt
  grep -q '^\[shards\] 4/4 done' sharded.log || fail "the sharded run did not report the 4 check shards done"
  for p in m6 thesis; do
    grep -q "^$p,.*,1,2,0,0,,,," single/sweep.csv || fail "$p is not a Pareto point with 2 GHDL runs, 0 failed, 0 mismatches"
  done
  checks_equal 4 ghdl
  echo "sweep_rtl: 2 configurations in 1 shard, then 4 GHDL checks of the 2 Pareto points in 4 shards: sweep.csv, sweep.json (timings aside), sweep.md (timing line aside) identical"
  ;;
sweep_rtl_no_wait)
  # sweep_rtl's command submitted with --no-wait (a Slurm runner): the first command submits
  # the configurations' shards and returns; a --resume after them merges and submits the
  # checks' shards; a second --resume after those renders the report
  sweep_rtl_inputs
  shards=1
  both_no_wait sweep --config spec.json --out out --kitti "$data/kitti" --cache cache --quiet --threads 1 \
    --backend mcode --regression-set streams.txt
  grep -q 'submitted' submit.log || fail "the first command did not say it submitted: $(head -3 submit.log)"
  checks_equal 4 ghdl
  echo "sweep_rtl_no_wait: submitted, then --resume twice: 4 GHDL checks in 4 shards: sweep.csv, sweep.json (timings aside), sweep.md (timing line aside) identical"
  ;;
sweep_verilator)
  # the Verilator run of every Pareto point (m6 and the thesis configuration) on KITTI 01's
  # first stereo pair, each as a check shard of its own; the trust cache emptied before each
  # run, so both runs verilate and run both netlists
  need "$data/kitti/sequences/01"
  cat > spec.json <<'SPEC'
{"name": "shard-verilator-test", "configs": [{"name": "m6", "m_drop": 6}], "data": {"sequence": "01", "pairs": "0:3"},
 "trust": {"rtl": false, "verilator_pairs": "0:1", "verilator_gate": false}}
SPEC
  fresh_trust_cache
  shards=1
  both sweep --config spec.json --out out --kitti "$data/kitti" --cache cache --quiet --threads 1
  grep -q '^\[shards\] 2/2 done' sharded.log || fail "the sharded run did not report the 2 check shards done"
  checks_equal 2 verilator
  echo "sweep_verilator: 2 Pareto points, each netlist run on KITTI 01 pair 0 in a shard of its own: sweep.csv, sweep.json (timings aside), sweep.md (timing line aside) identical"
  ;;
landmarks)
  need "$data/middlebury2006/half/Aloe"
  mkdir scenes
  for s in Aloe Baby1; do ln -s "$data/middlebury2006/half/$s" scenes/$s; done
  shards=6
  both landmarks --compare --middlebury scenes --overlays 0 --out out
  # results.csv without its ms_per_pair column (second to last), results.json without times
  for r in single sharded; do
    awk -F, -v OFS=, '{ $(NF-1) = ""; print }' $r/results.csv > $r-results.csv
    untimed_json $r/results.json > $r-results.json
  done
  same single-results.csv sharded-results.csv
  same single-results.json sharded-results.json
  n=0
  while IFS= read -r f; do same "single/$f" "sharded/$f"; n=$((n + 1)); done < <(cd single && find . -path '*/landmarks/*' -type f | sort)
  [ "$n" -gt 0 ] || fail "no landmark files were written"
  echo "landmarks: 2 scenes x 3 detectors x 8 descriptor rows in $shards shards: results.csv, results.json (times aside) and $n landmark files identical"
  ;;
*) echo "unknown kind $kind"; exit 2 ;;
esac
