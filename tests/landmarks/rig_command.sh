#!/bin/sh
# rig_command.sh HARRIS_COSIM SAMPLES_DIR: `harris-cosim calibrate` on OpenCV's stereo
# chessboard samples, then `harris-cosim landmarks --calib` on one unrectified pair: exit 0,
# a report saying the keypoints were rectified, landmark files; a calibration file that is
# missing or malformed, or --left/--right without --calib, exits 2 naming the input. Exits 77
# (skipped) without the samples.
set -u
hc=$1
samples="${HARRIS_COSIM_OPENCV_SAMPLES:-$2}"
[ -f "$samples/left01.jpg" ] || { echo "SKIP: OpenCV's stereo samples not found in '$samples'"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
expect2() {   # expect2 WHAT PATTERN ARGS...: exit status 2 and PATTERN in stderr
  what=$1; pattern=$2; shift 2
  "$hc" landmarks --out "$tmp/bad" "$@" >/dev/null 2>"$tmp/err"; rc=$?
  [ $rc -eq 2 ] && grep -qF -- "$pattern" "$tmp/err" || fail "$what: exit $rc, stderr: $(cat "$tmp/err")"
  echo "ok: $what: $(tail -1 "$tmp/err")"
}
"$hc" calibrate --left "$samples/left[0-9]*.jpg" --right "$samples/right[0-9]*.jpg" --board 9x6 --square 0.025 \
  --out "$tmp/cal" > "$tmp/log" 2>&1 || { cat "$tmp/log"; fail "calibrate exited non-zero"; }
"$hc" landmarks --calib "$tmp/cal/calib.yml" --left "$samples/left03.jpg" --right "$samples/right03.jpg" \
  --corners opencv --descriptor brief,grid --out "$tmp/lm" > "$tmp/log" 2>&1 || { cat "$tmp/log"; fail "landmarks --calib exited non-zero"; }
grep -q "unrectified pairs" "$tmp/lm/report.md" || fail "the report does not say the pairs were rectified"
[ -s "$tmp/lm/opencv-brief/landmarks/left03+right03.csv" ] || fail "no landmark CSV"
[ "$(wc -l < "$tmp/lm/opencv-brief/landmarks/left03+right03.csv")" -gt 20 ] || fail "fewer than 20 landmarks"
printf '%%YAML:1.0\n---\nimage_width: 640\n' > "$tmp/bad.yml"
expect2 "malformed calibration" "$tmp/bad.yml" --calib "$tmp/bad.yml" --left "$samples/left03.jpg" --right "$samples/right03.jpg"
expect2 "missing calibration" "no/such/calib.yml" --calib no/such/calib.yml --left "$samples/left03.jpg" --right "$samples/right03.jpg"
expect2 "calibration without images" "--left and --right" --calib "$tmp/cal/calib.yml"
expect2 "images without calibration" "--calib" --left "$samples/left03.jpg" --right "$samples/right03.jpg"
[ -f "$samples/aloeL.jpg" ] && expect2 "image of another size" "aloeL.jpg" --calib "$tmp/cal/calib.yml" --left "$samples/aloeL.jpg" --right "$samples/right03.jpg"
echo PASS
