#!/usr/bin/env python3
"""Pose errors of a tracker's poses against a sequence's truth (tests/track/synth.c's truth.csv), both
CSV with frame,tx,ty,tz,tux,tuy,tuz (metres, theta-u radians, ViSP's convention).

usage: errors.py TRUTH.csv POSES.csv [--jump K] [--from F]
Prints one line of key=value figures: frames, success (translation error < 5 cm and rotation error
< 5 degrees), rate, median and largest errors (mm, degrees), and with --jump K the frames from K to
the first of 5 successes in a row (the re-detection; -1 if it never comes), the rate of the frames
outside that window (tracked_rate), and the frames from K to the first of 5 in a row with the
translation alone within 5 cm (found: the object found again, whatever its orientation; -1 never).
Frames before --from are left out of the rates.""" 
import csv
import math
import sys


def rot(tu):
    th = math.sqrt(sum(v * v for v in tu))
    u = [v / th for v in tu] if th > 1e-15 else [1.0, 0.0, 0.0]
    c, s, C = math.cos(th), math.sin(th), 1 - math.cos(th)
    x, y, z = u
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def angle_deg(a, b):
    ra, rb = rot(a), rot(b)
    tr = sum(ra[k][i] * rb[k][i] for i in range(3) for k in range(3))   # trace(Ra^T Rb)
    return math.degrees(math.acos(max(-1.0, min(1.0, (tr - 1) / 2))))


def load(path):
    out = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            out[int(r["frame"])] = [float(r[k]) for k in ("tx", "ty", "tz", "tux", "tuy", "tuz")]
    return out


def median(v):
    v = sorted(v)
    n = len(v)
    return (v[n // 2] + v[(n - 1) // 2]) / 2 if n else float("nan")


def main():
    args = sys.argv[1:]
    jump = start = None
    if "--jump" in args:
        i = args.index("--jump"); jump = int(args[i + 1]); del args[i:i + 2]
    if "--from" in args:
        i = args.index("--from"); start = int(args[i + 1]); del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    truth, poses = load(args[0]), load(args[1])
    frames = sorted(k for k in poses if k in truth)
    if not frames:
        sys.exit("errors.py: no frame in both files")
    et, er, ok = {}, {}, {}
    for k in frames:
        t, p = truth[k], poses[k]
        et[k] = 1000 * math.sqrt(sum((t[i] - p[i]) ** 2 for i in range(3)))
        er[k] = angle_deg(t[3:], p[3:])
        ok[k] = et[k] < 50 and er[k] < 5
    counted = [k for k in frames if start is None or k >= start]
    succ = sum(ok[k] for k in counted)
    line = "frames=%d success=%d rate=%.4f median_mm=%.2f median_deg=%.2f max_mm=%.1f max_deg=%.1f" % (
        len(counted), succ, succ / len(counted), median([et[k] for k in counted]), median([er[k] for k in counted]),
        max(et[k] for k in counted), max(er[k] for k in counted))
    if jump is not None:
        def first_run(good):   # frames from the jump to the first of 5 good frames in a row, -1 never
            for k in frames:
                if k >= jump and all(good(k + j) for j in range(5)):
                    return k - jump
            return -1
        red = first_run(lambda k: ok.get(k, False))
        found = first_run(lambda k: k in et and et[k] < 50)
        # tracking apart from finding it again: the frames outside [jump, jump + redetect)
        kept = [k for k in counted if not (jump <= k < (jump + red if red >= 0 else 1 << 30))]
        line += " redetect=%d tracked_rate=%.4f found=%d" % (red, sum(ok[k] for k in kept) / max(1, len(kept)), found)
    print(line)


if __name__ == "__main__":
    main()
