#!/usr/bin/env python3
"""What a face hierarchy could spare a line drawing's passes: faces grouped G at a time, each
group's normal cone tested against random orthographic view directions.

For each view direction d (seeded, uniform on the sphere) a group is front when every normal in its
cone faces d (the angle between the cone's axis and d plus the cone's half-angle below 90 degrees),
back when none does, else mixed. A mixed group's faces need their own facing test; a uniform group
that shares an edge with a group of another class (or a mixed one) may hold silhouette edges on
that border; only the faces of a uniform group whose neighbours are all of its class could be
passed over whole. Prints, per grouping and group size, the mean shares of the faces over the
directions: mixed, uniform at a border, and skippable.

Groupings: "position" (faces in the Morton order of their centres, 10 bits an axis) and "normal"
(faces first by the cell of their normal, 4 x 4 cells on each face of the cube of directions, then
by that Morton order). Exact normals of the input file's faces, in doubles.

usage: cone_groups.py FILE.off DIRECTIONS SEED SIZE...   (one line per grouping and size)
"""
import math
import random
import sys


def read_off(path):
    tokens = " ".join(line.split("#")[0] for line in open(path)).split()
    if tokens[0] != "OFF":
        raise SystemExit(f"{path}: not an OFF file")
    nv, nf = int(tokens[1]), int(tokens[2])
    at = 4
    pts = [tuple(map(float, tokens[at + 3 * i:at + 3 * i + 3])) for i in range(nv)]
    at += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(tokens[at])
        faces.append(tuple(int(t) for t in tokens[at + 1:at + 4]))
        at += n + 1
    return pts, faces


def spread(x):   # 10 bits into every third bit
    r = 0
    for i in range(10):
        r |= ((x >> i) & 1) << (3 * i)
    return r


def main():
    path, directions, seed = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    sizes = [int(s) for s in sys.argv[4:]]
    pts, faces = read_off(path)
    normals, morton = [], []
    lo = [min(p[i] for p in pts) for i in range(3)]
    ext = max(max(p[i] for p in pts) - lo[i] for i in range(3)) or 1.0
    for a, b, c in faces:
        pa, pb, pc = pts[a], pts[b], pts[c]
        u = [pb[i] - pa[i] for i in range(3)]
        v = [pc[i] - pa[i] for i in range(3)]
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        length = math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2) or 1e-300
        normals.append((n[0] / length, n[1] / length, n[2] / length))
        q = [min(1023, int(((pa[i] + pb[i] + pc[i]) / 3 - lo[i]) / ext * 1023)) for i in range(3)]
        morton.append(spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2)

    def normal_cell(f):
        n = normals[f]
        axis = max(range(3), key=lambda k: abs(n[k]))
        big = abs(n[axis]) or 1.0
        s = min(3, int((n[(axis + 1) % 3] / big + 1) * 2)), min(3, int((n[(axis + 2) % 3] / big + 1) * 2))
        return ((axis * 2 + (n[axis] > 0)) * 4 + s[0]) * 4 + s[1]

    edges = {}
    for f, t in enumerate(faces):
        for k in range(3):
            e = (min(t[k], t[(k + 1) % 3]), max(t[k], t[(k + 1) % 3]))
            edges.setdefault(e, []).append(f)
    rng = random.Random(seed)
    views = []
    for _ in range(directions):
        d = [rng.gauss(0, 1) for _ in range(3)]
        length = math.sqrt(sum(x * x for x in d))
        views.append([x / length for x in d])
    F = len(faces)
    for grouping in ("position", "normal"):
        key = (lambda f: morton[f]) if grouping == "position" else (lambda f: (normal_cell(f), morton[f]))
        order = sorted(range(F), key=key)
        for size in sizes:
            group = [0] * F
            groups = [order[s:s + size] for s in range(0, F, size)]
            for g, members in enumerate(groups):
                for f in members:
                    group[f] = g
            cones = []
            for members in groups:
                axis = [sum(normals[f][k] for f in members) for k in range(3)]
                length = math.sqrt(sum(x * x for x in axis)) or 1.0
                axis = [x / length for x in axis]
                half = max(math.acos(max(-1.0, min(1.0, sum(axis[k] * normals[f][k] for k in range(3))))) for f in members)
                cones.append((axis, half))
            near = [set() for _ in groups]
            for fs in edges.values():
                for i in range(len(fs)):
                    for j in range(i + 1, len(fs)):
                        a, b = group[fs[i]], group[fs[j]]
                        if a != b:
                            near[a].add(b)
                            near[b].add(a)
            mixed = border = 0
            for d in views:
                cls = []
                for axis, half in cones:
                    angle = math.acos(max(-1.0, min(1.0, sum(axis[k] * d[k] for k in range(3)))))
                    cls.append(1 if angle + half < math.pi / 2 else -1 if angle - half > math.pi / 2 else 0)
                for g, members in enumerate(groups):
                    if cls[g] == 0:
                        mixed += len(members)
                    elif any(cls[h] != cls[g] for h in near[g]):
                        border += len(members)
            total = F * len(views)
            print(f"{grouping} {size} {len(groups)} {mixed / total:.3f} {border / total:.3f} {1 - (mixed + border) / total:.3f}")


if __name__ == "__main__":
    main()
