#!/usr/bin/env python3
"""How a tracker scores the poses on the straight way between two poses of one frame: where they all
score alike, the frame cannot tell them apart.

usage: pose_path.py TRACKER FRAMES CAMERA FRAME A.csv B.csv [--steps N] [--radius R]
TRACKER is a baked NAME-track; FRAMES its --frames pattern, CAMERA its --camera; A.csv and B.csv
are pose CSVs (frame,tx,ty,tz,tux,tuy,tuz: metres, theta-u radians), each giving its pose of FRAME.
The way: the translation linear, the rotation along the shortest arc (B's rotation times A's inverse,
its angle shared out), N steps (default 10). Each pose is scored by one run of TRACKER on FRAME with
one particle that does not move (--particles 1 --fresh 0 --step-t 0 --step-r 0 --layers 1 --detect 0,
--radius R, default 2): the estimate it prints is that pose, and its visible and matched columns the
pose's score. Prints a line per step "s visible matched", then one line of key=value figures: the
angle (degrees) and distance (mm) between A and B; A's score (a_visible, a_matched, a_ratio =
matched / visible); and over the steps after A, the least and most of visible and of the ratio
(way_min_visible, way_max_visible, way_min_ratio, way_max_ratio)."""
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from errors import rot   # noqa: E402  (theta-u to a rotation matrix, as errors.py measures)


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def log(r):   # theta-u of rotation r
    c = max(-1.0, min(1.0, (r[0][0] + r[1][1] + r[2][2] - 1) / 2))
    th = math.acos(c)
    w = [r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]]
    if th < 1e-12:
        return [0.0, 0.0, 0.0]
    k = th / (2 * math.sin(th))
    return [k * v for v in w]


def pose_of(path, frame):
    with open(path) as f:
        for r in csv.DictReader(f):
            if int(r["frame"]) == frame:
                return [float(r[k]) for k in ("tx", "ty", "tz", "tux", "tuy", "tuz")]
    sys.exit("pose_path.py: %s has no frame %d" % (path, frame))


def score(tracker, frames, camera, frame, pose, radius):
    cmd = [tracker, "--frames", frames, "--camera", camera, "--first", str(frame), "--count", "1",
           "--init", ",".join("%.12f" % v for v in pose), "--particles", "1", "--fresh", "0", "--step-t", "0",
           "--step-r", "0", "--layers", "1", "--detect", "0", "--radius", str(radius)]
    out = subprocess.run(cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("pose_path.py: %s failed: %s" % (tracker, out.stderr.strip().splitlines()[-1:]))
    rows = list(csv.DictReader(out.stdout.splitlines()))
    return int(rows[-1]["visible"]), int(rows[-1]["matched"])


def main():
    args = sys.argv[1:]
    steps, radius = 10, 2
    if "--steps" in args:
        i = args.index("--steps"); steps = int(args[i + 1]); del args[i:i + 2]
    if "--radius" in args:
        i = args.index("--radius"); radius = int(args[i + 1]); del args[i:i + 2]
    if len(args) != 6 or steps < 1:
        sys.exit(__doc__)
    tracker, frames, camera, frame = args[0], args[1], args[2], int(args[3])
    a, b = pose_of(args[4], frame), pose_of(args[5], frame)
    ra = rot(a[3:])
    w = log(mul(rot(b[3:]), transpose(ra)))   # the turn from A to B
    scores = []
    for s in range(steps + 1):
        f = s / steps
        t = [a[i] + f * (b[i] - a[i]) for i in range(3)]
        r = log(mul(rot([f * v for v in w]), ra))
        v, m = score(tracker, frames, camera, frame, t + r, radius)
        print("%d %d %d" % (s, v, m))
        scores.append((v, m))
    ratio = lambda v, m: m / v if v else 0.0
    way = scores[1:]
    print("angle_deg=%.2f distance_mm=%.2f a_visible=%d a_matched=%d a_ratio=%.4f way_min_visible=%d way_max_visible=%d "
          "way_min_ratio=%.4f way_max_ratio=%.4f" % (
              math.degrees(math.sqrt(sum(v * v for v in w))), 1000 * math.sqrt(sum((a[i] - b[i]) ** 2 for i in range(3))),
              scores[0][0], scores[0][1], ratio(*scores[0]), min(v for v, _ in way), max(v for v, _ in way),
              min(ratio(*x) for x in way), max(ratio(*x) for x in way)))

if __name__ == "__main__":
    main()
