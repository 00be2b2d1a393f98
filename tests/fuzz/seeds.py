#!/usr/bin/env python3
"""Seed inputs for the fuzzers, written at fuzz time from the catalogue (nothing here is data).

usage: seeds.py MODELS_DIR OUT_DIR

Writes OUT_DIR/{off,obj,ply,stl,xyz,cao,gltf,glb}/: small valid files cut from the catalogue's models
(the first faces of a mesh with their vertices renumbered, the first points of a point set), the
same meshes in every format the generator reads (OBJ, ASCII and binary STL, ASCII and binary PLY,
with and without colours, CAO with faces from lines and from points, glTF and GLB with a node
hierarchy, COLOR_0, a baseColorFactor, a PNG texture, strips and fans, and tests/gen/make_gltf.py's
malformed files), ViSP's cube as CAO written here, and truncated prefixes of the originals; and
OUT_DIR/bake/, each of the first six formats' seeds with the bake fuzzer's leading format byte
(tests/fuzz/fuzz_bake.cpp). Valid seeds let the mutations start deep in each
reader instead of at its first header check.
"""
import os
import shutil
import struct
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "gen"))
import make_gltf  # noqa: E402  (tests/gen/make_gltf.py: the glTF writer of tests/gen/gltf.sh)

EXTS = ["off", "obj", "ply", "stl", "xyz", "cao"]  # the bake target's format byte: new ones at the end


def read_off(path, faces_wanted):
    """The first FACES_WANTED faces of an OFF file and the vertices they use, renumbered."""
    with open(path) as f:
        words = f.read().split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    verts = [tuple(float(w) for w in words[4 + 3 * i:7 + 3 * i]) for i in range(nv)]
    pos, faces = 4 + 3 * nv, []
    for _ in range(min(nf, faces_wanted)):
        n = int(words[pos])
        faces.append([int(w) for w in words[pos + 1:pos + 1 + n]])
        pos += 1 + n
    used = sorted({i for face in faces for i in face})
    renum = {old: new for new, old in enumerate(used)}
    return [verts[i] for i in used], [[renum[i] for i in face] for face in faces]


def tris(faces):
    return [(f[0], f[k], f[k + 1]) for f in faces for k in range(1, len(f) - 1)]


def colour(i):
    return (37 * i % 256, 91 * i % 256, 173 * i % 256)


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def mesh_files(name, v, faces, out):
    t = tris(faces)
    off = "OFF\n%d %d 0\n" % (len(v), len(faces))
    off += "".join("%g %g %g\n" % p for p in v)
    off += "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces)
    write(f"{out}/off/{name}.off", off)
    coff = "COFF\n%d %d 0\n" % (len(v), len(faces))
    coff += "".join("%g %g %g %d %d %d 255\n" % (p + colour(i)) for i, p in enumerate(v))
    coff += "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces)
    write(f"{out}/off/{name}-colour.off", coff)
    obj = "# %s\n" % name + "".join("v %g %g %g\n" % p for p in v)
    obj += "".join("f %s\n" % " ".join(str(i + 1) for i in f) for f in faces)
    write(f"{out}/obj/{name}.obj", obj)
    obj = "".join("v %g %g %g %g %g %g\n" % (p + tuple(c / 255 for c in colour(i))) for i, p in enumerate(v))
    obj += "".join("f %s\n" % " ".join("%d/%d/%d" % (i + 1, i + 1, i + 1) for i in f) for f in faces)
    write(f"{out}/obj/{name}-colour.obj", obj)
    stl = "solid %s\n" % name
    for a, b, c in t:
        stl += " facet normal 0 0 0\n  outer loop\n"
        stl += "".join("   vertex %g %g %g\n" % v[i] for i in (a, b, c))
        stl += "  endloop\n endfacet\n"
    write(f"{out}/stl/{name}-ascii.stl", stl + "endsolid %s\n" % name)
    b = b"binary seed".ljust(80, b" ") + struct.pack("<I", len(t))
    for tri in t:
        b += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v[i]) for i in tri) + b"\0\0"
    write(f"{out}/stl/{name}-binary.stl", b)
    head = "ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
    colours = "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    tail = "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % len(faces)
    ply = (head % ("ascii", len(v))) + colours + tail
    ply += "".join("%g %g %g %d %d %d\n" % (p + colour(i)) for i, p in enumerate(v))
    ply += "".join("%d %s\n" % (len(f), " ".join(map(str, f))) for f in faces)
    write(f"{out}/ply/{name}-ascii.ply", ply)
    ply = ((head % ("binary_little_endian", len(v))) + tail).encode()
    ply += b"".join(struct.pack("<3f", *p) for p in v)
    ply += b"".join(struct.pack("<B%di" % len(f), len(f), *f) for f in faces)
    write(f"{out}/ply/{name}-binary.ply", ply)
    write(f"{out}/cao/{name}.cao", cao(name, v, faces))
    gltf_files(name, [tuple(make_gltf.f32(c) for c in p) for p in v], t, out)


def gltf_files(name, v, t, out):
    """glTF seeds: plain, and with a hierarchy, colours, a texture, strips and fans; then malformed."""
    M = make_gltf
    n = len(v)
    os.makedirs(f"{out}/gltf", exist_ok=True)
    os.makedirs(f"{out}/glb", exist_ok=True)
    d = M.Doc()
    d.node(mesh=d.mesh(v, t))
    d.glb(f"{out}/glb/{name}.glb")
    d = M.Doc()
    d.node(mesh=d.mesh(v, t))
    d.gltf(f"{out}/gltf/{name}.gltf")
    # a matrix node over a TRS node, COLOR_0 bytes, a factor and a texture on TEXCOORD_0
    for ext in ("gltf", "glb"):
        d = M.Doc()
        m = d.mesh(v, t, {"COLOR_0": d.accessor(M.U8, "VEC4", [c for i in range(n) for c in colour(i) + (255,)], n, True),
                          "TEXCOORD_0": d.accessor(M.F32, "VEC2", [0.3 * i for i in range(2 * n)], n)})
        child = d.node(root=False, mesh=m, translation=[1, 2, 3], rotation=[0, 0.6, 0, 0.8], scale=[1, 2, 1])
        d.node(children=[child], matrix=[0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1])
        image = M.png(2, 2, [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (9, 9, 9)]])
        ref = {"bufferView": d.view(image), "mimeType": "image/png"} if ext == "glb" else \
            {"uri": "data:image/png;base64," + M.base64.b64encode(image).decode()}
        d.material(baseColorFactor=[0.5, 0.7, 0.9, 1], baseColorTexture={"index": d.texture(ref, 33648, 33071)})
        d.glb(f"{out}/glb/{name}-coloured.glb") if ext == "glb" else d.gltf(f"{out}/gltf/{name}-coloured.gltf")
    d = M.Doc()
    d.node(mesh=d.mesh(v, None, mode=5))
    d.node(mesh=d.mesh(v, None, mode=6))
    d.node(mesh=d.mesh(v, None, mode=0))
    d.gltf(f"{out}/gltf/{name}-strip-fan.gltf")
    tmp = tempfile.mkdtemp()
    try:
        M.bad(tmp, v, t)
        for f in sorted(os.listdir(tmp)):
            ext = f.rsplit(".", 1)[-1]
            if ext in ("gltf", "glb"):
                shutil.copy(os.path.join(tmp, f), f"{out}/{ext}/bad-{f}")
    finally:
        shutil.rmtree(tmp)


def cao(name, v, faces, by_lines=4):
    """CAO: the first BY_LINES faces from 3D lines (their edges, each once), the rest from points."""
    lines, index = [], {}
    for f in faces[:by_lines]:
        for a, b in zip(f, f[1:] + f[:1]):
            if (a, b) not in index and (b, a) not in index:
                index[(a, b)] = len(lines)
                lines.append((a, b))

    def line(a, b):
        return index[(a, b)] if (a, b) in index else index[(b, a)]
    text = "V1\n# %s\n# points\n%d\n" % (name, len(v)) + "".join("%g %g %g\n" % p for p in v)
    text += "# 3D lines\n%d\n" % len(lines) + "".join("%d %d\n" % l for l in lines)
    text += "# faces from lines\n%d\n" % len(faces[:by_lines])
    text += "".join("%d %s name=l%d\n" % (len(f), " ".join(str(line(a, b)) for a, b in zip(f, f[1:] + f[:1])), k)
                    for k, f in enumerate(faces[:by_lines]))
    text += "# faces from points\n%d\n" % len(faces[by_lines:])
    text += "".join("%d %s name=\"p %d\"\n" % (len(f), " ".join(map(str, f)), k) for k, f in enumerate(faces[by_lines:]))
    return text + "# cylinders\n0\n# circles\n0\n"


def cube_files(out):
    """ViSP's cube (mbt/cube.cao in ViSP's images), written here: as ViSP ships it, from lines, and V2."""
    v = [(0, 0, 0), (-0.084, 0, 0), (-0.084, 0.084, 0), (0, 0.084, 0),
         (0, 0, 0.084), (-0.084, 0, 0.084), (-0.084, 0.084, 0.084), (0, 0.084, 0.084)]
    faces = [[0, 4, 5, 1], [1, 5, 6, 2], [6, 7, 3, 2], [3, 7, 4, 0], [0, 1, 2, 3], [7, 6, 5, 4]]
    write(f"{out}/cao/cube.cao", cao("cube", v, faces, 0))
    write(f"{out}/cao/cube-lines.cao", cao("cube", v, faces, 6))
    v2 = "V2\n8\n" + "".join("%g %g %g %d %d\n" % (p + (i, 2 * i)) for i, p in enumerate(v))
    v2 += "1\n0 6 useLod=true\n0\n6\n" + "".join("4 %s\n" % " ".join(map(str, f)) for f in faces)
    write(f"{out}/cao/cube-v2.cao", v2)  # no cylinder or circle counts, as in older files


def main():
    models, out = sys.argv[1], sys.argv[2]
    cube_files(out)
    for name in ["nefertiti", "head", "fandisk"]:
        path = f"{models}/{name}.off"
        if not os.path.exists(path):
            continue
        v, faces = read_off(path, 16)
        mesh_files(name, v, faces, out)
        with open(path, "rb") as f:
            write(f"{out}/off/{name}-prefix.off", f.read(700))  # a file cut short
    path = f"{models}/kitten.xyz"
    if os.path.exists(path):
        with open(path) as f:
            lines = f.read().splitlines()
        write(f"{out}/xyz/kitten-normals.xyz", "\n".join(lines[:40]) + "\n")
        write(f"{out}/xyz/kitten.xyz", "\n".join(" ".join(l.split()[:3]) for l in lines[:40]) + "\n")
        pts = ["%s 0 0 0" % " ".join(l.split()[:3]) for l in lines[:20]]
        ply = "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n" \
              "property float nx\nproperty float ny\nproperty float nz\nend_header\n" % len(pts)
        write(f"{out}/ply/kitten-points.ply", ply + "\n".join(pts) + "\n")
    path = f"{models}/b9_training.ply"
    if os.path.exists(path):
        with open(path, "rb") as f:
            data = f.read()
        end = data.index(b"end_header\n") + len(b"end_header\n")
        header = data[:end].replace(b"element vertex 22300", b"element vertex 30")
        rec = 3 * 8 + 3 + 4  # x y z doubles, red green blue uchar, label int
        write(f"{out}/ply/b9_training-points.ply", header + data[end:end + 30 * rec])
    # the bake target: every seed again behind its format byte (bit 7: with --views; bit 6: with
    # --as both, the progressive mesh, for the mesh formats)
    for i, ext in enumerate(EXTS):
        d = f"{out}/{ext}"
        if not os.path.isdir(d):
            continue
        for k, fname in enumerate(sorted(os.listdir(d))):
            with open(f"{d}/{fname}", "rb") as f:
                data = f.read()
            write(f"{out}/bake/{fname}", bytes([i]) + data)
            if k % 2 == 0:
                write(f"{out}/bake/views-{fname}", bytes([i | 0x80]) + data)
            elif ext != "xyz":
                write(f"{out}/bake/mesh-{fname}", bytes([i | 0x40]) + data)


main()
