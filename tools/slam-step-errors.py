#!/usr/bin/env python3
"""slam-step-errors.py: the frame-to-frame errors of a sequence run's odometry, from its states.csv.

    python3 tools/slam-step-errors.py DIR [DIR ...]

DIR is the directory of one sequence's report (`harris-cosim slam --sequences NN --out OUT`
writes OUT/NN/states.csv). For each, the odometry's step (the pose of frame k in frame k-1,
from the columns odo_x, odo_y, odo_theta) is compared with the true step (true_x, true_y,
true_theta); printed per directory:
  - the mean step error in the step's forward, left and heading components, with its standard
    error (mean / (sd / sqrt(n))): a systematic error shows as a large ratio;
  - the path-length ratio, odometry over truth (sums of the step lengths);
  - the lag-1 correlation of consecutive step errors per component (steps that share a frame);
  - the mean pose NEES of the odometry alone and of EKF-SLAM (nees_odometry, nees_slam).
Ground truth is read here only to score. Exit status 2 on a missing or malformed file.
"""
import csv
import math
import sys


def between(a, b):
    """Pose b in the frame of pose a (x, y, theta)."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy, -s * dx + c * dy, math.atan2(math.sin(b[2] - a[2]), math.cos(b[2] - a[2])))


def corr(x, y):
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxy = sum((a - mx) * (b - my) for a, b in zip(x, y))
    sxx = sum((a - mx) ** 2 for a in x)
    syy = sum((b - my) ** 2 for b in y)
    return sxy / math.sqrt(sxx * syy) if sxx > 0 and syy > 0 else float("nan")


def mean_finite(v):
    v = [x for x in v if math.isfinite(x)]
    return sum(v) / len(v) if v else float("nan")


def report(directory):
    path = directory.rstrip("/") + "/states.csv"
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
        truth = [tuple(float(r[k]) for k in ("true_x", "true_y", "true_theta")) for r in rows]
        odo = [tuple(float(r[k]) for k in ("odo_x", "odo_y", "odo_theta")) for r in rows]
        nees_o = [float(r["nees_odometry"]) for r in rows]
        nees_s = [float(r["nees_slam"]) for r in rows]
    except (OSError, KeyError, ValueError) as e:
        print(f"slam-step-errors: cannot read '{path}': {e}", file=sys.stderr)
        sys.exit(2)
    if len(rows) < 4:
        print(f"slam-step-errors: '{path}' has fewer than 4 frames", file=sys.stderr)
        sys.exit(2)
    err = []
    lo = lt = 0.0
    for k in range(1, len(rows)):
        so, st = between(odo[k - 1], odo[k]), between(truth[k - 1], truth[k])
        lo += math.hypot(so[0], so[1])
        lt += math.hypot(st[0], st[1])
        e = [so[i] - st[i] for i in range(3)]
        e[2] = math.atan2(math.sin(e[2]), math.cos(e[2]))
        err.append(e)
    n = len(err)
    print(f"{directory}: {n} steps, path-length ratio odometry/truth {lo / lt:.4f}")
    for i, name in enumerate(("forward (m)", "left (m)", "heading (rad)")):
        c = [e[i] for e in err]
        m = sum(c) / n
        sd = math.sqrt(sum((x - m) ** 2 for x in c) / (n - 1))
        r1 = corr(c[:-1], c[1:])
        print(f"  {name}: mean {m:.3g}, sd {sd:.3g}, mean/se {m / (sd / math.sqrt(n)):.2f}, lag-1 correlation {r1:.3f}")
    print(f"  mean pose NEES: odometry alone {mean_finite(nees_o):.4g}, EKF-SLAM {mean_finite(nees_s):.4g}")


def main():
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    for d in sys.argv[1:]:
        report(d)


if __name__ == "__main__":
    main()
