#!/usr/bin/env python3
"""Point sets made from a catalogue mesh, for tests/points/suite.sh.

    make_sets.py MESH.off SEED OUT:N:NORMALS...

writes each OUT (.xyz or .ply by its name, ASCII) with N points of the mesh's surface, with the
mesh's normals (NORMALS 1: area-weighted vertex normals, interpolated across a face) or without (0):
  - N at most the vertex count: N of the mesh's vertices, drawn at random without repetition (the
    sparse scan of the issue: a catalogue mesh's vertices subsampled);
  - more: every vertex, then random points on the faces (area-weighted) up to N.
The six vertices with the smallest and largest coordinate on each axis are always among them, so the
point set's bounding box, hence its grid cube (gen/normalize.hpp), is the mesh's: its bake and the
mesh's reference dump map the model into the unit cube the same way. Deterministic for a SEED."""
import bisect
import math
import random
import sys


def read_off(path):
    toks = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0]
            toks.extend(line.split())
    if toks[0] != "OFF":
        raise SystemExit(f"{path}: not an OFF file")
    nv, nf = int(toks[1]), int(toks[2])
    i = 4
    verts = []
    for _ in range(nv):
        verts.append((float(toks[i]), float(toks[i + 1]), float(toks[i + 2])))
        i += 3
    tris = []
    for _ in range(nf):
        k = int(toks[i])
        idx = [int(t) for t in toks[i + 1:i + 1 + k]]
        i += 1 + k
        for j in range(1, k - 1):   # fan, as the generator's readers
            tris.append((idx[0], idx[j], idx[j + 1]))
    return verts, tris


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(v):
    n = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    return (v[0] / n, v[1] / n, v[2] / n) if n > 0 else (0.0, 0.0, 1.0)


def make(verts, tris, vn, areas, extremes, out, n, with_normals, rng):
    if n <= len(verts):
        rest = [i for i in range(len(verts)) if i not in extremes]
        chosen = sorted(extremes) + rng.sample(rest, n - len(extremes))
        pts = [(verts[i], vn[i]) for i in chosen]
    else:
        pts = [(verts[i], vn[i]) for i in range(len(verts))]
        cum, s = [], 0.0
        for ar in areas:
            s += ar
            cum.append(s)
        while len(pts) < n:
            t = tris[min(bisect.bisect_left(cum, rng.random() * s), len(tris) - 1)]
            u, v = rng.random(), rng.random()
            if u + v > 1:
                u, v = 1 - u, 1 - v
            w = 1 - u - v
            p = tuple(w * verts[t[0]][a] + u * verts[t[1]][a] + v * verts[t[2]][a] for a in range(3))
            nn = unit(tuple(w * vn[t[0]][a] + u * vn[t[1]][a] + v * vn[t[2]][a] for a in range(3)))
            pts.append((p, nn))
    rng.shuffle(pts)   # no order the bake could lean on
    lines = []
    for p, nn in pts:
        f = "%.9g %.9g %.9g" % p
        if with_normals:
            f += " %.6f %.6f %.6f" % nn
        lines.append(f)
    with open(out, "w") as f:
        if out.endswith(".ply"):
            f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n" % n)
            if with_normals:
                f.write("property float nx\nproperty float ny\nproperty float nz\n")
            f.write("end_header\n")
        f.write("\n".join(lines) + "\n")


def main():
    verts, tris = read_off(sys.argv[1])
    seed = int(sys.argv[2])
    vn = [[0.0, 0.0, 0.0] for _ in verts]
    areas = []
    for t in tris:
        c = cross(sub(verts[t[1]], verts[t[0]]), sub(verts[t[2]], verts[t[0]]))   # |c| = 2 area
        for v in t:
            for a in range(3):
                vn[v][a] += c[a]
        areas.append(math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]))
    vn = [unit(v) for v in vn]
    extremes = set()
    for a in range(3):
        extremes.add(min(range(len(verts)), key=lambda i: verts[i][a]))
        extremes.add(max(range(len(verts)), key=lambda i: verts[i][a]))
    for k, spec in enumerate(sys.argv[3:]):
        out, n, with_normals = spec.rsplit(":", 2)
        make(verts, tris, vn, areas, extremes, out, int(n), with_normals == "1", random.Random(seed * 1000 + k))


if __name__ == "__main__":
    main()
