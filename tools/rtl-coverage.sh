#!/usr/bin/env bash
# rtl-coverage.sh: statement and branch coverage of rtl/ by the co-simulation regression.
#   rtl-coverage.sh SOURCE_DIR BUILD_DIR OUT_DIR HARRIS_COSIM RTL_FILES
# RTL_FILES: the design's VHDL files in analysis order, separated by ';' (CMake's list).
# Builds the co-simulation testbench with GHDL's gcc back end instrumented for gcov
# (-fprofile-arcs -ftest-coverage), runs every stream of golden/regression-set.txt through
# it against the cycle model (`harris-cosim rtl --sim-dir`), and has gcovr turn the counts
# into OUT_DIR/index.html (per file, line by line), OUT_DIR/summary.txt and
# OUT_DIR/summary.json. Exits non-zero if a stream mismatches or a tool fails.
set -euo pipefail
[ $# -eq 5 ] || { echo "usage: $0 SOURCE_DIR BUILD_DIR OUT_DIR HARRIS_COSIM RTL_FILES" >&2; exit 2; }
src=$(cd "$1" && pwd); build=$(cd "$2" && pwd); out=$3; cli=$4
command -v ghdl-gcc >/dev/null || { echo "rtl-coverage: ghdl-gcc is not installed"; exit 77; }
command -v gcovr >/dev/null || { echo "rtl-coverage: gcovr is not installed (Debian: gcovr)"; exit 77; }
sim=$build/coverage-sim
rm -rf "$sim"; mkdir -p "$sim/work" "$out"
IFS=';' read -r -a files <<< "$5"
[ ${#files[@]} -gt 0 ] || { echo "rtl-coverage: no RTL files given"; exit 2; }
files+=("$build/cosim/hc_bridge_pkg.vhd" "$build/cosim/harris_top_tb.vhd")
echo "[coverage] analysing ${#files[@]} files with coverage instrumentation"
(cd "$sim/work" && ghdl-gcc -a --std=08 -g -Wc,-fprofile-arcs -Wc,-ftest-coverage --workdir=. "${files[@]}")
(cd "$build/cosim" && ghdl-gcc -e --std=08 --workdir="$sim/work" -Wl,-lgcov \
   -Wl,-L"$build/cosim" -Wl,-lhc_bridge -Wl,-Wl,-rpath,"$build/cosim" -o "$sim/harris_top_tb_gcc" harris_top_tb)
n=0
while read -r pattern size frames idle _; do
  case "$pattern" in ''|\#*) continue ;; esac
  n=$((n + 1))
  echo "[coverage] stream $n: $pattern $size x$frames (idle every $idle)"
  case "$pattern" in
    *.pgm|*.png)   # an image chained `frames` times (paths relative to the set), the thesis's formats
      images=()
      for ((k = 0; k < frames; k++)); do images+=("$src/golden/$pattern"); done
      "$cli" rtl "${images[@]}" --idle-every "$idle" --backend gcc --sim-dir "$sim" --quiet ;;
    *)
      "$cli" rtl --pattern "$pattern" --size "$size" --frames "$frames" --idle-every "$idle" \
            --backend gcc --sim-dir "$sim" --quiet ;;
  esac
done < "$src/golden/regression-set.txt"
(cd "$sim/work" && gcovr --root "$src" --filter "$src/rtl/" --object-directory "$sim/work" \
   --html-details "$(cd "$out" && pwd)/index.html" --txt "$(cd "$out" && pwd)/summary.txt" \
   --json-summary "$(cd "$out" && pwd)/summary.json" --json-summary-pretty .)
(cd "$sim/work" && gcovr --root "$src" --filter "$src/rtl/" --object-directory "$sim/work" \
   --branches --txt "$(cd "$out" && pwd)/branches.txt" .)
echo "[coverage] $n streams; report: $out/index.html"
cat "$out/summary.txt" "$out/branches.txt"
# The goal is every statement of rtl/ executed: fail, naming the files, when one is not.
python3 - "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
short = [f"{f['filename']} ({f['line_covered']}/{f['line_total']})" for f in s["files"]
         if f["line_covered"] != f["line_total"]]
print(f"[coverage] statements {s['line_covered']}/{s['line_total']}, "
      f"gcov branches {s['branch_covered']}/{s['branch_total']}")
if short:
    print("[coverage] statements not executed in: " + ", ".join(short))
    sys.exit(1)
PY
