#!/usr/bin/env python3
"""Checks a baked edge model (tests/track/edges_dump.c's text) against a double-precision reading of
its source file, independently of the generator:
  - positions: every source point used, times UNIT metres, in micrometres, rounded (the same set);
  - lines: for a .cao, its lines and every polygon's sides; for a mesh, borders and the edges whose
    two faces' normals differ by more than ANGLE degrees (computed here in double);
  - faces: every source triangle (polygons fanned) with area, as a set of corner positions;
  - closed models: every face counter-clockwise from outside (six times the signed volume > 0, and
    each face's normal pointing away from the model's centre for the convex ones given --convex).

usage: edges_check.py DUMP SOURCE UNIT ANGLE [--convex]
Prints "ok" or the first difference; exit status 0 only for ok."""
import math
import struct
import sys


def f32(x):   # the readers keep mesh coordinates as float (gen/input/readers.hpp)
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def read_dump(path):
    pos, lines, faces = [], [], []
    head = None
    for ln in open(path):
        w = ln.split()
        if w[0] == "edges":
            head = [int(x) for x in w[1:]]
        elif w[0] == "v":
            pos.append(tuple(int(x) for x in w[1:]))
        elif w[0] == "l":
            lines.append(tuple(int(x) for x in w[1:]))
        elif w[0] == "f":
            faces.append(tuple(int(x) for x in w[1:]))
    return head, pos, lines, faces


def read_off(path):
    toks = []
    for ln in open(path):
        toks += ln.split("#")[0].split()
    assert toks[0].upper().endswith("OFF")
    nv, nf = int(toks[1]), int(toks[2])
    i = 4
    pts = []
    for _ in range(nv):
        pts.append(tuple(f32(x) for x in toks[i:i + 3]))
        i += 3
    polys = []
    for _ in range(nf):
        n = int(toks[i])
        polys.append([int(x) for x in toks[i + 1:i + 1 + n]])
        i += 1 + n
    return pts, polys, []


def read_cao(path):
    vals = []
    for ln in open(path):
        ln = ln.split("#")[0].strip()
        if ln:
            vals.append([w for w in ln.split() if "=" not in w])
    assert vals[0] == ["V1"]
    i = 1
    n = int(vals[i][0]); i += 1
    pts = [tuple(f32(x) for x in vals[i + k][:3]) for k in range(n)]; i += n
    n = int(vals[i][0]); i += 1
    flines = [tuple(int(x) for x in vals[i + k][:2]) for k in range(n)]; i += n
    n = int(vals[i][0]); i += 1
    polys = []
    for k in range(n):   # faces from lines: chain them into a loop
        ids = [int(x) for x in vals[i + k][1:1 + int(vals[i + k][0])]]
        segs = [flines[j] for j in ids]
        loop = list(segs[0])
        rest = segs[1:]
        while rest:
            for s in rest:
                if s[0] == loop[-1] or s[1] == loop[-1]:
                    loop.append(s[1] if s[0] == loop[-1] else s[0])
                    rest.remove(s)
                    break
            else:
                raise SystemExit("edges_check: face from lines is not a loop")
        polys.append(loop[:-1])
    i += n
    n = int(vals[i][0]); i += 1
    for k in range(n):
        polys.append([int(x) for x in vals[i + k][1:1 + int(vals[i + k][0])]])
    return pts, polys, flines


def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def norm(a): return math.sqrt(dot(a, a))


def main():
    args = sys.argv[1:]
    convex = "--convex" in args
    args = [a for a in args if a != "--convex"]
    dump, src, unit, angle = args[0], args[1], float(args[2]), float(args[3])
    head, pos, lines, faces = read_dump(dump)
    pts, polys, flines = (read_cao if src.endswith(".cao") else read_off)(src)
    # micrometres rounded half away from zero, as the generator (std::round; Python's round() halves to even)
    um = lambda p: tuple(int(math.copysign(math.floor(abs(c * unit * 1e6) + 0.5), c)) for c in p)
    tris = []
    for poly in polys:
        for k in range(1, len(poly) - 1):
            t = (poly[0], poly[k], poly[k + 1])
            if len(set(t)) < 3:
                continue
            a, b, c = (pts[j] for j in t)
            u, v, w = sub(b, a), sub(c, a), sub(c, b)
            if norm(cross(u, v)) <= 1e-6 * max(dot(u, u), dot(v, v), dot(w, w)):
                continue
            tris.append(t)
    # lines, as sets of position pairs
    if src.endswith(".cao"):
        want = set()
        for a, b in flines:
            want.add(frozenset((um(pts[a]), um(pts[b]))))
        for poly in polys:
            for k in range(len(poly)):
                want.add(frozenset((um(pts[poly[k]]), um(pts[poly[(k + 1) % len(poly)]]))))
    else:
        adj = {}
        for f, t in enumerate(tris):
            for k in range(3):
                adj.setdefault(frozenset((t[k], t[(k + 1) % 3])), []).append(f)
        normal = []
        for t in tris:
            n = cross(sub(pts[t[1]], pts[t[0]]), sub(pts[t[2]], pts[t[0]]))
            normal.append(tuple(x / norm(n) for x in n))
        want = set()
        for e, fs in adj.items():
            a, b = tuple(e)
            if len(fs) == 1:
                want.add(frozenset((um(pts[a]), um(pts[b]))))
            elif len(fs) == 2:
                c = max(-1.0, min(1.0, dot(normal[fs[0]], normal[fs[1]])))
                if math.degrees(math.acos(c)) > angle:
                    want.add(frozenset((um(pts[a]), um(pts[b]))))
    got = set(frozenset((pos[a], pos[b])) for a, b in lines)
    if len(got) != len(lines):
        return "a line twice"
    if got != want:
        return "lines differ: %d in the bake only, %d in the reference only (of %d)" % (len(got - want), len(want - got), len(want))
    used = set()
    for t in tris:
        used.update(t)
    for a, b in flines:
        used.update((a, b))
    if sorted(pos) != sorted(set(um(pts[j]) for j in used)):
        return "positions differ from the source's used points (%d against %d)" % (len(pos), len(used))
    key = lambda t: frozenset(t)
    if sorted(map(sorted, (tuple(pos[j] for j in f) for f in faces))) != sorted(map(sorted, (tuple(um(pts[j]) for j in t) for t in tris))):
        return "faces differ (%d against %d)" % (len(faces), len(tris))
    if head[3]:
        vol = sum(dot(pos[f[0]], cross(pos[f[1]], pos[f[2]])) for f in faces)
        if vol <= 0:
            return "closed, but the faces face inwards (volume %g)" % vol
        if convex:
            c = [sum(p[k] for p in pos) / len(pos) for k in range(3)]
            for f in faces:
                n = cross(sub(pos[f[1]], pos[f[0]]), sub(pos[f[2]], pos[f[0]]))
                if dot(n, sub(pos[f[0]], c)) <= 0:
                    return "face %s faces inwards" % (f,)
    return "ok"


if __name__ == "__main__":
    r = main()
    print(r)
    sys.exit(0 if r == "ok" else 1)
