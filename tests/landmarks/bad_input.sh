#!/bin/sh
# bad_input.sh HARRIS_COSIM DATA_DIR: `harris-cosim landmarks` refuses bad input with a
# message naming it and exit status 2. Exits 77 (skipped) without the Middlebury data.
set -u
hc=$1
data=$2
scene=$data/middlebury2006/half/Aloe
[ -f "$scene/disp1.png" ] || { echo "SKIP: no Middlebury half-size Aloe under $data"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
expect2() {   # expect2 WHAT PATTERN ARGS...: exit status 2 and PATTERN in stderr
  what=$1; pattern=$2; shift 2
  "$hc" landmarks --out "$tmp/out" --no-landmark-files --overlays 0 "$@" >/dev/null 2>"$tmp/err"
  rc=$?
  if [ $rc -ne 2 ] || ! grep -q -- "$pattern" "$tmp/err"; then
    echo "FAIL: $what: exit $rc, stderr: $(cat "$tmp/err")"; fail=1
  else
    echo "ok: $what: $(tail -1 "$tmp/err")"
  fi
}
expect2 "SIFT descriptor on a Hamming matcher" "Hamming" --middlebury "$scene" --descriptor sift --norm hamming
expect2 "grid side out of range" "g" --middlebury "$scene" --g 1000
expect2 "h out of range" "h" --middlebury "$scene" --h -1
expect2 "unknown corner source" "unknown corner source" --middlebury "$scene" --corners surf
mkdir -p "$tmp/nodisp" && cp "$scene/view1.png" "$scene/view5.png" "$tmp/nodisp/"
expect2 "Middlebury folder without disp1.png" "disp1.png" --middlebury "$tmp/nodisp"
mkdir -p "$tmp/sizes" && cp "$scene/view1.png" "$scene/disp1.png" "$tmp/sizes/"
cp "$data/middlebury2006/half/Baby1/view5.png" "$tmp/sizes/view5.png"
expect2 "left and right images of different sizes" "differ in size" --middlebury "$tmp/sizes"
expect2 "re-observations with the comparison" "runs alone" --middlebury "$scene" --reobservation --compare
expect2 "re-observations of one frame" "at least two consecutive frames" --middlebury "$scene" --reobservation
expect2 "re-observations of a float descriptor" "binary descriptors" --middlebury "$data/middlebury2006/half" --reobservation --descriptor sift-ratio1
exit $fail
