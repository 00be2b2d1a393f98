#!/usr/bin/env python3
"""The normal cones of a bake (gen/cones.hpp, runtime/include/modelc/octree.h) against the mesh, in
double precision and independently of CGAL: for every node of levels 1..D-3, every face of the mesh
that meets the node's cube (a separating-axis test, the cube shrunk by 1e-7 of the grid's side so
that faces merely touching it within rounding are left to the generator) must have its outward
normal within the stored cone: n . a >= sqrt(|a|^2 - s^2) |n| (s < 255; s = 255 holds anything), and
the record's n2 and n3 must count the node's subtree two and three levels down.

usage: cones_check.py MESH.off BAKE_DIR NAME
Prints one line of figures; exits 1 with the first violation. The mesh must be one closed shell
(its outward side is the one with positive signed volume)."""
import glob
import math
import re
import sys


def load_off(path):
    tok = open(path).read().split()
    i = 1 if tok[0] == "OFF" else 0
    nv, nf = int(tok[i]), int(tok[i + 1])
    i += 3
    pts = [tuple(float(tok[i + 3 * k + a]) for a in range(3)) for k in range(nv)]
    i += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(tok[i])
        vs = [int(x) for x in tok[i + 1:i + 1 + n]]
        i += 1 + n
        for k in range(1, n - 1):
            faces.append((vs[0], vs[k], vs[k + 1]))
    return pts, faces


def arrays(bake, name):
    out = {}
    for f in glob.glob("%s/%s_data_*.c" % (bake, name)):
        for sym, body in re.findall(r"const uint8_t (mc_\w+)\[\d+\] = \{([^}]*)\}", open(f).read()):
            out[sym] = bytes(int(x, 0) for x in body.replace("\n", " ").split(",") if x.strip())
    return out


def stream(arr, name, kind, level):
    parts, i = [], 0
    while "mc_%s_%s%d_%d" % (name, kind, level, i) in arr:
        parts.append(arr["mc_%s_%s%d_%d" % (name, kind, level, i)])
        i += 1
    return b"".join(parts)


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def tri_box(c, h, tri):
    """Akenine-Moller: does the triangle meet the box of centre c and half side h?"""
    v = [sub(p, c) for p in tri]
    e = [sub(v[1], v[0]), sub(v[2], v[1]), sub(v[0], v[2])]
    for a in range(3):   # the box's faces
        if min(p[a] for p in v) > h or max(p[a] for p in v) < -h:
            return False
    n = cross(e[0], e[1])   # the triangle's plane
    r = h * (abs(n[0]) + abs(n[1]) + abs(n[2]))
    if abs(dot(n, v[0])) > r:
        return False
    for ed in e:   # the nine edge cross axes
        for a in range(3):
            ax = [0.0, 0.0, 0.0]
            ax[a] = 1.0
            axis = cross(tuple(ax), ed)
            ps = [dot(axis, p) for p in v]
            r = h * (abs(axis[0]) + abs(axis[1]) + abs(axis[2]))
            if min(ps) > r or max(ps) < -r:
                return False
    return True


def main():
    mesh, bake, name = sys.argv[1:4]
    pts, faces = load_off(mesh)
    lo = [min(p[a] for p in pts) for a in range(3)]
    hi = [max(p[a] for p in pts) for a in range(3)]
    side = max(hi[a] - lo[a] for a in range(3)) * (1 + 1e-9)
    origin = [(lo[a] + hi[a]) / 2 - side / 2 for a in range(3)]
    tris = [(pts[a], pts[b], pts[c]) for a, b, c in faces]
    vol = sum(dot(t[0], cross(t[1], t[2])) for t in tris)
    sign = 1.0 if vol > 0 else -1.0
    normals = [tuple(sign * x for x in cross(sub(t[1], t[0]), sub(t[2], t[0]))) for t in tris]
    arr = arrays(bake, name)
    depth = max(int(m.group(1)) for m in (re.match(r"mc_\w+_c(\d+)_\d+$", s) for s in arr) if m)
    masks = [stream(arr, name, "m", l) for l in range(depth)]
    # nodes level by level in depth-first order, with their subtree counts two and three levels down
    at = [[] for _ in range(depth + 1)]
    cur = [0] * depth

    def walk(p, l, path):
        at[l].append([p, 0, 0])
        me = at[l][-1]
        if l >= 2:
            path[l - 2][1] += 1
        if l >= 3:
            path[l - 3][2] += 1
        if l == depth:
            return
        m = masks[l][cur[l]]
        cur[l] += 1
        for k in range(8):
            if m >> k & 1:
                walk((2 * p[0] + (k & 1), 2 * p[1] + (k >> 1 & 1), 2 * p[2] + (k >> 2 & 1)), l + 1, path + [me])
    sys.setrecursionlimit(10000)
    walk((0, 0, 0), 0, [])
    checked = tight = nodes = 0
    for l in range(1, depth - 2):
        rec = stream(arr, name, "k", l)
        if len(rec) != 7 * len(at[l]):
            print("level %d: %d cone bytes for %d nodes" % (l, len(rec), len(at[l])))
            return 1
        cs = side / 2 ** l
        # faces binned by the nodes their boxes reach
        bins = {}
        for fi, t in enumerate(tris):
            b0 = [int(math.floor((min(p[a] for p in t) - origin[a]) / cs)) for a in range(3)]
            b1 = [int(math.floor((max(p[a] for p in t) - origin[a]) / cs)) for a in range(3)]
            for x in range(b0[0], b1[0] + 1):
                for y in range(b0[1], b1[1] + 1):
                    for z in range(b0[2], b1[2] + 1):
                        bins.setdefault((x, y, z), []).append(fi)
        for i, (p, n2, n3) in enumerate(at[l]):
            r = rec[7 * i:7 * i + 7]
            a = tuple(x - 256 if x > 127 else x for x in r[:3])
            s, rn2, rn3 = r[3], r[4], r[5] | r[6] << 8
            nodes += 1
            if (rn2, rn3) != (n2, n3):
                print("level %d node %d: counts %d, %d; the masks give %d, %d" % (l, i, rn2, rn3, n2, n3))
                return 1
            if s == 255:
                continue
            tight += 1
            alen = math.sqrt(dot(a, a))
            cos_min = math.sqrt(max(0.0, alen * alen - s * s)) / alen
            c = tuple(origin[k] + (p[k] + 0.5) * cs for k in range(3))
            for fi in set(bins.get(p, [])) | set(
                    f for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                    for f in bins.get((p[0] + dx, p[1] + dy, p[2] + dz), [])):
                if not tri_box(c, cs / 2 - 1e-7 * side, tris[fi]):
                    continue
                nn = normals[fi]
                nl = math.sqrt(dot(nn, nn))
                if nl == 0:
                    continue
                checked += 1
                if dot(nn, a) / (nl * alen) < cos_min - 1e-9:
                    print("level %d node %d: face %d's normal at %.4f degrees from the axis, the cone holds %.4f" %
                          (l, i, fi, math.degrees(math.acos(max(-1, min(1, dot(nn, a) / (nl * alen))))),
                           math.degrees(math.acos(cos_min))))
                    return 1
    print("nodes %d with a cone %d; face-in-cube pairs checked %d" % (nodes, tight, checked))
    if not tight:
        print("no node has a cone narrower than a half-space")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
