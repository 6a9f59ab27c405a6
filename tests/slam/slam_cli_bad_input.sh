#!/usr/bin/env bash
# slam_cli_bad_input.sh: `harris-cosim slam` refuses bad input with a message naming it and
# exit status 2: a non-positive noise, an empty world, a sequence without poses or pairs, a
# ground truth that cannot be read, a ground-truth time tolerance that is not positive, a pair
# range that is not a:b or is given to --simulate, the flag --sequence (slam's is --sequences),
# and a run that is not exactly one of --simulate, --sequences and a rig's --calib --left --right.
# usage: slam_cli_bad_input.sh HARRIS_COSIM WORK_DIR
set -u
exe=$1
work=$2
mkdir -p "$work/kitti/poses"
: > "$work/kitti/poses/07.txt"   # a sequence whose poses file is empty
fail=0
out_dir=$work/out
expect2() {
    local what=$1 pattern=$2
    shift 2
    local err
    err=$("$exe" slam "$@" --out "$out_dir" 2>&1 >/dev/null)
    local rc=$?
    if [ $rc -ne 2 ] || ! grep -q -- "$pattern" <<<"$err"; then
        echo "FAIL: $what: status $rc, message: $err"
        fail=1
    else
        echo "ok: $what -> status 2: $err"
    fi
}
expect2 "zero range noise" "--sigma-range" --simulate --sigma-range 0
expect2 "negative odometry noise" "--sigma-dx" --simulate --sigma-dx -0.1
expect2 "empty world" "world is empty" --simulate --landmarks 0
expect2 "sequence without poses" "holds no pose" --sequences 07 --kitti "$work/kitti"
expect2 "sequence without pairs or poses" "sequence directory" --sequences 99 --kitti "$work/kitti"
expect2 "missing ground-truth file" "cannot read the ground-truth file" --sequences 07 --kitti "$work/kitti" --truth "$work/none.txt"
expect2 "neither mode" "exactly one of" --runs 3
expect2 "two modes" "exactly one of" --sequences 01 --calib "$work/rig.yml" --left "$work/l" --right "$work/r"
expect2 "a rig's images without its calibration" "give its --calib" --left "$work/l" --right "$work/r"
expect2 "one ground truth for two sequences" "ground truth of one sequence" --sequences 05,06 --kitti "$work/kitti1" --truth "$work/kitti1/poses/05.txt"
mkdir -p "$work/kitti1/poses" && printf '1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 1\n' > "$work/kitti1/poses/05.txt"
expect2 "unknown odometry" "neither visual nor synthetic" --sequences 05 --kitti "$work/kitti1" --odometry wheels
expect2 "unknown association" "neither jcbb nor nearest" --sequences 05 --kitti "$work/kitti1" --association greedy
expect2 "unknown odometry residual" "neither pixels nor top-view" --sequences 05 --kitti "$work/kitti1" --vo-residual depth
expect2 "a seed for deterministic visual odometry" "deterministic" --sequences 05 --kitti "$work/kitti1" --landmarks-from stereo --seed 3
expect2 "zero ground-truth time tolerance" "--truth-time-tolerance must be positive" --sequences 05 --kitti "$work/kitti1" --truth-time-tolerance 0
expect2 "Hamming fraction above 1" "max-hamming-fraction" --sequences 05 --kitti "$work/kitti1" --max-hamming-fraction 2
expect2 "a reversed pair range" "--pairs '5:2' is not FIRST:LAST" --sequences 05 --kitti "$work/kitti1" --pairs 5:2
expect2 "a pair range with --simulate" "--simulate has none" --simulate --pairs 0:5
expect2 "the old alias of --sequences" "--sequence" --sequence 05 --kitti "$work/kitti1"
expect2 "unknown world" "neither cloister nor random" --simulate --world maze
expect2 "negative runs" "--runs" --simulate --runs -1
out_dir=/proc/slam-report expect2 "unwritable output" "cannot create the output directory" --simulate --runs 1 --steps 2
out_dir=$work/out
[ -e "$work/out/report.md" ] && { echo "FAIL: a report was written for bad input"; fail=1; }
exit $fail
