#!/bin/sh
# `harris-cosim calibrate`: bad input exits 2 with a message naming it and writes nothing;
# on OpenCV's sample pairs it exits 0 and writes calib.txt, calib.yml, calib.json, views.csv,
# rectified.png and report.md, calib.txt holding exactly the rows P0 and P1 of 12 numbers.
#   calibrate_command.sh HARRIS_COSIM SAMPLES_DIR
set -u
cli="$1"; samples="${HARRIS_COSIM_OPENCV_SAMPLES:-$2}"
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

# expect_2 NEEDLE ARGS...: the command must exit 2, print NEEDLE, and leave no output directory
expect_2() {
  needle="$1"; shift
  "$cli" calibrate --out "$out/bad" "$@" > "$out/log" 2>&1; rc=$?
  [ $rc -eq 2 ] || { cat "$out/log"; fail "calibrate $* exited $rc, expected 2"; }
  grep -qF -- "$needle" "$out/log" || { cat "$out/log"; fail "calibrate $*: message does not name '$needle'"; }
  [ ! -e "$out/bad" ] || fail "calibrate $* created its output directory"
  echo "ok: $* -> 2 ($needle)"
}
expect_2 "no/such/l.png" --left no/such/l.png --right no/such/r.png
expect_2 "matches no file" --left "no/such/l*.png" --right no/such/r.png

if [ ! -f "$samples/left01.jpg" ]; then
  echo "SKIP: OpenCV's stereo samples not found in '$samples' (set HARRIS_COSIM_OPENCV_SAMPLES)"; exit 77
fi
expect_2 "--board '9x'" --left "$samples/left01.jpg" --right "$samples/right01.jpg" --board 9x
expect_2 "--square -1" --left "$samples/left01.jpg" --right "$samples/right01.jpg" --square -1
expect_2 "7x4 board not found" --left "$samples/left0[1-3].jpg" --right "$samples/right0[1-3].jpg" --board 7x4 --min-pairs 1
expect_2 "2 left images but 1 right" --left "$samples/left0[1-2].jpg" --right "$samples/right01.jpg"

# left*.jpg also matches left.jpg (612x459, no 9x6 board), sorted first: it is skipped and
# the 640x480 pairs after it are used
"$cli" calibrate --left "$samples/left*.jpg" --right "$samples/right*.jpg" --board 9x6 \
  --square 0.025 --out "$out/all" > "$out/log" 2>&1 || { cat "$out/log"; fail "calibrate over left*.jpg exited non-zero"; }
grep -qF "skipping left.jpg + right.jpg" "$out/log" || { cat "$out/log"; fail "left.jpg + right.jpg was not skipped"; }
[ "$(wc -l < "$out/all/views.csv")" -eq 14 ] || fail "views.csv over left*.jpg does not hold 13 pairs"

"$cli" calibrate --left "$samples/left[0-9]*.jpg" --right "$samples/right[0-9]*.jpg" --board 9x6 \
  --square 0.025 --out "$out/good" > "$out/log" 2>&1 || { cat "$out/log"; fail "calibrate on the samples exited non-zero"; }
for f in calib.txt calib.yml calib.json views.csv rectified.png report.md; do
  [ -s "$out/good/$f" ] || fail "calibrate did not write $f"
done
[ "$(cut -d' ' -f1 "$out/good/calib.txt" | tr '\n' ' ')" = "P0: P1: " ] || fail "calib.txt rows are not P0, P1"
[ "$(awk '{print NF}' "$out/good/calib.txt" | tr '\n' ' ')" = "13 13 " ] || fail "calib.txt rows do not hold 12 numbers"
[ "$(wc -l < "$out/good/views.csv")" -eq 14 ] || fail "views.csv does not hold 13 pairs"
ls "$out/good" | grep -q '\.tmp' && fail "a temporary file was left behind"
echo "PASS"
