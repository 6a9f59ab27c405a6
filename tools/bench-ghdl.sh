#!/usr/bin/env bash
# bench-ghdl.sh: GHDL co-simulation speed, every back end, with the full-signal compare and
# with reads only, on the same stream in one run; prints a Markdown table.
#   tools/bench-ghdl.sh [WRITES]   (default 20000 writes of a 1241x376 frame)
# Uses KITTI 01's first pair when ../shared/data (or $HARRIS_COSIM_DATA) has it, else a
# generated 1241x376 'blocks' frame.
set -euo pipefail
cd "$(dirname "$0")/.."
cli=build/tools/harris-cosim
writes="${1:-20000}"
data="${HARRIS_COSIM_DATA:-$(cd .. && pwd)/shared/data}"
if [ -d "$data/kitti/sequences/01/image_0" ]; then
  src=(--data "$data" --pairs 0:1); what="KITTI 01 pair 0 (1241x376)"
else
  src=(--pattern blocks --size 1241x376 --frames 1); what="generated 'blocks' 1241x376"
fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
num() { sed -n "s/.*\"$2\": *\([0-9.e+-]*\).*/\1/p" "$1" | head -1; }
echo "GHDL co-simulation speed: first $writes writes of $what; $(nproc) cores, load $(cut -d' ' -f1 /proc/loadavg)"
echo
echo "| back end | compare | cycles/s | signals per cycle | compare cost |"
echo "|---|---|---:|---:|---:|"
for be in gcc llvm mcode; do
  "$cli" rtl --help >/dev/null
  declare -A rate=()
  for cmp in reads all; do
    if "$cli" rtl "${src[@]}" --backend "$be" --compare "$cmp" --max-writes "$writes" --quiet \
         --json "$tmp/$be-$cmp.json" > "$tmp/log" 2>&1; then
      rate[$cmp]=$(num "$tmp/$be-$cmp.json" cycles_per_second)
      sig=$(num "$tmp/$be-$cmp.json" signals_compared_per_cycle)
      cost=""
      [ "$cmp" = all ] && cost=$(awk -v a="${rate[all]}" -v r="${rate[reads]}" 'BEGIN{printf "%+.0f %%", (r/a-1)*100}')
      printf "| %s | %s | %.0f | %s | %s |\n" "$be" "$cmp" "${rate[$cmp]}" "$sig" "$cost"
    else
      echo "| $be | $cmp | failed: $(tail -1 "$tmp/log") | | |"
    fi
  done
done
echo
echo "compare cost = extra time per cycle of the full-signal compare over reads-only, same back end."
