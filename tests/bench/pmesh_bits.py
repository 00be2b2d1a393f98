#!/usr/bin/env python3
"""What a progressive-mesh bake would take per split if its records were coded by variable-length
fields read in split order, beside the fixed-width records it has (runtime/include/modelc/pmesh.h).
A measure for choosing a format, not a format: nothing reads such a stream.

usage: pmesh_bits.py DIR NAME      (DIR/NAME: a modelc --as both bake, e.g. build/bench/pmesh bunny00)

Reads the bake's chunk arrays back from its NAME_data_*.c files and prints, in bytes per split:
  - fixed: the arrays as baked (positions 6, tree 2 index_bytes, splits index_bytes + 1, corners:
    its faces' 3 index_bytes each);
  - corners, split-relative: each corner of a split's faces is, at the split's level, the split
    vertex v, its parent p or a third vertex x; a full-mesh corner is a descendant of that vertex,
    its offset in the vertex's subtree (DFS numbering: [a, a + size(a))) takes ceil(log2 size(a))
    bits, and x itself an index among the level's vertices;
  - parent as v - parent (Elias gamma), subtree size (Elias gamma of size);
  - positions as the difference to the parent's, each axis Elias gamma of its zigzag;
and, for a decoder that keeps the level's mesh (each vertex's faces) as it goes, so that it knows
each vertex's neighbours: x as its rank among the parent's neighbours before the split, and the
position as the difference to the mean of the split vertex's neighbours after it. (Each x is checked
to be such a neighbour.)
"""
import collections
import glob
import math
import re
import sys


def gamma(n):   # Elias gamma bits of n >= 1
    return 2 * int(math.log2(n)) + 1


def width(n):   # bits of an offset below n
    return 0 if n <= 1 else math.ceil(math.log2(n))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    d, name = sys.argv[1] + "/" + sys.argv[2], sys.argv[2]
    chunks = collections.defaultdict(dict)
    pat = re.compile(r"mc_%s_pm_([a-z_]+)_(\d+)\[(\d+)\] = \{([^}]*)\}" % re.escape(name))
    for f in glob.glob(d + "/%s_data_*.c" % name):
        for m in pat.finditer(open(f).read()):
            chunks[m.group(1)][int(m.group(2))] = bytes(int(x) for x in m.group(4).split(",") if x.strip())
    if not chunks:
        sys.exit("pmesh_bits.py: no progressive-mesh arrays in %s_data_*.c" % d)
    arr = {k: b"".join(v[i] for i in sorted(v)) for k, v in chunks.items()}
    pos, tree, spl, cor = arr["positions"], arr["tree"], arr["splits"], arr["corners"]
    V = len(pos) // 6
    ib = len(tree) // (2 * V)
    S = len(spl) // (ib + 1)
    F = len(cor) // (3 * ib)
    idx = lambda b, i: int.from_bytes(b[i:i + ib], "little")
    par = [idx(tree, 2 * ib * v) for v in range(V)]
    size = [idx(tree, 2 * ib * v + ib) for v in range(V)]
    order = [idx(spl, (ib + 1) * s) for s in range(S)]
    nf = [spl[(ib + 1) * s + ib] for s in range(S)]
    V0, F0 = V - S, F - sum(nf)
    since = [0] * V   # the level (splits done) from which a vertex is present
    for s, v in enumerate(order):
        since[v] = s + 1

    def at(c, level):   # c's nearest ancestor present after `level` splits
        while since[c] > level:
            c = par[c]
        return c

    corner = lambda f, k: idx(cor, 3 * ib * f + ib * k)
    xyz = lambda v: [int.from_bytes(pos[6 * v + 2 * k:6 * v + 2 * k + 2], "little") for k in range(3)]
    zigzag_gamma = lambda q: gamma(2 * q if q > 0 else -2 * q + 1)
    # the decoder's view: the faces of each present vertex at the current level
    faces_of = collections.defaultdict(set)
    for f in range(F0):
        for k in range(3):
            faces_of[at(corner(f, k), 0)].add(f)
    bits = collections.Counter()
    f = F0
    for s, v in enumerate(order):
        p = par[v]
        ring = sorted({at(corner(g, k), s) for g in faces_of[p] for k in range(3)} - {p})   # p's neighbours before
        xs = []
        for _ in range(nf[s]):
            for k in range(3):
                c = corner(f, k)
                a = at(c, s + 1)
                if a == v:
                    bits["corner v"] += width(size[a])
                elif a == p:
                    bits["corner p"] += width(size[a])
                else:
                    bits["corner x index"] += width(V0 + s + 1)
                    if a not in ring:   # the format would not hold: say so rather than count it
                        sys.exit("pmesh_bits.py: split %d: its face's third corner %d is not a neighbour of %d" % (s, a, p))
                    bits["corner x in p's ring"] += width(len(ring))
                    bits["corner x"] += width(size[a])
                    xs.append(a)
            f += 1
        # the split: p's faces with a corner now standing for v go to v; the new faces join
        for g in list(faces_of[p]):
            if any(at(corner(g, k), s + 1) == v for k in range(3)):
                faces_of[p].discard(g)
                faces_of[v].add(g)
        for g in range(f - nf[s], f):
            for k in range(3):
                faces_of[at(corner(g, k), s + 1)].add(g)
        bits["parent"] += gamma(v - p)
        bits["size"] += gamma(size[v])
        pv, pp = xyz(v), xyz(p)
        nb = {at(corner(g, k), s + 1) for g in faces_of[v] for k in range(3)} - {v}   # v's ring after the split
        ctr = [sum(xyz(u)[k] for u in nb) / len(nb) for k in range(3)] if nb else pp
        for k in range(3):
            bits["position"] += zigzag_gamma(pv[k] - pp[k])
            bits["position from v's ring"] += zigzag_gamma(pv[k] - round(ctr[k]))
        bits["split vertex"] += 8 * ib
        bits["faces (1 or 2)"] += 1
    per = lambda b: b / 8 / S
    print("%s: %d vertices, %d splits, %d faces; fixed records: %.2f B per split (positions 6, tree %d, splits %d, corners %.2f)" % (
        name, V, S, F, (6 * S + 2 * ib * S + (ib + 1) * S + 3 * ib * (F - F0)) / S, 2 * ib, ib + 1, 3 * ib * (F - F0) / S))
    plain = ("position", "split vertex", "faces (1 or 2)", "parent", "size", "corner v", "corner p", "corner x index", "corner x")
    for k in plain:
        print("  %-22s %5.2f B per split" % (k, per(bits[k])))
    print("  total                  %5.2f B per split" % per(sum(bits[k] for k in plain)))
    ring = ("position from v's ring", "split vertex", "faces (1 or 2)", "parent", "size", "corner v", "corner p",
            "corner x in p's ring", "corner x")
    print("  with the mesh of the level kept while decoding (x a rank in p's ring of neighbours, the position")
    print("  from the mean of v's ring after the split):")
    for k in ("position from v's ring", "corner x in p's ring"):
        print("  %-22s %5.2f B per split" % (k, per(bits[k])))
    print("  total                  %5.2f B per split" % per(sum(bits[k] for k in ring)))


if __name__ == "__main__":
    main()
