#!/usr/bin/env python3
"""Compare two pose tracks of the same frames: modelc's cube-track and ViSP's peer (visp_track).

Both CSVs have the columns frame,tx,ty,tz,tux,tuy,tuz,... (cMo: metres, theta-u radians). For each
frame in both: the translation difference |t1 - t2| in mm and the rotation difference, the angle of
R1^T R2 in degrees (R from theta-u by Rodrigues); then their medians and maxima and the frames
within 1 cm and 3 degrees (both at once).

  tests/bench/cube_compare.py A.csv B.csv [--names A,B] [--range FIRST:LAST] [--quiet]
                              [--plot FILE.png] [--dat FILE.dat] [--judged A_ERR.csv,B_ERR.csv]

--range: only frames FIRST..LAST (inclusive; either may be left out). --quiet: the summary alone.
--plot: tx, ty, tz of both tracks against the frame (gnuplot, pngcairo or png terminal); --dat: the
joined table for gnuplot (frame, A's t, B's t, differences). --judged: a third party's score of
each pose, lower is better (visp_track --judge: ViSP's projection error, in degrees, of A's and of
B's poses), summed up as the medians, the frames where A's pose scores lower, and the same among the
frames outside 1 cm and 3 degrees: where two trackers disagree, which pose fits the frame better by
ViSP's own measure. Python 3 standard library only.
"""
import argparse
import csv
import math
import shutil
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "track"))
import errors  # noqa: E402  (tests/track/errors.py: the rotation angle between two theta-u vectors)


def read_track(path):
    poses = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            try:
                k = int(row["frame"])
                t = [float(row[c]) for c in ("tx", "ty", "tz")]
                w = [float(row[c]) for c in ("tux", "tuy", "tuz")]
            except (KeyError, TypeError, ValueError) as e:
                sys.exit(f"cube_compare: {path}: bad row {row}: {e}")
            poses[k] = (t, w)
    if not poses:
        sys.exit(f"cube_compare: {path}: no poses")
    return poses


def angle_between(w1, w2):
    """Angle of R1^T R2 in degrees (tests/track/errors.py's, Rodrigues)."""
    return errors.angle_deg(w1, w2)


median = errors.median


def read_judged(path):
    """visp_track --judge's CSV: frame -> error."""
    out = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            try:
                out[int(row["frame"])] = float(row["error"])
            except (KeyError, TypeError, ValueError) as e:
                sys.exit(f"cube_compare: {path}: bad row {row}: {e}")
    return out


def plot(png, dat, names):
    gp = shutil.which("gnuplot")
    if not gp:
        sys.exit("cube_compare: --plot: gnuplot not found (Debian gnuplot-nox); use --dat")
    r = subprocess.run([gp, "-e", "set terminal"], capture_output=True, text=True)
    terms = r.stdout + r.stderr
    term = "pngcairo size 1000,750" if "pngcairo" in terms else "png size 1000,750"
    a, b = names
    script = f"""
set terminal {term}
set output '{png}'
set multiplot layout 3,1 title 'cMo translation: {a} (lines) and {b} (points)'
set grid
set key top left
set xlabel 'frame'
"""
    for i, axis in enumerate(("tx", "ty", "tz")):
        script += f"""set ylabel '{axis} (m)'
plot '{dat}' using 1:{2 + i} with lines lw 2 title '{a} {axis}', '{dat}' using 1:{5 + i} with points pt 7 ps 0.4 title '{b} {axis}'
"""
    script += "unset multiplot\n"
    r = subprocess.run([gp], input=script, text=True, capture_output=True)
    if r.returncode:
        sys.exit(f"cube_compare: gnuplot failed: {r.stderr.strip()}")


def main():
    ap = argparse.ArgumentParser(description="translation and rotation differences between two pose CSVs")
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--names", default=None, help="labels A,B (default: the file names)")
    ap.add_argument("--range", default=None, help="FIRST:LAST frames, inclusive")
    ap.add_argument("--quiet", action="store_true", help="the summary only")
    ap.add_argument("--plot", default=None, help="PNG of tx, ty, tz against the frame (gnuplot)")
    ap.add_argument("--dat", default=None, help="write the joined table for gnuplot")
    ap.add_argument("--judged", default=None, help="A_ERR.csv,B_ERR.csv: visp_track --judge of A's and B's poses")
    o = ap.parse_args()
    names = o.names.split(",", 1) if o.names else [o.a, o.b]
    if len(names) != 2:
        sys.exit("cube_compare: --names A,B")
    A, B = read_track(o.a), read_track(o.b)
    frames = sorted(set(A) & set(B))
    if o.range:
        lo, _, hi = o.range.partition(":")
        lo = int(lo) if lo else -math.inf
        hi = int(hi) if hi else math.inf
        frames = [k for k in frames if lo <= k <= hi]
    if not frames:
        sys.exit("cube_compare: no frame in both files (and in --range)")
    judged = None
    if o.judged:
        paths = o.judged.split(",")
        if len(paths) != 2:
            sys.exit("cube_compare: --judged A_ERR.csv,B_ERR.csv")
        judged = [read_judged(q) for q in paths]
        for q, j in zip(paths, judged):
            missing = [k for k in frames if k not in j]
            if missing:
                sys.exit(f"cube_compare: {q}: no score for frame {missing[0]}")
    rows = []
    for k in frames:
        (ta, wa), (tb, wb) = A[k], B[k]
        dt = 1000 * math.sqrt(sum((x - y) ** 2 for x, y in zip(ta, tb)))
        rows.append((k, ta, tb, dt, angle_between(wa, wb)))
    if not o.quiet:
        print("frame  dt_mm  drot_deg")
        for k, _, _, dt, dr in rows:
            print(f"{k:5d} {dt:6.2f} {dr:9.3f}")
    dts = [r[3] for r in rows]
    drs = [r[4] for r in rows]
    within = sum(1 for r in rows if r[3] <= 10 and r[4] <= 3)
    only = (len(A) - len(frames) if not o.range else None, len(B) - len(frames) if not o.range else None)
    print(f"{names[0]} vs {names[1]}: {len(rows)} frames ({frames[0]}..{frames[-1]})")
    print(f"translation difference mm: median {median(dts):.2f}, max {max(dts):.2f} (frame {rows[dts.index(max(dts))][0]})")
    print(f"rotation difference deg: median {median(drs):.2f}, max {max(drs):.2f} (frame {rows[drs.index(max(drs))][0]})")
    print(f"frames within 1 cm and 3 deg: {within} of {len(rows)}")
    if judged:
        ja, jb = judged
        lower = sum(1 for k in frames if ja[k] < jb[k])
        out = [r[0] for r in rows if not (r[3] <= 10 and r[4] <= 3)]
        print(f"judged: median {names[0]} {median([ja[k] for k in frames]):.2f}, {names[1]} {median([jb[k] for k in frames]):.2f}; "
              f"{names[0]} lower in {lower} of {len(frames)}")
        print(f"judged outside 1 cm and 3 deg: {names[0]} lower in {sum(1 for k in out if ja[k] < jb[k])} of {len(out)}")
    if only[0] or only[1]:
        print(f"frames in one file only: {only[0]} in {names[0]}, {only[1]} in {names[1]}")
    if o.dat or o.plot:
        dat = o.dat or tempfile.NamedTemporaryFile(prefix="cube_compare", suffix=".dat", delete=False).name
        with open(dat, "w") as f:
            f.write(f"# frame  {names[0]}: tx ty tz  {names[1]}: tx ty tz  dt_mm drot_deg\n")
            for k, ta, tb, dt, dr in rows:
                f.write(f"{k} {ta[0]:.6f} {ta[1]:.6f} {ta[2]:.6f} {tb[0]:.6f} {tb[1]:.6f} {tb[2]:.6f} {dt:.3f} {dr:.4f}\n")
        if o.plot:
            plot(o.plot, dat, names)
            print(f"wrote {o.plot}")


if __name__ == "__main__":
    main()
