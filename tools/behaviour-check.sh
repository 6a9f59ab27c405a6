#!/usr/bin/env bash
# behaviour-check.sh: a fixed set of commands whose CSV and JSON outputs show the project's
# behaviour, with a digest of each output (timing fields and columns removed), so that two
# builds can be compared byte for byte: run it with the build before a change and with the
# build after it, then `diff BEFORE/digests.txt AFTER/digests.txt` (empty: same behaviour).
#   bash tools/behaviour-check.sh [--cli PATH] [--data DIR] OUT_DIR
#   bash tools/behaviour-check.sh --digest OUT_DIR    (the digests of an earlier run again)
# The commands (KITTI 01 and Middlebury from the data directory; about 15 minutes on an idle
# 2-core machine): eval --source spec (with the ablation), cycle and rtl on KITTI 01;
# landmarks --compare; slam --sequences 01 with stereo landmarks; a sweep of three
# configurations (tools/behaviour-sweep.json, RTL checks included); mutate (the hand-written
# smoke list); golden --check. Each command's exit status is recorded beside the digests.
set -uo pipefail
cd "$(dirname "$0")/.."
cli=build/tools/harris-cosim
data="${HARRIS_COSIM_DATA:-$(cd .. && pwd)/shared/data}"
digest_only=0
while (($#)); do
  case "$1" in
    --cli) cli="$2"; shift 2 ;;
    --digest) digest_only=1; shift ;;
    --data) data="$2"; shift 2 ;;
    -h|--help) sed -n '2,13p' "$0"; exit 0 ;;
    -*) echo "behaviour-check: unknown flag $1" >&2; exit 2 ;;
    *) break ;;
  esac
done
if (($# != 1)); then echo "usage: bash tools/behaviour-check.sh [--cli PATH] [--data DIR] OUT_DIR" >&2; exit 2; fi
out="$1"
status="$out/status.txt"
if ((digest_only == 0)); then
[ -x "$cli" ] || { echo "behaviour-check: no executable $cli (build first, or give --cli)" >&2; exit 2; }
[ -d "$data/kitti/sequences/01" ] || { echo "behaviour-check: no KITTI 01 under $data (give --data)" >&2; exit 2; }
command -v jq >/dev/null || { echo "behaviour-check: needs jq" >&2; exit 2; }
if [ -e "$out" ]; then echo "behaviour-check: $out exists; give a new directory" >&2; exit 2; fi
mkdir -p "$out"
: > "$status"

run() {   # run NAME COMMAND...: the command's output in $out/NAME.log, its status in status.txt
  local name="$1"; shift
  echo "behaviour-check: $name" >&2
  "$@" > "$out/$name.log" 2>&1
  echo "$name $?" >> "$status"
}

kitti="$data/kitti"
run eval-spec "$cli" eval --kitti "$kitti" --sequence 01 --source spec --out "$out/eval-spec"
run eval-cycle "$cli" eval --kitti "$kitti" --sequence 01 --source cycle --no-ablation --out "$out/eval-cycle"
run eval-rtl "$cli" eval --kitti "$kitti" --sequence 01 --source rtl --no-ablation --out "$out/eval-rtl"
run landmarks "$cli" landmarks --compare --data "$data" --out "$out/landmarks"
run slam "$cli" slam --sequences 01 --data "$data" --landmarks-from stereo --out "$out/slam"
run sweep "$cli" sweep --config tools/behaviour-sweep.json --data "$data" --cache "$out/sweep-cache" --quiet --out "$out/sweep"
run mutate "$cli" mutate --report "$out/mutate/mutation-smoke.md"
run golden "$cli" golden --check
fi

# digests: JSON without keys that hold times, hosts, the command line or the output folder (they name OUT_DIR) or the
# state of a cache (whether a result was recorded by an earlier run: `cached`, the gate's
# `detail`, gates run or recorded), CSV without such columns
timing='seconds|time|wall|elapsed|duration|host|date|_ms$|_s$|ms_per|per_second|^command$|^out$|cached|^gates_run$|^detail$'
digests="$out/digests.txt"
: > "$digests"
find "$out" -path "$out/sweep-cache" -prune -o -type f \( -name '*.json' -o -name '*.csv' \) -print | LC_ALL=C sort |
while read -r f; do
  rel="${f#"$out"/}"
  case "$f" in
    *.json) d=$(jq -S --arg t "$timing" 'walk(if type == "object" then with_entries(select(.key | test($t; "i") | not)) else . end)' "$f" 2>/dev/null | sha256sum | cut -c1-16) ;;
    *.csv) d=$(awk -F, -v t="$timing" 'NR == 1 { for (i = 1; i <= NF; i++) keep[i] = (tolower($i) !~ t) }
                 { s = ""; for (i = 1; i <= NF; i++) if (keep[i]) s = s $i ","; print s }' "$f" | sha256sum | cut -c1-16) ;;
  esac
  echo "$d  $rel" >> "$digests"
done
[ -f "$status" ] && cat "$status" >> "$digests"
echo "behaviour-check: $(wc -l < "$digests") lines in $digests" >&2
