#!/usr/bin/env bash
# slam_cli_stereo.sh: `harris-cosim slam --sequences 01 --landmarks-from stereo` runs visual
# odometry and the filter on landmarks of the project's own stereo pipeline (OpenCV Harris
# corners, ORB descriptors, the thesis's matching tests, triangulation) and ends closer to the
# ground truth than visual odometry alone. Exits 77 (skipped) without the data.
# usage: slam_cli_stereo.sh HARRIS_COSIM DATA_DIR WORK_DIR
set -u
exe=$1
data=${HARRIS_COSIM_DATA:-$2}
out=$3
seq=$data/kitti/sequences/01
[ -f "$data/kitti/poses/01.txt" ] && [ -d "$seq/image_1" ] || { echo "SKIPPED: no KITTI 01 stereo pairs and poses under $data/kitti"; exit 77; }
rm -rf "$out"
"$exe" slam --sequences 01 --kitti "$data/kitti" --landmarks-from stereo --corners opencv --descriptor orb \
    --out "$out" || exit 1
python3 - "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
slam, dr = s["ate_m"]["slam"], s["ate_m"]["dead_reckoning"]
print(f"APE: EKF-SLAM {slam:.3f} m, visual odometry alone {dr:.3f} m, {s['matched']} of {s['observations']} observations associated")
if s["frames"] != 51 or s["matched"] <= 0:
    sys.exit("FAIL: expected 51 frames and associated observations")
if not slam < dr:
    sys.exit("FAIL: the filter on stereo landmarks is not better than visual odometry alone")
PY
