#!/usr/bin/env bash
# eval_before_after.sh BEFORE AFTER [PAIRS] [SOURCE] [ROUNDS]: `harris-cosim eval` of KITTI 01
# (stereo pairs 0:PAIRS, default all) with the same source (default cycle) by two builds,
# run back to back and alternated ROUNDS times (default 2) in this one run, so both see the
# same machine. Prints each run's wall time and peak resident memory (/usr/bin/time -v),
# the ratio of the median wall times (BEFORE / AFTER: above 1 means AFTER is faster), and
# whether the reports are byte-identical (summary.md's and totals.json's timing lines aside).
# Data: $HARRIS_COSIM_DATA/kitti, else ../shared/data/kitti next to the source tree.
set -euo pipefail
before=$1; after=$2; pairs=${3:-}; source=${4:-cycle}; rounds=${5:-2}
here=$(cd "$(dirname "$0")/.." && pwd)
kitti=${HARRIS_COSIM_DATA:-$here/../shared/data}/kitti
[ -d "$kitti/sequences/01" ] || { echo "no KITTI sequence 01 under $kitti"; exit 77; }
d=$(mktemp -d); trap 'rm -rf "$d"' EXIT
frames=(); [ -n "$pairs" ] && frames=(--pairs "0:$pairs")
run() {   # NAME BINARY ROUND
  /usr/bin/time -v -o "$d/$1-$3.time" "$2" eval --kitti "$kitti" --sequence 01 --source "$source" \
    "${frames[@]}" --out "$d/out" 2> "$d/$1-$3.log" || { echo "$1 failed:"; tail -5 "$d/$1-$3.log"; exit 1; }
  rm -rf "$d/$1"; mv "$d/out" "$d/$1"   # one --out for both: the command line in the report is the same
  local wall rss
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n=split($2,t,":"); s=0; for(i=1;i<=n;i++) s=s*60+t[i]; print s}' "$d/$1-$3.time")
  rss=$(awk -F': ' '/Maximum resident set size/ {printf "%.0f", $2/1024}' "$d/$1-$3.time")
  cpu=$(awk -F': ' '/User time|System time/ {s+=$2} END {print s}' "$d/$1-$3.time")
  sys=$(awk -F': ' '/System time/ {print $2}' "$d/$1-$3.time")
  echo "$wall" >> "$d/$1.walls"
  echo "$cpu" >> "$d/$1.cpus"
  printf '%-7s round %d: %8.1f s wall, %6.2f s CPU (%5.2f s system), peak %5d MB\n' "$1" "$3" "$wall" "$cpu" "$sys" "$rss"
}
for r in $(seq 1 "$rounds"); do run before "$before" "$r"; run after "$after" "$r"; done
median() { sort -n "$1" | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
mb=$(median "$d/before.walls"); ma=$(median "$d/after.walls")
awk -v b="$mb" -v a="$ma" 'BEGIN {printf "median wall: before %.1f s, after %.1f s, ratio before/after %.2f\n", b, a, b/a}'
cb=$(median "$d/before.cpus"); ca=$(median "$d/after.cpus")
awk -v b="$cb" -v a="$ca" 'BEGIN {printf "median CPU (user + system): before %.2f s, after %.2f s, ratio before/after %.2f\n", b, a, b/a}'
same=yes
for f in frames.csv sequences.csv totals.json summary.md; do
  [ -e "$d/before/$f" ] || [ -e "$d/after/$f" ] || continue
  # timings: summary.md's Time line, totals.json's "seconds" object
  strip() { sed -e '/^Time: source/d' "$1" | python3 -c 'import json,sys
t=sys.stdin.read()
try:
  j=json.loads(t); j.pop("seconds",None); print(json.dumps(j,sort_keys=True))
except ValueError: sys.stdout.write(t)'; }
  if ! cmp -s <(strip "$d/before/$f") <(strip "$d/after/$f"); then echo "$f differs"; same=no; fi
done
echo "reports identical (timings aside): $same"
[ "$same" = yes ]
